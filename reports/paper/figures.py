"""The seed's figures from trusted runs, with the seed's claims checked on them.

``paper_figures_section(out_dir, particles=None, quick=False, echo=None, runs_dir=None)`` runs
(or reuses complete run directories in ``runs_dir``, default ``out_dir/runs``) the built-in
scenes paper-phase-space, paper-escape and paper-transport through ``reports.runs.driver.run``,
draws

    paper_fig1_phase_space   phase space at eps = 0.6                         (seed Fig. 1)
    paper_fig2_escape        P(n) log-linear and log-log, P(t) against sqrt(t) (seed Fig. 2)
    paper_fig3_transport     P_ij(t) for h = 0.1, 0.4, 1, 2.2                 (seed Fig. 3)
    paper_fig4_h1            h = 1, discrete vs continuous, stretched fits     (seed Fig. 4)
    paper_fermi              <v> against n and t at eps = 0.6, log-log

as PNG and PDF in ``out_dir``, and returns Markdown that states, for each figure, what the seed
claims and whether the data show it. The verdicts are computed:

* Fig. 2: on the late discrete-time decay (100/N <= P <= 0.01) an exponential and a power law
  are fitted (``reports.stats.least_squares.fit_survival``); the better chi^2/dof names the decay.
* Fig. 3: at the time t_q where the survival of entry hole 1, P_11 + P_12, has fallen to q
  (1e-3, or 100/N if larger), R = P_11/P_12; P_11 "dominates at late times" when R >= 10 and the
  hole-1 tail goes on for at least a decade in time beyond t_q (the last escape is >= 10 t_q).
* Fig. 4: stretched exponential and power law fitted to P_11's tail, chi^2/dof compared.
* Fermi: the slopes of log<v> against log n and log t (``reports.paper.fermi``).

Every figure states its particle count, horizon and the run's verification summary.
"""

from __future__ import annotations

import time
from pathlib import Path

from reports.paper.fermi import fermi_ensemble
from reports.paper.fermi_figure import fermi_markdown, figure_fermi
from reports.paper.fig1_phase_space import figure_phase_space, phase_space_markdown
from reports.paper.fig2_escape import escape_markdown, figure_escape
from reports.paper.fig3_transport import figure_transport, transport_markdown
from reports.paper.fig4_h1 import figure_h1, h1_markdown
from reports.paper.runs import (
    DEFAULT_PARTICLES,
    PHASE_SPACE_QUICK,
    QUICK_PARTICLES,
    ensure_run,
    say_nothing,
)
from reports.runs.scenes import load_scene


def paper_figures_section(out_dir, particles=None, quick=False, echo=None,
                          runs_dir=None) -> str:
    """Run or reuse the seed's scenes, write the figures (PNG + PDF) into ``out_dir`` and return
    Markdown (image links relative to ``out_dir``). ``particles``: per escape curve and per
    transport entry hole (default 10**6; quick 2000); the phase-space scene keeps its own count
    (4000 orbits; quick 200)."""
    echo = echo or say_nothing
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    runs_dir = Path(runs_dir) if runs_dir is not None else out_dir / "runs"
    runs_dir.mkdir(parents=True, exist_ok=True)
    n = int(particles) if particles else (QUICK_PARTICLES if quick else DEFAULT_PARTICLES)
    t0 = time.perf_counter()
    ps_particles = PHASE_SPACE_QUICK if quick else load_scene("paper-phase-space").particles
    ps_run = ensure_run("paper-phase-space", runs_dir, ps_particles, echo)
    esc_run = ensure_run("paper-escape", runs_dir, n, echo)
    tr_run = ensure_run("paper-transport", runs_dir, n, echo)
    echo("paper figures: Fermi acceleration ensemble")
    fermi = fermi_ensemble(bool(quick))
    echo("paper figures: drawing")
    figure_phase_space(ps_run, out_dir)
    _, esc = figure_escape(esc_run, out_dir)
    _, dominance = figure_transport(tr_run, out_dir)
    _, h1 = figure_h1(tr_run, out_dir)
    figure_fermi(fermi, out_dir)
    seconds = time.perf_counter() - t0
    md = [
        "## The seed's figures from trusted runs",
        "",
        "Every curve comes from a `bouncer run` of a built-in scene (runs in "
        f"`{runs_dir.name}/`), with its verification summary. The seed used 10^8 starts per "
        f"curve; these use {n:,}, so the tails end near P ~ 1/N = {1 / n:.0e}.",
        "",
        phase_space_markdown(ps_run, "paper_fig1_phase_space.png"),
        escape_markdown(esc, esc_run, "paper_fig2_escape.png"),
        transport_markdown(dominance, tr_run, "paper_fig3_transport.png"),
        h1_markdown(h1, "paper_fig4_h1.png"),
        fermi_markdown(fermi, "paper_fermi.png"),
        f"(paper figures: {seconds:.0f} s)",
        "",
    ]
    return "\n".join(md)
