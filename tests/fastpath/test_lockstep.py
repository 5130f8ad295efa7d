"""fastpath.elastic.lockstep: the straight-line flight of the ensembles' lanes, and the lanes'
collision (``fastpath.kernels.escape.lane_collide``).

It must be the function ``fastpath.step`` computes (one flight and a batch of lanes give the same
bits), answer only inside the certified bracket, agree with the general concave solver to the
rounding bound, and leave to that solver what it does not answer. ``lane_collide`` must return
what ``collide`` and ``departure_phase`` give for the same departure (the next flight's centred
phase and its error bound, bit for bit), and answer only where its moderate phase reduction is the
one ``collide`` uses (|phi + tau| < 2**20). The lane's comparisons are checked at exact equality
on crafted states.
"""

import math

import numpy as np

import fastpath
import verify
from fastpath.arithmetic.jit import jit
from fastpath.arithmetic.phase import centre_moderate, centre_phase, reduce_moderate, reduce_phase
from fastpath.arithmetic.sincos import sin_cos
from fastpath.elastic.collision import collide
from fastpath.elastic.concave import bracket, concave_flight
from fastpath.elastic.flight import GENERAL, departure_phase
from fastpath.elastic.gap import departure, gap_error, rate_error
from fastpath.elastic.lockstep import (
    COS,
    DELTA,
    DONE,
    FAILED,
    HI,
    LO,
    LOCKSTEP_EVALUATIONS,
    SIN,
    T,
    lockstep_flight,
    lockstep_flight_one,
    moderate_bracket,
)
from fastpath.kernels.escape import lane_collide

U = 2.0**-53


@jit  # fastpath's cached options: compiled once per version of fastpath and of this file
def _lanes(phi, v, eps, out):
    """lockstep_flight over arrays: the loop the ensembles vectorise."""
    for i in range(len(phi)):
        s, c = sin_cos(phi[i])
        _, w0_error = departure(phi[i], s, v[i], eps, 0.0)
        tau, s1, c1, k, done = lockstep_flight(phi[i], s, c, v[i], eps, w0_error)
        out[i, 0], out[i, 1], out[i, 2], out[i, 3], out[i, 4] = tau, s1, c1, k, done


def _states(n, seed=0, v=(0.3, 40.0)):
    rng = np.random.default_rng(seed)
    return rng.uniform(-math.pi, math.pi, n), rng.uniform(*v, n)


def test_lanes_give_the_bits_of_one_flight():
    phi, v = _states(4000)
    for eps in (0.6, -0.3, 0.999, 1.0):
        out = np.empty((len(phi), 5))
        _lanes(phi, v, eps, out)
        for i in range(0, len(phi), 7):
            s, c = sin_cos(phi[i])
            _, w0_error = departure(phi[i], s, v[i], eps, 0.0)
            one = lockstep_flight_one(phi[i], s, c, v[i], eps, w0_error)
            assert bool(out[i, 4]) == one[4]
            if one[4]:
                assert tuple(out[i, :4]) == (one[0], one[1], one[2], one[3])


def test_answers_lie_in_the_bracket_and_match_the_general_solver():
    phi, v = _states(6000, seed=1)
    answered = 0
    for eps in (0.6, 0.9, -0.5):
        for p, w in zip(phi, v, strict=True):
            s, c = sin_cos(p)
            w0, w0_error = departure(p, s, w, eps, 0.0)
            if not w0 > w0_error:
                continue
            tau, s1, c1, k, done = lockstep_flight_one(p, s, c, w, eps, w0_error)
            if not done:
                continue
            answered += 1
            lo, hi = bracket(w, w0, w0_error, eps)
            assert 0.0 < lo <= tau <= hi
            assert 1 <= k <= LOCKSTEP_EVALUATIONS
            ref, *_ = concave_flight(p, s, c, w, eps, w0_error)
            d1 = abs(w - tau + eps * math.sin(p + tau))
            # both answers are within the gap's rounding bound of the root (module docstrings)
            bound = 2.5 * (gap_error(p, w, eps, tau) / (d1 - rate_error(p, w, eps, tau)))
            assert abs(tau - ref) <= bound + 4 * U * tau, (p, w, eps, tau, ref)
            assert abs(s1 - math.sin(p + tau)) < 1e-14 and abs(c1 - math.cos(p + tau)) < 1e-14
    assert answered > 0.9 * 3 * len(phi) * 0.5  # most departures with 2*w0 >= 1 + |eps|


