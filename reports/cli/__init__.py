"""The ``bouncer`` command. Exit status: 0 ok, 1 failure, 2 bad input or a filesystem fault
(one-line message naming the path), 3 inconclusive (``check``), 130 interrupted (Ctrl-C, at any
moment; a run says how to resume). docs/runs.md has the table for every subcommand.

    bouncer --version

    bouncer demo [--eps E] [--collisions N] [--sample S] [--seed S]
    bouncer scenes
    bouncer run SCENE_OR_FILE [--particles N] [--seed S] [--out DIR] [--threads K]
                              [--resume] [--force] [--quiet] [--scheduler ADDRESS]
    bouncer sweep [SCENE_OR_FILE] [--eps LO HI N] [--centre LO HI N] [--width LO HI N]
                  [--n-star N] [--particles N] [--seed S] [--verify-samples N] [--out DIR]
                  [--threads K] [--scheduler ADDRESS] [--force] [--quiet]
    bouncer plot RUN_DIR [--out FILE] [--fit MODEL --window LO HI [--clock C] [--curve NAME]]
    bouncer fit PATH... [--clock collisions|time] [--json] [--out DIR]
    bouncer verify RUN_DIR
    bouncer check MODULE:FUNCTION [--step MODULE:FUNCTION] [--suite NAME]
    bouncer bench [--collisions N] [--repeats R] [--particles N]
    bouncer report [--particles N] [--out DIR] [--quick] [--compare MODULE:FUNCTION]
                   [--include-run RUN_DIR]
    bouncer orbits PHI V --eps E [--period P] [--winding M] [--shift L] [--model M]
                   [--certify] [--dps D] [--json]
"""

import signal
import sys

SUBCOMMANDS = ("demo", "scenes", "run", "sweep", "plot", "fit", "verify", "report", "check",
               "bench", "orbits")


def version():
    """The installed distribution's version (``importlib.metadata``); the source tree's
    pyproject.toml is not read, so a checkout that is not installed says so."""
    from importlib import metadata

    try:
        return metadata.version("bouncer-verify")
    except metadata.PackageNotFoundError:
        return "unknown (not installed: pip install -e .)"


def build_parser():
    import argparse
    import importlib

    class Parser(argparse.ArgumentParser):
        def error(self, message):  # one line (argparse prints the usage first), exit 2
            self.exit(2, f"{self.prog}: error: {message} (see {self.prog} --help)\n")

    parser = Parser(prog="bouncer", description="Validated numerics for the bouncer model.")
    parser.add_argument("--version", action="version", version=f"%(prog)s {version()}",
                        help="print the version of bouncer-verify and exit")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND",
                                help="what to do (bouncer COMMAND --help: its options)")
    for name in SUBCOMMANDS:
        importlib.import_module(f"reports.cli.{name}").add_parser(sub)
    return parser


def main(argv=None):
    """The ``bouncer`` command; returns the exit status. Everything, the imports of numba,
    scipy and the rest included, runs under the handlers below: a Ctrl-C at any moment is one
    line and exit status 130."""
    argv = sys.argv[1:] if argv is None else [str(a) for a in argv]
    try:
        mask = _block_for_check(argv)
        try:
            return _main(argv)
        finally:
            if mask is not None:
                signal.pthread_sigmask(signal.SIG_SETMASK, mask)
    except KeyboardInterrupt:
        print("bouncer: interrupted", file=sys.stderr)
        return 130


CHECK_SIGNALS = tuple(getattr(signal, name) for name in ("SIGINT", "SIGTERM", "SIGHUP")
                      if hasattr(signal, name))
MAX_LINE = 600  # characters of an error line (the values in it are clipped where they arise)


def _block_for_check(argv):
    """``bouncer check`` takes SIGINT, SIGTERM and SIGHUP in one thread that learns who sent
    them (``verify.check.signals``): they are blocked from the start, before the imports,
    so that every thread the imports start (numba's, a BLAS's) inherits the block and none
    takes a signal in its place. Returns the mask to restore, or None."""
    if argv[:1] != ["check"] or not hasattr(signal, "sigtimedwait"):
        return None
    return signal.pthread_sigmask(signal.SIG_BLOCK, CHECK_SIGNALS)


def _main(argv):
    from reports.runs.echo import clip, plain_text
    from reports.runs.rundir import RunFailed, RunInterrupted, os_error_text

    def say(line):  # one line, plain numbers, of bounded length
        print(clip(plain_text(str(line).replace("\n", " ")), MAX_LINE), file=sys.stderr)

    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return args.func(args)
    except ValueError as err:
        say(f"bouncer: error: {err}")
        return 2
    except RunFailed as err:
        say(f"bouncer: run failed: {err}")
        return 1
    except OSError as err:
        say(f"bouncer: error: {os_error_text(err)}")
        return 2
    except RunInterrupted as err:
        resume = getattr(args, "resume_command", None)
        hint = f"; continue with: {resume(err)}" if resume else ""
        print(f"bouncer: {err}{hint}", file=sys.stderr)
        return 130
