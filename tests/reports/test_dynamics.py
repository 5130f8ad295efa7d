"""The report's dynamics section: the claim schema, the figures, the rules on hand-made data.

The rule tests run on the committed study (reports/paper/studies/dynamics_study.json) with one
field broken by hand; the tests of the whole section (figures, re-checks) are slow."""

import copy
import fnmatch
import json
import tomllib
from pathlib import Path

import pytest

from reports.paper.claims import dynamics_claims
from reports.paper.claims import register_section2 as register
from reports.paper.claims.claim import FIELDS, claims_json
from reports.paper.sections import dynamics_section as dynamics
from reports.paper.studies.dynamics_study import QUICK, run


@pytest.fixture(scope="module")
def study():
    """The committed study (the section's own input)."""
    return json.loads(dynamics.STUDY.read_text(encoding="utf-8"))


def test_the_committed_study_is_installed_with_the_package():
    """The section reads the study from inside the reports package, and the package data names
    it, so that an installed copy (``pip install .``) re-checks the committed study instead of
    recomputing it for half an hour."""
    package = Path(dynamics.__file__).resolve().parents[2]
    assert dynamics.STUDY.is_file() and not dynamics.STUDY.is_symlink()
    assert dynamics.STUDY.is_relative_to(package)
    pyproject = tomllib.loads((package.parent / "pyproject.toml").read_text(encoding="utf-8"))
    data = pyproject["tool"]["setuptools"]["package-data"]
    module = ".".join(dynamics.STUDY.parent.relative_to(package.parent).parts)
    assert any(fnmatch.fnmatch(dynamics.STUDY.name, pattern) for pattern in data[module])


@pytest.fixture(scope="module")
def section(tmp_path_factory):
    out = tmp_path_factory.mktemp("dynamics")
    markdown, claims = dynamics.dynamics_section(out, quick=True, echo=lambda s: None)
    return out, markdown, claims


@pytest.mark.slow  # the section's figures and re-checks: ~12 s
def test_claims_have_exactly_the_register_keys_and_a_verdict(section):
    _, _, claims = section
    stored = claims_json(claims)  # the register's Claims: their family's agreement checked
    assert len({c["id"] for c in stored}) == len(stored) >= 9
    for c in stored:
        assert list(c) == list(FIELDS)
        assert c["verdict"] in ("confirmed", "refuted", "inconclusive")
        assert c["source"] == "paper"
        assert c["figure"] in ("sec2", "intro")
        assert c["quote"] and c["rule"] and c["evidence"] and c["family"]
    json.dumps(stored)  # JSON-ready


def test_quotes_are_the_papers_words():
    # spot checks of the verbatim LaTeX (the paper's text is not in the repository)
    assert register.Q_FIXED_HYPERBOLIC == \
        r"For $\epsilon<0$ or $\epsilon>1$ the orbit is hyperbolic."
    assert r"$K=0.971\ldots$" in register.Q_TRANSITION
    assert "``accelerator modes''" in register.Q_ACCELERATOR


@pytest.mark.slow  # the section's figures and re-checks: ~12 s
def test_figures_are_written_as_png_and_pdf(section):
    out, markdown, _ = section
    for stem in ("dynamics_residue", "dynamics_lyapunov", "dynamics_eps_c",
                 "dynamics_diffusion"):
        assert (out / f"{stem}.png").stat().st_size > 1000
        assert (out / f"{stem}.pdf").stat().st_size > 1000
        assert f"{stem}.png" in markdown


@pytest.mark.slow  # the section's figures and re-checks: ~12 s
def test_certified_facts_decide_the_stability_claims(section):
    _, _, claims = section
    verdicts = {c.id: c.verdict for c in claims}
    assert verdicts["sec2-fixed-elliptic"] == "confirmed"
    assert verdicts["sec2-fixed-hyperbolic"] == "confirmed"
    assert verdicts["sec2-period-two"] == "confirmed"


