"""The ``bouncer`` command. Exit status: 0 ok, 1 failure, 2 bad input (one-line message).

    bouncer demo [--eps E] [--collisions N] [--sample S] [--seed S]
    bouncer scenes
    bouncer run SCENE_OR_FILE [--particles N] [--seed S] [--out DIR] [--threads K]
                              [--resume] [--force] [--quiet] [--scheduler ADDRESS]
    bouncer sweep [SCENE_OR_FILE] [--eps LO HI N] [--centre LO HI N] [--width LO HI N]
                  [--n-star N] [--particles N] [--seed S] [--verify-samples N] [--out DIR]
                  [--threads K] [--scheduler ADDRESS] [--force] [--quiet]
    bouncer plot RUN_DIR [--out FILE] [--fit MODEL --window LO HI [--clock C] [--curve NAME]]
    bouncer verify RUN_DIR
    bouncer check MODULE:FUNCTION [--step MODULE:FUNCTION] [--suite NAME]
    bouncer bench [--collisions N] [--repeats R] [--particles N]
    bouncer report [--particles N] [--out DIR] [--quick] [--compare MODULE:FUNCTION]
                   [--include-run RUN_DIR]
"""

import argparse
import resource
import sys

from reports.bench import add_bench_parser
from reports.check_cli import add_check_parser
from reports.report import add_report_parser
from reports.rundir import RunFailed


def _demo(args):
    from reports.demo import run_demo

    run_demo(eps=args.eps, collisions=args.collisions, sample=args.sample, seed=args.seed)
    return 0


def _scenes(args):
    from reports.scenes import builtin_scenes, parse_scene

    for name, text in builtin_scenes().items():
        scene = parse_scene(text, name)
        curves = sum(len(x.curves) for x in scene.experiments())
        print(f"{name:20s} {scene.kind:12s} eps={scene.eps:g}  {scene.particles} particles x "
              f"{len(scene.experiments())} start sets, {curves} curves  {scene.description}")
    return 0


def _set_threads(threads):
    if threads is None:
        return None
    import numba

    limit = numba.config.NUMBA_NUM_THREADS
    if not 1 <= threads <= limit:
        raise ValueError(f"--threads must be between 1 and {limit}, got {threads}")
    numba.set_num_threads(threads)
    return threads


def _run(args):
    from reports.runner import run
    from reports.scenes import load_scene

    scene = load_scene(args.scene)
    threads = _threads(args)
    out = args.out or f"runs/{scene.name}"
    manifest = run(scene, out, particles=args.particles, seed=args.seed, resume=args.resume,
                   force=args.force, progress=not args.quiet, threads=threads,
                   scheduler=args.scheduler)
    ver = manifest["verification"]
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"{manifest['status']}: {out}  {manifest['particles_total']} particles, "
          f"{manifest['collisions']} collisions in {manifest['wall_time_s']:.1f} s "
          f"({manifest['collisions_per_s'] or 0:.3g}/s), peak memory {peak:.0f} MiB")
    print(f"verification: {ver['sampled']} sampled collisions, worst error "
          f"{ver['worst_error']:.3g} kappa*u, {ver['overstepped']} overstepped, "
          f"{ver['uncertain_settled']} uncertain settled by verify")
    session = manifest.get("session") or {}
    if session.get("scheduler"):
        print(f"cluster: {session['scheduler']}, {session['workers']} workers, "
              f"{session['chunks_computed']} chunks computed there")
    return 0


def _threads(args):
    """--threads: numba threads here; on a cluster, of each task (the workers check it)."""
    if args.threads is not None and args.scheduler is not None:
        if args.threads < 1:
            raise ValueError(f"--threads must be >= 1, got {args.threads}")
        return args.threads
    return _set_threads(args.threads)


def _sweep(args):
    from reports.scenes import load_scene
    from reports.sweep import grid_values, sweep

    scene = load_scene(args.scene)
    threads = _threads(args)
    grid = {name: grid_values(*getattr(args, name), name)
            for name in ("eps", "centre", "width") if getattr(args, name) is not None}
    out = args.out or f"sweeps/{scene.name}"
    manifest = sweep(scene, out, grid=grid, n_star=args.n_star, particles=args.particles,
                     seed=args.seed, verify_samples=args.verify_samples,
                     scheduler=args.scheduler, threads=threads, force=args.force,
                     progress=not args.quiet)
    ver = manifest["verification"]
    print(f"{manifest['status']}: {out}/sweep.csv, {out}/escape-rate.png  {manifest['points']}"
          f" points ({manifest['skipped']} skipped) x {manifest['particles']} particles,"
          f" n* = {manifest['n_star']}, {manifest['collisions']} collisions in"
          f" {manifest['wall_time_s']:.1f} s")
    print(f"verification: {ver['sampled']} sampled collisions, worst error "
          f"{ver['worst_error']:.3g} kappa*u, {ver['overstepped']} overstepped, "
          f"{ver['uncertain_settled']} uncertain settled by verify")
    return 0


