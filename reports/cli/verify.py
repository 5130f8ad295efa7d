"""``bouncer verify RUN_DIR``: recompute a run's verification sample."""

from reports.runs.recheck import recheck


def _verify(args):
    ok, lines = recheck(args.run_dir)
    for line in lines:
        print(line)
    return 0 if ok else 1


def add_parser(subparsers):
    recheck = subparsers.add_parser("verify", help="recompute a run's verification sample")
    recheck.add_argument("run_dir", metavar="RUN_DIR")
    recheck.set_defaults(func=_verify)
