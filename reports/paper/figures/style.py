"""Shared drawing and formatting helpers of the paper's figures.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from reports.runs.survival import Z95


def pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def save_figure(fig, out_dir, stem):
    paths = []
    for ext in ("png", "pdf"):
        path = Path(out_dir) / f"{stem}.{ext}"
        fig.savefig(path, dpi=130)
        paths.append(path)
    pyplot().close(fig)
    return paths


def band(ax, x, p, lo, hi, label, xs=None, **kw):
    pos = p > 0
    xs = x if xs is None else xs
    line, = ax.plot(xs[pos], p[pos], lw=1.2, label=label, **kw)
    ax.fill_between(xs[pos], lo[pos], hi[pos], color=line.get_color(), alpha=0.2, lw=0)
    return line


def caption(fig, text):
    fig.text(0.5, 0.005, text, ha="center", va="bottom", fontsize=7, wrap=True)


def hole_label(name):
    return name.split("=", 1)[1]


def chi2_dof(fit, x, p, lo, hi):
    sel = (x >= fit.window[0]) & (x <= fit.window[1]) & (p > 0) & (lo > 0)
    sig = (np.log(hi[sel]) - np.log(lo[sel])) / (2 * Z95)
    return float(np.sum(((np.log(p[sel]) - np.log(fit(x[sel]))) / sig) ** 2)
                 / max(1, sel.sum() - 2))


def yes_no(ok):
    return {True: "yes", False: "**no**", None: "n/a"}[ok]
