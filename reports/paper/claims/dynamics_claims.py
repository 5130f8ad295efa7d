"""The paper's Section 2 statements and its Lyapunov remark decided on the dynamics study
(``reports.paper.studies.dynamics_study``; the committed
``reports/paper/studies/dynamics_study.json``), through the register
(``reports.paper.claims.register_section2``): each claim the agreement of its family.

Members (the study's fields; tolerances ``NEAR``, ``LOWEST_MARGIN``, ``SIGMAS`` and the words'
bounds of ``reports.paper.claims.rules``):

* fixed points elliptic (0 < eps < 1) or hyperbolic (eps < 0, eps > 1): every certified fixed
  point in the range, confirmed if proved that kind with a trace enclosure holding 2 - 4 eps,
  refuted if proved the other kind or the enclosure misses 2 - 4 eps;
* period two: two parts, every certified fixed point above eps = 1 (hyperbolic) and every
  certified period-2 orbit below its first loss of stability (elliptic);
* the transition near eps = 0.24: three parts, "curves broken near 0.24 at all but the lowest
  velocities" (each band j >= 1 within ``NEAR`` of K_c/4; band 0 beyond ``LOWEST_MARGIN``; the
  high-velocity limit a = K_c/4 within 3 standard errors) and "unbounded velocity of some
  orbits" (the simulations across a band: some orbit crosses at 1.10 eps_c) and "none below
  eps_c" (none crosses at 0.95 eps_c);
* bounded velocity for small eps: every band keeps a curve up to (1 - NEAR) K_c/4, and the
  limit;
* accelerator modes: every certified period-1 block, and the first block found within one
  grid step of eps = pi/2;
* normal diffusion at eps = 0.6: two parts, "below the lowest accelerator modes" (every period
  searched: no elliptic block at eps <= 0.6) and "normal to a good approximation" (every
  window's mu of the study at eps = 0.6 past the transient, n0 >= the study's
  ``family_from``, within ``rules.SAME`` of 1, not beyond ``rules.SAME_FAILS``);
* anomalous diffusion where stable accelerator modes exist: two parts, the certified blocks
  elliptic, and every window's mu at an eps with elliptic accelerator blocks at least
  ``rules.SAME_FAILS`` from 1 (not within ``rules.SAME``);
* the Lyapunov exponent: two parts, lambda_n > 0 by ``SIGMAS`` standard errors at the last
  checkpoint and a decade before it, and every fitted exponent alpha of lambda_t ~ t^alpha
  below 0 by ``SIGMAS`` standard errors.

A part of the study whose re-check failed adds a member that cannot decide to every part of
the claims resting on it.
"""

from __future__ import annotations

import math

import numpy as np

from reports.paper.claims import family as F
from reports.paper.claims import rules as R
from reports.paper.claims.claim import CONFIRMED, INCONCLUSIVE, REFUTED
from reports.paper.claims.register import make_claim
from reports.paper.studies.dynamics_study import K_C_QUARTER

NEAR, LOWEST_MARGIN, SIGMAS = R.NEAR, R.LOWEST_MARGIN, R.SIGMAS
DEPENDS = {"sec2-fixed-elliptic": "fixed_points", "sec2-fixed-hyperbolic": "fixed_points",
           "sec2-period-two": "period_two", "sec2-fermi-transition": "critical",
           "sec2-small-eps-bounded": "critical", "intro-lyapunov": "lyapunov"}


def _mid(e):
    return 0.5 * (e["lo"] + e["hi"])


def _kind_member(variant, row, want, part="", quantity="residue"):
    """A certified orbit: confirmed if proved ``want``, refuted if proved the other kind,
    inconclusive if undecided."""
    kind = row["stability"]
    verdict = CONFIRMED if kind == want else INCONCLUSIVE if kind == "undecided" else REFUTED
    e = row[quantity]
    holds = (0.0, 1.0) if want == "elliptic" else (-math.inf, 0.0)
    fails = ((-math.inf, 0.0), (1.0, math.inf)) if want == "elliptic" else ((0.0, 1.0),)
    return F.Analysis(f"{variant}: {kind}", verdict, quantity, _mid(e), e["lo"], e["hi"], holds,
                      fails, "" if verdict != INCONCLUSIVE else F.STRADDLES, part)


