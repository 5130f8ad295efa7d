"""Independent reference for the bouncer model: mpmath precision plus interval certificates.

Layout: :mod:`verify.numerics` (precision, exact inputs and phase reduction, the first-root
search), :mod:`verify.elastic` (the paper's flight: gap, certificate, condition number),
:mod:`verify.dissipative` (physics description, drag laws, chattering and sticking), and the
public entry points :mod:`verify.flight`, :mod:`verify.collision` (the map),
:mod:`verify.jacobian`, :mod:`verify.orbit`; :mod:`verify.check` tests a user's integrator
(``verify.check.load_callable`` loads one from ``module:name``). Never imports ``fastpath``:
the reference is worth something only if it shares no code with the integrator it checks.
Every public function is safe to call from any thread (:mod:`verify.numerics.precision`).
"""

from importlib.metadata import PackageNotFoundError
from importlib.metadata import version as _version

from .check import CheckReport, Failure, assert_integrator, check_integrator
from .collision import step
from .dynamics import NotCertified, periodic_orbit
from .elastic.conditioning import condition_number
from .elastic.gap import gap
from .elastic.grazing import GrazingContact, grazing_contact, grazing_departure
from .errors import ChatteringDetected, UndecidableCollision
from .flight import FlightCertificate, certify_flight, flight_time
from .jacobian import jacobian
from .orbit import Orbit, orbit

__all__ = [
    "ChatteringDetected",
    "NotCertified",
    "FlightCertificate",
    "GrazingContact",
    "Orbit",
    "UndecidableCollision",
    "certify_flight",
    "condition_number",
    "flight_time",
    "gap",
    "grazing_contact",
    "grazing_departure",
    "jacobian",
    "orbit",
    "periodic_orbit",
    "step",
    "CheckReport",
    "Failure",
    "assert_integrator",
    "check_integrator",
    "__version__",
]

try:
    __version__ = _version("bouncer-verify")
except PackageNotFoundError:  # run from a source tree that was never installed
    __version__ = "0+unknown"
