"""The physics-check table in quick mode, and its pieces against known values."""

import math

import pytest
from scipy.special import jv

from reports.paper.checks.diffusion import accelerator_distance, rechester_white
from reports.paper.checks.rotation import rotation_angle
from reports.paper.sections.physics_checks_section import physics_checks_section

ROWS = ("<v> ~ n^beta", "<v> ~ t^beta", "cos(theta) at (0, pi), eps = 0.6",
        "exact map, eps = 2.5", "holmes map, eps = 2.5")


@pytest.fixture(scope="module")
def section(tmp_path_factory):
    out = tmp_path_factory.mktemp("physics")
    return physics_checks_section(out, quick=True)


def test_table_has_its_rows(section):
    rows = [line for line in section.splitlines() if line.startswith("| ")]
    assert rows[0].startswith("| quantity | measured | expected | method | agrees? |")
    for name in ROWS:
        assert sum(name in row for row in rows) >= 1, name
    # the stretched exponent is a claim decided by maximum likelihood, not a table row
    assert not any("ln(-ln P)" in row for row in rows)
    table = [r for r in rows[1:] if r.count("|") == 6]
    for row in table:
        assert row.rstrip().endswith(("| yes |", "| **no** |", "| n/a |")), row


def test_rotation_rows_agree(section):
    rows = [line for line in section.splitlines() if line.startswith("| cos(theta)")]
    assert len(rows) >= 5
    assert all(row.endswith("| yes |") for row in rows)


@pytest.mark.parametrize("eps", [0.2, 0.6, 0.9])
def test_rotation_angle_is_one_minus_two_eps(eps):
    cos_theta, det = rotation_angle(eps)
    assert cos_theta == pytest.approx(1 - 2 * eps, abs=1e-7)
    assert det == pytest.approx(1.0, abs=1e-7)


def test_rechester_white_factor():
    k = 10.0
    expected = 1 - 2 * jv(2, k) - 2 * jv(1, k) ** 2 + 2 * jv(2, k) ** 2 + 2 * jv(3, k) ** 2
    assert rechester_white(k) == pytest.approx(expected, rel=1e-15)
    assert rechester_white(1e6) == pytest.approx(1.0, abs=1e-2)


def test_accelerator_windows():
    assert accelerator_distance(2 * math.pi + 0.5) == 0.0
    assert accelerator_distance(math.sqrt((4 * math.pi) ** 2 + 16) - 1e-9) == 0.0
    assert accelerator_distance(10.0) == pytest.approx(10.0 - math.sqrt((2 * math.pi) ** 2 + 16))
    assert accelerator_distance(12.0) == pytest.approx(4 * math.pi - 12.0)
