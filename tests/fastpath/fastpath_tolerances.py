"""Tolerances of the fastpath property suite, derived from the unit roundoff (never tuned).

Flight time
-----------
The fast solver stops at a float t where the computed gap is within its error bound of zero,

    gap_error(t) = 4u*(|eps|*min(t, 2)*(|phi| + t + 3) + t*(|v| + t)),      u = 2**-53,

so at the stop the exact gap is within (computed gap) + (its actual rounding error) of zero,
and the root within that divided by |d'(tau)| of t, to first order. With the condition number

    kappa = (|v| + tau + |eps|*(1 + |phi| + tau)) / |d'(tau)|,
    d'(tau) = v - tau + eps*sin(phi + tau),

and min(t, 2)/t <= 1, |phi| + t + 3 <= 3*(1 + |phi| + t):

    gap_error(tau) / (|d'(tau)| * tau) <= 4u*(3*|eps|*(1 + |phi| + tau) + |v| + tau) / |d'(tau)|
                                       <= 12 * kappa * u.

One ulp of t (<= 2u*t, and kappa >= 1) for the last rounding of the iterate gives 14. The last
2 cover the actual rounding of the final computed gap and the linearisation: gap_error already
carries a factor 4 over the handful of roundings it bounds, so the actual error is ~gap_error/4
(~3 kappa u, of which 2 are budgeted; a worst case where every rounding adds up would need 26).

    |tau_fast - tau_ref| / tau_ref <= K * kappa * u,     K = 16.

Map outputs
-----------
phi1 = (phi + tau) mod 2*pi in float64: the tau error, the rounding of the sum (half an ulp of
|phi| + tau + 2*pi), and two Cody-Waite reductions (of phi if unreduced, of the sum), each a few
ulps of 2*pi: ``phase_rounding`` = 2*ulp(|phi| + tau + 2*pi) + 8*ulp(2*pi).
v1 = tau - v - 2*eps*sin(phi1): the tau error enters with weight 1 directly and 2|eps| through
the phase, the phase rounding with weight 2|eps|, and the three roundings of the formula are a
few ulps of |tau| + |v| + 2|eps|.

Kappa is computed here in mpmath (the formula above, as in ``verify.condition_number``) so that
fastpath-only tests do not need ``verify``; it is a scale, evaluated at the reference tau when
one is known and at the fast tau otherwise.
"""

import math

import mpmath
from mpmath import mp

from fastpath.elastic.gap import gap_error as _fast_gap_error

U = 2.0**-53
# Module docstring: 12 (gap_error/(|d'|*tau)) + 2 (one ulp of t) + 2 (final rounding, 1st order)
K = 16
ULP_2PI = math.ulp(2.0 * math.pi)
FLOAT_PI_ERROR = abs(float(mpmath.pi - mpmath.mpf(math.pi)))  # |pi - float(pi)| ~ 1.2e-16
DPS = 50  # working digits of every exact (mpmath) evaluation in the suite


def mpf(x):
    """x as an exact mpf (a float64 converts exactly)."""
    return mp.mpf(x)


def kappa(phi, v, eps, tau):
    """Condition number of the flight time (module docstring), an mpf; inf at a graze."""
    with mp.workdps(DPS):
        phi, v, eps, tau = mpf(phi), mpf(v), mpf(eps), mpf(tau)
        num = abs(v) + tau + abs(eps) * (1 + abs(phi) + tau)
        den = abs(v - tau + eps * mp.sin(phi + tau))
        return mp.inf if den == 0 else num / den


def tau_tolerance(phi, v, eps, tau):
    """Absolute tolerance K*kappa*u*tau on a fast flight time (tau: reference or fast)."""
    with mp.workdps(DPS):
        return K * kappa(phi, v, eps, tau) * U * mpf(tau)


def tau_error_units(tau_fast, tau_ref, phi, v, eps):
    """|tau_fast - tau_ref| / (kappa*u*tau_ref): the figure held to <= K."""
    with mp.workdps(DPS):
        tau_ref = mpf(tau_ref)
        err = abs(mpf(tau_fast) - tau_ref)
        return float(err / (kappa(phi, v, eps, tau_ref) * U * tau_ref))


def phase_rounding(phi, tau):
    """Rounding of the float phase (phi + tau) mod 2*pi besides the tau error (docstring)."""
    return 2.0 * math.ulp(abs(float(phi)) + abs(float(tau)) + 2.0 * math.pi) + 8.0 * ULP_2PI


