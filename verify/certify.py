"""Certified flight time: the smallest positive root of the gap ``d``.

Algorithm (precision ``wdps`` digits, raised on failure up to ``max_dps``):

1. ``w0 = d'(0) = v + eps*sin(phi)`` is enclosed in ``iv``; ``w0 <= 0`` is rejected and a ``w0``
   interval straddling 0 means the precision is too low. Since ``d'' >= -(1+|eps|)``,
   ``d(t) >= w0*t - (1+|eps|)*t**2/2 > 0`` on ``(0, 2*w0/(1+|eps|))`` (analytic start).
2. A candidate root ``c`` is found in plain ``mp`` (not rigorous): monotone Newton from the
   right for ``|eps| < 1``; for ``|eps| >= 1`` the lower-bound step of the seed, which never
   oversteps a root.
3. Certificate, in ``iv`` with outward rounding, on ``lo = c - delta``, ``hi = c + delta``,
   ``delta = c*10**-dps``:

   * ``|eps| < 1``: ``d'' <= -1 + |eps| < 0`` so ``d`` is strictly concave with ``d(0) = 0``;
     ``d(lo) > 0`` then gives ``d > 0`` on ``(0, lo]`` and ``d(hi) < 0`` a root in ``(lo, hi)``.
   * ``|eps| >= 1``: ``(a0, lo]`` is covered left to right by boxes ``[a, a+h]`` on which the
     second-order Taylor form ``d(a+s) >= d(a) + d'(a)*s + min d''([a, a+h])*s**2/2`` (all
     three enclosed in ``iv``) is proved positive for ``0 <= s <= h``; then ``d(hi) < 0``.
     If instead ``d(hi) > 0`` the candidate was a near-tangency that does not touch: the
     boxes continue past it and the search resumes. If the sign of ``d(hi)`` or the positivity
     of a box cannot be decided, the whole computation restarts at higher precision.

The certificate does not rely on the correctness of the candidate search: a wrong candidate
only makes the box or sign checks fail, which raises the precision and finally raises
:class:`UndecidableCollision`.
"""

from __future__ import annotations

from dataclasses import dataclass

import mpmath
from mpmath import iv, mp

from ._inputs import check_dps, exact_real
from ._precision import hi, lo, working_dps
from .conditioning import condition_number
from .errors import UndecidableCollision
from .gap import iv_gap, iv_gap_prime, iv_gap_second, mp_gap, mp_gap_prime

_MAX_STEPS = 200_000
_GUARD_DPS = 10


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


def certify_flight(phi, v, eps, dps: int = 50, max_dps: int | None = None) -> FlightCertificate:
    """Certify the smallest positive root of the gap ``d`` (see module docstring).

    Inputs are taken as exact binary values. Raises ``ValueError`` for NaN/inf inputs, a bad
    ``dps``, or ``w0 = v + eps*sin(phi) <= 0``; :class:`UndecidableCollision` when the first
    root cannot be decided at ``max_dps`` digits (default ``max(4*dps, 400)``).
    """
    dps = check_dps(dps)
    max_dps = max(4 * dps, 400) if max_dps is None else check_dps(max_dps, "max_dps")
    if max_dps < dps:
        raise ValueError(f"max_dps must be >= dps, got max_dps={max_dps}, dps={dps}")
    phi, v, eps = exact_real("phi", phi), exact_real("v", v), exact_real("eps", eps)
    wdps = min(dps + _GUARD_DPS, max_dps)
    while True:
        try:
            with working_dps(wdps):
                lo_, hi_, free, boxes = _attempt(phi, v, eps, dps, wdps)
                mid = (lo_ + hi_) / 2
            with working_dps(dps):
                tau = +mid
            return FlightCertificate(tau, (lo_, hi_), free, wdps, boxes)
        except _Undecided as und:
            if wdps >= max_dps:
                raise UndecidableCollision(phi, v, eps, wdps, und.what) from None
            wdps = min(max_dps, max(2 * wdps, und.needed))


def flight_time(phi, v, eps, dps: int = 50) -> mpmath.mpf:
    """Certified smallest positive root of ``d`` at ``dps`` digits: ``certify_flight(...).tau``."""
    return certify_flight(phi, v, eps, dps).tau


def _attempt(phi, v, eps, dps, wdps):
    """One attempt at the current precision; returns ``(lo, hi, free_until, boxes)``."""
    iphi, iv_v, ieps = iv.mpf(phi), iv.mpf(v), iv.mpf(eps)
    w0 = iv_v + ieps * iv.sin(iphi)
    if hi(w0) <= 0:
        raise ValueError(
            f"no departure: w0 = v + eps*sin(phi) = {mp.nstr(hi(w0), 8)} <= 0 "
            f"(phi={phi}, v={v}, eps={eps})"
        )
    if lo(w0) <= 0:
        raise _Undecided(
            f"w0 = v + eps*sin(phi) is within {mp.nstr(hi(w0) - lo(w0), 3)} of 0: departure or not"
        )
    args = (phi, v, eps, iphi, iv_v, ieps, dps, wdps)
    if abs(eps) < 1:
        return _concave(*args, w0_lo=lo(w0))
    return _general(*args, w0_lo=lo(w0))


