"""Each escape's collision count n and time t together, from a sampled study or a run's joint
(n, t) record, as weighted points; and the slopes the claims read on them.

Some of the paper's statements are about n and t of the same orbits: they made n ~ t^(1/2)
collisions; the late ones have tightly bounded velocity (t/n, twice the mean velocity, does not
grow with n); the transporting ones decay with many fewer collisions. A run's survival curves
hold n and t apart. A sampled study (``reports.paper.studies.follow``) records both for each
particle: ``from_followed`` gives it weight 1. A run that records the joint histogram of (n, t) at
escape gives one point per occupied cell at its centre, weighted by its count (``from_joint``); the
grid's resolution (20 bins per decade) is far below the decades the slopes span.

Intervals come from the Poisson bootstrap: every weight redrawn as Poisson(weight), which for
weights 1 is the ordinary bootstrap of particles and for a cell's count its counting error.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from reports.paper.studies.replicates import INTERVAL_REPLICATES
from reports.paper.studies.seeds import JOINT_SEED
from reports.runs.joint import load_joint
from reports.runs.joint_file import JOINT_FILE
from reports.runs.scenes import parse_scene

PER_DECADE = 4     # slopes over quarter decades of the binning variable
MIN_PER_BIN = 20   # escapes a quarter decade needs to count


@dataclass(frozen=True)
class JointSample:
    """Weighted escapes (and censorings): exit (hole index, -1 still inside at the horizon), n,
    t, weight; ``particles`` started; ``source`` in words; ``dn``, ``dt``: the width in log n
    and log t of each point's cell (0 for a particle)."""

    exit: np.ndarray
    n: np.ndarray
    t: np.ndarray
    weight: np.ndarray
    particles: int
    source: str
    dn: np.ndarray | None = None
    dt: np.ndarray | None = None

    def widths(self):
        zero = np.zeros(len(self.n))
        return (zero if self.dn is None else self.dn), (zero if self.dt is None else self.dt)

    def _keep(self, mask, weight):
        dn, dt = self.widths()
        return JointSample(self.exit[mask], self.n[mask], self.t[mask], weight[mask],
                           self.particles, self.source, dn[mask], dt[mask])

    def select(self, mask):
        return self._keep(mask, self.weight)

    def resampled(self, rng):
        """The Poisson bootstrap of this sample (module docstring)."""
        return self.redrawn(rng.poisson(self.weight).astype(np.float64))

    def redrawn(self, weight, within=None):
        """This sample with the redrawn weights ``weight``, the points drawn 0 times left out
        (``resampled``'s sample for that draw), and only those of the mask ``within``."""
        kept = weight > 0
        return self._keep(kept if within is None else kept & within, weight)

    @property
    def count(self):
        return float(self.weight.sum())


def from_followed(fol, source="sampled study"):
    """A ``follow.Followed`` as a sample of weight 1 per particle."""
    return JointSample(np.asarray(fol.exit, dtype=np.int64), np.asarray(fol.n, dtype=np.float64),
                       np.asarray(fol.t, dtype=np.float64), np.ones(len(fol.exit)),
                       int(fol.particles), f"{source} of {fol.particles:,} starts")


def cell_centres(edges, integer):
    """(geometric centre, width in log) of each bin [e_k, e_{k+1}) (integer bins: of e_k ..
    e_{k+1} - 1, the width from e_k - 1/2 to e_{k+1} - 1/2); the open last bin at its lower
    edge, width 0."""
    edges = np.asarray(edges, dtype=np.float64)
    upper = np.append(edges[1:] - (1.0 if integer else 0.0), edges[-1])
    lo = np.where(edges > 0, edges, upper)
    hi = np.maximum(upper, lo)
    half = 0.5 if integer else 0.0
    width = np.log((hi + half) / np.maximum(lo - half, 1e-300))
    width[-1] = 0.0
    return np.sqrt(lo * hi), np.where(np.isfinite(width), width, 0.0)


