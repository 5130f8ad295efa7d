"""The report's dynamics section: the claim schema, the figures, the rules on hand-made data.

The rule tests run on the committed study (docs/report/dynamics/study.json) with one field
broken by hand; the tests of the whole section (figures, re-checks) are slow."""

import copy
import json

import pytest

from reports.paper import dynamics
from reports.paper.dynamics_study import QUICK, run

KEYS = {"id", "figure", "statement", "quote", "observable", "regime", "rule", "tolerance",
        "source", "verdict", "evidence", "particles_per_curve", "statistical", "systematic",
        "run"}


@pytest.fixture(scope="module")
def study():
    """The committed study (the section's own input)."""
    return json.loads(dynamics.STUDY.read_text(encoding="utf-8"))


@pytest.fixture(scope="module")
def section(tmp_path_factory):
    out = tmp_path_factory.mktemp("dynamics")
    markdown, claims = dynamics.dynamics_section(out, quick=True, echo=lambda s: None)
    return out, markdown, claims


@pytest.mark.slow  # the section's figures and re-checks: ~12 s
def test_claims_have_exactly_the_register_keys_and_a_verdict(section):
    _, _, claims = section
    assert len({c["id"] for c in claims}) == len(claims) >= 8
    for c in claims:
        assert set(c) == KEYS
        assert c["verdict"] in ("confirmed", "refuted", "inconclusive")
        assert c["source"] == "paper"
        assert c["figure"] in ("sec2", "intro")
        assert c["quote"] and c["rule"] and c["evidence"]
    json.dumps(claims)  # JSON-ready


def test_quotes_are_the_papers_words():
    # spot checks of the verbatim LaTeX (the paper's text is not in the repository)
    assert dynamics.QUOTES["fixed-hyperbolic"] == \
        r"For $\epsilon<0$ or $\epsilon>1$ the orbit is hyperbolic."
    assert r"$K=0.971\ldots$" in dynamics.QUOTES["transition"]
    assert "``accelerator modes''" in dynamics.QUOTES["accelerator"]


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
    verdicts = {c["id"]: c["verdict"] for c in claims}
    assert verdicts["sec2-fixed-elliptic"] == "confirmed"
    assert verdicts["sec2-fixed-hyperbolic"] == "confirmed"
    assert verdicts["sec2-period-two"] == "confirmed"


def test_a_fixed_point_proved_of_the_other_kind_refutes(study):
    broken = copy.deepcopy(study)
    row = next(r for r in broken["fixed_points"]["rows"] if 0 < r["eps"] < 1)
    row["stability"] = "hyperbolic"
    claims = {c["id"]: c for c in dynamics.fixed_point_claims(broken, None)}
    assert claims["sec2-fixed-elliptic"]["verdict"] == "refuted"


def test_a_crossing_below_eps_c_refutes_the_transition(study):
    broken = copy.deepcopy(study)
    below = next(s for s in broken["crossing_simulation"] if s["factor"] < 1)
    below["crossed"] = 1
    transition = dynamics.transition_claims(broken, None)[0]
    assert transition["verdict"] == "refuted"


def test_ballistic_diffusion_at_the_papers_eps_refutes_normal_diffusion(study):
    broken = copy.deepcopy(study)
    d = next(d for d in broken["accelerator"]["diffusion"] if d["eps"] == 0.6)
    d["mu"], d["mu_se"], d["mu_systematic"] = 2.0, 0.01, 0.01
    assert dynamics.accelerator_claims(broken, None)[1]["verdict"] == "refuted"


def test_negative_exponent_refutes_the_lyapunov_remark(study):
    broken = copy.deepcopy(study)
    broken["lyapunov"]["mean_per_collision"][-1] = -0.5
    broken["lyapunov"]["se_per_collision"][-1] = 0.01
    assert dynamics.lyapunov_claim(broken, None)["verdict"] == "refuted"


def test_a_failed_recheck_makes_its_claims_inconclusive(study):
    checks = {"fixed_points": (False, "stored enclosure does not match")}
    claims = {c["id"]: c for c in dynamics.claims_of(study, None, checks)}
    assert claims["sec2-fixed-elliptic"]["verdict"] == "inconclusive"
    assert "re-check" in claims["sec2-fixed-elliptic"]["evidence"]


@pytest.mark.slow  # the section's figures and re-checks: ~12 s
def test_committed_study_supports_the_papers_statements(section):
    _, markdown, claims = section
    verdicts = {c["id"]: c["verdict"] for c in claims}
    assert set(verdicts.values()) == {"confirmed"}
    assert "FAILED" not in markdown  # every re-check of the committed data passed


@pytest.mark.slow
def test_section_computes_the_study_when_none_is_committed(tmp_path, monkeypatch):
    fresh = run(QUICK, echo=lambda s: None)
    monkeypatch.setattr(dynamics, "load_study", lambda quick, echo: (fresh, None))
    markdown, claims = dynamics.dynamics_section(tmp_path, quick=True, echo=lambda s: None)
    assert {c["id"] for c in claims} >= {"sec2-fixed-elliptic", "intro-lyapunov"}
    assert "computed for this report" in markdown
