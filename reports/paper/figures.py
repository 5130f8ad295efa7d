"""The seed's figures from trusted runs, with the seed's claims checked on them.

``paper_figures_section(out_dir, particles=None, quick=False, echo=None, runs_dir=None,
include_runs=())`` runs (or reuses complete run directories in ``runs_dir``, default
``out_dir/runs``) the built-in scenes paper-phase-space, paper-escape and paper-transport
through ``reports.runs.driver.run`` (or takes the larger included paper-scale runs), draws

    paper_fig1_phase_space   phase space at eps = 0.6                               (seed Fig. 1)
    paper_fig2_escape        2x2: discrete/continuous time, log-linear/log-log      (seed Fig. 2)
    paper_fig3_transport     P_ij(t) for h = 0.1, 0.4, 1, 2.2                       (seed Fig. 3)
    paper_fig4_h1            h = 1, 2x2: discrete/continuous, log-linear/log-log    (seed Fig. 4)
    paper_fermi              <v> against n and t at eps = 0.6, log-log
    paper_dissipation        <v_n> with restitution r < 1 and drag at eps = 2, and V_sat
                             against (1 - r) (``reports.paper.dissipation``)

as PNG and PDF in ``out_dir``, and returns the Markdown and the seed's claims (``claims.Claim``),
each with its verdict, uncertainties and the rule that produced it (in the docstrings of
``fig2_escape``, ``fig3_transport``, ``fig4_h1``, ``fermi.fermi_claims`` and
``dissipation``). Survival laws are
fitted by maximum likelihood on the binned, censored counts (``reports.stats``).

Every figure states its particle count, horizon and the run's verification summary.
"""

from __future__ import annotations

import time
from pathlib import Path

from reports.paper.claims import claims_json, claims_markdown
from reports.paper.dissipation import dissipation_claims, dissipation_study
from reports.paper.dissipation_figure import dissipation_markdown, figure_dissipation
from reports.paper.fermi import fermi_claims, fermi_ensemble
from reports.paper.fermi_figure import fermi_markdown, figure_fermi
from reports.paper.fig1_phase_space import figure_phase_space, phase_space_markdown
from reports.paper.fig2_escape import escape_analysis, escape_claims, escape_markdown, figure_escape
from reports.paper.fig3_transport import figure_transport, transport_claims, transport_markdown
from reports.paper.fig4_h1 import figure_h1, h1_analysis, h1_claims, h1_markdown
from reports.paper.runs import (
    DEFAULT_PARTICLES,
    PHASE_SPACE_QUICK,
    QUICK_PARTICLES,
    ensure_run,
    largest_run,
    read_manifest,
    say_nothing,
)
from reports.runs.scenes import load_scene


def paper_figures_section(out_dir, particles=None, quick=False, echo=None,
                          runs_dir=None, include_runs=()):
    """Run or reuse the seed's scenes, write the figures (PNG + PDF) into ``out_dir``; returns
    (Markdown with image links relative to ``out_dir``, the claims). ``particles``: per escape
    curve and per transport entry hole (default 10**6; quick 2000); the phase-space scene keeps
    its own count (4000 orbits; quick 200). A complete run of paper-escape or paper-transport
    among ``include_runs`` with more particles replaces the default-scale run for that figure
    and its claims (the paper-scale runs)."""
    echo = echo or say_nothing
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    runs_dir = Path(runs_dir) if runs_dir is not None else out_dir / "runs"
    runs_dir.mkdir(parents=True, exist_ok=True)
    n = int(particles) if particles else (QUICK_PARTICLES if quick else DEFAULT_PARTICLES)
    t0 = time.perf_counter()
    ps_particles = PHASE_SPACE_QUICK if quick else load_scene("paper-phase-space").particles
    ps_run = ensure_run("paper-phase-space", runs_dir, ps_particles, echo)
    runs = {}
    for scene in ("paper-escape", "paper-transport"):
        runs[scene] = ensure_run(scene, runs_dir, n, echo)
        bigger = largest_run(scene, [runs[scene], *include_runs])
        if bigger is not None and bigger != runs[scene]:
            echo(f"paper figures: {scene} verdicts from the included run {bigger}")
            runs[scene] = bigger
    esc_run, tr_run = runs["paper-escape"], runs["paper-transport"]
    echo("paper figures: Fermi acceleration ensemble")
    fermi = fermi_ensemble(bool(quick))
    echo("paper figures: dissipation (restitution and drag at eps = 2)")
    dissipation = dissipation_study(bool(quick))
    echo("paper figures: survival-law inference (escape)")
    esc = escape_analysis(esc_run)
    echo("paper figures: survival-law inference (transport, h = 1)")
    h1 = h1_analysis(tr_run)
    echo("paper figures: claims and drawing")
    esc_claims = escape_claims(esc, esc_run)
    tr_particles = read_manifest(tr_run)["particles"]
    figure_phase_space(ps_run, out_dir)
    figure_escape(esc_run, out_dir, esc)
    _, dominance = figure_transport(tr_run, out_dir)
    tr_claims = transport_claims(dominance, tr_run, tr_particles)
    figure_h1(tr_run, out_dir, h1)
    h1c = h1_claims(h1, tr_run)
    figure_fermi(fermi, out_dir)
    fc = fermi_claims(fermi)
    figure_dissipation(dissipation, out_dir)
    dc = dissipation_claims(dissipation)
    seconds = time.perf_counter() - t0

    def table(claims):
        return claims_markdown(claims_json(claims))

    md = [
        "## The seed's figures from trusted runs",
        "",
        "Every curve comes from a `bouncer run` of a built-in scene, with its verification "
        f"summary. The seed used 10^8 starts per curve; Fig. 2 uses "
        f"{read_manifest(esc_run)['particles']:,} (`{esc_run.name}`), Figs. 3-4 "
        f"{tr_particles:,} (`{tr_run.name}`). Every claim below is also in `report.json`.",
        "",
        phase_space_markdown(ps_run, "paper_fig1_phase_space.png"),
        escape_markdown(esc_run, "paper_fig2_escape.png", table(esc_claims)),
        transport_markdown(tr_run, "paper_fig3_transport.png", table(tr_claims)),
        h1_markdown("paper_fig4_h1.png", table(h1c)),
        fermi_markdown(fermi, "paper_fermi.png"),
        table(fc),
        dissipation_markdown(dissipation, "paper_dissipation.png"),
        table(dc),
        f"(paper figures: {seconds:.0f} s)",
        "",
    ]
    return "\n".join(md), esc_claims + tr_claims + h1c + fc + dc
