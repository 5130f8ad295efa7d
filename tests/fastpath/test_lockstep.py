"""fastpath.elastic.lockstep: the straight-line flight of the ensembles' lanes.

It must be the function ``fastpath.step`` computes (one flight and a batch of lanes give the same
bits), answer only inside the certified bracket, agree with the general concave solver to the
rounding bound, and leave to that solver what it does not answer.
"""

import math

import numba
import numpy as np

import fastpath
import verify
from fastpath.arithmetic.phase import centre_moderate, centre_phase, reduce_moderate, reduce_phase
from fastpath.arithmetic.sincos import sin_cos
from fastpath.elastic.concave import bracket, concave_flight
from fastpath.elastic.gap import departure, gap_error, rate_error
from fastpath.elastic.lockstep import (
    LOCKSTEP_EVALUATIONS,
    lockstep_flight,
    lockstep_flight_one,
    moderate_bracket,
)

U = 2.0**-53


@numba.njit(error_model="numpy")
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
