"""Dissipation figure and Markdown: <v_n> against n per physics, V_sat against (1 - r).
"""

from __future__ import annotations

import math

import numpy as np

from reports.paper.figures.style import caption, pyplot, save_figure
from reports.paper.studies.dissipation_study import BLOCKS, RANDOM_PHASE_BETA, STUDY, velocity_strip
from reports.paper.studies.sampling import fmt, verified_text


def figure_dissipation(d, out_dir):
    plt = pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    ax = axes[0]
    for c, style in [(d.elastic, "k-")] + [(c, "-") for c in d.restitution] + [
            (c, ":") for c in d.drag]:
        ok = np.isfinite(c.mean_v) & (c.mean_v > 0)
        ax.loglog(d.n[ok], c.mean_v[ok], style, lw=1.2, label=c.label)
    ax.axvspan(*d.window, color="0.9", zorder=0, label="plateau window")
    ax.set_xlabel("n (collisions)")
    ax.set_ylabel("<v_n>")
    ax.set_title(f"<v_n> at eps = {d.eps:g}: elastic, restitution r < 1, drag", fontsize=10)
    ax.legend(fontsize=6, ncol=2)
    ax = axes[1]
    plats = np.array([c.plateau for c in d.restitution])
    ax.loglog(d.one_minus_r, plats, "o", label="V_sat (plateau of <v_n>)")
    if math.isfinite(d.beta):
        x = np.geomspace(d.one_minus_r[0], d.one_minus_r[-1], 50)
        ax.loglog(x, d.amp * x**d.beta, "k-",
                  label=f"fit: beta = {fmt(d.beta, d.beta_err)} (+- {d.beta_sys:.2g} sys)")
        x0 = d.one_minus_r[-1]
        ax.loglog(x, plats[-1] * (x / x0) ** RANDOM_PHASE_BETA, "--", color="tab:red", lw=1,
                  label="slope -1/2 (random-phase estimate, not published)")
    if d.strip_max:
        x = np.geomspace(d.one_minus_r[0], d.one_minus_r[-1], 50)
        ax.loglog(x, [velocity_strip(1.0 - xi, d.eps) for xi in x], "-", color="tab:green",
                  lw=1, label="velocity strip V*(r) ~ 2 eps/(1 - r) (bound)")
        ax.loglog(d.one_minus_r, d.strip_max, "^", color="tab:green",
                  label=f"max |v_n| over {d.strip_orbits} orbits")
    ax.set_xlabel("1 - r")
    ax.set_ylabel("V_sat, velocity")
    ax.set_title("plateau against the restitution loss", fontsize=10)
    ax.legend(fontsize=7)
    fig.suptitle("Dissipation suppresses Fermi acceleration (paper's escape start box, no holes)",
                 fontsize=11)
    caption(fig, f"{d.particles:,} particles per curve, n <= {int(d.n[-1]):,}; "
                 f"{verified_text(d.verification)}; +- from a bootstrap over {BLOCKS} "
                 "particle blocks")
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    return save_figure(fig, out_dir, "paper_dissipation")


def dissipation_markdown(d, image):
    rows = ["| physics | V_sat | slope of log<v_n> in the window | stuck by n_max | "
            "reached n_max | collisions |", "|---|---|---|---|---|---|"]
    for c in [d.elastic, *d.restitution, *d.drag]:
        rows.append(f"| {c.label} | {c.plateau:.3g} | {fmt(c.slope, c.slope_err)} "
                    f"(+- {c.slope_sys:.2g} sys) | {c.stuck} | {c.reached} | "
                    f"{c.collisions:.3g} |")
    stuck = ", ".join(f"r = {r:g}: {frac:.1%}" for r, frac, _ in d.sticking)
    return "\n".join([
        "### Dissipation: <v> saturates",
        "",
        f"![Dissipation]({image})",
        "",
        f"eps = {d.eps:g}, {d.particles:,} particles from the paper's escape start box, no "
        f"holes, the same starts for every physics; {verified_text(d.verification)} "
        f"(dissipative orbits). Plateau V_sat = mean of <v_n> over the log-spaced grid points "
        f"with n in [{d.window[0]:g}, {d.window[1]:g}]. "
        + (f"Source: {d.source}." if d.source else f"Computed here in {d.seconds:.0f} s."),
        "",
        *rows,
        "",
        f"V_sat ~ (1 - r)^beta with beta = {fmt(d.beta, d.beta_err)} (bootstrap) +- "
        f"{d.beta_sys:.2g} (plateau window and fit range). **No published value of beta was "
        "found**: Livorati, Ladeira, Leonel, Phys. Rev. E 78, 056205 (2008) study this scaling "
        "for inelastic impacts, but we could not read their exponents; the only text we read "
        "is the abstract of de Souza, Simoes, da Silva, Leonel, Math. Probl. Eng. 2009, 409857 "
        "(linear drag: <v> grows, then bends to a constant). The comparison value -1/2 is our "
        "own random-phase estimate (`reports/paper/studies/dissipation_study.py`), not a citation.",
        "",
        *_strip_lines(d),
        f"Stuck for good by n = {int(d.n[-1]):,} at eps = {STUDY['sticking_eps']:g} "
        f"(|eps| <= 1: a particle that sticks never leaves): {stuck} of {d.particles:,} "
        f"particles. At eps = {d.eps:g} no particle sticks for good (it detaches where the "
        "plate's acceleration falls through -1).",
        "",
    ])


def _strip_lines(d):
    if not d.strip_max:
        return []
    ratios = ", ".join(f"{x:g}: {m / velocity_strip(1.0 - x, d.eps):.3f}"
                       for x, m in zip(d.one_minus_r, d.strip_max, strict=True))
    return [
        "The one published scaling law with numbers we could read is a bound: Barroso, "
        "Carneiro, Macau, Phys. Rev. E 79, 026206 (2009) find the chaotic orbits of the "
        "inelastic bouncer \"bounded by a velocity strip v = +-Gamma/(1 - r)\" (abstract). In "
        "our units the strip's edge is V*(r) = (|eps| + r sqrt(eps^2 + 4|eps|(1 - r)/(1 + r)))"
        "/(1 - r) ~ 2|eps|/(1 - r), derived from energy conservation in flight and the impact "
        "rule (`reports/paper/studies/dissipation_study.py`). Over "
        f"{d.strip_orbits} orbits of {int(d.n[-1]):,} collisions per r, max |v_n| / V*(r) "
        f"by 1 - r = {ratios}: every orbit stays inside, and ever deeper inside as r -> 1 "
        "(the plateau grows as (1 - r)^beta, the strip as (1 - r)^-1).",
        "",
    ]
