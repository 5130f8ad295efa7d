"""The Holmes map: the plate's displacement neglected, its velocity kept (docs/model.md).

    phi1 = (phi + 2*v) mod 2*pi,      v1 = |v - 2*eps*sin(phi1)|

The flight time is 2*v; the exact map agrees with it to O(eps/v). phi + 2*v is reduced exactly
(``fastpath.elastic.landing.landing_phase``): a few ulps of 2*pi at any v.
"""

import math

from fastpath.arithmetic.jit import jit
from fastpath.elastic.landing import landing_phase


@jit
def holmes_collide(phi, v, eps):
    """Return (phi1, v1) of the Holmes map."""
    phi1 = landing_phase(phi, 2.0 * v, 0.0)
    return phi1, abs(v - 2.0 * eps * math.sin(phi1))
