"""The concave solver's loops (``fastpath.elastic.concave``): the evaluation budget, Halley's
step, the refinement's rule at its exact ties, overflow, and ``bracket`` at its ties.

Some facts are about how many times the gap is evaluated. The solver bodies are run here as plain
Python (``py_func``; their callees stay compiled), so that the module globals they call can be
wrapped to count the evaluations: one ``classify`` per evaluation of the loose gap, one
``tight_gap`` per evaluation of the refinement. A flight makes at most ITERATION_LIMIT = 60
evaluations for any input; the reported count must be the number made, and MAX_ITERATIONS must mean
that all ITERATION_LIMIT were made (module docstring: "At most ITERATION_LIMIT evaluations (then
MAX_ITERATIONS)").

The budget, the overflow check and a start on a bracket end cannot be reached through
``concave_flight``: its brackets keep every flight below ~2|v| + 2 (natural flights need at most
38 evaluations over 200,000 near-triple ones). Those tests call the loops with a sound but loose
bracket, which is what the loops are specified for; the exact ties of ``_refine`` use crafted
states (eps = 0, or a flight found by search) with a w0_error chosen to put d or d' exactly on
its bound.

Comparisons whose strict and non-strict forms give the same result on every input, and so have
no test: ``bracket``'s ``1e-150 < |v| < 1e150`` ends (at |v| = 1e150,
sqrt(fl(v*v)) = |v| = hypot; at 1e-150 the two roots differ, by an ulp, only for |eps| below
~1e-284, and with w0_error < w0 the energy bound is used only for |eps| > 1/3),
``hi_energy < hi_concave`` and
``w0 - w0_error > 0`` at equality (the same value either way), ``_finish``'s ``|h| < 1e-8`` at
|h| = 1e-8 (``small_sin_cos(+-1e-8)`` is exactly (+-1e-8, 1.0): the rotation is the first-order
formula bit for bit), the Holmes loop's ``d1 < -d1_err`` before ``newton_is_final`` at
d' = -R (there |d| > E, so |h|*R >= |d|*(1 - u)**2 > E/16: not final either way),
``_refine``'s ``d >= -d_err`` at d = -E with d' > R (d' > R proves d' > 0, so the exact gap,
concave with d(0) = 0, is >= t*d' > 0, and the computed one > -E).
"""

import math
import struct

import pytest
from fastpath_tolerances import U, kappa
from mpmath import mp

import fastpath.elastic.concave as concave
from fastpath.elastic.concave import bracket
from fastpath.elastic.gap import departure
from fastpath.status import ITERATION_LIMIT, FlightStatus

DPS = 40
CONVERGED = int(FlightStatus.CONVERGED)
MAX_ITERATIONS = int(FlightStatus.MAX_ITERATIONS)


def _python(kernel):
    """The plain-Python body of a numba kernel (the kernel itself where jit is disabled)."""
    return getattr(kernel, "py_func", kernel)


@pytest.fixture
def evaluations(monkeypatch):
    """A list that receives one entry per gap evaluation of the solver bodies called through
    ``_python``: ("loose", t, d, d') from ``classify`` or ("tight", t, d, d', d'', s, c, E, R)
    from ``tight_gap``; ``_refine`` is replaced by its plain body so that its calls are seen."""
    points = []
    classify, tight_gap = concave.classify, concave.tight_gap

    def counted_classify(phi, v, eps, t, d, d1):
        points.append(("loose", t, d, d1))
        return classify(phi, v, eps, t, d, d1)

    def counted_tight_gap(sin_phi, cos_phi, v, eps, w0_error, t):
        out = tight_gap(sin_phi, cos_phi, v, eps, w0_error, t)
        points.append(("tight", t, *out))
        return out

    monkeypatch.setattr(concave, "classify", counted_classify)
    monkeypatch.setattr(concave, "tight_gap", counted_tight_gap)
    monkeypatch.setattr(concave, "_refine", _python(concave._refine))
    return points


def _exact_gap(phi, v, eps, t):
    with mp.workdps(DPS):
        phi, v, eps, t = (mp.mpf(x) for x in (phi, v, eps, t))
        return 2 * eps * mp.sin(phi + t / 2) * mp.sin(t / 2) + t * (v - t / 2)


# --- the evaluation budget (ITERATION_LIMIT) of each loop ---


