"""``bouncer report``: speed, work-precision, hard cases, the paper's figures, physics checks."""

from pathlib import Path

from reports.cli.run import count
from reports.precision.methods import method_from_callable
from reports.report import DEFAULT_OUT, build_report
from reports.runs import rundir
from reports.runs.recheck import load_run
from verify.check import load_callable


def report_command(args):
    """Entry point of ``bouncer report``."""
    if args.particles is not None and args.particles < 1:
        raise ValueError(f"--particles must be >= 1, got {args.particles}")
    for run_dir in args.include_run:  # refused now, not after the report's computations
        if not (Path(run_dir) / rundir.MANIFEST).is_file():
            raise ValueError(f"--include-run {run_dir}: not a run directory (no manifest.json)")
        load_run(run_dir)
    compare = []
    if args.compare:
        compare = [method_from_callable(spec, load_callable(spec)) for spec in args.compare]
    build_report(args.out, particles=args.particles, quick=args.quick, compare=compare,
                 include_runs=args.include_run)
    return 0


def add_parser(subparsers):
    report = subparsers.add_parser(
        "report", help="speed, work-precision, hard cases, the paper's figures, physics checks")
    report.add_argument("--out", default=DEFAULT_OUT, help=f"output folder (default {DEFAULT_OUT})")
    report.add_argument("--particles", type=count, default=None,
                        help="particles per curve of the ensemble runs (default: 10^6; the"
                        " whole report then takes about 11 minutes on 2 cores)")
    report.add_argument("--quick", action="store_true", help="tiny sizes, for a smoke test")
    report.add_argument("--compare", action="append", default=[], metavar="MODULE:FUNCTION",
                        help="add your flight_time(phi, v, eps) to the comparison (repeatable)")
    report.add_argument("--include-run", action="append", default=[], metavar="RUN_DIR",
                        help="add a finished run's survival figure and verification summary")
    report.set_defaults(func=report_command)
