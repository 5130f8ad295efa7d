"""Fermi acceleration figure: <v> against n and t at eps = 0.6.
"""

from __future__ import annotations

import math

import numpy as np

from reports.paper.figures.style import caption, pyplot, save_figure
from reports.paper.studies.sampling import fmt, verified_text


def figure_fermi(fermi, out_dir):
    plt = pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    for ax, x, y, beta, err, amp, window, expected, label in (
            (axes[0], fermi.n, fermi.mean_v_n, fermi.beta_n, fermi.beta_n_err, fermi.amp_n,
             fermi.n_window, 0.5, "n (collisions)"),
            (axes[1], fermi.t, fermi.mean_v_t, fermi.beta_t, fermi.beta_t_err, fermi.amp_t,
             fermi.t_window, 1 / 3, "t")):
        ok = np.isfinite(y) & (x > 0)
        if ax is axes[1]:
            ok &= fermi.reached_t == fermi.particles
        ax.loglog(x[ok], y[ok], "o", ms=3, label="<v>")
        if math.isfinite(beta):
            xf = np.geomspace(*window, 50)
            ax.loglog(xf, amp * xf**beta, "k-", lw=1.5,
                      label=f"fit: slope {fmt(beta, err)}")
            x0 = window[0]
            ref = amp * x0**beta
            xr = np.geomspace(x[ok][0], x[ok][-1], 20)
            ax.loglog(xr, ref * (xr / x0) ** expected, "--", color="tab:red", lw=1,
                      label=f"slope {expected:.3g} (expected)")
        ax.set_xlabel(label)
        ax.set_ylabel("<v>")
        ax.legend(fontsize=8)
    axes[0].set_title("<v_n> against collisions", fontsize=10)
    axes[1].set_title("<v(t)> against time (v after the last collision before t)", fontsize=10)
    fig.suptitle("Fermi acceleration at eps = 0.6 from the paper's escape start box, no holes",
                 fontsize=11)
    caption(fig, f"{fermi.particles:,} particles, horizon n <= {int(fermi.n[-1]):,} and "
                  f"t <= {fermi.t[-1]:.3g}, {fermi.collisions:.3g} collisions, {fermi.flagged} "
                  f"undecidable; {verified_text(fermi.verification)}; slope +- from a bootstrap "
                  "over 64 particle blocks")
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    return save_figure(fig, out_dir, "paper_fermi")


def fermi_markdown(fermi, image):
    ok_n = abs(fermi.beta_n - 0.5) <= 3 * fermi.beta_n_err
    ok_t = abs(fermi.beta_t - 1 / 3) <= 3 * fermi.beta_t_err
    return "\n".join([
        "### Fermi acceleration at eps = 0.6",
        "",
        f"![Fermi acceleration]({image})",
        "",
        f"{fermi.particles:,} particles from the paper's escape start box, no holes; "
        f"{verified_text(fermi.verification)}.",
        "",
        "The paper (Section 3): chaotic orbits diffuse in velocity, typical v ~ sqrt(n), "
        "hence t ~ n^(3/2) and v ~ t^(1/3); eps = 0.6 is below the accelerator modes, so the "
        "diffusion is normal.",
        "",
        f"Measured: <v_n> ~ n^{fmt(fermi.beta_n, fermi.beta_n_err)} over n in "
        f"[{fermi.n_window[0]:g}, {fermi.n_window[1]:g}] ({'consistent with' if ok_n else 'NOT'}"
        f" 1/2 within 3 sigma); <v(t)> ~ t^{fmt(fermi.beta_t, fermi.beta_t_err)} over t in "
        f"[{fermi.t_window[0]:g}, {fermi.t_window[1]:.3g}] "
        f"({'consistent with' if ok_t else 'NOT'} 1/3 within 3 sigma).",
        "",
    ])
