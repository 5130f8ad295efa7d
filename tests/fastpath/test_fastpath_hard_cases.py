"""The hard-case table (``hard_cases.HARD_CASES``) against ``verify``, K*kappa*u tolerance."""

import pytest
from fastpath_figures import record
from fastpath_reference import assert_flight_ok, flight_outcome
from fastpath_tolerances import K, exact_w0
from hard_cases import HARD_CASES

# fastpath answers UNCERTAIN here although float64 could place the root: at phi = -x, v = x,
# eps = 1 (a triple root, DESIGN fact 11) with x = 1e-6 the exact gap at the stop t = 6.7e-7 is
# ~4e-26 while the solver's error bound for d is larger, so it declines. An UNCERTAIN is honest
# (verify settles it) but needless; strict xfail, so tightening the bound shows up here.
CONSERVATIVE_UNCERTAIN = {"triple-x=1e-06-eps=1"}


def _cases():
    for case in HARD_CASES:
        marks = [pytest.mark.xfail(strict=True, reason="conservative UNCERTAIN (see above)")] \
            if case.id in CONSERVATIVE_UNCERTAIN else []
        yield pytest.param(*case.values, marks=marks, id=case.id)


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
    bad = [f"{cid}: {out.problem}" for cid, out in rows
           if out.problem is not None and cid not in CONSERVATIVE_UNCERTAIN]
    assert all(flight_outcome(*case.values[:3]).status == "UNCERTAIN"
               for case in HARD_CASES if case.id in CONSERVATIVE_UNCERTAIN)
    assert not bad, "\n".join(bad)
    assert worst.units <= K
