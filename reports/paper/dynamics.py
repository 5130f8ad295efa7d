r"""The report's dynamics section: the paper's Section 2 statements and its Lyapunov remark.

``dynamics_section(out_dir, quick, echo)`` reads the committed study
``docs/report/dynamics/study.json`` (``scripts/dynamics_study.py`` writes it; about 10 minutes)
and re-checks a sample of it here (certified orbits recomputed, float crossings and the first
collisions of the Lyapunov orbits recomputed bit for bit); without the file it computes the
study (``QUICK`` sizes with ``quick``). A failed re-check turns the claims resting on that part
``inconclusive``. It writes four figures and returns the markdown and the claims (dicts with the
register's keys). The rules and tolerances below are fixed in the code, before the data.
"""

from __future__ import annotations

import json
import math
import time
from pathlib import Path

import numpy as np

import verify
from fastpath import dynamics as fd
from reports.paper import dynamics_figures as figures
from reports.paper.dynamics_study import FULL, K_C_QUARTER, PAPER_BOX, QUICK, period_two_start, run

STUDY = Path(__file__).resolve().parents[2] / "docs" / "report" / "dynamics" / "study.json"
RUN = "docs/report/dynamics/study.json"
CONFIRMED, REFUTED, INCONCLUSIVE = "confirmed", "refuted", "inconclusive"
NEAR = 0.05  # "near eps = 0.24": within 5% of K_c/4
LOWEST_MARGIN = 0.20  # "all but the lowest velocities": band 0 keeps curves 20% beyond K_c/4
GOOD_APPROXIMATION = 0.1  # "normal to a good approximation": |mu - 1| <= 0.1 (+ errors)
SIGMAS = 5.0  # a sign (lambda > 0, alpha < 0) is decided at 5 standard errors

QUOTES = {
    "fixed-elliptic": r"the matrix has complex eigenvalues corresponding to an elliptic fixed "
                      r"point in the region $0<\epsilon<1$",
    "fixed-hyperbolic": r"For $\epsilon<0$ or $\epsilon>1$ the orbit is hyperbolic.",
    "period-two": r"For $\epsilon>1$ the fixed points studied above become unstable (initially "
                  r"bifurcating into elliptic period 2 orbits)",
    "small-eps": r"For small $\epsilon$ the velocity is bounded due to invariant curves.",
    "transition": r"Near $\epsilon\approx0.24$ (corresponding to $K=0.971\ldots$) invariant "
                  r"spanning curves at all but the lowest velocities are disrupted, leading to "
                  r"unbounded velocity (Fermi acceleration) of some orbits.",
    "accelerator": r"At some parameter values $K>2\pi$, the standard map also has ``accelerator "
                   r"modes'', which are orbits in which velocity increases linearly with "
                   r"discrete time",
    "normal-diffusion": r"this $\epsilon$ is below the lowest accelerator modes, so diffusion of "
                        r"velocity in discrete time is expected to be normal to a good "
                        r"approximation.",
    "lyapunov": r"The largest Lyapunov exponent as calculated for typical points in this "
                r"component are likely to be positive for the discrete dynamics but zero in "
                r"the continuous dynamics, as the chaos-inducing collisions are rare when the "
                r"particle has high velocity.",
}


def _claim(**fields):
    keys = ("id", "figure", "statement", "quote", "observable", "regime", "rule", "tolerance",
            "source", "verdict", "evidence", "particles_per_curve", "statistical",
            "systematic", "run")
    claim = {k: fields.get(k) for k in keys}
    claim["source"] = "paper"
    claim["statistical"] = claim["statistical"] or {}
    claim["systematic"] = claim["systematic"] or {}
    return claim


def _mid(e):
    return 0.5 * (e["lo"] + e["hi"])


# --- loading and re-checking -------------------------------------------------------------------

def load_study(quick, echo):
    """(study, source): the committed study, or one computed now."""
    if STUDY.exists():
        return json.loads(STUDY.read_text(encoding="utf-8")), RUN
    echo("dynamics: no committed study; computing the "
         + ("quick" if quick else "full (~10 min)") + " one")
    return run(QUICK if quick else FULL, echo), None


