"""A 60-digit reference for flights with drag, independent of the formulas of
``fastpath.dissipative.drag``.

The particle's motion is written in its textbook form (no stabilised rewriting: at 60 digits the
cancellations of these forms cost at most ~25 digits for drag >= 1e-12, far above float64):

    linear:     V = v*exp(-k t) + (exp(-k t) - 1)/k,   Y = (v + 1/k)*(1 - exp(-k t))/k - t/k
    quadratic:  rising  V = tan(atan(s v) - s t)/s,  Y = ln(cos(atan(s v) - s t)/cos(atan(s v)))/k
                falling from the top (or from v <= 0, with the virtual top at -atanh(-s v)/s
                when |s v| < 1; faster than terminal: V = -coth(...)/s) by the ODE solution
                V = (v - tanh(s t)/s)/(1 - s v tanh(s t)), Y = -ln(cosh(s t) - s v sinh(s t))/k
    k = 0:      V = v - t,  Y = t*(v - t/2)

Roots: the gap is sampled on a grid and every sampled local minimum is refined (Newton on d');
the first sign change (grid or refined minimum) is bracketed and solved by bisection-safe
``mp.findroot`` (anderson) with its sign checked at both ends of the bracket.
"""

import math

from mpmath import mp

DPS = 60
U = 2.0**-53
LINEAR, QUADRATIC = 1, 2
STOP_DIGITS = 30  # digits of a dip's position at which local_minimum stops (its docstring)


def particle(v, k, law, t):
    """(Y, V) at 60 digits."""
    with mp.workdps(DPS):
        v, k, t = mp.mpf(v), mp.mpf(k), mp.mpf(t)
        if k == 0:
            return t * (v - t / 2), v - t
        if law == LINEAR:
            e = mp.exp(-k * t)
            return (v + 1 / k) * (1 - e) / k - t / k, v * e + (e - 1) / k
        s = mp.sqrt(k)
        if v > 0:
            top = mp.atan(s * v) / s
            if t <= top:
                x0 = mp.atan(s * v)
                return mp.log(mp.cos(x0 - s * t) / mp.cos(x0)) / k, mp.tan(x0 - s * t) / s
            tp = t - top
            y_top = mp.log(1 + k * v * v) / (2 * k)
            return y_top - mp.log(mp.cosh(s * tp)) / k, -mp.tanh(s * tp) / s
        th = mp.tanh(s * t)
        y = -mp.log(mp.cosh(s * t) - s * v * mp.sinh(s * t)) / k
        return y, (v - th / s) / (1 - s * v * th)


def eta(vel, k, law):
    return k * vel if law == LINEAR else k * vel * abs(vel)


def gap(phi, v, eps, k, law, t):
    with mp.workdps(DPS):
        y, _ = particle(v, k, law, t)
        return y + mp.mpf(eps) * (mp.cos(mp.mpf(phi)) - mp.cos(mp.mpf(phi) + mp.mpf(t)))


def rate(phi, v, eps, k, law, t):
    with mp.workdps(DPS):
        _, vel = particle(v, k, law, t)
        return vel + mp.mpf(eps) * mp.sin(mp.mpf(phi) + mp.mpf(t))


def curvature(phi, v, eps, k, law, t):
    with mp.workdps(DPS):
        _, vel = particle(v, k, law, t)
        return -1 - eta(vel, mp.mpf(k), law) + mp.mpf(eps) * mp.cos(mp.mpf(phi) + mp.mpf(t))


def local_minimum(phi, v, eps, k, law, t):
    """(s, d(s)) at the local minimum of the gap near t (Newton on d'), None if not convex.

    Stops at 30 digits of s (STOP_DIGITS): the textbook forms lose up to ~25 digits to
    cancellation (module docstring) and a shallow dip divides that noise of d' by a small d''
    (linear drag 1e-8 with d'' ~ 1e-4 leaves Newton steps of ~1e-50 at 60 digits, which a
    52-digit stop never met: it returned None for a real dip). d(s) is second order in the
    error of s (d'(s) = 0), so 30 digits of s give d(s) to the working precision."""
    with mp.workdps(DPS):
        s = mp.mpf(t)
        for _ in range(200):
            c = curvature(phi, v, eps, k, law, s)
            if c <= 0:
                return None
            ds = rate(phi, v, eps, k, law, s) / c
            s -= ds
            if abs(ds) <= abs(s) * mp.mpf(10) ** -STOP_DIGITS:
                return s, gap(phi, v, eps, k, law, s)
        return None


def first_root(phi, v, eps, k, law, t_max, points=400):
    """(first root in (0, t_max], smallest sampled/refined gap before it) at 60 digits, or
    (None, smallest gap) if the gap stays positive on (0, t_max]."""
    with mp.workdps(DPS):
        t_max = mp.mpf(t_max)
        ts = [t_max * j / points for j in range(1, points + 1)]
        ds = [gap(phi, v, eps, k, law, t) for t in ts]
        lowest = min(ds)
        prev_t = mp.mpf(0)
        for j, (t, d) in enumerate(zip(ts, ds, strict=True)):
            if d <= 0:
                return _bracketed(phi, v, eps, k, law, prev_t, t), lowest
            if 0 < j < points - 1 and d < ds[j - 1] and d <= ds[j + 1]:
                found = local_minimum(phi, v, eps, k, law, t)
                if found is not None and prev_t < found[0] < ts[j + 1]:
                    lowest = min(lowest, found[1])
                    if found[1] <= 0:
                        return _bracketed(phi, v, eps, k, law, prev_t, found[0]), lowest
            prev_t = t
        return None, lowest


def _bracketed(phi, v, eps, k, law, a, b):
    """The root in (a, b] where the gap is > 0 at a (or a = 0) and <= 0 at b."""
    def f(t):
        return gap(phi, v, eps, k, law, t)

    assert a == 0 or f(a) > 0
    assert f(b) <= 0
    if f(b) == 0:
        return b
    if a == 0:  # d ~ w0*t near 0: move the left end off the root at 0
        a = b / 2**20
        while f(a) <= 0:
            a /= 2
    root = mp.findroot(f, (a, b), solver="anderson")
    assert a <= root <= b, "findroot left its bracket"
    return root


def tau_tolerance(d_error, phi, v, eps, k, law, tau):
    """|tau_fast - tau| allowed: the solver stops where the computed gap is within its bound
    E = d_error of zero, so the exact gap there is within 2E, and the root within 2E/|d'|
    (first order; the factor 1.25 on it covers the curvature over that distance), plus two
    ulps of tau for the last rounding."""
    slope = abs(rate(phi, v, eps, k, law, tau))
    return 2.5 * d_error / float(slope) + 2 * math.ulp(float(tau))


def kappa(phi, v, eps, k, law, tau):
    """The elastic condition number's scale (|v| + tau + |eps|*(1 + |phi| + tau))/|d'(tau)|."""
    with mp.workdps(DPS):
        num = abs(v) + tau + abs(eps) * (1 + abs(phi) + tau)
        return num / abs(rate(phi, v, eps, k, law, tau))
