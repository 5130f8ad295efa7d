"""Reading a run's joint record of (n, t) for an analysis: ``load_joint(RUN_DIR)``.

The record (``reports.runs.joint_file``, docs/runs.md "Records"): for each curve of a run whose
scene has ``[record] joint = true``, counts[b, c] of its escapes with the escape index n in
collision bin b and the escape time t in time bin c, on the bins of counts.csv; for each set of
starts the same of its censored (the bounds N > n, T > t) and stuck particles. Its marginals are
counts.csv's histograms exactly. From it: t/n per escape at any survival level or in any window
of n or t, the typical n at time t, matched quantiles of n and t.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from reports.runs import rundir
from reports.runs.integrity import parse_counts
from reports.runs.joint_file import JOINT_FILE, joint_problems, marginal_problems, parse_joint
from reports.runs.manifest import load_manifest
from reports.runs.plan import make_plan
from reports.runs.scenes import parse_scene


@dataclass(frozen=True)
class JointRecord:
    """A run's joint record of (n, t), for an analysis.

    ``n_edges``, ``t_edges``: lower bin edges (bin b holds n_edges[b] <= n < n_edges[b + 1], the
    last bin open above; t_edges[0] = 0). ``escapes[curve]``: counts[b, c] of the escapes of a
    curve (a hole of an escape scene, P_ij of a transport scene, as named in counts.csv);
    ``censored[experiment]``, ``stuck[experiment]``: the bounds (n, t) of the particles of a set
    of starts that did not escape; ``experiment[curve]``: the set of starts of a curve;
    ``particles``: starts per set."""

    n_edges: np.ndarray
    t_edges: np.ndarray
    particles: int
    escapes: dict
    censored: dict
    stuck: dict
    experiment: dict


def load_joint(run_dir):
    """The joint record of a complete run directory (``JointRecord``). ValueError (one line)
    if it is not a run whose scene records one, joint.csv's SHA-256 is not the manifest's, or
    joint.csv does not parse or its marginals differ from counts.csv. (``bouncer verify``
    audits the rest: the checkpoint, the sample, every field of the manifest.)"""
    run_dir = Path(run_dir)
    manifest = load_manifest(run_dir)
    try:
        scene = parse_scene((run_dir / "scene.toml").read_bytes().decode("utf-8"),
                            str(run_dir / "scene.toml"))
    except (OSError, UnicodeDecodeError) as err:
        raise ValueError(f"{run_dir / 'scene.toml'}: unreadable ({err})") from None
    if not scene.joint:
        raise ValueError(f"{run_dir}: scene {scene.name!r} records no joint histogram"
                         " ([record] joint = true)")
    if manifest["status"] != "complete":
        raise ValueError(f"{run_dir}: the run is not complete (status {manifest['status']})")
    path = run_dir / JOINT_FILE
    recorded = manifest["hashes"].get(JOINT_FILE)
    try:
        data = rundir.read_input(path)  # a regular file of bounded size
        counts_text = rundir.read_input_text(run_dir / "counts.csv")
    except (OSError, ValueError) as err:
        raise ValueError(f"{path.parent}: {err}") from None
    if hashlib.sha256(data).hexdigest() != recorded:
        raise ValueError(f"{path}: its SHA-256 is not the manifest's")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as err:
        raise ValueError(f"{path}: not UTF-8 text (byte {err.start})") from None
    plan = make_plan(scene, manifest["particles"], manifest["seed"])
    joint, problems = parse_joint(plan, text)
    counts, _, count_problems, _ = parse_counts(plan, counts_text)
    problems += count_problems + marginal_problems(plan, joint, counts)
    problems += joint_problems(plan, joint, [plan.particles] * len(plan.experiments))
    if problems:
        more = f" (and {len(problems) - 1} more)" if len(problems) > 1 else ""
        raise ValueError(f"{run_dir}: {problems[0]}{more}")
    escapes, censored, stuck, experiment = {}, {}, {}, {}
    for e, exp in enumerate(plan.experiments):
        for j, curve in enumerate(exp.curves):
            escapes[curve] = joint[e, j]
            experiment[curve] = exp.name
        censored[exp.name] = joint[e, -2]
        stuck[exp.name] = joint[e, -1]
    return JointRecord(plan.n_edges, plan.t_edges, plan.particles, escapes, censored, stuck,
                       experiment)