def _plot(args):
    from reports.plotting import plot_run

    for line in plot_run(args.run_dir, out=args.out, fit=args.fit, window=args.window,
                         clock=args.clock, curve=args.curve):
        print(line)
    return 0


def _verify(args):
    from reports.recheck import recheck

    ok, lines = recheck(args.run_dir)
    for line in lines:
        print(line)
    return 0 if ok else 1


def build_parser():
    parser = argparse.ArgumentParser(
        prog="bouncer", description="Validated numerics for the bouncer model.")
    sub = parser.add_subparsers(dest="command", required=True)
    demo = sub.add_parser("demo", help="an orbit with fastpath, a sample of it checked by verify")
    demo.add_argument("--eps", type=float, default=0.6)
    demo.add_argument("--collisions", type=int, default=100_000)
    demo.add_argument("--sample", type=int, default=200)
    demo.add_argument("--seed", type=int, default=0)
    demo.set_defaults(func=_demo)

    scenes = sub.add_parser("scenes", help="list the built-in scenes")
    scenes.set_defaults(func=_scenes)

    run = sub.add_parser("run", help="a trusted ensemble run of a scene (built-in name or TOML)")
    run.add_argument("scene", metavar="SCENE_OR_FILE")
    run.add_argument("--particles", type=int, help="starts per curve (default: the scene's)")
    run.add_argument("--seed", type=int, help="seed (default: the scene's)")
    run.add_argument("--out", help="run directory (default: runs/SCENE_NAME)")
    run.add_argument("--threads", type=int, help="numba threads (results do not depend on it)")
    run.add_argument("--resume", action="store_true", help="continue a killed run in --out")
    run.add_argument("--force", action="store_true", help="overwrite an existing run directory")
    run.add_argument("--quiet", action="store_true", help="no progress bar")
    run.add_argument("--scheduler", metavar="ADDRESS",
                     help="Dask scheduler (tcp://host:8786): run the chunks on that cluster")
    run.set_defaults(func=_run)

    sweep = sub.add_parser("sweep", help="escape-rate map over eps, hole centre and/or width")
    sweep.add_argument("scene", metavar="SCENE_OR_FILE", nargs="?", default="paper-escape",
                       help="base escape scene (default: paper-escape)")
    for name, what in (("eps", "eps"), ("centre", "hole centre"), ("width", "hole width")):
        sweep.add_argument(f"--{name}", type=float, nargs=3, metavar=("LO", "HI", "N"),
                           help=f"sweep {what} over N values from LO to HI")
    sweep.add_argument("--n-star", type=int, default=50,
                       help="rate = -ln P(n*)/n* (default 50 collisions)")
    sweep.add_argument("--particles", type=int, default=2000, help="starts per grid point")
    sweep.add_argument("--seed", type=int, help="seed (default: the scene's)")
    sweep.add_argument("--verify-samples", type=int, default=500,
                       help="collisions verified over the whole sweep (default 500)")
    sweep.add_argument("--out", help="sweep directory (default: sweeps/SCENE_NAME)")
    sweep.add_argument("--threads", type=int, help="numba threads (results do not depend on it)")
    sweep.add_argument("--scheduler", metavar="ADDRESS",
                       help="Dask scheduler (tcp://host:8786): run the chunks on that cluster")
    sweep.add_argument("--force", action="store_true", help="overwrite an existing sweep")
    sweep.add_argument("--quiet", action="store_true", help="no progress bar")
    sweep.set_defaults(func=_sweep)

    plot = sub.add_parser("plot", help="survival curves (or the portrait) of a run, as PNG")
    plot.add_argument("run_dir", metavar="RUN_DIR")
    plot.add_argument("--out", help="image file (default: RUN_DIR/survival.png)")
    plot.add_argument("--fit", choices=["exponential", "stretched", "power"])
    plot.add_argument("--window", type=float, nargs=2, metavar=("LO", "HI"))
    plot.add_argument("--clock", choices=["collisions", "time"], default="time")
    plot.add_argument("--curve", help="fit only this curve")
    plot.set_defaults(func=_plot)

    recheck = sub.add_parser("verify", help="recompute a run's verification sample")
    recheck.add_argument("run_dir", metavar="RUN_DIR")
    recheck.set_defaults(func=_verify)

    add_report_parser(sub)
    add_check_parser(sub)
    add_bench_parser(sub)
    return parser


def main(argv=None):
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return args.func(args)
    except ValueError as err:
        print(f"bouncer: error: {err}", file=sys.stderr)
        return 2
    except RunFailed as err:
        print(f"bouncer: run failed: {err}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