def fixed_point_claims(study, run):
    rows = study["fixed_points"]["rows"]
    out = []
    for key, sel, want in (("fixed-elliptic", [r for r in rows if 0 < r["eps"] < 1],
                            "elliptic"),
                           ("fixed-hyperbolic", [r for r in rows
                                                 if r["eps"] < 0 or r["eps"] > 1],
                            "hyperbolic")):
        members = []
        for r in sel:
            a = _kind_member(f"m = {r['m']}, eps = {r['eps']}", r, want)
            if not r["trace_contains"]:
                a = F.Analysis(a.variant + " (trace misses 2 - 4 eps)", REFUTED, a.quantity,
                               a.value, a.lo, a.hi, a.holds, a.fails)
            members.append(a)
        out.append(make_claim(f"sec2-{key}", f"{F.family_text(members)}.", analyses=members,
                              run=run))
    return out


def period_two_claim(study, run):
    branches = [b for b in study["period_two"]["branches"] if b["model"] == "exact"]
    members = [_kind_member(f"fixed point m = {r['m']}, eps = {r['eps']}", r, "hyperbolic",
                            "the fixed points unstable above 1")
               for r in study["fixed_points"]["rows"] if r["eps"] > 1]
    for b in branches:
        members += [_kind_member(f"period 2, m = {b['m']}, eps = {c['eps']}", c, "elliptic",
                                 "born elliptic period-2 orbits")
                    for c in b["certified"] if c["eps"] < b["loss_of_stability"]]
    loss = ", ".join(f"m = {b['m']}: {b['loss_of_stability']:.6f}" for b in branches)
    return make_claim("sec2-period-two", f"First loss of stability (float64): {loss}; "
                      f"{F.family_text(members)}.", analyses=members, run=run)


def _bands(study):
    return {b["band"]: b for b in study["critical"]["band_max"]}


def _limit_member(study, part):
    crit = study["critical"]
    limit = crit["limits"].get("golden2") or crit["limits"].get("golden")
    if limit is None:
        return F.in_part(part, [F.too_few("no high-velocity fit", "limit a")])[0]
    lo, hi = limit["a"] - 3 * limit["a_error"] - 1e-6, limit["a"] + 3 * limit["a_error"] + 1e-6
    inside = lo <= K_C_QUARTER <= hi
    return F.Analysis(f"high-velocity fit a + b/v + c/v^2: a = {limit['a']:.8f} +- "
                      f"{limit['a_error']:.1e} (3 standard errors)", CONFIRMED if inside
                      else INCONCLUSIVE, "limit a", limit["a"], lo, hi,
                      (K_C_QUARTER, K_C_QUARTER), (), "" if inside else F.STRADDLES, part)


def transition_claims(study, run):
    bands = _bands(study)
    near_part = "curves broken near 0.24 at all but the lowest velocities"
    members = []
    for j, b in sorted(bands.items()):
        dist = (b["eps_c"] - K_C_QUARTER) / K_C_QUARTER
        if j == 0:
            members.append(F.threshold_member(
                f"band 0 (omega {b['omega']:.3f}): eps_c = {b['eps_c']:.9f}",
                "(eps_c - K_c/4) / (K_c/4)", dist, dist, dist, LOWEST_MARGIN, False))
            members[-1] = F.in_part(near_part, [members[-1]])[0]
        else:
            members.append(F.in_part(near_part, [F.threshold_member(
                f"band {j} (omega {b['omega']:.3f}): eps_c = {b['eps_c']:.9f} +- "
                f"{b['uncertainty']:.1e}", "|eps_c - K_c/4| / (K_c/4)", abs(dist), abs(dist),
                abs(dist), NEAR, True)])[0])
    members.append(_limit_member(study, near_part))
    for s in study["crossing_simulation"]:
        variant = (f"band {s['band']} at {s['factor']:g} eps_c: {s['crossed']}/"
                   f"{s['particles']} crossed within {s['collisions']:,} collisions")
        if s["factor"] < 1:
            part = "no crossing below eps_c"
            verdict, note = (CONFIRMED, "") if s["crossed"] == 0 else (REFUTED, "")
        else:
            part = "unbounded velocity above eps_c"
            verdict, note = (CONFIRMED, "") if s["crossed"] > 0 else (INCONCLUSIVE, F.TOO_FEW)
        members.append(F.Analysis(variant, verdict, "orbits crossed", s["crossed"],
                                  s["crossed"], s["crossed"], (0.0, math.inf), (), note, part))
    holmes = ", ".join(f"{h['eps_c']:.10f} +- {h['uncertainty']:.1e}"
                       for h in study["critical"]["holmes"])
    transition = make_claim("sec2-fermi-transition", f"K_c/4 = {K_C_QUARTER:.10f}; Holmes "
                            f"map (the standard map): {holmes}: {F.family_text(members)}.",
                            analyses=members, run=run,
                            statistical={f"eps_c_band_{j}": [b["eps_c"], b["uncertainty"]]
                                         for j, b in sorted(bands.items())})
    floor = (1 - NEAR) * K_C_QUARTER
    kept = [F.threshold_member(f"band {j}: eps_c = {b['eps_c']:.9f}", "eps_c", b["eps_c"],
                               b["eps_c"], b["eps_c"], floor, False)
            for j, b in sorted(bands.items())]
    kept.append(_limit_member(study, ""))
    bounded = make_claim("sec2-small-eps-bounded", f"every band keeps a curve up to at least "
                         f"{floor:.6f} (float64 Greene residues, not a proof that the curves "
                         f"exist): {F.family_text(kept)}.", analyses=kept, run=run)
    return [transition, bounded]


