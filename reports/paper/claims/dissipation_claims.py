"""Claims from other publications and this project about dissipation, decided on the study of
``reports.paper.studies.dissipation_study`` (its docstring gives the sources, the random-phase
estimate of beta and the derivation of the velocity strip): <v_n> saturates
(``dissipation-saturates``), V_sat ~ (1 - r)^beta (``dissipation-exponent``) and the orbits stay
in the velocity strip (``dissipation-velocity-strip``), each the agreement of its family.
"""

from __future__ import annotations

import math

import numpy as np

from reports.paper.claims import family as F
from reports.paper.claims.claim import CONFIRMED, INCONCLUSIVE, REFUTED, Claim, agreement
from reports.paper.studies.dissipation_study import (
    BLOCKS,
    RANDOM_PHASE_BETA,
    _beta_of_stacked,
    exponent,
    log_slope,
    plateau,
    velocity_strip,
)
from reports.paper.studies.sampling import bootstrap_blocks

RESOLUTION = 0.25  # half the distance from -1/2 to 0 (no suppression) and to -1

PLATEAU_WINDOWS = (1.0, 0.5)  # the plateau: the last decade of n, and the last half decade


def plateau_windows(window):
    """The plateau windows of the family: [n_max 10^-d, n_max] for d in PLATEAU_WINDOWS."""
    return [(window[1] * 10 ** -d, window[1]) for d in PLATEAU_WINDOWS]


def saturation_member(n, elastic, c, window):
    """Does <v_n> of ``c`` saturate over ``window`` while the elastic curve grows? The slope of
    log<v_n> with U = 1.96 sigma (bootstrap over particle blocks): inconclusive when the elastic
    slope is not above its U (no Fermi acceleration to suppress); refuted if the curve grows as
    fast as the elastic one (slope >= elastic slope - U - U_elastic); confirmed if its slope is
    within U of 0; inconclusive otherwise."""
    def slope_u(curve):
        s = log_slope(n, curve.mean_v, *window)
        err = bootstrap_blocks(curve.sum_v, curve.count, lambda m: log_slope(n, m, *window))
        return s, 1.96 * err
    el, u_el = slope_u(elastic)
    sl, u = slope_u(c)
    variant = (f"{c.label}, n in [{window[0]:g}, {window[1]:g}]: slope {sl:.3f} +- {u:.3f} "
               f"(elastic {el:.3f} +- {u_el:.3f})")
    if not all(math.isfinite(x) for x in (el, u_el, sl, u)):
        return F.too_few(variant, "slope of log<v_n>", sl)
    if not el > u_el:
        verdict, note = INCONCLUSIVE, F.TOO_FEW
    elif sl >= el - u - u_el:
        verdict, note = REFUTED, ""
    elif abs(sl) <= u:
        verdict, note = CONFIRMED, ""
    else:
        verdict, note = INCONCLUSIVE, F.STRADDLES
    return F.Analysis(variant, verdict, "slope of log<v_n>", sl, sl - u, sl + u, (0.0, 0.0),
                      ((el - u_el, math.inf),), note)


def exponent_verdict(beta, sigma, systematic, expected=RANDOM_PHASE_BETA):
    """U = 1.96 sigma + systematic. refuted: |beta - expected| > U; confirmed: within U and
    U <= RESOLUTION (1/4: tells -1/2 from 0 and from -1); inconclusive otherwise."""
    u = 1.96 * sigma + systematic
    if not (math.isfinite(u) and math.isfinite(beta)):
        return INCONCLUSIVE
    off = abs(beta - expected)
    return REFUTED if off > u else CONFIRMED if u <= RESOLUTION else INCONCLUSIVE


def exponent_members(d):
    """beta of V_sat ~ (1 - r)^beta over each plateau window and two fit ranges (every 1 - r,
    and without the largest), each with its bootstrap sigma, under ``exponent_verdict``."""
    out = []
    x_all = np.asarray(d.one_minus_r, float)
    for window in plateau_windows(d.window):
        for keep, name in ((len(x_all), "every 1 - r"), (len(x_all) - 1, "without the largest")):
            x, curves = x_all[:keep], d.restitution[:keep]
            beta = exponent(x, [plateau(d.n, c.mean_v, *window) for c in curves])[0]
            num, den = np.hstack([c.sum_v for c in curves]), np.hstack([c.count for c in curves])
            sigma = bootstrap_blocks(num, den, _beta_of_stacked(d.n, x, window))
            verdict = exponent_verdict(beta, sigma, 0.0)
            u = 1.96 * sigma
            out.append(F.Analysis(
                f"n in [{window[0]:g}, {window[1]:g}], {name}: beta = {beta:.3f} +- {u:.3f}",
                verdict, "beta", beta, beta - u, beta + u,
                (RANDOM_PHASE_BETA - RESOLUTION, RANDOM_PHASE_BETA + RESOLUTION), (),
                "" if verdict != INCONCLUSIVE else F.STRADDLES))
    return out


