"""Fast float64 integrator of the bouncer model (numba).

Public API: ``flight_time``, ``step``, ``holmes_step``, ``orbit``, plus
``flight`` (times with iteration counts and statuses), ``carried_step`` (one step of a
chattering orbit from its carried state, as the kernels made it), ``moments`` (velocity moments
of many particles), and the dynamics ``periodic_orbit`` and ``lyapunov``
(``fastpath.dynamics``). Every function takes the state positionally, (phi, v, eps) and where
it applies n or period, and everything after it by keyword, with the names ``verify`` uses.
The subpackages: ``arithmetic`` (float64 building blocks), ``elastic`` (the paper's map),
``dissipative`` (drag, restitution, sticking), ``kernels`` (many particles),
``dynamics`` (periodic orbits, Lyapunov exponents); ``physics`` describes the model they take.
"""

from importlib.metadata import PackageNotFoundError, version

from fastpath.api import (
    FlightResult,
    Moments,
    Orbit,
    carried_step,
    flight,
    flight_time,
    holmes_step,
    moments,
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
    "Moments",
    "Orbit",
    "UncertainCollision",
    "carried_step",
    "flight",
    "flight_time",
    "holmes_step",
    "lyapunov",
    "moments",
    "orbit",
    "periodic_orbit",
    "step",
]
