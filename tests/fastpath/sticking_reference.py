"""A 60-digit mpmath reference for inelastic impacts and chattering (independent of ``verify``).

Flights are written in relative coordinates (particle minus plate velocity w at departure):

    d(t) = w*t - t**2/2 + eps*(cos(phi)*(1 - cos(t)) - sin(phi)*(t - sin(t))),

the model's gap. A flight is solved only where its first root is certified by
concavity: either |eps| < 1 (d'' <= -1 + |eps| < 0 everywhere: one positive root, bracketed by
2w/(1 + |eps|) and 2w/(1 - |eps|)), or a = 1 - eps*cos(phi) > 0 and the plate's acceleration
keeps d'' <= -a/2 over [0, h], h = 4w/a (d''(s) <= -a + |eps*sin(phi)|*s + |eps|*s**2/2), so the
one root lies in [2w/(1 + |eps|), 2w/(a/2)]; Newton from the upper end moves monotonically
onto it (a concave function's tangent beyond the root crosses zero between them).
1 - cos(t) is 2*sin(t/2)**2 and t - sin(t) is evaluated with extra digits (w down to 1e-22
makes t tiny). The impact: w1 = -r*d'(tau). Accumulation: iterate until w < 1e-22, then add
the bare geometric tail T0 = 2w/(a(1 - r)) (its error is of order |J|*T0**2/a, ~1e-40 there,
far below u times any time compared).
"""

from mpmath import mp

DPS = 60


def _t_minus_sin(t):
    """t - sin(t) ~ t**3/6, its cancellation paid for with 3*log10(1/t) extra digits."""
    extra = max(0, -3 * int(mp.log10(t))) + 10
    with mp.workdps(mp.dps + extra):
        return +(t - mp.sin(t))


def _gap(phi, w, eps, t):
    one_minus_cos = 2 * mp.sin(t / 2) ** 2
    return w * t - t**2 / 2 + eps * (mp.cos(phi) * one_minus_cos - mp.sin(phi) * _t_minus_sin(t))


def _rate(phi, w, eps, t):
    one_minus_cos = 2 * mp.sin(t / 2) ** 2
    return w - t + eps * (mp.cos(phi) * mp.sin(t) - mp.sin(phi) * one_minus_cos)


def flight(phi, w, eps):
    """(tau, d'(tau)) of the certified first root (module docstring); raises if not certified."""
    with mp.workdps(DPS):
        phi, w, eps = mp.mpf(phi), mp.mpf(w), mp.mpf(eps)
        assert w > 0
        lo = 2 * w / (1 + abs(eps))
        if abs(eps) < 1:
            hi = 2 * w / (1 - abs(eps))
        else:
            a = 1 - eps * mp.cos(phi)
            assert a > 0, "the reference needs A < 0 at departure"
            h = 4 * w / a
            assert a - abs(eps * mp.sin(phi)) * h - abs(eps) * h**2 / 2 >= a / 2, "not certified"
            hi = h
        assert _gap(phi, w, eps, lo) >= 0 and _gap(phi, w, eps, hi) < 0
        t = hi  # Newton from beyond the root of a concave function: monotone down onto it
        for _ in range(100):
            step = _gap(phi, w, eps, t) / _rate(phi, w, eps, t)
            t -= step
            assert lo <= t <= hi
            if abs(step) <= t * mp.mpf(10) ** (-DPS + 3):
                break
        else:
            raise AssertionError("Newton did not converge")
        return t, _rate(phi, w, eps, t)


W_STOP = 1e-22


def chatter(phi, w, eps, r, w_stop=W_STOP):
    """(t_acc, impacts): time from (phi, w) to the accumulation point, number of impacts summed."""
    with mp.workdps(DPS):
        phi, w, eps, r = mp.mpf(phi), mp.mpf(w), mp.mpf(eps), mp.mpf(r)
        total, impacts = mp.mpf(0), 0
        while w > w_stop:
            tau, w_in = flight(phi, w, eps)
            total, phi, w, impacts = total + tau, phi + tau, -r * w_in, impacts + 1
        a = 1 - eps * mp.cos(phi)
        return total + 2 * w / (a * (1 - r)), impacts


def detachment_phase(eps):
    """theta* with eps*cos(theta*) = 1 and -eps*sin(theta*) > 0, in [0, 2*pi)."""
    with mp.workdps(DPS):
        eps = mp.mpf(eps)
        alpha = mp.acos(1 / abs(eps))
        return 2 * mp.pi - alpha if eps > 0 else mp.pi - alpha


def detachment_flight(eps):
    """First root of the exact gap from theta* with relative velocity 0 (a detachment):

        d(t) = sqrt(eps**2 - 1)*(t - sin(t)) - (t**2/2 - 1 + cos(t)),

    positive on (0, t_c], t_c = 2*arccos(1/|eps|) (d'' > 0 there). From t_c the paper's
    lower-bound steps (d'' >= -(1 + |eps|)) approach the first root from below, never past it,
    until d < 1e-50; Newton then finishes. Returns (tau, t_c).
    """
    with mp.workdps(DPS):
        eps = mp.mpf(eps)
        s = mp.sqrt(eps**2 - 1)

        def d(t):
            return s * _t_minus_sin(t) - (t**2 / 2 - 2 * mp.sin(t / 2) ** 2)

        def d1(t):
            return s * (1 - mp.cos(t)) - (t - mp.sin(t))

        a = 1 + abs(eps)
        t_c = 2 * mp.acos(1 / abs(eps))
        t = t_c
        assert d(t) > 0
        for _ in range(100000):
            g, r = d(t), d1(t)
            if g < mp.mpf(10) ** -50:
                break
            root = mp.sqrt(r * r + 2 * a * g)  # larger root of g + r*s - a*s**2/2, no cancellation
            t += (r + root) / a if r >= 0 else 2 * g / (root - r)
        else:
            raise AssertionError("lower-bound steps did not converge")
        for _ in range(5):
            t -= d(t) / d1(t)
        return t, t_c
