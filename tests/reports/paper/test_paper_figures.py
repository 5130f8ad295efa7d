"""The seed's figures section in quick mode: runs, figures (PNG + PDF), Markdown, verdicts."""

import math

import numpy as np
import pytest

from reports.paper.fig3_transport import transport_dominance
from reports.paper.figures import paper_figures_section

STEMS = ("paper_fig1_phase_space", "paper_fig2_escape", "paper_fig3_transport", "paper_fig4_h1",
         "paper_fermi")


@pytest.fixture(scope="module")
def section(tmp_path_factory):
    out = tmp_path_factory.mktemp("figures")
    said = []
    md = paper_figures_section(out, quick=True, echo=said.append)
    return out, md, said


def test_figures_exist_as_png_and_pdf(section):
    out, md, _ = section
    for stem in STEMS:
        for ext in ("png", "pdf"):
            assert (out / f"{stem}.{ext}").stat().st_size > 1000, (stem, ext)
        assert f"]({stem}.png)" in md, stem


def test_markdown_states_claims_runs_and_verification(section):
    out, md, said = section
    assert md.count("Seed's claim") == 5
    assert md.count("overstepped") >= 4
    for h in ("0.1", "0.4", "1", "2.2"):
        assert any(line.startswith(f"| {h} |") for line in md.splitlines()), h
    for run in ("paper-phase-space-200", "paper-escape-2000", "paper-transport-2000"):
        assert (out / "runs" / run / "manifest.json").is_file(), run
    assert any(msg.startswith("running paper-escape") for msg in said)


def test_complete_runs_are_reused(section):
    out, md, _ = section
    said = []
    again = paper_figures_section(out, quick=True, echo=said.append)
    assert sum(msg.startswith("reusing") for msg in said) == 3
    assert not any(msg.startswith("running") for msg in said)
    strip = [line for line in again.splitlines() if not line.startswith("(paper figures")]
    assert strip == [line for line in md.splitlines() if not line.startswith("(paper figures")]


def transport_curve(x, p):
    p = np.asarray(p, float)
    return np.asarray(x, float), p, p, p


def test_dominance_is_computed_from_the_curves():
    x = np.array([1.0, 10, 100, 1e3, 1e4, 1e5])
    n = 10**6
    # P12 dies at t = 100 while P11 has a tail to 1e5: P11 dominates
    data = {("h=1/P11", "time"): transport_curve(x, [0.9, 0.1, 0.01, 1e-3, 5e-4, 2e-4]),
            ("h=1/P12", "time"): transport_curve(x[:3], [0.1, 0.01, 0.0])}
    r = transport_dominance(data, "1", n)
    assert r["t_q"] == 1e3 and r["k12"] == 0 and r["dominates"]
    assert r["ratio"] == math.inf and r["ratio_lower"] == pytest.approx(1000 / 3)
    # comparable channels: no
    data[("h=1/P12", "time")] = transport_curve(x, [0.1, 0.05, 0.005, 5e-4, 2e-4, 1e-4])
    r = transport_dominance(data, "1", n)
    assert r["ratio"] == pytest.approx(2.0) and not r["dominates"]
    # no tail beyond t_q: no
    data = {("h=1/P11", "time"): transport_curve(x[:4], [0.9, 0.1, 0.002, 0.0]),
            ("h=1/P12", "time"): transport_curve(x[:3], [0.1, 0.01, 0.0])}
    r = transport_dominance(data, "1", n)
    assert r["t_q"] == 100 and not r["tail"] and not r["dominates"]