def window_fits(d):
    """The fitted windows of a diffusion run that lie past its transient: those starting at
    the study's ``family_starts`` (n0 >= ``family_from``); all of them in a study without."""
    fits = d.get("fits") or {"main": [d["mu"], d["mu_se"]]}
    if "family_starts" not in d:
        return fits
    starts = {str(n0) for n0 in d["family_starts"]}
    return {name: fit for name, fit in fits.items() if name in starts}


def transient_text(d):
    """The slopes of the windows that start in the transient (not members), in words."""
    early = [f"from n0 = {name}: {fit[0]:.3f}" for name, fit in (d.get("fits") or {}).items()
             if name.isdigit() and int(name) < d.get("family_from", 0)]
    return (f"; windows starting in the transient (not members) give larger slopes at eps = "
            f"{d['eps']} ({', '.join(early)})" if early else "")


def _mu_members(d, holds, fails, part):
    """One member per window of a diffusion run past its transient (``window_fits``): mu with
    1.96 standard errors, under the two-band rule (``holds``, ``fails``) or, with ``holds``
    None, the anomalous reading (|mu - 1| at least ``rules.SAME_FAILS``, fails within
    ``rules.SAME``)."""
    fits = window_fits(d)
    if not fits:
        return F.in_part(part, [F.too_few(f"eps = {d['eps']}: no fitted window past the "
                                          "transient", "mu")])
    out = []
    for name, (mu, se) in fits.items():
        window = f"n0 = {name}" if name.isdigit() else f"{name} window"
        variant = f"eps = {d['eps']}, {window}: mu = {mu:.3f} +- {1.96 * se:.3f}"
        if holds is None:
            off = abs(mu - 1)
            out.append(F.word_member(variant, "|mu - 1|", off, max(0.0, off - 1.96 * se),
                                     off + 1.96 * se, R.SAME_FAILS, R.SAME))
        else:
            out.append(F.band_member(variant, "mu", mu, mu - 1.96 * se, mu + 1.96 * se, holds,
                                     fails))
    return F.in_part(part, out)


