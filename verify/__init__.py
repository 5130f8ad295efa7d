"""Independent reference for the bouncer model: mpmath precision plus interval certificates.

Never imports ``fastpath`` (the independence rule of DESIGN.md Section 3).
"""

from .certify import FlightCertificate, certify_flight, flight_time
from .check import CheckReport, Failure, assert_integrator, check_integrator, load_callable
from .collision import step
from .conditioning import condition_number
from .dynamics import NotCertified, periodic_orbit
from .errors import ChatteringDetected, UndecidableCollision
from .gap import gap
from .grazing import GrazingContact, grazing_contact, grazing_departure
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
    "load_callable",
]
