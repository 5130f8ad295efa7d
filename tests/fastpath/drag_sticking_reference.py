"""A high-precision mpmath reference for chattering and sticking with drag (no ``verify``, no
``fastpath``): the closed forms of the dissipation spec evaluated at DPS digits.

Particle from velocity v (V' = -1 - eta(V)):
  linear:    V = v*exp(-k t) + expm1(-k t)/k,  Y = (v + 1/k)*(1 - exp(-k t))/k - t/k
  quadratic: s = sqrt(k); rising (v > 0, t <= t_top = atan(s v)/s): V = tan(atan(s v) - s t)/s,
             Y = ln(cos(atan(s v) - s t)/cos(atan(s v)))/k; then falling from rest:
             V = -tanh(s t')/s, Y = Y_top - ln(cosh(s t'))/k; from v <= 0 (|s v| < 1):
             b = atanh(-s v), V = -tanh(b + s t)/s, Y = -ln(cosh(b + s t)/cosh(b))/k.
At DPS = 100 digits the direct forms lose at most ~30 digits to cancellation at the small times
used (t >= 1e-25), far more than the 20 the comparisons need.

Flights of a chattering sequence depart with a small relative velocity w > 0 where the riding
force a = 1 + eta(u) - eps*cos(phi) > 0: the gap is concave over the flight (its curvature is
-a + O(t)), so its one root in [tau0/4, 4*tau0] (tau0 = 2w/a, the signs checked) is found by
mp.findroot's bracketing solver.
"""

from mpmath import mp

DPS = 100
W_STOP = mp.mpf("1e-24")


def eta(v, k, law):
    return k * v if law == "linear" else k * v * abs(v)


def motion(v, k, law, t):
    """(Y(t), V(t)) from velocity v (module docstring)."""
    if law == "linear":
        e = mp.exp(-k * t)
        return (v + 1 / k) * (1 - e) / k - t / k, v * e + (e - 1) / k
    s = mp.sqrt(k)
    if v > 0:
        alpha = mp.atan(s * v)
        top = alpha / s
        if t <= top:
            return mp.log(mp.cos(alpha - s * t) / mp.cos(alpha)) / k, mp.tan(alpha - s * t) / s
        y_top = -mp.log(mp.cos(alpha)) / k
        rest = t - top
        return y_top - mp.log(mp.cosh(s * rest)) / k, -mp.tanh(s * rest) / s
    assert abs(s * v) < 1
    b = mp.atanh(-s * v)
    return -mp.log(mp.cosh(b + s * t) / mp.cosh(b)) / k, -mp.tanh(b + s * t) / s


def gap(phi, v, eps, k, law, t):
    y, vel = motion(v, k, law, t)
    return y + eps * (mp.cos(phi) - mp.cos(phi + t)), vel + eps * mp.sin(phi + t)


def short_flight(phi, w, eps, k, law):
    """(tau, d'(tau)) of the flight from phase phi with relative velocity w (module docstring)."""
    u = -eps * mp.sin(phi)
    v = u + w
    a = 1 + eta(u, k, law) - eps * mp.cos(phi)
    assert a > 0 and w > 0
    tau0 = 2 * w / a
    lo, hi = tau0 / 4, 4 * tau0
    assert gap(phi, v, eps, k, law, lo)[0] > 0 > gap(phi, v, eps, k, law, hi)[0]
    tau = mp.findroot(lambda t: gap(phi, v, eps, k, law, t)[0], (lo, hi), solver="anderson")
    assert lo < tau < hi
    return tau, gap(phi, v, eps, k, law, tau)[1]


def chatter(phi, w, eps, k, law, r, w_stop=W_STOP):
    """(t_acc, impacts): time from (phi, w) to accumulation: the impacts one by one until
    w < w_stop, then the bare geometric tail 2w/(a(1 - r)) (error of order T0**2 ~ 1e-48)."""
    with mp.workdps(DPS):
        phi, w, eps, k, r = (mp.mpf(x) for x in (phi, w, eps, k, r))
        total, impacts = mp.mpf(0), 0
        while w > w_stop:
            tau, w_in = short_flight(phi, w, eps, k, law)
            total, phi, w, impacts = total + tau, phi + tau, -r * w_in, impacts + 1
        u = -eps * mp.sin(phi)
        a = 1 + eta(u, k, law) - eps * mp.cos(phi)
        return total + 2 * w / (a * (1 - r)), impacts


def riding_f(theta, eps, k, law):
    """f(theta) = eps*cos(theta) - eta(u(theta)): the particle rides while f <= 1."""
    return eps * mp.cos(theta) - eta(-eps * mp.sin(theta), k, law)


def detachment_phase(eps, k, law, dps=50):
    """theta* in [0, 2*pi): f rises through 1 (dense scan for the sign change, then findroot)."""
    with mp.workdps(dps):
        eps, k = mp.mpf(eps), mp.mpf(k)
        n = 4000
        grid = [2 * mp.pi * j / n for j in range(n + 1)]
        vals = [riding_f(x, eps, k, law) - 1 for x in grid]
        roots = [j for j in range(n) if vals[j] < 0 <= vals[j + 1]]
        assert len(roots) == 1, roots
        j = roots[0]
        theta = mp.findroot(lambda x: riding_f(x, eps, k, law) - 1, (grid[j], grid[j + 1]),
                            solver="anderson")
        slope = mp.diff(lambda x: riding_f(x, eps, k, law), theta)
        return theta % (2 * mp.pi), slope
