"""Certified flight time: the smallest positive root of the gap ``d``.

Algorithm (precision ``wdps`` digits, raised on failure up to ``max_dps``):

1. The phase is reduced exactly modulo 2*pi (:mod:`verify.phase`: the precision of the
   reduction grows with the exponent of ``phi``), giving an ``iv`` enclosure of it.
   ``w0 = d'(0) = v + eps*sin(phi)`` is enclosed in ``iv``; ``w0 <= 0`` is rejected and a ``w0``
   interval straddling 0 means the precision is too low. Since ``d'' >= -(1+|eps|)``,
   ``d(t) >= w0*t - (1+|eps|)*t**2/2 > 0`` on ``(0, 2*w0/(1+|eps|))`` (analytic start).
2. ``|eps| <= 1`` (including exactly 1): ``d`` is concave, so it has exactly one positive root;
   :func:`_concave` encloses it by sign changes of ``d`` in ``iv`` inside a proved bracket
   (the proof is in its docstring). A candidate from Newton's method from the right is
   tested first; a wrong one is replaced by Newton from the bracket's right end or bisection.
3. ``|eps| > 1``: a candidate root ``c`` is found in plain ``mp`` (not rigorous) by the
   lower-bound step of the seed, which never oversteps a root. The certificate, in ``iv`` with
   outward rounding, on ``lo = c - delta``, ``hi = c + delta``, ``delta = c*10**-dps``:
   ``(a0, lo]`` is covered left to right by boxes ``[a, a+h]`` on which the second-order
   Taylor form ``d(a+s) >= d(a) + d'(a)*s + min d''([a, a+h])*s**2/2`` (all three enclosed in
   ``iv``) is proved positive for ``0 <= s <= h``; then ``d(hi) < 0``. If instead
   ``d(hi) > 0`` the candidate was a near-tangency that does not touch: the boxes continue past
   it and the search resumes. If the sign of ``d(hi)`` or the positivity of a box cannot be
   decided, the whole computation restarts at higher precision. Where ``v**2 > 4|eps|`` the
   proved part jumps over ``(t_-, t_+)``, on which ``d >= t*(v - t/2) - 2|eps| > 0``.
   A search that needs more than ``_MAX_STEPS`` candidate steps (a flight over very many plate
   periods, e.g. ``v = 1e154, eps = 1e300``) raises ``ValueError`` instead of running for hours.

The certificate does not rely on the correctness of the candidate search: a wrong candidate
only makes the box or sign checks fail, which raises the precision and finally raises
:class:`UndecidableCollision` (``|eps| > 1``), or costs bisection steps (``|eps| <= 1``).
:func:`certify_candidate` runs the proof step alone on a claimed enclosure.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import mpmath
from mpmath import iv, mp

from ._inputs import check_dps, check_physics, check_state, exact_real, w0_is_zero
from ._precision import hi, lo, working_dps
from .conditioning import condition_number
from .drag import NotDecided
from .drag_certify import DragContext, departure_start
from .errors import UndecidableCollision
from .gap import iv_gap, iv_gap_prime, iv_gap_second, mp_gap, mp_gap_prime
from .phase import reduce_phase

_MAX_STEPS = 100_000  # candidate steps per search: beyond it, ValueError (out of budget)
_MAX_BOXES = 20_000  # Taylor boxes per flight (a few seconds): beyond it, ValueError
_MAX_BISECTIONS = 4_000  # halvings of the concave bracket: enough for 1e-1000 relative width
_GUARD_DPS = 10
_LOCAL_GROWTH = 30  # windows [t, t + 4**j * s] tried by the local candidate step


@dataclass(frozen=True)
class FlightCertificate:
    """Proof data for one flight.

    ``tau``: midpoint of the enclosure, rounded to ``dps`` digits. ``enclosure``: ``(lo, hi)``
    exact ``mpf`` with ``d(lo) > 0 > d(hi)`` proved in interval arithmetic, so the smallest
    positive root lies in ``(lo, hi)``. ``free_until``: ``d > 0`` is proved on
    ``(0, free_until]`` (equal to ``lo``). ``dps_used``: working digits of the successful attempt.
    ``boxes``: interval evaluations (points and boxes) the proof examined.
    """

    tau: mpmath.mpf
    enclosure: tuple[mpmath.mpf, mpmath.mpf]
    free_until: mpmath.mpf
    dps_used: int
    boxes: int


class _Undecided(Exception):
    """One attempt could not decide; ``needed`` is a precision hint in digits."""

    def __init__(self, what: str, needed: int = 0) -> None:
        super().__init__(what)
        self.what = what
        self.needed = needed


def certify_flight(phi, v, eps, dps: int = 50, max_dps: int | None = None, *, drag=0.0,
                   drag_law: str = "linear", restitution=1.0) -> FlightCertificate:
    """Certify the smallest positive root of the gap ``d`` (see module docstring).

    Inputs are taken as exact binary values and checked by :func:`verify._inputs.check_state`:
    ``ValueError`` for NaN/inf/non-real inputs, a bad ``dps`` or ``max_dps``, or
    ``w0 = v + eps*sin(phi) <= 0``; :class:`UndecidableCollision` when the first root cannot be
    decided at ``max_dps`` digits (default ``max(4*dps, 400)``).

    Physics (keyword-only, :func:`verify._inputs.check_physics`): ``drag`` k >= 0 with
    ``drag_law`` "linear" or "quadratic" (:mod:`verify.drag`); ``restitution`` does not change a
    flight and is only validated. Without drag the elastic code above runs unchanged (bit for
    bit), except for a departure at rest, ``w0 = 0`` exactly, which it rejects and which goes
    to the drag certificate (:func:`_drag_attempt`) with ``k = 0``.
    """
    phys = check_physics(drag, drag_law, restitution)
    state = check_state(phi, v, eps, dps=dps, w0_zero_ok=True)
    phi, v, eps, dps = state.phi, state.v, state.eps, state.dps
    max_dps = max(4 * dps, 400) if max_dps is None else check_dps(max_dps, "max_dps")
    if max_dps < dps:
        raise ValueError(f"max_dps must be >= dps, got max_dps={max_dps}, dps={dps}")
    if phys.drag == 0 and not w0_is_zero(phi, v, eps):
        attempt = _attempt
    else:
        def attempt(phi, v, eps, dps, wdps):
            return _drag_attempt(phi, v, eps, phys, dps, wdps)
    wdps = min(dps + _GUARD_DPS, max_dps)
    while True:
        try:
            with working_dps(wdps):
                lo_, hi_, free, boxes = attempt(phi, v, eps, dps, wdps)
                mid = (lo_ + hi_) / 2
            with working_dps(dps):
                tau = +mid
            return FlightCertificate(tau, (lo_, hi_), free, wdps, boxes)
        except (_Undecided, NotDecided) as und:
            if wdps >= max_dps:
                raise UndecidableCollision(phi, v, eps, wdps, str(und)) from None
            wdps = min(max_dps, max(2 * wdps, getattr(und, "needed", 0)))


def flight_time(phi, v, eps, dps: int = 50, *, drag=0.0, drag_law: str = "linear",
                restitution=1.0) -> mpmath.mpf:
    """Certified smallest positive root of ``d`` at ``dps`` digits: ``certify_flight(...).tau``."""
    return certify_flight(phi, v, eps, dps, drag=drag, drag_law=drag_law,
                          restitution=restitution).tau


def _drag_attempt(phi, v, eps, phys, dps, wdps):
    """One attempt for a drag flight (:mod:`verify.drag_certify`): the analytic start
    ``d > 0`` on ``(0, w0/a]`` with ``a`` the curvature bound (or, for ``w0 = 0`` exactly,
    :func:`verify.drag_certify.departure_start`), then :func:`_search` with the concavity
    shortcut where ``w0 > 0``."""
    ctx = DragContext(phi, reduce_phase(phi, mp.prec).enclosure, v, eps, phys.drag,
                      phys.drag_law, dps, wdps)
    w0 = ctx.w0()
    if hi(w0) < 0:
        raise ValueError(
            f"no departure: w0 = v + eps*sin(phi) = {mp.nstr(hi(w0), 8)} < 0 "
            f"(phi={phi}, v={v}, eps={eps})"
        )
    curv = ctx.curvature_bound()
    if lo(w0) == 0 == hi(w0):
        return _search(ctx, curv, departure_start(ctx), None, candidate=_local_candidate)
    if lo(w0) <= 0:
        raise _Undecided(
            f"w0 = v + eps*sin(phi) is within {mp.nstr(hi(w0) - lo(w0), 3)} of 0: departure or not"
        )
    return _search(ctx, curv, lo(w0) / curv, None, concave_from=ctx.concave_on,
                   candidate=_local_candidate)


class _Context(NamedTuple):
    """One attempt's data: exact inputs, the reduced phase (point and interval), digits."""

    phi: mpmath.mpf  # the reduced phase (an mpf at working precision), for the candidate search
    v: mpmath.mpf
    eps: mpmath.mpf
    iphi: object  # iv enclosure of the exactly reduced phase
    iv_v: object
    ieps: object
    dps: int
    wdps: int
    phi_exact: mpmath.mpf  # the phase as given (for conditioning and messages)

    def d(self, t):
        """Interval enclosure of ``d`` at the exact point ``t``."""
        return iv_gap(self.iphi, self.iv_v, self.ieps, iv.mpf(t))

    def d_and_slope(self, ia):
        """Enclosures of ``d`` and ``d'`` at the point interval ``ia``."""
        return (iv_gap(self.iphi, self.iv_v, self.ieps, ia),
                iv_gap_prime(self.iphi, self.iv_v, self.ieps, ia))

    def curvature(self, a, b):
        """Enclosure of ``d''`` over ``[a, b]``."""
        return iv_gap_second(self.iphi, self.ieps, iv.mpf([a, b]))

    def point(self, t):
        """Non-rigorous ``(d(t), d'(t))`` in ``mp`` for the candidate search."""
        return (mp_gap(self.phi, self.v, self.eps, t), mp_gap_prime(self.phi, self.v, self.eps, t))

    def needed(self, t):
        return _needed_dps(self.phi_exact, self.v, self.eps, t, self.dps)


