"""The dissipative sub-table of the hard-case section (``hard_case_table.dissipative_*``)."""

import math

import pytest
from mpmath import mp

from reports.precision.hard_case_table import (
    DissipativeRow,
    _passed_a_root,
    dissipative_case_markdown,
    dissipative_rows,
)
from verify.hard_cases import CHATTERING_GRAZES, DISSIPATIVE_CASES

ONE_PER_CLASS_AND_PHYSICS = {}
for _case in DISSIPATIVE_CASES:
    ONE_PER_CLASS_AND_PHYSICS.setdefault((_case.kind, _case.drag, _case.drag_law), _case)
SAMPLE = list(ONE_PER_CLASS_AND_PHYSICS.values())


def _case(case_id):
    return next(c for c in DISSIPATIVE_CASES if c.id == case_id)


@pytest.mark.slow
def test_rows_and_rendering():
    rows = dissipative_rows(SAMPLE)
    md = dissipative_case_markdown(rows)
    assert md.startswith("### Dissipative hard cases")
    for row in rows:
        case = row.case
        line = next(x for x in md.splitlines() if x.startswith(f"| {case.id} |"))
        cells = [x.strip() for x in line.strip("|").split("|")]
        assert len(cells) == 12 and cells[1] == case.kind
        assert float(cells[2]) == case.phi and float(cells[3]) == case.v
        assert cells[5] == ("elastic" if case.drag == 0 else f"{case.drag_law} {case.drag:g}")
        assert row.tau is not None and float(row.tau) == case.tau  # the table's certified tau
        assert abs(float(cells[6]) / case.tau - 1) < 1e-9
        assert cells[11] == row.status and not row.missed
        if row.status == "CONVERGED":
            assert float(cells[9]) == float(f"{row.units:.2g}") and row.units <= 16
    for kind in {c.kind for c in SAMPLE}:
        assert any(x.startswith(f"| {kind} | ") for x in md.splitlines())
    # departures at rest: fastpath.flight takes w0 > 0 only, and says so
    assert all(r.status == "NOT_DEPARTING" for r in rows if r.case.kind == "w0=0 departure")


def test_undecidable_and_missed_rows_render():
    case = CHATTERING_GRAZES[0]
    rows = [DissipativeRow(case, None, None, 0.5, math.nan, 1.0, 3, "UNCERTAIN", math.nan, False),
            DissipativeRow(case, mp.mpf(case.tau), mp.mpf(case.tau), 0.1, 11.0, 9.0, 4,
                           "CONVERGED", 1e9, True)]
    md = dissipative_case_markdown(rows)
    assert "| undecidable |" in md and "| **missed** |" in md
    summary = next(x for x in md.splitlines() if x.startswith("| chattering-graze | 2 |"))
    assert summary.split("|")[3:8] == [" 1 ", " 1 ", " 0 ", " 1 ", " 1e+09 "]


def test_missed_means_past_a_later_root():
    """Dip clearance -1e-6: roots at ~0.0649 and ~0.0826 around the dip at 0.0740, then the gap
    stays positive up to the landing ~3.6. Inside the pair is wrong but not past a later root;
    past the pair's second root, or at the far landing, is a miss."""
    case = _case("chatter-graze-elastic-eps=1.5-w=0.001-c=-1e-6")
    upper = mp.mpf(case.tau) * (1 + mp.mpf(10) ** -40)
    assert not _passed_a_root(case, upper, case.tau)
    assert not _passed_a_root(case, upper, 0.07)
    assert _passed_a_root(case, upper, 0.1)
    assert _passed_a_root(case, upper, 1.0)
