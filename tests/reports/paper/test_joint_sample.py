"""Joint (n, t) data as weighted points: a study's particles, a joint histogram's cells."""

import math

import numpy as np

from reports.paper.studies.joint_sample import (
    binned_slope,
    bootstrap_interval,
    from_joint,
    run_joint,
    weighted_quantile,
)


def test_weighted_quantiles_count_each_point_by_its_weight():
    assert weighted_quantile(np.array([1.0, 2.0, 3.0]), np.array([1.0, 1.0, 10.0]), 0.5) == 3.0
    assert weighted_quantile(np.array([1.0, 2.0, 3.0]), np.ones(3), 0.5) == 2.0


def test_a_binned_slope_finds_a_power_law():
    rng = np.random.default_rng(0)
    t = 10 ** rng.uniform(2, 4, 20000)
    n = t ** 0.5 * rng.lognormal(0, 0.2, len(t))
    slope, bins = binned_slope(t, n, np.ones(len(t)), 100.0, 1e4)
    assert abs(slope - 0.5) < 0.02 and bins == 8


def test_a_joint_histogram_gives_the_same_slope_as_its_particles():
    """The median of a cell-binned variable is interpolated inside its cell: its bootstrap
    interval does not collapse onto the cell's centre."""
    rng = np.random.default_rng(1)
    t = 10 ** rng.uniform(2, 4, 50000)
    n = np.maximum(1, np.round(t ** 0.5 * rng.lognormal(0, 0.2, len(t))))
    n_edges = np.unique(np.round(np.geomspace(1, 1e3, 61)))
    t_edges = np.concatenate([[0.0], np.geomspace(0.1, 1e5, 121)])
    counts = np.zeros((2, len(n_edges), len(t_edges)), np.int64)
    np.add.at(counts, (0, np.searchsorted(n_edges, n, "right") - 1,
                       np.searchsorted(t_edges, t, "right") - 1), 1)
    s = from_joint(n_edges, t_edges, counts, len(t), "synthetic joint record")
    assert s.count == len(t) and np.all(s.exit == 0)
    particles = binned_slope(t, n, np.ones(len(t)), 100.0, 1e4)[0]

    def slope(x):
        return binned_slope(x.t, x.n, x.weight, 100.0, 1e4, y_width=x.dn)[0]
    assert abs(slope(s) - particles) < 0.02
    lo, hi = bootstrap_interval(s, slope, reps=40)
    assert lo < slope(s) < hi and math.isfinite(lo)


def test_a_runs_joint_record_gives_each_entry_holes_escapes_and_bounds(tmp_path):
    """run_joint reads a run's joint.csv (through ``reports.runs.joint.load_joint``): per entry
    hole every start once, the escapes by exit hole as counts.csv has them, the particles
    still inside at the horizon with exit -1; a run without the record gives {}."""
    from reports.runs import driver
    from reports.runs.scenes import parse_scene
    from reports.stats.histogram import read_run
    from tests.reports.runs.scene_texts import TINY

    scene = TINY.replace('name = "tiny"', 'name = "tiny-joint"') + "[record]\njoint = true\n"
    out = tmp_path / "run"
    driver.run(parse_scene(scene), out, progress=False)
    samples = run_joint(out, width="1")
    assert sorted(samples) == [1, 2]
    curves = {(c.experiment, c.curve): c for c in read_run(out, clocks=("collisions",))}
    for entry, s in samples.items():
        assert s.count == s.particles == 200
        for exit_ in (0, 1):
            c = curves[(f"from hole {entry}", f"P{entry}{exit_ + 1}")]
            assert s.weight[s.exit == exit_].sum() == c.escapes.sum()
        assert s.weight[s.exit == -1].sum() == c.censored.sum()
    assert run_joint(out, width="0.5") == {}
    (out / "joint.csv").unlink()
    assert run_joint(out) == {}


def test_a_run_without_the_joint_record_falls_back_on_the_study_and_says_so(tmp_path):
    from types import SimpleNamespace

    from reports.paper.sections.paper_figures_section import joint_samples

    fol = SimpleNamespace(exit=np.array([0, -1]), n=np.array([3, 9]), t=np.array([10.0, 50.0]),
                          particles=2)
    (sample,) = joint_samples(tmp_path / "run-without-joint", {"0": fol}).values()
    assert sample.count == 2
    assert sample.source == ("run run-without-joint records no joint (n, t) histogram: sampled "
                             "study of 2 starts")


def test_cell_quantiles_are_those_of_the_cells_spread_uniformly_in_log():
    """Overlapping cells and a point: each quantile is the mixture's (sampled here), and the
    quantile moves continuously as a weight changes (no jump from cell to cell)."""
    from reports.paper.studies.joint_sample import CellQuantile

    rng = np.random.default_rng(0)
    centres, widths = np.array([1.0, 3.0, 10.0, 2.0]), np.array([0.5, 1.0, 0.3, 0.0])
    weights = np.array([1.0, 2.0, 3.0, 0.5])
    cells = CellQuantile(centres, widths)
    m = 2_000_000
    i = rng.choice(4, size=m, p=weights / weights.sum())
    x = np.log(centres[i]) + widths[i] * (rng.random(m) - 0.5)
    for q in (0.1, 0.25, 0.5, 0.75, 0.9):
        assert abs(math.log(cells.quantile(weights, q)) - np.quantile(x, q)) < 2e-3, q
    steps = [cells.quantile(weights * np.array([1.0, 1.0 + e, 1.0, 1.0]), 0.5)
             for e in np.linspace(0, 0.2, 41)]
    assert np.max(np.abs(np.diff(np.log(steps)))) < 0.01
