"""Fast float64 integrator of the bouncer model (numba).

Public API: ``flight_time``, ``step``, ``holmes_step``, ``orbit``, plus
``flight`` (times with iteration counts and statuses) and ``carried_step`` (one step of a
chattering orbit from its carried state, as the kernels made it), and the dynamics
``periodic_orbit`` and ``lyapunov`` (``fastpath.dynamics``). The subpackages: ``arithmetic``
(float64 building blocks), ``elastic`` (the paper's map), ``dissipative`` (drag, restitution,
sticking), ``kernels`` (many particles), ``dynamics`` (periodic orbits, Lyapunov exponents);
``physics`` describes the model they take.
"""

from importlib.metadata import PackageNotFoundError, version

from fastpath.api import (
    FlightResult,
    Orbit,
    carried_step,
    flight,
    flight_time,
    holmes_step,
    orbit,
    step,
)
from fastpath.dynamics import lyapunov, periodic_orbit
from fastpath.status import FlightStatus, UncertainCollision

try:
    __version__ = version("bouncer-verify")
except PackageNotFoundError:  # a source tree that was not installed
    __version__ = "0+unknown"

__all__ = [
    "FlightResult",
    "FlightStatus",
    "Orbit",
    "UncertainCollision",
    "carried_step",
    "flight",
    "flight_time",
    "holmes_step",
    "lyapunov",
    "orbit",
    "periodic_orbit",
    "step",
]
