"""The first positive root of a gap ``d(t)``: a candidate search and a proof, for any gap.

A *gap* is an object with, at the current ``mp``/``iv`` precision (see :class:`Gap`):

* ``d(t)``: an ``iv`` enclosure of ``d`` at the exact point ``t``;
* ``d_and_slope(ia)``: enclosures of ``d`` and ``d'`` at the point interval ``ia``;
* ``curvature(a, b)``: an enclosure of ``d''`` over ``[a, b]``;
* ``point(t)``: non-rigorous ``(d(t), d'(t))`` in ``mp`` for the candidate search;
* ``needed(t)``: a precision hint in digits for a sign left undecided near ``t`` (0: none);
* ``dps``, ``wdps`` (promised and working digits) and ``phi_exact``, ``v``, ``eps`` (messages).

The elastic gap (:mod:`verify.elastic.certificate`), the drag gap
(:mod:`verify.dissipative.drag_gap`) and the gaps of flights from detachment
(:mod:`verify.dissipative.sticking`, :mod:`verify.dissipative.drag_sticking`) are such objects.

:func:`search_first_root` alternates a candidate (not rigorous: the lower-bound step of the
paper, which never oversteps a root in exact arithmetic) and a proof: ``d > 0`` on the part
before the candidate by Taylor-form boxes (:func:`prove_positive`), then ``d < 0`` just after
it. A wrong candidate only makes a proof fail (:class:`NotDecided`: the caller raises the
precision) or costs more boxes; it never yields a wrong enclosure.
"""

from __future__ import annotations

from typing import Protocol

import mpmath

from .precision import NotDecided, hi, iv, lo, mp

MAX_STEPS = 100_000  # candidate steps per search: beyond it, ValueError (out of budget)
MAX_BOXES = 20_000  # Taylor boxes per flight (a few seconds): beyond it, ValueError
_LOCAL_GROWTH = 30  # windows [t, t + L] tried by one local candidate step (L grows >= 4x)


class Gap(Protocol):
    """The interface :func:`search_first_root` runs on (module docstring)."""

    dps: int
    wdps: int
    phi_exact: mpmath.mpf
    v: mpmath.mpf
    eps: mpmath.mpf

    def d(self, t): ...
    def d_and_slope(self, ia): ...
    def curvature(self, a, b): ...
    def point(self, t): ...
    def needed(self, t) -> int: ...


def search_first_root(gap: Gap, curv, free, window, concave_from=None, candidate=None):
    """Enclose the first positive root of ``gap``; return ``(lo, hi, free_until, boxes)``.

    ``d > 0`` is proved on ``(0, free]``; ``curv`` bounds ``-d''`` from above; ``window`` is an
    interval known to lie in ``d > 0`` or None. ``concave_from``: where given (a callable of
    ``right``), a proof that ``d`` is concave on ``[0, right]`` lets two point evaluations
    certify (the chord argument of the elastic ``|eps| <= 1`` case) before the box-by-box proof
    is tried. ``candidate``: the (non-rigorous) candidate search, :func:`local_candidate`
    unless given.

    Each candidate ``c`` is tested on ``[c - delta, c + delta]``, ``delta = c*10**-dps``:
    ``d > 0`` is proved up to the left end, then ``d < 0`` at the right end encloses the root.
    If instead ``d > 0`` there, the candidate was a near-tangency that does not touch: the proof
    continues past it and the search resumes. :class:`NotDecided` when a sign cannot be decided
    at this precision; ``ValueError`` when the search runs out of its budget.
    """
    search_from = free
    boxes = 0
    scale = mp.mpf(10) ** (-gap.dps)
    for _ in range(MAX_STEPS):
        if window is not None and window[0] <= free < window[1]:
            free = search_from = window[1]  # (free, window[1]] lies inside d > 0
        c = (candidate or local_candidate)(gap, curv, search_from)
        if c < search_from:  # the search only moves forward: a candidate behind it is refused
            raise NotDecided(f"candidate tau={mp.nstr(c, 20)} is behind the proved part")
        delta = c * scale
        left = max(c - delta, free)
        right = c + delta
        if concave_from is not None and concave_from(right):
            d_left, d_right = gap.d(left), gap.d(right)
            boxes += 2
            if lo(d_left) > 0 and hi(d_right) < 0:
                return left, right, left, boxes
        if left > free:
            boxes += prove_positive(gap, free, left)
            free = left
        d_right = gap.d(right)
        boxes += 1
        if hi(d_right) < 0:
            return left, right, left, boxes
        if lo(d_right) > 0:
            # a near-tangency that does not touch: prove the gap positive across it, go on
            boxes += prove_positive(gap, left, right)
            free = search_from = right
            if boxes > MAX_BOXES:  # one near-tangency per plate period: a budget in total
                raise over_budget(gap, f"{MAX_BOXES} proof boxes", right)
            continue
        size = max(abs(lo(d_right)), abs(hi(d_right)))
        raise NotDecided(
            f"d has a minimum within {mp.nstr(size, 3)} of 0 near tau={mp.nstr(c, 20)}: "
            "graze or not",
            gap.needed(c),
        )
    raise over_budget(gap, f"{MAX_STEPS} near-tangencies", search_from)  # not reached


