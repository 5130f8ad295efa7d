"""The paper's Fig. 4: h = 1, discrete time (left) against continuous time (right).

Top: log P_ij against sqrt(n) and sqrt(t), where exp(-c x^(1/2)) is a straight line; bottom:
log-log. In black, the maximum-likelihood stretched exponential of P_11 over its long-lived
window (``reports.paper.claims.transport_claims.long_lived_detail``), anchored at the data there;
the fitted beta is in the legend (the paper leaves open whether it is exactly 1/2).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from reports.paper.claims.transport_claims import long_lived_detail
from reports.paper.figures.paper_fig3_transport import PAIRS
from reports.paper.figures.style import band, caption, pyplot, save_figure
from reports.paper.studies.paper_runs import read_manifest, run_summary
from reports.runs.scenes import CLOCKS
from reports.runs.survival import read_survival
from reports.stats.hazard import curve_probability


def figure_h1(run_dir, out_dir, transport, h="1"):
    plt = pyplot()
    n = read_manifest(run_dir)["particles"]
    data = read_survival(Path(run_dir) / "survival.csv")
    fig, axes = plt.subplots(2, 2, figsize=(12, 9))
    for col, clock in enumerate(CLOCKS):
        detail = long_lived_detail(transport[h], clock) if h in transport else None
        for row in range(2):
            ax = axes[row, col]
            sq = np.sqrt if row == 0 else None
            for ij in PAIRS:
                c = data.get((f"h={h}/{ij}", clock))
                if c is not None:
                    band(ax, *c, ij, xs=np.sqrt(c[0]) if sq else None)
            if detail is not None:
                curve = transport[h][1][clock]["P11"]
                a, b = detail["bins"]
                fit = detail["fits"]["stretched_exponential"]
                x = np.geomspace(curve.x[a], curve.x[b], 80)
                p = curve_probability(curve)[a] * np.exp(fit.log_survival(x))
                ax.plot(np.sqrt(x) if sq else x, p, "k-.", lw=1.2,
                        label=f"stretched fit, beta = {fit.params['beta']:.2f}")
            ax.set_yscale("log")
            ax.set_ylim(0.3 / n, 1.5)
            if row == 1:
                ax.set_xscale("log")
            unit = "n" if clock == "collisions" else "t"
            ax.set_xlabel(f"sqrt({unit})" if row == 0 else unit)
            ax.set_ylabel("P_ij")
            ax.set_title(f"{'discrete' if clock == 'collisions' else 'continuous'} time"
                         f"{', against the square root' if row == 0 else ', log-log'}",
                         fontsize=9)
            ax.legend(fontsize=7, loc="upper right")
    fig.suptitle(f"Fig. 4: transport for h = {h}; black: maximum-likelihood stretched "
                 "exponential of P_11 over its long-lived window", fontsize=9)
    caption(fig, run_summary(run_dir) + " (per entry hole)")
    fig.tight_layout(rect=(0, 0.03, 1, 0.97))
    return save_figure(fig, out_dir, "paper_fig4_h1")


def h1_markdown(image):
    return "\n".join([
        "### Fig. 4: h = 1, discrete against continuous time", "",
        f"![Fig. 4: h = 1]({image})", ""])
