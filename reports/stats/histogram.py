"""Binned, censored escape counts of one curve, read from a run directory or a CSV histogram.

The survival clock. Every curve is stored as bins k = 0..K-1 with boundaries x_0 < ... < x_K
(x_K may be inf) such that an escape counted in bin k has clock value X with x_k < X <= x_{k+1},
so that P(bin k) = S(x_k) - S(x_{k+1}) with S(x) = P(X > x):

* collisions (integer escape index N >= 1, a run bin holds e_k <= N < e_{k+1}):
  x_k = e_k - 1, since #{N >= e_k} = #{N > e_k - 1};
* time (continuous T, a bin holds e_k <= T < e_{k+1}): x_k = e_k (P(T = e_k) = 0).

Horizon censoring. A particle censored at the horizon in bin k is known only to outlive the
lower edge: X > e_k >= x_k. Fits therefore stop at or before x_k of the first bin holding a
censoring bound, where every censored particle contributes exactly S(x_end)/S(x_start).

Competing outcomes (transport: hole 1 -> hole 1 and hole 1 -> hole 2). A curve is one outcome;
the other outcomes' escapes are treated as independent censoring at the mean clock value of
their bin, m_k = (e_k + e_{k+1} - 1)/2 (collisions; exact for one-value bins, where it is
e_k: the latent escape time through this outcome exceeds N = e_k) or (e_k + e_{k+1})/2 (time),
the actuarial convention: with hazard h and bin width w the rate estimate is then biased by
O((h w)^2) instead of O(h w) for censoring at either edge.

Run directories (``bouncer run``): ``manifest.json`` (per experiment ``particles_done``,
``censored``, ``escaped``; ``bins``) and ``counts.csv`` with header
``experiment,clock,outcome,lower_edge,count``. The bin grid is rebuilt from ``bins`` exactly as
the runner built it (``fastpath.kernels.histogram.log_edges``): collisions
unique(round(10**(k/per_decade))), time [0] + first*10**(k/per_decade); the last bin is open.

CSV histograms: header ``lower,upper,count``, rows counting lower <= X < upper, increasing and
not overlapping (gaps are empty bins), edges in [0, 2**53] and counts adding up to at most 2**53
(``MAX_CLOCK``, ``MAX_COUNT``); a last row with upper = inf counts particles censored at
``lower``.
"""

from __future__ import annotations

import csv
import io
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from fastpath.kernels.histogram import log_edges
from reports.runs.echo import clip
from reports.runs.manifest import load_manifest
from reports.runs.rundir import read_input_text
from reports.runs.scenes import CLOCKS

# Counts and clock values up to 2**53: float64, in which the fits work, holds every integer up
# to it exactly (a count or total beyond it, or a bin edge beyond it, where neighbouring
# integers merge, would be silently rounded).
MAX_COUNT = 2**53
MAX_CLOCK = float(2**53)


@dataclass(frozen=True)
class Curve:
    """One outcome's binned escapes with everything that censors it (survival clock x)."""

    source: str
    experiment: str
    curve: str
    clock: str
    x: np.ndarray          # bin boundaries x_0 < ... < x_K (x_K may be inf)
    escapes: np.ndarray    # escapes through this outcome per bin (K,)
    competing: np.ndarray  # other outcomes' escapes per bin, censored at ``mid``
    censored: np.ndarray   # horizon censoring bounds per bin
    mid: np.ndarray        # censoring point of the competing escapes per bin
    particles: int

    @property
    def horizon(self):
        """x of the first bin with a horizon censoring bound (inf if none): fits end there."""
        hit = np.flatnonzero(self.censored)
        return float(self.x[hit[0]]) if len(hit) else math.inf


def survival_boundaries(edges, clock):
    """Survival-clock boundaries (x_0..x_K, x_K = inf) of bins with lower edges ``edges``."""
    edges = np.asarray(edges, dtype=np.float64)
    x = edges - 1.0 if clock == "collisions" else edges.copy()
    return np.append(x, math.inf)


