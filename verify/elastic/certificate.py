"""The certificate of an elastic flight: the first positive root of the gap ``d`` of
:mod:`verify.elastic.gap`, enclosed by a proof in interval arithmetic.

Algorithm (one attempt at ``wdps`` working digits; :func:`verify.certify_flight` raises the
precision on failure, :func:`verify.numerics.precision.escalate`):

1. The phase is reduced exactly modulo 2*pi (:mod:`verify.numerics.phase`: the precision of the
   reduction grows with the exponent of ``phi``), giving an ``iv`` enclosure of it.
   ``w0 = d'(0) = v + eps*sin(phi)`` is enclosed in ``iv``; ``w0 <= 0`` is rejected and a ``w0``
   interval straddling 0 means the precision is too low. Since ``d'' >= -(1+|eps|)``,
   ``d(t) >= w0*t - (1+|eps|)*t**2/2 > 0`` on ``(0, 2*w0/(1+|eps|))`` (analytic start).
2. ``|eps| <= 1`` (including exactly 1): ``d`` is concave, so it has exactly one positive root;
   :func:`_concave` encloses it by sign changes of ``d`` in ``iv`` inside a proved bracket
   (the proof is in its docstring). A candidate from Newton's method from the right is
   tested first; a wrong one is replaced by Newton from the bracket's right end or bisection.
3. ``|eps| > 1``: the candidate-and-proof search of :mod:`verify.numerics.first_root`: a
   candidate root ``c`` from the lower-bound step of the paper (not rigorous; it never
   oversteps a root) with a local bound of ``-d''`` (an interval enclosure of ``d''`` over the
   step's window, not the global ``1 + |eps|``: just above ``|eps| = 1`` the curvature near a
   near-triple root is ~1e-15 and the global bound would crawl), then, in ``iv`` with outward
   rounding, ``d > 0`` proved on ``(0, c - delta]`` by Taylor-form boxes and
   ``d(c + delta) < 0``, ``delta = c*10**-dps``. Where ``v**2 > 4|eps|`` the proved part jumps
   over ``(t_-, t_+)``, on which ``d >= t*(v - t/2) - 2|eps| > 0``. A search that needs more
   than :data:`verify.numerics.first_root.MAX_STEPS` candidate steps (a flight over very many
   plate periods, e.g. ``v = 1e154, eps = 1e300``) raises ``ValueError`` instead of running
   for hours.

The certificate does not rely on the correctness of the candidate search: a wrong candidate
only makes the box or sign checks fail, which raises the precision and finally raises
:class:`verify.UndecidableCollision` (``|eps| > 1``), or costs bisection steps (``|eps| <= 1``).
:func:`certify_candidate` runs the proof step alone on a claimed enclosure.
"""

from __future__ import annotations

from typing import NamedTuple

import mpmath

from ..numerics.first_root import (
    MAX_STEPS,
    local_candidate,
    prove_positive,
    search_first_root,
)
from ..numerics.inputs import check_state, exact_real
from ..numerics.phase import reduce_phase
from ..numerics.precision import DEFAULT_DPS, GUARD_DPS, NotDecided, hi, iv, lo, mp, working_dps
from .conditioning import kappa
from .gap import iv_gap, iv_gap_prime, iv_gap_second, mp_gap, mp_gap_prime

_MAX_BISECTIONS = 4_000  # halvings of the concave bracket: enough for 1e-1000 relative width


class ElasticGap(NamedTuple):
    """The elastic gap at one attempt's precision: exact inputs, the reduced phase (point and
    interval), digits; the interface of :class:`verify.numerics.first_root.Gap`."""

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


def elastic_gap(phi, v, eps, dps, wdps) -> ElasticGap:
    """The :class:`ElasticGap` of the exact departure at the current precision."""
    reduced = reduce_phase(phi, mp.prec)
    return ElasticGap(reduced.value, v, eps, reduced.enclosure, iv.mpf(v), iv.mpf(eps), dps,
                      wdps, phi)


