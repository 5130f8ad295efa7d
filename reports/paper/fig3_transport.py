"""Seed Fig. 3: transport P_ij(t) for hole widths 0.1, 0.4, 1, 2.2, and its claims.

The seed (Section 4): "a very strong P_11(t) for hole sizes h = 0.4 and h = 1 ... a hole that is
too small (h = 0.1) does not effectively trap these orbits, and one that is too large (h = 2.2)
allows all orbits to escape within a finite time". One claim per width, ``fig3-h=H``: P_11
dominates at late times (yes for 0.4 and 1, no for 0.1 and 2.2).

Statistical criterion (continuous time, entry hole 1). Late time t_q: the last time at which
P_11 + P_12 >= q, q = max(1e-3, 100/N) (the survivors of the first 99.9% of the decay). Of the
k = N (P_11 + P_12)(t_q) particles still inside then, k_11 leave by hole 1: the reflected share
f = k_11 / k with its 95% Wilson interval. The share's trend: the k particles split at t_2, the
last time with P_11 + P_12 >= max(q/10, 20/N), into those leaving in [t_q, t_2) and those still
inside at t_2; a one-sided two-proportion z-test (level 0.05) compares their reflected shares.

    dominates           lower 95% bound of f > 1/2, and the share does not fall significantly
    does not dominate   upper 95% bound of f < 1/2, or the share falls significantly
    undecided           otherwise (f compatible with 1/2, or no survivors at t_q)

confirmed: the seed's answer; refuted: the other answer; inconclusive: undecided. The
systematic uncertainty of f is its half-range with q moved by 10**(+-1/4).
"""

from __future__ import annotations

import math
from pathlib import Path

from scipy.stats import norm

from reports.paper.claims import CONFIRMED, INCONCLUSIVE, REFUTED, Claim
from reports.paper.runs import read_manifest, run_summary
from reports.paper.style import band, caption, pyplot, save_figure
from reports.runs.survival import read_survival, wilson

SEED_P11_DOMINATES = {"0.1": False, "0.4": True, "1": True, "2.2": False}  # seed Section 4
LATE_Q = 1e-3
MIN_SURVIVORS = 100
TREND_SURVIVORS = 20
LEVEL = 0.05


def transport_curve(data, name, clock):
    return data.get((name, clock))


def _counts_at(x, p, t, n):
    """N P(t) on the curve's grid (0 past its last point)."""
    hit = [i for i, xi in enumerate(x) if xi <= t]
    return round(p[hit[-1]] * n) if hit and hit[-1] < len(p) else 0


def transport_dominance(data, h, particles, clock="time", q_scale=1.0):
    """The late-time reflected share and its trend for width h (module docstring), or None."""
    c11 = transport_curve(data, f"h={h}/P11", clock)
    c12 = transport_curve(data, f"h={h}/P12", clock)
    if c11 is None or c12 is None:
        return None
    grid = sorted(set(c11[0]) | set(c12[0]))

    def inside(t):
        return (_counts_at(c11[0], c11[1], t, particles),
                _counts_at(c12[0], c12[1], t, particles))

    q = max(LATE_Q, MIN_SURVIVORS / particles) * q_scale
    late = [t for t in grid if sum(inside(t)) >= q * particles]
    if not late:
        return None
    t_q = late[-1]
    k11, k12 = inside(t_q)
    k = k11 + k12
    f = k11 / k
    lo, hi = (float(v) for v in wilson(k11, k))
    floor = max(q / 10, TREND_SURVIVORS / particles) * particles
    later = [t for t in grid if t > t_q and sum(inside(t)) >= floor]
    trend_z, trend_p, t_2 = math.nan, math.nan, None
    if later:
        t_2 = later[-1]
        s11, s12 = inside(t_2)
        m11, m12 = k11 - s11, k12 - s12  # left in [t_q, t_2)
        if s11 + s12 and m11 + m12:
            f_mid, f_late = m11 / (m11 + m12), s11 / (s11 + s12)
            pool = k11 / k
            se = math.sqrt(pool * (1 - pool) * (1 / (m11 + m12) + 1 / (s11 + s12)))
            trend_z = (f_late - f_mid) / se if se > 0 else 0.0
            trend_p = float(norm.cdf(trend_z))  # one-sided: small when the share falls
    falls = math.isfinite(trend_p) and trend_p < LEVEL
    if lo > 0.5 and not falls:
        dominates = True
    elif hi < 0.5 or falls:
        dominates = False
    else:
        dominates = None
    return {"h": h, "q": q, "t_q": t_q, "k11": k11, "k12": k12, "share": f,
            "share_ci95": [lo, hi], "t_2": t_2, "trend_z": trend_z, "trend_p": trend_p,
            "dominates": dominates}


def hole_widths(data):
    return list(dict.fromkeys(name.split("/")[0][2:] for name, _ in data if "/" in name))