def recheck(study, quick):
    """Recompute a sample of the study; {part: (ok, text)}."""
    out = {}
    start = time.perf_counter()
    row = study["fixed_points"]["rows"][0]
    orbit = verify.periodic_orbit(0.0, math.pi * row["m"], row["eps"], 1)
    ok = _overlaps(orbit.trace, row["trace"]) and orbit.stability == row["stability"]
    out["fixed_points"] = (ok, f"fixed point m={row['m']}, eps={row['eps']} re-certified")
    branch = study["period_two"]["branches"][0]
    cert = branch["certified"][0]
    s = period_two_start(cert["eps"])
    orbit = verify.periodic_orbit(s, math.pi * branch["m"] - s, cert["eps"], 2)
    ok = _overlaps(orbit.residue, cert["residue"]) and orbit.stability == cert["stability"]
    out["period_two"] = (ok, f"period-2 orbit m={branch['m']}, eps={cert['eps']} re-certified")
    row = next(r for r in study["critical"]["rows"] if r["band"] == 1 and r["prefix"] == [2])
    stored = row.get("float_crossings", row["crossings"])  # the float64 ones
    levels = min(len(stored), 8 if quick else len(stored))
    again = fd.critical_amplitude(1, (2,), levels=levels)
    diffs = [abs(a.eps - b) for a, b in zip(again.crossings, stored, strict=False)]
    ok = max(diffs) <= 1e-9
    out["critical"] = (ok, f"band 1 (omega = 1.382) crossings of {levels} approximants "
                           f"recomputed, largest difference {max(diffs):.1e}")
    lyap = study["lyapunov"]
    rng = np.random.default_rng(lyap["seed"])
    (p0, p1), (v0, v1) = PAPER_BOX
    early = np.array(lyap["first_orbits_early"])
    phi, v = rng.uniform(p0, p1, lyap["orbits"] + lyap["stopped"]), None
    v = rng.uniform(v0, v1, len(phi))
    points = lyap["checkpoints"][: early.shape[1]]
    n_early = points[-1]
    mine = fd.lyapunov(phi[: len(early)], v[: len(early)], lyap["eps"], n_early,
                       checkpoints=points)
    got = mine.running_per_collision
    worst = float(np.max(np.abs(got - early)))
    out["lyapunov"] = (worst <= 1e-8, f"first {n_early} collisions of {len(early)} Lyapunov "
                                      f"orbits recomputed, largest difference {worst:.1e}")
    if not quick:
        cc = study["certified_crossings"]
        if cc:
            c = min(cc, key=lambda r: r["period"])
            guess = fd.symmetric_orbit(c["point"][1]["lo"], c["eps"], c["period"], c["winding"])
            orbit = verify.periodic_orbit(float(guess.phi[0]), float(guess.v[0]), c["eps"],
                                          c["period"], winding=c["winding"])
            ok = _overlaps(orbit.residue, c["residue"])
            out["certified_crossings"] = (ok, f"period-{c['period']} orbit of band {c['band']} "
                                              f"at eps={c['eps']:.9f} re-certified")
    out["seconds"] = (True, f"{time.perf_counter() - start:.1f} s")
    return out


def _overlaps(enclosure, stored):
    return float(enclosure.lo) <= stored["hi"] and stored["lo"] <= float(enclosure.hi)


# --- claims ------------------------------------------------------------------------------------

def fixed_point_claims(study, run_name):
    rows = study["fixed_points"]["rows"]
    contains = all(r["trace_contains"] for r in rows)
    inner = [r for r in rows if 0 < r["eps"] < 1]
    outer = [r for r in rows if r["eps"] < 0 or r["eps"] > 1]
    cost = np.median([r["seconds"] for r in rows])
    where = (f"m in {sorted({r['m'] for r in rows})}, eps in "
             f"{sorted({r['eps'] for r in rows})}")
    out = []
    for key, sel, want in (("fixed-elliptic", inner, "elliptic"),
                           ("fixed-hyperbolic", outer, "hyperbolic")):
        proved = [r for r in sel if r["stability"] == want]
        wrong = [r for r in sel if r["stability"] not in (want, "undecided")]
        verdict = (REFUTED if wrong or not contains else
                   CONFIRMED if sel and len(proved) == len(sel) else INCONCLUSIVE)
        out.append(_claim(
            id=f"sec2-{key}", figure="sec2",
            statement=f"The fixed points (0, pi m) are {want} for "
                      + ("0 < eps < 1" if want == "elliptic" else "eps < 0 or eps > 1"),
            quote=QUOTES[key],
            observable="certified enclosure of tr DF at the fixed point and its residue "
                       "R = (2 - tr)/4 (Krawczyk's operator on the exact map)",
            regime=where,
            rule=f"{CONFIRMED} if every certified fixed point in the range is proved {want} and "
                 f"every trace enclosure contains 2 - 4 eps; {REFUTED} if one is proved the "
                 "other kind or an enclosure misses 2 - 4 eps",
            tolerance="none: interval proofs",
            verdict=verdict,
            evidence=f"{len(proved)}/{len(sel)} fixed points proved {want}; "
                     f"{sum(r['trace_contains'] for r in rows)}/{len(rows)} trace enclosures "
                     f"contain 2 - 4 eps (widths <= "
                     f"{max(r['trace']['hi'] - r['trace']['lo'] for r in rows):.1e}); "
                     f"median {cost:.2f} s per certified orbit",
            particles_per_curve=None, run=run_name))
    return out


