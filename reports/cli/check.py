"""``bouncer check MODULE:FUNCTION [--step MODULE:FUNCTION] [--suite NAME]``.

Runs ``verify.check_integrator`` on a user's flight-time function (and step function) from the
shell. The callables run in a worker process (the module is imported there, never in this
process), each call under ``--call-timeout`` and the whole check under ``--budget``; progress
goes to stderr. Exit status: 0 when every property ran and held, 1 when one fails (the report,
then the smallest failing input of each failed property) or the check did not finish (one
line), 2 for bad input (a module that raises, exits or crashes while importing, a name that is
not callable, an unknown suite: one line ``bouncer: error: ...``), 3 when a property did not
run to the end and none failed (inconclusive: the budget ran out, the report gives the counts
reached; or no input could be checked).

Wire it into the ``bouncer`` parser with ``add_parser(subparsers)``; ``main`` runs it alone
(``python -m reports.cli.check check MODULE:FUNCTION``).

The checked code runs in its own process group, with its output kept from the terminal; it is
killed with everything it started however the check ends. A module that hangs while it is
imported is bad input after ``--import-timeout`` (exit 2). A signal it sends to this process
fails the property that made the call; SIGTERM or SIGHUP from elsewhere stops the check and its
worker (one line, exit status 128 + the signal: 143, 129), Ctrl-C likewise (exit 130).
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
    check.add_argument("--call-timeout", type=float, default=5.0, metavar="SECONDS",
                       help="longest one call may take; a call that takes longer is a failure "
                       "of its property (default 5)")
    check.add_argument("--budget", type=float, default=120.0, metavar="SECONDS",
                       help="time for the whole check; properties not finished by then are "
                       "inconclusive, exit status 3 (default 120)")
    check.add_argument("--import-timeout", type=float, default=60.0, metavar="SECONDS",
                       help="longest the import of MODULE may take; a module that takes "
                       "longer (it hangs, or waits for input) is bad input, exit status 2 "
                       "(default 60)")
    check.add_argument("--no-progress", action="store_true",
                       help="no progress bar on stderr")
    check.set_defaults(func=check_command)
    return check


def _error(message: str) -> int:
    from reports.cli import MAX_LINE
    from reports.runs.echo import clip, plain_text

    print(clip(plain_text(f"bouncer: error: {message}".replace("\n", " ")), MAX_LINE),
          file=sys.stderr)
    return 2


def check_command(args) -> int:
    """Run the check described by parsed ``args``; print the report; return the exit status."""
    try:
        import hypothesis  # noqa: F401
    except ImportError:
        return _error("bouncer check needs hypothesis: pip install 'bouncer-verify[test]'")
    from verify.check import SUITES, check_integrator
    from verify.check.calling import one_line
    from verify.check.signals import Terminated, watch_signals

    if args.suite not in SUITES:
        return _error(f"unknown suite {args.suite!r}; choose one of {', '.join(SUITES)}")
    if args.suite == "energy" and args.step is None:
        return _error("suite 'energy' needs --step MODULE:FUNCTION")
    if args.max_examples is not None and args.max_examples < 1:
        return _error(f"--max-examples must be >= 1, got {args.max_examples}")
    if not 0 < args.k < float("inf"):
        return _error(f"-k must be a positive finite number, got {args.k}")
    for option, value in (("--call-timeout", args.call_timeout), ("--budget", args.budget),
                          ("--import-timeout", args.import_timeout)):
        if not value > 0:
            return _error(f"{option} must be a positive number of seconds, got {value}")
    # the worker process imports the user's module (never this process: a module that exits
    # or crashes while importing must not end the check with its own status); a signal the
    # checked code sends to this process stops its worker, one from elsewhere ends the check
    bar = None if args.no_progress else _ProgressBar()
    try:
        with watch_signals():
            report = check_integrator(args.target, step=args.step, suite=args.suite,
                                      max_examples=args.max_examples, seed=args.seed, k=args.k,
                                      call_timeout=args.call_timeout, budget=args.budget,
                                      progress=bar, import_timeout=args.import_timeout)
    except ValueError as err:
        return _error(str(err))
    except Terminated as stop:
        print(f"bouncer: {stop}: the check was stopped with its worker process",
              file=sys.stderr)
        return 128 + stop.signum
    except Exception as err:  # noqa: BLE001 - no report: the check did not run, not a pass
        print(f"bouncer: error: the check did not finish: {one_line(err)}", file=sys.stderr)
        return 1
    finally:
        if bar is not None:
            bar.close()
    print(report)
    if report.ok:
        return 0
    if report.verdict == "inconclusive":
        return 3
    print("smallest failing inputs (rerun them in Python):")
    for f in report.failures:
        fn = args.step if f.call == "step" else args.target
        print(f"  {f.property}: {fn} at phi={f.phi!r}, v={f.v!r}, eps={f.eps!r}")
    return 1


class _ProgressBar:
    """``progress(property, done, planned)`` for ``check_integrator`` on stderr: a tqdm bar per
    property on a terminal, else one line as each property starts."""

    def __init__(self) -> None:
        self.bar = None
        self.name = None
        self.tty = sys.stderr.isatty()

    def __call__(self, name: str, done: int, planned: int) -> None:
        from tqdm import tqdm

        if name != self.name:
            self.close()
            self.name = name
            if not self.tty:
                print(f"bouncer check: {name} ({planned} inputs) ...", file=sys.stderr,
                      flush=True)
                return
            self.bar = tqdm(total=planned, desc=f"{name:<13}", unit=" inputs", file=sys.stderr)
        if self.bar is not None:
            self.bar.update(done - self.bar.n)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()
            self.bar = None


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
