"""The paper's lower-bound step: a flight approached from below, never overstepping its root.

Used for |eps| > 1, where the gap can have several roots (and for every eps with the method
"lower_bound").

Global step (the paper's; docs/method.md). Gravity and the plate's acceleration give
d2(t) >= -(1 + |eps|) =: -a (d1, d2, d3: the first three derivatives of d), so from a time t_k
with d_k = d(t_k) > 0 and slope r_k = d1(t_k),

    d(t_k + s) >= d_k + r_k*s - a*s**2/2,

and the larger root s_a of the right-hand side is a rigorous lower bound on the time left before
the next collision.

Local step (fast near a double root). The derivatives of the plate term are bounded by |eps|, so
with c_k = d2(t_k) = -1 + eps*cos(phi + t_k) and j_k = d3(t_k) = -eps*sin(phi + t_k),

    d2(t_k + s) >= c_k + j_k*s - |eps|*s**2/2 >= min(c_k, c_k + j_k*H - |eps|*H**2/2) =: c_H

for 0 <= s <= H (a concave quadratic in s has its minimum at an end), and c_H >= -a too. Hence
d(t_k + s) >= q_H(s) := d_k + r_k*s + c_H*s**2/2 on [0, H]. If the first positive root s_H of
q_H is <= H, d > 0 on [t_k, t_k + s_H): a step of s_H never oversteps; if q_H has no root in
[0, H], a step of H does not. H starts at s_a and grows towards s_H for a few rounds; the step is
the largest certified one. Near a double root t* (d ~ m*(t - t*)**2/2) the model's error is
O(|eps|*h**4) at a distance h, so h shrinks quadratically instead of the global step's crawl
(eps just above 1: the global bound a ~ 2 dwarfs the dip's curvature <= eps - 1, and steps of
~sqrt(2*d/a) took up to 20,000 iterations).

Rounding: the models use d_k, r_k and c_k lowered by their error bounds (``gap_error``,
``rate_error``), so they bound the exact gap from below; a discriminant within its rounding of zero
counts as a root. Root formulas are chosen by the sign of r_k so that they never subtract nearly
equal numbers (``first_root``). The iteration stops when the gap is within its rounding error of
zero; a final Newton correction (``polish``) then moves onto the crossing: the stop can be up to
~12 kappa*u early, the polish leaves only the gap's actual rounding. It is taken only where the
slope d1 < 0 beyond its error; where d is convex over the step the tangent lies below d and its
root is not beyond the crossing, where it is concave the overshoot is at most s**2*a/(2|d1|) for a
step s itself at rounding level (|d| <= E). No second root lies that close (``may_be_graze``).

For |eps| > 1 the gap can be convex (d2 <= |eps| - 1 =: b), and a zero gap with a small slope may
be the bottom of a near-tangent dip whose sign float64 cannot tell: that flight is UNCERTAIN. At
most ITERATION_LIMIT evaluations for any input (then MAX_ITERATIONS, as UNCERTAIN).

Range. The analysis above needs every intermediate finite: a bound E or R that overflows to inf
would make any point "within rounding of zero" (a CONVERGED far from the root), and an overflowing
r*r in a step formula gives a zero step and a stop at an arbitrary point. So each point is checked
(``next_point``): with X = (|r| + R)**2 + 2*a*(|d| + E), OVERFLOW unless X <= RANGE_LIMIT = 2**1000
and d, r are finite. Then every step formula is finite: the discriminants are at most X; the step
s_a <= 2*sqrt(X)/a; the local step's trials h <= 64*s_a give |eps|*h <= 2**508 and
|eps|*h**2/2 either finite or +inf, which lowers c_H to its floor -a (still a valid bound), never
NaN; E and R are finite by the check. Which inputs pass: before the root t <= v + sqrt(v**2 +
4|eps|), so with A = |v| + sqrt(|eps|) + 1 (T <= 2A, |r| <= 3A + |eps|, |d| <= 2|eps| + 4A**2,
|eps| <= A**2) X <= 30*A**2*(1 + |eps|) (to a few u): no elastic flight with
30*A**2*(1 + |eps|) <= 2**1000 ends OVERFLOW here, e.g. |eps| <= 5e149 for |v| <= 1 and
|v| <= 4e149 for |eps| <= 1; beyond, a flight ends OVERFLOW at the first point whose X
exceeds the limit (and where d or r themselves overflow, as before), never CONVERGED. (The
concave path of ``fastpath.elastic.concave`` for |eps| <= 1 starts at the Holmes time 2*v, where
|tau - 2*v| <= 4|eps|/tau (docs/model.md): that start,
where its bound E overflows (v > 5e153) is within rounding of the root and is returned.)
"""

