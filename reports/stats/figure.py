"""One PNG per curve: the life-table survival in the fit window with the fitted laws, and the
Pearson residuals of the escape counts per bin.

Life table (actuarial): in bin j the n_j particles at risk at x_j, less half the competing
escapes of the bin, face E_j escapes: q_j = E_j / r_j, and S(x_{j+1})/S(x_a) = prod (1 - q_i)
with the Greenwood variance S**2 sum q_i / (r_i (1 - q_i)). A law predicts r_j Q_j escapes,
Q_j = 1 - S(x_{j+1})/S(x_j); the residual is (E_j - r_j Q_j) / sqrt(r_j Q_j (1 - Q_j)).
"""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from reports.stats.likelihood import shape  # noqa: E402

COLOURS = {"exponential": "tab:blue", "power_law": "tab:orange",
           "stretched_exponential": "tab:green"}


def life_table(curve, window):
    """(x boundaries, S at them, Greenwood sd, at-risk r_j, escapes E_j) in the window."""
    a = int(np.searchsorted(curve.x, window.start))
    b = a + len(window.escapes)
    later = (curve.escapes + curve.competing + curve.censored)[::-1].cumsum()[::-1]
    risk = later[a:b] - 0.5 * curve.competing[a:b]
    e = curve.escapes[a:b].astype(np.float64)
    q = np.divide(e, risk, out=np.zeros_like(e), where=risk > 0)
    s = np.concatenate([[1.0], np.cumprod(1.0 - q)])
    terms = np.divide(q, risk * (1.0 - q), out=np.zeros_like(q), where=(risk > 0) & (q < 1))
    sd = s * np.sqrt(np.concatenate([[0.0], np.cumsum(terms)]))
    return window.x, s, sd, risk, e


def plot_curve(result, curve, path):
    """Write the figure of one analysed curve (``analysis.analyse`` result) to ``path``."""
    fits = result["_fits"]
    window = next(iter(fits.values())).window
    x, s, sd, risk, e = life_table(curve, window)
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