def test_against_verify_in_units_of_kappa_u():
    """The answers are within 2 kappa*u of verify's certified flight time (60 digits)."""
    phi, v = _states(200, seed=2, v=(1.0, 6.0))
    worst, checked = 0.0, 0
    for p, w in zip(phi, v, strict=True):
        eps = 0.6
        s, c = sin_cos(p)
        w0, w0_error = departure(p, s, w, eps, 0.0)
        if not w0 > w0_error:
            continue
        tau, *_, done = lockstep_flight_one(p, s, c, w, eps, w0_error)
        if not done:
            continue
        ref = verify.flight_time(p, w, eps, dps=60)
        kappa = verify.condition_number(p, w, eps, ref)
        worst = max(worst, float(abs((tau - ref) / ref) / (kappa * U)))
        checked += 1
    assert checked > 100 and worst <= 2.0, (checked, worst)


def test_what_it_does_not_answer():
    s, c = sin_cos(-1e-5)
    _, w0_error = departure(-1e-5, s, 1e-5, 1.0, 0.0)
    assert not lockstep_flight_one(-1e-5, s, c, 1e-5, 1.0, w0_error)[4]  # short flight
    phi, v = 3.0, 6e5  # |phi + 2v| >= 2**20
    s, c = sin_cos(phi)
    _, w0_error = departure(phi, s, v, 0.6, 0.0)
    assert not lockstep_flight_one(phi, s, c, v, 0.6, w0_error)[4]
    # and step still answers both, through the general solver
    assert fastpath.flight_time(-1e-5, 1e-5, 1.0) > 0 and fastpath.flight_time(phi, v, 0.6) > 0


def test_moderate_bracket_is_the_bracket():
    rng = np.random.default_rng(5)
    for _ in range(3000):
        v = float(10 ** rng.uniform(-3, 5))
        eps = float(rng.uniform(-1, 1)) if rng.random() < 0.9 else float(rng.choice([-1.0, 1.0]))
        w0 = v * float(rng.uniform(0.01, 1.0))
        err = w0 * float(10 ** rng.uniform(-16, -3))
        assert moderate_bracket(v, w0, err, eps) == bracket(v, w0, err, eps)


def test_moderate_reductions_are_the_reductions():
    rng = np.random.default_rng(6)
    xs = list(rng.uniform(-2**20 + 1, 2**20 - 1, 3000)) + list(rng.uniform(-30, 30, 3000))
    for k in range(-50, 50):
        for edge in (k * math.pi, k * 2 * math.pi):
            xs += [edge, np.nextafter(edge, math.inf), np.nextafter(edge, -math.inf)]
    for x in xs:
        assert reduce_moderate(x) == reduce_phase(x)
        assert centre_moderate(x) == centre_phase(x)


def _lane_states(n, seed=5):
    rng = np.random.default_rng(seed)
    return (rng.uniform(-np.pi, np.pi, n), rng.uniform(0.6, 30.0, n),
            rng.choice([0.6, -0.6, 0.99, 0.1], n))


def test_lanes_carry_the_departure_phase_of_the_landing():
    """Answered lanes: (tau, phi1, v1) are collide's, and (centred phi1, its error bound) are
    departure_phase(phi1), bit for bit; landings on both sides of pi occur (centred != phi1
    after a landing in [pi, 2*pi), where the centring adds an error)."""
    phi, v, eps = _lane_states(400)
    shifted = 0
    for p, w, e in zip(phi, v, eps, strict=True):
        centred, error = departure_phase(p)
        tau, phi1, v1, centred1, error1, answered = lane_collide(centred, w, e, error)
        if not answered:
            continue
        assert (phi1, v1, tau) == collide(p, w, e)[:3]  # AUTO: with the lockstep flight
        assert (centred1, error1) == departure_phase(phi1)
        shifted += centred1 != phi1
    assert 100 < shifted < 300


def _landing_at_the_limit(above):
    """A departure at phase 0 (eps = 0.5) whose landing phi + tau is 2**20 exactly (above=False)
    or just above it, with the Holmes start phi + 2v below 2**20 (the lockstep flight runs)."""
    eps = 0.5
    v = 2.0**19
    for _ in range(200000):
        v = np.nextafter(v, 0.0)
        tau, _, _, _, _, answered = lane_collide(0.0, v, eps, 0.0)
        x = 0.0 + tau
        if (x > 2.0**20) if above else (x == 2.0**20):
            return v, eps, tau
    raise AssertionError("no landing at 2**20 constructed")