def period_two_claim(study, run_name):
    branches = [b for b in study["period_two"]["branches"] if b["model"] == "exact"]
    holmes = next(b for b in study["period_two"]["branches"] if b["model"] == "holmes")
    fixed_above = [r for r in study["fixed_points"]["rows"] if r["eps"] > 1]
    first = [c for b in branches for c in b["certified"] if c["eps"] < b["loss_of_stability"]]
    beyond = [c for b in branches for c in b["certified"] if c["eps"] > b["loss_of_stability"]]
    elliptic = [c for c in first if c["stability"] == "elliptic"]
    unstable = all(r["stability"] == "hyperbolic" for r in fixed_above)
    verdict = (CONFIRMED if unstable and first and len(elliptic) == len(first)
               else REFUTED if any(c["stability"] == "hyperbolic" for c in first)
               else INCONCLUSIVE)
    loss = ", ".join(f"m={b['m']}: {b['loss_of_stability']:.6f}" for b in branches)
    holmes_changes = ", ".join(f"R={c['level']:g} at {c['eps']:.6f} ({c['direction']})"
                               for c in holmes["changes"])
    return _claim(
        id="sec2-period-two", figure="sec2",
        statement="Above eps = 1 the fixed points are hyperbolic and period-2 orbits born there "
                  "are elliptic",
        quote=QUOTES["period-two"],
        observable="certified residues of the fixed points (eps > 1) and of the period-2 orbits "
                   "(s, pi m - s), (-s, pi m + s), eps sin s = s",
        regime=f"m in {[b['m'] for b in branches]}, eps from 1 to the first loss of stability",
        rule=f"{CONFIRMED} if the fixed points are proved hyperbolic above 1 and every certified "
             f"period-2 orbit below its first loss of stability is proved elliptic; {REFUTED} if "
             "one there is proved hyperbolic",
        tolerance="none: interval proofs",
        verdict=verdict,
        evidence=f"{len(elliptic)}/{len(first)} period-2 orbits proved elliptic between eps = "
                 f"{min(c['eps'] for c in first):g} and their loss of stability (R = 1, float64: "
                 f"{loss}); proved hyperbolic just beyond it: "
                 f"{sum(c['stability'] == 'hyperbolic' for c in beyond)}/{len(beyond)}"
                 f"; {len(fixed_above)} fixed points with eps > 1 proved hyperbolic: {unstable}. "
                 "The Holmes map's period-2 orbit never passes R = 1 (its residue c (2 - c), "
                 f"c = 2 eps cos s, only touches 1; its changes: {holmes_changes}): the exact "
                 "map's first instability of these orbits is a finite-velocity effect that "
                 "closes up as m grows",
        particles_per_curve=None,
        statistical={f"loss_of_stability_m{b['m']}": b["loss_of_stability"] for b in branches},
        run=run_name)


def _band_table(study):
    crit = study["critical"]
    return {b["band"]: b for b in crit["band_max"]}


