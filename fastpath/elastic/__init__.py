"""The paper's exact map: one flight and one elastic impact (Dettmann & Leonel, equations (1)-(2)).

A particle leaves the plate at phase phi with velocity v; the gap between them after a time t is

    d(t) = eps*(cos(phi) - cos(phi + t)) + t*(v - t/2),

the flight time tau is its smallest positive root, and the impact reverses the velocity relative
to the plate (u = -eps*sin(phi + tau)):

    phi1 = (phi + tau) mod 2*pi,      v1 = 2*u - (v - tau) = tau - v - 2*eps*sin(phi + tau).

Reading order:

``gap``          d, d' and their rounding bounds; the departure speed w0 = v + eps*sin(phi).
``lower_bound``  the paper's lower-bound step, never past the first root (any eps).
``concave``      |eps| <= 1: a concave gap, one root, Halley in a certified bracket.
``tight_gap``    the gap near a short near-triple root, with a bound scaled to its terms.
``lockstep``     the common concave flight in straight-line code (the ensembles' lanes).
``flight``       the choice of method for one flight; the departure checks.
``collision``    the map (phi, v) -> (phi1, v1, tau).
``holmes``       the Holmes map, flight time 2*v.
"""
