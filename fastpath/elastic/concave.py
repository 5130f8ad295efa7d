"""Fast flight solver for |eps| <= 1 (exactly 1 included), where the gap is concave (docs/model.md).

With d'' = -1 + eps*cos(phi + t) <= -1 + |eps| <= 0 the gap has exactly one positive root, so a
point t where the computed gap exceeds its rounding bound E (``fastpath.elastic.gap.gap_error``)
lies before it and a point with d < -E after it: every such evaluation narrows a certified bracket
[lo, hi]. It starts from the bounds of fact 2 and, since d <= 2|eps| + t*v - t**2/2,

    2*w0/(1 + |eps|)  <=  tau  <=  min(2*w0/(1 - |eps|),  v + sqrt(v**2 + 4|eps|)),

the second upper bound finite at |eps| = 1 (w0 taken with its rounding error, ``departure``).
Inside it we take Halley steps t <- t - 2*d*d' / (2*d'**2 - d*d''), or a bisection step (the
geometric mean while hi > 4*lo) when a step leaves the bracket. A point with |d| <= E is

* after the maximum of d (d' < -its error): the root is within rounding of t. One Newton
  correction -d/d' gives the answer, CLAMPED to [lo, hi], so it is always in the certified bracket
  (also from a point with |d| > E where the Newton step is provably as good, ``newton_is_final``)
  (near a triple root, eps -> 1 with phi = -x, v = x, d' is tiny and the unclamped step is wild);
* before the maximum (d' > its error): d increases there, so the root lies beyond t: lo = t;
* at a flat top (|d'| within its error too): float64 cannot place the root: UNCERTAIN.

At most ITERATION_LIMIT evaluations (then MAX_ITERATIONS, as UNCERTAIN).

Refinement near (near-)triple roots (``_refine``, half-angle start only). E = gap_error allows an
absolute error of a few u in the plate term's sine; where the gap's terms are small (t and phi
small: d ~ x**4/24 at phi = -x, v = x, eps -> 1) it is 1e3-1e6 times the actual rounding. A stop
there is either flat (UNCERTAIN although float64 could decide) or far from the root, and the Newton
correction's second-order error |d''|*(d/d')**2/(2|d'|) dominates (2.29 kappa*u at x = 3e-5).
So when the loop stops flat, or where that second-order term may exceed u*t/2
(``newton_inexact``; never on ordinary flights, where d/d' ~ u*t), the iteration goes on with
``fastpath.elastic.tight_gap``: fresh half-angle sines and a bound E, R from the sizes of the terms,
proved there. Its points narrow the same certified bracket by the same rules, so every answer stays
in it. Only short flights need this: a concave gap with d(0) = d(tau) = 0 lies between 0 and its
tangent at tau, 0 <= d <= |d'(tau)|*tau on [0, tau], so a small d'(tau) needs d'' ~ 0 over the
whole flight, i.e. eps ~ 1 and phi + t ~ 0 (mod 2*pi): impossible over the Holmes start's flights
(tau >= 2*w0/(1 + |eps|) >= 1).

Two starts and two ways of evaluating the gap, each one libm sine and cosine per flight; later
iterates move the angles along by angle addition (``fastpath.arithmetic.rotation``):

- Unless the flight may be short (lower bound 2*w0/(1+|eps|) below 1), start at the Holmes
  flight time t = 2*v, where t*(v - t/2) vanishes, and
  write t = 2*v + delta: d = eps*(cos(phi) - cos(phi + t)) - t*delta/2, d' = -v - delta +
  eps*sin(phi + t), d'' = -1 + eps*cos(phi + t), the sine and cosine at the start taken of the
  exact sum phi + 2*v (``sin_cos_of_sum``: TwoSum, libm, the remainder by angle addition) and
  rotated on by the steps in delta. Here t >= 1, so the plate
  term's rounding error, ~|eps|*u, is within the gap's error bound (``fastpath.elastic.gap``).
- Otherwise start at the root of w0*t - (1 - eps*cos(phi))*t**2/2 (the plate's acceleration
  frozen at departure) and use the half angle t/2: d = 2*eps*sin(t/2)*sin(phi + t/2) +
  t*(v - t/2), free of cancellation at small t.

Both return sin and cos of phi + tau, which the collision needs and the next flight reuses.
"""

