"""The gap of a drag flight in interval arithmetic, the proofs its certificate needs, the attempt.

With the closed forms of :mod:`verify.dissipative.drag` (``Y``, ``V`` from the departure
velocity ``v``)::

    d(t)   = Y(t) + eps*(cos(phi) - cos(phi+t)) = Y(t) + 2*eps*sin(phi + t/2)*sin(t/2)
    d'(t)  = V(t) + eps*sin(phi+t)
    d''(t) = -1 - eta(V(t)) + eps*cos(phi+t)
    d'''(t) = -eta'(V)*V' - eps*sin(phi+t),  V' = -1 - eta(V)

:class:`DragGap` offers the interface the search of :mod:`verify.numerics.first_root` runs on
(``d``, ``d_and_slope``, ``curvature``, ``point``). Facts used (the paper's Section 2):

* ``V`` is monotone during a flight and ``eta`` increasing, so ``eta(V(t))`` lies between
  ``eta(v)`` and ``eta(V(T))`` on ``[0, T]``. Hence ``-d'' <= a = max(1 + eta(v), 0) + |eps|``
  (:meth:`DragGap.curvature_bound`): if ``V`` decreases, ``eta(V) <= eta(v)``; if it
  increases (either law below its terminal velocity), ``1 + eta(V) <= 0``. With ``w0 > 0``,
  ``d(t) >= w0*t - a*t**2/2 > 0`` on ``(0, 2*w0/a)``: the analytic start. The paper's
  lower-bound step uses this ``a``.
* Concavity on ``[0, T]`` (:meth:`DragGap.concave_on`): ``d'' <= -1 - min(eta(v), eta(V(T)))
  + |eps| <= 0`` proved in ``iv``, or the ``iv`` enclosure of ``d''`` over the box ``[0, T]``
  (:meth:`DragGap.curvature`) ``<= 0``. Then ``d(lo) > 0 > d(hi)`` with ``hi <= T``
  certify the first root as in the elastic ``|eps| <= 1`` case (chord argument).
* Long flights (:func:`positive_window`). The plate term eps*(cos(phi) - cos(phi+t)) is at
  least ``-P``, ``P = |eps| - eps*cos(phi)``, so ``d(t) >= Y(t) - P``. ``Y' = V`` is monotone, so
  ``Y`` is concave, or convex and decreasing (``V`` rises only below the terminal velocity,
  where ``V < 0``): either way its minimum over ``[a, b]`` is at an end, and ``Y(a) > P``,
  ``Y(b) > P`` prove ``d > 0`` on ``[a, b]``. A particle thrown high against strong drag (k = 1000
  from v = 1e4: up to Y = 10, then falling at the terminal speed 1e-3 for 1e4 time units)
  spends thousands of plate periods there; the search skips them in one window, which ends
  at most one plate period before the collision (once ``Y < P`` the next minimum of the plate
  term makes ``d < 0``).
* A departure at rest relative to the plate, ``w0 = 0`` exactly (:func:`departure_start`):
  ``d(0) = d'(0) = 0`` and ``d(t) = integral_0^t (t-s)*d''(s) ds``, so ``d'' > 0`` on ``(0, h]``
  gives ``d > 0`` there. ``d''`` is proved ``> 0`` on ``(0, h]`` either directly
  (``d''([0, h]) > 0``) or, when ``d''(0) = 0`` exactly, from ``d'''([0, h]) > 0``.
  ``d''(0) < 0``, or ``d''(0) = 0`` with ``d'''(0) < 0``, is no departure: ``ValueError``.
"""

from __future__ import annotations

from ..numerics.first_root import local_candidate, search_first_root
from ..numerics.phase import reduce_phase
from ..numerics.precision import NotDecided, hi, iv, lo, mp
from .drag import DragFlight

_HALVINGS = 200  # tries for the opening box of a departure at rest
_DOUBLINGS = 4_000  # of a time, in the search of a long flight's window (2**4000 > any flight)
_MIN_PERIODS = 8  # a window shorter than this many plate periods is not worth placing
_PLACE = 0.5  # a window's ends are placed to this (absolute time; a plate period is 2*pi)


