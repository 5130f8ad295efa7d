"""The seed's figures section in quick mode: runs, figures (PNG + PDF), Markdown, verdicts."""

import numpy as np
import pytest

from reports.paper.fig3_transport import transport_dominance
from reports.paper.figures import paper_figures_section

STEMS = ("paper_fig1_phase_space", "paper_fig2_escape", "paper_fig3_transport", "paper_fig4_h1",
         "paper_fermi", "paper_dissipation")


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


def test_every_claim_of_figs_2_to_4_and_fermi_has_a_verdict(section):
    out, md, claims, said = section
    ids = {c.id for c in claims}
    for hole in ("0", "0.5", "1", "1.5", "2", "2.5"):
        assert f"fig2-n-phi_c={hole}" in ids
    for h in ("0.1", "0.4", "1", "2.2"):
        assert f"fig3-h={h}" in ids
    assert {"fig4-P11-collisions", "fig4-P11-time", "fermi-n", "fermi-t",
            "dissipation-saturates", "dissipation-exponent"} <= ids
    for c in claims:
        assert c.verdict in ("confirmed", "refuted", "inconclusive")
        assert c.rule and c.evidence and c.seed_says
        assert f"**{c.id}** ({c.verdict})" in md  # the markdown states every verdict
    assert md.count("overstepped") >= 4
    for run in ("paper-phase-space-200", "paper-escape-2000", "paper-transport-2000"):
        assert (out / "runs" / run / "manifest.json").is_file(), run
    assert any(msg.startswith("running paper-escape") for msg in said)


def test_complete_runs_are_reused(section):
    out, md, _, _ = section
    said = []
    again, _ = paper_figures_section(out, quick=True, echo=said.append)
    assert sum(msg.startswith("reusing") for msg in said) == 3
    assert not any(msg.startswith("running") for msg in said)
    strip = [line for line in again.splitlines() if not line.startswith("(paper figures")]
    assert strip == [line for line in md.splitlines() if not line.startswith("(paper figures")]


def transport_curve(x, p):
    p = np.asarray(p, float)
    return np.asarray(x, float), p, p, p


X = np.array([1.0, 10, 100, 1e3, 1e4, 1e5])
N = 10**6


def test_a_channel_that_dies_leaves_p11_dominating():
    # P12 dies at t = 100 while P11 has a tail to 1e5
    data = {("h=1/P11", "time"): transport_curve(X, [0.9, 0.1, 0.01, 1e-3, 5e-4, 2e-4]),
            ("h=1/P12", "time"): transport_curve(X[:3], [0.1, 0.01, 0.0])}
    r = transport_dominance(data, "1", N)
    assert r["t_q"] == 1e3 and (r["k11"], r["k12"]) == (1000, 0)
    assert r["share"] == 1.0 and r["share_ci95"][0] > 0.99 and r["dominates"] is True


def test_the_minority_channel_does_not_dominate():
    data = {("h=1/P11", "time"): transport_curve(X, [0.5, 0.05, 0.005, 2e-4, 1e-4, 5e-5]),
            ("h=1/P12", "time"): transport_curve(X, [0.5, 0.05, 0.005, 8e-4, 4e-4, 2e-4])}
    r = transport_dominance(data, "1", N)
    assert r["share"] == pytest.approx(0.2) and r["share_ci95"][1] < 0.5
    assert r["dominates"] is False


def test_a_falling_share_does_not_dominate_even_from_a_majority():
    # 60% reflected at t_q, but the late survivors are mostly transmitted
    data = {("h=1/P11", "time"): transport_curve(X, [0.5, 0.05, 0.005, 6e-4, 5e-5, 1e-5]),
            ("h=1/P12", "time"): transport_curve(X, [0.5, 0.05, 0.005, 4e-4, 2e-4, 1e-4])}
    r = transport_dominance(data, "1", N)
    assert r["share_ci95"][0] > 0.5 and r["trend_p"] < 0.05 and r["dominates"] is False


def test_an_even_split_is_undecided():
    data = {("h=1/P11", "time"): transport_curve(X, [0.5, 0.05, 0.005, 5e-4, 1e-4, 5e-5]),
            ("h=1/P12", "time"): transport_curve(X, [0.5, 0.05, 0.005, 5e-4, 1e-4, 5e-5])}
    r = transport_dominance(data, "1", N)
    assert r["share"] == 0.5 and r["dominates"] is None