def bin_means(edges, clock):
    """Mean clock value of each bin under a flat density (inf for the open last bin)."""
    edges = np.append(np.asarray(edges, dtype=np.float64), math.inf)
    upper = edges[1:] - 1.0 if clock == "collisions" else edges[1:]
    return np.where(np.isfinite(upper), 0.5 * (edges[:-1] + upper), math.inf)


def run_edges(bins, clock):
    """Lower bin edges of a run's clock, rebuilt from the manifest's ``bins`` entry."""
    spec = bins[clock]
    edges = log_edges(float(spec["first"]), int(spec["decades"]), int(spec["per_decade"]),
                      integer=bool(spec.get("integer")))
    if "below_first" in spec:
        edges = np.concatenate([[float(spec["below_first"][0])], edges])
    return edges.astype(np.float64)


def _int_count(text, where):
    try:
        value = float(text)
    except ValueError:
        raise ValueError(f"{where}: count {clip(repr(text))} is not a number") from None
    if not math.isfinite(value) and text.strip().lstrip("+").isdigit():
        value = math.inf  # an integer beyond float64: above 2**53 below
    elif not math.isfinite(value) or value != int(value):
        raise ValueError(f"{where}: count {clip(repr(text))} is not an integer")
    if value < 0:
        raise ValueError(f"{where}: negative count {clip(text)}")
    if value > MAX_COUNT:
        raise ValueError(f"{where}: count {clip(text)} is above 2**53 = {MAX_COUNT}, the"
                         " largest count float64 holds exactly")
    return int(value)


def read_run(path, clocks=CLOCKS):
    """Curves (experiment order of the manifest, then clock, then outcome) of a run directory."""
    path = Path(path)
    if not (path / "manifest.json").exists():
        raise ValueError(f"{path}: no manifest.json (not a run directory)")
    manifest = load_manifest(path / "manifest.json")  # its schema: one line if malformed
    counts_file = path / "counts.csv"
    if not counts_file.exists():
        kind = manifest["scene"]["kind"]
        if kind in ("phase-space", "velocity"):  # these kinds record no survival counts
            raise ValueError(f"{path}: a {kind} run has no survival counts to fit (no counts.csv;"
                             f" `bouncer plot {path}` draws what it recorded)")
        raise ValueError(f"{path}: no counts.csv")
    experiments = manifest["curves"]
    rows = {}
    text = read_input_text(counts_file)
    with io.StringIO(text, newline="") as f:
        reader = csv.reader(f)
        header = next(reader, None)
        if header != ["experiment", "clock", "outcome", "lower_edge", "count"]:
            raise ValueError(f"{counts_file}: header must be experiment,clock,outcome,"
                             f"lower_edge,count, got {clip(header)}")
        for line, row in enumerate(reader, start=2):
            where = f"{counts_file}:{line}"
            if len(row) != 5:
                raise ValueError(f"{where}: expected 5 fields, got {len(row)}")
            exp, clock, outcome, edge, count = row
            try:
                edge = float(edge)
            except ValueError:
                raise ValueError(f"{where}: lower_edge {clip(repr(edge))} is not a number") \
                    from None
            key = (exp, clock, outcome)
            rows.setdefault(key, []).append((edge, _int_count(count, where)))
    curves = []
    for exp, info in experiments.items():
        particles = int(info["particles_done"])
        outcomes = list(info.get("escaped", {}))
        for clock in clocks:
            if clock not in manifest["bins"]:
                continue
            edges = run_edges(manifest["bins"], clock)
            table = {}
            for outcome in [*outcomes, "censored"]:
                counts = np.zeros(len(edges), dtype=np.int64)
                for edge, count in rows.get((exp, clock, outcome), []):
                    k = np.searchsorted(edges, edge)
                    if k == len(edges) or edges[k] != edge:
                        raise ValueError(f"{counts_file}: {exp}/{clock}/{outcome}: lower_edge "
                                         f"{edge!r} is not on the manifest's bin grid")
                    counts[k] += count
                table[outcome] = counts
            total = sum(int(c.sum()) for c in table.values())
            if total != particles:
                raise ValueError(f"{path}: {exp}/{clock}: escapes + censored = {total} but "
                                 f"particles_done = {particles}")
            for outcome in outcomes:
                others = sum(table[o] for o in outcomes if o != outcome)
                curves.append(Curve(
                    source=str(path), experiment=exp, curve=outcome, clock=clock,
                    x=survival_boundaries(edges, clock), escapes=table[outcome],
                    competing=np.asarray(others if len(outcomes) > 1 else 0 * table[outcome]),
                    censored=table["censored"], mid=bin_means(edges, clock),
                    particles=particles))
    return curves