def test_half_angle_loop_makes_exactly_the_budget(evaluations):
    """``flight_half_angle`` makes exactly ITERATION_LIMIT evaluations before MAX_ITERATIONS.

    A flight that cannot converge within the budget, built so that this follows from the
    maths alone: eps = 1e-3 and a sound but loose bracket [lo, 2**200], lo the solver's own
    first guess (the root of the frozen-acceleration parabola, checked to lie before the root:
    the exact gap there is positive), so the loop starts at the midpoint ~2**199. For t >> 1
    the gap is d = -t**2/2 + O(t), d' = -t + O(1), d'' = -1 + eps*cos(phi + t), and Halley's
    step gives t_next/t = (1/2 + eps*c/2)/(3/2 + eps*c/2) in [0.3331, 0.3336] (to relative
    O(1/t)): inside the bracket (no bisection), so 60 steps end above 2**199 * 0.3331**60 >
    2**103, far from the root (~0.5). The loop must make all 60 evaluations, report 60 and
    MAX_ITERATIONS (not 58 or 59 evaluations reported as 60, nor 61)."""
    phi, v, eps = -1.5, 0.25, 1e-3
    sin_phi, cos_phi = math.sin(phi), math.cos(phi)
    w0, w0_error = departure(phi, sin_phi, v, eps, 0.0)
    assert 2.0 * w0 < 1.0 + abs(eps)  # the half-angle start
    lo = 2.0 * w0 / (1.0 - eps * cos_phi)  # the solver's first guess, computed as it does
    assert _exact_gap(phi, v, eps, lo) > 0  # before the (only) root: a sound lower end
    hi = 2.0**200
    tau, _, _, reported, status = _python(concave.flight_half_angle)(
        phi, sin_phi, cos_phi, v, eps, lo, hi, w0_error)
    assert evaluations[0][1] == 0.5 * (lo + hi)  # the start left the bracket: its midpoint
    assert len(evaluations) == reported == ITERATION_LIMIT
    assert status == MAX_ITERATIONS
    assert all(point[0] == "loose" for point in evaluations)
    assert tau > 2.0**103  # the next iterate, 60 steps of ratio >= 0.3331 from 2**199


def test_holmes_loop_makes_exactly_the_budget(evaluations):
    """``flight_from_holmes`` makes exactly ITERATION_LIMIT evaluations before MAX_ITERATIONS.

    A Holmes flight (2*w0 >= 1 + |eps|) given the loose but sound bracket [lo, 2**600]: phi =
    1.2, v = 0.3, eps = 0.5. At the start t = 2v = 0.6 the gap is positive and rising (d' =
    -v + eps*sin(phi + 2v) ~ 0.19 > 0), so Halley's step points back towards t = 0, leaves
    [0.6, hi] and is replaced by the geometric mean sqrt(0.6 * 2**600) ~ 2**299.6. From there,
    as for the half-angle test, t_next/t = (1/2 + eps*c/2)/(3/2 + eps*c/2) in [0.2, 0.43]
    (|eps*c| <= 1/2), inside the bracket, and t**3 ~ 2**899 does not overflow: after 58 more
    steps t is still above 2**299 * 0.2**59 > 2**160, far from the root (~1.2). The loop must
    make all 60 evaluations and say so (not 58 reported as 60, nor 61)."""
    phi, v, eps = 1.2, 0.3, 0.5
    sin_phi, cos_phi = math.sin(phi), math.cos(phi)
    w0, w0_error = departure(phi, sin_phi, v, eps, 0.0)
    assert 2.0 * w0 >= 1.0 + abs(eps)  # the Holmes start
    lo, _ = bracket(v, w0, w0_error, eps)
    tau, _, _, reported, status = _python(concave.flight_from_holmes)(
        phi, sin_phi, cos_phi, v, eps, lo, 2.0**600)
    assert evaluations[0][1] == 2.0 * v and evaluations[0][3] > 0.1  # rising at the start
    assert 2.0**299 < evaluations[1][1] < 2.0**300  # the geometric mean
    assert len(evaluations) == reported == ITERATION_LIMIT
    assert status == MAX_ITERATIONS
    assert tau > 2.0**160


