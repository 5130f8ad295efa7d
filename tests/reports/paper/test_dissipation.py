"""The dissipation section: its estimators on curves of known shape, its verdict rules, and a
small ensemble that must saturate (restitution) or stick (eps <= 1). No timing asserted."""

import dataclasses
import math

import numpy as np
import pytest

from reports.paper.claims.claim import CONFIRMED, INCONCLUSIVE, REFUTED, VERDICTS
from reports.paper.claims.dissipation_claims import (
    dissipation_claims,
    exponent_verdict,
    saturation_member,
    strip_members,
)
from reports.paper.figures.paper_dissipation import dissipation_markdown
from reports.paper.studies.dissipation_study import (
    STUDY,
    Curve,
    Dissipation,
    _beta_systematic,
    _curve,
    exponent,
    log_slope,
    plateau,
    velocity_strip,
)
from reports.precision.bench import DISSIPATIVE_MODELS, dissipative_table, time_dissipative_orbits

U = 2.0**-53
N = np.unique(np.round(np.logspace(0, 4, 41))).astype(float)
WINDOW = (1e3, 1e4)
OMR = np.array([0.005, 0.01, 0.02, 0.05, 0.1])


def fake_curve(label, slope, err=0.01, sys=0.0, mean_v=None, noise=0.01, seed=0):
    """<v_n> = 5 n^slope (or ``mean_v``) from 16 particle blocks, each scaled by 1 + its own
    relative ``noise`` and tilted by n^(+-noise), half of them each way (the bootstrap's spread
    of the plateau and of the slope; the mean curve's slope stays within noise^2 log n of
    ``slope``)."""
    mean_v = 5.0 * N ** slope if mean_v is None else mean_v
    rng = np.random.default_rng(seed)
    tilt = noise * np.repeat([1.0, -1.0], 8)[:, None]
    blocks = mean_v * (1 + noise * rng.standard_normal((16, 1))) * (N / 3e3) ** tilt
    return Curve(label, {}, blocks.mean(axis=0), blocks, np.ones((16, len(N))), 0, 1, 1, 0,
                 plateau(N, mean_v, *WINDOW), slope, err, sys)


def test_plateau_is_the_mean_over_the_window_only():
    v = np.where(N >= WINDOW[0], 7.0, 1.0)
    assert plateau(N, v, *WINDOW) == 7.0
    v[-1] = np.nan
    assert plateau(N, v, *WINDOW) == 7.0  # a grid point nobody reached is left out
    assert math.isnan(plateau(N, v, 2e4, 3e4))


@pytest.mark.parametrize("beta", [-0.5, -0.618, -1.0])
def test_exponent_recovers_a_power_law(beta):
    # least squares on 5 points with |log| <= 8 and a log(x) spread of 3: a few hundred ulps
    got, log_amp = exponent(OMR, 3.0 * OMR**beta)
    assert abs(got - beta) <= 1000 * U * 8 / 3
    assert abs(log_amp - math.log(3.0)) <= 1000 * U * 8
    slope = log_slope(N, 2.0 * N**0.5, *WINDOW)
    assert abs(slope - 0.5) <= 1000 * U * 10


def test_beta_systematic_is_zero_for_an_exact_power_law_and_not_otherwise():
    curves = [fake_curve(f"{x}", 0.0, mean_v=np.full(len(N), 4 * x**-0.5)) for x in OMR]
    assert _beta_systematic(N, OMR, curves, WINDOW) <= 1000 * U
    bent = [fake_curve(f"{x}", 0.0, mean_v=np.full(len(N), 4 * x**-0.5 + 10)) for x in OMR]
    assert _beta_systematic(N, OMR, bent, WINDOW) > 0.01  # curvature: dropping ends moves beta


