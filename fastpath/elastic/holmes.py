"""The Holmes map: the plate's displacement neglected, its velocity kept (DESIGN fact 5).

    phi1 = (phi + 2*v) mod 2*pi,      v1 = |v - 2*eps*sin(phi1)|

The flight time is 2*v; the exact map agrees with it to O(eps/v).
"""

import math

from fastpath.arithmetic.jit import jit
from fastpath.arithmetic.phase import reduce_phase


@jit
def holmes_collide(phi, v, eps):
    """Return (phi1, v1) of the Holmes map."""
    phi1 = reduce_phase(phi + 2.0 * v)
    return phi1, abs(v - 2.0 * eps * math.sin(phi1))
