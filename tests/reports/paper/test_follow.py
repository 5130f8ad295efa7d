"""Particles followed collision by collision (``reports.paper.studies.follow``) against single
orbits."""

import math

import numpy as np
import pytest

import fastpath
from reports.paper.studies.follow import follow, in_holes
from reports.paper.studies.islands import classify


def test_a_followed_particle_escapes_at_its_orbits_first_collision_in_the_hole():
    eps, lo, width = 0.6, 1.85, 0.3
    starts = [(4.0, 3.0), (3.9, 2.5), (4.1, 3.7)]
    fol = follow([p for p, _ in starts], [v for _, v in starts], eps, [lo], [width], 20_000)
    for i, (phi0, v0) in enumerate(starts):
        orb = fastpath.orbit(phi0, v0, eps, int(fol.n[i]))
        inside = np.flatnonzero(in_holes(orb.phi[1:], [lo], [width]) == 0)
        assert fol.exit[i] == 0 and inside[0] + 1 == fol.n[i]
        # the same map; the orbit kernel carries its phase between collisions, the array step
        # starts each collision from the rounded state: agreement to rounding over n steps
        assert fol.t[i] == pytest.approx(orb.t[int(fol.n[i])], rel=1e-12)
        assert fol.v_exit[i] == pytest.approx(orb.v[int(fol.n[i])], rel=1e-12)
        assert fol.v_max[i] == pytest.approx(max(v0, orb.v[1:].max()), rel=1e-12)
    assert fol.verification["overstepped"] == 0


def test_the_horizon_censors_and_snapshots_watch_the_survivors():
    fol = follow([4.0, 0.0], [3.0, math.pi], 0.6, [math.pi - 0.15], [0.3], 50,
                 snapshot_at=(10,), snapshot_length=5)
    island = 1  # the fixed point (0, pi) never reaches the hole at pi
    assert fol.exit[island] == -1 and fol.n[island] == 50
    ids, phi, v, t = fol.snapshots[10]
    assert island in ids and phi.shape == (len(ids), 5)
    row = int(np.flatnonzero(ids == island)[0])
    orb = fastpath.orbit(0.0, math.pi, 0.6, 15)
    assert np.allclose(v[row], orb.v[11:16], rtol=1e-12)
    assert np.allclose(t[row], orb.t[11:16], rtol=1e-12)


def test_hole_membership_wraps_through_two_pi():
    lo = 2 * math.pi - 0.1
    got = in_holes(np.array([0.05, 0.15, 2 * math.pi - 0.05, 3.0]), [lo], [0.2])
    assert got.tolist() == [0, -1, 0, -1]


@pytest.mark.slow
def test_the_fixed_point_is_on_the_large_island_and_a_sea_start_is_chaotic():
    """(0, pi): the large island; (3.14, 1.95): the small island below the hole at pi, regular
    but not locked to the period-1 resonance; (4, 3): the chaotic sea."""
    cls = classify(np.array([0.0, 3.14, 4.0]), np.array([math.pi, 1.95, 3.0]), 0.6)
    assert cls.regular.tolist() == [True, True, False]
    assert cls.large.tolist() == [True, False, False]
