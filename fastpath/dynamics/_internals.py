"""The fastpath internals the dynamics kernels call inside their compiled loops, in one place.

The public ``fastpath.step`` validates its input and runs one flight per Python call; a Newton
iteration on F^p or a tangent-map loop over 10^6 collisions needs the scalar kernel itself.
"""

from fastpath.arithmetic.jit import jit, parallel_jit
from fastpath.arithmetic.phase import reduce_phase
from fastpath.arithmetic.rounding import UNIT_ROUNDOFF
from fastpath.elastic.collision import collide_from
from fastpath.elastic.flight import GENERAL
from fastpath.status import CONVERGED, NOT_DEPARTING, UNCERTAIN, FlightStatus, UncertainCollision

__all__ = [
    "CONVERGED",
    "FlightStatus",
    "GENERAL",
    "NOT_DEPARTING",
    "UNCERTAIN",
    "UNIT_ROUNDOFF",
    "UncertainCollision",
    "collide_from",
    "jit",
    "parallel_jit",
    "reduce_phase",
]
