"""verify.check.api: check_integrator / assert_integrator arguments, skips, the independence
rule for the whole of verify/.

Importing fastpath here is fine: only ``verify/`` itself must not import it.
"""

import pytest

import fastpath
import verify
from examples import planted_defects
from verify.check import SUITES


@pytest.mark.slow
def test_assert_integrator():
    with pytest.raises(AssertionError) as err:
        verify.assert_integrator(planted_defects.biased_flight_time, suite="fixed_points")
    assert "FAIL  fixed_points" in str(err.value)
    assert "fixed_points: flight_time(phi=0.0" in str(err.value)
    report = verify.assert_integrator(fastpath.flight_time, suite="holmes_limit")
    assert report.ok


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


@pytest.mark.slow
def test_energy_is_skipped_without_step():
    report = verify.check_integrator(fastpath.flight_time, suite="fast", max_examples=3)
    assert report.result("energy").status == "SKIP"
    assert report.ok


def test_verify_does_not_import_fastpath():
    import pathlib

    root = pathlib.Path(verify.__file__).parent
    for path in root.rglob("*.py"):  # verify/check/ too
        for line in path.read_text().splitlines():
            words = line.split()
            assert not (words[:1] in (["import"], ["from"]) and "fastpath" in line), path
