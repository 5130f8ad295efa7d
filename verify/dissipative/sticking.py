"""Chattering, accumulation and sticking with restitution r < 1 and no drag (the dissipation spec).

Relative motion. Between impacts the gap x (particle minus plate) obeys x'' = A(theta) =
-1 + eps*cos(theta); an impact maps the relative velocity w_in < 0 to w = -r*w_in.

Accumulation (:func:`accumulation`). After an impact at phase theta with relative velocity
w > 0, write a = -A(theta) = 1 - eps*cos(theta) and J = A'(theta) = -eps*sin(theta). With A
frozen at -a every flight lasts 2*w/a and the impacts accumulate after the geometric sum
T0 = 2*w/(a*(1 - r)); the first correction from the jerk J gives (the model of
``fastpath.dissipative.sticking.elastic_accumulation_tail``, derived independently in the
project notes)

    T = T0 + J*T0**2/(3*a) + R,     |R| <= C*q*T0,   q = T0**2*(J**2/a**2 + |eps|/a),

with C <= 1/2 (not proved: measured here against impacts iterated to a 30 digits smaller w at
a higher precision, tests/verify/test_sticking.py). The tail is summed once q*T0 <= 10**-dps
(``w ~ 10**(-dps/3)``, about (dps/3)*ln(10)/ln(1/r) impacts), so R is below the last digit of
the orbit's times. Independently of the model, a RIGOROUS enclosure [T_lo, T_hi] of the time to
the accumulation point is proved in interval arithmetic (and T is required to lie in it):

    on a window [theta, theta + H] let a_lo <= -A <= a_hi (iv enclosure of eps*cos), a_lo > 0,
    rho = a_hi/a_lo. A flight from w > 0 on which a_lo <= -A <= a_hi lasts tau with
    2*w/a_hi <= tau <= 2*w/a_lo (w*t - a_hi*t**2/2 <= x(t) <= w*t - a_lo*t**2/2), and returns
    with -w_in = -w - integral(A) in [a_lo*tau - w, a_hi*tau - w], so the next w' = -r*w_in
    lies in [r*w*(2/rho - 1), r*w*(2*rho - 1)]. Summing the geometric bounds,

        T_lo = 2*w/(a_hi*(1 - r*max(2/rho - 1, 0))) <= T <= T_hi = 2*w/(a_lo*(1 - r*(2*rho - 1)))

    provided r*(2*rho - 1) < 1 and T_hi <= H (then every flight lies in the window, by
    induction). Its width is O(T0**2): with w ~ 10**(-dps/3), ~10**(-2*dps/3), a certificate of
    accumulation and a bound far below float64's rounding (the model's T is the value used).

Where A < 0 is not proved over the window (a chattering run reaching a phase where the plate
pulls away, eps*cos(theta) -> 1), no tail is summed: the impacts go on one by one and the
particle leaves with an ordinary flight. So the accumulation point always lies where
eps*cos(theta) < 1 and sticking starts there; it never lands where the plate already pulls away.

Sticking and detachment (:func:`detachment_phase`). From the accumulation point the particle
rides the plate (w = 0) while A <= 0, i.e. eps*cos(theta) <= 1. It leaves where A turns
positive: theta* = 2*pi - arccos(1/eps) for eps > 1, pi - arccos(1/|eps|) for eps < -1 (there
A' = -eps*sin(theta*) > 0), the first such phase after the accumulation phase; for |eps| <= 1
never (stuck for good).

Flight from detachment (:func:`detachment_step`). Departure at theta* with v = u(theta*) =
sqrt(eps**2 - 1) and w0 = 0 exactly. With eps*cos(theta*) = 1 the gap is, for either sign of eps,

    d(t) = s*(t - sin(t)) - (t**2/2 - 2*sin(t/2)**2),          s = sqrt(eps**2 - 1),
    d'(t) = 2*s*sin(t/2)**2 - (t - sin(t)),   d''(t) = -1 + cos(t) + s*sin(t).

d(0) = d'(0) = d''(0) = 0 and d'' = -1 + eps*cos(theta* + t) > 0 on (0, t_c),
t_c = 2*arccos(1/|eps|) (eps*cos returns to 1 there), so d(t) = integral_0^t (t - x)*d''(x) dx > 0
on (0, t_c]. The certificate (:func:`verify.numerics.first_root.search_first_root`, the proof
boxes and candidate search of every other flight) starts from the proved part (0, lo(t_c)] and
encloses the first root. The
exact closed form is used, so no rounded (phase, velocity) pair with a w0 that is only nearly 0
enters the proof.
"""

from __future__ import annotations

from typing import NamedTuple

import mpmath

from ..elastic.gap import departure_speed
from ..errors import UndecidableCollision
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
from .impact import Impact, detachment_impact, landing

WINDOW = 2  # the window H of the rigorous enclosure of an accumulation, in units of T0