@pytest.mark.parametrize("done", [0, 50, 57, 58, 59])
def test_refinement_makes_at_most_the_evaluations_left(evaluations, done):
    """``_refine`` continues a flight that has made ``done`` evaluations: it may make at most
    ITERATION_LIMIT - done more, and reports the total, done + the number it made. Started on
    the triple family (phi = -x, v = x, eps = 1: the exact root is 2x) at
    64 times the root, it needs about ten Halley steps (each shrinks t by about 3/5, the rate
    on the quartic d ~ -t**4/24, until the tight bound can place the root): with done = 0 it
    converges to the root (within 2*kappa*u, the triple family's bound) in fewer than 60; with
    done >= 50 it runs out, MAX_ITERATIONS with no Newton point found, after exactly the
    evaluations left."""
    x = 1e-4
    phi, v, eps = -x, x, 1.0
    sin_phi, cos_phi = math.sin(phi), math.cos(phi)
    _, w0_error = departure(phi, sin_phi, v, eps, 0.0)
    tau, _, _, reported, status = _python(concave._refine)(
        phi, sin_phi, cos_phi, v, eps, w0_error, 64 * 2 * x, x, 1.0, done)
    made = len(evaluations)
    assert all(point[0] == "tight" for point in evaluations)
    assert 1 <= made <= ITERATION_LIMIT - done
    assert reported == done + made
    if done == 0:
        assert status == CONVERGED and made < ITERATION_LIMIT
        with mp.workdps(DPS):
            assert abs(tau - 2 * mp.mpf(x)) <= 2 * kappa(phi, v, eps, 2 * x) * U * 2 * x
    if done >= 50:
        assert status == MAX_ITERATIONS and math.isnan(tau)
        assert made == ITERATION_LIMIT - done


# --- the iteration itself ---


def _exact_derivatives(phi, v, eps, t):
    """d, d', d'' of the exact gap at t (mpmath)."""
    with mp.workdps(DPS):
        phi, v, eps, t = (mp.mpf(x) for x in (phi, v, eps, t))
        d = 2 * eps * mp.sin(phi + t / 2) * mp.sin(t / 2) + t * (v - t / 2)
        return d, v - t + eps * mp.sin(phi + t), -1 + eps * mp.cos(phi + t)


@pytest.mark.parametrize("phi, v, eps", [
    (1.0, 0.8, 0.9), (2.5, 0.6, 1.0), (-2.0, 1.5, 0.7),  # Holmes start
    (0.5, 0.7, -0.95),  # half-angle start
])
def test_the_second_point_is_halleys_step_from_the_first(evaluations, phi, v, eps):
    """Both loops (Holmes and half-angle) step by Halley with d'' = -1 + eps*cos(phi + t).

    The module docstring's step is Halley's, t - 2*d*d'/(2*d'**2 - d*d''), with
    d'' = -1 + eps*cos(phi + t). On these flights the first step stays inside the bracket, so
    the second evaluation point is that step from the first, computed from the computed d, d'
    (errors of a few u of their terms): within 1e-12 relative of the step from the exact
    d, d', d'' (mpmath). With d'' of the wrong sign the step moves by more than 1e-4 (checked
    below), so a solver that takes it is caught."""
    sin_phi, cos_phi = math.sin(phi), math.cos(phi)
    w0, w0_error = departure(phi, sin_phi, v, eps, 0.0)
    lo, hi = bracket(v, w0, w0_error, eps)
    if 2.0 * w0 >= 1.0 + abs(eps):
        answer = _python(concave.flight_from_holmes)(phi, sin_phi, cos_phi, v, eps, lo, hi)
    else:
        answer = _python(concave.flight_half_angle)(phi, sin_phi, cos_phi, v, eps, lo, hi,
                                                     w0_error)
    assert answer[4] == CONVERGED and len(evaluations) >= 2
    t1, t2 = evaluations[0][1], evaluations[1][1]
    d, d1, d2 = _exact_derivatives(phi, v, eps, t1)
    with mp.workdps(DPS):
        halley = t1 - 2 * d * d1 / (2 * d1 * d1 - d * d2)
        wrong = t1 - 2 * d * d1 / (2 * d1 * d1 - d * (-2 - d2))  # d'' = -1 - eps*cos
        assert lo < halley < hi and abs(wrong - halley) > 1e-4 * halley
        assert abs(t2 - halley) <= 1e-12 * halley, (t2, halley)


# --- the helpers at their exact boundaries ---


def test_newton_inexact_at_its_threshold():
    """``newton_inexact`` at its threshold: whether the Newton point may miss the root by MORE than
    u*t/2 in second order (docstring): (|d''| + |eps*delta|)*delta**2 > u*t*|d'| with delta = d/d'.
    At equality it is not inexact (the answer is final). With eps = 0, d'' = -1, d' = -1, d = 2**-30
    and t = 2**-7 both sides are exactly 2**-60."""
    from fastpath.elastic.concave import newton_inexact

    t, d, d1 = 2.0**-7, 2.0**-30, -1.0
    assert (abs(-1.0) + 0.0) * (d / d1) ** 2 == U * t * abs(d1) == 2.0**-60  # the tie, exact
    assert not newton_inexact(t, d, d1, -1.0, 0.0)
    assert newton_inexact(t, math.nextafter(d, 1.0), d1, -1.0, 0.0)
    assert not newton_inexact(t, math.nextafter(d, 0.0), d1, -1.0, 0.0)


