"""Calibration on synthetic histograms of known law: hit rate and interval coverage.

A synthetic curve: N particles with survival S on the collision clock's grid (integer log bins,
20 per decade, survival-clock boundaries x = e - 1, see ``histogram``), S(x) = 1 for x <= 1 and

    exponential             S = exp(-gamma (x - 1))        gamma = 0.02
    power law               S = x**-alpha                  alpha = 1.5
    stretched exponential   S = exp(-c (x**beta - 1))      c = 0.5, beta = 0.5

(the same law conditioned on x >= 1, so the truth is known in any window starting at x >= 1),
censored at the horizon n = 1e5 (only N > 1e5 - 1 known, as a run's bin of edge 1e5 says).
The counts are one multinomial draw over the bins and the censored cell, which costs the same
at any N. Each replicate runs the whole inference (``analysis.analyse``). A hit is ``best``
equal to the true law; a parameter of the true law is covered if its 95% interval (in the
late-time window the inference chose) contains the truth.

Run ``python -m reports.stats.calibration [--replicates R] [--sizes N ...] [--seed S]`` for the
table (law, N, hit rate, coverage per parameter, inconclusive rate).
"""

from __future__ import annotations

import argparse
import math
import sys

import numpy as np

from fastpath.kernels.histogram import log_edges
from reports.stats.analysis import analyse
from reports.stats.histogram import Curve, bin_means, survival_boundaries
from reports.stats.likelihood import LAWS, PARAMS

TRUTH = {
    "exponential": {"gamma": 0.02},
    "power_law": {"alpha": 1.5},
    "stretched_exponential": {"c": 0.5, "beta": 0.5},
}
HORIZON = 1e5
SIZES = (300, 10_000, 1_000_000, 100_000_000)


def grid_edges(decades=6, per_decade=20):
    """Integer log lower edges 1..10**decades: the runs' collision bins."""
    return log_edges(1.0, decades, per_decade, integer=True)


def survival(law, params, x):
    """S(x) of the module docstring (S = 1 for x <= 1)."""
    x = np.maximum(np.asarray(x, dtype=np.float64), 1.0)
    if law == "exponential":
        return np.exp(-params["gamma"] * (x - 1.0))
    if law == "power_law":
        return x ** -params["alpha"]
    if law == "stretched_exponential":
        return np.exp(-params["c"] * (x ** params["beta"] - 1.0))
    raise ValueError(f"law must be one of {', '.join(LAWS)}, got {law!r}")


def draw(law, n, rng, params=None, edges=None, horizon=HORIZON):
    """A synthetic ``Curve`` of n particles (module docstring)."""
    params = TRUTH[law] if params is None else params
    edges = grid_edges() if edges is None else edges
    x = survival_boundaries(edges, "collisions")
    h = int(np.searchsorted(edges, horizon))  # bins from h on lie beyond the horizon
    if h == len(edges) or edges[h] != horizon:
        raise ValueError(f"horizon {horizon:g} is not a bin edge")
    s = survival(law, params, x[: h + 1])
    probs = np.append(-np.diff(s), s[-1])  # bins below the horizon, then the censored cell
    counts = rng.multinomial(n, probs / probs.sum())
    escapes = np.zeros(len(edges), dtype=np.int64)
    censored = np.zeros(len(edges), dtype=np.int64)
    escapes[:h] = counts[:-1]
    censored[h] = counts[-1]
    return Curve(source="synthetic", experiment="", curve=f"{law} N={n}", clock="collisions",
                 x=x, escapes=escapes, competing=np.zeros_like(escapes), censored=censored,
                 mid=bin_means(edges, "collisions"), particles=int(n))


def covers(ci, value):
    lo, hi = ci
    lo = -math.inf if lo is None else lo
    hi = math.inf if hi is None else hi
    return lo <= value <= hi


def replicate(law, n, rng):
    """(best, {param: covered}) of one synthetic curve."""
    result = analyse(draw(law, n, rng))
    model = result["models"][law]
    return result["best"], {p: covers(model[f"{p}_ci95"], TRUTH[law][p]) for p in PARAMS[law]}


def calibrate(law, n, replicates, seed):
    """Row of the table: hit rate, coverage per parameter, inconclusive rate."""
    rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(LAWS.index(law), n)))
    hits = inconclusive = 0
    cover = {p: 0 for p in PARAMS[law]}
    for _ in range(replicates):
        best, cov = replicate(law, n, rng)
        hits += best == law
        inconclusive += best == "inconclusive"
        for p, ok in cov.items():
            cover[p] += ok
    return {"law": law, "N": n, "replicates": replicates, "hit_rate": hits / replicates,
            "coverage": {p: k / replicates for p, k in cover.items()},
            "inconclusive_rate": inconclusive / replicates}


def main(argv=None):
    p = argparse.ArgumentParser(description="hit rate and coverage on synthetic histograms")
    p.add_argument("--replicates", type=int, default=200)
    p.add_argument("--sizes", type=int, nargs="+", default=list(SIZES))
    p.add_argument("--laws", nargs="+", default=list(LAWS), choices=LAWS)
    p.add_argument("--seed", type=int, default=2009)
    args = p.parse_args(argv)
    print(f"{'law':22s} {'N':>10s} {'hit rate':>9s} {'coverage':28s} {'inconclusive':>12s}")
    for law in args.laws:
        for n in args.sizes:
            row = calibrate(law, n, args.replicates, args.seed)
            cov = " ".join(f"{k}={v:.3f}" for k, v in row["coverage"].items())
            print(f"{law:22s} {n:>10d} {row['hit_rate']:9.3f} {cov:28s} "
                  f"{row['inconclusive_rate']:12.3f}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
