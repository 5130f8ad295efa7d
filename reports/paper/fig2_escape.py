"""Seed Fig. 2: escape survival P(n) and P(t) for six holes of width 0.3, and its claims.

Every curve of the run is analysed by ``reports.stats.analysis.analyse`` (maximum likelihood on
the binned, censored counts; regimes where the law changes). Each claim is judged on the
regime the seed's sentence is about (``reports.stats.regime_fit``): the *bulk* regime (the one
holding the most escapes) for the "primarily" / "rapid decay" statements, the *late* regime
(the last one) for the "eventually" / "algebraic" statements. The decay *type* of a regime is
named by Vuong's test of the exponential against the power law on it, at level 0.05:
exponential if Z > 0, algebraic if Z < 0, none if p >= 0.05.

* ``fig2-n-phi_c=X``, holes over or near the islands (phi_c = 0, 0.5, 1, 1.5): "primarily
  exponential" in discrete time; type of the bulk regime. Holes in the chaotic sea (2, 2.5):
  "algebraic"; type of the late regime. confirmed: the seed's type; refuted: the other type;
  inconclusive: no type.
* ``fig2-n-tail-phi_c=X``, island holes: "eventually a slow power law, as islands not covered
  by the hole become significant"; type of the late regime, judged as above.
* ``fig2-t-phi_c=X``, island holes: continuous time, "the rapid decay is close to a stretched
  exponential, with sqrt(t) in the exponent". Rule: the stretched exponent beta of the bulk
  regime with U = half width of its 95% profile interval + its systematic half-range.
  confirmed: |beta - 1/2| <= U and U <= 1/4; refuted: |beta - 1/2| > U; inconclusive: U > 1/4
  (1/4 is half the distance from 1/2 to either neighbour, beta = 0 the power law and beta = 1
  the exponential: a wider U cannot tell them apart).
* ``fig2-same-power-phi_c=X``, sea holes: "the algebraic decay has the same power as for
  discrete time". Rule: the power-law exponent alpha of the late regime in each clock, each with
  U = interval half width + systematic half-range; d = alpha_n - alpha_t, U_d = U_n + U_t.
  confirmed: |d| <= U_d and U_d <= alpha/4 (the comparison resolves a 25% difference);
  refuted: |d| > U_d; inconclusive otherwise.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from reports.paper.claims import CONFIRMED, INCONCLUSIVE, REFUTED, Claim
from reports.paper.runs import read_manifest, run_summary
from reports.paper.style import band, caption, hole_label, pyplot, save_figure
from reports.runs.survival import read_survival
from reports.stats.analysis import analyse
from reports.stats.histogram import read_run
from reports.stats.regime_fit import bulk_regime, fitted_curve, half_width, regime_detail
from reports.stats.selection import LEVEL

SEED_EXPONENTIAL_HOLES = ("0", "0.5", "1", "1.5")  # the seed's Fig. 2 caption
SEED_ALGEBRAIC_HOLES = ("2", "2.5")
SQRT_T_BETA = 0.5
BETA_RESOLUTION = 0.25
RELATIVE_POWER_RESOLUTION = 0.25
LAW_STYLE = {"exponential": ":", "power_law": "--", "stretched_exponential": "-.",
             "inconclusive": "-."}


def escape_analysis(run_dir):
    """{(hole, clock): (curve, analysis)} for every curve of an escape run."""
    return {(c.experiment, c.clock): (c, analyse(c)) for c in read_run(run_dir)}


def decay_type(detail):
    """'exponential', 'algebraic' or None from Vuong's test (module docstring)."""
    test = detail["tests"]["vuong_exponential_vs_power_law"]
    if test["p"] >= LEVEL:
        return None
    return "exponential" if test["statistic"] > 0 else "algebraic"


def _g(x, digits=3):
    return "inf" if x == math.inf else f"{x:.{digits}g}"


def _law_text(regime):
    law, p = regime["law"], regime.get("params", {})
    shown = ", ".join(f"{k} = {_g(v)}" for k, v in p.items() if k != "c")
    return f"{law.replace('_', ' ')}" + (f" ({shown})" if shown else "")