def test_a_fixed_point_proved_of_the_other_kind_refutes(study):
    broken = copy.deepcopy(study)
    row = next(r for r in broken["fixed_points"]["rows"] if 0 < r["eps"] < 1)
    row["stability"] = "hyperbolic"
    claims = {c.id: c for c in dynamics_claims.fixed_point_claims(broken, None)}
    # one fixed point proved hyperbolic against the others proved elliptic: the family
    # disagrees; every one of them hyperbolic refutes
    assert (claims["sec2-fixed-elliptic"].verdict,
            claims["sec2-fixed-elliptic"].inconclusive) == ("inconclusive", "analysis")
    for r in broken["fixed_points"]["rows"]:
        if 0 < r["eps"] < 1:
            r["stability"] = "hyperbolic"
    claims = {c.id: c for c in dynamics_claims.fixed_point_claims(broken, None)}
    assert claims["sec2-fixed-elliptic"].verdict == "refuted"


def test_a_crossing_below_eps_c_refutes_the_transition(study):
    broken = copy.deepcopy(study)
    for s in broken["crossing_simulation"]:
        s["crossed"] = 1 if s["factor"] < 1 else 0  # crossings below eps_c, none above
    transition = dynamics_claims.transition_claims(broken, None)[0]
    assert transition.verdict == "refuted"


def test_ballistic_diffusion_at_the_papers_eps_refutes_normal_diffusion(study):
    broken = copy.deepcopy(study)
    d = next(d for d in broken["accelerator"]["diffusion"] if d["eps"] == 0.6)
    d["fits"] = {str(n0): [2.0 - 0.05 * k, 0.01] for k, n0 in enumerate(d["family_starts"])}
    assert dynamics_claims.accelerator_claims(broken, None)[1].verdict == "refuted"


def test_only_windows_past_the_transient_are_members_of_the_diffusion_family(study):
    """A window starting in the transient is no reading of "normal diffusion": its slope is
    not a member; with no window past the transient the claim cannot be decided."""
    before = dynamics_claims.accelerator_claims(study, None)[1]
    broken = copy.deepcopy(study)
    d = next(d for d in broken["accelerator"]["diffusion"] if d["eps"] == 0.6)
    early = str(min(int(k) for k in d["fits"]))
    d["fits"][early] = [2.0, 0.01]
    assert int(early) < d["family_from"]
    claim = dynamics_claims.accelerator_claims(broken, None)[1]
    assert (claim.verdict, claim.analyses) == (before.verdict, before.analyses)
    assert not any(a["variant"].startswith(f"eps = 0.6, n0 = {early}:") for a in claim.analyses)
    d["fits"] = {early: [1.0, 0.01]}
    claim = dynamics_claims.accelerator_claims(broken, None)[1]
    assert (claim.verdict, claim.inconclusive) == ("inconclusive", "data")


def test_negative_exponent_refutes_the_lyapunov_remark(study):
    broken = copy.deepcopy(study)
    broken["lyapunov"]["mean_per_collision"][-1] = -0.5
    broken["lyapunov"]["se_per_collision"][-1] = 0.01
    one = dynamics_claims.lyapunov_claim(broken, None)
    assert (one.verdict, one.inconclusive) == ("inconclusive", "analysis")
    broken["lyapunov"]["mean_per_collision"] = [-0.5] * len(broken["lyapunov"]["checkpoints"])
    assert dynamics_claims.lyapunov_claim(broken, None).verdict == "refuted"


def test_a_failed_recheck_makes_its_claims_inconclusive(study):
    checks = {"fixed_points": (False, "stored enclosure does not match")}
    claims = {c.id: c for c in dynamics.claims_of(study, None, checks)}
    assert claims["sec2-fixed-elliptic"].verdict == "inconclusive"
    assert "re-check" in claims["sec2-fixed-elliptic"].evidence
    assert claims["sec2-period-two"].verdict == "confirmed"  # rests on another part


@pytest.mark.slow  # the section's figures and re-checks: ~12 s
def test_committed_study_supports_the_papers_statements(section):
    _, markdown, claims = section
    verdicts = {c.id: c.verdict for c in claims}
    assert "refuted" not in verdicts.values()
    assert "FAILED" not in markdown  # every re-check of the committed data passed


@pytest.mark.slow
def test_section_computes_the_study_when_none_is_committed(tmp_path, monkeypatch):
    fresh = run(QUICK, echo=lambda s: None)
    monkeypatch.setattr(dynamics, "load_study", lambda quick, echo: (fresh, None))
    markdown, claims = dynamics.dynamics_section(tmp_path, quick=True, echo=lambda s: None)
    assert {c.id for c in claims} >= {"sec2-fixed-elliptic", "intro-lyapunov"}
    assert "computed for this report" in markdown