def from_joint(n_edges, t_edges, counts, particles, source):
    """The joint record counts[outcome, k_n, k_t] of one experiment (outcomes: its holes, then
    censored) as weighted cell centres; the exit of the censored row is -1."""
    counts = np.asarray(counts)
    holes = counts.shape[0] - 1
    o, i, j = np.nonzero(counts)
    exit_ = np.where(o < holes, o, -1)
    (n_mid, n_width), (t_mid, t_width) = cell_centres(n_edges, True), cell_centres(t_edges, False)
    return JointSample(exit_.astype(np.int64), n_mid[i], t_mid[j],
                       counts[o, i, j].astype(np.float64), int(particles), source,
                       n_width[i], t_width[j])


def weighted_quantile(values, weights, q, widths=None):
    """The q-quantile of weighted values: the first value whose cumulative weight reaches q of
    the total; where values stand for cells of log width ``widths``, the quantile of the
    mixture that spreads each weight uniformly in log over its cell (``CellQuantile``)."""
    if widths is not None:
        return CellQuantile(values, widths).quantile(np.asarray(weights, dtype=float), q)
    order = np.argsort(values, kind="stable")
    return _sorted_quantile(np.asarray(values)[order], np.asarray(weights)[order], q)


class CellQuantile:
    """Quantiles of weighted cells: cell i spreads its weight w_i uniformly in log y over
    [log c_i - d_i/2, log c_i + d_i/2] (c_i its centre, d_i its log width; d_i = 0: a point).
    Cells may overlap; the mixture's distribution function is continuous and piecewise linear
    in log y between the cells' ends (a jump at a point), so its quantile moves continuously
    with the weights. The ends are sorted once; ``quantile`` takes any weights of the cells
    (a bootstrap redraws only the weights)."""

    def __init__(self, centres, widths):
        log_c = np.log(np.asarray(centres, dtype=float))
        self.width = np.asarray(widths, dtype=float)
        ends = np.concatenate([log_c - self.width / 2, log_c + self.width / 2])
        self.order = np.argsort(ends, kind="stable")
        self.at = ends[self.order]
        m = len(log_c)
        self.cell = np.concatenate([np.arange(m), np.arange(m)])[self.order]
        self.start = np.concatenate([np.ones(m, bool), np.zeros(m, bool)])[self.order]

    def quantile(self, weights, q):
        spread = self.width > 0
        density = np.where(spread, weights / np.where(spread, self.width, 1.0), 0.0)
        change = np.where(self.start, 1.0, -1.0) * density[self.cell]
        jump = np.where(self.start & ~spread[self.cell], weights[self.cell], 0.0)
        slope = np.cumsum(change)  # density of the mixture after each end
        area = np.concatenate([[0.0], np.cumsum(slope[:-1] * np.diff(self.at))])
        after = np.cumsum(jump) + area  # distribution function just after each end
        target = q * float(np.sum(weights))
        j = min(int(np.searchsorted(after, target)), len(after) - 1)
        if j == 0 or after[j] - jump[j] < target or slope[j - 1] <= 0:
            return float(math.exp(self.at[j]))  # reached at an end (or in a point's jump)
        return float(math.exp(self.at[j - 1] + (target - after[j - 1]) / slope[j - 1]))


def weighted_mean(values, weights):
    return float(np.dot(values, weights) / np.sum(weights))


class BinnedSlope:
    """The slope of log (q-quantile of y, or its mean if q is None) against log x over bins of
    1/per_decade decade of x in [x_lo, x_hi] holding at least ``min_per_bin`` weight (NaN with
    fewer than two bins), for any weights of the same points: the bins and the order of y in
    each are found once, so that a bootstrap only redraws the weights. ``y_width``: the log
    width of each y's cell (``weighted_quantile``)."""

    def __init__(self, x, y, x_lo, x_hi, y_width=None, per_decade=PER_DECADE,
                 min_per_bin=MIN_PER_BIN):
        x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
        use = (x >= x_lo) & (x <= x_hi) & (x > 0) & (y > 0)
        self.use = use
        self.min_per_bin = min_per_bin
        self.bins = []
        if not use.any() or not x_hi > x_lo:
            return
        k = max(1, int(math.ceil(per_decade * math.log10(x_hi / x_lo) - 1e-9)))
        edges = np.geomspace(x_lo, x_hi * (1 + 1e-12), k + 1)
        where = np.flatnonzero(use)
        idx = np.searchsorted(edges, x[where], side="right") - 1
        widths = None if y_width is None else np.asarray(y_width, dtype=float)
        for b in range(k):
            members = where[idx == b]
            order = members[np.argsort(y[members], kind="stable")]
            cells = None if widths is None else CellQuantile(y[order], widths[order])
            self.bins.append((math.log(math.sqrt(edges[b] * edges[b + 1])), order, y[order],
                              cells))

    def slope(self, w, q=0.5):
        """(slope, bins used) for the weights ``w`` of all points."""
        pts = []
        for log_x, order, ys, cells in self.bins:
            ww = w[order]
            if ww.sum() < self.min_per_bin:
                continue
            stat = (weighted_mean(ys, ww) if q is None else
                    _sorted_quantile(ys, ww, q) if cells is None else cells.quantile(ww, q))
            pts.append((log_x, math.log(stat)))
        if len(pts) < 2:
            return math.nan, len(pts)
        return float(np.polyfit([p[0] for p in pts], [p[1] for p in pts], 1)[0]), len(pts)


