"""Certified dynamics of the exact collision map: periodic orbits by Krawczyk's operator.

Self-contained: private mpmath contexts per call (the global precision is never changed), and no
use of ``fastpath``.
"""

from verify.dynamics.errors import NotCertified
from verify.dynamics.numbers import Enclosure
from verify.dynamics.periodic_orbit import CertifiedOrbit, periodic_orbit

__all__ = ["CertifiedOrbit", "Enclosure", "NotCertified", "periodic_orbit"]