def _context(phi, v, eps, dps, wdps) -> _Context:
    reduced = reduce_phase(phi, mp.prec)
    return _Context(reduced.value, v, eps, reduced.enclosure, iv.mpf(v), iv.mpf(eps), dps, wdps,
                    phi)


def _attempt(phi, v, eps, dps, wdps):
    """One attempt at the current precision; returns ``(lo, hi, free_until, boxes)``."""
    ctx = _context(phi, v, eps, dps, wdps)
    w0 = ctx.iv_v + ctx.ieps * iv.sin(ctx.iphi)
    if hi(w0) <= 0:
        raise ValueError(
            f"no departure: w0 = v + eps*sin(phi) = {mp.nstr(hi(w0), 8)} <= 0 "
            f"(phi={phi}, v={v}, eps={eps})"
        )
    if lo(w0) <= 0:
        raise _Undecided(
            f"w0 = v + eps*sin(phi) is within {mp.nstr(hi(w0) - lo(w0), 3)} of 0: departure or not"
        )
    if abs(eps) <= 1:
        return _concave(ctx, w0_lo=lo(w0))
    return _general(ctx, w0_lo=lo(w0))


def _needed_dps(phi, v, eps, c, dps):
    try:
        kappa = condition_number(phi, v, eps, c)
    except (ZeroDivisionError, ValueError):
        return 0
    if not mp.isfinite(kappa) or kappa <= 1:
        return dps + _GUARD_DPS
    return dps + _GUARD_DPS + int(mp.ceil(mp.log10(kappa)))


