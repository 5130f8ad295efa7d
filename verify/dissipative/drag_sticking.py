"""Chattering, accumulation, sticking and detachment with drag and restitution r < 1.

The no-drag case is :mod:`verify.dissipative.sticking`, whose structure this module follows.
Independent of ``fastpath``.

Relative motion. Let x = y - eps*cos(theta) be the gap (particle minus plate), theta the phase
(time), u(theta) = -eps*sin(theta) the plate's velocity and V = u + x' the particle's. In flight
V' = -1 - eta(V) (eta(V) = k*V "linear", k*V*|V| "quadratic", nondecreasing, eta(0) = 0), so

    x'' = -1 - eta(u + x') + eps*cos(theta) = -a(theta) - [eta(u + x') - eta(u)],
    a(theta) = 1 + eta(u(theta)) - eps*cos(theta)        (the riding force)

and an impact maps x' = w_in < 0 to w = -r*w_in. The bracket has the sign of x'.

1. Accumulation (:func:`drag_accumulation`). After an impact at phase theta with relative
velocity w > 0 (an interval ``iw``), take the time window [0, H], H = 2*T0, T0 = 2*w/(a*(1-r)),
and the velocity box W = 2*hi(w). In interval arithmetic over the phase box Theta = theta + [0, H]
and the relative velocities [-W, W]:

    a_lo <= 1 + eta(u(Theta) + [-W, W]) - eps*cos(Theta) <= a_hi,     a_lo > 0,  rho = a_hi/a_lo,

(eta's enclosure from the ends of its argument: eta is nondecreasing). While the motion stays
in the window with |x'| <= W, -a_hi <= x'' <= -a_lo, and the no-drag argument applies verbatim:
a flight from w lasts 2*w/a_hi <= tau <= 2*w/a_lo, x' decreases from w to w_in with
-w_in in [w*(2/rho - 1), w*(2*rho - 1)], so the next w' = -r*w_in is in
[r*w*(2/rho - 1), r*w*(2*rho - 1)] and |x'| <= w*(2*rho - 1) during the flight. With
g = r*(2*rho - 1) < 1, w_k <= w*g**k <= w, so |x'| <= hi(w)*(2*rho - 1) < W when 2*rho - 1 < 2
(checked): the velocity bound holds strictly wherever the acceleration bound was used, so by
continuity (first time where |x'| = W: impossible) it holds throughout. Summing,

    T_lo = 2*w/(a_hi*(1 - r*max(2/rho - 1, 0))) <= T <= T_hi = 2*w/(a_lo*(1 - g)),

provided T_hi <= H (every flight then lies in the window, by induction). This is PROVED (iv
arithmetic with outward rounding; ``ArithmeticError`` if the model value below falls outside it).
Its width is O(T0**2).

The value used (the model, derived as in
``fastpath.dissipative.sticking.drag_accumulation_tail`` but independently): to first
order x'' = -a + J*t - c*x' with J = dA/dtheta = c*eps*cos(theta) - eps*sin(theta) (A = -a at
x' = 0) and c = eta'(u) (k, resp. 2*k*|u|). One flight from w: x = w*t - a*t**2/2 + J*t**3/6 -
c*(w*t**2/2 - a*t**3/6), so tau = tau0 + J*tau0**2/(3a) - c*tau0**2/6 (tau0 = 2w/a) and
w_in = -w*(1 - c*tau0/3) + J*tau0**2/6. Summing the drag part over w_k ~ r**k*w*prod(1 - c*tau0_j/3)
gives -c*tau0**2*[r/(3(1-r)**2(1+r)) + 1/(6(1-r**2))] = -c*T0**2/6, so

    T = T0 + J*T0**2/(3a) - c*T0**2/6 + R,

with |R| <= C*q*T0, q = T0**2*(J**2/a**2 + |J|*c/a + c**2 + A2/a + p2*a), A2 = |eps|*(1 + k)
(linear) or |eps| + 2*k*eps**2 (quadratic) bounding |A''|, p2 = |eta''| (0, resp. 2k). C <= 1/2
is NOT proved: it is measured (tests/verify/test_drag_sticking_verify.py: the tail against the
impacts iterated at 70 digits stays inside the proved enclosure and agrees to the working
precision). The tail is summed once q*T0 <= 10**-dps (w ~ 10**(-dps/3)), so R is below the last
digit of the orbit's times, and the proved enclosure is ~10**(-2*dps/3) wide: the accumulation is
certified, its time to the working precision rests on the measured constant.

2. Riding and detachment (:func:`riding`). From the accumulation point the particle rides the
plate (x = x' = 0, V = u) while a >= 0 and leaves where a falls through 0.

Never detaches, decided EXACTLY (the inputs are binary numbers; rational arithmetic):
linear drag, a = 1 - eps*(cos(theta) + k*sin(theta)) = 1 - E*cos(theta - beta'), E =
|eps|*sqrt(1 + k**2), beta' = atan(k) (eps > 0) or atan(k) + pi (eps < 0), so min a = 1 - E and
the particle can leave iff eps**2*(1 + k**2) > 1 (at equality a touches 0 without crossing:
never). Quadratic drag, in the frame e = |eps|, theta' = theta (eps > 0) or theta - pi:
a = 1 - f, f = e*cos(theta') + k*e**2*sin(theta')*|sin(theta')|; on sin >= 0 f = e*c + k*e**2*(1 -
c**2) (c = cos theta') is largest at c = 1/(2ke) if 2ke > 1 (max k*e**2 + 1/(4k)), else at c = 1
(max e); on sin < 0 f <= e*c <= e. So the particle can leave iff e > 1 (2ke <= 1), resp.
4*k**2*e**2 - 4*k + 1 > 0 (2ke > 1). Stuck for good: ``t_end = inf``, ``stopped = "stuck"``.

Where it can leave, the detachment phase theta* and the end theta_2 of the arc where a < 0 are
isolated in iv (:func:`_isolate`): boxes Theta*, Theta_2 with a(lo) > 0 > a(hi), a' < 0 on
Theta* (one simple falling root) and a(lo) < 0 < a(hi), a' > 0 on Theta_2. Candidates (not
rigorous): linear theta* = beta' - alpha, theta_2 = beta' + alpha, alpha = arccos(1/E) =
atan(sqrt(E**2 - 1)) (the closed form: theta* = atan(k) - arccos(1/E) mod 2*pi for
eps > 0, + pi for eps < 0); quadratic by bisection of f - 1 on its increasing branch
[theta'_min, theta'_max] and decreasing branch [theta'_max, theta'_min + 2*pi] (theta'_max =
arccos(1/(2ke)), theta'_min = -arccos(-1/(2ke)) if 2ke > 1, else 0 and -pi; f' =
sin*(2k*e**2*c - e) on sin > 0, |sin|*(e + 2k*e**2*c) on sin < 0). Then :func:`_prove_arc`
proves a < 0 on (theta*, theta_2) and a > 0 on (theta_2, theta* + 2*pi) in iv: monotone pieces
next to each root (a' of one sign on [lo(Theta), hi(Theta) + delta], a vanishing at the root
inside) and boxes with a proved sign in between (:func:`_has_sign`: the interval value of a,
or its mean-value form). So the sign of a over a whole period is
PROVED: a ride that starts where a > 0 (the accumulation phase, where a >= a_lo > 0 is proved by
step 1) lasts until the next theta* (:func:`riding_time`), and never ends in the middle of the
arc where the plate already pulls away. Undecided (E within ~10**-wdps of 1, where the two
roots merge, or a degenerate root with a' = 0 such as e = 1 with 2ke > 1 quadratic) raises the
precision and finally :class:`UndecidableCollision`: no guess.

3. Flight from detachment (:func:`drag_detachment_flight`). Departure at the exact theta* with
V = u(theta*), x = x' = 0, known only through the enclosure Theta* (the departure velocity
is the interval u(Theta*): no rounded state with a w0 that is only nearly 0 enters the proof).
x' > 0 on (0, theta_2 - theta*): where x' <= 0, x'' = -a - [eta(u + x') - eta(u)] >= -a > 0,
so x' cannot reach or stay at a value <= 0 after starting at 0 (if x'(t1) <= 0, on the last
stretch [s, t1] with x' <= 0 and x'(s) = 0, x' increases strictly: x'(t1) > 0, a contradiction).
Hence the gap d = x > 0 on (0, free], free = lo(Theta_2) - hi(Theta*) (rounded down), for every
nondecreasing eta. The certificate :func:`verify.numerics.first_root.search_first_root` (Taylor
boxes, candidate search) runs from there on the drag gap of :mod:`verify.dissipative.drag_gap`
evaluated for the phase interval Theta* and the velocity interval u(Theta*): every enclosure is
valid for all departures in the box, the exact one included.
"""