# --- the refinement's classification at exact ties (crafted states, eps = 0) ---


def _w0_error_for(index, target, sin_phi, cos_phi, v, eps, t, least=0.0):
    """The smallest w0_error >= ``least`` at which ``tight_gap``'s output ``index`` (5: E,
    6: R) reaches ``target``, by bisection over the float64 bit patterns (E and R do not
    decrease as w0_error grows)."""
    from fastpath.elastic.tight_gap import tight_gap

    def bits(x):
        return struct.unpack("<q", struct.pack("<d", x))[0]

    def as_float(i):
        return struct.unpack("<d", struct.pack("<q", i))[0]

    lo, hi = bits(least), bits(1.0)
    assert tight_gap(sin_phi, cos_phi, v, eps, 1.0, t)[index] >= target
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if tight_gap(sin_phi, cos_phi, v, eps, as_float(mid), t)[index] < target:
            lo = mid
        else:
            hi = mid
    return as_float(hi)


_PHI = 0.5  # any phase: with eps = 0 it enters only the returned sine and cosine


@pytest.mark.parametrize("t, side", [(2.0 - 2.0**-30, 1.0), (2.0 + 2.0**-29, -1.0)],
                         ids=["d=+E", "d=-E"])
def test_refinement_at_a_gap_exactly_on_its_bound_is_at_the_root(t, side):
    """``_refine`` at a gap exactly on its bound, |d| = E: the side is not proved.

    eps = 0, v = 1: d(t) = t*(1 - t/2), d' = 1 - t, the root exactly 2 (eps = 0: tau = 2v). At
    t = 2 - 2**-30 (2 + 2**-29) the computed d is exact, 2**-30 - 2**-61 (-(2**-29 + 2**-59)),
    and w0_error is chosen so that the bound E is exactly |d| (asserted). |d| <= E proves
    nothing about the side, d' = 1 - t ~ -1 is far beyond R: the point is after the maximum
    with the root within rounding (module docstring), so the refinement answers at once with
    the Newton point t - d/d' = 2 + O(2**-59), i.e. exactly 2.0, after one evaluation
    (the correction is not inexact: (d/d')**2 ~ 2**-60 <= u*t*|d'| ~ 2**-52). Taking d = +E as
    "before" (d = -E as "after") would spend a Halley step: two evaluations."""
    from fastpath.elastic.tight_gap import tight_gap

    sin_phi, cos_phi, v = math.sin(_PHI), math.cos(_PHI), 1.0
    d = t * (v - 0.5 * t)
    assert d == side * (2.0**-30 - 2.0**-61 if side > 0 else 2.0**-29 + 2.0**-59)
    w0_error = _w0_error_for(5, abs(d), sin_phi, cos_phi, v, 0.0, t)
    d_c, d1, _, _, _, d_err, d1_err = tight_gap(sin_phi, cos_phi, v, 0.0, w0_error, t)
    assert d_c == d and d_err == abs(d) and d1 < -d1_err  # on the bound, after the maximum
    done = 7
    tau, _, _, reported, status = concave._refine(_PHI, sin_phi, cos_phi, v, 0.0, w0_error, t,
                                                  1.0, 3.0, done)
    assert status == CONVERGED and tau == 2.0 and reported == done + 1


def test_refinement_at_a_slope_exactly_minus_its_bound_is_flat():
    """``_refine`` at a slope exactly minus its bound, d' = -R: no certain descent.

    eps = 0, v = 1, t = 2 (the root): d = 0 and d' = -1 exactly, and w0_error is chosen so that
    the slope's bound R is exactly 1 (asserted). |d| <= E, and d' = -R does not prove d' < 0
    (the exact slope may be 0): float64 cannot tell a root from a flat top there, and the
    refinement must say UNCERTAIN (at t, after one evaluation), not call it a root."""
    from fastpath.elastic.tight_gap import tight_gap

    sin_phi, cos_phi, v, t = math.sin(_PHI), math.cos(_PHI), 1.0, 2.0
    w0_error = _w0_error_for(6, 1.0, sin_phi, cos_phi, v, 0.0, t)
    d, d1, _, _, _, d_err, d1_err = tight_gap(sin_phi, cos_phi, v, 0.0, w0_error, t)
    assert d == 0.0 <= d_err and d1 == -1.0 and d1_err == 1.0
    done = 7
    tau, _, _, reported, status = concave._refine(_PHI, sin_phi, cos_phi, v, 0.0, w0_error, t,
                                                  1.0, 3.0, done)
    assert status == int(FlightStatus.UNCERTAIN) and tau == t and reported == done + 1