def figure_transport(run_dir, out_dir):
    plt = pyplot()
    man = read_manifest(run_dir)
    n = man["particles"]
    data = read_survival(Path(run_dir) / "survival.csv")
    widths = hole_widths(data)
    fig, axes = plt.subplots(2, 2, figsize=(11, 8.4), squeeze=False)
    results = []
    for ax, h in zip(axes.ravel(), widths, strict=False):
        for ij in ("P11", "P12", "P21", "P22"):
            c = transport_curve(data, f"h={h}/{ij}", "time")
            if c is not None:
                band(ax, *c, ij)
        dom = transport_dominance(data, h, n)
        results.append(dom)
        if dom:
            ax.axvline(dom["t_q"], color="grey", ls=":", lw=1)
            lo, hi = dom["share_ci95"]
            ax.text(0.03, 0.04, f"at t_q = {dom['t_q']:.3g} (P11+P12 = {dom['q']:.0e}):\n"
                                f"share leaving by hole 1 = {dom['share']:.3f} "
                                f"[{lo:.3f}, {hi:.3f}]", transform=ax.transAxes, fontsize=7,
                    bbox={"fc": "white", "ec": "none", "alpha": 0.8})
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_ylim(0.3 / n, 1.5)
        ax.set_xlim(1, None)
        ax.set_xlabel("t")
        ax.set_ylabel("P_ij(t)")
        ax.set_title(f"h = {h}", fontsize=10)
        ax.legend(fontsize=7, loc="upper right")
    fig.suptitle("Fig. 3: transport P_ij(t), holes centred at 0 (1) and pi (2), eps = 0.6",
                 fontsize=11)
    caption(fig, "starts uniform on hole i, 2 < v < 4; " + run_summary(run_dir)
             + " (per entry hole and width); bands: 95% Wilson")
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    return save_figure(fig, out_dir, "paper_fig3_transport"), results


def share_systematic(data, h, particles):
    """Half-range of the late share f over q moved by 10**(+-1/4) (the window family of
    ``reports.stats.analysis``, applied to the late time)."""
    shares = [r["share"] for k in (-0.25, 0.0, 0.25)
              if (r := transport_dominance(data, h, particles, q_scale=10.0 ** k)) is not None]
    return 0.5 * (max(shares) - min(shares)) if shares else math.nan


def transport_claims(results, run_dir, particles):
    run = Path(run_dir).name
    data = read_survival(Path(run_dir) / "survival.csv")
    claims = []
    for r in results:
        if r is None or r["h"] not in SEED_P11_DOMINATES:
            continue
        sys = share_systematic(data, r["h"], particles)
        seed = SEED_P11_DOMINATES[r["h"]]
        verdict = (INCONCLUSIVE if r["dominates"] is None else
                   CONFIRMED if r["dominates"] == seed else REFUTED)
        lo, hi = r["share_ci95"]
        trend = ("no later point with enough survivors" if r["t_2"] is None else
                 f"share trend to t_2 = {r['t_2']:.3g}: z = {r['trend_z']:.2f} "
                 f"(one-sided p of a fall = {r['trend_p']:.2g})")
        answer = {True: "dominates", False: "does not dominate", None: "undecided"}
        evidence = (f"At t_q = {r['t_q']:.3g} (P_11 + P_12 = {r['q']:.0e}): {r['k11']:,} of "
                    f"{r['k11'] + r['k12']:,} survivors leave by hole 1, share f = "
                    f"{r['share']:.3f} [{lo:.3f}, {hi:.3f}] +- {sys:.3f} (q moved by "
                    f"10^(+-1/4)); {trend}; P_11 "
                    f"{answer[r['dominates']]}.")
        claims.append(Claim(
            id=f"fig3-h={r['h']}", figure="3",
            seed_says=f"P_11 {'dominates' if seed else 'does not dominate'} at late times "
                      f"for h = {r['h']}",
            verdict=verdict, evidence=evidence, particles_per_curve=particles,
            statistical={"share": r["share"], "share_ci95": [lo, hi], "trend_z": r["trend_z"],
                         "trend_p": r["trend_p"]},
            systematic={"share": sys}, run=run,
            rule="Wilson bound of the late reflected share against 1/2, one-sided trend test "
                 "(reports/paper/fig3_transport.py)"))
    return claims


def transport_markdown(run_dir, image, claims_text):
    return "\n".join([
        "### Fig. 3: transport (seed Section 4)", "",
        f"![Fig. 3: transport P_ij(t)]({image})", "",
        f"Run: {run_summary(run_dir)} (per entry hole and width).", "",
        "Dominance criterion (module docstring of `reports/paper/fig3_transport.py`): the share "
        "f of the late survivors (P_11 + P_12 down to q) that leave by hole 1, with its 95% "
        "Wilson interval against 1/2, and a one-sided test that the share does not fall later.",
        "", claims_text, ""])
