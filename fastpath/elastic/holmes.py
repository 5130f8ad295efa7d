"""The Holmes map: the plate's displacement neglected, its velocity kept (docs/model.md).

    phi1 = (phi + 2*v) mod 2*pi,      v1 = |v - 2*eps*sin(phi1)|

The flight time is 2*v; the exact map agrees with it to O(eps/v). phi + 2*v is reduced exactly
(``fastpath.elastic.landing.landing_phase``): a few ulps of 2*pi at any v. ``holmes_phase`` is
that one phase, for every Holmes step of fastpath (``holmes_collide``, which the loops take,
and the Jacobians of ``fastpath.dynamics.kernels``).
"""

import math

from fastpath.arithmetic.jit import jit
from fastpath.elastic.landing import landing_phase


@jit
def holmes_phase(phi, v):
    """phi1 = (phi + 2*v) mod 2*pi in [0, 2*pi), reduced exactly (2*v is exact in float64)."""
    return landing_phase(phi, 2.0 * v, 0.0)


@jit
def holmes_collide(phi, v, eps):
    """Return (phi1, v1) of the Holmes map."""
    phi1 = holmes_phase(phi, v)
    return phi1, abs(v - 2.0 * eps * math.sin(phi1))