def elastic_attempt(phi, v, eps, dps, wdps):
    """One attempt at the current precision; returns ``(lo, hi, free_until, boxes)``."""
    ctx = elastic_gap(phi, v, eps, dps, wdps)
    w0 = ctx.iv_v + ctx.ieps * iv.sin(ctx.iphi)
    if hi(w0) <= 0:
        raise ValueError(
            f"no departure: w0 = v + eps*sin(phi) = {mp.nstr(hi(w0), 8)} <= 0 "
            f"(phi={phi}, v={v}, eps={eps})"
        )
    if lo(w0) <= 0:
        raise NotDecided(
            f"w0 = v + eps*sin(phi) is within {mp.nstr(hi(w0) - lo(w0), 3)} of 0: departure or not"
        )
    if abs(eps) <= 1:
        return _concave(ctx, w0_lo=lo(w0))
    return _general(ctx, w0_lo=lo(w0))


def _needed_dps(phi, v, eps, c, dps):
    """Precision hint for a sign left undecided near ``c``: ``dps + 10`` plus the digits of the
    condition number there (a cheap estimate at the working precision)."""
    if not c > 0:
        return 0
    k = kappa(phi, v, eps, c, max_bits=mp.prec)
    if not mp.isfinite(k) or k <= 1:
        return dps + GUARD_DPS
    return dps + GUARD_DPS + int(mp.ceil(mp.log10(k)))


def _concave(ctx: ElasticGap, w0_lo):
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
            raise NotDecided(
                f"sign change of d across tau={mp.nstr(c, 20)} +- {mp.nstr(delta, 3)} not "
                "resolved", ctx.needed(c),
            )
        c = _newton_from_right(ctx, b)  # the candidate was wrong: a new one from the right end
    raise NotDecided(f"no enclosure of the root in {_MAX_BISECTIONS} bracket steps")


def _concave_upper(ctx: ElasticGap, abs_eps):
    """A proved upper bound ``b`` with ``d(b) < 0`` (see :func:`_concave`): slightly above
    ``min(v + sqrt(v**2 + 4|eps|), 2*w0/(1 - |eps|))`` computed with upward rounding."""
    i_v, i_e = ctx.iv_v, iv.mpf(abs_eps)
    bound = hi(i_v + iv.sqrt(i_v * i_v + 4 * i_e))
    if abs_eps < 1:
        w0 = i_v + ctx.ieps * iv.sin(ctx.iphi)
        bound = min(bound, hi(2 * w0 / (1 - i_e)))
    return bound * (1 + mp.mpf(2) ** (-(mp.prec // 2)))


def _newton_from_right(ctx: ElasticGap, t):
    """Non-rigorous candidate: Newton's method from ``t`` right of the root. For concave ``d``
    with ``d(t) < 0`` the iterates decrease monotonically to the root (exact arithmetic)."""
    tol = mp.mpf(10) ** (-(ctx.wdps - 3))
    phi, v, eps = ctx.phi, ctx.v, ctx.eps
    for _ in range(MAX_STEPS):
        g, slope = mp_gap(phi, v, eps, t), mp_gap_prime(phi, v, eps, t)
        if g >= 0 or slope >= 0:  # in exact arithmetic d < 0 at every iterate: noise reached
            break
        step = g / slope
        t -= step
        if step <= t * tol:
            break
    return t


def certify_candidate(phi, v, eps, lo_, hi_, dps: int = DEFAULT_DPS) -> bool:
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
    wdps = state.dps + GUARD_DPS
    with working_dps(wdps):
        ctx = elastic_gap(state.phi, state.v, state.eps, state.dps, wdps)
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
                    prove_positive(ctx, free, lo_)
                proved_lo = True
        except NotDecided:
            return False
        return proved_lo and hi(ctx.d(hi_)) < 0


def _general(ctx: ElasticGap, w0_lo):
    """``|eps| > 1``: see the module docstring, item 3. Two analytic facts skip work:
    ``d > 0`` on ``(0, 2*w0/(1+|eps|))``, and ``d(t) >= t*(v - t/2) - 2*|eps| > 0`` strictly
    between ``t_- = v - sqrt(v**2 - 4|eps|)`` and ``t_+ = v + sqrt(v**2 - 4|eps|)`` (when
    ``v**2 > 4|eps|``): once the proved part reaches ``t_-`` it jumps to ``t_+``, so a fast
    particle over a strong plate is not followed period by period."""
    curv = 1 + abs(ctx.eps)  # bound on |d''|
    free = w0_lo / curv  # d > 0 on (0, free] analytically: free < 2*w0/(1+|eps|)
    return search_first_root(ctx, curv, free, _positive_window(ctx), candidate=local_candidate)


def _positive_window(ctx: ElasticGap):
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
