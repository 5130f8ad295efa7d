"""``bouncer check MODULE:FUNCTION [--step MODULE:FUNCTION] [--suite NAME]``.

Runs ``verify.check_integrator`` on a user's flight-time function (and step function) from the
shell. Exit status: 0 when every property holds, 1 when one fails (the report, then the
smallest failing input of each failed property), 2 for bad input (a module that does not
import, a name that is not callable, an unknown suite: one line ``bouncer: error: ...``).

Wire it into the ``bouncer`` parser with ``add_parser(subparsers)``; ``main`` runs it alone
(``python -m reports.cli.check check MODULE:FUNCTION``).
"""

import argparse
import sys

SUITE_HELP = (
    "all (default), fast (20 inputs per property), or one property: no_overstep, accuracy, "
    "fixed_points, energy (needs --step), holmes_limit, reversibility"
)


def add_parser(subparsers):
    """Add the ``check`` subcommand to an ``argparse`` subparsers object; return its parser."""
    check = subparsers.add_parser(
        "check",
        help="run the property suite against your own integrator (MODULE:FUNCTION)",
        description="Hold a flight-time function flight_time(phi, v, eps) -> tau (and "
        "optionally step(phi, v, eps) -> (phi1, v1, tau)) to verify's certified reference: "
        "no overstepped collision, accuracy within k x condition number x unit roundoff, "
        "fixed points and their Jacobian, energy bookkeeping, the Holmes limit, "
        "reversibility. MODULE is a module name importable from the current directory or a "
        "path to a .py file.",
    )
    check.add_argument("target", metavar="MODULE:FUNCTION",
                       help="the flight-time function, e.g. mysolver:flight_time")
    check.add_argument("--step", metavar="MODULE:FUNCTION",
                       help="the collision map step(phi, v, eps) -> (phi1, v1, tau)")
    check.add_argument("--suite", default="all", metavar="NAME", help=SUITE_HELP)
    check.add_argument("--max-examples", type=int, metavar="N",
                       help="inputs per property (default 100; 20 for --suite fast)")
    check.add_argument("--seed", type=int, default=0,
                       help="hypothesis seed: the same seed draws the same inputs (default 0)")
    check.add_argument("-k", type=float, default=16.0, metavar="K",
                       help="allowed error in units of condition number x unit roundoff "
                       "(default 16)")
    check.set_defaults(func=check_command)
    return check


def _error(message: str) -> int:
    print(f"bouncer: error: {message}", file=sys.stderr)
    return 2


def check_command(args) -> int:
    """Run the check described by parsed ``args``; print the report; return the exit status."""
    try:
        import hypothesis  # noqa: F401
    except ImportError:
        return _error("bouncer check needs hypothesis: pip install 'bouncer-verify[test]'")
    from verify.check import SUITES, check_integrator, load_callable

    if args.suite not in SUITES:
        return _error(f"unknown suite {args.suite!r}; choose one of {', '.join(SUITES)}")
    if args.suite == "energy" and args.step is None:
        return _error("suite 'energy' needs --step MODULE:FUNCTION")
    if args.max_examples is not None and args.max_examples < 1:
        return _error(f"--max-examples must be >= 1, got {args.max_examples}")
    if not 0 < args.k < float("inf"):
        return _error(f"-k must be a positive finite number, got {args.k}")
    try:
        flight_time = load_callable(args.target, search_cwd=True)
        step = None if args.step is None else load_callable(args.step, search_cwd=True)
    except ValueError as err:
        return _error(str(err))
    report = check_integrator(flight_time, step=step, suite=args.suite,
                              max_examples=args.max_examples, seed=args.seed, k=args.k)
    print(report)
    if report.ok:
        return 0
    print("smallest failing inputs (rerun them in Python):")
    for f in report.failures:
        fn = args.step if f.call == "step" else args.target
        print(f"  {f.property}: {fn} at phi={f.phi!r}, v={f.v!r}, eps={f.eps!r}")
    return 1


def build_parser() -> argparse.ArgumentParser:
    """A ``bouncer`` parser with only the ``check`` subcommand (for ``main``)."""
    parser = argparse.ArgumentParser(prog="bouncer")
    sub = parser.add_subparsers(dest="command", required=True)
    add_parser(sub)
    return parser


def main(argv=None) -> int:
    args = build_parser().parse_args(argv)
    return args.func(args)


if __name__ == "__main__":
    sys.exit(main())