import math
from typing import NamedTuple

from fastpath.arithmetic.jit import jit, typed_overload
from fastpath.arithmetic.rounding import UNIT_ROUNDOFF
from fastpath.elastic.gap import gap, gap_error, gap_rate, rate_error
from fastpath.physics import NONE, Elastic
from fastpath.status import CONVERGED, ITERATION_LIMIT, MAX_ITERATIONS, OVERFLOW, UNCERTAIN

_GROWTH_ROUNDS = 4  # rounds of growing H in the local step
RANGE_LIMIT = 2.0**1000  # the largest X of a point the analysis admits (module docstring: Range)
GOING_ON = -1  # ``next_point``: no end yet


class GapBounds(NamedTuple):
    """What a lower-bound step at t needs (``elastic_gap_bounds``, and with drag
    ``fastpath.dissipative.drag_flight.drag_gap_bounds``)."""

    gap: float  # d(t)
    rate: float  # d'(t)
    gap_error: float  # E, the rounding bound of d
    rate_error: float  # R, the rounding bound of d'
    curvature: float  # c: d''(t) lowered by its rounding bound
    jerk: float  # j = d'''(t) = -eps*sin(phi + t)
    eps: float
    curvature_bound: float  # a: the bound on -d'' for the rest of the flight


@jit
def lower_bound_step(d, r, a):
    """Larger root s of d + r*s - a*s**2/2 = 0 (d >= 0, a > 0), cancellation-free."""
    root = math.sqrt(r * r + 2.0 * a * d)
    if r >= 0.0:
        return (r + root) / a
    return 2.0 * d / (root - r)


@jit
def first_root(d, r, k):
    """Smallest positive root of d + r*s + k*s**2/2 (d > 0), inf if none; cancellation-free.

    A discriminant within its rounding error of zero counts as zero (a root: the shorter step).
    """
    disc = r * r - 2.0 * k * d
    if disc < -4.0 * UNIT_ROUNDOFF * (r * r + 2.0 * abs(k) * d) or (r >= 0.0 and k >= 0.0):
        return math.inf
    disc = max(disc, 0.0)
    if r < 0.0:
        return 2.0 * d / (math.sqrt(disc) - r)
    return (r + math.sqrt(disc)) / -k


@jit
def certified_step(d, r, c, j, eps, a):
    """Largest step from a point with d > 0 that the module docstring's lower models certify.

    a > 0 bounds -d2 from above for the rest of the flight (1 + |eps| here; with drag
    ``fastpath.dissipative.drag_flight`` passes its own bound), c is a lower bound on d2 at the
    point where only the plate's part still varies (third derivative j, Taylor remainder
    |eps|*s**2/2).
    """
    best = lower_bound_step(d, r, a)
    h = best
    for _ in range(_GROWTH_ROUNDS):
        c_h = max(min(c, c + j * h - 0.5 * abs(eps) * h * h), -a)
        s_h = first_root(d, r, c_h)
        if s_h <= h:
            return max(best, s_h)
        best = h  # q_H > 0 on [0, H]
        h = min(s_h, 4.0 * h)
    return best


