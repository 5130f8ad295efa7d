"""Dynamics of the collision map in float64: periodic orbits, residues, Lyapunov exponents.

``periodic_orbit`` (Newton on F^p - id with the exact Jacobian), ``lyapunov`` (tangent map with
renormalisation, both clocks), ``separation`` (the same exponent from two nearby orbits),
``symmetric_orbit`` and ``critical_amplitude`` (Greene's residue criterion on the symmetric
orbits of the reversible map). Nothing here is a proof: ``verify.periodic_orbit`` certifies
orbits found here.
"""

from fastpath.dynamics.greene import (
    Approximant,
    CriticalAmplitude,
    Crossing,
    approximants,
    critical_amplitude,
    residue_crossing,
    symmetric_orbit,
)
from fastpath.dynamics.lyapunov import Lyapunov, lyapunov, separation
from fastpath.dynamics.periodic_orbit import OrbitNotFound, PeriodicOrbit, periodic_orbit

__all__ = [
    "Approximant",
    "CriticalAmplitude",
    "Crossing",
    "Lyapunov",
    "OrbitNotFound",
    "PeriodicOrbit",
    "approximants",
    "critical_amplitude",
    "lyapunov",
    "periodic_orbit",
    "residue_crossing",
    "separation",
    "symmetric_orbit",
]
