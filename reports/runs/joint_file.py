"""joint.csv, the joint record of (n, t) of a run whose scene has ``[record] joint = true``:
its rows, its parser and its invariants.

The escape histograms of counts.csv count the escape index n and the escape time t of a curve
separately. The joint record counts them together, on the same bins: for experiment e (a set of
starts) and outcome o (each of its curves, i.e. exit holes, then ``censored``, then ``stuck``),

    joint[e, o, b, c] = particles with n_edges[b] <= n < n_edges[b + 1]
                                   and t_edges[c] <= t < t_edges[c + 1]

(the last bin open above; the plan's edges, ``manifest.json``'s ``bins``), where (n, t) is the
escape index and time of an escape, the index and time bounds of a censored particle
(N > n and T > t, as in counts.csv), and for a stuck one the index of the impact after which it
came to rest and the time it did. So its marginals are counts.csv's histograms exactly:

    sum over c of joint[e, o, :, c] = counts.csv's collisions histogram of (e, o)
    sum over b of joint[e, o, b, :] = counts.csv's time histogram of (e, o)

and every particle of a curve set is in exactly one bin of one outcome. ``bouncer verify``
checks both (``joint_problems``, ``marginal_problems``), and that joint.csv is the one written
from the checkpoint.

joint.csv holds the non-zero bins, one per line, sorted by experiment, outcome, n bin, t bin:

    experiment,outcome,n_lower_edge,t_lower_edge,count

``reports.runs.joint.load_joint(RUN_DIR)`` reads it for an analysis.
"""

from __future__ import annotations

import csv
import io

import numpy as np

from reports.runs import rundir

JOINT_FILE = "joint.csv"
JOINT_COLUMNS = ("experiment", "outcome", "n_lower_edge", "t_lower_edge", "count")
ENDS = ("censored", "stuck")  # the outcomes after an experiment's curves


def outcomes(exp):
    """The outcomes of experiment ``exp`` in the order of the joint record's axis 1."""
    return (*exp.curves, *ENDS)


def joint_rows(plan, joint):
    """Rows of joint.csv from the dense record ``joint`` (experiments, outcomes, n bins,
    t bins): its non-zero bins."""
    rows = []
    for e, exp in enumerate(plan.experiments):
        for o, name in enumerate(outcomes(exp)):
            for b, c in np.argwhere(joint[e, o]):
                rows.append([exp.name, name, repr(float(plan.n_edges[b])),
                             repr(float(plan.t_edges[c])), int(joint[e, o, b, c])])
    return rows


def joint_text(plan, joint):
    """joint.csv's text."""
    return rundir.csv_text(JOINT_COLUMNS, joint_rows(plan, joint))


def joint_shape(plan):
    """(experiments, outcomes, n bins, t bins) of the plan's joint record."""
    holes = max([len(x.hole_lo) for x in plan.experiments] + [1])
    return (len(plan.experiments), holes + len(ENDS), len(plan.n_edges), len(plan.t_edges))


def parse_joint(plan, text, name=JOINT_FILE):
    """joint.csv text -> (dense record, problems by line). A row must name an experiment and one
    of its outcomes, two lower edges of the plan's bins and a positive int64 count, once."""
    joint = np.zeros(joint_shape(plan), np.int64)
    exps = {x.name: (e, outcomes(x)) for e, x in enumerate(plan.experiments)}
    n_bin = {repr(float(x)): b for b, x in enumerate(plan.n_edges)}
    t_bin = {repr(float(x)): c for c, x in enumerate(plan.t_edges)}
    problems, seen = [], set()
    reader = csv.reader(io.StringIO(text, newline=""))
    header = next(reader, None)
    if header != list(JOINT_COLUMNS):
        return joint, [f"{name}:1: header {header} is not the joint.csv header"]
    for line, row in enumerate(reader, start=2):
        try:
            exp, outcome, n_edge, t_edge, count = row
            e, names = exps[exp]
            key = (e, names.index(outcome), n_bin[n_edge], t_bin[t_edge])
            c = int(count)
            if not 0 < c < 2**63:
                raise ValueError
        except (ValueError, KeyError):
            problems.append(f"{name}:{line}: not a row of this run: {','.join(row)}")
            continue
        if key in seen:
            problems.append(f"{name}:{line}: bin ({exp}, {outcome}, {n_edge}, {t_edge}) again")
            continue
        seen.add(key)
        joint[key] = c
    return joint, problems


def joint_problems(plan, joint, done):
    """The joint record against the plan: its shape, counts non-negative, and per experiment
    e every particle of its finished chunks (``done[e]``) in exactly one bin."""
    shape = joint_shape(plan)
    if joint.shape != shape:
        return [f"joint record has shape {joint.shape}, the plan needs {shape}"]
    if np.any(joint < 0):
        return ["joint record has negative counts"]
    out = []
    for e, exp in enumerate(plan.experiments):
        total = int(joint[e].sum())
        if total != done[e]:
            out.append(f"joint record of {exp.name!r}: {total} particles, but {done[e]} were"
                       " run")
    return out


def marginal_problems(plan, joint, counts, where="joint.csv"):
    """Where the marginals of the joint record differ from the histograms ``counts``
    (``reports.runs.counts.Counts`` with an experiment axis: counts.csv or the checkpoint)."""
    out = []
    for e, exp in enumerate(plan.experiments):
        holes = len(exp.curves)
        sides = [(name, counts.esc_n[e, j], counts.esc_t[e, j]) for j, name in
                 enumerate(exp.curves)]
        sides += [("censored", counts.cens_n[e], counts.cens_t[e]),
                  ("stuck", counts.stuck_n[e], counts.stuck_t[e])]
        for o, (name, by_n, by_t) in enumerate(sides):
            record = joint[e, o if o < holes else joint.shape[1] - len(ENDS) + (o - holes)]
            for clock, axis, hist in (("collisions", 1, by_n), ("time", 0, by_t)):
                diff = np.flatnonzero(record.sum(axis=axis) != hist)
                if len(diff):
                    edges = plan.n_edges if clock == "collisions" else plan.t_edges
                    b = diff[0]
                    out.append(f"{where}: {exp.name}, {name}: the {clock} marginal has"
                               f" {int(record.sum(axis=axis)[b])} in the bin from"
                               f" {float(edges[b])!r}, counts.csv {int(hist[b])}"
                               f" ({len(diff)} bins differ)")
    return out
