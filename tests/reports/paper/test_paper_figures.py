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

@pytest.mark.parametrize(("particles", "second_box"), [
    (None, 1_000_000), (300_000, 300_000), (10**8, 10**7)])
def test_the_second_start_box_is_made_at_the_reports_size_and_a_larger_included_run_used(
        tmp_path, monkeypatch, particles, second_box):
    """escape-second-box is compared curve by curve with paper-escape: made with the report's
    particles per curve (at most its scene's 10^7); a larger complete run given to the report
    replaces it, as for paper-escape."""
    asked, used = [], {}

    def ensure_run(scene, runs_dir, n, echo, scene_text=None):
        asked.append((scene, n))
        return runs_dir / f"{scene}-{n}"

    included = tmp_path / "escape-second-box-big"

    def largest_run(scene, runs):
        return included if scene == "escape-second-box" and included in runs else None

    def decide(out_dir, runs, quick, echo, on_one_core=None):
        used.update(runs)
        raise RunsInHand

    monkeypatch.setattr(figures, "ensure_run", ensure_run)
    monkeypatch.setattr(figures, "largest_run", largest_run)
    monkeypatch.setattr(figures, "decide", decide)
    with pytest.raises(RunsInHand):
        paper_figures_section(tmp_path, particles=particles)
    assert ("escape-second-box", second_box) in asked
    assert used["escape-second-box"].name == f"escape-second-box-{second_box}"
    with pytest.raises(RunsInHand):
        paper_figures_section(tmp_path, particles=particles, include_runs=[included])
    assert used["escape-second-box"] == included


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
