"""The gap between particle and plate during a flight, and its rate of change.

For a departure at phase phi with velocity v, after a time t (DESIGN section 2):

    d(t)  = eps*(cos(phi) - cos(phi + t)) + t*(v - t/2)
          = 2*eps*sin(phi + t/2)*sin(t/2) + t*(v - t/2)        (no cancellation at small t)
    d'(t) = v - t + eps*sin(phi + t)

``gap_error`` bounds the rounding error of ``gap`` in float64 (phi reduced to [0, 2*pi)).
"""

import math

from fastpath._jit import jit

UNIT_ROUNDOFF = 2.0**-53


@jit
def gap(phi, v, eps, t):
    """d(t) = 2*eps*sin(phi + t/2)*sin(t/2) + t*(v - t/2)."""
    return 2.0 * eps * math.sin(phi + 0.5 * t) * math.sin(0.5 * t) + t * (v - 0.5 * t)


@jit
def gap_rate(phi, v, eps, t):
    """d'(t) = v - t + eps*sin(phi + t): particle velocity minus plate velocity."""
    return v - t + eps * math.sin(phi + t)


@jit
def gap_error(phi, v, eps, t):
    """A bound on |computed gap - exact gap| at the float t.

    The plate term 2*eps*sin(phi + t/2)*sin(t/2) has magnitude <= |eps|*min(t, 2) and an argument
    error of about u*(|phi| + t); the flight term t*(v - t/2) is good to a few u*(t*|v| + t**2).
    The factor 4 covers the handful of roundings in each term.
    """
    plate = abs(eps) * min(t, 2.0) * (abs(phi) + t + 3.0)
    flight = t * (abs(v) + t)
    return 4.0 * UNIT_ROUNDOFF * (plate + flight)
