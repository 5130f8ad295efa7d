"""Late survivors of the escape problem, the paper's mechanism made visible (sampled studies,
``reports.paper.studies.followed_samples.escape_sample``):

(a) where they are: the states of survivors after collision n_tail (the slow population holds
    90% of the escapes) over their next 200 collisions, on the phase portrait (centred phases):
    for the holes in the chaotic sea they circle the large islands, for a hole over the islands
    the few left sit elsewhere;
(b) the orbits escaping at time t in the intermediate regime made n ~ t^(1/2) collisions (median
    n of the escapes per quarter-decade of t, island holes), not the n ~ t^(2/3) of a typical
    diffusing orbit;
(c) the slow decay does not accelerate: the mean time per collision t/n of the escapes after
    n_half, per quarter-decade of their n, stays flat (velocity diffusion would make it grow as
    n^(1/2)).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from reports.paper.figures.paper_fig1_phase_space import centred_portrait
from reports.paper.figures.style import caption, pyplot, save_figure
from reports.paper.studies.islands import centred
from reports.runs.scenes import load_scene


def _median_by_t(x, t, per_decade=4, minimum=20):
    """Median of x per quarter-decade of t (bins with at least ``minimum`` values)."""
    if not len(t):
        return np.array([]), np.array([])
    top = max(t.max() * 1.0001, max(t.min(), 1.0) * 1.01)
    edges = np.geomspace(max(t.min(), 1.0), top,
                         max(2, int(per_decade * math.log10(top / max(t.min(), 1.0)))) + 1)
    k = np.searchsorted(edges, t, side="right") - 1
    mids, meds = [], []
    for b in range(len(edges) - 1):
        sel = x[k == b]
        if len(sel) >= minimum:
            mids.append(math.sqrt(edges[b] * edges[b + 1]))
            meds.append(float(np.median(sel)))
    return np.array(mids), np.array(meds)


def _legend(ax, **kw):
    if ax.get_legend_handles_labels()[0]:  # a quick study may leave a panel without data
        ax.legend(fontsize=7, **kw)


def figure_survivors(portrait_run, out_dir, analysis, follow, snapshots):
    """``follow``: {hole: Followed}; ``snapshots``: {hole: collision count of its snapshot}."""
    plt = pyplot()
    scene = load_scene("paper-phase-space")
    counts = centred_portrait(np.load(Path(portrait_run) / "portrait.npy"))
    fig, axes = plt.subplots(1, 3, figsize=(16, 5.4))
    ax = axes[0]
    ax.imshow(np.log1p(counts.T), origin="lower", aspect="auto", cmap="Greys", alpha=0.5,
              extent=(-math.pi, math.pi, *scene.v_range), interpolation="nearest")
    colours = {"2": "tab:blue", "2.5": "tab:cyan", "1": "tab:red", "0": "tab:orange"}
    for hole, colour in colours.items():
        fol, s = follow.get(hole), snapshots.get(hole)
        if fol is None or s is None or s not in fol.snapshots:
            continue
        _, phi, v, _ = fol.snapshots[s]
        ok = np.isfinite(phi)
        ax.plot(centred(phi[ok]), v[ok], ",", color=colour, alpha=0.6, rasterized=True)
        ax.plot([], [], "o", ms=3, color=colour,
                label=f"phi_c = {hole}: {len(phi)} survivors after n = {s}")
    ax.set_xlim(-math.pi, math.pi)
    ax.set_ylim(0, 12)
    ax.set_xlabel("collision phase phi (centred)")
    ax.set_ylabel("v")
    ax.set_title("(a) late survivors, next 200 collisions", fontsize=9)
    _legend(ax, loc="upper left")
    ax = axes[1]
    for hole in ("0", "0.5", "1", "1.5"):
        fol = follow.get(hole)
        if fol is None:
            continue
        esc = fol.exit >= 0
        mids, meds = _median_by_t(fol.n[esc].astype(float), fol.t[esc])
        ax.plot(mids, meds, "o-", ms=3, lw=0.8, label=f"phi_c = {hole}")
        d = analysis.get(hole, {}).get("details", {}).get(("time", "intermediate"))
        if d is not None and hole == "1":
            ax.axvspan(d["from"], d["to"], color="grey", alpha=0.12, lw=0,
                       label="intermediate window (phi_c = 1)")
            t0 = math.sqrt(d["from"] * d["to"])
            n0 = float(np.interp(math.log(t0), np.log(mids), meds)) if len(mids) else 1.0
            tt = np.geomspace(d["from"], d["to"], 10)
            ax.plot(tt, n0 * (tt / t0) ** 0.5, "k--", lw=1, label="n ~ t^(1/2)")
            ax.plot(tt, n0 * (tt / t0) ** (2 / 3), "k:", lw=1, label="n ~ t^(2/3)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("escape time t")
    ax.set_ylabel("median collisions n of the escapes")
    ax.set_title("(b) holes over the islands: n of the orbits escaping at t", fontsize=9)
    _legend(ax)
    ax = axes[2]
    for hole in ("2", "2.5", "1", "1.5"):
        fol = follow.get(hole)
        n_half = analysis.get(hole, {}).get("windows")
        if fol is None or n_half is None or n_half.n_at.get("half") is None:
            continue
        late = (fol.exit >= 0) & (fol.n > n_half.n_at["half"])
        n = fol.n[late].astype(float)
        mids, meds = _median_by_t(fol.t[late] / n, n)
        if len(mids):
            ax.plot(mids, meds, "o-", ms=3, lw=0.8,
                    label=f"phi_c = {hole} (n > {n_half.n_at['half']:g})")
    if ax.lines:  # the diffusing slope, anchored at the first point drawn
        xs = np.concatenate([line.get_xdata() for line in ax.lines])
        x0, y0 = ax.lines[0].get_xdata()[0], ax.lines[0].get_ydata()[0]
        nn = np.geomspace(xs.min(), xs.max(), 10)
        ax.plot(nn, y0 * (nn / x0) ** 0.5, "k:", lw=1, label="n^(1/2) (diffusing)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("collisions n at escape")
    ax.set_ylabel("median t/n (twice the mean velocity)")
    ax.set_title("(c) the slow decay: time per collision of late escapes", fontsize=9)
    _legend(ax)
    sizes = {h: f.particles for h, f in follow.items()}
    caption(fig, "Sampled studies of the paper's escape setup (eps = 0.6, start box 3.85 < phi <"
                 " 4.15, 2 < v < 4), each particle followed with fastpath.step and its n and t "
                 "recorded together: " + ", ".join(f"phi_c = {h}: {m:,}"
                                                   for h, m in sizes.items()) + " starts")
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    return save_figure(fig, out_dir, "paper_survivors")
