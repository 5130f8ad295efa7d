"""Arrays of status codes (``fastpath.FlightStatus`` values) have one dtype across fastpath."""

import numpy as np

import fastpath
import fastpath.dynamics as fd
from fastpath.status import STATUS_DTYPE

PHI, V = np.array([4.0, 1.0, 2.0]), np.array([3.0, 2.5, 4.0])


def test_status_arrays_of_the_api_and_the_dynamics_share_one_dtype():
    assert STATUS_DTYPE == np.int8
    statuses = {
        "flight": fastpath.flight(PHI, V, 0.6).status,
        "velocities": fd.velocities(PHI, V, 0.6, [1, 5])[1],
        "first_passage": fd.first_passage(PHI, V, 0.6, 6.0, 20)[1],
        "lyapunov": fd.lyapunov(PHI, V, 0.6, 20).status,
        "lyapunov_by_band": fd.lyapunov_by_band(PHI, V, 0.6, 20, [0.0, 5.0, 10.0]).status,
    }
    assert {name: s.dtype for name, s in statuses.items()} == dict.fromkeys(statuses, STATUS_DTYPE)
    assert all(np.all(s == fastpath.FlightStatus.CONVERGED) for s in statuses.values())
