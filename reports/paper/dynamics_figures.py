"""Figures of the dynamics section: residue against eps, Lyapunov convergence in both clocks,
eps_c against velocity band, velocity diffusion. Each takes the study dict
(``reports.paper.dynamics_study``) and writes PNG and PDF into ``out_dir``.
"""

from __future__ import annotations

import numpy as np

from reports.paper.style import caption, pyplot, save_figure


def residue_figure(study, out_dir):
    """Residue R = (2 - trace)/4 of the fixed points and of the period-2 orbits against eps."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(8, 5))
    ax.axhspan(0, 1, color="tab:green", alpha=0.08, lw=0)
    ax.text(-0.28, 0.5, "elliptic\n0 < R < 1", fontsize=8, color="tab:green", va="center")
    fixed = study["period_two"]["fixed_point_residue"]
    ax.plot(fixed["eps"], fixed["residue"], "k-", lw=1.5, label="fixed points (0, pi m): R = eps")
    rows = study["fixed_points"]["rows"]
    ax.plot([r["eps"] for r in rows], [0.5 * (r["residue"]["lo"] + r["residue"]["hi"])
                                       for r in rows], "ks", ms=5, mfc="none",
            label="fixed points, certified")
    for branch in study["period_two"]["branches"]:
        label = (f"period 2, m = {branch['m']}" if branch["model"] == "exact"
                 else "period 2, Holmes map")
        style = "--" if branch["model"] == "holmes" else "-"
        line, = ax.plot(branch["eps"], branch["residue"], style, lw=1.2, label=label)
        cert = branch["certified"]
        if cert:
            ax.plot([c["eps"] for c in cert], [0.5 * (c["residue"]["lo"] + c["residue"]["hi"])
                                               for c in cert], "o", ms=5, mfc="none",
                    color=line.get_color())
    ax.axvline(1.0, color="grey", lw=0.8, ls=":")
    ax.set_xlim(-0.3, 1.8)
    ax.set_ylim(-0.5, 1.5)
    ax.set_xlabel("eps")
    ax.set_ylabel("residue R = (2 - tr DF^p)/4")
    ax.set_title("Stability of the fixed points and of the period-2 orbits born at eps = 1",
                 fontsize=10)
    ax.legend(fontsize=7, loc="lower left")
    caption(fig, "Lines: float64 (Newton on F^p - id). Open markers: certified by "
                 "verify.periodic_orbit (Krawczyk); the enclosures are far narrower than the "
                 "markers.")
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    return save_figure(fig, out_dir, "dynamics_residue")


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
