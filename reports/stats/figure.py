"""One PNG per curve: the life-table survival in the fit window with the fitted laws, and the
Pearson residuals of the escape counts per bin.

The data are the life table of the window (``reports.stats.life_table``). A law predicts
r_j Q_j escapes, Q_j = 1 - S(x_{j+1})/S(x_j); the residual is
(E_j - r_j Q_j) / sqrt(r_j Q_j (1 - Q_j)).
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


def plot_curve(result, curve, path):
    """Write the figure of one analysed curve (``analysis.analyse`` result) to ``path``."""
    fits = result["_fits"]
    window = next(iter(fits.values())).window
    table = life_table(curve, window)
    x, s, risk, e = table.x, table.survival, table.at_risk, table.escapes
    sd = s * table.sd_log
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(6.4, 6.4), sharex=True,
                                      gridspec_kw={"height_ratios": [3, 1.4]})
    keep = s > 0
    top.errorbar(x[keep], s[keep], yerr=1.96 * sd[keep], fmt=".", color="k", ms=3, lw=0.8,
                 label="data (life table, 95%)")
    grid = np.geomspace(x[0], x[-1], 400)
    mid = np.sqrt(x[:-1] * x[1:])
    for law, f in fits.items():
        top.plot(grid, np.exp(f.log_survival(grid)), color=COLOURS[law], lw=1.2,
                 label=law.replace("_", " ") + (" (best)" if law == result["best"] else ""))
        h = shape(law, x, window.start, f.params.get("beta"))
        big_q = -np.expm1(-f.scale * np.diff(h))
        expect = risk * big_q
        var = expect * (1.0 - big_q)
        res = np.divide(e - expect, np.sqrt(var), out=np.zeros_like(e), where=var > 0)
        bottom.plot(mid, res, ".", color=COLOURS[law], ms=3)
    top.set_xscale("log")
    top.set_yscale("log")
    top.set_ylim(0.3 * s[keep].min(), 2.0)  # the data's range, not the fastest law's
    top.set_ylabel(f"S(x) / S({window.start:g})")
    top.set_title(f"{result['curve']} ({result['clock']}): best {result['best']}", fontsize=10)
    top.legend(fontsize=8)
    bottom.axhline(0.0, color="k", lw=0.6)
    for level in (-2.0, 2.0):
        bottom.axhline(level, color="k", lw=0.4, ls=":")
    bottom.set_ylabel("Pearson residual")
    bottom.set_xlabel("collisions n" if result["clock"] == "collisions" else "time t")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
