"""A check passes only when every property of its suite ran and held: a property with no
checked input, or a module that exits while importing, is never a pass, and nothing the user's
code does ends the caller's process."""

import re

import pytest

import verify
from verify.check import api
from verify.check.driver import _Outcome
from verify.check.report import CheckReport, PropertyResult


def _report(*statuses):
    results = tuple(PropertyResult(f"p{i}", s, 0 if s == "SKIP" else 5)
                    for i, s in enumerate(statuses))
    return CheckReport(target="m:f", step_target=None, suite="all", k=16.0, seed=0,
                       max_examples=5, results=results, worst_accuracy_k=None)


@pytest.mark.parametrize(
    "statuses, verdict",
    [
        (("PASS", "PASS"), "passed"),
        (("PASS", "SKIP"), "passed"),  # a property that needs a step, none given
        (("SKIP",), "inconclusive"),  # nothing ran
        ((), "inconclusive"),
        (("PASS", "INCONCLUSIVE"), "inconclusive"),
        (("PASS", "FAIL", "INCONCLUSIVE"), "failed"),
    ],
)
def test_verdict_needs_every_property_run_and_held(statuses, verdict):
    report = _report(*statuses)
    assert report.verdict == verdict
    assert report.ok == (verdict == "passed")


def test_a_property_with_no_checked_input_is_inconclusive(monkeypatch):
    monkeypatch.setattr(api, "run_property", lambda *args: _Outcome(inputs=0))
    report = verify.check_integrator(verify.flight_time, suite="holmes_limit")
    (result,) = report.results
    assert result.status == "INCONCLUSIVE" and "no input could be checked" in result.note
    assert report.verdict == "inconclusive" and not report.ok
    assert "not run" in str(report)
    with pytest.raises(AssertionError):
        verify.assert_integrator(verify.flight_time, suite="holmes_limit")


@pytest.mark.slow
@pytest.mark.parametrize(
    "ending, text",
    [("import sys\nsys.exit(0)\n", "called sys.exit(0)"),
     ("import os\nos._exit(0)\n", "died (exit code 0) while importing")],
)
def test_a_spec_whose_module_exits_while_importing_raises_value_error(ending, text, tmp_path,
                                                                      monkeypatch):
    """The worker process imports the spec, so neither exit ends this (the caller's) process."""
    (tmp_path / "script_style.py").write_text(
        "def flight_time(phi, v, eps):\n    return 2.0 * v\n" + ending)
    monkeypatch.chdir(tmp_path)
    for check in (verify.check_integrator, verify.assert_integrator):
        with pytest.raises(ValueError, match=re.escape(text)):
            check("script_style:flight_time", suite="fixed_points")


def test_an_in_process_callable_that_exits_fails_without_ending_the_caller():
    """A lambda cannot be pickled, so it runs in this process: its sys.exit() is a failure."""
    def exits(phi, v, eps):
        raise SystemExit(0)

    report = verify.check_integrator(lambda phi, v, eps: exits(phi, v, eps),
                                     suite="fixed_points", max_examples=3)
    assert "IN-PROCESS" in str(report)
    (failure,) = report.failures
    assert "SystemExit" in str(failure.obtained)
    assert report.verdict == "failed"
