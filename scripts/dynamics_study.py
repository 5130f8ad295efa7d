"""Compute the full dynamics study (``reports.paper.studies.dynamics_study.FULL``) and write it to
``reports/paper/studies/dynamics_study.json`` (atomically; the package installs it), which the
report's dynamics section reads and re-checks a sample of.

Cost (2 cores shared with other work): about 25 minutes, mostly the multiprecision Greene
crossings (periods 610 to 1597 of six curves, ~11 minutes), the certified high-period orbits
(period 233 at ~350 digits, about a minute each), the Lyapunov ensembles (64 orbits x 10^6
collisions, three times) and the accelerator search. Deterministic for the fixed random seed of
the study.

Run: ``python scripts/dynamics_study.py [--out PATH] [--quick]``.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from reports.paper.studies.dynamics_study import COMMITTED, FULL, QUICK, run
from reports.runs.rundir import write_atomic

DEFAULT = COMMITTED


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, default=DEFAULT, help="the JSON file to write")
    parser.add_argument("--quick", action="store_true", help="the small sizes (seconds)")
    args = parser.parse_args(argv)
    study = run(QUICK if args.quick else FULL, echo=lambda s: print(s, flush=True))
    args.out.parent.mkdir(parents=True, exist_ok=True)
    write_atomic(args.out, json.dumps(study, indent=1) + "\n")
    print(f"wrote {args.out} ({study['seconds']:.0f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
