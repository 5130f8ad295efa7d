"""Construct the "chattering-graze" hard cases of ``verify.hard_cases``.

A chattering particle (restitution r < 1) leaves each impact with a small relative speed w. Near
the phase theta* = 2*pi - arccos(1/eps) (eps > 1) the relative acceleration A(t) = d''(t) =
-1 - eta(V) + eps*cos(phi + t) changes sign: before theta* the plate pulls the particle back,
after it the plate falls away faster than gravity. A departure at phi = theta* - delta with a
small w0 = w therefore has the gap (elastic, to third order, a = sqrt(eps**2 - 1))

    d(t) ~ w*t - a*delta*t**2/2 + a*t**3/6 = (a/6)*t*(t**2 - 3*delta*t + 6*w/a),

which has a double root (a tangency) at t = 3*delta/2 when w = 3*a*delta**2/8: a smaller w lands
in the dip right after the departure (two close roots), a larger w passes above it and the
particle flies off for an ordinary O(1) flight. At delta -> 0 the tangency merges with the
departure into a triple root at t = 0. The hump before the dip is ~a*delta**3/12 high.

Here, for each (eps, drag law, k, w, clearance c): phi = float(theta* - delta) with delta from
w = 3*a*delta**2/8, then v is tuned at 60 digits (Newton on v of the dip's minimum d(t_m) = c,
t_m found by Newton on d' = 0) and rounded to float64, and the clearance of the float64 inputs
is recomputed. ``tau`` is ``verify.certify_flight(...).tau`` rounded to float64.

Run: ``python scripts/chattering_grazes.py [--verbose]`` prints the table rows (the numbers of
``verify.hard_cases._CHATTER_GRAZES``; with ``--verbose`` also delta, w0, the certificate's
working digits and boxes, and verify's time). "0+" and "0-" are the two float64 values of v
next to the exact tangency v* (v_- <= v* < v_+): the dip's minimum of the float inputs is then
of order t_m*ulp(v) ~ 1e-17..1e-21, on either side of zero. The drag is written in its textbook
closed forms here (as in tests/fastpath/drag_reference.py), independent of
verify.dissipative.drag and fastpath.dissipative.drag.
"""

from __future__ import annotations

import math
import sys
import time

from mpmath import mp

DPS = 60  # digits the tangency is tuned to
WORK_DPS = 90  # working digits: the textbook drag forms cancel ~10 digits at drag 1e-8
LAWS = ("linear", "quadratic")


def particle(v, k, law, t):
    """(Y, V) of the particle under gravity and drag (textbook closed forms), at mp precision."""
    if k == 0:
        return t * (v - t / 2), v - t
    if law == "linear":
        e = mp.exp(-k * t)
        return (v + 1 / k) * (1 - e) / k - t / k, v * e + (e - 1) / k
    s = mp.sqrt(k)
    assert v > 0
    top = mp.atan(s * v) / s
    if t <= top:
        x0 = mp.atan(s * v)
        return mp.log(mp.cos(x0 - s * t) / mp.cos(x0)) / k, mp.tan(x0 - s * t) / s
    tp = t - top
    return mp.log(1 + k * v * v) / (2 * k) - mp.log(mp.cosh(s * tp)) / k, -mp.tanh(s * tp) / s


def eta(vel, k, law):
    return k * vel if law == "linear" else k * vel * abs(vel)


def gap(phi, v, eps, k, law, t):
    y, _ = particle(v, k, law, t)
    return y + 2 * eps * mp.sin(phi + t / 2) * mp.sin(t / 2)


def rate(phi, v, eps, k, law, t):
    return particle(v, k, law, t)[1] + eps * mp.sin(phi + t)


def curvature(phi, v, eps, k, law, t):
    vel = particle(v, k, law, t)[1]
    return -1 - eta(vel, k, law) + eps * mp.cos(phi + t)


def dip(phi, v, eps, k, law, t):
    """(t_m, d(t_m)): the local minimum of the gap near t (Newton on d')."""
    t = mp.mpf(t)
    for _ in range(200):
        step = rate(phi, v, eps, k, law, t) / curvature(phi, v, eps, k, law, t)
        t -= step
        if abs(step) <= abs(t) * mp.mpf(10) ** (8 - DPS):
            return t, gap(phi, v, eps, k, law, t)
    raise ArithmeticError("no dip")