from __future__ import annotations

import threading
from fractions import Fraction
from typing import NamedTuple

from ..elastic.gap import departure_speed
from ..errors import ChatteringDetected, UndecidableCollision
from ..numerics.first_root import local_candidate, search_first_root
from ..numerics.phase import reduce_phase, time_until
from ..numerics.precision import (
    GUARD_DPS,
    NotDecided,
    default_max_dps,
    escalate,
    hi,
    iv,
    lo,
    mid,
    mp,
    working_dps,
)
from .drag import LAWS, DragFlight
from .drag_gap import DragGap
from .impact import Impact, detachment_impact, landing
from .sticking import WINDOW, Accumulation, geometric_enclosure, summed_tail

_MAX_DEPTH = 60  # halvings of a box in the sign proofs of the riding force
_MAX_ARC_BOXES = 20_000  # boxes per sign proof of an arc: beyond it, NotDecided


# --- the riding force a(theta) in interval arithmetic ------------------------------------------
def _force(ieps, ik, law, ith, rel=None):
    """``1 + eta(u + rel) - eps*cos(theta)`` over the phase interval ``ith`` (``u = -eps*sin``),
    ``rel`` an interval of relative velocities (default 0: the riding force ``a``)."""
    vel = -ieps * iv.sin(ith)
    if rel is not None:
        vel = vel + rel
    return 1 + LAWS[law].eta(ik, vel) - ieps * iv.cos(ith)


