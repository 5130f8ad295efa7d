"""The flight over a box of departures, certified; and the point flight that proposes it.

Gap of a departure (phi, v) (docs/model.md), product form without cancellation:

    d(t)  = 2*eps*sin(phi + t/2)*sin(t/2) + t*(v - t/2),      d'(t) = v - t + eps*sin(phi + t),
    d''(t) = -1 + eps*cos(phi + t) >= -a,   a = 1 + |eps|.

Certificate for a box Phi x V (intervals) and a bracket [t_lo, t_hi], in interval arithmetic
with outward rounding, for every (phi, v) in the box:

1. w0 = v + eps*sin(phi) > 0 (the particle departs);
2. d > 0 on (0, t_lo]: for |eps| <= 1 d is strictly concave with d(0) = 0, d'(0) = w0 > 0, so
   d(t_lo) > 0 suffices. For |eps| > 1: d(t) >= w0*t - a*t**2/2 > 0 on (0, w0/a]; from there
   points A are proved d(A) > 0 and, with dl, sl lower bounds of d(A), d'(A) over the box,
   d(A + s) >= dl + sl*s - a*s**2/2 > 0 for s below that quadratic's positive root, which gives
   the next A; the chain must pass t_lo (at most ``MAX_BOXES`` links);
3. d(t_hi) < 0 and d' < 0 on [t_lo, t_hi].

Then every departure in the box has exactly one root of d in [t_lo, t_hi], it is the first
collision (no earlier root), and it is transversal (d' < 0): the flight time is a smooth function
on the box with values in [t_lo, t_hi], and the implicit-function derivatives hold.

``point_flight`` finds the candidate in the point context by the paper's lower-bound steps
(which approach the first root from below) and a Newton polish. It proves nothing: a wrong
candidate only makes the certificate fail.
"""

from __future__ import annotations

from typing import NamedTuple

from verify.dynamics.numbers import hi, lo, negative, positive

MAX_BOXES = 20_000  # links of the chain in step 2 (a near-tangency crawls: refused beyond)
MAX_STEPS = 100_000  # lower-bound steps of the point search
_SHRINK = 1 - 2.0**-20  # a link moves to just before the proved end, never past it
_NEAR_ROOT = 1e-12  # lower-bound steps stop at this relative step; Newton finishes


class Undecided(Exception):
    """The certificate could not be completed for this box and bracket (``what`` says why)."""

    def __init__(self, what: str) -> None:
        super().__init__(what)
        self.what = what


def gap(iv, phi, v, eps, t):
    """d(t) over intervals (product form)."""
    half = t / 2
    return 2 * eps * iv.sin(phi + half) * iv.sin(half) + t * (v - half)


def gap_prime(iv, phi, v, eps, t):
    """d'(t) = v - t + eps*sin(phi + t) over intervals."""
    return v - t + eps * iv.sin(phi + t)


def box_flight(ctx, phi_box, v_box, eps, t_lo, t_hi) -> tuple:
    """Certify the bracket [t_lo, t_hi] (exact point values) for every departure in the box.

    Returns (T, links): T = [t_lo, t_hi] as an interval, links the points of the step-2 chain.
    Raises :class:`Undecided` naming the step that failed.
    """
    iv = ctx.iv
    eps_iv = iv.mpf(eps)
    w0 = v_box + eps_iv * iv.sin(phi_box)
    if not positive(w0):
        raise Undecided(f"departure w0 = v + eps*sin(phi) > 0 not proved (w0 in [{lo(w0)}, "
                        f"{hi(w0)}])")
    if not t_lo > 0:
        raise Undecided("the bracket does not start after 0")
    links = 0
    if abs(eps) > 1:
        links = _cover(ctx, phi_box, v_box, eps_iv, w0, t_lo)
    if not positive(gap(iv, phi_box, v_box, eps_iv, iv.mpf(t_lo))):
        raise Undecided("d(t_lo) > 0 not proved: the bracket may start after the root")
    if not negative(gap(iv, phi_box, v_box, eps_iv, iv.mpf(t_hi))):
        raise Undecided("d(t_hi) < 0 not proved: the bracket may end before the root")
    bracket = iv.mpf([t_lo, t_hi])
    if not negative(gap_prime(iv, phi_box, v_box, eps_iv, bracket)):
        raise Undecided("d' < 0 on the bracket not proved (near-tangency, or a wide box)")
    return bracket, links