def test_refinement_at_a_slope_exactly_its_bound_is_flat():
    """``_refine`` at a slope exactly its bound, d' = R, with |d| <= E: a flat top.

    A point with |d| <= E is before the maximum (so the root lies beyond it) only if d' > R
    proves d' > 0; at d' = R exactly the exact slope may be 0: a flat top, UNCERTAIN after one
    evaluation (module docstring). Such a point needs a gap that is flat to rounding over the
    whole of [0, t] (d ~ t*d', both at rounding level): eps = -1, phi = pi - x (so that
    d'' = -1 + cos(t - x) ~ -x**2/2), x = 9.03e-9, a departure w0 = 1.5e-23 and t = 2.05e-10,
    found by a search over such flights; w0_error (above the departure's own bound, so still a
    valid bound) is chosen so that R is exactly the computed d' (asserted, with |d| <= E). The
    point must not be taken as "before"."""
    from fastpath.elastic.tight_gap import tight_gap

    phi, v, eps, t = 3.141592644557456, 9.032337222943266e-09, -1.0, 2.054437778516293e-10
    sin_phi, cos_phi = math.sin(phi), math.cos(phi)
    w0, least = departure(phi, sin_phi, v, eps, 0.0)
    assert w0 > least
    d1 = tight_gap(sin_phi, cos_phi, v, eps, least, t)[1]
    w0_error = _w0_error_for(6, d1, sin_phi, cos_phi, v, eps, t, least)
    d, d1_c, _, _, _, d_err, d1_err = tight_gap(sin_phi, cos_phi, v, eps, w0_error, t)
    assert d1_c == d1 == d1_err > 0.0 and abs(d) <= d_err  # the tie, with the gap undecided
    lo, hi = bracket(v, w0, w0_error, eps)
    done = 7
    tau, _, _, reported, status = concave._refine(phi, sin_phi, cos_phi, v, eps, w0_error, t,
                                                  lo, hi, done)
    assert status == int(FlightStatus.UNCERTAIN) and tau == t and reported == done + 1


# --- the refinement's Newton continuation and its stall counter ---


def _replay_refinement(points, eps):
    """The refinement's rule (``_refine`` docstring) replayed on its recorded evaluations:
    (index of the evaluation where it must stop, why, stalls, continuations). Each point is
    classified by E and R; one with |d| <= E and d' < -R gives the Newton point t - d/d', the
    next iterate while the correction may miss by more than u*t/2 in second order
    (``newton_inexact``: (|d''| + |eps*delta|)*delta**2 > u*t*|d'|, delta = d/d'), except
    that a Newton step not shorter than half the previous one is a stall, and the third stall
    stops it (_NEWTON_STALLS = 2 may fail to halve)."""
    last_step, stalls, continuations = math.inf, 0, 0
    for i, (_, t, d, d1, d2, _, _, d_err, d1_err) in enumerate(points):
        if d > d_err or (d >= -d_err and d1 > d1_err) or d < -d_err:
            continue  # a Halley step (or a bisection) follows
        if not d1 < -d1_err:
            return i, "flat", stalls, continuations
        newton = t - d / d1
        step = abs(newton - t)
        if not step < 0.5 * last_step:
            stalls += 1
        if stalls > 2:
            return i, "stalls", stalls, continuations
        delta = d / d1
        if not (abs(d2) + abs(eps * delta)) * delta * delta > U * t * abs(d1):
            return i, "exact", stalls, continuations
        assert i + 1 < len(points) and points[i + 1][1] == newton  # the Newton point is next
        last_step = step
        continuations += 1
    return None, "ran out", stalls, continuations


_NEAR_TRIPLE = [  # phi = -x*(1 + a), v = x, eps ~ 1, x ~ 1e-9: flat to rounding around the root
    (-9.99999999999e-10, 1e-09, 1.0 - 1e-15),  # stops on the third stall
    (-1.2134827665356604e-09, 1.213482767749143e-09, 1.0 - 1e-12),  # exact after 3 Newton steps
    (-9.999999990000001e-10, 1e-09, 1.0 - 1e-12),  # after 2
    (-1.3367506985829556e-09, 1.3367506999197064e-09, 1.0 - 1e-15),  # at the first
    (-2.3886430765959576e-09, 2.3886430789846004e-09, 1.0 - 1e-15),  # after 2
]


