"""``fastpath.dynamics.velocities`` is the loop of the velocity moments with each orbit's v_n
recorded: one implementation of the velocities of many orbits at collision counts. Its rows are
the orbits of ``fastpath.orbit`` and, one particle per block, the sums of ``fastpath.moments``,
bit for bit, for both maps."""

import numpy as np
import pytest

import fastpath
import fastpath.dynamics as fd
from fastpath.status import CONVERGED

EPS = 0.6
COUNTS = [1, 2, 7, 30, 200]


def _starts(m, seed):
    rng = np.random.default_rng(seed)
    return rng.uniform(0.0, 2.0 * np.pi, m), rng.uniform(2.0, 4.0, m)


@pytest.mark.parametrize("model", ["exact", "holmes"])
def test_velocities_are_the_orbits_at_the_counts(model):
    phi, v = _starts(40, 1)
    vel, status = fd.velocities(phi, v, EPS, COUNTS, model=model)
    assert (status == CONVERGED).all()
    for i in range(len(phi)):
        orbit = fastpath.orbit(phi[i], v[i], EPS, COUNTS[-1], model=model)
        assert np.array_equal(vel[i], orbit.v[COUNTS])


@pytest.mark.parametrize("model", ["exact", "holmes"])
def test_velocities_are_the_moment_sums_of_one_particle_per_block(model):
    phi, v = _starts(40, 2)
    vel, _ = fd.velocities(phi, v, EPS, COUNTS, model=model)
    mom = fastpath.moments(phi, v, EPS, COUNTS, model=model, blocks=len(phi))
    assert (mom.count_n == 1).all()
    assert np.array_equal(vel, mom.sum_v_n)
    assert np.array_equal(vel * vel, mom.sum_v2_n)


def test_the_holmes_velocities_fold_where_the_velocity_would_turn_negative():
    """The Holmes map's v1 = |v - 2*eps*sin(phi1)|: slow orbits fold and go on (the
    standard-map form of the Jacobians would stop them)."""
    rng = np.random.default_rng(3)
    phi, v = rng.uniform(0.0, 2.0 * np.pi, 200), rng.uniform(0.05, 1.0, 200)
    leaves = v + EPS * np.sin(phi) > 0.0
    phi, v = phi[leaves], v[leaves]
    vel, status = fd.velocities(phi, v, EPS, [1, 50], model="holmes")
    assert (status == CONVERGED).all() and np.isfinite(vel).all() and (vel >= 0.0).all()
    phi1, v1 = fastpath.holmes_step(phi, v, EPS)
    assert np.array_equal(vel[:, 0], v1)
    folded = v - 2.0 * EPS * np.sin(phi1) < 0.0
    assert folded.any()


@pytest.mark.parametrize("model", ["exact", "holmes"])
def test_first_passage_is_the_first_count_at_which_the_orbit_reaches_the_velocity(model):
    """``first_passage`` runs the orbits of ``fastpath.orbit``: its count is the first n with
    v_n >= v_top on that orbit, -1 where none within n collisions."""
    phi, v = _starts(40, 4)
    v_top, n = 5.0, 300
    passage, status = fd.first_passage(phi, v, EPS, v_top, n, model=model)
    assert (status == CONVERGED).all()
    for i in range(len(phi)):
        reached = np.flatnonzero(fastpath.orbit(phi[i], v[i], EPS, n, model=model).v[1:] >= v_top)
        assert passage[i] == (reached[0] + 1 if len(reached) else -1)
    assert (passage > 0).any() and (passage == -1).any()


def test_the_holmes_first_passage_folds_where_the_velocity_would_turn_negative():
    rng = np.random.default_rng(6)
    phi, v = rng.uniform(0.0, 2.0 * np.pi, 200), rng.uniform(0.05, 1.0, 200)
    leaves = v + EPS * np.sin(phi) > 0.0
    passage, status = fd.first_passage(phi[leaves], v[leaves], EPS, 3.0, 400, model="holmes")
    assert (status == CONVERGED).all()
    assert (passage > 0).any()