def _concave(ctx: _Context, w0_lo):
    """``|eps| <= 1``: the single positive root, enclosed by sign changes of ``d``.

    Proof. ``d'' = -1 + eps*cos(phi+t) <= -1 + |eps| <= 0``: ``d`` is concave (strictly for
    ``|eps| < 1``; at ``|eps| = 1``, ``d''`` vanishes at isolated points only, concave is all
    the argument uses). ``d(0) = 0`` and ``d'(0) = w0 > 0`` (proved in ``iv``).

    * Positivity before ``lo``: if ``d(lo) > 0`` (proved in ``iv``) then for ``0 < t < lo``,
      concavity gives ``d(t) >= (1 - t/lo)*d(0) + (t/lo)*d(lo) > 0``.
    * Existence: ``d(hi) < 0`` (proved in ``iv``, or ``hi > U``, see below) and continuity give a
      root in ``(lo, hi)``.
    * Uniqueness: two positive roots ``r1 < r2`` with ``d(0) = 0`` would make the concave ``d``
      meet its chord from 0 to ``r2`` at the interior point ``r1``, so ``d`` would be affine on
      ``[0, r2]``, hence 0 there, contradicting ``d'(0) = w0 > 0``.

    Upper bound: ``d(t) <= 2*|eps| + t*v - t**2/2 < 0`` for ``t > U = v + sqrt(v**2 + 4*|eps|)``
    and, if ``|eps| < 1``, ``d(t) <= w0*t - (1 - |eps|)*t**2/2 < 0`` for ``t > 2*w0/(1-|eps|)``.
    Lower bound: ``d(t) >= w0*t - (1+|eps|)*t**2/2 > 0`` on ``(0, 2*w0/(1+|eps|))``.

    The search keeps a proved bracket ``a < root < b`` (``d > 0`` on ``(0, a]``, ``d(b) < 0``).
    A candidate ``c`` (Newton from the right, not rigorous) is tested at ``c -+ delta``,
    ``delta = c*10**-dps``; each decided sign shrinks the bracket. A wrong candidate is replaced
    by Newton from ``b`` or, failing that, by bisection; an undecided sign raises the precision.
    """
    abs_eps = abs(ctx.eps)
    upper = _concave_upper(ctx, abs_eps)
    a, b = w0_lo / (1 + abs_eps), upper  # both ends proved analytically (docstring)
    scale = mp.mpf(10) ** (-ctx.dps)
    c = _newton_from_right(ctx, upper)
    boxes = 0
    for _ in range(_MAX_BISECTIONS):
        if not a < c < b:
            c = (a + b) / 2
        delta = c * scale
        lo_, hi_ = max(c - delta, a), min(c + delta, b)
        signs = []
        for t in (lo_, hi_):
            if t in (a, b):  # already proved
                signs.append(1 if t == a else -1)
                continue
            d_t = ctx.d(t)
            boxes += 1
            sign = 1 if lo(d_t) > 0 else -1 if hi(d_t) < 0 else 0
            if sign > 0:
                a = max(a, t)
            elif sign < 0:
                b = min(b, t)
            signs.append(sign)
        if signs == [1, -1]:
            return lo_, hi_, lo_, boxes
        if 0 in signs:
            raise _Undecided(
                f"sign change of d across tau={mp.nstr(c, 20)} +- {mp.nstr(delta, 3)} not "
                "resolved", ctx.needed(c),
            )
        c = _newton_from_right(ctx, b)  # the candidate was wrong: a new one from the right end
    raise _Undecided(f"no enclosure of the root in {_MAX_BISECTIONS} bracket steps")