def _sorted_quantile(v, w, q):
    """``weighted_quantile`` of values already sorted (points)."""
    cum = np.cumsum(w)
    k = min(int(np.searchsorted(cum, q * cum[-1])), len(v) - 1)
    return float(v[k])


def binned_slope(x, y, w, x_lo, x_hi, q=0.5, per_decade=PER_DECADE, min_per_bin=MIN_PER_BIN,
                 y_width=None):
    """(slope, bins used) of ``BinnedSlope`` for the weights ``w``."""
    return BinnedSlope(x, y, x_lo, x_hi, y_width, per_decade, min_per_bin).slope(
        np.asarray(w, dtype=float), q)


def bootstrap_weights(weight, statistic, reps=INTERVAL_REPLICATES, seed=JOINT_SEED):
    """95% percentile interval of ``statistic(weights)`` over Poisson-redrawn weights (NaN
    when fewer than half of them give a number)."""
    rng = np.random.default_rng(seed)
    values = np.array([statistic(rng.poisson(weight).astype(float)) for _ in range(reps)])
    values = values[np.isfinite(values)]
    if len(values) <= reps // 2:
        return math.nan, math.nan
    return float(np.percentile(values, 2.5)), float(np.percentile(values, 97.5))


def bootstrap_interval(sample, statistic, reps=INTERVAL_REPLICATES, seed=JOINT_SEED):
    """95% percentile interval of ``statistic(sample)`` over Poisson-bootstrap resamples (NaN
    when fewer than half of them give a number)."""
    rng = np.random.default_rng(seed)
    values = [statistic(sample.resampled(rng)) for _ in range(reps)]
    values = np.array([v for v in values if math.isfinite(v)])
    if len(values) <= reps // 2:
        return math.nan, math.nan
    return float(np.percentile(values, 2.5)), float(np.percentile(values, 97.5))


def run_joint(run_dir, width=None):
    """The joint (n, t) records of a run as JointSamples, {} when the run has none (no
    joint.csv): of an escape run {hole: JointSample} (experiments "phi_c=<hole>"); of a
    transport run and a ``width``, {entry hole: JointSample} (experiments "h=<width>/from hole
    <entry>", or "from hole <entry>" in a scene of one width). The record is read and checked
    by ``reports.runs.joint.load_joint`` (a ValueError of one line if it is corrupt); per set of
    starts its curves in the scene's order, then its
    censored and stuck particles together (exit -1: they did not escape by the horizon)."""
    if not (Path(run_dir) / JOINT_FILE).is_file():
        return {}
    record = load_joint(run_dir)
    scene = parse_scene((Path(run_dir) / "scene.toml").read_text(encoding="utf-8"))
    only = f"{scene.hole_widths[0]:g}" if len(scene.hole_widths) == 1 else None
    curves = {}
    for curve, name in record.experiment.items():
        curves.setdefault(name, []).append(record.escapes[curve])
    out = {}
    for name, escapes in curves.items():
        counts = np.stack([*escapes, record.censored[name] + record.stuck[name]])
        sample = from_joint(record.n_edges, record.t_edges, counts, record.particles,
                            f"joint (n, t) record of run {Path(run_dir).name}")
        if width is None:
            out[name.split("=", 1)[1] if "=" in name else name] = sample
        elif (name.split("/")[0].split("=", 1)[-1] if "/" in name else only) == width:
            out[int(name.rsplit(" ", 1)[1])] = sample
    return out
