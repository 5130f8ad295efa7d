"""The paper's Fig. 2: escape survival through one hole of width 0.3 centred at phi_c, eps = 0.6.

As the paper draws it: discrete time on the left, continuous time on the right; the holes over
or near the large islands (phi_c = 0, 0.5, 1, 1.5) on top, P(n) log-linear and P(t) against
sqrt(t); the holes in the chaotic sea (2, 2.5) below, log-log. On every curve the law of each
of its regimes (intermediate and late tail, ``reports.paper.studies.escape_regimes``) is drawn in
black over its window: the best of the three maximum-likelihood fits there (dotted exponential,
dashed power law, dash-dot stretched exponential), anchored at the data's survival at the window
start. The claims are decided in ``reports.paper.claims.escape_claims``.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from reports.paper.claims.register import ISLAND_HOLES, SEA_HOLES
from reports.paper.figures.style import band, caption, pyplot, save_figure
from reports.paper.studies.paper_runs import read_manifest, run_summary
from reports.runs.survival import read_survival
from reports.stats.hazard import all_cause_survival

LAW_STYLE = {"exponential": ":", "power_law": "--", "stretched_exponential": "-."}


def draw_detail(ax, curve, detail, xs=None, color="k"):
    """The window's best law (stretched when inconclusive), anchored at S(x_a)."""
    law = detail["best"] if detail["best"] in LAW_STYLE else "stretched_exponential"
    a, b = detail["bins"]
    x = np.geomspace(max(curve.x[a], 1e-9), curve.x[b], 80)
    s = all_cause_survival(curve)[a] * np.exp(detail["fits"][law].log_survival(x))
    ax.plot(x if xs is None else xs(x), s, LAW_STYLE[law], color=color, lw=1.1)


def _draw_regimes(ax, a, clock, xs=None):
    """At most three regimes: the intermediate one and the late tail (discrete time) or the
    matched late levels (continuous time)."""
    drawn = 0
    for regime in ("intermediate", "tail" if clock == "collisions" else "matched"):
        d = a["details"].get((clock, regime))
        if d is not None and drawn < 3:
            draw_detail(ax, a["curves"][clock], d, xs)
            drawn += 1


def figure_escape(run_dir, out_dir, analysis):
    plt = pyplot()
    data = read_survival(Path(run_dir) / "survival.csv")
    n = read_manifest(run_dir)["particles"]
    fig, axes = plt.subplots(2, 2, figsize=(12, 9))
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    names = list(dict.fromkeys(name for name, _ in data))
    for i, name in enumerate(names):
        hole = name.split("=", 1)[1]
        if hole not in analysis:
            continue
        row = 0 if hole in ISLAND_HOLES else 1
        col_colour = colors[i % len(colors)]
        for col, clock in enumerate(("collisions", "time")):
            if (name, clock) not in data:
                continue
            x, p, lo, hi = data[name, clock]
            ax = axes[row, col]
            sq = np.sqrt if (row == 0 and clock == "time") else None
            band(ax, x, p, lo, hi, f"phi_c = {hole}", xs=np.sqrt(x) if sq else None,
                 color=col_colour)
            _draw_regimes(ax, analysis[hole], clock, sq)
    for ax in axes.flat:
        ax.set_yscale("log")
        ax.set_ylim(0.3 / n, 1.5)
        ax.set_ylabel("survival P")
        ax.legend(fontsize=7, loc="upper right")
    for ax in axes[1]:
        ax.set_xscale("log")
    axes[0, 0].set_xlim(0, 1200)
    axes[0, 1].set_xlim(0, 150)
    axes[0, 0].set_xlabel("n (collisions)")
    axes[0, 1].set_xlabel("sqrt(t)")
    axes[1, 0].set_xlabel("n (collisions)")
    axes[1, 1].set_xlabel("t")
    axes[1, 0].set_xlim(1, None)
    axes[1, 1].set_xlim(1, None)
    axes[0, 0].set_title("holes over or near the islands: discrete time", fontsize=9)
    axes[0, 1].set_title("holes over or near the islands: continuous time against sqrt(t)",
                         fontsize=9)
    axes[1, 0].set_title("holes in the chaotic sea: discrete time, log-log", fontsize=9)
    axes[1, 1].set_title("holes in the chaotic sea: continuous time, log-log", fontsize=9)
    fig.suptitle("Fig. 2: escape through one hole of width 0.3 centred at phi_c, eps = 0.6. "
                 "Black: maximum-likelihood law of each regime (dotted exponential, dashed "
                 "power law, dash-dot stretched)", fontsize=9)
    caption(fig, "starts 3.85 < phi < 4.15, 2 < v < 4; " + run_summary(run_dir)
            + "; bands: 95% Wilson")
    fig.tight_layout(rect=(0, 0.03, 1, 0.97))
    return save_figure(fig, out_dir, "paper_fig2_escape")


def windows_table(analysis):
    """Markdown table of each hole's windows."""
    rows = ["| phi_c | t_D | n_a | plateau hazard | intermediate (n) | intermediate (t) | "
            "late tail (n) |", "|---|---|---|---|---|---|---|"]
    for hole, a in analysis.items():
        w = a["windows"]

        def span(clock, regime, a=a):
            d = a["details"].get((clock, regime))
            return "-" if d is None else f"[{d['from']:.4g}, {d['to']:.4g}] ({d['escapes']:,})"
        rows.append(f"| {hole} | {w.onset_t:.3g} | {w.onset_n:.3g} | "
                    f"{w.plateau if math.isfinite(w.plateau) else float('nan'):.3g} | "
                    f"{span('collisions', 'intermediate')} | {span('time', 'intermediate')} | "
                    f"{span('collisions', 'tail')} |")
    return "\n".join(rows)


def escape_markdown(run_dir, image, analysis):
    return "\n".join([
        "### Fig. 2: escape (the paper's Section 3)", "",
        f"![Fig. 2: escape survival]({image})", "",
        f"Run: {run_summary(run_dir)}.", "",
        "Regime windows (placed by the physics, `reports/paper/studies/escape_regimes.py`; "
        "escapes in brackets):", "", windows_table(analysis), "",
        f"Holes over or near the islands: {', '.join(ISLAND_HOLES)}; in the chaotic sea: "
        f"{', '.join(SEA_HOLES)}.", ""])