def read_csv_histogram(path, clock="time"):
    """The one curve of a ``lower,upper,count`` CSV histogram (module docstring)."""
    path = Path(path)
    try:  # a regular file of bounded size; a byte-order mark (a spreadsheet's export) dropped
        text = read_input_text(path, bom=True)
    except FileNotFoundError:
        raise ValueError(f"{path}: no such file") from None
    reader = csv.reader(text.splitlines())
    header = [h.strip() for h in next(reader, [])]
    if header != ["lower", "upper", "count"]:
        raise ValueError(f"{path}: header must be lower,upper,count, got"
                         f" {clip(repr(','.join(header)))}")
    lower, upper, counts = [], [], []
    censored = None  # count of the censored row, once read
    total = 0
    for line, row in enumerate(reader, start=2):
        where = f"{path}:{line}"
        if not row:
            continue
        if len(row) != 3:
            raise ValueError(f"{where}: expected 3 fields, got {len(row)}")
        try:
            lo, hi = float(row[0]), float(row[1])
        except ValueError:
            raise ValueError(f"{where}: bin edges {clip(repr(row[0]))}, {clip(repr(row[1]))}"
                             " are not numbers") from None
        count = _int_count(row[2], where)
        total += count
        if total > MAX_COUNT:
            raise ValueError(f"{where}: the counts add up to more than 2**53 = {MAX_COUNT},"
                             " the largest total float64 holds exactly")
        if censored is not None:
            raise ValueError(f"{where}: rows after the censored row (upper = inf)")
        if not math.isfinite(lo) or math.isnan(hi) or not lo < hi:
            raise ValueError(f"{where}: bins not increasing: lower {clip(row[0])} upper"
                             f" {clip(row[1])}")
        if lo < 0 or (math.isfinite(hi) and hi > MAX_CLOCK):
            raise ValueError(f"{where}: bin edges {clip(row[0])}, {clip(row[1])} outside"
                             " [0, 2**53]: clock values (collisions, time) are >= 0, and"
                             " float64 cannot tell neighbouring ones apart above 2**53")
        if lower and lo < upper[-1]:
            raise ValueError(f"{where}: bins not increasing: lower {clip(row[0])} < previous"
                             f" upper {upper[-1]!r}")
        if clock == "collisions" and (lo != round(lo) or (math.isfinite(hi) and hi != round(hi))):
            raise ValueError(f"{where}: collision-clock bins need integer edges, got"
                             f" {clip(row[0])}, {clip(row[1])}")
        if lower and lo > upper[-1]:  # a gap: an empty bin
            lower.append(upper[-1])
            upper.append(lo)
            counts.append(0)
        if math.isinf(hi):
            censored = count
            continue
        lower.append(lo)
        upper.append(hi)
        counts.append(count)
    if not lower:
        raise ValueError(f"{path}: no bins")
    # the open last bin starts at the censoring bound (or the last upper edge) and holds them
    edges = np.array(lower + [upper[-1]], dtype=np.float64)
    escapes = np.array(counts + [0], dtype=np.int64)
    cens = np.zeros(len(edges), dtype=np.int64)
    censored = censored or 0
    cens[-1] = censored
    if escapes.sum() == 0:
        raise ValueError(f"{path}: no escapes")
    return Curve(source=str(path), experiment="", curve=path.stem, clock=clock,
                 x=survival_boundaries(edges, clock), escapes=escapes,
                 competing=np.zeros_like(escapes), censored=cens, mid=bin_means(edges, clock),
                 particles=int(escapes.sum() + censored))
