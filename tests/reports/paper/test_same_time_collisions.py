"""fig4-fewer-collisions at the same time, read on a joint (n, t) record's cells."""

import numpy as np

from reports.paper.claims.transport_joint_claims import same_time_members
from reports.paper.studies.joint_sample import from_joint


def _record(n_scale, rng, m=20_000):
    """A joint record of one entry hole: exits 0 and 1 with n ~ n_scale * t^(1/2) (noisy)."""
    n_edges = np.unique(np.round(np.geomspace(1, 1e4, 81)))
    t_edges = np.concatenate([[0.0], np.geomspace(0.1, 1e5, 121)])
    counts = np.zeros((3, len(n_edges), len(t_edges)), np.int64)
    for exit_, scale in enumerate(n_scale):
        t = 10 ** rng.uniform(1, 3, m)
        n = np.maximum(1, np.round(scale * np.sqrt(t) * rng.lognormal(0, 0.3, m)))
        np.add.at(counts, (exit_, np.searchsorted(n_edges, n, "right") - 1,
                           np.searchsorted(t_edges, t, "right") - 1), 1)
    return from_joint(n_edges, t_edges, counts, 2 * m, "synthetic joint record")


def test_the_median_ratio_has_an_interval_from_both_curves_inside_the_cells():
    """Medians of n read on cells of a joint record are interpolated inside their cells, and the
    interval redraws both curves: it is not a point, and it holds the true ratio 1/2."""
    rng = np.random.default_rng(5)
    joint = {1: _record((2.0, 1.0), rng), 2: _record((1.0, 1.0), rng)}
    members = same_time_members("P12", joint)
    assert len(members) == 2
    for m in members:
        assert m.lo < m.hi
        assert m.lo <= 0.5 <= m.hi, (m.lo, m.hi)
