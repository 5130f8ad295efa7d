"""Invariants of a run's counts and curves, checked on resume (the checkpoint) and by
``bouncer verify`` (the output files). Each check returns a list of problems (strings, empty if
all hold); file checks name the file and line.

* per curve (experiment e) and recorded clock, every particle ends exactly once:
      sum_j escapes_j + censored + stuck = particles of e in finished chunks
  (``stuck``, particles that come to rest on the plate, is 0 for the elastic model);
* counts are non-negative integers, the finished chunks lie in the plan, and every sample row
  belongs to a finished chunk that carries picks, at most ``samples_per_chunk`` of them;
* survival.csv: 0 <= p_lo <= p <= p_hi <= 1 and p non-increasing along each (curve, clock);
* velocity scenes: at every grid point moving + stuck = particles, and the exact sums are
  consistent (``reports.runs.velocity.velocity_problems``);
* scenes with a joint record: it has the plan's shape, every particle is in one bin, and its
  marginals are the histograms of the clocks (``record_problems``, ``reports.runs.joint_file``).
"""

from __future__ import annotations

import csv
import io
from collections import Counter
from fractions import Fraction

import numpy as np

from reports.runs.counts import Counts, Tally
from reports.runs.joint_file import joint_problems, marginal_problems
from reports.runs.velocity import velocity_problems

ARRAYS = ("esc_n", "esc_t", "cens_n", "cens_t", "portrait", "stuck_n", "stuck_t")


def _clock_arrays(tally, e, clock):
    if clock == "collisions":
        return tally.esc_n[e], tally.cens_n[e]
    return tally.esc_t[e], tally.cens_t[e]


def _stuck_array(tally, e, clock):
    return tally.stuck_n[e] if clock == "collisions" else tally.stuck_t[e]


def curve_problems(plan, counts, done, stuck=None):
    """Per experiment e and recorded clock: escapes + censored + stuck == done[e], ``stuck``
    from the dict {(e, clock): count} if given, else from ``counts.stuck_n``/``stuck_t``.
    Returns [(e, clock, message)]."""
    out = []
    if plan.scene.kind == "phase-space":
        return out
    for e, exp in enumerate(plan.experiments):
        for clock in plan.scene.clocks:
            esc, cens = _clock_arrays(counts, e, clock)
            n_esc, n_cens = int(esc.sum()), int(cens.sum())
            n_stuck = (int(_stuck_array(counts, e, clock).sum()) if stuck is None
                       else int(stuck.get((e, clock), 0)))
            total = n_esc + n_cens + n_stuck
            if total != done[e]:
                out.append((e, clock, f"curve {exp.name!r}, clock {clock}: {n_esc} escaped +"
                            f" {n_cens} censored + {n_stuck} stuck = {total}, but {done[e]}"
                            " particles were run"))
    return out


def tally_problems(plan, tally):
    """Problems of a checkpoint's tally against its plan (module docstring)."""
    ref = Tally.empty(plan)
    problems = [f"{name} has shape {getattr(tally, name).shape}, the plan needs"
                f" {getattr(ref, name).shape}" for name in ARRAYS
                if getattr(tally, name).shape != getattr(ref, name).shape]
    problems += [f"{name} has negative counts" for name in ARRAYS
                 if np.any(np.asarray(getattr(tally, name)) < 0)]
    if tally.collisions < 0 or tally.settled < 0:
        problems.append(f"negative totals: collisions {tally.collisions}, settled {tally.settled}")
    fin, n_exp, per = tally.finished, len(plan.experiments), plan.chunks_per_experiment
    if len(fin.prefix) != n_exp or not all(0 <= p <= per for p in fin.prefix):
        problems.append(f"finished-chunk prefixes {fin.prefix} do not fit {n_exp} curves x"
                        f" {per} chunks")
    elif not all(0 <= e < n_exp and fin.prefix[e] < k < per for e, k in fin.extra):
        problems.append(f"finished chunks outside the plan: {sorted(fin.extra)[:3]}")
    if plan.scene.kind == "velocity":
        problems += velocity_shape_problems(plan, tally)
    if problems:
        return problems
    done = [fin.particles_done(plan, e) for e in range(n_exp)]
    problems += [msg for _, _, msg in curve_problems(plan, tally, done)]
    if plan.scene.kind == "velocity":
        problems += velocity_problems(plan, tally, done)
    problems += record_problems(plan, tally, done)
    if plan.scene.kind == "phase-space" and int(tally.portrait.sum()) > tally.collisions:
        problems.append(f"{int(tally.portrait.sum())} portrait visits but only"
                        f" {tally.collisions} collisions")
    per_chunk = Counter((int(r[0]), int(r[1])) for r in tally.samples)
    for (e, k), count in sorted(per_chunk.items()):
        if not (0 <= e < n_exp and (e, k) in fin and plan.sampled(e, k)):
            problems.append(f"sample rows of chunk ({e}, {k}), which is not a finished sampled"
                            " chunk")
            break
        if count > plan.samples_per_chunk:
            problems.append(f"{count} sample rows in chunk ({e}, {k}), at most"
                            f" {plan.samples_per_chunk} are drawn")
            break
    return problems