def test_refinement_stops_where_its_rule_says(evaluations):
    """``_refine`` stops where its rule says: the stall counter and the Newton steps.

    Near-triple flights (eps -> 1, phi ~ -v ~ -1e-9) whose root float64 can only place to
    within the noise of the computed gap: the refinement goes on from Newton point to Newton
    point until the correction is exact to second order or the steps stop halving (module
    docstring: then rounding dominates). Its recorded evaluations are replayed against that
    rule (``_replay_refinement``): it must stop exactly where the rule says, having taken
    each Newton point as the next iterate. Among the flights one stops on its third stall, and
    others after two and three continuations (asserted, so that the rule is exercised); each
    answer is CONVERGED inside the certified bracket."""
    seen = set()
    for phi, v, eps in _NEAR_TRIPLE:
        sin_phi, cos_phi = math.sin(phi), math.cos(phi)
        w0, w0_error = departure(phi, sin_phi, v, eps, 0.0)
        lo, hi = bracket(v, w0, w0_error, eps)
        evaluations.clear()
        tau, _, _, reported, status = _python(concave.flight_half_angle)(
            phi, sin_phi, cos_phi, v, eps, lo, hi, w0_error)
        tight = [point for point in evaluations if point[0] == "tight"]
        stop, why, stalls, continuations = _replay_refinement(tight, eps)
        assert stop == len(tight) - 1, (phi, v, eps, stop, len(tight), why)
        assert reported == len(evaluations) <= ITERATION_LIMIT
        assert status == CONVERGED and lo <= tau <= hi
        seen.add((why, stalls if why == "stalls" else continuations))
    assert ("stalls", 3) in seen and ("exact", 2) in seen and ("exact", 3) in seen, seen


# --- a gap that overflows ---


def test_an_overflowing_gap_is_an_overflow():
    """A gap that overflows ends a flight as OVERFLOW (Holmes and half-angle loops).

    Given the brackets ``concave_flight`` builds, every iterate is below ~2|v| + 2 and d stays
    finite; given a sound but loose bracket [lo, 2**1023] the loops reach points where
    t*(v - t/2) overflows, and d = -inf must end the flight as OVERFLOW (NaN answer, the
    evaluations made so far) rather than be classified and stepped from (inf/inf is NaN).
    Half-angle (phi = -1.5, v = 0.25, eps = 1e-3, as in the budget test): the start is the
    midpoint 2**1022, where t**2/2 overflows: OVERFLOW at the first evaluation. Holmes (phi =
    pi/2, v = 0, eps = 1: 2*w0 = 2 = 1 + |eps|): at the start t = 2v = 0 the gap is exactly 0
    and rising, Halley's step is 0 (not inside the bracket) and the bisection of [0, 2**1023]
    is the arithmetic midpoint 2**1022 (lo = 0), where t*delta/2 overflows: OVERFLOW at the
    second evaluation."""
    overflow = int(FlightStatus.OVERFLOW)
    phi, v, eps = -1.5, 0.25, 1e-3
    sin_phi, cos_phi = math.sin(phi), math.cos(phi)
    w0, w0_error = departure(phi, sin_phi, v, eps, 0.0)
    lo = 2.0 * w0 / (1.0 - eps * cos_phi)
    assert 2.0 * w0 < 1.0 + abs(eps) and _exact_gap(phi, v, eps, lo) > 0
    tau, s, c, reported, status = concave.flight_half_angle(phi, sin_phi, cos_phi, v, eps, lo,
                                                             2.0**1023, w0_error)
    assert status == overflow and reported == 1 and math.isnan(tau) and math.isnan(s)

    phi, v, eps = math.pi / 2, 0.0, 1.0
    sin_phi, cos_phi = math.sin(phi), math.cos(phi)
    w0, w0_error = departure(phi, sin_phi, v, eps, 0.0)
    assert 2.0 * w0 >= 1.0 + abs(eps)
    lo, _ = bracket(v, w0, w0_error, eps)
    tau, s, c, reported, status = concave.flight_from_holmes(phi, sin_phi, cos_phi, v, eps, lo,
                                                              2.0**1023)
    assert status == overflow and reported == 2 and math.isnan(tau) and math.isnan(c)