def test_lanes_do_not_answer_landings_at_or_beyond_2_to_20():
    """|phi + tau| >= 2**20: collide reduces the landing with Payne-Hanek, not the lanes'
    Cody-Waite reduction, so the lane leaves that flight to collide (answered False)."""
    for above in (False, True):
        v, eps, tau = _landing_at_the_limit(above)
        assert 0.0 + 2 * v < 2.0**20 <= 0.0 + tau
        assert not lane_collide(0.0, v, eps, 0.0)[5]
        phi1 = collide(0.0, v, eps, GENERAL)[0]
        assert 0.0 <= phi1 < 2 * np.pi and centre_phase(phi1) == departure_phase(phi1)[0]


def test_lockstep_step_is_halley_from_the_holmes_start():
    """The first lockstep evaluation (at the Holmes start t = 2v) steps to Halley's iterate
    t - 2*d*d1/(2*d1**2 - d*d2) of the d, d1 = d', d2 = d'' it evaluated, where that lies inside
    the bracket: the same iterate to the rounding of the step (a few roundings of relative u
    each: 8u*|step|, plus u*t for the subtraction), checked in mpmath from the same floats."""
    import mpmath

    from fastpath.arithmetic.sincos import sin_cos
    from fastpath.elastic.gap import departure
    from fastpath.elastic.lockstep import lane_evaluation, lane_start

    u = 2.0**-53
    phi, v, eps = _lane_states(300, seed=11)
    checked = 0
    for p, w, e in zip(phi, v, eps, strict=True):
        s, c = sin_cos(p)
        _, w0_error = departure(p, s, w, e, 0.0)
        state, two_v = lane_start(p, s, w, e, w0_error)
        if state[FAILED]:  # not eligible
            continue
        t, delta, s0, c0, lo, hi = (state[T], state[DELTA], state[SIN], state[COS],
                                    state[LO], state[HI])
        after = lane_evaluation(state, p, c, w, e, two_v, 1)
        if after[DONE] or after[FAILED] or after[T] == 0.5 * (lo + hi):  # answered, gave up, halved
            continue
        d = e * (c - c0) - 0.5 * t * delta  # as lane_evaluation computes them, from the same floats
        d1 = -w - delta + e * s0
        with mpmath.workdps(40):
            d, d1, d2 = mpmath.mpf(d), mpmath.mpf(d1), -1 + mpmath.mpf(e) * mpmath.mpf(c0)
            step = 2 * d * d1 / (2 * d1 * d1 - d * d2)
            assert abs(after[T] - (t - step)) <= 8 * u * abs(step) + u * t
        checked += 1
    assert checked > 100


def test_lockstep_iterates_stay_inside_the_bracket():
    """Every evaluation that neither answers nor gives up moves to a point strictly inside the
    updated bracket; where Halley's step leaves it (short flights, v < 1, eps near +-1) the
    guard takes the bracket's midpoint."""
    from fastpath.arithmetic.sincos import sin_cos
    from fastpath.elastic.gap import departure
    from fastpath.elastic.lockstep import lane_evaluation, lane_start

    rng = np.random.default_rng(0)
    guarded = 0
    for _ in range(1500):
        p, w = rng.uniform(-np.pi, np.pi), 10 ** rng.uniform(-0.2, 3)
        e = rng.choice([1.0, -1.0, 0.999, 0.9, 0.6, 0.3])
        s, c = sin_cos(p)
        w0, w0_error = departure(p, s, w, e, 0.0)
        if not w0 > w0_error:
            continue
        state, two_v = lane_start(p, s, w, e, w0_error)
        for k in range(1, 5):
            if state[DONE] or state[FAILED]:
                break
            state = lane_evaluation(state, p, c, w, e, two_v, k)
            t, lo, hi = state[T], state[LO], state[HI]
            if not (state[DONE] or state[FAILED]):
                assert lo < t < hi
                guarded += t == 0.5 * (lo + hi)
    assert guarded > 0


