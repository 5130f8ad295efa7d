"""``bouncer verify RUN_DIR``: audit a run (hashes, invariants, re-derived curves, every field of
its manifest), recompute its verification sample and replay it from the seed
(``reports.runs.recheck``). Exit 0 when every check holds, 1 on any discrepancy, 2 when the
directory is not a readable run."""

from reports.runs.recheck import recheck


def _verify(args):
    ok, lines = recheck(args.run_dir, progress=not args.quiet)
    for line in lines:
        print(line)
    return 0 if ok else 1


def add_parser(subparsers):
    recheck = subparsers.add_parser(
        "verify", help="audit a run and recompute its verification sample")
    recheck.add_argument("run_dir", metavar="RUN_DIR", help="the run directory to audit")
    recheck.add_argument("--quiet", action="store_true", help="no progress bar")
    recheck.set_defaults(func=_verify)