@pytest.mark.parametrize("phi, v, eps, end", [(-1.5, 0.6, 0.5, "lo"), (1.5, 0.25, 0.5, "hi")])
def test_a_first_guess_on_a_bracket_end_is_replaced_by_the_midpoint(evaluations, phi, v, eps,
                                                                     end):
    """The half-angle start is the root of the frozen-acceleration parabola,
    2*w0/(1 - eps*cos(phi)), if it lies strictly inside the bracket, else the bracket's midpoint
    (an end is a bound, not a candidate). Here the bracket is given with that guess as one end,
    a sound one: for phi = -1.5 the plate's pull weakens along the flight (cos(phi + t) rises),
    so the exact gap is still positive at the guess and it is a lower end; for phi = 1.5 it
    strengthens, the gap is negative there and the guess is an upper end (both checked in
    mpmath). The first evaluation must be at the midpoint, not at the guess."""
    sin_phi, cos_phi = math.sin(phi), math.cos(phi)
    w0, w0_error = departure(phi, sin_phi, v, eps, 0.0)
    assert 2.0 * w0 < 1.0 + abs(eps)  # the half-angle start
    guess = 2.0 * w0 / (1.0 - eps * cos_phi)
    natural_lo, natural_hi = bracket(v, w0, w0_error, eps)
    if end == "lo":
        assert _exact_gap(phi, v, eps, guess) > 0
        lo, hi = guess, natural_hi
    else:
        assert _exact_gap(phi, v, eps, guess) < 0
        lo, hi = natural_lo, guess
    tau, _, _, _, status = _python(concave.flight_half_angle)(phi, sin_phi, cos_phi, v, eps, lo,
                                                               hi, w0_error)
    assert evaluations[0][1] == 0.5 * (lo + hi) != guess
    assert status == CONVERGED and lo <= tau <= hi


# --- when the half-angle loop hands over to the refinement ---


@pytest.mark.parametrize("phi, v, eps", [
    (-0.00018229153862124727, 0.000182291539037519, 0.9999997499131908),
    (3.1396782760976083, 0.001914377242062036, -1.0),
    (-0.002435281146165613, 0.0024352801687179157, 1.0),
])
def test_no_refinement_where_the_newton_correction_is_exact(evaluations, phi, v, eps):
    """``flight_half_angle`` judges its Newton correction with d'' = -1 + eps*cos(phi + t).

    Short near-triple flights (found by a search over such flights) whose loose loop stops at a
    point with |d| <= E and d' < -R where the Newton correction delta = d/d' is exact to second
    order by a wide margin: (|d''| + |eps*delta|)*delta**2, with the exact d'' = -1 +
    eps*cos(phi + t) (small here: eps*cos ~ 1), is below u*t*|d'|/100 (checked in mpmath from
    the computed d, d'). The module docstring's rule then answers with that correction: no
    refinement, no ``tight_gap`` evaluation. With d'' = -1 - eps*cos(phi + t) ~ -2 the same
    term exceeds 100*u*t*|d'| (checked): a solver using it would refine."""
    sin_phi, cos_phi = math.sin(phi), math.cos(phi)
    w0, w0_error = departure(phi, sin_phi, v, eps, 0.0)
    assert 2.0 * w0 < 1.0 + abs(eps)
    lo, hi = bracket(v, w0, w0_error, eps)
    tau, _, _, reported, status = _python(concave.flight_half_angle)(
        phi, sin_phi, cos_phi, v, eps, lo, hi, w0_error)
    assert status == CONVERGED and lo <= tau <= hi
    _, t, d, d1 = evaluations[-1]
    assert all(point[0] == "loose" for point in evaluations) and reported == len(evaluations)
    with mp.workdps(DPS):
        delta, c = mp.mpf(d) / mp.mpf(d1), mp.cos(mp.mpf(phi) + mp.mpf(t))
        scale = U * mp.mpf(t) * abs(mp.mpf(d1))
        assert (abs(-1 + eps * c) + abs(eps * delta)) * delta**2 < scale / 100
        assert (abs(-1 - eps * c) + abs(eps * delta)) * delta**2 > 100 * scale


