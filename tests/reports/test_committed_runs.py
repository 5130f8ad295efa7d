"""Every run committed under docs/report/ passes ``bouncer verify`` with this code.

The report's claims and the README's figures are read from these runs; ``bouncer verify``
re-derives their sampled collisions with ``fastpath.step`` bit for bit. A fastpath change that
moves a last bit makes this fail, and the runs must then be redone (or the change made
bit-identical).
"""

from pathlib import Path

import pytest

from reports.runs.recheck import recheck

ROOT = Path(__file__).resolve().parents[2]
RUNS = sorted(p.parent for p in (ROOT / "docs" / "report").glob("**/manifest.json"))


def test_there_are_committed_runs():
    assert len(RUNS) >= 4, RUNS


@pytest.mark.slow
@pytest.mark.parametrize("run_dir", RUNS, ids=[p.name for p in RUNS])
def test_committed_run_passes_bouncer_verify(run_dir):
    ok, lines = recheck(run_dir)
    assert ok, "\n".join(lines[-5:])