def record_problems(plan, tally, done):
    """The joint record of a checkpoint's tally: present exactly when the scene asks for it,
    and consistent (``reports.runs.joint_file``: shape, one bin per particle, marginals)."""
    if tally.joint is None:
        return ["no joint record, but the scene asks for one"] if plan.scene.joint else []
    if not plan.scene.joint:
        return ["a joint record, but the scene asks for none"]
    problems = joint_problems(plan, tally.joint, done)
    return problems or marginal_problems(plan, tally.joint, tally, "checkpoint joint record")


def velocity_shape_problems(plan, tally):
    """The velocity arrays of a velocity scene's tally: present, (curves, grid) shaped, counts
    non-negative, sums exact rationals."""
    shape = (len(plan.experiments), len(plan.n_grid))
    out = []
    for name in ("moving", "stuck_at", "sum_v", "sum_v2"):
        a = getattr(tally, name)
        if a is None or a.shape != shape:
            out.append(f"{name} has shape {None if a is None else a.shape}, the plan needs"
                       f" {shape}")
        elif name in ("moving", "stuck_at") and np.any(a < 0):
            out.append(f"{name} has negative counts")
        elif name in ("sum_v", "sum_v2") and not all(isinstance(x, Fraction) for x in a.flat):
            out.append(f"{name} holds values that are not exact sums")
    return out


def parse_counts(plan, text, name="counts.csv"):
    """counts.csv text -> (Counts with an experiment axis, {(e, clock): stuck}, problems,
    {(e, clock): first line}). Lines are numbered from 1 (the header)."""
    holes = max([len(x.hole_lo) for x in plan.experiments] + [1])
    counts = Counts.zeros(plan, holes, experiments=len(plan.experiments))
    exps = {x.name: e for e, x in enumerate(plan.experiments)}
    edges = {"collisions": {repr(float(x)): b for b, x in enumerate(plan.n_edges)},
             "time": {repr(float(x)): b for b, x in enumerate(plan.t_edges)}}
    stuck, problems, first = Counter(), [], {}
    reader = csv.reader(io.StringIO(text))
    header = next(reader, None)
    if header != ["experiment", "clock", "outcome", "lower_edge", "count"]:
        return counts, stuck, [f"{name}:1: header {header} is not the counts.csv header"], first
    for line, row in enumerate(reader, start=2):
        try:
            exp, clock, outcome, edge, count = row
            e, b, c = exps[exp], edges[clock][edge], int(count)
            curves = plan.experiments[e].curves
            if not 0 < c < 2**63 or clock not in plan.scene.clocks:  # counts are int64
                raise ValueError
        except (ValueError, KeyError):
            problems.append(f"{name}:{line}: not a row of this run: {','.join(row)}")
            continue
        first.setdefault((e, clock), line)
        esc, cens = _clock_arrays(counts, e, clock)
        if outcome == "censored":
            cens[b] += c
        elif outcome == "stuck":
            stuck[e, clock] += c
            _stuck_array(counts, e, clock)[b] += c
        elif outcome in curves:
            esc[curves.index(outcome), b] += c
        else:
            problems.append(f"{name}:{line}: unknown outcome {outcome!r}")
    return counts, stuck, problems, first


def survival_problems(text, name="survival.csv"):
    """Range and monotonicity of the survival curves in survival.csv text, by line."""
    problems, last = [], {}
    reader = csv.DictReader(io.StringIO(text))
    for line, row in enumerate(reader, start=2):
        try:
            p, lo, hi = float(row["p"]), float(row["p_lo"]), float(row["p_hi"])
            key = (row["curve"], row["clock"])
        except (KeyError, TypeError, ValueError):
            problems.append(f"{name}:{line}: not a survival row")
            continue
        if not 0.0 <= lo <= p <= hi <= 1.0:
            problems.append(f"{name}:{line}: {key[0]} ({key[1]}): p {p!r} with band"
                            f" [{lo!r}, {hi!r}] is not 0 <= p_lo <= p <= p_hi <= 1")
        if key in last and p > last[key]:
            problems.append(f"{name}:{line}: {key[0]} ({key[1]}): p rises from {last[key]!r}"
                            f" to {p!r}")
        last[key] = p
    return problems
