"""``bouncer run SCENE_OR_FILE``: a trusted ensemble run of a scene."""

import argparse
import math
import resource
import shlex

from reports.cli.threads import threads_option
from reports.runs import rundir
from reports.runs.driver import run
from reports.runs.manifest import load_provenance
from reports.runs.provenance import dirty_text
from reports.runs.scenes import load_scene


def _run(args):
    args.resume_command = _resume_command(args)
    scene = load_scene(args.scene)
    threads = threads_option(args)
    out = args.out or rundir.default_out("runs", scene.name)
    manifest = run(scene, out, particles=args.particles, seed=args.seed, resume=args.resume,
                   force=args.force, progress=not args.quiet, threads=threads,
                   scheduler=args.scheduler, require_clean=args.require_clean)
    record = load_provenance(out)
    ver = manifest["verification"]
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    compiled = "" if record["compile_s"] is None else \
        f", kernels compiled in {record['compile_s']:.1f} s"
    print(f"{manifest['status']}: {out}  {manifest['particles_total']} particles, "
          f"{manifest['collisions']} collisions in {record['compute_s'] or 0:.1f} s "
          f"({record['collisions_per_s'] or 0:.3g}/s{compiled}), peak memory {peak:.0f} MiB")
    print(f"verification: {ver['sampled']} sampled collisions, worst error "
          f"{ver['worst_error']:.3g} kappa*u, {ver['overstepped']} overstepped, "
          f"{ver['uncertain_settled']} uncertain settled by verify")
    problem = dirty_text(record["git"])
    if problem:
        print(f"provenance: {problem}")
    session = record["session"]
    if session["scheduler"]:
        print(f"cluster: {session['scheduler']}, {session['workers']} workers, "
              f"{session['chunks_computed']} chunks computed there")
    return 0


def count(text):
    """An integer given as 1000000 or 1e6 (an exact integer); ``argparse.ArgumentTypeError``
    (argparse's one-line error naming the option) otherwise."""
    try:
        return int(text)
    except ValueError:
        pass
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not value.is_integer():
        raise argparse.ArgumentTypeError(f"need an integer such as 1000000 or 1e6, got {text!r}")
    return int(value)


def _resume_command(args):
    def command(err):
        parts = ["bouncer", "run", args.scene, "--out", str(err.out), "--resume"]
        for flag in ("particles", "seed", "scheduler"):
            if getattr(args, flag) is not None:
                parts += [f"--{flag}", str(getattr(args, flag))]
        return shlex.join(parts)
    return command


def add_parser(subparsers):
    run = subparsers.add_parser(
        "run", help="a trusted ensemble run of a scene (built-in name or TOML)")
    run.add_argument("scene", metavar="SCENE_OR_FILE",
                     help="a built-in scene (bouncer scenes lists them) or a scene TOML file")
    run.add_argument("--particles", type=count,
                     help="starts per curve, e.g. 1000000 or 1e6 (default: the scene's)")
    run.add_argument("--seed", type=int, help="random seed (default: the scene's)")
    run.add_argument("--out", help="run directory (default: runs/SCENE_NAME, which must stay"
                     " inside runs/)")
    run.add_argument("--threads", type=int, help="numba threads (results do not depend on it)")
    run.add_argument("--resume", action="store_true", help="continue a killed run in --out")
    run.add_argument("--force", action="store_true", help="overwrite an existing run directory")
    run.add_argument("--quiet", action="store_true", help="no progress bar")
    run.add_argument("--scheduler", metavar="ADDRESS",
                     help="Dask scheduler (tcp://host:8786): run the chunks on that cluster")
    run.add_argument("--require-clean", action="store_true",
                     help="refuse to run from a git tree with uncommitted changes (outside the"
                     " run directory), so that provenance.json names the exact code")
    run.set_defaults(func=_run, resume_command=None)