def strip_members(d):
    """Per 1 - r (a part each), max |v_n| of each half of the strip orbits against V*(r):
    confirmed inside, refuted outside (a rigorous bound: no tolerance)."""
    out = []
    for x, halves in zip(d.one_minus_r, d.strip_halves or [], strict=False):
        edge = velocity_strip(1.0 - x, d.eps)
        for i, m in enumerate(halves):
            verdict = CONFIRMED if m <= edge else REFUTED
            out.append(F.Analysis(f"half {i + 1} of the orbits: max |v| = {m:.4g}, V* = "
                                  f"{edge:.4g}", verdict, "max |v| / V*", m / edge, m / edge,
                                  m / edge, (0.0, 1.0), ((1.0, math.inf),), "",
                                  f"1 - r = {x:g}"))
    return out


def _claim(members, **fields):
    verdict, kind = agreement(F.analyses_json(members))
    return Claim(**fields, verdict=verdict, inconclusive=kind,
                 analyses=F.analyses_json(members))


def dissipation_claims(d):
    """Claims ``dissipation-saturates``, ``dissipation-exponent`` and
    ``dissipation-velocity-strip``, each the agreement of its family (the member rules:
    ``saturation_member``, ``exponent_verdict``, ``strip_members``)."""
    curves = d.restitution + d.drag
    sat = [saturation_member(d.n, d.elastic, c, w) for w in plateau_windows(d.window)
           for c in curves]
    beta = exponent_members(d)
    strip = strip_members(d)
    where = (f"eps = {d.eps:g}, {d.particles} starts in the paper's escape box, plateau window "
             f"n in [{d.window[0]:g}, {d.window[1]:g}]")
    windows = "the plateau windows: the last decade of n and the last half decade"
    return [
        _claim(
            sat, id="dissipation-saturates", figure="dissipation",
            statement="dissipation suppresses Fermi acceleration: <v> grows, then bends to a "
                      "constant (the source shows it for linear drag; checked here for "
                      "restitution and both drag laws)",
            quote="the average velocity starts growing at first and then bends towards a regime "
                  "of constant value, thus confirming that the introduction of drag force is a "
                  "sufficient condition to suppress Fermi acceleration",
            observable="slope of log<v_n> against log n over the plateau window, eps = 2",
            regime="the plateau: n in the last decade of the study",
            family=f"every dissipative physics (restitution and both drag laws) over {windows}",
            tolerance="a slope compatible with 0 within 1.96 sigma is a plateau",
            source="de Souza, Simoes, da Silva, Leonel, Math. Probl. Eng. 2009, 409857 "
                   "(abstract; not the paper)",
            evidence=f"{where}: {F.family_text(sat)} (bootstrap over {BLOCKS} particle "
                     "blocks).",
            particles_per_curve=d.particles,
            statistical={c.label: c.slope_err for c in [d.elastic, *curves]},
            systematic={c.label: c.slope_sys for c in [d.elastic, *curves]}, run=None,
            rule="each member: its slope within 1.96 sigma of 0 while the elastic one grows; "
                 "refuted if it grows as fast as the elastic curve; the claim is the agreement "
                 "of its members"),
        _claim(
            beta, id="dissipation-exponent", figure="dissipation",
            statement="V_sat ~ (1 - r)^(-1/2), our random-phase estimate (no published value "
                      "found: Livorati, Ladeira, Leonel, PRE 78, 056205 (2008) and the other "
                      "sources in reports/paper/studies/dissipation_study.py give none in their "
                      "abstracts)",
            quote="",
            observable="least-squares slope of log V_sat against log(1 - r), eps = 2",
            regime="the plateau of each r",
            family=f"{windows}; the fit over every 1 - r and without the largest",
            tolerance="|beta + 1/2| within 1.96 sigma, resolving U <= 1/4",
            source="this project",
            evidence=f"{where}: {F.family_text(beta)}; 1 - r in "
                     f"{', '.join(f'{x:g}' for x in d.one_minus_r)}.",
            particles_per_curve=d.particles,
            statistical={"beta": d.beta_err}, systematic={"beta": d.beta_sys}, run=None,
            rule="each member: |beta + 1/2| <= 1.96 sigma, with U <= 1/4; refuted if beyond; "
                 "the claim is the agreement of its members"),
        _claim(
            strip, id="dissipation-velocity-strip", figure="dissipation",
            statement="inelastic impacts confine the chaotic orbits to a velocity strip of width"
                      " ~ 1/(1 - r); in our units its edge is V*(r) ~ 2 abs(eps)/(1 - r), "
                      "derived in reports/paper/studies/dissipation_study.py",
            quote="bounded by a velocity strip v = +-Gamma/(1 - r)",
            observable="max |v_n| of the study's orbits against V*(r)",
            regime="every collision of 10,000 per orbit",
            family="each 1 - r (a part each), the orbits in two independent halves",
            tolerance="none: V* is a rigorous bound of the exact dynamics",
            source="Barroso, Carneiro, Macau, Phys. Rev. E 79, 026206 (2009) (abstract; not the "
                   "paper)",
            evidence=f"eps = {d.eps:g}, {d.strip_orbits} orbits of {int(d.n[-1]):,} "
                     f"collisions per r from the study's starts: {F.family_text(strip)}; the "
                     f"strip is a bound (width ~ (1 - r)^-1), the plateau grows only as "
                     f"(1 - r)^{d.beta:.2f}.",
            particles_per_curve=d.strip_orbits, statistical={}, systematic={}, run=None,
            rule="every max |v_n| <= V*(r) (a rigorous bound of the exact dynamics: no "
                 "tolerance); refuted if an orbit leaves the strip; one part per 1 - r"),
    ]
