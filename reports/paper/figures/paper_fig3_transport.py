"""The paper's Fig. 3: transmission and reflection probabilities P_ij(t) for hole widths 0.1,
0.4, 1 and 2.2 (holes centred at 0 and pi, starts uniform on hole i with 2 < v < 4).

All four P_ij per width, continuous time, log-log; h = 2.2 on a linear time axis to its end,
where the last entrant has left. The grey line marks the long-lived time (the entrants of
hole 1 still inside fall to ``rules.LONG_LIVED_LEVEL``) with the share leaving by hole 2 there.
The claims are decided in ``reports.paper.claims.transport_claims``.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from reports.paper.claims.transport_claims import trap_measure
from reports.paper.figures.style import band, caption, pyplot, save_figure
from reports.paper.studies.paper_runs import read_manifest, run_summary
from reports.runs.survival import read_survival

PAIRS = ("P11", "P12", "P21", "P22")


def hole_widths(data):
    return list(dict.fromkeys(name.split("/")[0][2:] for name, _ in data if "/" in name))


def figure_transport(run_dir, out_dir, transport):
    plt = pyplot()
    n = read_manifest(run_dir)["particles"]
    data = read_survival(Path(run_dir) / "survival.csv")
    widths = hole_widths(data)
    fig, axes = plt.subplots(2, 2, figsize=(11, 8.4), squeeze=False)
    for ax, h in zip(axes.ravel(), widths, strict=False):
        last = 0.0
        for ij in PAIRS:
            c = data.get((f"h={h}/{ij}", "time"))
            if c is None:
                continue
            band(ax, *c, ij)
            x, p = c[0], c[1]
            if (p > 0).any():
                last = max(last, float(x[np.flatnonzero(p > 0)[-1]]))
        ax.set_yscale("log")
        ax.set_ylim(0.3 / n, 1.5)
        if h == "2.2":
            ax.set_xlim(0, 1.15 * last)
            ax.axvline(last, color="k", ls="--", lw=0.8)
            ax.text(last, 3 / n, f" all {2 * n:,} entrants\n gone by t = {last:.3g}",
                    fontsize=7, va="bottom", ha="right")
        else:
            ax.set_xscale("log")
            ax.set_xlim(1, None)
            got = trap_measure(transport[h]) if h in transport else None
            if got is not None:
                k11, k12, share, ci, t = got
                ax.axvline(t, color="grey", ls=":", lw=1)
                ax.text(0.03, 0.04, f"t = {t:.3g}: entrants of hole 1 still inside = "
                        f"{k11 + k12:,}\nshare leaving by hole 2 = {share:.3f} "
                        f"[{ci[0]:.3f}, {ci[1]:.3f}]", transform=ax.transAxes, fontsize=7,
                        bbox={"fc": "white", "ec": "none", "alpha": 0.8})
        ax.set_xlabel("t")
        ax.set_ylabel("P_ij(t)")
        ax.set_title(f"h = {h}", fontsize=10)
        ax.legend(fontsize=7, loc="upper right")
    fig.suptitle("Fig. 3: transport P_ij(t), holes centred at 0 (1) and pi (2), eps = 0.6",
                 fontsize=11)
    caption(fig, "starts uniform on hole i, 2 < v < 4; " + run_summary(run_dir)
            + " (per entry hole and width); bands: 95% Wilson")
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    return save_figure(fig, out_dir, "paper_fig3_transport")


def transport_markdown(run_dir, image):
    return "\n".join([
        "### Fig. 3: transport (the paper's Section 4)", "",
        f"![Fig. 3: transport P_ij(t)]({image})", "",
        f"Run: {run_summary(run_dir)} (per entry hole and width).", ""])