def phi1_tolerance(phi, v, eps, tau):
    """Absolute tolerance on phi1 (as a distance mod 2*pi)."""
    return float(tau_tolerance(phi, v, eps, tau)) + phase_rounding(phi, tau)


def v1_tolerance(phi, v, eps, tau):
    """Absolute tolerance on v1 = tau - v - 2*eps*sin(phi1)."""
    e2 = 2.0 * abs(float(eps))
    tau_tol = float(tau_tolerance(phi, v, eps, tau))
    return (
        (1.0 + e2) * tau_tol
        + e2 * phase_rounding(phi, tau)
        + 4.0 * math.ulp(abs(float(tau)) + abs(float(v)) + e2)
    )


def phase_distance(a, b):
    """|a - b| mod 2*pi, folded into [0, pi], as an mpf (exact inputs, DPS digits)."""
    with mp.workdps(DPS):
        two_pi = 2 * mp.pi
        d = (mpf(a) - mpf(b)) % two_pi
        return min(d, two_pi - d)


def exact_gap(phi, v, eps, t):
    """d(t) of the float (or mpf) inputs at DPS digits, in product form (no cancellation)."""
    with mp.workdps(DPS):
        phi, v, eps, t = mpf(phi), mpf(v), mpf(eps), mpf(t)
        half = t / 2
        return 2 * eps * mp.sin(phi + half) * mp.sin(half) + t * (v - half)


def exact_gap_rate(phi, v, eps, t):
    with mp.workdps(DPS):
        return mpf(v) - mpf(t) + mpf(eps) * mp.sin(mpf(phi) + mpf(t))


def exact_gap_curvature(phi, eps, t):
    with mp.workdps(DPS):
        return -1 + mpf(eps) * mp.cos(mpf(phi) + mpf(t))


def exact_w0(phi, v, eps):
    """w0 = v + eps*sin(phi) of the float inputs, exactly (DPS digits)."""
    with mp.workdps(DPS):
        return mpf(v) + mpf(eps) * mp.sin(mpf(phi))


def fast_gap_error(phi, v, eps, t):
    """fastpath's own bound on the rounding error of its gap (phi reduced as the solver does)."""
    from fastpath.arithmetic.phase import reduce_phase

    return _fast_gap_error(reduce_phase(float(phi)), float(v), float(eps), float(t))


def local_minimum_of_gap(phi, v, eps, t):
    """(s, d(s), d''(s)) at the local minimum of the exact gap nearest to t, or None when the
    gap is not convex there (no dip: d''(t) <= 0). Newton on d' from t, DPS digits."""
    with mp.workdps(DPS):
        s = mpf(t)
        if exact_gap_curvature(phi, eps, s) <= 0:
            return None
        for _ in range(100):
            c = exact_gap_curvature(phi, eps, s)
            if c <= 0:
                return None
            ds = exact_gap_rate(phi, v, eps, s) / c
            s -= ds
            if abs(ds) <= abs(s) * mpf(10) ** (-(DPS - 5)):
                break
        return s, exact_gap(phi, v, eps, s), exact_gap_curvature(phi, eps, s)


def uncertain_justification(phi, v, eps, t):
    """Why an UNCERTAIN/MAX_ITERATIONS answer at float t is legitimate, or None if it is not.

    fastpath returns UNCERTAIN where the computed gap is <= E = gap_error(t) and the computed
    slope r > -4*sqrt(b*E), b = |eps| - 1 (its curvature bound). If E bounds the rounding, the
    exact gap at t is <= 2E, and (the solver never oversteps by more than rounding) >= -E; a
    parabola of curvature c >= d''(dip) dips below d(t) by at most r**2/(2c) <= 8*b*E/c. So the
    minimum m of the dip satisfies -E*(1 + 8*b/c) <= m <= 2E: the clearance is within a few
    gap_error of zero. Returns (m, E, bound) when that holds, else None.
    """
    found = local_minimum_of_gap(phi, v, eps, t)
    if found is None:
        return None
    s, m, c = found
    b = abs(float(eps)) - 1.0
    if b <= 0:
        return None
    e = fast_gap_error(phi, v, eps, max(float(t), float(s)))
    c_min = min(float(c), float(exact_gap_curvature(phi, eps, t)))
    if c_min <= 0:
        return None
    lower = -e * (1.0 + 8.0 * b / c_min)
    if lower <= float(m) <= 2.0 * e:
        return float(m), e, lower
    return None