def test_the_refinement_is_tried_at_the_smallest_t():
    """``tight_gap`` is proved for t >= SMALLEST_T = 2**-1000 (t/2 exact, the underflow
    allowance), and a point the loose bound leaves flat at such a t goes to the refinement.
    The flight phi = 0, eps = 1/2, v = 2**-1001 (exact root 4v*(1 - O(v**2)), just below
    2**-999) with the sound bracket (0, 2**-999): the frozen guess 2*w0/(1 - eps) = 2**-999 is
    its upper end, so the first point is the midpoint, exactly 2**-1000. There the gap and its
    slope are below every rounding bound (both underflow): flat by the loose test, and the
    refinement must evaluate ``tight_gap`` there (it finds it flat too: UNCERTAIN after two
    evaluations), not stop at the loose verdict without trying."""
    from fastpath.elastic.tight_gap import SMALLEST_T

    phi, v, eps = 0.0, 2.0**-1001, 0.5
    sin_phi, cos_phi = math.sin(phi), math.cos(phi)
    w0, w0_error = departure(phi, sin_phi, v, eps, 0.0)
    assert 2.0 * w0 / (1.0 - eps * cos_phi) == 2.0**-999
    points = []
    classify, tight_gap = concave.classify, concave.tight_gap

    def counted_classify(*args):
        points.append(("loose", args[3]))
        return classify(*args)

    def counted_tight_gap(*args):
        points.append(("tight", args[5]))
        return tight_gap(*args)

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(concave, "classify", counted_classify)
        patch.setattr(concave, "tight_gap", counted_tight_gap)
        patch.setattr(concave, "_refine", _python(concave._refine))
        tau, _, _, reported, status = _python(concave.flight_half_angle)(
            phi, sin_phi, cos_phi, v, eps, 0.0, 2.0**-999, w0_error)
    assert points == [("loose", SMALLEST_T), ("tight", SMALLEST_T)]
    assert status == int(FlightStatus.UNCERTAIN) and tau == SMALLEST_T and reported == 2


# --- bracket: the documented choice at its exact ties (both bounds are sound: these pin it) ---


def test_bracket_at_its_ties():
    """``bracket_from_root`` at its ties: the concave bound unless it EXCEEDS 2|v| + 2, the
    energy bound v + sqrt(v**2 + 4|eps|) in that form for v >= 0 (its docstring, and
    ``test_concave_flight._documented_bracket``). Other choices at the ties would give certified
    upper bounds too; these pin the documented one.

    v = 1, w0 = 1, w0_error = 0 (phi = 0: w0 = v exactly), eps = 1/2: the concave bound
    2*w0/(1 - |eps|) = 4 is exactly 2|v| + 2, so it is the bound, hi = 4*(1 + 4u), not the energy
    bound 1 + sqrt(3). v = 0 (a departure at rest, w0 = eps*sin(phi)) with
    eps = 0.6066357757671799 and a concave bound above 2: the energy bound is
    0 + sqrt(4|eps|), one correctly rounded square root; the form 4|eps|/sqrt(4|eps|) (the one
    for v < 0) rounds a second time and lands one ulp lower here."""
    lo, hi = bracket(1.0, 1.0, 0.0, 0.5)
    assert 2.0 * 1.0 / (1.0 - 0.5) == 2.0 * 1.0 + 2.0  # the tie, exact
    assert hi == 4.0 * (1.0 + 4.0 * U)
    eps = 0.6066357757671799
    w0 = eps * math.sin(1.5)
    assert 2.0 * w0 / (1.0 - eps) > 2.0  # the energy bound is the one used
    root = math.sqrt(4.0 * eps)
    assert 4.0 * eps / root != root  # the two forms differ here (one rounding more)
    lo, hi = bracket(0.0, w0, 2.0 * U * w0, eps)
    assert hi == root * (1.0 + 4.0 * U)


def test_a_newton_step_of_exactly_half_the_previous_is_a_stall(monkeypatch):
    """The rule (``_refine`` docstring) counts a Newton step that
    fails to HALVE the previous one as a stall, so a step of exactly half is one. The stand-in
    puts every point at the root (|d| <= E = 1, d' = -1 < -R = 0) with Newton steps 2**-10,
    2**-11, ... (all iterates exact dyadics) and a large |d''| so that the correction is never
    exact to second order: steps 2, 3, 4 are stalls and the third ends the refinement at the
    fourth evaluation; without the stalls it would run to ITERATION_LIMIT."""
    steps = iter([2.0**-k for k in range(10, 80)])

    def stand_in(sin_phi, cos_phi, v, eps, w0_error, t):
        step = next(steps)
        return -step, -1.0, -1e6, 0.0, 1.0, 1.0, 0.0  # d, d', d'', s, c, E, R

    monkeypatch.setattr(concave, "tight_gap", stand_in)
    done = 5
    tau, _, _, reported, status = _python(concave._refine)(
        0.0, 0.0, 1.0, 1.0, 0.5, 0.0, 1.0, 0.0, 2.0, done)
    assert reported == done + 4 and status == CONVERGED
    assert tau == 1.0 - 2.0**-10 - 2.0**-11 - 2.0**-12 - 2.0**-13
