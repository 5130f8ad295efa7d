"""The exact collision map (phi, v) -> (phi1, v1) of the seed's equations (1)-(2).

After the flight time tau (``solve_flight``), with plate velocity u = -eps*sin(phi + tau) and
incoming velocity v_in = v - tau, the elastic impact gives

    phi1 = (phi + tau) mod 2*pi,      v1 = 2*u - v_in = tau - v - 2*eps*sin(phi + tau).
"""

import math

from fastpath._jit import jit
from fastpath.flight import solve_flight
from fastpath.phase import reduce_phase


@jit
def collide(phi, v, eps):
    """Return (phi1, v1, tau, iterations, status) for one flight and impact."""
    phi = reduce_phase(phi)
    tau, iterations, status = solve_flight(phi, v, eps)
    phi1 = reduce_phase(phi + tau)
    v1 = tau - v - 2.0 * eps * math.sin(phi1)
    return phi1, v1, tau, iterations, status