def test_a_saturation_member_is_flat_while_the_elastic_curve_grows():
    grows = fake_curve("elastic", 0.5)
    assert saturation_member(N, grows, fake_curve("a", 0.0), WINDOW).verdict == CONFIRMED
    assert saturation_member(N, grows, fake_curve("c", 0.1), WINDOW).verdict == INCONCLUSIVE
    assert saturation_member(N, grows, fake_curve("d", 0.55, seed=1), WINDOW).verdict == REFUTED
    flat_elastic = fake_curve("elastic", 0.0)
    assert saturation_member(N, flat_elastic, fake_curve("a", 0.0), WINDOW).verdict == \
        INCONCLUSIVE


def test_exponent_verdict_rules():
    assert exponent_verdict(-0.52, 0.01, 0.01) == CONFIRMED
    assert exponent_verdict(-0.62, 0.006, 0.025) == REFUTED
    assert exponent_verdict(-0.545, 0.01, 0.01) == REFUTED  # off 0.045 > U = 0.0296
    assert exponent_verdict(-0.525, 0.01, 0.01) == CONFIRMED  # off 0.025 <= U
    assert exponent_verdict(-0.55, 0.1, 0.1) == INCONCLUSIVE  # U = 0.296 > 1/4
    assert exponent_verdict(math.nan, 0.01, 0.01) == INCONCLUSIVE


def test_claims_and_markdown_from_a_study():
    rest = [fake_curve(f"1 - r = {x:g}", 0.0, mean_v=np.full(len(N), 4 * x**-0.5), seed=i)
            for i, x in enumerate(OMR)]
    d = Dissipation(2.0, 10, N, WINDOW, fake_curve("elastic", 0.5), rest,
                    [fake_curve("linear drag k = 0.01", 0.0)], OMR, -0.5, 0.01, 0.0, 4.0,
                    [(0.5, 1.0, 10)], {"sampled": 3, "worst_error": 0.5, "overstepped": 0}, 1.0)
    d.strip_max = [0.5 * velocity_strip(1 - x, 2.0) for x in OMR]
    d.strip_halves = [(m, 0.9 * m) for m in d.strip_max]
    d.strip_orbits = 4
    claims = dissipation_claims(d)
    assert [c.id for c in claims] == ["dissipation-saturates", "dissipation-exponent",
                                      "dissipation-velocity-strip"]
    assert all(c.verdict in VERDICTS for c in claims)
    assert [c.verdict for c in claims] == [CONFIRMED, CONFIRMED, CONFIRMED]
    # not the paper's claims: each names its source; our own estimate says so
    assert claims[0].source.startswith("de Souza") and claims[0].quote
    assert claims[1].source == "this project" and "no published value" in claims[1].statement
    assert "Barroso" in claims[2].source and "max |v| / V* = 0.5" in claims[2].evidence
    assert all(len(c.analyses) >= 2 for c in claims)
    md = dissipation_markdown(d, "x.png")
    assert "No published value of beta was found" in md and "r = 0.5: 100.0%" in md
    assert "velocity strip" in md and "0.1: 0.500" in md


def test_velocity_strip_is_the_fixed_point_and_scales_as_one_over_one_minus_r():
    for eps in (0.6, 2.0, 5.0):
        for r in (0.1, 0.5, 0.9, 0.99, 0.999):
            vs = velocity_strip(r, eps)
            g = (1 + r) * eps + r * math.sqrt(vs**2 + 4 * eps)
            assert abs(g - vs) <= 8 * U * vs
            assert vs >= eps
        x = 1e-6
        assert abs(velocity_strip(1 - x, eps) * x / (2 * eps) - 1) < 1e-5


def test_the_velocity_strip_is_a_part_per_r_refuted_by_one_orbit_outside():
    omr = [0.01, 0.1]
    d = Dissipation(2.0, 10, N, WINDOW, None, [], [], omr, -0.5, 0.01, 0.0, 4.0, [], {}, 1.0)
    inside = [0.9 * velocity_strip(1 - x, 2.0) for x in omr]
    d.strip_halves = [(m, m) for m in inside]
    members = strip_members(d)
    assert {a.part for a in members} == {"1 - r = 0.01", "1 - r = 0.1"}
    assert all(a.verdict == CONFIRMED for a in members)
    d.strip_halves[1] = (inside[1], 1.0001 * velocity_strip(0.9, 2.0))
    assert [a.verdict for a in strip_members(d)][-1] == REFUTED


