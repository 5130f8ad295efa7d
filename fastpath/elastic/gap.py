"""The gap between particle and plate during a flight, and its rate of change.

For a departure at phase phi with velocity v, after a time t (docs/model.md):

    d(t)  = eps*(cos(phi) - cos(phi + t)) + t*(v - t/2)
          = 2*eps*sin(phi + t/2)*sin(t/2) + t*(v - t/2)        (no cancellation at small t)
    d'(t) = v - t + eps*sin(phi + t)

``gap_error`` and ``rate_error`` bound the rounding errors of ``gap`` and ``gap_rate`` in float64
(phi reduced); ``departure`` computes w0 = d'(0) = v + eps*sin(phi) with its error bound, and
``departure_verdict`` says whether the particle leaves the plate. The three bounds are inlined
where they are called, so that the lanes of ``fastpath.kernels.escape`` still vectorise with
their underflow allowance (``fastpath.arithmetic.rounding.plus_underflow``).
"""

import math

from fastpath.arithmetic.jit import inline_jit, jit
from fastpath.arithmetic.rounding import UNIT_ROUNDOFF, plus_underflow
from fastpath.status import CONVERGED, NOT_DEPARTING, OVERFLOW, UNCERTAIN


@jit
def gap(phi, v, eps, t):
    """d(t) = 2*eps*sin(phi + t/2)*sin(t/2) + t*(v - t/2)."""
    return 2.0 * eps * math.sin(phi + 0.5 * t) * math.sin(0.5 * t) + t * (v - 0.5 * t)


@jit
def gap_rate(phi, v, eps, t):
    """d'(t) = v - t + eps*sin(phi + t): particle velocity minus plate velocity."""
    return v - t + eps * math.sin(phi + t)


@inline_jit
def gap_error(phi, v, eps, t):
    """A bound on |computed gap - exact gap| at the float t.

    The plate term 2*eps*sin(phi + t/2)*sin(t/2) has magnitude <= |eps|*min(t, 2) and an argument
    error of about u*(|phi| + t); the flight term t*(v - t/2) is good to a few u*(t*|v| + t**2).
    The factor 4 covers the handful of roundings in each term. Results in the subnormal range
    round in absolute terms: six operations, two of them sines scaled by 2|eps|, add
    (4 + 2|eps|)*SUBNORMAL.
    """
    plate = abs(eps) * min(t, 2.0) * (abs(phi) + t + 3.0)
    flight = t * (abs(v) + t)
    return plus_underflow(4.0 * UNIT_ROUNDOFF * (plate + flight), 4.0 + 2.0 * abs(eps))


@inline_jit
def rate_error(phi, v, eps, t):
    """A bound on |computed d' - exact d'| at the float t: a few u of each term of
    v - t + eps*sin(phi + t), the sine's argument carrying u*(|phi| + t); in the subnormal
    range (2 + |eps|)*SUBNORMAL for the absolute rounding of the sum and the sine."""
    return plus_underflow(4.0 * UNIT_ROUNDOFF * (abs(v) + t + abs(eps) * (1.0 + abs(phi) + t)),
                          2.0 + abs(eps))


@inline_jit
def departure(phi, sin_phi, v, eps, phase_error):
    """(w0, bound) with w0 = fl(v + eps*sin_phi) and |w0 - (v + eps*sin(phi_exact))| <= bound.

    phase_error bounds |phi - phi_exact| (0 for a phase used as given; the reduction's error
    otherwise) plus any absolute error of sin_phi beyond libm's (a sine carried by rotation).
    The sine, the product and the sum each round by <= u of their size, or, where they are
    subnormal, by <= SUBNORMAL/2 in absolute terms (the sine's scaled by |eps|): (2 + |eps|)
    SUBNORMAL, without which a subnormal w0 would be judged certain. With eps = 0 or phi = 0
    nothing rounds (the product is an exact zero and w0 = v), and nothing is added.
    """
    w0 = v + eps * sin_phi
    bound = 2.0 * UNIT_ROUNDOFF * abs(w0) + 3.0 * UNIT_ROUNDOFF * abs(eps * sin_phi)
    exact = eps == 0.0 or (phi == 0.0 and sin_phi == 0.0)
    return w0, plus_underflow(bound + abs(eps) * phase_error, 0.0 if exact else 2.0 + abs(eps))


@jit
def departure_verdict(w0, bound):
    """CONVERGED for a certain departure (w0 > bound), NOT_DEPARTING where w0 <= 0 is certain
    (w0 <= -bound), UNCERTAIN where w0 is within its rounding bound of 0, OVERFLOW for a w0 that
    is not finite."""
    if not abs(w0) < math.inf:
        return OVERFLOW
    if not w0 > -bound:
        return NOT_DEPARTING
    if not w0 > bound:
        return UNCERTAIN
    return CONVERGED