def accelerator_claims(study, run):
    acc = study["accelerator"]
    cert = acc["certified"]
    p1 = next((s for s in acc["search"] if s["period"] == 1), None)
    p1_first = p1["first"]["eps"] if p1 and p1["first"] else None
    step = acc["search_eps"][2]
    members = [_kind_member(f"eps = {c['eps']}, v = pi {c['m']}", c, "elliptic") for c in cert]
    members.append(F.threshold_member(
        f"first period-1 block found at eps = {p1_first} (pi/2 = {acc['half_pi']:.4f}, grid "
        f"step {step:g})", "|first eps - pi/2|",
        abs(p1_first - acc["half_pi"]) if p1_first is not None else math.nan,
        abs(p1_first - acc["half_pi"]) if p1_first is not None else math.nan,
        abs(p1_first - acc["half_pi"]) if p1_first is not None else math.nan, step, True))
    modes = make_claim("sec2-accelerator-modes", f"{F.family_text(members)}.",
                       analyses=members, run=run)
    diff = {d["eps"]: d for d in acc["diffusion"]}
    normal = diff.get(0.6)
    below = "below the lowest accelerator modes"
    members = []
    for s in acc["search"]:
        fe = s["first_elliptic"]
        eps = fe["eps"] if fe else math.inf
        members.append(F.in_part(below, [F.threshold_member(
            f"period {s['period']}: first elliptic block at eps = {fe['eps'] if fe else 'none'}",
            "first elliptic eps", eps, eps, eps, 0.6, False)])[0])
    if normal is not None:
        members += _mu_members(normal, R.relative_band(1.0, R.SAME),
                               R.relative_band(1.0, R.SAME_FAILS),
                               "normal to a good approximation")
    diffusion = make_claim("sec2-normal-diffusion", f"Search grid {acc['search_grid']}^2 "
                           f"starts per (eps, period), a search, not a proof of absence: "
                           f"{F.family_text(members)}"
                           f"{transient_text(normal) if normal else ''}.", analyses=members,
                           particles_per_curve=normal["particles"] if normal else None,
                           run=run)
    elliptic_eps = sorted({c["eps"] for c in cert if c["stability"] == "elliptic"})
    members = [_kind_member(f"eps = {c['eps']}, v = pi {c['m']}", c, "elliptic",
                            "stable, surrounded by islands") for c in cert]
    for e in elliptic_eps:
        if e in diff:
            members += _mu_members(diff[e], None, None, "anomalous diffusion")
    anomalous = make_claim("sec2-anomalous-diffusion", f"{F.family_text(members)}"
                           + "".join(transient_text(diff[e]) for e in elliptic_eps if e in diff)
                           + ".", analyses=members, run=run)
    return [modes, diffusion, anomalous]


def lyapunov_claim(study, run):
    lyap = study["lyapunov"]
    n = np.array(lyap["checkpoints"])
    k = int(np.searchsorted(n, n[-1] / 10))
    positive = "positive per collision"
    members = []
    for i in (k, len(n) - 1):
        lam, se = lyap["mean_per_collision"][i], lyap["se_per_collision"][i]
        members.append(F.in_part(positive, [F.threshold_member(
            f"lambda_n at n = {int(n[i]):,}: {lam:.4f} +- {se:.4f}", "lambda_n", lam,
            lam - SIGMAS * se, lam + SIGMAS * se, 0.0, False)])[0])
    fits = lyap.get("fits") or {"main": [lyap["alpha"], lyap["alpha_se"]]}
    for name, (alpha, se) in fits.items():
        members.append(F.in_part("zero per unit time", [F.threshold_member(
            f"lambda_t ~ t^alpha, {name} window: alpha = {alpha:.3f} +- {se:.3f}", "alpha",
            alpha, alpha - SIGMAS * se, alpha + SIGMAS * se, 0.0, True)])[0])
    return make_claim("intro-lyapunov", f"eps = {lyap['eps']}, {lyap['orbits']} orbits from "
                      f"the paper's start box: {F.family_text(members)}; signs at {SIGMAS:g} "
                      f"standard errors. lambda_n is {where_measured(lyap)}.", analyses=members,
                      particles_per_curve=lyap["orbits"], run=run)


def where_measured(lyap):
    """Where the orbits are when lambda_n is read, lambda by velocity band, and the standard
    map's value (the Holmes model), from the study (older studies lack them)."""
    if "final_velocity_quartiles" not in lyap:
        return "read at velocities not recorded"
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


def with_recheck(claim, checks):
    """The claim with a member that cannot decide in every part when the re-check of the part
    of the study it rests on failed."""
    part = DEPENDS.get(claim.id)
    if not part or part not in checks or checks[part][0]:
        return claim
    members = [F.Analysis(a["variant"], a["verdict"], a["figure"]["quantity"],
                          a["figure"]["value"], *a["figure"]["interval"],
                          tuple(a["bounds"]["holds"]),
                          tuple(tuple(z) for z in a["bounds"]["fails"]), a["note"], a["part"])
               for a in claim.analyses]
    failed = [F.in_part(p, [F.too_few(f"re-check of the committed data failed: "
                                      f"{checks[part][1]}", "re-check")])[0]
              for p in {a.part for a in members}]
    return make_claim(claim.id, claim.evidence + " [re-check of the committed data failed]",
                      analyses=members + failed, particles_per_curve=claim.particles_per_curve,
                      statistical=claim.statistical, run=claim.run)


def dynamics_claims(study, run, checks):
    """Every claim of the dynamics study (module docstring)."""
    claims = (fixed_point_claims(study, run) + [period_two_claim(study, run)]
              + transition_claims(study, run) + accelerator_claims(study, run)
              + [lyapunov_claim(study, run)])
    return [with_recheck(c, checks) for c in claims]
