"""The dynamics section's figure ``dynamics_diffusion``: velocity diffusion in discrete time, the
mean squared velocity change against n. It takes the study dict
(``reports.paper.studies.dynamics_study``) and writes PNG and PDF into ``out_dir``.
"""

from __future__ import annotations

import numpy as np

from reports.paper.figures.style import pyplot, save_figure


def diffusion_figure(study, out_dir):
    """Mean squared velocity change against n for each amplitude of the diffusion study."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7, 4.6))
    for d in study["accelerator"]["diffusion"]:
        n = np.array(d["n"], dtype=float)
        msd = np.array(d["msd"])
        ax.loglog(n, msd, "o-", ms=3, lw=1,
                  label=f"eps = {d['eps']}: slope {d['mu']:.3f} +- {d['mu_se']:.3f}")
    n = np.array(study["accelerator"]["diffusion"][0]["n"], dtype=float)
    ax.loglog(n, n * 2.0, "k:", lw=1, label="slope 1 (normal)")
    ax.loglog(n, n**2 * 0.5, "k--", lw=1, label="slope 2 (ballistic)")
    ax.set_xlabel("n (collisions)")
    ax.set_ylabel("<(v_n - v_0)^2>")
    ax.set_title("Velocity diffusion in discrete time", fontsize=10)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return save_figure(fig, out_dir, "dynamics_diffusion")
