"""The paper's figures section in quick mode: runs, figures (PNG + PDF), Markdown, and a verdict
for every claim of the register (slow: the quick section takes a few minutes)."""

import pytest

from reports.paper.claims import FIELDS, claims_json
from reports.paper.figures import paper_figures_section
from reports.paper.register import entries

pytestmark = pytest.mark.slow

STEMS = ("paper_fig1_phase_space", "paper_fig2_escape", "paper_fig3_transport", "paper_fig4_h1",
         "paper_survivors", "paper_fermi", "paper_dissipation")


@pytest.fixture(scope="module")
def section(tmp_path_factory):
    out = tmp_path_factory.mktemp("figures")
    said = []
    md, claims = paper_figures_section(out, quick=True, echo=said.append)
    return out, md, claims, said


def test_figures_exist_as_png_and_pdf(section):
    out, md, _, _ = section
    for stem in STEMS:
        for ext in ("png", "pdf"):
            assert (out / f"{stem}.{ext}").stat().st_size > 1000, (stem, ext)
        assert f"]({stem}.png)" in md, stem


def test_every_claim_of_the_register_has_a_verdict(section):
    out, md, claims, said = section
    ids = [c.id for c in claims]
    assert len(ids) == len(set(ids))
    assert {e["id"] for e in entries()} <= set(ids)
    assert {"dissipation-saturates", "dissipation-exponent"} <= set(ids)
    for c in claims_json(claims):
        assert list(c) == list(FIELDS)
        assert c["verdict"] in ("confirmed", "refuted", "inconclusive")
        assert c["rule"] and c["evidence"] and c["statement"] and c["source"]
    for run in ("paper-phase-space-200", "paper-escape-2000", "paper-transport-2000",
                "escape-second-box-2000", "escape-island-start-500"):
        assert (out / "runs" / run / "manifest.json").is_file(), run
    assert any(msg.startswith("running paper-escape") for msg in said)


def test_complete_runs_are_reused(section):
    out, md, _, _ = section
    said = []
    again, _ = paper_figures_section(out, quick=True, echo=said.append)
    assert sum(msg.startswith("reusing") for msg in said) == 5
    assert not any(msg.startswith("running") for msg in said)