def regimes_text(result, unit):
    return "; ".join(f"{_law_text(r)} for {unit} in [{_g(r['from'])}, {_g(r['to'])}] "
                     f"({r['escapes']:,} escapes)" for r in result["regimes"])


def _param(detail, law, name):
    fit = detail["fits"][law]
    value, ci = fit.params[name], fit.ci95.get(name, (math.nan, math.nan))
    sys = detail["systematic"][law][name]
    return value, ci, (sys if sys is not None else math.inf)


def _type_verdict(detail, expected):
    kind = decay_type(detail)
    return kind, (INCONCLUSIVE if kind is None else CONFIRMED if kind == expected else REFUTED)


def _regime_evidence(detail, unit, kind):
    z = detail["tests"]["vuong_exponential_vs_power_law"]
    beta, beta_ci, beta_sys = _param(detail, "stretched_exponential", "beta")
    return (f"{unit} in [{_g(detail['from'])}, {_g(detail['to'])}] ({detail['escapes']:,} "
            f"escapes): Vuong Z = {z['statistic']:.1f} (p = {z['p']:.2g}) -> {kind or 'no type'};"
            f" best law there {detail['best'].replace('_', ' ')}, stretched beta = {beta:.3f} "
            f"[{beta_ci[0]:.3f}, {beta_ci[1]:.3f}] +- {_g(beta_sys, 2)} (sys)")


def _type_statistics(detail):
    z = detail["tests"]["vuong_exponential_vs_power_law"]
    beta, beta_ci, beta_sys = _param(detail, "stretched_exponential", "beta")
    return ({"vuong_z": z["statistic"], "vuong_p": z["p"], "beta": beta,
             "beta_ci95": list(beta_ci)}, {"beta": beta_sys})


def discrete_claim(name, curve, result, run):
    hole = hole_label(name)
    island = hole in SEED_EXPONENTIAL_HOLES
    regime = bulk_regime(result) if island else result["regimes"][-1]
    detail = regime_detail(curve, regime)
    kind, verdict = _type_verdict(detail, "exponential" if island else "algebraic")
    statistical, systematic = _type_statistics(detail)
    which = "Bulk regime" if island else "Late regime"
    evidence = (f"{which} {_regime_evidence(detail, 'n', kind)}. All regimes: "
                f"{regimes_text(result, 'n')}.")
    return Claim(
        id=f"fig2-n-{name}", figure="2",
        seed_says=(f"discrete-time escape through the hole at phi_c = {hole} is "
                   f"{'primarily exponential' if island else 'algebraic'}"),
        verdict=verdict, evidence=evidence, particles_per_curve=curve.particles,
        statistical=statistical, systematic=systematic, run=run,
        rule=f"Vuong exponential vs power law on the {'bulk' if island else 'late'} regime, "
             "level 0.05")


def tail_claim(name, curve, result, run):
    hole = hole_label(name)
    detail = regime_detail(curve, result["regimes"][-1])
    kind, verdict = _type_verdict(detail, "algebraic")
    statistical, systematic = _type_statistics(detail)
    alpha = result["models"]["power_law"]
    evidence = (f"Late regime {_regime_evidence(detail, 'n', kind)}; power law alpha = "
                f"{alpha['alpha']:.3f} [{alpha['alpha_ci95'][0]:.3f}, "
                f"{alpha['alpha_ci95'][1]:.3f}]. Crossovers at n = "
                + ", ".join(f"{_g(c['x'])} [{_g(c['range95'][0])}, {_g(c['range95'][1])}]"
                            for c in sorted(result.get("crossovers", []), key=lambda c: c["x"]))
                + ".")
    return Claim(
        id=f"fig2-n-tail-{name}", figure="2",
        seed_says=f"escape through the hole at phi_c = {hole} eventually follows a slow power "
                  "law (islands not covered by the hole)",
        verdict=verdict, evidence=evidence, particles_per_curve=curve.particles,
        statistical=statistical, systematic=systematic, run=run,
        rule="Vuong exponential vs power law on the late regime, level 0.05")