@jit
def may_be_graze(phi, eps, t, r, d_err):
    """Whether a gap within rounding of zero at t (|d| <= d_err) may be a near-tangent dip.

    The exact gap is then <= 2*d_err at t. Where it is locally concave, d2 = d''(t) < 0, it
    stays concave for a time R = -d2/|eps| (the third derivative is bounded by |eps|), so with
    slope r < 0 it surely crosses zero within 2*d_err/|r| if that is shorter than R: a collision
    at t up to rounding. Otherwise a dip of depth <= 2*d_err can follow only if
    r > -sqrt(4*b*d_err), with b = |eps| - 1 the largest possible curvature (safety factor 2).
    """
    convex_bound = abs(eps) - 1.0
    if convex_bound <= 0.0:
        return False  # the gap is concave everywhere: no dip
    # raised by its rounding bound, the argument's rounding u*(|phi| + t) included (as in
    # elastic_gap_bounds): the shortcut needs d'' < 0 for certain
    curvature = -1.0 + eps * math.cos(phi + t) + 4.0 * UNIT_ROUNDOFF * abs(eps) * (1.0 + t)
    if curvature < 0.0 and r < 0.0 and 2.0 * d_err < -r * (-curvature / abs(eps)):
        return False
    return r > -2.0 * math.sqrt(4.0 * convex_bound * d_err)


@jit
def elastic_gap_bounds(phi, v, eps, t):
    """What a lower-bound step at t needs, without drag: ``GapBounds`` (d, d1, E, R, c, j, eps, a).

    d and its slope d1 with their rounding bounds E, R (``fastpath.elastic.gap``); c = d2(t)
    lowered by its rounding bound (the argument's u*(|phi| + t) included); the jerk
    j = d3(t) = -eps*sin(phi + t); a = 1 + |eps|, the bound on -d2 for the rest of the flight.
    """
    d = gap(phi, v, eps, t)
    r = gap_rate(phi, v, eps, t)
    d_err = gap_error(phi, v, eps, t)
    r_err = rate_error(phi, v, eps, t)
    theta = phi + t
    curvature = -1.0 + eps * math.cos(theta) - 4.0 * UNIT_ROUNDOFF * abs(eps) * (1.0 + t)
    return GapBounds(d, r, d_err, r_err, curvature, -eps * math.sin(theta), eps,
                     1.0 + abs(eps))


@jit
def next_point(t, bounds, grazes):
    """One lower-bound iteration from t, given the gap's ``bounds`` there
    (``GapBounds``) and whether a zero gap there may be a graze: (t_next, status),
    status GOING_ON or the FlightStatus of the flight's end at t_next.

    The models take the worst values within rounding: d, d1 and d2 lowered by their bounds.
    """
    d, r, d_err, r_err, curvature, jerk, eps, a = bounds
    if not (abs(d) < math.inf and abs(r) < math.inf):
        return math.nan, OVERFLOW
    if not (abs(r) + r_err) ** 2 + 2.0 * a * (abs(d) + d_err) <= RANGE_LIMIT:
        return math.nan, OVERFLOW  # beyond the range of the error analysis
    if d <= d_err:
        if grazes:
            return t, UNCERTAIN
        return polish(t, d, r, r_err), CONVERGED
    t_next = t + certified_step(d - d_err, r - r_err, curvature, jerk, eps, a)
    if t_next == t:  # the root is within rounding of t: d <= d_err + |r|*ulp(t)
        return polish(t, d, r, r_err), CONVERGED
    return t_next, GOING_ON


@jit
def lower_bound_flight(phi, v, eps, t):
    """(tau, evaluations, status) by certified lower-bound steps from t without drag; phi
    reduced: ``lower_bound_steps`` for the elastic description with amplitude eps.

    t: a time certified to lie before the first root: the step from the departure,
    2*w0/(1 + |eps|), or a later point where d > 0 is known, as after a detachment
    (``fastpath.dissipative.sticking``).
    """
    return lower_bound_steps(phi, v, Elastic(eps, 0.0, NONE, 1.0), t, 0)