def _force_slope(ieps, ik, law, ith):
    """``a'(theta) = eta'(u)*u' + eps*sin(theta)``, ``u' = -eps*cos(theta)``."""
    u = -ieps * iv.sin(ith)
    return LAWS[law].eta_prime(ik, u) * (-ieps * iv.cos(ith)) + ieps * iv.sin(ith)


# --- 1. accumulation -----------------------------------------------------------------------------
def drag_accumulation(phi, v, eps, k, law, r, dps: int) -> Accumulation | None:
    """The summed tail from the impact state ``(phi, v)`` (exact ``mpf``) with drag ``k``, or None
    when the module docstring's conditions (``q*T0 <= 10**-dps``, the enclosure proved) fail.

    Computed at ``dps + 10`` digits; ``tail`` (the model T), ``enclosure`` ``(T_lo, T_hi)``
    (proved) and ``phase`` (theta + T) are returned at that precision.
    """
    with working_dps(dps + GUARD_DPS) as prec:
        model = _tail_model(phi, v, eps, k, law, r, prec)
        if model is None or not model.q * model.t0 <= mp.mpf(10) ** (-dps):
            return None
        iphi, iw, w, a, jerk, c, t0, q = model
        enclosure = _enclosure(iphi, iw, iv.mpf(eps), iv.mpf(k), law, iv.mpf(r), WINDOW * t0)
        if enclosure is None:
            return None
        return summed_tail(t0 + jerk * t0**2 / (3 * a) - c * t0**2 / 6, enclosure, iphi,
                           phi=phi, v=v, drag=k, drag_law=law)


class _TailModel(NamedTuple):
    """The accumulation model's terms after an impact (module docstring, 1.): the phase and
    ``w`` enclosures, ``w``, the riding force ``a``, ``J``, ``c = eta'(u)``, ``T0`` and
    ``q`` (the tail's relative second-order term over ``T0``)."""

    iphi: object
    iw: object
    w: object
    a: object
    jerk: object
    c: object
    t0: object
    q: object


def _tail_model(phi, v, eps, k, law, r, prec) -> _TailModel | None:
    """:class:`_TailModel` at the current precision ``prec``, or None unless ``w > 0`` and
    ``a > 0`` are proved and ``r < 1``."""
    iphi = reduce_phase(phi, prec).enclosure
    iw = departure_speed(phi, v, eps, prec)  # w to prec bits of itself
    ia = _force(iv.mpf(eps), iv.mpf(k), law, iphi)
    if not (lo(iw) > 0 and lo(ia) > 0 and r < 1):
        return None
    w, a = mid(iw), mid(ia)
    u = -eps * mp.sin(mid(iphi))
    c, a2, p2 = LAWS[law].tail_terms(eps, k, u)
    jerk = c * eps * mp.cos(mid(iphi)) - eps * mp.sin(mid(iphi))
    t0 = 2 * w / (a * (1 - r))
    q = t0**2 * (jerk**2 / a**2 + abs(jerk) * c / a + c**2 + a2 / a + p2 * a)
    return _TailModel(iphi, iw, w, a, jerk, c, t0, q)