def _needed_dps(phi, v, eps, c, dps):
    try:
        kappa = condition_number(phi, v, eps, c)
    except (ZeroDivisionError, ValueError):
        return 0
    if not mp.isfinite(kappa) or kappa <= 1:
        return dps + _GUARD_DPS
    return dps + _GUARD_DPS + int(mp.ceil(mp.log10(kappa)))


def _concave(phi, v, eps, iphi, iv_v, ieps, dps, wdps, w0_lo):
    abs_eps = abs(eps)
    w0 = v + eps * mp.sin(phi)
    # both are upper bounds on the root; Newton from the right converges monotonically
    t = v + mp.sqrt(v * v + 4 * abs_eps)
    if abs_eps < 1:
        t = min(t, 2 * w0 / (1 - abs_eps))
    tol = mp.mpf(10) ** (-(wdps - 3))
    for _ in range(_MAX_STEPS):
        g, slope = mp_gap(phi, v, eps, t), mp_gap_prime(phi, v, eps, t)
        if g >= 0 or slope >= 0:  # in exact arithmetic d < 0 at every iterate: noise reached
            break
        step = g / slope
        t -= step
        if step <= t * tol:
            break
    c = t
    delta = c * mp.mpf(10) ** (-dps)
    lo_, hi_ = c - delta, c + delta
    d_lo = iv_gap(iphi, iv_v, ieps, iv.mpf(lo_))
    d_hi = iv_gap(iphi, iv_v, ieps, iv.mpf(hi_))
    if lo(d_lo) > 0 and hi(d_hi) < 0:
        return lo_, hi_, lo_, 2
    raise _Undecided(
        f"sign change of d across tau={mp.nstr(c, 20)} +- {mp.nstr(delta, 3)} not resolved",
        _needed_dps(phi, v, eps, c, dps),
    )


def _general(phi, v, eps, iphi, iv_v, ieps, dps, wdps, w0_lo):
    curv = 1 + abs(eps)  # bound on |d''|
    free = w0_lo / curv  # d > 0 on (0, free] analytically: free < 2*w0/(1+|eps|)
    search_from = free
    boxes = 0
    scale = mp.mpf(10) ** (-dps)
    while True:
        c = _candidate(phi, v, eps, curv, search_from, wdps)
        delta = c * scale
        left = max(c - delta, free)
        right = c + delta
        if left > free:
            boxes += _prove_positive(phi, v, eps, iphi, iv_v, ieps, free, left, wdps, dps)
            free = left
        d_right = iv_gap(iphi, iv_v, ieps, iv.mpf(right))
        boxes += 1
        if hi(d_right) < 0:
            return left, right, left, boxes
        if lo(d_right) > 0:
            # a near-tangency that does not touch: prove the gap positive across it, go on
            boxes += _prove_positive(phi, v, eps, iphi, iv_v, ieps, left, right, wdps, dps)
            free = search_from = right
            continue
        size = max(abs(lo(d_right)), abs(hi(d_right)))
        raise _Undecided(
            f"d has a minimum within {mp.nstr(size, 3)} of 0 near tau={mp.nstr(c, 20)}: "
            "graze or not",
            _needed_dps(phi, v, eps, c, dps),
        )


def _candidate(phi, v, eps, curv, t, wdps):
    """Non-rigorous: step ``t`` by the larger root of ``d + d'*s - curv*s**2/2`` (never past a
    root in exact arithmetic) until ``d`` vanishes at working precision."""
    tol = mp.mpf(10) ** (-(wdps - 4))
    for _ in range(_MAX_STEPS):
        g = mp_gap(phi, v, eps, t)
        if g <= 0:
            return t
        p = mp_gap_prime(phi, v, eps, t)
        disc = mp.sqrt(p * p + 2 * curv * g)
        s = (p + disc) / curv if p >= 0 else 2 * g / (disc - p)
        t += s
        if s <= t * tol:
            return t
    raise _Undecided(f"candidate search did not converge in {_MAX_STEPS} steps near tau={t}")


def _prove_positive(phi, v, eps, iphi, iv_v, ieps, a, end, wdps, dps):
    """Prove ``d > 0`` on ``[a, end]`` by Taylor-form boxes; return the number examined."""
    boxes = 0
    tiny = mp.mpf(10) ** (-(wdps - 6))
    shrink = 1 - mp.mpf(2) ** -20
    h_prev = end - a
    while a < end:
        ia = iv.mpf(a)
        d_iv = iv_gap(iphi, iv_v, ieps, ia)
        p_iv = iv_gap_prime(iphi, iv_v, ieps, ia)
        d_a, p_a = lo(d_iv), lo(p_iv)
        boxes += 1
        if d_a <= 0:
            raise _Undecided(_unresolved(a, d_iv, p_iv), _needed_dps(phi, v, eps, a, dps))
        cap = min(2 * h_prev, end - a)
        while True:
            box_end = min(a + cap, end)
            q = lo(iv_gap_second(iphi, ieps, iv.mpf([a, box_end])))
            boxes += 1
            h_root = _first_zero(d_a, p_a, q)
            new_a = box_end if h_root is None else min(box_end, a + h_root * shrink)
            h = hi(iv.mpf(new_a) - ia)
            if _taylor_lower(d_a, p_a, q, h) > 0:
                h_prev = new_a - a
                a = new_a
                break
            cap = (new_a - a) / 4
            if cap <= tiny * (abs(a) + 1):
                raise _Undecided(_unresolved(a, d_iv, p_iv), _needed_dps(phi, v, eps, a, dps))
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
