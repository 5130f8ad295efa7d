"""The Jacobian of one collision of the map, in float64 (``kernels.step_tangent``)."""

import math

import numpy as np

from fastpath.dynamics._checks import departing, model_code
from fastpath.dynamics._internals import CONVERGED, NOT_DEPARTING, reduce_phase
from fastpath.dynamics.kernels import step_tangent
from fastpath.dynamics.periodic_orbit import _raise_for_status
from fastpath.inputs import real_scalar as real


def step_jacobian(phi, v, eps, *, model="exact"):
    """DF at (phi, v): [[dphi1/dphi, dphi1/dv], [dv1/dphi, dv1/dv]] (phases unreduced).

    Raises ValueError for bad input or a state that does not depart, and
    ``fastpath.UncertainCollision`` for a flight float64 cannot decide.
    """
    phi, v, eps = real("phi", phi), real("v", v), real("eps", eps)
    code = model_code(model)
    departing(phi, v, eps)
    phase = reduce_phase(phi)
    *_, j11, j12, j21, j22, status = step_tangent(phase, math.sin(phase), math.cos(phase), v,
                                                  eps, code)
    if status == NOT_DEPARTING:
        raise ValueError(f"the Holmes map's absolute value acts at phi={phi!r}, v={v!r}")
    if status != CONVERGED:
        _raise_for_status(status, phi, v, eps, "the flight")
    return np.array([[j11, j12], [j21, j22]])