def _enclosure(iphi, iw, ieps, ik, law, ir, window):
    """``(T_lo, T_hi)`` proved on the window ``[0, window]`` (module docstring, 1.), or None."""
    big_w = 2 * hi(iw)
    accel = _force(ieps, ik, law, iphi + iv.mpf([0, window]), iv.mpf([-big_w, big_w]))
    a_lo, a_hi = iv.mpf(lo(accel)), iv.mpf(hi(accel))
    if not lo(a_lo) > 0 or not hi(2 * (a_hi / a_lo) - 1) < 2:  # |x'| <= hi(w)*(2*rho - 1) < W
        return None
    return geometric_enclosure(a_lo, a_hi, iw, ir, window)


# --- 2. riding and detachment --------------------------------------------------------------------
def _fraction(x) -> Fraction:
    sign, man, exp, _ = mp.mpf(x)._mpf_
    value = Fraction(man) * (Fraction(2) ** exp)
    return -value if sign else value


def leaves_plate_with_drag(eps, k, law) -> bool:
    """A particle riding the plate ever leaves it (module docstring, 2.): decided exactly on the
    binary values of ``eps`` and ``k`` by the law (:meth:`verify.dissipative.drag.LinearDrag.
    leaves_plate`)."""
    return LAWS[law].leaves_plate(abs(_fraction(eps)), _fraction(k))


class Riding(NamedTuple):
    """The sign structure of the riding force over one period (module docstring, 2.): ``a``
    falls through 0 at the unique theta* in ``theta_star`` (an ``iv`` box, ``lo`` in
    ``[-pi, 2*pi)``), is < 0 up to theta_2 in ``theta_2`` (an ``iv`` box right of it) and > 0
    from there to theta* + 2*pi. ``free``: ``lo(theta_2) - hi(theta_star)`` rounded down (the gap
    of the flight from detachment is > 0 on (0, free]). ``wdps``: the working digits."""

    theta_star: object
    theta_2: object
    free: object
    wdps: int


def _isolate(ieps, ik, law, c, falling):
    """An ``iv`` box around ``c`` holding exactly one root of ``a``, proved (module docstring):
    opposite signs at the ends and ``a'`` of one sign over the box; else :class:`NotDecided`."""
    for shift in (12, 24, 48):
        delta = mp.ldexp(1 + abs(c), shift - mp.prec)
        left, right = c - delta, c + delta
        a_l = _force(ieps, ik, law, iv.mpf(left))
        a_r = _force(ieps, ik, law, iv.mpf(right))
        slope = _force_slope(ieps, ik, law, iv.mpf([left, right]))
        if falling:
            proved = lo(a_l) > 0 and hi(a_r) < 0 and hi(slope) < 0
        else:
            proved = hi(a_l) < 0 and lo(a_r) > 0 and lo(slope) > 0
        if proved:
            return iv.mpf([left, right])
    raise NotDecided(f"root of the riding force near theta={mp.nstr(c, 20)} not isolated")


def _prove_arc(ieps, ik, law, left, right, sign):
    """Prove ``sign*a > 0`` strictly between the roots in the boxes ``left`` and ``right``
    (module docstring, 2.); :class:`NotDecided` when it cannot be done at this precision."""
    x0, x1 = hi(left), lo(right)
    span = x1 - x0
    if not span > 0:
        raise NotDecided("the two roots of the riding force are not separated")
    start = _monotone_end(ieps, ik, law, lo(left), x0, span, sign, +1)
    end = _monotone_end(ieps, ik, law, hi(right), x1, span, -sign, -1)
    if start >= end:
        return
    stack = [(start, end, 0)]
    boxes = 0
    while stack:
        a, b, depth = stack.pop()
        boxes += 1
        if _has_sign(ieps, ik, law, a, b, sign):
            continue
        if depth >= _MAX_DEPTH or boxes >= _MAX_ARC_BOXES:
            raise NotDecided(f"sign of the riding force not proved on [{mp.nstr(a, 15)}, "
                             f"{mp.nstr(b, 15)}]")
        m = (a + b) / 2
        stack += [(a, m, depth + 1), (m, b, depth + 1)]


