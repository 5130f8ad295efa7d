"""Seed Fig. 4: h = 1, discrete against continuous time, with the fitted laws; its claims.

The seed (Section 4): "particularly in the plot for hole size 1, ... the long lived orbits are
well approximated by a stretched exponential, a e^{b sqrt(t)}", and Fig. 4 shows stretched
exponential fits to the reflection probability of hole 1 in discrete and continuous time. One
claim per clock, ``fig4-P11-CLOCK``: the late regime of P_11 (``reports.stats.analysis``; the
other outcome's escapes are competing censoring) follows a stretched exponential.

Rule: the late regime's law chosen by ``reports.stats.selection`` (likelihood-ratio tests
against the stretched exponential, Vuong between the simple laws, level 0.05). confirmed:
stretched exponential; refuted: exponential or power law; inconclusive: inconclusive. The
stretched exponent beta (the seed's fit has beta = 1/2) is reported with its interval and
systematic half-range.
"""

from __future__ import annotations

import math
from pathlib import Path

from reports.paper.claims import CONFIRMED, INCONCLUSIVE, REFUTED, Claim
from reports.paper.fig2_escape import draw_regimes, regimes_text
from reports.paper.fig3_transport import transport_curve
from reports.paper.runs import read_manifest, run_summary
from reports.paper.style import band, caption, pyplot, save_figure
from reports.runs.survival import read_survival
from reports.stats.analysis import analyse
from reports.stats.histogram import read_run

H = "1"
CLOCKS = ("collisions", "time")


def h1_analysis(run_dir, h=H):
    """{clock: (curve, analysis)} of P_11 for width h."""
    return {c.clock: (c, analyse(c)) for c in read_run(run_dir)
            if c.experiment == f"h={h}/from hole 1" and c.curve == f"h={h}/P11"}


def h1_claims(analysis, run_dir, h=H):
    claims = []
    for clock in CLOCKS:
        if clock not in analysis:
            continue
        curve, res = analysis[clock]
        best = res["best"]
        verdict = (CONFIRMED if best == "stretched_exponential" else
                   INCONCLUSIVE if best == "inconclusive" else REFUTED)
        m = res["models"]["stretched_exponential"]
        sys = res["systematic"]["stretched_exponential"]["beta"]
        sys = math.inf if sys is None else sys
        unit = "n" if clock == "collisions" else "t"
        lo, hi = res["window"]
        evidence = (f"Late regime of P_11, {unit} in [{lo:.3g}, {hi:.3g}] "
                    f"({res['escapes_in_window']:,} escapes): best law "
                    f"{best.replace('_', ' ')}; stretched beta = {m['beta']:.3f} "
                    f"[{m['beta_ci95'][0]:.3f}, {m['beta_ci95'][1]:.3f}] +- {sys:.2g} (sys); "
                    f"LR stretched vs exponential p = "
                    f"{res['tests']['lr_stretched_vs_exponential']['p']:.2g}, vs power law p = "
                    f"{res['tests']['lr_stretched_vs_power_law']['p']:.2g}. All regimes: "
                    f"{regimes_text(res, unit)}.")
        claims.append(Claim(
            id=f"fig4-P11-{clock}", figure="4",
            seed_says=f"for h = {h} the long-lived reflected orbits (P_11) decay as a stretched "
                      f"exponential in {'discrete' if clock == 'collisions' else 'continuous'} "
                      "time",
            verdict=verdict, evidence=evidence, particles_per_curve=curve.particles,
            statistical={"beta": m["beta"], "beta_ci95": m["beta_ci95"], "c": m["c"],
                         "c_ci95": m["c_ci95"]},
            systematic={"beta": sys}, run=Path(run_dir).name,
            rule="law of the late regime by LR and Vuong tests at level 0.05"))
    return claims


def figure_h1(run_dir, out_dir, analysis, h=H):
    """Fig. 4 as the seed drew it: discrete (left) and continuous (right) time, log-linear
    (top) and log-log (bottom), P_ij with P_11's fitted law in each regime drawn in black."""
    plt = pyplot()
    n = read_manifest(run_dir)["particles"]
    data = read_survival(Path(run_dir) / "survival.csv")
    fig, axes = plt.subplots(2, 2, figsize=(12, 9))
    for col, clock in enumerate(CLOCKS):
        for row in range(2):
            ax = axes[row, col]
            for ij in ("P11", "P12", "P21", "P22"):
                c = transport_curve(data, f"h={h}/{ij}", clock)
                if c is not None:
                    band(ax, *c, ij)
            if clock in analysis:
                draw_regimes(ax, *analysis[clock])
            ax.set_yscale("log")
            ax.set_ylim(0.3 / n, 1.5)
            if row == 1:
                ax.set_xscale("log")
            ax.set_xlabel("n (collisions)" if clock == "collisions" else "t")
            ax.set_ylabel("P_ij")
            ax.set_title(f"{'discrete' if clock == 'collisions' else 'continuous'} time, "
                         f"{'log-linear' if row == 0 else 'log-log'}", fontsize=9)
            ax.legend(fontsize=7, loc="upper right")
    fig.suptitle(f"Fig. 4: transport for h = {h}; black: maximum-likelihood law of each regime "
                 "of P_11 (dotted exponential, dashed power law, dash-dot stretched)", fontsize=9)
    caption(fig, run_summary(run_dir) + " (per entry hole)")
    fig.tight_layout(rect=(0, 0.03, 1, 0.97))
    return save_figure(fig, out_dir, "paper_fig4_h1")


def h1_markdown(image, claims_text):
    return "\n".join([
        "### Fig. 4: h = 1, discrete against continuous time", "",
        f"![Fig. 4: h = 1]({image})", "",
        "Claims (rule in `reports/paper/fig4_h1.py`):", "", claims_text, ""])
