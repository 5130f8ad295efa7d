"""``bouncer sweep``: an escape-rate map over eps, hole centre and/or width."""

from reports.cli.threads import threads_option
from reports.runs import rundir
from reports.runs.scenes import load_scene
from reports.runs.sweep import grid_values, sweep


def _sweep(args):
    scene = load_scene(args.scene)
    threads = threads_option(args)
    grid = {name: grid_values(*getattr(args, name), name)
            for name in ("eps", "centre", "width") if getattr(args, name) is not None}
    out = args.out or rundir.default_out("sweeps", scene.name)
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


def add_parser(subparsers):
    sweep = subparsers.add_parser(
        "sweep", help="escape-rate map over eps, hole centre and/or width")
    sweep.add_argument("scene", metavar="SCENE_OR_FILE", nargs="?", default="paper-escape",
                       help="base escape scene (default: paper-escape)")
    for name, what in (("eps", "eps"), ("centre", "hole centre"), ("width", "hole width")):
        sweep.add_argument(f"--{name}", type=float, nargs=3, metavar=("LO", "HI", "N"),
                           help=f"sweep {what} over N values from LO to HI")
    sweep.add_argument("--n-star", type=int, default=50,
                       help="rate = -ln P(n*)/n* (default 50 collisions)")
    sweep.add_argument("--particles", type=int, default=2000, help="starts per grid point")
    sweep.add_argument("--seed", type=int, help="random seed (default: the scene's)")
    sweep.add_argument("--verify-samples", type=int, default=500,
                       help="collisions verified over the whole sweep (default 500)")
    sweep.add_argument("--out", help="sweep directory (default: sweeps/SCENE_NAME)")
    sweep.add_argument("--threads", type=int, help="numba threads (results do not depend on it)")
    sweep.add_argument("--scheduler", metavar="ADDRESS",
                       help="Dask scheduler (tcp://host:8786): run the chunks on that cluster")
    sweep.add_argument("--force", action="store_true", help="overwrite an existing sweep")
    sweep.add_argument("--quiet", action="store_true", help="no progress bar")
    sweep.set_defaults(func=_sweep)
