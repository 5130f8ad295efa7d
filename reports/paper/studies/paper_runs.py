"""The runs behind the paper's figures: reused when complete and ``bouncer verify`` passes on
them with this code, else run (``ensure_run``).
"""

from __future__ import annotations

import time
from pathlib import Path

from reports.runs import rundir
from reports.runs.driver import run
from reports.runs.recheck import recheck
from reports.runs.rundir import RunFailed
from reports.runs.scenes import load_scene, parse_scene

DEFAULT_PARTICLES = 1_000_000  # per escape curve and per transport entry hole


QUICK_PARTICLES = 2000


PHASE_SPACE_QUICK = 200


def say_nothing(_msg):
    return None


def ensure_run(name, runs_dir, particles, echo=say_nothing, scene_text=None):
    """Run directory of the built-in scene ``name`` (or of the scene ``scene_text``, named
    ``name``) with ``particles`` (per curve): reused when complete with the same scene,
    particles and seed and ``bouncer verify`` (``recheck``) passes on it (this code re-derives
    its sampled collisions bit for bit: a run made by other solver code is run again), resumed
    when partial, else run."""
    scene = load_scene(name) if scene_text is None else parse_scene(scene_text, origin=name)
    out = Path(runs_dir) / f"{name}-{particles}"
    resume = force = False
    man_path = out / rundir.MANIFEST
    if man_path.is_file():
        man = rundir.read_json(man_path)
        stored = (out / "scene.toml").read_text(encoding="utf-8") if (
            out / "scene.toml").is_file() else ""
        same = (stored == scene.source and man.get("particles") == particles
                and man.get("seed") == scene.seed)
        complete = same and man.get("status") == "complete"
        audit = recheck(out) if complete else None
        if audit and audit[0]:
            echo(f"reusing {out} (complete, bouncer verify passes)")
            return out
        if complete:
            echo(f"{out}: bouncer verify fails on it ({audit[1][-1]}; `bouncer verify {out}` lists"
                 " them): this code does not reproduce the stored run, running it again")
            force = True
        elif same and man.get("status") == "partial":
            resume = True
        elif man.get("status") == "failed" and same:
            raise RunFailed(f"{out}: the stored run failed: {man.get('failure')}")
        else:
            force = True
    elif out.exists() and any(out.iterdir()):
        raise ValueError(f"{out} exists and holds no run; not touching it")
    echo(f"running {name} with {particles} particles per curve into {out}")
    t0 = time.perf_counter()
    man = run(scene, out, particles=particles, resume=resume, force=force, progress=True)
    echo(f"  {name}: {man['collisions']:.3g} collisions in {time.perf_counter() - t0:.1f} s, "
         f"verification: {man['verification']['sampled']} sampled, worst "
         f"{man['verification']['worst_error']:.2g} kappa*u")
    return out


def run_summary(run_dir):
    """One line: particles, horizon and the verification summary of a run directory."""
    man = rundir.read_json(Path(run_dir) / rundir.MANIFEST)
    hz = man["scene"]["horizon"]
    horizon = ", ".join(f"{k} <= {v:g}" for k, v in (("n", hz["collisions"]),
                                                    ("t", hz["time"])) if v)
    ver = man["verification"]
    return (f"{man['particles']:,} particles per curve, horizon {horizon}; verify: "
            f"{ver['sampled']} sampled collisions, worst error {ver['worst_error']:.2g} "
            f"kappa*u, {ver['uncertain_settled']} settled, {ver['overstepped']} overstepped")


def read_manifest(run_dir):
    return rundir.read_json(Path(run_dir) / rundir.MANIFEST)


def largest_run(scene_name, candidates):
    """The complete run of built-in scene ``scene_name`` with the most particles per curve among
    the run directories ``candidates``, or None."""
    best = None
    for path in candidates:
        man_path = Path(path) / rundir.MANIFEST
        if not man_path.is_file():
            continue
        man = rundir.read_json(man_path)
        if man.get("status") != "complete" or man.get("scene", {}).get("name") != scene_name:
            continue
        if best is None or man["particles"] > best[0]:
            best = (man["particles"], Path(path))
    return None if best is None else best[1]