class Accumulation(NamedTuple):
    """The impacts from an impact state accumulate ``tail`` after it (the model's ``T``);
    ``enclosure`` = ``(T_lo, T_hi)`` is proved (module docstring); ``phase`` = theta + T."""

    tail: mpmath.mpf
    enclosure: tuple[mpmath.mpf, mpmath.mpf]
    phase: mpmath.mpf


def accumulation(phi, v, eps, r, dps: int) -> Accumulation | None:
    """The summed tail from the impact state ``(phi, v)`` (exact ``mpf``; ``w = v + eps*sin(phi)``
    is evaluated to ``dps + 10`` digits of itself however small), or None when the
    module docstring's conditions (``q*T0 <= 10**-dps``, the enclosure proved) do not hold.

    Computed at ``dps + 10`` digits; ``tail`` and ``phase`` are returned at that precision.
    """
    with working_dps(dps + GUARD_DPS) as prec:
        iphi = reduce_phase(phi, prec).enclosure
        ieps, ir = iv.mpf(eps), iv.mpf(r)
        iw = departure_speed(phi, v, eps, prec)  # w to dps + 10 digits of itself
        ia = 1 - ieps * iv.cos(iphi)
        if not (lo(iw) > 0 and lo(ia) > 0 and r < 1):
            return None
        w, a, jerk = mid(iw), mid(ia), mid(-ieps * iv.sin(iphi))
        t0 = 2 * w / (a * (1 - r))
        q = t0**2 * (jerk**2 / a**2 + abs(eps) / a)
        if not q * t0 <= mp.mpf(10) ** (-dps):
            return None
        enclosure = _enclosure(iphi, iw, ieps, ir, WINDOW * t0)
        if enclosure is None:
            return None
        return summed_tail(t0 + jerk * t0**2 / (3 * a), enclosure, iphi, phi=phi, v=v)


def summed_tail(tail, enclosure, iphi, **inputs) -> Accumulation:
    """The :class:`Accumulation` of the model's ``tail`` from the phase enclosure ``iphi``, after
    checking that it lies in its proved ``enclosure`` (an ``ArithmeticError`` naming the
    ``inputs`` otherwise: the model and the proof disagree). Shared by :func:`accumulation` and
    :func:`verify.dissipative.drag_sticking.drag_accumulation`."""
    if not enclosure[0] <= tail <= enclosure[1]:
        named = ", ".join(f"{name}={value}" for name, value in inputs.items())
        raise ArithmeticError(
            f"accumulation tail {mp.nstr(tail, 20)} outside its proved enclosure "
            f"[{mp.nstr(enclosure[0], 20)}, {mp.nstr(enclosure[1], 20)}] ({named})"
        )
    return Accumulation(tail, enclosure, mid(iphi) + tail)


def _enclosure(iphi, iw, ieps, ir, window):
    """``(T_lo, T_hi)`` proved on the window ``[0, window]`` (module docstring), or None."""
    accel = -1 + ieps * iv.cos(iphi + iv.mpf([0, window]))
    return geometric_enclosure(iv.mpf(-hi(accel)), iv.mpf(-lo(accel)), iw, ir, window)


def geometric_enclosure(a_lo, a_hi, iw, ir, window):
    """``(T_lo, T_hi)``: the geometric sums of the module docstring for flights from ``iw`` on
    which ``a_lo <= -x'' <= a_hi`` (intervals), restitution ``ir``; None unless ``a_lo > 0``,
    ``r*(2*rho - 1) < 1`` and ``T_hi <= window`` are proved (used by
    :mod:`verify.dissipative.drag_sticking` too)."""
    if not lo(a_lo) > 0:
        return None
    rho = a_hi / a_lo
    growth = ir * (2 * rho - 1)
    if not hi(growth) < 1:
        return None
    t_hi = hi(2 * iw / (a_lo * (1 - growth)))
    if not t_hi <= window:
        return None
    shrink = max(lo(ir * (2 / rho - 1)), mp.zero)
    t_lo = lo(2 * iw / (a_hi * (1 - iv.mpf(shrink))))
    return t_lo, t_hi


def leaves_plate(eps) -> bool:
    """A particle riding the plate ever leaves it: ``|eps| > 1`` (module docstring)."""
    return abs(eps) > 1


def detachment_phase(eps):
    """theta* in [0, 2*pi): ``2*pi - arccos(1/eps)`` (eps > 1), ``pi - arccos(1/|eps|)``
    (eps < -1), at the current precision; ``ValueError`` for ``|eps| <= 1`` (never leaves)."""
    if not leaves_plate(eps):
        raise ValueError(f"no detachment for |eps| <= 1, got eps={eps}")
    alpha = mp.acos(1 / abs(eps))
    return 2 * mp.pi - alpha if eps > 0 else mp.pi - alpha


def detachment_velocity(eps):
    """``u(theta*) = -eps*sin(theta*) = sqrt(eps**2 - 1)`` at the current precision."""
    return mp.sqrt(eps * eps - 1)