@pytest.mark.parametrize("r", [0.5, 0.9])
def test_orbits_never_leave_the_velocity_strip_even_from_its_edge(r):
    """Started on the strip's edge (the worst start), 2000 collisions never exceed V*."""
    import fastpath

    eps = 2.0
    vs = velocity_strip(r, eps)
    for phi in np.linspace(0.0, 2 * math.pi, 7, endpoint=False):
        v = vs if vs + eps * math.sin(phi) > 0 else -eps * math.sin(phi) + 1.0
        orb = fastpath.orbit(float(phi), float(v), eps, 2000, on_uncertain="stop", restitution=r)
        assert float(np.max(np.abs(orb.v))) <= vs


@pytest.mark.slow
def test_restitution_saturates_and_eps_below_one_sticks():
    rng = np.random.default_rng(5)
    phi0, v0 = rng.uniform(3.85, 4.15, 32), rng.uniform(2.0, 4.0, 32)
    n = np.unique(np.round(np.logspace(0, 3, 25)).astype(np.int64))
    window = (100.0, 1000.0)
    elastic = _curve("elastic", {}, phi0, v0, STUDY["eps"], n, window)
    lossy = _curve("r = 0.9", {"restitution": 0.9}, phi0, v0, STUDY["eps"], n, window)
    assert saturation_member(n.astype(float), elastic, lossy, window).verdict == CONFIRMED
    assert lossy.plateau < elastic.plateau and lossy.stuck == 0  # eps > 1: never stuck
    assert lossy.reached == 32
    stuck = _curve("r = 0.5", {"restitution": 0.5}, phi0, v0, 0.6, n, window)
    assert stuck.stuck + stuck.reached + stuck.flagged <= 32 and stuck.stuck > 0


def test_bench_dissipative_rows_make_every_collision():
    best = time_dissipative_orbits(collisions=2000, repeats=1)
    assert list(best) == [label for label, _ in DISSIPATIVE_MODELS]
    assert all(made == 2000 and ns > 0 for ns, made in best.values())
    table = dissipative_table(best, 2000, 2.0, 1)
    assert "| elastic |" in table and "| 1.00 |" in table


@pytest.mark.slow
def test_the_study_begun_in_the_background_is_the_study_computed_in_line(monkeypatch):
    from reports.paper.studies import dissipation_study as study

    monkeypatch.setattr(study, "_STUDIES", {})
    in_line = study.dissipation_study(True)
    study._STUDIES.clear()
    finish = study.start_dissipation_study(True)
    background = finish()
    assert background is not in_line
    assert same_numbers_but_source(background, in_line)
    assert study.dissipation_study(True) is background  # one study for figure and claims


def test_an_error_in_the_background_reaches_the_caller(monkeypatch):
    from reports.paper.studies import dissipation_study as study

    def broken(quick, only=None):
        raise ValueError("moments failed")

    monkeypatch.setattr(study, "_STUDIES", {})
    monkeypatch.setattr(study, "_study_moments", broken)
    finish = study.start_dissipation_study(True)
    with pytest.raises(ValueError, match="moments failed"):
        finish()
    assert study._STUDIES == {}


@pytest.fixture(scope="module")
def quick_study():
    from reports.paper.studies import dissipation_study as study

    return study._finished_study(True, *study._study_moments(True))


@pytest.mark.slow
def test_a_written_study_reads_back_with_the_same_numbers(quick_study):
    from reports.paper.studies.dissipation_study import from_json, same_numbers, to_json

    again = from_json(to_json(quick_study))
    assert same_numbers(again, quick_study)
    assert type(again.window) is tuple
    assert again.elastic.sum_v.dtype == quick_study.elastic.sum_v.dtype
    assert not same_numbers(dataclasses.replace(again, beta=again.beta + 1e-15), quick_study)