def continuous_claim(name, curve, result, run):
    hole = hole_label(name)
    regime = bulk_regime(result)
    detail = regime_detail(curve, regime)
    beta, ci, sys = _param(detail, "stretched_exponential", "beta")
    u = half_width(ci) + sys
    off = abs(beta - SQRT_T_BETA)
    verdict = (REFUTED if off > u else CONFIRMED if u <= BETA_RESOLUTION else INCONCLUSIVE)
    evidence = (f"Bulk regime t in [{_g(regime['from'])}, {_g(regime['to'])}] "
                f"({detail['escapes']:,} escapes): stretched beta = {beta:.3f} "
                f"[{ci[0]:.3f}, {ci[1]:.3f}] +- {_g(sys, 2)} (sys), |beta - 1/2| = {off:.3f} "
                f"against U = {_g(u, 2)}; "
                f"best law there {detail['best'].replace('_', ' ')}. All regimes: "
                f"{regimes_text(result, 't')}.")
    return Claim(
        id=f"fig2-t-{name}", figure="2",
        seed_says=f"continuous-time escape through the hole at phi_c = {hole} is a stretched "
                  "exponential exp(-c sqrt(t))",
        verdict=verdict, evidence=evidence, particles_per_curve=curve.particles,
        statistical={"beta": beta, "beta_ci95": list(ci)}, systematic={"beta": sys}, run=run,
        rule="|beta - 1/2| <= U (95% interval half width + systematic) with U <= 1/4")


def _late_alpha(result):
    m = result["models"]["power_law"]
    sys = result["systematic"]["power_law"]["alpha"]
    return m["alpha"], m["alpha_ci95"], (sys if sys is not None else math.inf)


def same_power_claim(name, res_n, res_t, run, particles):
    hole = hole_label(name)
    a_n, ci_n, s_n = _late_alpha(res_n)
    a_t, ci_t, s_t = _late_alpha(res_t)
    d = a_n - a_t
    u = half_width(ci_n) + s_n + half_width(ci_t) + s_t
    scale = RELATIVE_POWER_RESOLUTION * 0.5 * (a_n + a_t)
    verdict = REFUTED if abs(d) > u else CONFIRMED if u <= scale else INCONCLUSIVE
    laws = (f"late laws: {res_n['best'].replace('_', ' ')} (n), "
            f"{res_t['best'].replace('_', ' ')} (t)")
    evidence = (f"Power-law exponent of the late regime: alpha_n = {a_n:.3f} [{ci_n[0]:.3f}, "
                f"{ci_n[1]:.3f}] +- {_g(s_n, 2)} (n >= {_g(res_n['window'][0])}), alpha_t = "
                f"{a_t:.3f} [{ci_t[0]:.3f}, {ci_t[1]:.3f}] +- {_g(s_t, 2)} "
                f"(t >= {_g(res_t['window'][0])}); d = {d:.3f}, U_d = {_g(u, 2)}; {laws}.")
    return Claim(
        id=f"fig2-same-power-{name}", figure="2",
        seed_says=f"the algebraic decay (phi_c = {hole}) has the same power in continuous as "
                  "in discrete time",
        verdict=verdict, evidence=evidence, particles_per_curve=particles,
        statistical={"alpha_n": a_n, "alpha_n_ci95": list(ci_n), "alpha_t": a_t,
                     "alpha_t_ci95": list(ci_t)},
        systematic={"alpha_n": s_n, "alpha_t": s_t}, run=run,
        rule="|alpha_n - alpha_t| <= U_d with U_d <= alpha/4")


def escape_claims(analysis, run_dir):
    run = Path(run_dir).name
    claims = []
    names = list(dict.fromkeys(name for name, _ in analysis))
    for name in names:
        curve, res = analysis[name, "collisions"]
        claims.append(discrete_claim(name, curve, res, run))
        if hole_label(name) in SEED_EXPONENTIAL_HOLES:
            claims.append(tail_claim(name, curve, res, run))
    for name in names:
        if hole_label(name) in SEED_EXPONENTIAL_HOLES and (name, "time") in analysis:
            curve, res = analysis[name, "time"]
            claims.append(continuous_claim(name, curve, res, run))
    for name in names:
        if hole_label(name) in SEED_ALGEBRAIC_HOLES and (name, "time") in analysis:
            claims.append(same_power_claim(name, analysis[name, "collisions"][1],
                                           analysis[name, "time"][1], run,
                                           analysis[name, "time"][0].particles))
    return claims