def _has_sign(ieps, ik, law, a, b, sign) -> bool:
    """``sign*a(theta) > 0`` proved on ``[a, b]``: by the interval value of ``a`` over the box,
    else by the mean-value form ``a(m) + a'([a, b])*([a, b] - m)`` (``m`` the midpoint), whose
    overestimate is second order in the box's width: near the arc's extremum, where ``a`` is
    within ~1e-16 of 0 (``E`` just above 1), the plain interval value would need boxes of that
    width."""
    box = iv.mpf([a, b])
    val = _force(ieps, ik, law, box)
    if (lo(val) > 0) if sign > 0 else (hi(val) < 0):
        return True
    m = (a + b) / 2
    val = _force(ieps, ik, law, iv.mpf(m)) + _force_slope(ieps, ik, law, box) * (box - m)
    return (lo(val) > 0) if sign > 0 else (hi(val) < 0)


def _monotone_end(ieps, ik, law, outer, inner, span, slope_sign, direction):
    """The far end of a stretch from the root box (``outer``..``inner``) on which ``a'`` has the
    sign ``slope_sign``: a vanishes at the root, so a has the arc's sign on the rest of it."""
    delta = span / 2
    for _ in range(_MAX_DEPTH):
        end = inner + direction * delta
        box = iv.mpf([min(outer, end), max(outer, end)])
        slope = _force_slope(ieps, ik, law, box)
        if (lo(slope) > 0) if slope_sign > 0 else (hi(slope) < 0):
            return end
        delta /= 2
    return inner


def _riding_at(eps, k, law) -> Riding:
    """:class:`Riding` proved at the current precision (module docstring, 2.), or
    :class:`NotDecided`."""
    ieps, ik = iv.mpf(eps), iv.mpf(k)
    c_star, c_two = LAWS[law].riding_candidates(eps, k)
    star = _isolate(ieps, ik, law, c_star, falling=True)
    two = _isolate(ieps, ik, law, c_two, falling=False)
    _prove_arc(ieps, ik, law, star, two, -1)
    _prove_arc(ieps, ik, law, two, star + 2 * iv.pi, +1)
    return Riding(star, two, lo(iv.mpf(lo(two)) - hi(star)), mp.dps)


def riding(eps, k, law, dps: int, max_dps: int | None = None) -> Riding | None:
    """The sign structure of the riding force (module docstring, 2.): None when the particle
    never leaves the plate (decided exactly), else a :class:`Riding` proved at the first
    precision from ``dps + 10`` digits that decides it (doubled up to ``max_dps``, default
    ``max(4*dps, 400)``); :class:`UndecidableCollision` beyond. Cached per inputs and thread."""
    if not leaves_plate_with_drag(eps, k, law):
        return None
    key = (eps, k, law, dps)
    cache = _caches.ridings
    if key not in cache:
        cache[key] = _escalate(lambda wdps: _riding_at(eps, k, law), eps, k, law, dps, max_dps,
                               "detachment")
    return cache[key]


def _escalate(attempt, eps, k, law, dps, max_dps, what):
    """:func:`verify.numerics.precision.escalate` from ``dps + 10`` digits up to ``max_dps``
    (default ``max(4*dps, 400)``); then :class:`UndecidableCollision`."""
    max_dps = default_max_dps(dps) if max_dps is None else max_dps

    def undecidable(wdps, why):
        return UndecidableCollision(None, None, eps, wdps, f"{what} with drag={k} ({law}): {why}")

    return escalate(attempt, dps, max_dps, undecidable)


def riding_time(phase, ride: Riding):
    """Time riding the plate from ``phase`` (where a > 0 is proved) to the next theta*:
    ``(theta* - phase) mod 2*pi`` in ``(0, 2*pi]`` at the current precision."""
    return time_until(mid(ride.theta_star), phase)