import math

from fastpath.arithmetic.jit import inline_jit, jit
from fastpath.arithmetic.rotation import rotate, sin_cos_of_sum
from fastpath.arithmetic.rounding import UNIT_ROUNDOFF
from fastpath.elastic.gap import gap_error, rate_error
from fastpath.elastic.tight_gap import SMALLEST_T, tight_gap
from fastpath.status import CONVERGED, ITERATION_LIMIT, MAX_ITERATIONS, OVERFLOW, UNCERTAIN

_NEWTON_STALLS = 2  # Newton steps in ``_refine`` that may fail to halve before it stops

# classification of one evaluation (see the module docstring; ``fastpath.dissipative.drag_flight``
# classifies its points the same way)
BEFORE, AFTER, AT_ROOT, FLAT = 0, 1, 2, 3


@jit
def bracket(v, w0, w0_error, eps):
    """Certified (lo, hi) for the root (module docstring), rounded outwards."""
    if 1e-150 < abs(v) < 1e150:
        root = math.sqrt(v * v + 4.0 * abs(eps))
    else:  # v**2 would underflow or overflow
        root = math.hypot(v, 2.0 * math.sqrt(abs(eps)))
    return bracket_from_root(v, w0, w0_error, eps, root)


@inline_jit
def bracket_from_root(v, w0, w0_error, eps, root):
    """``bracket`` given root = sqrt(v**2 + 4|eps|), in selects only (the lanes of
    ``fastpath.elastic.lockstep`` vectorise it): both upper bounds are computed, the energy bound
    (<= 2|v| + 2) is used only where the concave one is not already below 2|v| + 2."""
    a = 1.0 + abs(eps)
    lo = 2.0 * (w0 - w0_error if w0 - w0_error > 0.0 else 0.0) / a * (1.0 - 4.0 * UNIT_ROUNDOFF)
    hi_concave = 2.0 * (w0 + w0_error) / (1.0 - abs(eps)) if abs(eps) < 1.0 else math.inf
    hi_energy = v + root if v >= 0.0 else 4.0 * abs(eps) / (root - v)
    use_energy = not hi_concave <= 2.0 * abs(v) + 2.0
    hi = hi_energy if use_energy and hi_energy < hi_concave else hi_concave
    return lo, hi * (1.0 + 4.0 * UNIT_ROUNDOFF)


@jit
def classify(phi, v, eps, t, d, d1):
    """Where t lies relative to the root, from d(t) and d'(t) with their error bounds."""
    d_err = gap_error(phi, v, eps, t)
    if d > d_err:
        return BEFORE
    if d < -d_err:
        return AFTER
    d1_err = rate_error(phi, v, eps, t)
    if d1 < -d1_err:
        return AT_ROOT
    if d1 > d1_err:
        return BEFORE
    return FLAT


@jit
def halley(t, d, d1, d2, where, lo, hi):
    """Narrow the bracket (lo, hi) by where t lies, then step: (t_next, lo, hi).

    t_next is the Halley step from t, or a bisection point if that step leaves the bracket.
    """
    if where == BEFORE:
        lo = t
    else:
        hi = t
    t_next = t - 2.0 * d * d1 / (2.0 * d1 * d1 - d * d2)
    if not lo < t_next < hi:
        if lo > 0.0 and hi > 4.0 * lo:
            t_next = math.sqrt(lo) * math.sqrt(hi)
        else:
            t_next = 0.5 * (lo + hi)
    return t_next, lo, hi


@jit
def newton_is_final(newton, d_err, d1_err, eps):
    """Whether the Newton correction h = -d/d' from a point after the maximum (d' < -d1_err)
    is as good as one from a point where |d| <= d_err, the gap's rounding bound.

    The root t* = t + h* solves 0 = d + d'*h* + d''(xi)*h***2/2 with |d''| <= a = 1 + |eps|, so
    |h* - h| <= a*h**2/(2|d'|), and the rounding of d and d' adds (d_err + |h|*d1_err)/(|d'| -
    d1_err): in all at most (d_err + |h|*d1_err + a*h**2/2)/(|d'| - d1_err) to first order, the
    bound of a stop at |d| <= d_err with |h|*d1_err + a*h**2/2 added. Where that addition is at
    most d_err/16 the answer is as good (within 1/16 of the bound) and one evaluation, at
    t + h, is saved: after a Halley step from an error ~1e-3 the next error is ~1e-9, and
    |h| <~ 4e-8 is final.
    """
    return (0.5 * (1.0 + abs(eps)) * newton * newton + abs(newton) * d1_err) <= d_err / 16.0


