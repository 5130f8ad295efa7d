"""verify.check.worker and the budget: a hang, an exit() or a segfault of the user's callable
is a finding that names the input, never a stuck or dead checker; a correct but slow callable
passes, or is INCONCLUSIVE (not failed) when the budget runs out first.

The fault injectors live in examples/planted_defects.py. Fast tests use small timeouts and
budgets; the ``slow`` ones judge each injector with the defaults (call timeout 5 s, budget
120 s) and check that the verdict comes within the budget.
"""

import math
import time

import pytest

import verify
from examples import planted_defects as pd
from verify.strategies import exact_w0


def _timed(fn, **kwargs):
    t0 = time.monotonic()
    report = verify.check_integrator(fn, **kwargs)
    return report, time.monotonic() - t0


@pytest.mark.slow
def test_a_hang_is_a_failure_naming_the_input():
    report, wall = _timed(pd.hanging_flight_time, suite="accuracy", call_timeout=0.5)
    (failure,) = report.failures
    assert report.verdict == "failed"
    assert exact_w0(*failure.input) < pd.HANG_BELOW_W0  # the input it hangs on
    assert failure.obtained == "no answer within 0.5 s"
    assert "did not return within the call timeout" in failure.message
    assert "stopped at the first timeout or crash" in report.result("accuracy").note
    assert wall < 20, wall


@pytest.mark.slow
@pytest.mark.parametrize(
    "fn, suite, death",
    [(pd.exiting_flight_time, "accuracy", "exit code 3"),
     (pd.segfault_flight_time, "holmes_limit", "signal SIGSEGV")],
)
def test_a_crash_is_a_failure_naming_the_input(fn, suite, death):
    report = verify.check_integrator(fn, suite=suite)
    (failure,) = report.failures
    assert failure.obtained == f"the worker process died ({death})"
    assert "crashed the worker process" in failure.message
    if fn is pd.segfault_flight_time:
        assert failure.v > 1e3
    else:
        assert exact_w0(*failure.input) < pd.HANG_BELOW_W0


@pytest.mark.slow
def test_the_worker_restarts_after_a_crash():
    """holmes_limit segfaults (v > 1e3); the properties after it run on a fresh worker."""
    report = verify.check_integrator(pd.segfault_flight_time, suite="fast", max_examples=5)
    assert [f.property for f in report.failures] == ["holmes_limit"]
    assert report.result("reversibility").status == "PASS"
    assert report.result("reversibility").inputs > 0
    assert "1 timeouts or crashes, 1 restarts" in str(report)


@pytest.mark.slow
def test_slow_but_right_is_inconclusive_when_the_budget_runs_out():
    report, wall = _timed(pd.slow_flight_time, suite="fast", budget=4.0)
    assert report.verdict == "inconclusive" and not report.ok and report.failures == []
    statuses = {r.status for r in report.results}
    assert "INCONCLUSIVE" in statuses and "FAIL" not in statuses
    cut = [r for r in report.results if r.status == "INCONCLUSIVE"][0]
    assert cut.inputs < 20
    assert f"{cut.inputs} of 20 inputs when the budget ran out" in str(report)
    assert "inconclusive: the budget of 4 s ran out" in str(report)
    with pytest.raises(AssertionError, match="inconclusive"):
        verify.assert_integrator(pd.slow_flight_time, suite="fast", budget=1.5)
    assert wall < 4.0 + 10, wall  # the budget plus stopping the worker and the report


@pytest.mark.slow
def test_a_hang_longer_than_the_budget_is_cut_by_the_budget():
    report, wall = _timed(pd.hanging_flight_time, suite="accuracy", call_timeout=1e6,
                          budget=3.0)
    assert report.verdict == "inconclusive"
    assert wall < 3.0 + 10, wall


def test_unpicklable_callable_runs_in_process_with_a_note():
    report = verify.check_integrator(lambda phi, v, eps: pd.biased_flight_time(phi, v, eps),
                                     suite="accuracy", max_examples=5)
    assert "IN-PROCESS: cannot pickle" in str(report)
    assert [f.property for f in report.failures] == ["accuracy"]


@pytest.mark.slow
def test_spec_strings_are_loaded_by_the_worker():
    report = verify.check_integrator("examples/planted_defects.py:exiting_flight_time",
                                     suite="accuracy", max_examples=20)
    assert report.target == "examples/planted_defects.py:exiting_flight_time"
    assert "each call in a worker process" in str(report)
    assert report.failures[0].obtained == "the worker process died (exit code 3)"


def test_bad_budget_and_timeout():
    for kwargs in ({"budget": 0}, {"budget": -1.0}, {"budget": math.nan},
                   {"call_timeout": 0}, {"call_timeout": "5"}):
        with pytest.raises(ValueError, match=next(iter(kwargs))):
            verify.check_integrator(pd.holmes_flight_time, **kwargs)


# ------------------------------------------------------------ the defaults, measured (slow)

DEFAULT_BUDGET = 120.0


@pytest.mark.slow
@pytest.mark.parametrize(
    "fn, verdict, failing",
    [
        (pd.hanging_flight_time, "failed", "did not return within the call timeout of 5 s"),
        (pd.exiting_flight_time, "failed", "crashed the worker process"),
        (pd.segfault_flight_time, "failed", "crashed the worker process"),
        (pd.scanner_flight_time, "failed", "the first collision was skipped"),
        (pd.slow_flight_time, "passed", None),
    ],
    ids=["hanging", "exiting", "segfault", "grazing-blind scanner", "slow but right"],
)
def test_judged_within_the_default_budget(fn, verdict, failing):
    report, wall = _timed(fn)
    print(f"{fn.__name__}: {report.verdict} in {wall:.1f} s")
    assert report.verdict == verdict, str(report)
    if failing:
        assert any(failing in f.message for f in report.failures), str(report)
    assert wall < DEFAULT_BUDGET + 10, wall
