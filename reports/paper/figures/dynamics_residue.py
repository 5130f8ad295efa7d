"""The dynamics section's figure ``dynamics_residue``: residue R = (2 - trace)/4 of the fixed points
and of the period-2 orbits against eps. It takes the study dict
(``reports.paper.studies.dynamics_study``) and writes PNG and PDF into ``out_dir``.
"""

from __future__ import annotations

from reports.paper.figures.style import caption, pyplot, save_figure


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
