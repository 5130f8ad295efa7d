"""Seed Fig. 1: the phase space at eps = 0.6.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from reports.paper.runs import read_manifest, run_summary
from reports.paper.style import caption, pyplot, save_figure
from reports.runs.scenes import load_scene


def figure_phase_space(run_dir, out_dir):
    plt = pyplot()
    man = read_manifest(run_dir)
    scene = load_scene("paper-phase-space")
    counts = np.load(Path(run_dir) / "portrait.npy")
    fig, ax = plt.subplots(figsize=(8, 5.6))
    ax.imshow(np.log1p(counts.T), origin="lower", aspect="auto", cmap="Greys",
              extent=(0, 2 * np.pi, *scene.v_range), interpolation="nearest")
    esc = load_scene("paper-escape")
    (p0, p1), (v0, v1) = esc.start_phi, esc.start_v
    ax.add_patch(plt.Rectangle((p0, v0), p1 - p0, v1 - v0, fill=False, ec="tab:red", lw=1.2,
                               label="escape start box"))
    m = np.arange(1, int(scene.v_range[1] / np.pi) + 1)
    ax.plot(np.zeros_like(m, dtype=float), np.pi * m, "o", ms=5, mfc="none", mec="tab:blue",
            label="fixed points (0, pi m)", clip_on=False)
    for c in esc.hole_centres:
        ax.axvline(c, ymin=0.97, ymax=1.0, color="tab:orange", lw=2)
    ax.set_xlabel("collision phase phi")
    ax.set_ylabel("velocity v after collision")
    ax.set_xlim(0, 2 * np.pi)
    ax.set_title(f"Fig. 1: phase space of the bouncer, eps = {scene.eps:g} "
                 f"(orange ticks: escape hole centres)", fontsize=10)
    ax.legend(loc="upper center", fontsize=7, framealpha=0.9)
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
        "### Fig. 1: phase space at eps = 0.6",
        "",
        f"![Fig. 1: phase space]({image})",
        "",
        f"Run: {run_summary(run_dir)}.",
        "",
        "Seed's claim: elliptic islands around the fixed points (0, pi m) coexisting with a "
        "chaotic sea that carries Fermi acceleration; the structure is nearly periodic in v with "
        "period pi, visibly not at small v. (A qualitative figure: look at it.)",
        "",
    ])