def transition_claims(study, run_name):
    crit = study["critical"]
    bands = _band_table(study)
    high = {j: b for j, b in bands.items() if j >= 1}
    near = {j: abs(b["eps_c"] - K_C_QUARTER) / K_C_QUARTER for j, b in high.items()}
    lowest = bands.get(0)
    sims = study["crossing_simulation"]
    below_crossed = [s for s in sims if s["factor"] < 1 and s["crossed"] > 0]
    above_crossed = [s for s in sims if s["factor"] > 1 and s["crossed"] > 0]
    limit = crit["limits"].get("golden2") or crit["limits"].get("golden")
    limit_ok = limit is not None and abs(limit["a"] - K_C_QUARTER) <= 3 * limit["a_error"] + 1e-6
    ok_near = bool(high) and max(near.values()) <= NEAR
    ok_low = lowest is not None and lowest["eps_c"] > (1 + LOWEST_MARGIN) * K_C_QUARTER
    if below_crossed:
        verdict = REFUTED
    elif ok_near and ok_low and limit_ok and above_crossed:
        verdict = CONFIRMED
    elif high and not ok_near:
        verdict = REFUTED
    else:
        verdict = INCONCLUSIVE
    table = "; ".join(f"band {j}: {b['eps_c']:.9f} +- {b['uncertainty']:.1e} "
                      f"(omega {b['omega']:.3f})" for j, b in sorted(bands.items()))
    holmes_text = ", ".join(f"{h['eps_c']:.10f} +- {h['uncertainty']:.1e}"
                            for h in crit["holmes"])
    sim_text = "; ".join(f"band {s['band']} at {s['factor']:g} eps_c: {s['crossed']}/"
                         f"{s['particles']} crossed within {s['collisions']:,}" for s in sims)
    transition = _claim(
        id="sec2-fermi-transition", figure="sec2",
        statement="Invariant spanning curves break near eps = 0.24 at all velocities but the "
                  "lowest; beyond, velocity is unbounded for some orbits",
        quote=QUOTES["transition"],
        observable="Greene's eps_c (residues of symmetric approximants crossing the critical "
                   "residue R_c = 0.2500888, Aitken-extrapolated) of noble "
                   "curves per velocity band j (v ~ pi (j + omega)); direct simulation across "
                   "each band (from the hyperbolic point (pi, pi j) to v = pi (j + 1))",
        regime=f"bands {sorted(bands)}; approximants up to period "
               f"{max(max(r['periods']) for r in crit['rows'])}",
        rule=f"{CONFIRMED} if the largest eps_c of every band j >= 1 is within {NEAR:.0%} of "
             f"K_c/4 = {K_C_QUARTER:.6f}, band 0 keeps a curve beyond {1 + LOWEST_MARGIN:g} "
             "K_c/4, the high-velocity fit a + b/v + c/v^2 gives a = K_c/4 within 3 standard "
             "errors, no orbit crosses a band at 0.95 of its eps_c and some do at 1.10; "
             f"{REFUTED} if an orbit crosses below eps_c or a band j >= 1 is farther than "
             f"{NEAR:.0%}",
        tolerance=f"'near 0.24' = within {NEAR:.0%} of K_c/4; 'lowest velocities' = band 0 "
                  f"(v < pi) beyond {1 + LOWEST_MARGIN:g} K_c/4",
        verdict=verdict,
        evidence=f"largest eps_c per band: {table}. High-velocity limit: a = "
                 f"{limit['a']:.8f} +- {limit['a_error']:.1e} vs K_c/4 = {K_C_QUARTER:.8f}, "
                 f"b = {limit['b']:+.4f} (golden^2; the golden curves approach from below "
                 f"with b = {crit['limits'].get('golden', {}).get('b', math.nan):+.4f}). "
                 f"Holmes map: {holmes_text} "
                 f"(K_c/4 = {K_C_QUARTER:.10f}). Simulation: {sim_text}"
        if limit else "no high-velocity fit",
        particles_per_curve=None,
        statistical={f"eps_c_band_{j}": [b["eps_c"], b["uncertainty"]]
                     for j, b in sorted(bands.items())},
        systematic={"limit_a": [limit["a"], limit["a_error"]]} if limit else {},
        run=run_name)
    smallest = min(b["eps_c"] for b in bands.values())
    bounded = _claim(
        id="sec2-small-eps-bounded", figure="sec2",
        statement="For eps below the first break-up every band keeps an invariant spanning "
                  "curve, so velocities stay bounded",
        quote=QUOTES["small-eps"],
        observable="the smallest over bands of the largest Greene eps_c found in a band, and "
                   "the high-velocity limit",
        regime=f"bands {sorted(bands)} and the fitted limit v -> infinity",
        rule=f"{CONFIRMED} if every band computed keeps a curve up to at least K_c/4 (1 - "
             f"{NEAR:g}) and the limit is K_c/4 > 0",
        tolerance=f"{NEAR:.0%} of K_c/4",
        verdict=CONFIRMED if smallest >= (1 - NEAR) * K_C_QUARTER and limit_ok else
        INCONCLUSIVE,
        evidence=f"smallest band maximum {smallest:.6f} (>= {(1 - NEAR) * K_C_QUARTER:.6f}); "
                 f"fitted limit {limit['a']:.7f}: for eps < {smallest:.4f} every band computed "
                 "keeps a noble curve (float64 Greene residues, not a proof that the curves "
                 "exist); direct simulation found no orbit crossing a band at 0.95 of its eps_c"
        if limit else "no fit",
        particles_per_curve=None, run=run_name)
    return [transition, bounded]