@pytest.mark.slow
def test_the_recheck_finds_each_committed_number_that_this_code_does_not_compute(quick_study):
    from reports.paper.studies import dissipation_study as study

    parts, _ = study._study_moments(True, study.RECHECKED)
    ver = study._spot_check(*study._starts(True), True)
    assert study.recheck(quick_study, parts, ver) == []
    curve = quick_study.restitution[-1]
    assert curve.label in study.RECHECKED
    mean_v = curve.mean_v.copy()
    mean_v[-1] *= 1 + 2**-52
    tampered = dataclasses.replace(quick_study, restitution=[
        *quick_study.restitution[:-1], dataclasses.replace(curve, mean_v=mean_v)])
    assert study.recheck(tampered, parts, ver) == [f"the curve {curve.label}"]
    tampered = dataclasses.replace(quick_study, verification={
        **quick_study.verification, "worst_error": quick_study.verification["worst_error"] * 2})
    assert study.recheck(tampered, parts, ver) == ["the verify spot check"]
    tampered = dataclasses.replace(quick_study, strip_halves=quick_study.strip_halves[:-1])
    assert study.recheck(tampered, parts, ver) == ["the velocity strip"]


@pytest.mark.slow
def test_the_report_takes_the_committed_study_only_where_its_recheck_passes(
        quick_study, tmp_path, monkeypatch):
    from reports.paper.studies import dissipation_study as study

    path = tmp_path / "study.json"
    path.write_text(study.to_json(quick_study), encoding="utf-8")
    monkeypatch.setattr(study, "_committed_for", lambda quick: path)
    monkeypatch.setattr(study, "_STUDIES", {})
    said = []
    got = study.start_dissipation_study(True, said.append)()
    assert same_numbers_but_source(got, quick_study)
    assert "the committed study (`study.json`" in got.source and not said
    # a committed number this code does not reproduce: the whole study computed here
    study._STUDIES.clear()
    elastic = dataclasses.replace(quick_study.elastic, plateau=quick_study.elastic.plateau * 2)
    path.write_text(study.to_json(dataclasses.replace(quick_study, elastic=elastic)),
                    encoding="utf-8")
    got = study.start_dissipation_study(True, said.append)()
    assert same_numbers_but_source(got, quick_study)
    assert got.source.startswith("computed here") and "the curve elastic" in got.source
    assert len(said) == 1 and "differ" in said[0]


def same_numbers_but_source(a, b):
    from reports.paper.studies.dissipation_study import same_numbers

    return same_numbers(dataclasses.replace(a, source="", seconds=0.0),
                        dataclasses.replace(b, source="", seconds=0.0))


def test_the_committed_study_is_the_full_study_and_installed_with_the_package():
    """The committed study has the full sizes and the curves of ``STUDY`` (else every report
    would recompute it), and the package data names it, so that an installed copy re-checks it
    instead of spending minutes on it."""
    import fnmatch
    import tomllib
    from pathlib import Path

    from reports.paper.studies import dissipation_study as study

    committed = study.from_json(study.COMMITTED.read_text(encoding="utf-8"))
    assert committed.particles == STUDY[False]["particles"]
    assert committed.n[-1] == STUDY[False]["n_max"]
    labels = [c.label for c in [committed.elastic, *committed.restitution, *committed.drag]]
    assert labels == [label for label, _ in study._curves_of_study()]
    assert set(study.RECHECKED) <= set(labels) and len(set(study.RECHECKED)) == 4
    assert [r for r, _, _ in committed.sticking] == list(STUDY["sticking_r"])
    package = Path(study.__file__).resolve().parents[3]
    assert study.COMMITTED.is_relative_to(package / "reports")
    pyproject = tomllib.loads((package / "pyproject.toml").read_text(encoding="utf-8"))
    data = pyproject["tool"]["setuptools"]["package-data"]
    module = ".".join(study.COMMITTED.parent.relative_to(package).parts)
    assert any(fnmatch.fnmatch(study.COMMITTED.name, pattern) for pattern in data[module])
