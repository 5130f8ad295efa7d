"""The dynamics section's figure ``dynamics_lyapunov``: the Lyapunov exponents converging, per
collision against n and per unit time against t. It takes the study dict
(``reports.paper.studies.dynamics_study``) and writes PNG and PDF into ``out_dir``.
"""

from __future__ import annotations

import numpy as np

from reports.paper.figures.style import caption, pyplot, save_figure


def lyapunov_figure(study, out_dir):
    """lambda per collision against n and lambda per unit time against t (ensemble means)."""
    lyap = study["lyapunov"]
    plt = pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.6))
    n = np.array(lyap["checkpoints"], dtype=float)
    mean, se = np.array(lyap["mean_per_collision"]), np.array(lyap["se_per_collision"])
    axes[0].semilogx(n, mean, "o-", ms=3, label="mean over orbits")
    axes[0].fill_between(n, mean - 1.96 * se, mean + 1.96 * se, alpha=0.25, lw=0)
    axes[0].axhline(0, color="grey", lw=0.8)
    axes[0].set_xlabel("n (collisions)")
    axes[0].set_ylabel("lambda per collision")
    axes[0].set_title(f"per collision: {mean[-1]:.4f} +- {se[-1]:.4f} at n = {int(n[-1]):,}",
                      fontsize=10)
    t = np.exp(np.array(lyap["mean_log_time"]))
    log_lt = np.array(lyap["mean_log_per_time"], dtype=float)
    ok = np.isfinite(log_lt)
    axes[1].loglog(t[ok], np.exp(log_lt[ok]), "o", ms=3, label="geometric mean over orbits")
    alpha = lyap["alpha"]
    if np.isfinite(alpha) and ok.any():
        late = ok & (n >= n[-1] / 100)
        t0, y0 = t[late][0], np.exp(log_lt[late][0])
        tt = np.geomspace(t[late][0], t[late][-1], 20)
        axes[1].loglog(tt, y0 * (tt / t0) ** alpha, "k-",
                       label=f"fit: t^({alpha:.3f} +- {lyap['alpha_se']:.3f})")
        axes[1].loglog(tt, y0 * (tt / t0) ** (-1 / 3), "r--", lw=1, label="t^(-1/3)")
    axes[1].set_xlabel("t")
    axes[1].set_ylabel("lambda per unit time")
    axes[1].set_title("per unit time: falls towards zero", fontsize=10)
    for ax in axes:
        ax.legend(fontsize=8)
    fig.suptitle(f"Largest Lyapunov exponent at eps = {lyap['eps']} (tangent map, "
                 f"{lyap['orbits']} orbits from the paper's start box)", fontsize=11)
    caption(fig, f"{lyap['orbits']} orbits x {lyap['collisions_per_orbit']:,} collisions; band: "
                 "95% (1.96 standard errors over orbits); fit over the last two decades of n, "
                 "error from a bootstrap over orbits")
    fig.tight_layout(rect=(0, 0.04, 1, 0.95))
    return save_figure(fig, out_dir, "dynamics_lyapunov")
