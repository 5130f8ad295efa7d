"""verify.check.properties: fastpath passes every property; each planted defect is caught
by the property that targets them, with the right input and size.

Importing fastpath here is fine: only ``verify/`` itself must not import it.
"""

import math

import pytest

import fastpath
import verify
from examples import planted_defects
from verify.check import PROPERTIES


@pytest.fixture(scope="module")
def fastpath_report():
    return verify.check_integrator(fastpath.flight_time, step=fastpath.step)


@pytest.mark.slow
def test_fastpath_passes_every_property(fastpath_report):
    report = fastpath_report
    assert report.ok, str(report)
    assert [r.name for r in report.results] == list(PROPERTIES)
    for r in report.results:
        assert r.status == "PASS" and r.inputs >= 50, str(report)
    assert report.failures == []
    assert report.worst_accuracy_k is not None and report.worst_accuracy_k <= 16
    assert "all properties hold" in str(report)


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(planted_defects.DEFECTS))
def test_planted_defect_is_caught_by_its_property(name):
    fn, prop = planted_defects.DEFECTS[name]
    report = verify.check_integrator(fn, suite=prop)
    assert not report.ok
    (failure,) = report.failures
    assert failure.property == prop
    assert f"FAIL  {prop}" in str(report)
    # the failing input is a valid departure and the failure says what went wrong
    assert verify.strategies.exact_w0(*failure.input) > 0
    assert isinstance(failure.obtained, float) and isinstance(failure.expected, float)
    assert failure.obtained != failure.expected and failure.message


@pytest.mark.slow
def test_holmes_flight_time_is_exact_only_at_fixed_points():
    fn = planted_defects.holmes_flight_time
    assert verify.check_integrator(fn, suite="fixed_points").ok
    report = verify.check_integrator(fn, suite="fast")
    assert {f.property for f in report.failures} >= {"accuracy", "no_overstep"}


@pytest.mark.slow
def test_scanner_skips_close_root_pairs_for_eps_above_one():
    report = verify.check_integrator(planted_defects.scanner_flight_time, suite="no_overstep")
    (failure,) = report.failures
    assert failure.eps > 1
    assert failure.obtained > failure.expected  # it lands at a later root
    assert "skipped" in failure.message
    # only the near-grazing inputs (close root pairs) catch it, the random ones do not
    assert "random 0/" in report.result("no_overstep").note
    assert verify.check_integrator(planted_defects.scanner_flight_time, suite="accuracy").ok


@pytest.mark.slow
def test_naive_gap_fails_accuracy_by_a_large_factor_at_small_departure_speed():
    report = verify.check_integrator(planted_defects.naive_gap_flight_time, suite="accuracy")
    assert report.worst_accuracy_k > 1e6
    phi, v, eps = report.worst_accuracy_input
    assert verify.strategies.exact_w0(phi, v, eps) < 1e-6
    # elsewhere it is fine: fixed points, the Holmes limit
    for prop in ("fixed_points", "holmes_limit"):
        assert verify.check_integrator(planted_defects.naive_gap_flight_time, suite=prop).ok


def test_bias_of_1e_9_is_caught_with_its_size():
    report = verify.check_integrator(planted_defects.biased_flight_time, suite="accuracy")
    (failure,) = report.failures
    assert failure.obtained / failure.expected - 1 == pytest.approx(1e-9, rel=1e-3)


def _holmes_step(phi, v, eps):
    """A step that uses the Holmes flight time: energy bookkeeping fails."""
    tau = 2.0 * v
    return (phi + tau) % (2 * math.pi), tau - v - 2 * eps * math.sin(phi + tau), tau


def _departure_plate_step(phi, v, eps):
    """Impact with the plate velocity at departure instead of at impact: exact at the fixed
    points themselves, but the Jacobian there is wrong."""
    phi1, v1, tau = fastpath.step(phi, v, eps)
    return phi1, tau - v - 2 * eps * math.sin(phi), tau


@pytest.mark.slow
def test_step_defects():
    report = verify.check_integrator(fastpath.flight_time, step=_holmes_step, suite="energy")
    assert [f.property for f in report.failures] == ["energy"]
    assert report.failures[0].call == "step"
    report = verify.check_integrator(
        fastpath.flight_time, step=_departure_plate_step, suite="fixed_points"
    )
    (failure,) = report.failures
    assert "Jacobian" in failure.message
    m = round(failure.v / math.pi)
    assert failure.expected == ((1.0, 2.0), (-2 * failure.eps, 1 - 4 * failure.eps))
    assert m >= 1