def accelerator_claims(study, run_name):
    acc = study["accelerator"]
    cert = acc["certified"]
    ok_cert = all(c["stability"] == "elliptic" for c in cert)
    p1 = next((s for s in acc["search"] if s["period"] == 1), None)
    p1_first = p1["first"]["eps"] if p1 and p1["first"] else None
    step = acc["search_eps"][2]
    ok_threshold = p1_first is not None and abs(p1_first - acc["half_pi"]) <= step
    k_claim = _claim(
        id="sec2-accelerator-modes", figure="sec2",
        statement="Accelerator modes (v growing linearly in n) exist for K = 4 eps > 2 pi; in "
                  "the exact map the period-1 ones are exact, from eps = pi/2 on",
        quote=QUOTES["accelerator"],
        observable="certified period-1 blocks F(x) = x + (2 pi m, pi) of the exact map; "
                   "Newton search for period-1 blocks on an eps grid",
        regime=f"eps in {sorted({c['eps'] for c in cert})}, m in "
               f"{sorted({c['m'] for c in cert})}; search {acc['search_eps']}",
        rule=f"{CONFIRMED} if the blocks are certified and the search finds the first period-1 "
             "block within one grid step of eps = pi/2 (K = 2 pi)",
        tolerance=f"one grid step ({step:g}) in eps",
        verdict=CONFIRMED if ok_cert and ok_threshold else INCONCLUSIVE,
        evidence="certified: " + "; ".join(
            f"eps={c['eps']}, v=pi*{c['m']}: R in [{c['residue']['lo']:.6f}, "
            f"{c['residue']['hi']:.6f}] ({c['stability']}), det = {_mid(c['determinant']):.6f} "
            f"(= (2m-1)/(2m+1) = {c['expected_determinant']:.6f})" for c in cert)
                 + f". First period-1 block found at eps = {p1_first} (pi/2 = "
                 f"{acc['half_pi']:.4f}). The flight of 2 pi m from phase phi lands at the same "
                 "plate height, so tau = 2v exactly and the block repeats at every v = pi m",
        particles_per_curve=None, run=run_name)
    diff = {d["eps"]: d for d in acc["diffusion"]}
    normal = diff.get(0.6)
    other = [d for e, d in diff.items() if e != 0.6]
    elliptic_below = [s for s in acc["search"] if s["first_elliptic"]
                      and s["first_elliptic"]["eps"] <= 0.6]
    lowest_elliptic = min((s["first_elliptic"]["eps"], s["period"]) for s in acc["search"]
                          if s["first_elliptic"]) if any(s["first_elliptic"]
                                                          for s in acc["search"]) else None
    hyperbolic_low = [(s["first"]["eps"], s["period"]) for s in acc["search"]
                      if s["first"] and s["first"]["eps"] <= 0.6]
    if normal is None:
        verdict, mu_text = INCONCLUSIVE, "no diffusion run at eps = 0.6"
    else:
        allowed = GOOD_APPROXIMATION + 1.96 * normal["mu_se"] + normal["mu_systematic"]
        ok_mu = abs(normal["mu"] - 1) <= allowed
        verdict = (CONFIRMED if ok_mu and not elliptic_below else
                   REFUTED if not ok_mu and abs(normal["mu"] - 1) > allowed else INCONCLUSIVE)
        if elliptic_below:
            verdict = REFUTED
        early = ", ".join(f"from n0 = {start}: {fit[0]:.3f}" for start, fit in
                          normal["fits"].items()
                          if start.isdigit() and int(start) < normal.get("family_from", 0))
        mu_text = (f"mu(0.6) = {normal['mu']:.3f} +- {normal['mu_se']:.3f} (bootstrap) +- "
                   f"{normal['mu_systematic']:.3f} (spread over the window family), |mu - 1| "
                   f"allowed {allowed:.3f}"
                   + (f"; windows starting in the transient give larger slopes ({early})"
                      if early else ""))
    diffusion = _claim(
        id="sec2-normal-diffusion", figure="sec2",
        statement="eps = 0.6 lies below the lowest elliptic (island-bearing) accelerator modes, "
                  "and velocity diffusion in discrete time is normal (<(v_n - v_0)^2> ~ n)",
        quote=QUOTES["normal-diffusion"],
        observable="slope mu of log <(v_n - v_0)^2> against log n from the paper's start box; "
                   "Newton search for accelerator blocks (Holmes map, standard-map form) by "
                   "period",
        regime=(f"fit windows [n0, {normal['n'][-1]:,}] with n0 in "
                f"{normal.get('family_starts', [normal['n'][-1] // 100])} (past the transient: "
                f"n0 >= {normal.get('family_from', normal['n'][-1] // 100):,}), "
                f"{normal['particles']} particles; periods "
                f"{[s['period'] for s in acc['search']]}") if normal else "",
        rule=f"{CONFIRMED} if |mu - 1| <= {GOOD_APPROXIMATION} + 1.96 sigma + systematic at eps "
             "= 0.6 and no elliptic (island-bearing) accelerator block is found at eps <= 0.6; "
             f"{REFUTED} if either fails",
        tolerance=f"'normal to a good approximation' = |mu - 1| <= {GOOD_APPROXIMATION}",
        verdict=verdict,
        evidence=f"{mu_text}; contrast "
                 + "; ".join(f"mu({d['eps']}) = {d['mu']:.3f} +- {d['mu_se']:.3f}"
                             for d in other)
                 + f". Lowest elliptic accelerator block found: eps = "
                 f"{lowest_elliptic[0] if lowest_elliptic else 'none'} (period "
                 f"{lowest_elliptic[1] if lowest_elliptic else '-'}); unstable (hyperbolic) "
                 f"accelerator orbits at eps <= 0.6: {hyperbolic_low or 'none'} (they carry no "
                 f"islands). Search grid {acc['search_grid']}^2 starts per (eps, period): a "
                 "search, not a proof of absence",
        particles_per_curve=normal["particles"] if normal else None,
        statistical={"mu_0.6": [normal["mu"], normal["mu_se"]]} if normal else {},
        systematic={"mu_0.6": normal["mu_systematic"]} if normal else {},
        run=run_name)
    return [k_claim, diffusion]


