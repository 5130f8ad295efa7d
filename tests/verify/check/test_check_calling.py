"""verify.check.calling: misbehaving callables (raise, NaN, wrong shape) are failures of the
property that called them, not crashes of the checker.

Importing fastpath here is fine: only ``verify/`` itself must not import it.
"""

import math

import pytest

import fastpath
import verify
from verify.check import PROPERTIES


def _raises(phi, v, eps):
    raise RuntimeError("solver blew up")


def _nan(phi, v, eps):
    return math.nan


def _pair(phi, v, eps):
    return (1.0, 2.0)


@pytest.mark.slow
@pytest.mark.parametrize(
    "fn, text",
    [(_raises, "RuntimeError: solver blew up"), (_nan, "not finite"), (_pair, "not a real")],
)
def test_misbehaving_callables_are_failures_not_crashes(fn, text):
    report = verify.check_integrator(fn, suite="fast", max_examples=5)
    assert not report.ok
    assert {f.property for f in report.failures} == set(PROPERTIES) - {"energy"}
    assert text in str(report)


def test_misbehaving_step():
    report = verify.check_integrator(fastpath.flight_time, step=_pair, suite="energy",
                                     max_examples=5)
    assert "step must return (phi1, v1, tau)" in str(report)
