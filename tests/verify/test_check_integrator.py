"""verify.check_integrator: fastpath passes every property; the planted defects are caught by
the property that targets them; misbehaving callables are failures, not crashes.

Importing fastpath here is fine: only ``verify/`` itself must not import it.
"""

import math

import pytest

import fastpath
import verify
from examples import planted_defects
from verify.check import PROPERTIES, SUITES


@pytest.fixture(scope="module")
def fastpath_report():
    return verify.check_integrator(fastpath.flight_time, step=fastpath.step)


def test_fastpath_passes_every_property(fastpath_report):
    report = fastpath_report
    assert report.ok, str(report)
    assert [r.name for r in report.results] == list(PROPERTIES)
    for r in report.results:
        assert r.status == "PASS" and r.inputs >= 50, str(report)
    assert report.failures == []
    assert report.worst_accuracy_k is not None and report.worst_accuracy_k <= 16
    assert "all properties hold" in str(report)


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


def test_holmes_flight_time_is_exact_only_at_fixed_points():
    fn = planted_defects.holmes_flight_time
    assert verify.check_integrator(fn, suite="fixed_points").ok
    report = verify.check_integrator(fn, suite="fast")
    assert {f.property for f in report.failures} >= {"accuracy", "no_overstep"}


def test_scanner_skips_close_root_pairs_for_eps_above_one():
    report = verify.check_integrator(planted_defects.scanner_flight_time, suite="no_overstep")
    (failure,) = report.failures
    assert failure.eps > 1
    assert failure.obtained > failure.expected  # it lands at a later root
    assert "skipped" in failure.message
    # only the near-grazing inputs (close root pairs) catch it, the random ones do not
    assert "random 0/" in report.result("no_overstep").note
    assert verify.check_integrator(planted_defects.scanner_flight_time, suite="accuracy").ok


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


def test_assert_integrator():
    with pytest.raises(AssertionError) as err:
        verify.assert_integrator(planted_defects.biased_flight_time, suite="fixed_points")
    assert "FAIL  fixed_points" in str(err.value)
    assert "fixed_points: flight_time(phi=0.0" in str(err.value)
    report = verify.assert_integrator(fastpath.flight_time, suite="holmes_limit")
    assert report.ok


def _holmes_step(phi, v, eps):
    """A step that uses the Holmes flight time: energy bookkeeping fails."""
    tau = 2.0 * v
    return (phi + tau) % (2 * math.pi), tau - v - 2 * eps * math.sin(phi + tau), tau


def _departure_plate_step(phi, v, eps):
    """Impact with the plate velocity at departure instead of at impact: exact at the fixed
    points themselves, but the Jacobian there is wrong."""
    phi1, v1, tau = fastpath.step(phi, v, eps)
    return phi1, tau - v - 2 * eps * math.sin(phi), tau


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


def _raises(phi, v, eps):
    raise RuntimeError("solver blew up")


def _nan(phi, v, eps):
    return math.nan


def _pair(phi, v, eps):
    return (1.0, 2.0)


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


def test_same_seed_same_report():
    a = verify.check_integrator(planted_defects.naive_gap_flight_time, suite="no_overstep",
                                seed=3, max_examples=40)
    b = verify.check_integrator(planted_defects.naive_gap_flight_time, suite="no_overstep",
                                seed=3, max_examples=40)
    assert a.failures == b.failures
    assert [r.failed for r in a.results] == [r.failed for r in b.results]


def test_bad_arguments():
    with pytest.raises(ValueError) as err:
        verify.check_integrator(fastpath.flight_time, suite="everything")
    for suite in SUITES:
        assert suite in str(err.value)
    with pytest.raises(ValueError, match="needs a step"):
        verify.check_integrator(fastpath.flight_time, suite="energy")
    with pytest.raises(ValueError, match="max_examples"):
        verify.check_integrator(fastpath.flight_time, max_examples=0)
    with pytest.raises(ValueError, match="k must be"):
        verify.check_integrator(fastpath.flight_time, k=-1)
    with pytest.raises(ValueError, match="callable"):
        verify.check_integrator(3.0)


def test_energy_is_skipped_without_step():
    report = verify.check_integrator(fastpath.flight_time, suite="fast", max_examples=3)
    assert report.result("energy").status == "SKIP"
    assert report.ok


def test_load_callable(tmp_path, monkeypatch):
    assert verify.load_callable("examples.planted_defects:holmes_flight_time") is \
        planted_defects.holmes_flight_time
    assert verify.load_callable("fastpath:flight_time") is fastpath.flight_time
    assert verify.load_callable("os.path:join.__call__")  # dotted attributes
    by_path = verify.load_callable("examples/planted_defects.py:holmes_flight_time")
    assert by_path(0.0, 1.5, 0.6) == 3.0
    (tmp_path / "mysolver.py").write_text("def tau(phi, v, eps):\n    return 2.0 * v\n")
    monkeypatch.chdir(tmp_path)
    assert verify.load_callable("mysolver:tau")(0.0, 2.0, 0.1) == 4.0
    bad = {
        "nocolon": "MODULE:FUNCTION",
        ":f": "MODULE:FUNCTION",
        "no_such_module_xyz:f": "cannot import module",
        "math:no_such_function": "has no attribute",
        "math:pi": "not callable",
        "missing_file.py:f": "no such file",
    }
    for spec, text in bad.items():
        with pytest.raises(ValueError, match=text):
            verify.load_callable(spec)
    (tmp_path / "broken.py").write_text("raise ImportError('needs a GPU')\n")
    with pytest.raises(ValueError, match="needs a GPU"):
        verify.load_callable("broken:f")


def test_verify_does_not_import_fastpath():
    import pathlib

    root = pathlib.Path(verify.__file__).parent
    for path in root.glob("*.py"):
        for line in path.read_text().splitlines():
            words = line.split()
            assert not (words[:1] in (["import"], ["from"]) and "fastpath" in line), path