@jit
def concave_flight(phi, sin_phi, cos_phi, v, eps, w0_error):
    """(tau, sin(phi + tau), cos(phi + tau), evaluations, status) for |eps| <= 1, w0 > w0_error.

    phi reduced to [-pi, pi); status CONVERGED, UNCERTAIN, MAX_ITERATIONS or OVERFLOW.
    """
    w0 = v + eps * sin_phi
    lo, hi = bracket(v, w0, w0_error, eps)
    if not hi < math.inf:
        return math.nan, math.nan, math.nan, 0, OVERFLOW
    if 2.0 * w0 >= 1.0 + abs(eps):
        return flight_from_holmes(phi, sin_phi, cos_phi, v, eps, lo, hi)
    return flight_half_angle(phi, sin_phi, cos_phi, v, eps, lo, hi, w0_error)


@jit
def _finish(t, d, d1, s, c, phi, lo, hi, evaluations, where):
    """The answer from the last evaluation at t (module docstring)."""
    if where == FLAT:
        return t, s, c, evaluations, UNCERTAIN
    if where == AT_ROOT:
        tau = min(max(t - d / d1, lo), hi)
    else:  # the bracket closed to adjacent floats around the root
        tau = lo
    h = tau - t
    if abs(h) < 1e-8:  # first order: the neglected h**2/2 is below u/2
        return tau, s + c * h, c - s * h, evaluations, CONVERGED
    s, c = rotate(s, c, h, phi, tau)
    return tau, s, c, evaluations, CONVERGED


@jit
def flight_from_holmes(phi, sin_phi, cos_phi, v, eps, lo, hi):
    two_v = 2.0 * v
    s, c = sin_cos_of_sum(phi, two_v)
    delta, t = 0.0, two_v
    for evaluations in range(1, ITERATION_LIMIT + 1):
        d = eps * (cos_phi - c) - 0.5 * t * delta
        d1 = -v - delta + eps * s
        if not abs(d) < math.inf:
            return math.nan, math.nan, math.nan, evaluations, OVERFLOW
        where = classify(phi, v, eps, t, d, d1)
        if where >= AT_ROOT:
            return _finish(t, d, d1, s, c, phi, lo, hi, evaluations, where)
        d1_err = rate_error(phi, v, eps, t)
        if d1 < -d1_err and newton_is_final(-d / d1, gap_error(phi, v, eps, t), d1_err, eps):
            lo, hi = (t, hi) if where == BEFORE else (lo, t)
            return _finish(t, d, d1, s, c, phi, lo, hi, evaluations, AT_ROOT)
        t_next, lo, hi = halley(t, d, d1, -1.0 + eps * c, where, lo, hi)
        if t_next == lo or t_next == hi:
            return _finish(t, d, d1, s, c, phi, lo, hi, evaluations, BEFORE)
        delta_next = t_next - two_v
        s, c = rotate(s, c, delta_next - delta, phi, t_next)
        delta, t = delta_next, t_next
    return t, s, c, ITERATION_LIMIT, MAX_ITERATIONS


@jit
def newton_inexact(t, d, d1, d2, eps):
    """Whether the correction -d/d1 from t may miss the root by more than u*t/2 in second order.

    With delta = d/d1 the Newton point misses by |d''(xi)|*delta**2/(2|d'|), and
    |d''(xi)| <= |d2| + |eps|*|delta| near t (the third derivative is bounded by |eps|).
    """
    delta = d / d1
    return (abs(d2) + abs(eps * delta)) * delta * delta > UNIT_ROUNDOFF * t * abs(d1)


