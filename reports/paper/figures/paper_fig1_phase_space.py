"""The paper's Fig. 1: the phase space at eps = 0.6, phases centred on 0 so that the large
islands around the fixed points (0, pi m) are drawn whole, the escape holes of Fig. 2 as
strips and the start boxes of the escape studies as rectangles.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from fastpath.arithmetic.phase import TWO_PI
from reports.paper.figures.style import caption, pyplot, save_figure
from reports.paper.studies.paper_runs import read_manifest, run_summary
from reports.runs.scenes import load_scene

BOXES = (("paper-escape", "tab:red", "the paper's start box"),
         ("escape-second-box", "tab:purple", "second start box"),
         ("escape-island-start", "tab:green", "island start box"))


def centred_portrait(counts):
    """The (phi, v) histogram over [0, 2 pi) rolled to (-pi, pi]."""
    return np.roll(counts, counts.shape[0] // 2, axis=0)


def _centred(x):
    return (x + math.pi) % TWO_PI - math.pi


def _box(ax, plt, phi, v, colour, label):
    """A start box in centred phases (split where it crosses +-pi)."""
    lo, hi = _centred(phi[0]), _centred(phi[0]) + (phi[1] - phi[0])
    pieces = [(lo, min(hi, math.pi))] + ([(-math.pi, hi - TWO_PI)] if hi > math.pi else [])
    for i, (a, b) in enumerate(pieces):
        ax.add_patch(plt.Rectangle((a, v[0]), b - a, v[1] - v[0], fill=False, ec=colour, lw=1.3,
                                   label=label if i == 0 else None))


def figure_phase_space(run_dir, out_dir):
    plt = pyplot()
    man = read_manifest(run_dir)
    scene = load_scene("paper-phase-space")
    counts = centred_portrait(np.load(Path(run_dir) / "portrait.npy"))
    fig, ax = plt.subplots(figsize=(9, 6))
    ax.imshow(np.log1p(counts.T), origin="lower", aspect="auto", cmap="Greys",
              extent=(-math.pi, math.pi, *scene.v_range), interpolation="nearest")
    esc = load_scene("paper-escape")
    width = esc.hole_widths[0]
    for i, c in enumerate(esc.hole_centres):
        x = _centred(c)
        ax.axvspan(x - width / 2, x + width / 2, color="tab:orange", alpha=0.25, lw=0,
                   label="escape holes (width 0.3)" if i == 0 else None)
        ax.text(x, scene.v_range[1] * 0.985, f"{c:g}", ha="center", va="top", fontsize=7)
    for name, colour, label in BOXES:
        s = load_scene(name)
        _box(ax, plt, s.start_phi, s.start_v, colour, label)
    m = np.arange(1, int(scene.v_range[1] / np.pi) + 1)
    ax.plot(np.zeros_like(m, dtype=float), np.pi * m, "o", ms=5, mfc="none", mec="tab:blue",
            label="fixed points (0, pi m)")
    ax.set_xlabel("collision phase phi (centred)")
    ax.set_ylabel("velocity v after collision")
    ax.set_xlim(-math.pi, math.pi)
    ax.set_title(f"Fig. 1: phase space of the bouncer, eps = {scene.eps:g}; escape holes of "
                 "Fig. 2 as strips (phi_c on top)", fontsize=10)
    ax.legend(loc="upper left", fontsize=7, framealpha=0.9)
    ver = man["verification"]
    caption(fig, f"{man['particles']:,} orbits x {scene.max_collisions:,} collisions "
                 f"({man['collisions']:.3g} states), starts uniform in phi, {scene.start_v[0]:g}"
                 f" < v < {scene.start_v[1]:g}; log(1 + count) of a {scene.phi_bins} x "
                 f"{scene.v_bins} histogram. verify: {ver['sampled']} sampled, worst "
                 f"{ver['worst_error']:.2g} kappa*u, {ver['overstepped']} overstepped")
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    return save_figure(fig, out_dir, "paper_fig1_phase_space")


def phase_space_markdown(run_dir, image):
    return "\n".join([
        "### Fig. 1: phase space at eps = 0.6", "",
        f"![Fig. 1: phase space]({image})", "",
        f"Run: {run_summary(run_dir)}.", "",
        "Elliptic islands around the fixed points (0, pi m) coexist with a chaotic sea that "
        "carries Fermi acceleration. Where each hole lies is measured, not read off the picture"
        " (claims fig2-hole-*, sec4-holes, sec4-hole-2: shares of the strips on islands, "
        "`reports/paper/studies/islands.py`).", ""])
