"""The dynamics section's figure ``dynamics_eps_c``: Greene's eps_c against the velocity of the
invariant curve, and its departure from the standard map's K_c/4. It takes the study dict
(``reports.paper.studies.dynamics_study``) and writes PNG and PDF into ``out_dir``.
"""

from __future__ import annotations

import numpy as np

from reports.paper.figures.style import caption, pyplot, save_figure


def eps_c_figure(study, out_dir):
    """Greene's eps_c against the curve's velocity (left), and its departure from the standard
    map's K_c/4 with the high-velocity fits (right)."""
    crit = study["critical"]
    k4 = crit["k_c_quarter"]
    rows = crit["rows"]
    plt = pyplot()
    fig, (ax, dev) = plt.subplots(1, 2, figsize=(13, 5))
    pairs = (([], "golden: omega = j + 0.618", "o"), ([2], "golden^2: omega = j + 0.382", "s"))
    for prefix, label, marker in pairs:
        sel = sorted((r for r in rows if r["prefix"] == prefix), key=lambda r: r["v"])
        v = np.array([r["v"] for r in sel])
        y = np.array([r["eps_c"] for r in sel])
        err = np.array([r["uncertainty"] for r in sel])
        ax.errorbar(v, y, yerr=err, fmt=marker + "-", ms=4, lw=1, label=label)
        dev.errorbar(v, 1e3 * (y - k4), yerr=1e3 * err, fmt=marker, ms=4, label=label)
    others = [r for r in rows if r["prefix"] not in ([], [2])]
    if others:
        ax.plot([r["v"] for r in others], [r["eps_c"] for r in others], "^", ms=5,
                color="grey", label="other noble curves (low bands)")
    for a in (ax, dev):
        a.set_xscale("log")
        a.set_xlabel("velocity of the curve, v = pi*omega")
    ax.axhline(k4, color="k", ls="--", lw=1, label=f"Holmes / standard map: K_c/4 = {k4:.6f}")
    ax.set_ylabel("eps_c (Greene's residue criterion)")
    ax.set_title("Break-up of invariant spanning curves, by velocity", fontsize=10)
    ax.legend(fontsize=7)
    v = np.geomspace(min(r["v"] for r in rows if r["band"] >= 1), 2000, 100)
    for name, fit in crit["limits"].items():
        dev.plot(v, 1e3 * (fit["a"] - k4 + fit["b"] / v + fit["c"] / v**2), ":", lw=1,
                 label=f"fit ({name}): a - K_c/4 = {fit['a'] - k4:+.1e}, b = {fit['b']:+.4f}")
    dev.axhline(0, color="k", ls="--", lw=1)
    dev.set_ylabel("1000 (eps_c - K_c/4)")
    dev.set_xlim(left=3)
    dev.set_ylim(-3, 12)
    dev.set_title("Approach to the standard map: eps_c = K_c/4 + b/v + c/v^2", fontsize=10)
    dev.legend(fontsize=7)
    caption(fig, "float64 residues of symmetric periodic orbits, approximants up to period "
                 f"{max(max(r['periods']) for r in rows)}; error bars: geometric tail of the "
                 "approximants plus rounding. Below v ~ 2 (band 0) curves survive far longer.")
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    return save_figure(fig, out_dir, "dynamics_eps_c")