@jit
def _refine(phi, sin_phi, cos_phi, v, eps, w0_error, t, lo, hi, done):
    """Continue from t with ``tight_gap``, whose bound E is near the actual rounding: points that
    the generic bound left undecided narrow the bracket, and the stop is at the root.

    Each point is classified as by ``classify``, with E and R. From a point with |d| <= E and
    d' < -R (after the maximum, the root within rounding) the Newton point is the next iterate
    while ``newton_inexact``, up to _NEWTON_STALLS steps that fail to halve the previous one
    (then rounding dominates: the computed gap is noise at the scale of the step); otherwise it
    is the answer (clamped into the certified bracket, ``_finish``). ``done``: evaluations
    so far. If the evaluations run out, the answer is the last such Newton point, or
    MAX_ITERATIONS if there was none.
    """
    last = (math.nan, math.nan, math.nan, ITERATION_LIMIT, MAX_ITERATIONS)
    last_step = math.inf
    stalls = 0
    for evaluations in range(done + 1, ITERATION_LIMIT + 1):
        d, d1, d2, s, c, d_err, d1_err = tight_gap(sin_phi, cos_phi, v, eps, w0_error, t)
        if d > d_err or (d >= -d_err and d1 > d1_err):
            where = BEFORE
        elif d < -d_err:
            where = AFTER
        elif d1 < -d1_err:
            where = AT_ROOT
        else:
            return _finish(t, d, d1, s, c, phi, lo, hi, evaluations, FLAT)
        if where == AT_ROOT:
            last = _finish(t, d, d1, s, c, phi, lo, hi, ITERATION_LIMIT, AT_ROOT)
            t_next = last[0]
            step = abs(t_next - t)
            if not step < 0.5 * last_step:
                stalls += 1
            if stalls > _NEWTON_STALLS or not newton_inexact(t, d, d1, d2, eps):
                return _finish(t, d, d1, s, c, phi, lo, hi, evaluations, AT_ROOT)
            last_step = step
        else:
            t_next, lo, hi = halley(t, d, d1, d2, where, lo, hi)
            if t_next == lo or t_next == hi:
                return _finish(t, d, d1, s, c, phi, lo, hi, evaluations, BEFORE)
        t = t_next
    return last


@jit
def flight_half_angle(phi, sin_phi, cos_phi, v, eps, lo, hi, w0_error):
    w0 = v + eps * sin_phi
    t = 2.0 * w0 / (1.0 - eps * cos_phi)  # the frozen-acceleration root
    if not lo < t < hi:
        t = 0.5 * (lo + hi)
    sin_h, cos_h = math.sin(0.5 * t), math.cos(0.5 * t)
    for evaluations in range(1, ITERATION_LIMIT + 1):
        sin_mid = sin_phi * cos_h + cos_phi * sin_h  # sin(phi + t/2)
        cos_mid = cos_phi * cos_h - sin_phi * sin_h
        s = sin_mid * cos_h + cos_mid * sin_h  # sin(phi + t)
        c = cos_mid * cos_h - sin_mid * sin_h
        d = 2.0 * eps * sin_h * sin_mid + t * (v - 0.5 * t)
        d1 = v - t + eps * s
        if not abs(d) < math.inf:
            return math.nan, math.nan, math.nan, evaluations, OVERFLOW
        where = classify(phi, v, eps, t, d, d1)
        if where >= AT_ROOT:
            if t >= SMALLEST_T and (where == FLAT or newton_inexact(t, d, d1, -1.0 + eps * c,
                                                                        eps)):
                refined = _refine(phi, sin_phi, cos_phi, v, eps, w0_error, t, lo, hi,
                                  evaluations)
                if refined[4] != MAX_ITERATIONS:
                    return refined
                evaluations = ITERATION_LIMIT  # refinement ran out: the loose verdict stands
            return _finish(t, d, d1, s, c, phi, lo, hi, evaluations, where)
        t_next, lo, hi = halley(t, d, d1, -1.0 + eps * c, where, lo, hi)
        if t_next == lo or t_next == hi:
            return _finish(t, d, d1, s, c, phi, lo, hi, evaluations, BEFORE)
        sin_h, cos_h = rotate(sin_h, cos_h, 0.5 * (t_next - t), 0.0, 0.5 * t_next)
        t = t_next
    return t, s, c, ITERATION_LIMIT, MAX_ITERATIONS
