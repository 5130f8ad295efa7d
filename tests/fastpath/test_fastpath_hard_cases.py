"""The hard-case table (``hard_cases.HARD_CASES``) against ``verify``, K*kappa*u tolerance."""

import pytest
from fastpath_figures import record
from fastpath_reference import assert_flight_ok, flight_outcome
from fastpath_tolerances import K, exact_w0
from hard_cases import HARD_CASES


def _cases():
    for case in HARD_CASES:
        yield pytest.param(*case.values, id=case.id)


@pytest.mark.parametrize("phi, v, eps, reason", list(_cases()))
def test_hard_case_against_verify(phi, v, eps, reason):
    assert exact_w0(phi, v, eps) > 0, f"table entry is not a departure ({reason})"
    assert_flight_ok(phi, v, eps)


def test_hard_case_worst_error_figure():
    """Worst error over the whole table in units of kappa*u (outcomes are cached)."""
    rows = []
    for case in HARD_CASES:
        phi, v, eps, _ = case.values
        out = flight_outcome(phi, v, eps)
        rows.append((case.id, out))
    judged = [(cid, out) for cid, out in rows if out.units is not None]
    uncertain = [cid for cid, out in rows if out.status in ("UNCERTAIN", "MAX_ITERATIONS")]
    worst_id, worst = max(judged, key=lambda row: row[1].units)
    record("hard cases: worst tau error [kappa*u]", f"{worst.units:.3g} at {worst_id} (K = {K})")
    record("hard cases: UNCERTAIN/MAX_ITERATIONS", f"{len(uncertain)} of {len(rows)} {uncertain}")
    bad = [f"{cid}: {out.problem}" for cid, out in rows if out.problem is not None]
    assert not bad, "\n".join(bad)
    assert worst.units <= K
