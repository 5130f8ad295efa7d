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
phi + tau and makes one Newton step h in delta, from delta = tau - 2*v (exact by Sterbenz's lemma,
since v <= tau <= 4*v), rotating the sine and cosine along by h (its Taylor series,
``fastpath.arithmetic.rotation``). It returns the root as the unevaluated sum
tau + tau_lo = 2*v + delta + h (``two_sum``), tau the nearest float. Only where the root is the
unique simple root near 2*v:

* |eps| <= 1 (the gap is concave: one root), or v >= 2|eps| + 4: then d > 0 on
  (0, 2v - 4|eps|/v) (d >= t*(v/2 - |eps|) for t <= v, d >= v*(2v - t)/2 - 2|eps| beyond) and
  d' <= -v + |eps| + 4|eps|/v < 0 on the rest of the window |delta| <= 4|eps|/v: one simple root;
* tau >= LONG_FLIGHT = 8 (shorter flights keep their phase to ulp(8) = 2 ulps of 2*pi);
* v <= tau <= 4*v (delta exact);
* the step is final: (1 + |eps|)*h**2 <= u*|d'|. From the certified tau (within 16*kappa*u*tau
  of the root) the Newton point misses the root by at most |d''|*h**2/(2|d'|) to second order,
  |d''| <= 1 + |eps|: below u/2, half an ulp of 1, far below an ulp of 2*pi. A larger step (an
  ill-conditioned flight, or a large v at which the certified tau is many ulps from the root)
  leaves tau as it is.

``landing_phase`` reduces phi + tau + tau_lo exactly: TwoSum of phi and tau, the reduction of the
rounded sum (Cody-Waite below 2**20, Payne-Hanek above: ``fastpath.arithmetic.phase``), then the
two small remainders added, and 2*pi (in two parts) added or taken away where that sum leaves
[0, 2*pi). Its error is a few ulps of 2*pi (and 2**-70 from Payne-Hanek), whatever |phi + tau|.
"""

from fastpath.arithmetic.jit import inline_jit
from fastpath.arithmetic.phase import TWO_PI, TWO_PI_LOW, reduce_moderate, reduce_phase
from fastpath.arithmetic.rotation import small_sin_cos
from fastpath.arithmetic.rounding import UNIT_ROUNDOFF, select, two_sum

LONG_FLIGHT = 8.0  # flights at least this long get their root as an unevaluated sum


@inline_jit
def refine_long_flight(cos_phi, v, eps, tau, s, c):
    """(tau, tau_lo, sin, cos of phi + tau + tau_lo): the root of a certified flight from phase
    phi (cos_phi its cosine) with speed v as an unevaluated sum, where the module docstring's
    conditions hold; else (tau, 0, s, c) unchanged. s, c: sin and cos of phi + tau. In selects
    only (the lanes of ``fastpath.kernels.escape`` vectorise it)."""
    two_v = 2.0 * v
    delta = tau - two_v
    d = eps * (cos_phi - c) - delta * (v + 0.5 * delta)
    d1 = -v - delta + eps * s
    h = -d / d1
    refined = ((abs(eps) <= 1.0 or v >= 2.0 * abs(eps) + 4.0) and tau >= LONG_FLIGHT
               and v <= tau <= 4.0 * v and (1.0 + abs(eps)) * h * h <= UNIT_ROUNDOFF * abs(d1))
    h = select(refined, h, 0.0)
    sh, ch = small_sin_cos(h)  # |h| <= sqrt(u) here: the series holds
    hi, lo = two_sum(two_v, delta + h)
    return (select(refined, hi, tau), select(refined, lo, 0.0), s * ch + c * sh,
            c * ch - s * sh)


@inline_jit
def _wrap(x):
    """x in (-2*pi, 4*pi) (a reduced phase plus a small remainder) brought into [0, 2*pi) with
    2*pi in two parts, in selects only; x already in range is returned unchanged."""
    x = select(x < 0.0, (x + TWO_PI) + TWO_PI_LOW, x)
    x = select(x >= TWO_PI, (x - TWO_PI) - TWO_PI_LOW, x)
    return select(x >= TWO_PI, 0.0, select(x < 0.0, 0.0, x))


@inline_jit
def landing_phase(phi, tau, tau_lo):
    """(phi + tau + tau_lo) mod 2*pi in [0, 2*pi), a few ulps of 2*pi (module docstring)."""
    total, rest = two_sum(phi, tau)
    return _wrap(reduce_phase(total) + (rest + tau_lo))


@inline_jit
def landing_phase_moderate(phi, tau, tau_lo):
    """``landing_phase`` for |phi + tau| < 2**20, in selects only (the lanes)."""
    total, rest = two_sum(phi, tau)
    return _wrap(reduce_moderate(total) + (rest + tau_lo))