def draw_regimes(ax, curve, result, xs=None):
    """Each regime's fitted law in black, styled by law (``LAW_STYLE``)."""
    for regime in result["regimes"]:
        law = regime["law"]
        try:
            x, s = fitted_curve(curve, regime, "stretched_exponential" if law == "inconclusive"
                                else law)
        except ValueError:
            continue
        ax.plot(x if xs is None else xs(x), s, LAW_STYLE[law], color="k", lw=0.8)


def figure_escape(run_dir, out_dir, analysis):
    """Fig. 2 as the seed drew it: 2x2 panels, discrete (top) and continuous (bottom) time,
    log-linear (left) and log-log (right); each regime's fitted law drawn in black."""
    plt = pyplot()
    data = read_survival(Path(run_dir) / "survival.csv")
    man = read_manifest(run_dir)
    names = list(dict.fromkeys(name for name, _ in analysis))
    fig, axes = plt.subplots(2, 2, figsize=(12, 9))
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for i, name in enumerate(names):
        col = colors[i % len(colors)]
        label = f"phi_c = {hole_label(name)}"
        for row, clock in enumerate(("collisions", "time")):
            if (name, clock) not in data:
                continue
            x, p, lo, hi = data[name, clock]
            curve, res = analysis[name, clock]
            sq = np.sqrt if clock == "time" else None
            band(axes[row, 0], x, p, lo, hi, label, xs=np.sqrt(x) if sq else None, color=col)
            band(axes[row, 1], x, p, lo, hi, label, color=col)
            draw_regimes(axes[row, 0], curve, res, xs=sq)
            draw_regimes(axes[row, 1], curve, res)
    floor = 0.3 / man["particles"]
    for ax in axes.flat:
        ax.set_yscale("log")
        ax.set_ylim(floor, 1.5)
        ax.set_ylabel("survival P")
    for ax in axes[:, 1]:
        ax.set_xscale("log")
    axes[0, 0].set_xlabel("n (collisions)")
    axes[0, 1].set_xlabel("n (collisions)")
    axes[1, 0].set_xlabel("sqrt(t)")
    axes[1, 1].set_xlabel("t")
    axes[0, 0].set_xlim(0, 2000)
    axes[1, 0].set_xlim(0, 300)
    axes[0, 0].set_title("discrete time, log-linear", fontsize=9)
    axes[0, 1].set_title("discrete time, log-log", fontsize=9)
    axes[1, 0].set_title("continuous time against sqrt(t)", fontsize=9)
    axes[1, 1].set_title("continuous time, log-log", fontsize=9)
    axes[0, 1].legend(fontsize=7)
    fig.suptitle("Fig. 2: escape through one hole of width 0.3 centred at phi_c, eps = 0.6 "
                 "(black: maximum-likelihood law of each regime; dotted exponential, dashed "
                 "power law, dash-dot stretched)", fontsize=9)
    caption(fig, "starts 3.85 < phi < 4.15, 2 < v < 4; " + run_summary(run_dir)
            + "; bands: 95% Wilson")
    fig.tight_layout(rect=(0, 0.03, 1, 0.97))
    return save_figure(fig, out_dir, "paper_fig2_escape")


def escape_markdown(run_dir, image, claims_text):
    return "\n".join([
        "### Fig. 2: escape (seed Section 3)", "",
        f"![Fig. 2: escape survival]({image})", "",
        f"Run: {run_summary(run_dir)}.", "",
        "Claims (rules in `reports/paper/fig2_escape.py`; fits by maximum likelihood on the "
        "binned, censored counts, `bouncer fit` gives the same numbers):", "",
        claims_text, ""])