def test_lockstep_start_is_the_holmes_time_in_the_certified_bracket():
    """lane_start: t = 2v, the certified bracket of this departure
    (``fastpath.elastic.concave.bracket`` of w0 = v + eps*sin(phi)), no answer yet, and the lane
    eligible exactly when 2*w0 >= 1 + |eps| (the other conditions hold for these states)."""
    from fastpath.arithmetic.sincos import sin_cos
    from fastpath.elastic.concave import bracket
    from fastpath.elastic.gap import departure
    from fastpath.elastic.lockstep import lane_start

    phi, v, eps = _lane_states(300, seed=2)
    for p, w, e in zip(phi, v * 0.1, eps, strict=True):
        s, _ = sin_cos(p)
        w0, w0_error = departure(p, s, w, e, 0.0)
        if not w0 > w0_error:
            continue
        state, two_v = lane_start(p, s, w, e, w0_error)
        assert two_v == state[T] == 2 * w and state[DELTA] == 0.0
        assert (state[LO], state[HI]) == bracket(w, w + e * s, w0_error, e)
        assert state[FAILED] == (not 2 * (w + e * s) >= 1 + abs(e))
    for w, e in ((0.5, 0.0), (0.75, 0.5), (1.0, 1.0)):  # phi = 0: 2*w0 = 1 + |eps| exactly
        assert not lane_start(0.0, 0.0, w, e, 0.0)[0][FAILED]
        assert lane_start(0.0, 0.0, np.nextafter(w, 0.0), e, 0.0)[0][FAILED]
    # |v| > 1e-150 (v**2 must not underflow): eps = 1, phi = pi/2 makes 2*w0 = 2 >= 1 + |eps|
    s, _ = sin_cos(np.pi / 2)
    assert s == 1.0
    assert lane_start(np.pi / 2, s, 1e-150, 1.0, 0.0)[0][FAILED]
    assert not lane_start(np.pi / 2, s, np.nextafter(1e-150, 1.0), 1.0, 0.0)[0][FAILED]
    # the Holmes phase phi + 2v must be inside sin_cos's range |x| < 2**20
    assert lane_start(0.0, 0.0, 2.0**19, 0.6, 0.0)[0][FAILED]
    assert not lane_start(0.0, 0.0, np.nextafter(2.0**19, 0.0), 0.6, 0.0)[0][FAILED]


def test_lockstep_collide_answers_eps_one():
    """|eps| = 1 is concave (d'' <= -1 + |eps| = 0): the lanes answer such flights too (eps = 1)."""
    from fastpath.arithmetic.sincos import sin_cos
    from fastpath.elastic.lockstep import lockstep_collide

    centred, error = departure_phase(0.3)
    s, c = sin_cos(centred)
    tau, *_, done = lockstep_collide(centred, s, c, 2.0, 1.0, error)
    assert done
    assert tau == collide(0.3, 2.0, 1.0)[2]


# Crafted lane states for the comparisons at exact equality in ``lane_evaluation``. With eps = 0
# the plate term and its error bounds vanish: d = -t*delta/2, d' = -v - delta, and (t = 1)
# d_err = d1_err = 4u*(|v| + 1), all exact in float64 for the dyadic values below, so d and d'
# can be put exactly on their error bounds. delta is read from the state (not t - 2v), so it is
# a free input. Each test first checks that the crafted floats are on the boundary as intended.
_U = 2.0**-53


def _crafted(v, delta, lo=0.25, hi=4.0):
    """(state, arguments) of a running lane at t = 1 with eps = 0 (phi = 0, sin = 0, cos = 1)."""
    state = (1.0, delta, 0.0, 1.0, 0.0, lo, hi, np.nan, 0.0, 0.0, 1.0, 0, False, False)
    return state, (0.0, 1.0, v, 0.0, 2.0 * v, 1)


def _bounds(v):
    """(d_err, d1_err) at t = 1, eps = 0, as ``gap_error`` and ``rate_error`` give them."""
    from fastpath.elastic.gap import gap_error, rate_error

    return gap_error(0.0, v, 0.0, 1.0), rate_error(0.0, v, 0.0, 1.0)