def local_candidate(gap: Gap, curv, t):
    """Non-rigorous candidate: the paper's lower-bound step with a LOCAL bound of ``-d''``.

    From ``t`` the step ``s`` (larger root of ``d + d'*s - a*s**2/2``) never passes a root if
    ``a >= -d''`` on ``[t, t+s]``. ``a`` is taken from the ``iv`` enclosure of ``d''`` over
    ``[t, t+L]``, and ``L`` is raised (at least 4 times, to the step if the step is longer)
    until the step fits inside it (else the global ``curv``): where ``|d''|`` is small near
    the root (a departure at rest, a near-triple root just above ``|eps| = 1``) this is far
    faster than the global bound, which crawls there. Only ``gap.point`` values decide the stop.
    """
    tol = mp.mpf(10) ** (-(gap.wdps - 4))
    for _ in range(MAX_STEPS):
        g, p = gap.point(t)
        if g <= 0:
            return t
        s = lower_step(g, p, curv)
        length = 4 * s
        for _ in range(_LOCAL_GROWTH):
            try:
                a = max(hi(-gap.curvature(t, t + length)), mp.zero)
            except NotDecided:
                break
            s_loc = lower_step(g, p, a)  # no root before min(s_loc, length)
            s = max(s, length if s_loc is None else min(s_loc, length))
            if s_loc is not None and s_loc <= length:
                break
            # the step reaches past the window: the next window is 4 times longer, or as long
            # as this step (a longer window only lowers the bound's step)
            length = 4 * length if s_loc is None else max(4 * length, s_loc)
        t += s
        if s <= t * tol:
            return t
    raise over_budget(gap, f"{MAX_STEPS} lower-bound steps", t)


def lower_step(g, p, a):
    """Larger root of ``g + p*s - a*s**2/2`` (``g > 0``); None when ``a = 0`` and ``p >= 0``."""
    if a == 0:
        return None if p >= 0 else g / -p
    disc = mp.sqrt(p * p + 2 * a * g)
    return (p + disc) / a if p >= 0 else 2 * g / (disc - p)


def over_budget(gap: Gap, what: str, t) -> ValueError:
    """The ``ValueError`` of a search that ran out of its budget at ``t``."""
    return ValueError(
        f"flight beyond verify's search budget: {what} reached "
        f"tau={mp.nstr(t, 8)} with the gap still positive (phi={mp.nstr(gap.phi_exact, 8)}, "
        f"v={mp.nstr(gap.v, 8)}, eps={mp.nstr(gap.eps, 8)}): too many plate periods to cross "
        "one by one"
    )


def prove_positive(gap: Gap, a, end):
    """Prove ``d > 0`` on ``[a, end]`` by Taylor-form boxes; return the number examined.

    On a box ``[a, a+h]``: ``d(a+s) >= d(a) + d'(a)*s + q*s**2/2`` for ``0 <= s <= h`` with
    ``q = min d''([a, a+h])`` (Taylor with the Lagrange remainder), all three enclosed in ``iv``
    and their lower ends used; :func:`taylor_lower` bounds the quadratic from below.
    """
    boxes = 0
    tiny = mp.mpf(10) ** (-(gap.wdps - 6))
    shrink = 1 - mp.mpf(2) ** -20
    h_prev = end - a
    while a < end:
        ia = iv.mpf(a)
        d_iv, p_iv = gap.d_and_slope(ia)
        d_a, p_a = lo(d_iv), lo(p_iv)
        boxes += 1
        if d_a <= 0:
            raise NotDecided(_unresolved(a, d_iv, p_iv), gap.needed(a))
        cap = min(2 * h_prev, end - a)
        while True:
            box_end = end if cap >= end - a else a + cap  # end may carry more bits than a
            q = lo(gap.curvature(a, box_end))
            boxes += 1
            if boxes > MAX_BOXES:
                raise over_budget(gap, f"{MAX_BOXES} proof boxes", a)
            h_root = _first_zero(d_a, p_a, q)
            new_a = box_end if h_root is None else min(box_end, a + h_root * shrink)
            if new_a <= a:  # the step rounds away at this precision: no progress possible
                raise NotDecided(_unresolved(a, d_iv, p_iv), gap.needed(a))
            h = hi(iv.mpf(new_a) - ia)
            if taylor_lower(d_a, p_a, q, h) > 0:
                h_prev = new_a - a
                a = new_a
                break
            cap = (new_a - a) / 4
            if cap <= tiny * (abs(a) + 1):
                raise NotDecided(_unresolved(a, d_iv, p_iv), gap.needed(a))
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


def taylor_lower(d0, p, q, h):
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
