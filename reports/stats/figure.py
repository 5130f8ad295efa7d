"""One PNG per curve: the life-table survival in the fit window with the fitted laws, and the
Pearson residuals of the escape counts.

The data are the life table of the window (``reports.stats.life_table``). A law predicts
r_j Q_j escapes in bin j, Q_j = 1 - S(x_{j+1})/S(x_j), with variance r_j Q_j (1 - Q_j).

What is drawn scales with what a reader can see, not with the number of bins: the window's
boundaries are thinned to at most DISPLAY_POINTS spread evenly in log x (the figure's axis,
about 3 pixels apart), the survival is drawn at the kept boundaries (its values there are
exact: the life table's own), and the bins between two kept boundaries form one group whose
residual is that of the group's summed counts, (sum E_j - sum r_j Q_j) / sqrt(sum r_j Q_j
(1 - Q_j)) (the terms are uncorrelated under the law, so the variances add). A window of at
most DISPLAY_POINTS bins is drawn bin by bin. The fits are those of the analysis, on every bin.
"""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from reports.stats.life_table import life_table  # noqa: E402
from reports.stats.likelihood import shape  # noqa: E402

COLOURS = {"exponential": "tab:blue", "power_law": "tab:orange",
           "stretched_exponential": "tab:green"}
DISPLAY_POINTS = 200  # survival points and residual groups across the x axis, at most
LAW_POINTS = 400  # points of each fitted law's line


def display_boundaries(x, points=DISPLAY_POINTS):
    """Indices of the boundaries ``x`` (increasing, > 0) kept for drawing: the first, the last,
    and those nearest to ``points`` values spread evenly in log x; every index when there are
    at most ``points`` bins."""
    if len(x) <= points + 1:
        return np.arange(len(x))
    targets = np.geomspace(x[0], x[-1], points + 1)
    return np.unique(np.concatenate([[0, len(x) - 1], np.searchsorted(x, targets)
                                     .clip(0, len(x) - 1)]))


def group_sums(values, kept):
    """Sums of ``values`` (one per bin) over the groups of bins between kept boundaries."""
    return np.add.reduceat(values, kept[:-1]) if len(kept) > 1 else np.zeros(0)


def plot_curve(result, curve, path):
    """Write the figure of one analysed curve (``analysis.analyse`` result) to ``path``, a PNG
    file (the ``savefig`` target: a path or a binary file)."""
    fits = result["_fits"]
    window = next(iter(fits.values())).window
    table = life_table(curve, window)
    x, s, risk, e = table.x, table.survival, table.at_risk, table.escapes
    sd = s * table.sd_log
    kept = display_boundaries(x)
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(6.4, 6.4), sharex=True,
                                      gridspec_kw={"height_ratios": [3, 1.4]})
    shown = kept[s[kept] > 0]
    top.errorbar(x[shown], s[shown], yerr=1.96 * sd[shown], fmt=".", color="k", ms=3, lw=0.8,
                 label="data (life table, 95%)")
    grid = np.geomspace(x[0], x[-1], LAW_POINTS)
    mid = np.sqrt(x[kept[:-1]] * x[kept[1:]])
    for law, f in fits.items():
        top.plot(grid, np.exp(f.log_survival(grid)), color=COLOURS[law], lw=1.2,
                 label=law.replace("_", " ") + (" (best)" if law == result["best"] else ""))
        h = shape(law, x, window.start, f.params.get("beta"))
        big_q = -np.expm1(-f.scale * np.diff(h))
        expect = risk * big_q
        observed, expected = group_sums(e, kept), group_sums(expect, kept)
        var = group_sums(expect * (1.0 - big_q), kept)
        res = np.divide(observed - expected, np.sqrt(var), out=np.zeros_like(observed),
                        where=var > 0)
        bottom.plot(mid, res, ".", color=COLOURS[law], ms=3)
    top.set_xscale("log")
    top.set_yscale("log")
    top.set_ylim(0.3 * s[shown].min(), 2.0)  # the data's range, not the fastest law's
    top.set_ylabel(f"S(x) / S({window.start:g})")
    top.set_title(f"{result['curve']} ({result['clock']}): best {result['best']}", fontsize=10)
    top.legend(fontsize=8, loc="lower left")  # a falling curve leaves that corner free
    bottom.axhline(0.0, color="k", lw=0.6)
    for level in (-2.0, 2.0):
        bottom.axhline(level, color="k", lw=0.4, ls=":")
    bottom.set_ylabel("Pearson residual" if len(kept) == len(x) else
                      f"Pearson residual ({len(kept) - 1} groups of bins)")
    bottom.set_xlabel("collisions n" if result["clock"] == "collisions" else "time t")
    fig.tight_layout()
    fig.savefig(path, dpi=110, format="png")
    plt.close(fig)