def lyapunov_claim(study, run_name):
    lyap = study["lyapunov"]
    lam, se = lyap["mean_per_collision"][-1], lyap["se_per_collision"][-1]
    n = np.array(lyap["checkpoints"])
    k = int(np.searchsorted(n, n[-1] / 10))
    drift = abs(lam - lyap["mean_per_collision"][k])
    drift_se = math.hypot(se, lyap["se_per_collision"][k])
    alpha, a_se, a_sys = lyap["alpha"], lyap["alpha_se"], lyap["alpha_systematic"]
    positive = lam > SIGMAS * se
    converged = drift <= 3 * drift_se + 0.02 * lam
    decays = math.isfinite(alpha) and alpha + SIGMAS * a_se < 0
    third = math.isfinite(alpha) and abs(alpha + 1 / 3) <= 1.96 * a_se + (a_sys or 0)
    verdict = (CONFIRMED if positive and converged and decays else
               REFUTED if (lam + SIGMAS * se < 0) or (math.isfinite(alpha)
                                                       and alpha - SIGMAS * a_se > 0)
               else INCONCLUSIVE)
    return _claim(
        id="intro-lyapunov", figure="intro",
        statement="The largest Lyapunov exponent is positive per collision and tends to zero "
                  "per unit time",
        quote=QUOTES["lyapunov"],
        observable="lambda_n = S_n/n and lambda_t = S_n/t_n from the tangent map (exact "
                   "Jacobian, renormalised every collision), mean over orbits",
        regime=f"eps = {lyap['eps']}, {lyap['orbits']} orbits from the paper's start box, "
               f"n <= {lyap['collisions_per_orbit']:,}",
        rule=f"{CONFIRMED} if lambda_n > {SIGMAS:g} standard errors above 0 and changes by less "
             "than 3 standard errors + 2% over the last decade, and the fitted exponent alpha "
             f"of lambda_t ~ t^alpha is below 0 by {SIGMAS:g} standard errors; {REFUTED} if "
             "either sign is the other way at that level",
        tolerance="signs at 5 standard errors; convergence 3 standard errors + 2%",
        verdict=verdict,
        evidence=f"lambda_n = {lam:.4f} +- {se:.4f} at n = {int(n[-1]):,} (change over the last "
                 f"decade {drift:.4f}), {_where_measured(lyap)}; lambda_t ~ t^alpha with "
                 f"alpha = {alpha:.3f} +- "
                 f"{a_se:.3f} (bootstrap over orbits) +- {a_sys:.3f} (window), "
                 f"{'consistent' if third else 'not consistent'} with the velocity-diffusion "
                 f"value -1/3 (lambda_t = lambda_n n/t, t ~ n^(3/2)). Cross-checks: tangent "
                 f"map vs verify.jacobian at {lyap['jacobian_states']} states: largest relative "
                 f"difference {lyap['jacobian_worst_relative']:.1e}; separation of nearby orbits "
                 f"minus tangent map over {lyap['separation_collisions']:,} collisions: "
                 f"{lyap['separation_mean_difference']:+.2e} +- "
                 f"{lyap['separation_se_difference']:.1e}. Cost: "
                 f"{lyap['total_collisions']:.3g} collisions in {lyap['seconds']:.0f} s",
        particles_per_curve=lyap["orbits"],
        statistical={"lambda_n": [lam, se], "alpha": [alpha, a_se]},
        systematic={"alpha": a_sys},
        run=run_name)