class DetachedGap:
    """The gap of the flight from detachment in closed form (module docstring): a
    :class:`verify.numerics.first_root.Gap`."""

    def __init__(self, eps, dps, wdps):
        self.eps, self.dps, self.wdps = eps, dps, wdps
        self.s = iv.sqrt(iv.mpf(eps) ** 2 - 1)
        self.phi_exact, self.v = detachment_phase(eps), detachment_velocity(eps)

    def _at(self, it):
        half_sin = iv.sin(it / 2)
        rate_sin = it - iv.sin(it)
        d = self.s * rate_sin - (it * it / 2 - 2 * half_sin**2)
        slope = 2 * self.s * half_sin**2 - rate_sin
        return d, slope

    def d(self, t):
        return self._at(iv.mpf(t))[0]

    def d_and_slope(self, ia):
        if lo(ia) != hi(ia):
            raise NotDecided("a box end is not representable at this precision")
        return self._at(ia)

    def curvature(self, a, b):
        box = iv.mpf([a, b])
        return -1 + iv.cos(box) + self.s * iv.sin(box)

    def point(self, t):
        d_iv, p_iv = self._at(iv.mpf(t))
        return mid(d_iv), mid(p_iv)

    def needed(self, t):
        return 0


def detachment_box(eps):
    """``iv`` enclosures of theta* (module docstring) and of the plate's velocity there,
    ``u(theta*) = sqrt(eps**2 - 1)``, at the current precision (``|eps| > 1``)."""
    ieps = iv.mpf(eps)
    speed = iv.sqrt(ieps * ieps - 1)
    alpha = iv.atan2(speed, 1)  # arccos(1/|eps|)
    theta = (2 * iv.pi if eps > 0 else iv.pi) - alpha
    return theta, speed


def detachment_step(eps, r, dps: int, max_dps: int | None = None) -> Impact:
    """The impact ending the flight from detachment (module docstring), as an
    :class:`verify.dissipative.impact.Impact`: the proved enclosure of the first root of the
    detachment gap (:func:`verify.dissipative.impact.detachment_impact`), the impact of
    :func:`verify.dissipative.impact.landing` from theta*, with ``v_in = sqrt(eps**2 - 1) -
    tau``; the precision is raised (as :func:`verify.certify_flight` does) until the phase and
    velocity are known to ``dps`` digits. :class:`UndecidableCollision` when it stays undecided
    at ``max_dps`` (default ``max(4*dps, 400)``: ``|eps|`` within ~10**(-dps/2) of 1, where
    d(t_c) ~ (8/3)*(|eps| - 1)**2 is below the working precision)."""
    max_dps = default_max_dps(dps) if max_dps is None else max_dps
    digits = [dps + 3]  # the flight time's relative digits, kept from attempt to attempt

    def attempt(wdps):
        theta, speed = detachment_box(eps)

        def search(enclosure_digits):
            ctx = DetachedGap(eps, enclosure_digits, wdps)
            free = lo(2 * iv.atan2(ctx.s, 1))  # lo(t_c): d > 0 on (0, free]
            return search_first_root(ctx, 1 + abs(eps), free, None,
                                     candidate=local_candidate)[:2]

        def landing_of(left, right):
            itau = iv.mpf([left, right])
            return landing(theta, itau, speed - itau, eps, r)

        hit, digits[0] = detachment_impact(search, landing_of, eps, digits[0], dps)
        return hit

    def undecidable(wdps, why):
        with working_dps(wdps):
            return UndecidableCollision(detachment_phase(eps), detachment_velocity(eps), eps,
                                        wdps, f"flight from detachment: {why}")

    return escalate(attempt, dps, max_dps, undecidable)


def time_to_detachment(phase, eps):
    """Time riding the plate from the accumulation phase to theta*: ``(theta* - phase) mod
    2*pi`` in ``(0, 2*pi]`` at the current precision."""
    return time_until(detachment_phase(eps), phase)


class RestitutionSticking:
    """The sticking model of restitution ``r < 1`` without drag, for the orbit loop
    (:class:`verify.dissipative.sticking_model.StickingModel`): the summed tail
    (:func:`accumulation`), ``|eps| > 1`` to leave the plate, the ride to theta* and the flight
    from it (:func:`detachment_step`). It never reports chattering: without drag every
    chattering run either sums its tail or leaves with an ordinary flight (module docstring)."""

    def __init__(self, eps, r, dps: int) -> None:
        self.eps, self.r, self.dps = eps, r, dps

    def accumulation(self, phi, v) -> Accumulation | None:
        return accumulation(phi, v, self.eps, self.r, self.dps)

    def leaves_plate(self) -> bool:
        return leaves_plate(self.eps)

    def riding_time(self, phase):
        return time_to_detachment(phase, self.eps)

    def detachment_step(self) -> Impact:
        return detachment_step(self.eps, self.r, self.dps)

    def check_chattering(self, n: int, t, phi, v) -> None:
        return None
