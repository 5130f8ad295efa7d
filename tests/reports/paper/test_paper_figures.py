"""The paper's figures section in quick mode: runs, figures (PNG + PDF), Markdown, and a verdict
for every claim of the register (slow: the quick section takes a few minutes; the quick tier
checks only which runs it asks for)."""

import pytest

from reports.paper.claims.claim import FIELDS, claims_json
from reports.paper.claims.register import entries
from reports.paper.claims.register_section2 import dynamics_entries
from reports.paper.sections import paper_figures_section as figures
from reports.paper.sections.paper_figures_section import paper_figures_section

QUICK_RUNS = ["paper-phase-space-200", "paper-escape-2000", "paper-transport-2000",
              "escape-second-box-2000", "escape-island-start-500", "transport-width-sweep-2000"]


class RunsInHand(Exception):
    """Raised in place of the claims, to stop a section once its runs are in hand."""


def stop_after_the_runs(monkeypatch):
    def stop(*args, **kwargs):
        raise RunsInHand

    monkeypatch.setattr(figures, "decide", stop)


def test_quick_section_asks_for_the_six_runs_at_their_quick_sizes(tmp_path, monkeypatch):
    asked = []

    def ensure_run(scene, runs_dir, particles, echo, scene_text=None):
        asked.append(f"{scene}-{particles}")
        return runs_dir / asked[-1]

    monkeypatch.setattr(figures, "ensure_run", ensure_run)
    monkeypatch.setattr(figures, "largest_run", lambda scene, runs: None)
    stop_after_the_runs(monkeypatch)
    with pytest.raises(RunsInHand):
        paper_figures_section(tmp_path, quick=True)
    assert asked == QUICK_RUNS

STEMS = ("paper_fig1_phase_space", "paper_fig2_escape", "paper_fig3_transport", "paper_fig4_h1",
         "paper_survivors", "paper_fermi", "paper_dissipation")


@pytest.fixture(scope="module")
def section(tmp_path_factory):
    out = tmp_path_factory.mktemp("figures")
    said = []
    md, claims = paper_figures_section(out, quick=True, echo=said.append)
    return out, md, claims, said


@pytest.mark.slow
def test_figures_exist_as_png_and_pdf(section):
    out, md, _, _ = section
    for stem in STEMS:
        for ext in ("png", "pdf"):
            assert (out / f"{stem}.{ext}").stat().st_size > 1000, (stem, ext)
        assert f"]({stem}.png)" in md, stem


@pytest.mark.slow
def test_every_claim_of_the_register_has_a_verdict(section):
    out, md, claims, said = section
    ids = [c.id for c in claims]
    assert len(ids) == len(set(ids))
    dynamics = {e["id"] for e in dynamics_entries()}  # the dynamics section decides these
    assert {e["id"] for e in entries()} - dynamics <= set(ids)
    assert {"dissipation-saturates", "dissipation-exponent"} <= set(ids)
    for c in claims_json(claims):
        assert list(c) == list(FIELDS)
        assert c["verdict"] in ("confirmed", "refuted", "inconclusive")
        assert c["rule"] and c["evidence"] and c["statement"] and c["source"]
    for run in QUICK_RUNS:
        assert (out / "runs" / run / "manifest.json").is_file(), run
    assert any(msg.startswith("running paper-escape") for msg in said)


@pytest.mark.slow
def test_complete_runs_are_reused(section, monkeypatch):
    """A second section in the same folder reuses the six complete runs and runs none (it is
    stopped once its runs are in hand: its claims and figures would be the first one's)."""
    out, md, _, _ = section
    said = []
    stop_after_the_runs(monkeypatch)
    with pytest.raises(RunsInHand):
        paper_figures_section(out, quick=True, echo=said.append)
    assert sum(msg.startswith("reusing") for msg in said) == 6
    assert not any(msg.startswith("running") for msg in said)
