"""verify.check.driver: the same seed draws the same inputs and gives the same report.

Importing fastpath here is fine: only ``verify/`` itself must not import it.
"""

import pytest

import verify
from examples import planted_defects


@pytest.mark.parametrize("examples", [5, pytest.param(40, marks=pytest.mark.slow)])
def test_same_seed_same_report(examples):
    a = verify.check_integrator(planted_defects.naive_gap_flight_time, suite="no_overstep",
                                seed=3, max_examples=examples)
    b = verify.check_integrator(planted_defects.naive_gap_flight_time, suite="no_overstep",
                                seed=3, max_examples=examples)
    assert a.failures == b.failures
    assert [r.failed for r in a.results] == [r.failed for r in b.results]