def test_lockstep_root_test_includes_a_gap_on_its_error_bound():
    """|d| == d_err with d' < -d1_err is a root (``abs(d) <= d_err``), even where the Newton
    correction is far from final (|d'| only 2*d1_err): the lane answers at t + newton (inside
    the bracket here). As ``abs(d) < d_err`` it would give up as a flat top."""
    from fastpath.elastic.concave import newton_is_final
    from fastpath.elastic.lockstep import TAU, lane_evaluation

    v = 16 * _U
    d_err, d1_err = _bounds(v)
    delta = -2.0 * d_err  # d = d_err
    state, args = _crafted(v, delta)
    d, d1 = -0.5 * delta, -v - delta
    assert d == d_err and -16 * d1_err < d1 < -d1_err
    assert not newton_is_final(-d / d1, d_err, d1_err, 0.0)
    after = lane_evaluation(state, *args)
    assert after[DONE] and not after[FAILED]
    assert abs(after[TAU] - (1.0 - d / d1)) <= 8 * _U  # the Newton point t - d/d' ~ 1.5


def test_lockstep_root_test_needs_a_rate_below_its_error_bound():
    """d' == -d1_err exactly (with |d| < d_err) is not a certain descent: no answer; the lane
    gives up as a flat top (``not d1 > d1_err``). As ``d1 <= -d1_err`` it would answer."""
    from fastpath.elastic.lockstep import lane_evaluation

    v = 2.0**-50
    d_err, d1_err = _bounds(v)
    delta = d1_err - v  # d' = -v - delta = -d1_err
    state, args = _crafted(v, delta)
    assert -v - delta == -d1_err and abs(-0.5 * delta) < d_err
    after = lane_evaluation(state, *args)
    assert after[FAILED] and not after[DONE]


def test_lockstep_flat_top_includes_a_rate_on_its_error_bound():
    """d' == d1_err exactly with |d| < d_err is a flat top (the rise is not certain): the
    lane gives up. As ``not d1 >= d1_err`` it would raise lo to t and step on."""
    from fastpath.elastic.lockstep import lane_evaluation

    v = 2.0**-52
    d_err, d1_err = _bounds(v)
    delta = -v - d1_err  # d' = d1_err
    state, args = _crafted(v, delta)
    assert -v - delta == d1_err and abs(-0.5 * delta) < d_err
    after = lane_evaluation(state, *args)
    assert after[FAILED] and not after[DONE]


def test_lockstep_bracket_moves_only_on_a_gap_beyond_its_error_bound():
    """d == +-d_err exactly with |d'| <= d1_err: the sign of the gap is not certain, so neither
    bracket end moves and the lane gives up as a flat top. As ``d >= d_err`` (``d <= -d_err``)
    it would move lo (hi) to t and step on."""
    from fastpath.elastic.lockstep import lane_evaluation

    for v in (2.0**-50, -(2.0**-50)):  # d = +d_err, then d = -d_err
        d_err, d1_err = _bounds(v)
        delta = -2.0 * d_err if v > 0 else 2.0 * d_err
        state, args = _crafted(v, delta)
        d, d1 = -0.5 * delta, -v - delta
        assert abs(d) == d_err and abs(d1) <= d1_err
        after = lane_evaluation(state, *args)
        assert after[FAILED] and not after[DONE]
        assert (after[LO], after[HI]) == (0.25, 4.0)


def test_lockstep_halley_step_onto_a_bracket_end_is_bisected():
    """A Halley step that lands exactly on a bracket end is not inside the bracket: the guard
    bisects (``lo < t_next < hi``). As ``<=`` the lane would stop there (bracket closed) and
    give up. The step is first taken in a wide bracket; that end is then put on it."""
    from fastpath.elastic.lockstep import lane_evaluation

    # d = 0.5 > d_err, d' = -1: lo moves to t = 1 and Halley steps right (to 1.4);
    # d = -0.5 < -d_err, d' = -1.5: hi moves to t = 1 and Halley steps left (to 0.625)
    for v, delta, end in ((2.0, -1.0, HI), (0.5, 1.0, LO)):
        state, args = _crafted(v, delta)
        wide = lane_evaluation(state, *args)
        t_next = wide[T]
        assert not (wide[DONE] or wide[FAILED]) and 0.25 < t_next < 4.0 and t_next != 1.0
        lo, hi = (1.0, t_next) if end == HI else (t_next, 1.0)
        state, args = _crafted(v, delta, *((0.25, t_next) if end == HI else (t_next, 4.0)))
        after = lane_evaluation(state, *args)
        assert not (after[DONE] or after[FAILED])
        assert (after[LO], after[HI]) == (lo, hi) and after[T] == 0.5 * (lo + hi)