def _concave_upper(ctx: _Context, abs_eps):
    """A proved upper bound ``b`` with ``d(b) < 0`` (see :func:`_concave`): slightly above
    ``min(v + sqrt(v**2 + 4|eps|), 2*w0/(1 - |eps|))`` computed with upward rounding."""
    i_v, i_e = ctx.iv_v, iv.mpf(abs_eps)
    bound = hi(i_v + iv.sqrt(i_v * i_v + 4 * i_e))
    if abs_eps < 1:
        w0 = i_v + ctx.ieps * iv.sin(ctx.iphi)
        bound = min(bound, hi(2 * w0 / (1 - i_e)))
    return bound * (1 + mp.mpf(2) ** (-(mp.prec // 2)))


def _newton_from_right(ctx: _Context, t):
    """Non-rigorous candidate: Newton's method from ``t`` right of the root. For concave ``d``
    with ``d(t) < 0`` the iterates decrease monotonically to the root (exact arithmetic)."""
    tol = mp.mpf(10) ** (-(ctx.wdps - 3))
    phi, v, eps = ctx.phi, ctx.v, ctx.eps
    for _ in range(_MAX_STEPS):
        g, slope = mp_gap(phi, v, eps, t), mp_gap_prime(phi, v, eps, t)
        if g >= 0 or slope >= 0:  # in exact arithmetic d < 0 at every iterate: noise reached
            break
        step = g / slope
        t -= step
        if step <= t * tol:
            break
    return t


def certify_candidate(phi, v, eps, lo_, hi_, dps: int = 50) -> bool:
    """The proof step alone: is ``(lo_, hi_)`` a proved enclosure of the FIRST positive root?

    True iff, at ``dps + 10`` digits, ``d > 0`` is proved on ``(0, lo_]`` (``|eps| <= 1``:
    ``d(lo_) > 0`` and concavity; otherwise Taylor-form boxes from the analytic start
    ``w0/(1+|eps|)``) and ``d(hi_) < 0``. False when the proof fails (a wrong candidate, e.g. a
    later root, or too little precision). Exposed so that the proof can be tested on its own.
    """
    state = check_state(phi, v, eps, dps=dps)
    lo_, hi_ = exact_real("lo", lo_), exact_real("hi", hi_)
    if not 0 < lo_ < hi_:
        raise ValueError(f"need 0 < lo < hi, got lo={lo_}, hi={hi_}")
    wdps = state.dps + _GUARD_DPS
    with working_dps(wdps):
        ctx = _context(state.phi, state.v, state.eps, state.dps, wdps)
        try:
            if abs(state.eps) <= 1:
                # d concave with d(0) = 0: d(lo_) > 0 gives d >= (t/lo_)*d(lo_) > 0 on (0, lo_]
                # and with it the departure, w0 = d'(0) >= d(lo_)/lo_ > 0 (no w0 test needed)
                proved_lo = lo(ctx.d(lo_)) > 0
            else:
                w0 = ctx.iv_v + ctx.ieps * iv.sin(ctx.iphi)
                if lo(w0) <= 0:
                    return False
                free = lo(w0) / (1 + abs(state.eps))
                if lo_ > free:
                    _prove_positive(ctx, free, lo_)
                proved_lo = True
        except _Undecided:
            return False
        return proved_lo and hi(ctx.d(hi_)) < 0


def _general(ctx: _Context, w0_lo):
    """``|eps| > 1``: see the module docstring, item 3. Two analytic facts skip work:
    ``d > 0`` on ``(0, 2*w0/(1+|eps|))``, and ``d(t) >= t*(v - t/2) - 2*|eps| > 0`` strictly
    between ``t_- = v - sqrt(v**2 - 4|eps|)`` and ``t_+ = v + sqrt(v**2 - 4|eps|)`` (when
    ``v**2 > 4|eps|``): once the proved part reaches ``t_-`` it jumps to ``t_+``, so a fast
    particle over a strong plate is not followed period by period."""
    curv = 1 + abs(ctx.eps)  # bound on |d''|
    free = w0_lo / curv  # d > 0 on (0, free] analytically: free < 2*w0/(1+|eps|)
    return _search(ctx, curv, free, _positive_window(ctx))


def _search(ctx, curv, free, window, concave_from=None, candidate=None):
    """The candidate-and-proof loop of :func:`_general` for any gap ``ctx`` (the elastic
    :class:`_Context` or a :class:`verify.drag_certify.DragContext`): ``d > 0`` is proved on
    ``(0, free]``; ``curv`` bounds ``-d''`` from above; ``window`` is an interval known to lie
    in ``d > 0`` or None. ``concave_from``: where given (a callable of ``right``), a proof that
    ``d`` is concave on ``[0, right]`` lets two point evaluations certify (as in
    :func:`_concave`) before the box-by-box proof is tried. ``candidate``: the (non-rigorous)
    candidate search, :func:`_candidate` unless given."""
    search_from = free
    boxes = 0
    scale = mp.mpf(10) ** (-ctx.dps)
    for _ in range(_MAX_STEPS):
        if window is not None and window[0] <= free < window[1]:
            free = search_from = window[1]  # (free, window[1]] lies inside (t_-, t_+)
        c = (candidate or _candidate)(ctx, curv, search_from)
        if c < search_from:  # the search only moves forward: a candidate behind it is refused
            raise _Undecided(f"candidate tau={mp.nstr(c, 20)} is behind the proved part")
        delta = c * scale
        left = max(c - delta, free)
        right = c + delta
        if concave_from is not None and concave_from(right):
            d_left, d_right = ctx.d(left), ctx.d(right)
            boxes += 2
            if lo(d_left) > 0 and hi(d_right) < 0:
                return left, right, left, boxes
        if left > free:
            boxes += _prove_positive(ctx, free, left)
            free = left
        d_right = ctx.d(right)
        boxes += 1
        if hi(d_right) < 0:
            return left, right, left, boxes
        if lo(d_right) > 0:
            # a near-tangency that does not touch: prove the gap positive across it, go on
            boxes += _prove_positive(ctx, left, right)
            free = search_from = right
            if boxes > _MAX_BOXES:  # one near-tangency per plate period: a budget in total
                raise _over_budget(ctx, f"{_MAX_BOXES} proof boxes", right)
            continue
        size = max(abs(lo(d_right)), abs(hi(d_right)))
        raise _Undecided(
            f"d has a minimum within {mp.nstr(size, 3)} of 0 near tau={mp.nstr(c, 20)}: "
            "graze or not",
            ctx.needed(c),
        )
    raise _over_budget(ctx, f"{_MAX_STEPS} near-tangencies", search_from)  # not reached


def _candidate(ctx: _Context, curv, t):
    """Non-rigorous: step ``t`` by the larger root of ``d + d'*s - curv*s**2/2`` (never past a
    root in exact arithmetic) until ``d`` vanishes at working precision."""
    tol = mp.mpf(10) ** (-(ctx.wdps - 4))
    for _ in range(_MAX_STEPS):
        g, p = ctx.point(t)
        if g <= 0:
            return t
        disc = mp.sqrt(p * p + 2 * curv * g)
        s = (p + disc) / curv if p >= 0 else 2 * g / (disc - p)
        t += s
        if s <= t * tol:
            return t
    raise _over_budget(ctx, f"{_MAX_STEPS} lower-bound steps", t)


def _local_candidate(ctx, curv, t):
    """Non-rigorous candidate for drag flights: the seed's step with a LOCAL bound of ``-d''``.

    From ``t`` the step ``s`` (larger root of ``d + d'*s - a*s**2/2``) never passes a root if
    ``a >= -d''`` on ``[t, t+s]``. ``a`` is taken from the ``iv`` enclosure of ``d''`` over
    ``[t, t+L]``, and ``L`` is raised to the step until the step fits inside it (else the
    global ``curv``): near a root where ``d''`` is small this is far faster than the global
    bound, which crawls at a departure at rest. Only ``ctx.point`` values decide the stop.
    """
    tol = mp.mpf(10) ** (-(ctx.wdps - 4))
    for _ in range(_MAX_STEPS):
        g, p = ctx.point(t)
        if g <= 0:
            return t
        s = _lower_step(g, p, curv)
        length = s
        for _ in range(_LOCAL_GROWTH):
            length *= 4
            try:
                a = max(hi(-ctx.curvature(t, t + length)), mp.zero)
            except NotDecided:
                break
            s_loc = _lower_step(g, p, a)  # no root before min(s_loc, length)
            s = max(s, length if s_loc is None else min(s_loc, length))
            if s_loc is not None and s_loc <= length:
                break
        t += s
        if s <= t * tol:
            return t
    raise _over_budget(ctx, f"{_MAX_STEPS} lower-bound steps", t)


def _lower_step(g, p, a):
    """Larger root of ``g + p*s - a*s**2/2`` (``g > 0``); None when ``a = 0`` and ``p >= 0``."""
    if a == 0:
        return None if p >= 0 else g / -p
    disc = mp.sqrt(p * p + 2 * a * g)
    return (p + disc) / a if p >= 0 else 2 * g / (disc - p)


def _over_budget(ctx: _Context, what: str, t) -> ValueError:
    return ValueError(
        f"flight beyond verify's search budget: {what} reached "
        f"tau={mp.nstr(t, 8)} with the gap still positive (phi={mp.nstr(ctx.phi_exact, 8)}, "
        f"v={mp.nstr(ctx.v, 8)}, eps={mp.nstr(ctx.eps, 8)}): too many plate periods to cross "
        "one by one"
    )


def _positive_window(ctx: _Context):
    """``(hi(t_-), lo(t_+)*(1 - 2**(4-prec)))`` from ``iv``, or None if ``v**2 <= 4|eps|``:
    ``d > 0`` on this interval (see :func:`_general`)."""
    i_v, i_e = ctx.iv_v, abs(ctx.ieps)
    disc = i_v * i_v - 4 * i_e
    if not lo(disc) > 0 or not lo(i_v) > 0:
        return None
    root = iv.sqrt(disc)
    t_minus, t_plus = hi(4 * i_e / (i_v + root)), lo(i_v + root)  # t_- without cancellation
    t_plus *= 1 - mp.mpf(2) ** (4 - mp.prec)  # strictly below t_+
    return (t_minus, t_plus) if t_minus < t_plus else None


def _prove_positive(ctx: _Context, a, end):
    """Prove ``d > 0`` on ``[a, end]`` by Taylor-form boxes; return the number examined.

    On a box ``[a, a+h]``: ``d(a+s) >= d(a) + d'(a)*s + q*s**2/2`` for ``0 <= s <= h`` with
    ``q = min d''([a, a+h])`` (Taylor with the Lagrange remainder), all three enclosed in ``iv``
    and their lower ends used; :func:`_taylor_lower` bounds the quadratic from below.
    """
    boxes = 0
    tiny = mp.mpf(10) ** (-(ctx.wdps - 6))
    shrink = 1 - mp.mpf(2) ** -20
    h_prev = end - a
    while a < end:
        ia = iv.mpf(a)
        d_iv, p_iv = ctx.d_and_slope(ia)
        d_a, p_a = lo(d_iv), lo(p_iv)
        boxes += 1
        if d_a <= 0:
            raise _Undecided(_unresolved(a, d_iv, p_iv), ctx.needed(a))
        cap = min(2 * h_prev, end - a)
        while True:
            box_end = end if cap >= end - a else a + cap  # end may carry more bits than a
            q = lo(ctx.curvature(a, box_end))
            boxes += 1
            if boxes > _MAX_BOXES:
                raise _over_budget(ctx, f"{_MAX_BOXES} proof boxes", a)
            h_root = _first_zero(d_a, p_a, q)
            new_a = box_end if h_root is None else min(box_end, a + h_root * shrink)
            if new_a <= a:  # the step rounds away at this precision: no progress possible
                raise _Undecided(_unresolved(a, d_iv, p_iv), ctx.needed(a))
            h = hi(iv.mpf(new_a) - ia)
            if _taylor_lower(d_a, p_a, q, h) > 0:
                h_prev = new_a - a
                a = new_a
                break
            cap = (new_a - a) / 4
            if cap <= tiny * (abs(a) + 1):
                raise _Undecided(_unresolved(a, d_iv, p_iv), ctx.needed(a))
    return boxes


def _unresolved(a, d_iv, p_iv):
    d_size = max(abs(lo(d_iv)), abs(hi(d_iv)))
    p_size = max(abs(lo(p_iv)), abs(hi(p_iv)))
    return (
        f"d has a minimum within {mp.nstr(d_size, 3)} of 0 near tau={mp.nstr(a, 20)} "
        f"(|d'| <= {mp.nstr(p_size, 3)} there): graze or not"
    )


def _first_zero(d0, p, q):
    """First positive zero of ``d0 + p*s + q*s**2/2`` (``d0 > 0``), or None if none."""
    disc = p * p - 2 * q * d0
    if disc < 0:
        return None
    denom = mp.sqrt(disc) - p
    if denom <= 0:
        return None
    return 2 * d0 / denom


def _taylor_lower(d0, p, q, h):
    """Rigorous lower bound of ``d0 + p*s + q*s**2/2`` over ``0 <= s <= h`` (iv rounding)."""
    i_d, i_p, i_q, i_h = iv.mpf(d0), iv.mpf(p), iv.mpf(q), iv.mpf(h)
    at_h = lo(i_d + i_p * i_h + i_q * i_h * i_h / 2)
    if q <= 0:
        return min(d0, at_h)
    if p >= 0:
        return d0
    if lo(-i_p / i_q) >= h:
        return min(d0, at_h)
    return lo(i_d - i_p * i_p / (2 * i_q))