def _cover(ctx, phi_box, v_box, eps_iv, w0, t_lo) -> int:
    """Step 2 for |eps| > 1: prove d > 0 on (0, t_lo] for the whole box; return the links."""
    iv, mp = ctx.iv, ctx.mp
    a = 1 + abs(eps_iv)
    a_hi = mp.make_mpf(a._mpi_[1])
    point = mp.make_mpf(w0._mpi_[0]) / a_hi * _SHRINK
    for links in range(MAX_BOXES):
        if point >= t_lo:
            return links
        at = iv.mpf(point)
        dl = iv.mpf(mp.make_mpf(gap(iv, phi_box, v_box, eps_iv, at)._mpi_[0]))
        if not positive(dl):
            raise Undecided(f"d > 0 not proved at t = {mp.nstr(point, 12)} before the bracket")
        sl = iv.mpf(mp.make_mpf(gap_prime(iv, phi_box, v_box, eps_iv, at)._mpi_[0]))
        root_disc = iv.sqrt(sl * sl + 2 * a * dl)
        reach = (sl + root_disc) / a if lo(sl) >= 0 else 2 * dl / (root_disc - sl)
        if lo(at + reach) > t_lo:
            return links + 1
        point = point + mp.make_mpf(reach._mpi_[0]) * _SHRINK
    raise Undecided(f"more than {MAX_BOXES} links to prove d > 0 before the bracket")


class PointFlight(NamedTuple):
    """A candidate flight in the point context (not a proof): tau, the new state (phase
    unreduced: phi + tau), the Jacobian (j11, j12, j21, j22), the gradient of tau and w1."""

    tau: object
    phi1: object
    v1: object
    jacobian: tuple
    gradient: tuple
    w1: object


def point_flight(ctx, phi, v, eps) -> PointFlight:
    """The first root of d from (phi, v) in the point context, with the map's derivatives.

    Raises :class:`Undecided` if the particle does not depart, the search crawls (a
    near-tangency) or the slope at the root is not negative.
    """
    mp = ctx.mp
    w0 = v + eps * mp.sin(phi)
    if not w0 > 0:
        raise Undecided(f"the state does not depart: w0 = {mp.nstr(w0, 8)}")
    a = 1 + abs(eps)
    t, d, slope = mp.zero, mp.zero, w0
    for _ in range(MAX_STEPS):
        disc = mp.sqrt(slope * slope + 2 * a * d)
        step = (slope + disc) / a if slope >= 0 else 2 * d / (disc - slope)
        t += step
        half = t / 2
        d = 2 * eps * mp.sin(phi + half) * mp.sin(half) + t * (v - half)
        slope = v - t + eps * mp.sin(phi + t)
        if step <= _NEAR_ROOT * (1 + t) or d <= 0:
            break
    else:
        raise Undecided("the candidate search did not reach a root (near-tangency?)")
    tolerance = mp.mpf(2) ** (-mp.prec + 8) * (1 + t)
    for _ in range(60):
        if not slope < 0:
            raise Undecided("the candidate root is not transversal (d' >= 0)")
        delta = d / slope
        t -= delta
        half = t / 2
        d = 2 * eps * mp.sin(phi + half) * mp.sin(half) + t * (v - half)
        slope = v - t + eps * mp.sin(phi + t)
        if abs(delta) <= tolerance:
            break
    else:
        raise Undecided("Newton's polish of the candidate root did not settle")
    phi1 = phi + t
    s0, s1, c1 = mp.sin(phi), mp.sin(phi1), mp.cos(phi1)
    v1 = t - v - 2 * eps * s1
    w1 = -slope
    ga = eps * (s1 - s0) / w1
    gb = t / w1
    c = 2 * eps * c1
    jac = (1 + ga, gb, ga - c * (1 + ga), -1 + gb - c * gb)
    return PointFlight(t, phi1, v1, jac, (ga, gb), w1)