@jit
def lower_bound_steps(phi, v, physics, t, used):
    """(tau, evaluations, status) by certified lower-bound steps from t, a time certified to lie
    before the first root, counting ``used`` evaluations already spent: the one iteration of the
    paper's steps, for every description (with drag ``fastpath.dissipative.drag_flight``).

    Each round: the model's ``jump`` (a certified later start, paid for from the same budget of
    ITERATION_LIMIT evaluations), then one evaluation, ``bounds_at`` (the ``GapBounds`` at t and
    whether a zero gap there may be a graze), and the shared ``next_point``. What a model
    changes are these two and ``jumps_of`` (what its jumps need, computed once per flight),
    chosen by the description's class when numba compiles this loop (``lower_bound_model``):
    the loop compiled for ``Elastic`` holds only the elastic bounds, and its jump (none: zero
    evaluations, the start unchanged) folds away.

    The choice is an overload (``fastpath.arithmetic.jit.typed_overload``) of each of the three
    on the description's class, as ``fastpath.kernels.particle`` chooses a model's collision:
    made when the loop is typed, so no branch at run time and no other class's code compiled.
    The functions come from a table of ``LowerBoundModel`` by class, which each model's module
    fills (``fastpath.dissipative.drag_flight`` the ``Dissipative`` row: elastic code never
    imports dissipative code), and which the three functions read as plain Python too, so the
    loop runs uncompiled (``py_func``) for every class as it does compiled.
    """
    jumps = jumps_of(phi, v, physics)
    evaluations = used
    while evaluations < ITERATION_LIMIT:
        t, jumped = jump(v, physics, t, jumps, ITERATION_LIMIT - evaluations)
        evaluations += jumped
        if evaluations >= ITERATION_LIMIT:
            break
        evaluations += 1
        bounds, grazes = bounds_at(phi, v, physics, t)
        t, status = next_point(t, bounds, grazes)
        if status != GOING_ON:
            return t, evaluations, status
    return t, ITERATION_LIMIT, MAX_ITERATIONS


class LowerBoundModel(NamedTuple):
    """What one class of description gives ``lower_bound_steps``: three plain functions with the
    parameters of ``bounds_at``, ``jumps_of`` and ``jump``, compiled by numba into the loop
    (and called as they are where the loop runs as plain Python)."""

    bounds_at: object
    jumps_of: object
    jump: object


_MODELS = {}  # description class: its LowerBoundModel


def lower_bound_model(cls, model):
    """Register the ``LowerBoundModel`` of the descriptions of class ``cls`` (``Elastic`` below;
    ``Dissipative`` in ``fastpath.dissipative.drag_flight``, which elastic code never imports)."""
    _MODELS[cls] = model


def bounds_at(phi, v, physics, t):
    """(``GapBounds`` at t, whether a gap within rounding of zero there may be a graze)."""
    return _MODELS[type(physics)].bounds_at(phi, v, physics, t)


def jumps_of(phi, v, physics):
    """What the model's jumps need, computed once per flight."""
    return _MODELS[type(physics)].jumps_of(phi, v, physics)


def jump(v, physics, t, jumps, budget):
    """(t', evaluations): a certified later start than t (t itself where none applies), at most
    ``budget`` evaluations."""
    return _MODELS[type(physics)].jump(v, physics, t, jumps, budget)


@typed_overload(bounds_at)
def _bounds_at_of_model(phi, v, physics, t):
    return _MODELS[physics.instance_class].bounds_at


@typed_overload(jumps_of)
def _jumps_of_model(phi, v, physics):
    return _MODELS[physics.instance_class].jumps_of


@typed_overload(jump)
def _jump_of_model(v, physics, t, jumps, budget):
    return _MODELS[physics.instance_class].jump


def elastic_bounds_at(phi, v, physics, t):
    """``bounds_at`` without drag: ``elastic_gap_bounds`` and ``may_be_graze``."""
    eps = physics.eps
    bounds = elastic_gap_bounds(phi, v, eps, t)
    grazes = bounds.gap <= bounds.gap_error and may_be_graze(phi, eps, t, bounds.rate,
                                                             bounds.gap_error)
    return bounds, grazes


def no_jumps(phi, v, physics):
    """``jumps_of`` without drag: nothing."""
    return None


def no_jump(v, physics, t, jumps, budget):
    """``jump`` without drag: none, no evaluation."""
    return t, 0


lower_bound_model(Elastic, LowerBoundModel(elastic_bounds_at, no_jumps, no_jump))


@jit
def polish(t, d, r, r_err):
    """One certified Newton correction t - d/r at a stop with |d| within rounding of zero,
    taken only where the slope r is negative beyond its rounding bound r_err."""
    if not r < -r_err:
        return t
    return t - d / r