class DragGap:
    """One attempt's drag gap at the current precision (the interface of
    :class:`verify.numerics.first_root.Gap`): the phase ``phi`` (for messages) and an ``iv``
    enclosure ``iphi`` of it reduced, the departure velocity ``v`` (an exact ``mpf``, or an
    ``iv`` interval of velocities: every enclosure then holds for each departure in the box),
    ``eps``, the drag ``k`` and its law."""

    def __init__(self, phi, iphi, v, eps, k, law, dps, wdps):
        self.phi_exact, self.iphi, self.eps = phi, iphi, eps
        self.dps, self.wdps = dps, wdps
        self.ieps = iv.mpf(eps)
        self.flight = DragFlight(v, k, law)
        self.v = self.flight.v

    def d(self, t):
        """Enclosure of ``d`` at the exact point ``t``."""
        return self._at(t, iv.mpf(t))[0]

    def d_and_slope(self, ia):
        """Enclosures of ``d`` and ``d'`` at the point interval ``ia`` (one exact number)."""
        if lo(ia) != hi(ia):
            raise NotDecided("a box end is not representable at this precision")
        return self._at(lo(ia), ia)

    def _at(self, t, ia):
        disp, vel = self.flight.motion(t)
        half = ia / 2
        plate = 2 * self.ieps * iv.sin(self.iphi + half) * iv.sin(half)
        return disp + plate, vel + self.ieps * iv.sin(self.iphi + ia)

    def curvature(self, a, b):
        """Enclosure of the gap's second derivative over ``[a, b]``: the interval value
        (``V`` over the box from its ends) intersected, on a box of positive width, with the
        mean-value form (the value at the midpoint ``m`` plus :meth:`third` over the box times
        ``[a, b] - m``). The interval value overestimates by the box's width (``eta(V)`` and
        ``eps*cos`` move together along the flight, their enclosures do not), the mean-value
        form by its square: where the curvature is nearly constant (a flight from detachment
        with ``E`` next to 1, curvature ~1e-16) only the latter resolves it. (Computed only
        where the interval value leaves the sign undecided.)"""
        box = self._curvature(a, b)
        if a == b or not lo(box) <= 0 <= hi(box):  # the sign is decided: enough as it is
            return box
        m = (a + b) / 2
        centred = self._curvature(m, m) + self.third(a, b) * (iv.mpf([a, b]) - m)
        return iv.mpf([max(lo(box), lo(centred)), min(hi(box), hi(centred))])

    def _curvature(self, a, b):
        vel = self.flight.velocity_box(a, b)
        return -1 - self.flight.eta(vel) + self.ieps * iv.cos(self.iphi + iv.mpf([a, b]))

    def third(self, a, b):
        """Enclosure of ``d'''`` over ``[a, b]``."""
        vel = self.flight.velocity_box(a, b)
        accel = -1 - self.flight.eta(vel)
        return -self.flight.eta_prime(vel) * accel - self.ieps * iv.sin(self.iphi + iv.mpf([a, b]))

    def point(self, t):
        """Non-rigorous ``(d(t), d'(t))``: midpoints of the enclosures, for the candidate search."""
        d_iv, p_iv = self.d_and_slope(iv.mpf(t))
        return (lo(d_iv) + hi(d_iv)) / 2, (lo(p_iv) + hi(p_iv)) / 2

    def w0(self):
        """Enclosure of ``w0 = d'(0) = v + eps*sin(phi)``."""
        return self.flight.iv_v + self.ieps * iv.sin(self.iphi)

    def curvature_bound(self):
        """``a = max(1 + eta(v), 0) + |eps| >= -d''`` during the flight (module docstring)."""
        top = hi(1 + self.flight.eta(self.flight.iv_v))
        return max(top, mp.zero) + abs(self.eps)

    def concave_on(self, end) -> bool:
        """Proved ``d'' <= 0`` on ``[0, end]`` (module docstring): from the global bound, else
        from the enclosure of ``d''`` over the box ``[0, end]`` (a short flight, e.g. one of a
        chattering run, where ``-d''`` is close to the riding force ``1 + eta(u) - eps*cos``)."""
        try:
            eta_end = self.flight.eta(self.flight.velocity(end))
        except NotDecided:
            return False
        eta_min = min(lo(eta_end), lo(self.flight.eta(self.flight.iv_v)))
        if hi(-1 - iv.mpf(eta_min) + abs(self.ieps)) <= 0:
            return True
        try:
            return hi(self.curvature(mp.zero, end)) <= 0
        except NotDecided:
            return False

    def needed(self, t):
        return 0  # no conditioning estimate with drag: the precision is doubled