# --- 3. the flight from detachment ---------------------------------------------------------------
def drag_detachment_step(eps, k, law, r, dps: int, max_dps: int | None = None) -> Impact:
    """The impact ending the flight from detachment (module docstring, 3.), as an
    :class:`verify.dissipative.impact.Impact` (the same after every episode: cached per
    thread). The gap is :class:`verify.dissipative.drag_gap.DragGap` from the phase box theta*
    and the velocity box ``u(theta*)``; the first root's enclosure
    (:func:`verify.dissipative.impact.detachment_impact`) and the box flight's ``V`` over it give
    the impact (:func:`verify.dissipative.impact.landing`). The precision is raised as
    :func:`verify.certify_flight` does until the phase and velocity are known to ``dps`` digits;
    :class:`UndecidableCollision` at ``max_dps``."""
    key = (eps, k, law, r, dps)
    cache = _caches.steps
    if key not in cache:
        digits = [dps + 3]  # the flight time's relative digits, kept from attempt to attempt

        def attempt(wdps):
            ride = _riding_at(eps, k, law)
            ith = ride.theta_star
            ieps = iv.mpf(eps)

            flight = DragGap(mid(ith), ith, -ieps * iv.sin(ith), eps, k, law, dps, wdps).flight

            def search(enclosure_digits):
                ctx = DragGap(mid(ith), ith, -ieps * iv.sin(ith), eps, k, law, enclosure_digits,
                              wdps)
                return search_first_root(ctx, ctx.curvature_bound(), ride.free, None,
                                         candidate=local_candidate)[:2]

            def landing_of(left, right):
                v_in = flight.velocity_box(left, right)
                return landing(ith, iv.mpf([left, right]), v_in, eps, r)

            hit, digits[0] = detachment_impact(search, landing_of, eps, digits[0], dps)
            return hit

        cache[key] = _escalate(attempt, eps, k, law, dps, max_dps, "flight from detachment")
    return cache[key]


class _Caches(threading.local):
    """Per-thread caches (their numbers belong to the thread's own mpmath context)."""

    def __init__(self) -> None:
        self.ridings: dict = {}
        self.steps: dict = {}


_caches = _Caches()


class DragSticking:
    """The sticking model with drag and restitution ``r < 1``, for the orbit loop
    (:class:`verify.dissipative.sticking_model.StickingModel`): :func:`drag_accumulation`, the
    exact decision to leave the plate and the proved :class:`Riding`, and
    :func:`drag_detachment_step`; :meth:`check_chattering` stops a chattering run that crawls
    below any tail that could be summed (:class:`verify.ChatteringDetected`)."""

    def __init__(self, eps, k, law, r, dps: int) -> None:
        self.eps, self.k, self.law, self.r, self.dps = eps, k, law, r, dps

    def accumulation(self, phi, v) -> Accumulation | None:
        return drag_accumulation(phi, v, self.eps, self.k, self.law, self.r, self.dps)

    def leaves_plate(self) -> bool:
        return riding(self.eps, self.k, self.law, self.dps) is not None

    def riding_time(self, phase):
        return riding_time(phase, riding(self.eps, self.k, self.law, self.dps))

    def detachment_step(self) -> Impact:
        return drag_detachment_step(self.eps, self.k, self.law, self.r, self.dps)

    def check_chattering(self, n: int, t, phi, v) -> None:
        """:class:`verify.ChatteringDetected` after collision ``n`` when the relative velocity
        ``w = v + eps*sin(phi)`` fell far below where :func:`drag_accumulation` would sum the
        tail, while ``d''(0) < 0`` is proved (the plate pulls the particle back). "Far below":
        ``w < w_min = min(10**(-dps//2)*(1 + |v| + |eps|), w_tail*10**(-dps//6))``, ``w_tail``
        the relative velocity at which the model's ``q*T0`` reaches ``10**-dps`` with the
        riding force ``a`` and jerk at this impact (``w_tail ~ 10**(-dps/3)`` for ``a ~ 1``,
        much smaller where ``a`` is small, e.g. just after the phase where the plate stops
        pulling away, ``E`` close to 1)."""
        eps, dps = self.eps, self.dps
        with working_dps(dps + GUARD_DPS) as prec:
            w_min = mp.mpf(10) ** (-(dps // 2)) * (1 + abs(v) + abs(eps))
            model = _tail_model(phi, v, eps, self.k, self.law, self.r, prec)
            if model is not None:
                t0_tail = (mp.mpf(10) ** (-dps) * model.t0**3 / (model.q * model.t0)) ** (
                    mp.one / 3)
                w_tail = model.w * t0_tail / model.t0
                w_min = min(w_min, w_tail * mp.mpf(10) ** (-(dps // 6)))
            w = departure_speed(phi, v, eps, prec)
            if hi(w) >= w_min:
                return
            flight = DragFlight(v, self.k, self.law)
            curvature = -1 - flight.eta(iv.mpf(v)) + iv.mpf(eps) * iv.cos(iv.mpf(phi))
            if hi(curvature) < 0:
                raise ChatteringDetected(n, t, phi, v, eps, mp.mpf(hi(w)), w_min, dps)
