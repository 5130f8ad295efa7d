"""Velocity scenes' results: <v_n> against the collision index n, one curve per restitution.

A chunk (``reports.runs.chunk.simulate_velocity_chunk``) runs
``fastpath.kernels.moments.moments_chunk`` on its starts with its curve's physics
(``Scene.curve_physics``); flagged collisions are settled by ``verify.step`` and the particle
resumes in the kernel; the sampled collisions are those of escape runs (the same picks, rows and
carried state), so ``bouncer verify`` re-derives them the same way. This module turns the
merged counts into velocity.csv and checks their invariants.

Every particle ends at the horizon N = ``horizon.collisions`` or stuck on the plate for good
(r < 1, |eps| <= 1). At each grid point n_grid[j] (``Plan.n_grid``):

    moving[j] + stuck_at[j] = particles         (a particle flagged is settled and goes on)

A stuck particle rides the plate with the plate's velocity; it is NOT in the means: the means
are over the particles still moving, and the stuck ones are reported in their own column, as
the report's dissipation study (``fastpath.kernels.moments``, ``Moments.stuck_n``) does.

velocity.csv, one row per curve and grid point:

    curve, n, moving, stuck, mean_v, mean_v2, se_v

mean_v = S1/M, mean_v2 = S2/M, each the exact rational (``reports.runs.counts``: exact sums)
rounded once to float64; se_v = sqrt(s**2/M), s**2 = (M*S2 - S1**2)/(M*(M - 1)) the sample
variance, also exact before its one rounding (no cancellation), empty for M < 2; mean_v and
mean_v2 are empty where M = 0.
"""

from __future__ import annotations

import csv
import io
import math
from fractions import Fraction

from fastpath.arithmetic.rounding import UNIT_ROUNDOFF

COLUMNS = ("curve", "n", "moving", "stuck", "mean_v", "mean_v2", "se_v")
MEAN_SLACK = 8.0 * UNIT_ROUNDOFF  # file_problems: rounding of mean_v**2 against mean_v2


def _float(x):
    return repr(float(x))


def velocity_rows(plan, counts):
    """Rows of velocity.csv (module docstring) from Counts with an experiment axis."""
    rows = []
    for e, exp in enumerate(plan.experiments):
        for j, n in enumerate(plan.n_grid):
            m = int(counts.moving[e, j])
            s1, s2 = Fraction(counts.sum_v[e, j]), Fraction(counts.sum_v2[e, j])
            mean_v = _float(s1 / m) if m else ""
            mean_v2 = _float(s2 / m) if m else ""
            se = ""
            if m >= 2:
                var = (m * s2 - s1 * s1) / (m * (m - 1))
                se = _float(math.sqrt(float(var / m)))
            rows.append([exp.name, int(n), m, int(counts.stuck_at[e, j]), mean_v, mean_v2, se])
    return rows


def velocity_problems(plan, counts, done):
    """Invariants of a velocity tally, per curve e with ``done[e]`` particles finished: at every
    grid point moving + stuck = done, stuck never decreases along n, an empty point has zero
    sums, sum_v2 >= 0 and sum_v**2 <= moving*sum_v2 (Cauchy-Schwarz, exact)."""
    out = []
    for e, exp in enumerate(plan.experiments):
        for j, n in enumerate(plan.n_grid):
            m, st = int(counts.moving[e, j]), int(counts.stuck_at[e, j])
            s1, s2 = Fraction(counts.sum_v[e, j]), Fraction(counts.sum_v2[e, j])
            where = f"curve {exp.name!r}, n = {int(n)}"
            if m + st != done[e]:
                out.append(f"{where}: {m} moving + {st} stuck = {m + st}, but {done[e]}"
                           " particles were run")
            if j and st < int(counts.stuck_at[e, j - 1]):
                out.append(f"{where}: stuck falls from {int(counts.stuck_at[e, j - 1])} to {st}")
            if m == 0 and (s1 != 0 or s2 != 0):
                out.append(f"{where}: no particle moving but non-zero velocity sums")
            if s2 < 0 or s1 * s1 > m * s2:
                out.append(f"{where}: sums violate sum_v**2 <= moving*sum_v2 (v sum {s1},"
                           f" v**2 sum {s2}, {m} moving)")
    return out


def file_problems(plan, text, name="velocity.csv"):
    """What velocity.csv alone allows to check: its header and rows (curves and grid of the
    plan), moving + stuck = particles, mean_v**2 <= mean_v2 (to rounding) and se_v >= 0."""
    reader = csv.reader(io.StringIO(text))
    header = next(reader, None)
    if header != list(COLUMNS):
        return [f"{name}:1: header {header} is not the velocity.csv header"]
    out = []
    names = [x.name for x in plan.experiments]
    grid = [int(n) for n in plan.n_grid]
    for line, row in enumerate(reader, start=2):
        try:
            curve, n, m, st = row[0], int(row[1]), int(row[2]), int(row[3])
            mean_v, mean_v2, se = (float(x) if x else None for x in row[4:7])
            if curve not in names or n not in grid:
                raise ValueError
        except (ValueError, IndexError):
            out.append(f"{name}:{line}: not a row of this run: {','.join(row)}")
            continue
        if m < 0 or st < 0 or m + st != plan.particles:
            out.append(f"{name}:{line}: {curve} n = {n}: {m} moving + {st} stuck is not"
                       f" {plan.particles} particles")
        if (m > 0) != (mean_v is not None and mean_v2 is not None) or (m >= 2) != (se is not None):
            out.append(f"{name}:{line}: {curve} n = {n}: means given for {m} moving particles")
            continue
        # exactly (S1/M)**2 <= S2/M; three roundings of the square and one of S2/M leave
        # mean_v**2 <= mean_v2*(1 + 4u + O(u**2)): MEAN_SLACK = 8u covers it with room
        if m > 0 and not mean_v * mean_v <= mean_v2 * (1.0 + MEAN_SLACK):
            out.append(f"{name}:{line}: {curve} n = {n}: mean_v**2 > mean_v2")
        if se is not None and not se >= 0.0:
            out.append(f"{name}:{line}: {curve} n = {n}: se_v {se!r} < 0")
    return out


def velocity_text(plan, counts):
    """velocity.csv text."""
    buf = io.StringIO()
    writer = csv.writer(buf, lineterminator="\n")
    writer.writerow(COLUMNS)
    writer.writerows(velocity_rows(plan, counts))
    return buf.getvalue()