def positive_window(ctx: DragGap, start):
    """``(a, b)`` with ``d > 0`` proved on ``[a, b]`` and ``a >= start`` (module docstring: long
    flights), or None where it would not span a few plate periods. The ends are placed by
    bisection on point values (not rigorous) and then proved: ``Y(a) > P`` and ``Y(b) > P`` in
    ``iv``."""
    floor = hi(abs(ctx.ieps) - ctx.ieps * iv.cos(ctx.iphi))  # the plate term is >= -floor

    def above(t):  # Y(t) > P, non-rigorous (the midpoint), for the bisections
        disp = ctx.flight.displacement(t)
        return (lo(disp) + hi(disp)) / 2 > floor

    try:
        peak = start
        for _ in range(_DOUBLINGS):  # a point above P (none once falling), then one below
            if above(peak):
                break
            if hi(ctx.flight.velocity(peak)) < 0:
                return None
            peak = 2 * peak
        else:
            return None
        far = 2 * peak
        for _ in range(_DOUBLINGS):
            if not above(far):
                break
            far = 2 * far
        else:
            return None
        if far - peak < _MIN_PERIODS * 2 * mp.pi:
            return None  # a short flight: the box-by-box search is as fast
        a = start if above(start) else _boundary(above, peak, start)
        b = _boundary(above, peak, far)
        if not (lo(ctx.flight.displacement(a)) > floor and lo(ctx.flight.displacement(b))
                > floor):
            return None
    except NotDecided:
        return None
    return (a, b) if a < b else None


def _boundary(above, inside, outside):
    """A point on the ``inside`` side of where ``above`` changes, within a tenth of a plate
    period of it (bisection; ``above(inside)`` holds, ``above(outside)`` does not)."""
    while abs(outside - inside) > _PLACE:
        mid = (inside + outside) / 2
        if above(mid):
            inside = mid
        else:
            outside = mid
    return inside


def departure_start(ctx: DragGap):
    """For ``w0 = 0`` exactly: ``h > 0`` with ``d > 0`` proved on ``(0, h]`` (module docstring).

    ``ValueError`` when the gap is proved not to open (no departure); :class:`NotDecided` when
    the signs cannot be decided at this precision.
    """
    state = f"(phi={ctx.phi_exact}, v={ctx.v}, eps={ctx.eps})"
    d2 = ctx.curvature(mp.zero, mp.zero)
    if hi(d2) < 0:
        raise ValueError(
            f"no departure: w0 = 0 and d''(0) = {mp.nstr(hi(d2), 8)} < 0 (the plate pushes "
            f"the particle) {state}"
        )
    if lo(d2) > 0:
        proof = ctx.curvature
    elif lo(d2) == 0 == hi(d2):
        d3 = ctx.third(mp.zero, mp.zero)
        if hi(d3) < 0:
            raise ValueError(f"no departure: w0 = 0, d''(0) = 0 and d'''(0) < 0 {state}")
        if not lo(d3) > 0:
            raise NotDecided("w0 = 0 and d''(0) = 0: the sign of d'''(0) is not decided")
        proof = ctx.third
    else:
        raise NotDecided("w0 = 0 and the sign of d''(0) is not decided: departure or not")
    h = mp.one
    for _ in range(_HALVINGS):
        try:
            if lo(proof(mp.zero, h)) > 0:
                return h
        except NotDecided:
            pass
        h /= 2
    raise NotDecided("no opening box found for the departure at rest")


def drag_attempt(phi, v, eps, phys, dps, wdps):
    """One attempt for a drag flight at the current precision; ``(lo, hi, free_until, boxes)``.

    The analytic start ``d > 0`` on ``(0, w0/a]`` with ``a`` the curvature bound (or, for
    ``w0 = 0`` exactly, :func:`departure_start`), then the search of
    :mod:`verify.numerics.first_root` with the concavity shortcut where ``w0 > 0``.
    """
    ctx = DragGap(phi, reduce_phase(phi, mp.prec).enclosure, v, eps, phys.drag,
                  phys.drag_law, dps, wdps)
    w0 = ctx.w0()
    if hi(w0) < 0:
        raise ValueError(
            f"no departure: w0 = v + eps*sin(phi) = {mp.nstr(hi(w0), 8)} < 0 "
            f"(phi={phi}, v={v}, eps={eps})"
        )
    curv = ctx.curvature_bound()
    if lo(w0) == 0 == hi(w0):
        return search_first_root(ctx, curv, departure_start(ctx), None,
                                 candidate=local_candidate)
    if lo(w0) <= 0:
        raise NotDecided(
            f"w0 = v + eps*sin(phi) is within {mp.nstr(hi(w0) - lo(w0), 3)} of 0: departure or not"
        )
    free = lo(w0) / curv
    return search_first_root(ctx, curv, free, positive_window(ctx, free),
                             concave_from=ctx.concave_on, candidate=local_candidate)
