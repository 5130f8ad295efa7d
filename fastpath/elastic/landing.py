"""The landing phase phi1 = (phi + tau) mod 2*pi to a few ulps of 2*pi, whatever the speed.

A flight time returned as one float has an absolute error of at least half an ulp of tau; at
v = 1e8 that is 1.5e-8 rad of phase, at v = 1e16 the whole circle. The root itself is known much
better. For a long flight write t = 2*v + delta (the Holmes time plus a correction):

    d(t)  = eps*(cos(phi) - cos(phi + t)) - delta*(v + delta/2),
    d'(t) = -v - delta + eps*sin(phi + t),

whose terms at the root are of size |eps| (|delta| <= 4|eps|/tau there). With the sine and cosine
of the exact angle phi + t they are computed to a few u*(|eps| + |delta*v|) in absolute terms,
so the root's delta is known to a few u*|eps|/|d'(tau)|, far below ulp(tau).

``refine_long_flight`` takes a certified flight time tau (float) with the sine and cosine of
phi + tau and makes two Newton steps in delta, starting from delta = tau - 2*v (exact by
Sterbenz's lemma, since v <= tau <= 4*v), rotating the sine and cosine along
(``fastpath.elastic.lockstep.rotate_by``). It returns the root as the unevaluated sum
tau + tau_lo = 2*v + delta (``two_sum``), tau the nearest float. Only where the root is the
unique simple root near 2*v:

* |eps| <= 1 (the gap is concave: one root), or v >= 2|eps| + 4: then d > 0 on
  (0, 2v - 4|eps|/v) (d >= t*(v/2 - |eps|) for t <= v, d >= v*(2v - t)/2 - 2|eps| beyond) and
  d' <= -v + |eps| + 4|eps|/v < 0 on the rest of the window |delta| <= 4|eps|/v: one simple root;
* tau >= LONG_FLIGHT = 8 (shorter flights keep their phase to ulp(8) = 2 ulps of 2*pi);
* v <= tau <= 4*v (delta exact);
* the steps converge: |h2| <= |h1|/1024 + 64u*(1 + |delta|), and |h1| <= 2**-26*tau (the
  certified tau is within 16*kappa*u of the root: a larger first step means a flight too ill
  conditioned for the refinement, whose tau is kept as it is).

The Newton error after the first step from a start within e0 of the root is at most
(1 + |eps|)*e0**2/(2*|d'|) (|d''| <= 1 + |eps|), the second squares that again: from the
certified tau (e0 <= 16*kappa*u*tau) both are far below the rounding floor.

``landing_phase`` reduces phi + tau + tau_lo exactly: TwoSum of phi and tau, the reduction of the
rounded sum (Cody-Waite below 2**20, Payne-Hanek above: ``fastpath.arithmetic.phase``), then the
two small remainders added and the sum reduced once more (a moderate reduction). Its error is a
few ulps of 2*pi (and 2**-70 from Payne-Hanek), whatever |phi + tau|.
"""

from fastpath.arithmetic.jit import inline_jit
from fastpath.arithmetic.phase import reduce_moderate, reduce_phase
from fastpath.arithmetic.rounding import UNIT_ROUNDOFF, select, two_sum
from fastpath.elastic.lockstep import rotate_by

LONG_FLIGHT = 8.0  # flights at least this long get their root as an unevaluated sum


@inline_jit
def _newton(phi_cos, v, eps, delta, s, c):
    """The Newton step -d/d' in delta at t = 2v + delta (module docstring)."""
    d = eps * (phi_cos - c) - delta * (v + 0.5 * delta)
    d1 = -v - delta + eps * s
    return -d / d1


@inline_jit
def refine_long_flight(cos_phi, v, eps, tau, s, c):
    """(tau, tau_lo, sin, cos of phi + tau + tau_lo): the root of a certified flight from phase
    phi (cos_phi its cosine) with speed v as an unevaluated sum, where the module docstring's
    conditions hold; else (tau, 0, s, c) unchanged. s, c: sin and cos of phi + tau. In selects
    only (the lanes of ``fastpath.kernels.escape`` vectorise it)."""
    two_v = 2.0 * v
    delta = tau - two_v
    h1 = _newton(cos_phi, v, eps, delta, s, c)
    s1, c1 = rotate_by(s, c, h1)
    delta1 = delta + h1
    h2 = _newton(cos_phi, v, eps, delta1, s1, c1)
    s2, c2 = rotate_by(s1, c1, h2)
    hi, lo = two_sum(two_v, delta1 + h2)
    refined = ((abs(eps) <= 1.0 or v >= 2.0 * abs(eps) + 4.0) and tau >= LONG_FLIGHT
               and v <= tau <= 4.0 * v and abs(h1) <= 2.0**-26 * tau
               and abs(h2) <= abs(h1) * 2.0**-10 + 64.0 * UNIT_ROUNDOFF * (1.0 + abs(delta1)))
    return (select(refined, hi, tau), select(refined, lo, 0.0), select(refined, s2, s),
            select(refined, c2, c))


@inline_jit
def landing_phase(phi, tau, tau_lo):
    """(phi + tau + tau_lo) mod 2*pi in [0, 2*pi), a few ulps of 2*pi (module docstring)."""
    total, rest = two_sum(phi, tau)
    return reduce_moderate(reduce_phase(total) + (rest + tau_lo))


@inline_jit
def landing_phase_moderate(phi, tau, tau_lo):
    """``landing_phase`` for |phi + tau| < 2**20, in selects only (the lanes)."""
    total, rest = two_sum(phi, tau)
    return reduce_moderate(reduce_moderate(total) + (rest + tau_lo))
