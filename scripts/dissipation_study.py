"""Compute the full dissipation study (``reports.paper.studies.dissipation_study``, the sizes of
``STUDY[False]``) and write it to ``reports/paper/studies/dissipation_study.json`` (atomically;
the package installs it), which the report reads and re-checks part of.

Cost: about 3 minutes on 2 cores (1000 orbits of 10^4 collisions at eps = 2 for each of 11
physics, mostly the paper's lower-bound steps). Deterministic: fixed starts, 64 particle blocks
whatever the number of threads.

Run: ``python scripts/dissipation_study.py [--out PATH]``.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from reports.paper.studies.dissipation_study import (
    COMMITTED,
    _finished_study,
    _study_moments,
    to_json,
)
from reports.runs.rundir import write_atomic


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, default=COMMITTED, help="the JSON file to write")
    args = parser.parse_args(argv)
    study = _finished_study(False, *_study_moments(False))
    args.out.parent.mkdir(parents=True, exist_ok=True)
    write_atomic(args.out, to_json(study))
    print(f"wrote {args.out} ({study.seconds:.0f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
