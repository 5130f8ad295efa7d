"""Dynamics of the collision map in float64: periodic orbits, residues, Lyapunov exponents.

``periodic_orbit`` (Newton on F^p - id with the exact Jacobian), ``lyapunov`` (tangent map with
renormalisation, both clocks), ``lyapunov_by_band`` (its log-stretches by velocity band),
``separation`` (the same exponent from two nearby orbits),
``symmetric_orbit`` and ``critical_amplitude`` (Greene's residue criterion on the symmetric
orbits of the reversible map), ``accelerator_search``, ``velocities`` and ``first_passage``
(ensembles). Nothing here is a proof: ``verify.periodic_orbit`` certifies
orbits found here.
"""

from fastpath.dynamics.accelerator import search as accelerator_search
from fastpath.dynamics.ensemble import first_passage, velocities
from fastpath.dynamics.greene import (
    Approximant,
    CriticalAmplitude,
    Crossing,
    approximants,
    critical_amplitude,
    residue_crossing,
    symmetric_orbit,
)
from fastpath.dynamics.jacobian import step_jacobian
from fastpath.dynamics.lyapunov import BandExponents, Lyapunov, lyapunov, separation
from fastpath.dynamics.lyapunov import by_band as lyapunov_by_band
from fastpath.dynamics.periodic_orbit import OrbitNotFound, PeriodicOrbit, periodic_orbit

__all__ = [
    "Approximant",
    "BandExponents",
    "CriticalAmplitude",
    "Crossing",
    "Lyapunov",
    "OrbitNotFound",
    "PeriodicOrbit",
    "accelerator_search",
    "approximants",
    "critical_amplitude",
    "first_passage",
    "lyapunov",
    "lyapunov_by_band",
    "periodic_orbit",
    "residue_crossing",
    "separation",
    "step_jacobian",
    "symmetric_orbit",
    "velocities",
]