def tune(phi, eps, k, law, w, delta, c):
    """v (mpf) with the dip's minimum exactly c, from the cubic model's tangency."""
    a = mp.sqrt(eps**2 - 1)
    v = -eps * mp.sin(phi) + w + c / (mp.mpf(1.5) * delta)
    t = mp.mpf(1.5) * delta
    for _ in range(200):
        t, m = dip(phi, v, eps, k, law, t)
        h = abs(v) * mp.mpf(10) ** -25
        _, m2 = dip(phi, v + h, eps, k, law, t)
        step = (m - c) / ((m2 - m) / h)
        v -= step
        if abs(step) <= abs(v) * mp.mpf(10) ** (10 - DPS):
            return v, t
    raise ArithmeticError(f"no tangency (a={a})")


def first_root(phi, v, eps, k, law, t_end, points=2000):
    """The first sign change of the gap on (0, t_end] (grid, then findroot), or None."""
    prev = mp.zero
    for j in range(1, points + 1):
        t = t_end * j / points
        if gap(phi, v, eps, k, law, t) <= 0:
            lo_ = prev if prev > 0 else t / 2**30
            return mp.findroot(lambda s: gap(phi, v, eps, k, law, s), (lo_, t), solver="anderson")
        prev = t
    return None


# (eps, law, k, nominal w, clearances)
PLAN = (
    (1.5, "linear", 0.0, 1e-3, ("1e-6", "1e-10", "1e-14", "0+", "0-", "-1e-14", "-1e-10", "-1e-6")),
    (1.5, "linear", 0.0, 1e-5, ("1e-10", "1e-14", "0+", "0-", "-1e-14", "-1e-10")),
    (1.5, "linear", 0.0, 1e-8, ("1e-14", "0+", "0-", "-1e-14")),
    (1.5, "linear", 0.0, 1e-9, ("1e-15", "1e-16", "0+", "0-", "-1e-15")),
    (3.0, "linear", 0.0, 1e-6, ("1e-10", "0+", "0-", "-1e-10")),
    *[(1.5, law, 1e-8, w, cs) for law in LAWS
      for w, cs in ((1e-3, ("1e-6", "1e-10", "0+", "0-", "-1e-10", "-1e-6")),
                    (1e-8, ("0+", "0-")))],
)


def build(eps, law, k, w, c_text):
    import verify

    with mp.workdps(WORK_DPS):
        eps_m, k_m, c = mp.mpf(eps), mp.mpf(k), mp.mpf(c_text.rstrip("+-") or 0)
        a = mp.sqrt(eps_m**2 - 1)
        delta = mp.sqrt(8 * mp.mpf(w) / (3 * a))
        theta = 2 * mp.pi - mp.acos(1 / eps_m)
        phi = float(theta - delta)
        v_star, t_m = tune(mp.mpf(phi), eps_m, k_m, law, mp.mpf(w), delta, c)
        v = float(v_star)
        if c_text in ("0-", "0+"):  # the float64 neighbours of the exact tangency: v_- <= v* < v_+
            if mp.mpf(v) > v_star:
                v = math.nextafter(v, -math.inf)
            if c_text == "0+":
                v = math.nextafter(v, math.inf)
        t_m, clearance = dip(mp.mpf(phi), mp.mpf(v), eps_m, k_m, law, t_m)
        w0 = mp.mpf(v) + eps_m * mp.sin(mp.mpf(phi))
    start = time.perf_counter()
    try:
        cert = verify.certify_flight(phi, v, eps, drag=k, drag_law=law)
        tau, dps = float(cert.tau), (cert.dps_used, cert.boxes)
    except verify.UndecidableCollision as err:
        tau, dps = None, str(err)[:60]
    seconds = time.perf_counter() - start
    return dict(phi=phi, v=v, eps=eps, law=law, k=k, w=w, c=c_text, delta=float(delta),
                t_m=float(t_m), clearance=float(clearance), w0=float(w0), tau=tau, dps=dps,
                seconds=round(seconds, 2))


def main(argv):
    """Print the rows of ``verify.hard_cases._CHATTER_GRAZES`` (``--verbose``: every figure)."""
    for eps, law, k, w, cs in PLAN:
        for c in cs:
            r = build(eps, law, k, w, c)
            if "--verbose" in argv:
                print(r, flush=True)
                continue
            print(f"    ({r['eps']!r}, \"{r['law']}\", {r['k']!r}, {r['w']!r}, \"{r['c']}\", "
                  f"{r['phi']!r}, {r['v']!r},\n     {r['t_m']!r}, {r['clearance']!r}, "
                  f"{r['tau']!r}),", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