def _where_measured(lyap):
    """Where the orbits are when lambda_n is read, lambda by velocity band, and the standard
    map's value (the Holmes model), from the study (older studies lack them)."""
    if "final_velocity_quartiles" not in lyap:
        return "velocities at the end not recorded"
    q = lyap["final_velocity_quartiles"]
    b = lyap["bands"]
    rows = [f"v in [{b['edges'][j]:g}, {b['edges'][j + 1]:g}): {b['per_collision'][j]:.3f} +- "
            f"{b['standard_error'][j]:.3f}" for j in range(len(b["per_collision"]))
            if b["collisions"][j] > 0]
    return (f"read when the orbits' speeds have grown to a median of {q[1]:.0f} (quartiles "
            f"{q[0]:.0f}-{q[2]:.0f}), where the exact map is the standard map at K = 4 eps "
            f"(its value, the Holmes model from the same phases at v + 10^4: "
            f"{lyap['holmes_per_collision']:.4f} +- {lyap['holmes_se']:.4f}); by velocity band "
            f"(log-stretch per collision pooled over the orbits): " + "; ".join(rows))


def claims_of(study, run_name, checks):
    """All claims; those resting on a part whose re-check failed become inconclusive."""
    claims = (fixed_point_claims(study, run_name) + [period_two_claim(study, run_name)]
              + transition_claims(study, run_name) + accelerator_claims(study, run_name)
              + [lyapunov_claim(study, run_name)])
    depends = {"sec2-fixed-elliptic": "fixed_points", "sec2-fixed-hyperbolic": "fixed_points",
               "sec2-period-two": "period_two", "sec2-fermi-transition": "critical",
               "sec2-small-eps-bounded": "critical", "intro-lyapunov": "lyapunov"}
    for claim in claims:
        part = depends.get(claim["id"])
        if part and part in checks and not checks[part][0]:
            claim["verdict"] = INCONCLUSIVE
            claim["evidence"] += f" [re-check of the committed data failed: {checks[part][1]}]"
    return claims


# --- markdown ----------------------------------------------------------------------------------

def _table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(lines)


