"""``bouncer verify RUN_DIR``: recompute a finished run's verification sample.

For every row of ``sample.csv`` (a pre-collision state (phi, v) and the fast result):

* ``fastpath.step(phi, v, eps)`` must give the stored (phi1, v1, tau) bit for bit (the run is
  reproducible on this machine and version);
* ``verify.step`` recomputes tau_ref; the error |tau - tau_ref| / (tau_ref*kappa*u) is compared
  with the run's, and tau - tau_ref > 16*kappa*u*tau_ref (an overstep) fails the check.
"""

from __future__ import annotations

from pathlib import Path

import fastpath
from reports.runs import rundir
from reports.runs.chunk import OVERSTEP_TOLERANCE, check_sample
from reports.runs.scenes import parse_scene


def load_run(run_dir):
    """(manifest, scene) of a run directory; ValueError if it is not one."""
    run_dir = Path(run_dir)
    if not (run_dir / rundir.MANIFEST).is_file() or not (run_dir / "scene.toml").is_file():
        raise ValueError(f"{run_dir} is not a run directory (no manifest.json and scene.toml)")
    manifest = rundir.read_json(run_dir / rundir.MANIFEST)
    scene = parse_scene((run_dir / "scene.toml").read_text(encoding="utf-8"), "stored scene")
    return manifest, scene


def recheck(run_dir):
    """Recompute the sample; returns (ok, report lines)."""
    run_dir = Path(run_dir)
    manifest, scene = load_run(run_dir)
    if not (run_dir / "sample.csv").is_file():
        raise ValueError(f"{run_dir} has no sample.csv (status {manifest['status']})")
    rows = rundir.read_csv(run_dir / "sample.csv")
    worst, mismatched, overstepped = 0.0, [], []
    for row in rows:
        phi, v = float(row["phi"]), float(row["v"])
        stored = (float(row["phi1"]), float(row["v1"]), float(row["tau"]))
        if tuple(fastpath.step(phi, v, scene.eps)) != stored:
            mismatched.append(row)
        _, error, overstep = check_sample(phi, v, stored[2], scene.eps)
        worst = max(worst, error)
        if overstep:
            overstepped.append(row)
    recorded = manifest["verification"]["worst_error"]
    lines = [
        f"run {run_dir}: scene {scene.name}, status {manifest['status']}",
        f"{len(rows)} sampled collisions recomputed by verify: worst error {worst:.3g} kappa*u"
        f" (recorded {recorded:.3g}), {len(overstepped)} overstepped"
        f" (tolerance {OVERSTEP_TOLERANCE:g} kappa*u)",
        f"fastpath reproduces {len(rows) - len(mismatched)} of {len(rows)} stored results"
        " bit for bit",
    ]
    for row in overstepped[:5]:
        lines.append(f"OVERSTEP: {dict(row)}")
    for row in mismatched[:5]:
        lines.append(f"NOT REPRODUCED: {dict(row)}")
    ok = not overstepped and not mismatched and manifest["status"] == "complete"
    if manifest["status"] != "complete":
        lines.append(f"the run is not complete (status {manifest['status']})")
    lines.append("OK" if ok else "FAILED")
    return ok, lines
