"""The Jacobian of one collision of the map, in float64 (``kernels.step_tangent``)."""

import math

import numpy as np

from fastpath.arithmetic.phase import reduce_phase
from fastpath.dynamics.kernels import step_tangent
from fastpath.dynamics.periodic_orbit import _raise_for_status
from fastpath.inputs import departing, model_physics
from fastpath.inputs import real_scalar as real
from fastpath.status import CONVERGED, NOT_DEPARTING


def step_jacobian(phi, v, eps, *, model="exact"):
    """DF at (phi, v): [[dphi1/dphi, dphi1/dv], [dv1/dphi, dv1/dv]] (phases unreduced).

    Raises ValueError for bad input or a state that does not depart, and
    ``fastpath.UncertainCollision`` for a flight float64 cannot decide.
    """
    phi, v, eps = real("phi", phi), real("v", v), real("eps", eps)
    physics = model_physics(model, eps)
    departing(phi, v, eps)
    phase = reduce_phase(phi)
    *_, j11, j12, j21, j22, status = step_tangent(phase, math.sin(phase), math.cos(phase), v,
                                                  physics)
    if status == NOT_DEPARTING:
        raise ValueError(f"the Holmes map's absolute value acts at phi={phi!r}, v={v!r}")
    if status != CONVERGED:
        _raise_for_status(status, phi, v, eps, "the flight")
    return np.array([[j11, j12], [j21, j22]])