def markdown(study, claims, checks, images, source):
    crit = study["critical"]
    lines = ["## Dynamics: periodic orbits, stability, Lyapunov exponents, Fermi acceleration",
             "",
             "Certified (interval proofs, `verify.periodic_orbit`): the fixed points, the period-2 "
             "orbits, the accelerator modes and the Greene orbits in the table of certified "
             "crossings. Computed in float64 (not proved): the residue curves, Greene's eps_c "
             "(approximants up to period "
             f"{max(max(r['periods']) for r in crit['rows'])}), the Lyapunov exponents, the "
             "diffusion exponents and the accelerator search.",
             "",
             f"Data: {source or 'computed for this report'}; study time "
             f"{study['seconds']:.0f} s. Re-checked here: "
             + "; ".join(f"{text} ({'ok' if ok else 'FAILED'})"
                         for part, (ok, text) in checks.items() if part != "seconds")
             + f" [{checks['seconds'][1]}].", ""]
    lines += [f"![residue against eps]({images['residue']})", ""]
    rows = []
    for b in study["period_two"]["branches"]:
        changes = ", ".join(f"R={c['level']:g} {c['direction']} at {c['eps']:.6f}"
                            for c in b["changes"])
        cert = ", ".join(f"{c['eps']:.4g}: {c['stability']}" for c in b["certified"])
        rows.append([b["model"], b["m"], changes or "-", cert or "-"])
    lines += ["Period-2 orbits (s, pi m - s), (-s, pi m + s), eps sin s = s:", "",
              _table(["map", "m", "stability changes (float64)", "certified"], rows), ""]
    lines += [f"![eps_c against velocity band]({images['eps_c']})", ""]
    best = _band_table(study)
    rows = []
    for j in sorted({r["band"] for r in crit["rows"]}):
        g = next((r for r in crit["rows"] if r["band"] == j and r["prefix"] == []), None)
        g2 = next((r for r in crit["rows"] if r["band"] == j and r["prefix"] == [2]), None)
        sim = [s for s in study["crossing_simulation"] if s["band"] == j]
        sim_text = ", ".join(f"{s['factor']:g}: {s['crossed']}/{s['particles']}" for s in sim)
        rows.append([j, f"{g['eps_c']:.9f} +- {g['uncertainty']:.1e}" if g else "-",
                     f"{g2['eps_c']:.9f} +- {g2['uncertainty']:.1e}" if g2 else "-",
                     f"{best[j]['eps_c']:.9f} (omega {best[j]['omega']:.3f})",
                     f"{K_C_QUARTER:.9f}", sim_text or "-"])
    lines += ["eps_c per velocity band j (Greene's criterion with the critical residue R_c, "
              "the crossings' Aitken extrapolation; float64 to period 987, the last levels of "
              "the golden pairs of bands 1 and 10 and of the Holmes map in multiprecision); "
              "Holmes map = standard map, "
              "K_c/4 in every band (computed: "
              + ", ".join(f"{h['eps_c']:.10f} +- {h['uncertainty']:.1e}" for h in crit["holmes"])
              + "); simulation: orbits crossing the band within the stated collisions at "
              "factor x the band's largest eps_c:", "",
              _table(["band j", "omega = j+0.618", "omega = j+0.382", "largest found",
                      "Holmes map", "crossed (factor: k/N)"], rows), ""]
    cc = study["certified_crossings"]
    if cc:
        rows = [[c["band"], "j+" + ("0.618" if c["prefix"] == [] else "0.382"), c["period"],
                 f"{c['eps']:.9f}", c["side"],
                 f"[{c['residue']['lo_str'][:14]}, {c['residue']['hi_str'][:14]}]",
                 "yes" if c["decided"] else "**no**", c["dps"], f"{c['seconds']:.1f}"]
                for c in cc]
        lines += ["Greene orbits certified on both sides of their crossing of R_c:", "",
                  _table(["band", "omega", "period", "eps", "side", "residue enclosure",
                          "decided", "digits", "s"], rows), ""]
    lines += [f"![Lyapunov exponents]({images['lyapunov']})", "",
              f"![velocity diffusion]({images['diffusion']})", ""]
    acc = study["accelerator"]
    rows = [[s["period"], s["first"]["eps"] if s["first"] else "none",
             f"{s['first_elliptic']['eps']} (R = {s['first_elliptic']['residue']:.3f})"
             if s["first_elliptic"] else "none"] for s in acc["search"]]
    lines += ["Accelerator blocks of the Holmes map (standard-map form) found by Newton from a "
              f"{acc['search_grid']}^2 grid, eps scanned {acc['search_eps']} (first eps found):",
              "", _table(["period", "any", "elliptic"], rows), "", "### Claims", ""]
    for c in claims:
        lines += [f"- **{c['id']}** ({c['verdict']}): {c['statement']}. {c['evidence']}"]
    return "\n".join(lines) + "\n"


def dynamics_section(out_dir, quick=False, echo=print):
    """Write the figures into ``out_dir``; return (markdown, claims)."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    study, source = load_study(quick, echo)
    checks = recheck(study, quick)
    echo(f"dynamics: re-checks {'ok' if all(ok for ok, _ in checks.values()) else 'FAILED'}")
    images = {}
    for name, draw in (("residue", figures.residue_figure), ("lyapunov", figures.lyapunov_figure),
                       ("eps_c", figures.eps_c_figure), ("diffusion", figures.diffusion_figure)):
        images[name] = draw(study, out_dir)[0].name
    claims = claims_of(study, source, checks)
    return markdown(study, claims, checks, images, source), claims


__all__ = ["dynamics_section"]
