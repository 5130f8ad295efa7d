"""The paper's claims about its numerical method (Section 2): the time step from the rigorous
lower bound "never oversteps" the first collision "modulo round-off", "typically converges
quadratically", and reaches machine precision in "around five steps".

The method is ``fastpath.flight(method="lower_bound")`` (the paper's lower-bound steps); its
iterates are also taken here in mpmath (``lower_bound_iterates``, the same step at
``ITERATE_DPS`` digits) to read the order of convergence below float64's precision. Samples
(``SAMPLES``), two per claim:

* "paper orbits": the departures along orbits from the paper's escape box (eps = 0.6,
  3.85 < phi < 4.15, 2 < v < 4), the flights the paper's simulations make ("in practice");
* "phase space": uniform departures at eps = 0.6, phi in [0, 2 pi), pi/2 < v < 5 pi/2 (the
  first two velocity periods of Fig. 1), those that leave the plate.

"Never overstepped" is judged by ``reports.precision.evaluate.overstepped`` against ``verify``
(a final time past a later root; the rounding of the last step is not an overstep) on the two
samples and on the close root pairs and hard cases of the precision comparison
(``reports.precision.cases``), where a step past the first root is possible at all.
"""

from __future__ import annotations

import functools
import math

import mpmath
import numpy as np
from mpmath import mp

import fastpath
from fastpath.arithmetic.phase import TWO_PI
from reports.paper.claims import family as F
from reports.paper.claims import rules as R
from reports.paper.claims.register import make_claim
from reports.paper.studies.replicates import INTERVAL_REPLICATES
from reports.paper.studies.sampling import EPS, ESCAPE_BOX, uniform_box
from reports.paper.studies.seeds import SAMPLING_SEED

SIZES = {False: {"orbits": 200, "collisions": 50, "phase": 5000, "iterates": 200,
                 "overstep": 300},
         True: {"orbits": 20, "collisions": 20, "phase": 400, "iterates": 30, "overstep": 40}}
ITERATE_DPS = 80
ITERATE_STEPS = 12
FIVE = 5.0
FIVE_HOLDS = (4.0, 6.0)    # "around five": within one step of five
FIVE_FAILS = (2.5, 10.0)   # ... not: a factor two off
QUADRATIC = 2.0            # order of convergence


@functools.lru_cache(maxsize=2)
def samples(quick=False):
    """{name: (phi, v)} of the two samples (module docstring)."""
    size = SIZES[bool(quick)]
    rng = np.random.default_rng(SAMPLING_SEED)
    phi0, v0 = uniform_box(rng, ESCAPE_BOX, size["orbits"])
    orbits = [fastpath.orbit(float(p), float(w), EPS, size["collisions"])
              for p, w in zip(phi0, v0, strict=True)]
    phi = np.concatenate([o.phi[:-1] for o in orbits])
    v = np.concatenate([o.v[:-1] for o in orbits])
    ph = rng.uniform(0.0, TWO_PI, size["phase"])
    vv = rng.uniform(0.5 * math.pi, 2.5 * math.pi, size["phase"])
    leaves = vv + EPS * np.sin(ph) > 0
    return {"paper orbits": (phi, v), "phase space": (ph[leaves], vv[leaves])}


def _bootstrap_mean(x, seed=SAMPLING_SEED):
    rng = np.random.default_rng(seed)
    means = [float(np.mean(rng.choice(x, len(x)))) for _ in range(INTERVAL_REPLICATES)]
    return float(np.percentile(means, 2.5)), float(np.percentile(means, 97.5))


def five_steps_claim(quick=False):
    members = []
    for name, (phi, v) in samples(quick).items():
        it = np.asarray(fastpath.flight(phi, v, EPS, method="lower_bound").iterations, float)
        lo, hi = _bootstrap_mean(it)
        members.append(F.band_member(
            f"{name}: {len(it):,} flights, mean {it.mean():.3f} steps (median "
            f"{np.median(it):g}, largest {it.max():g})", "mean lower-bound steps",
            float(it.mean()), lo, hi, FIVE_HOLDS, FIVE_FAILS))
    return make_claim("sec2-five-steps", "fastpath.flight(method='lower_bound') at eps = 0.6: "
                      f"{F.family_text(members)}.", analyses=members)


def _gap(phi, v, eps, t):
    return eps * (mp.cos(phi) - mp.cos(phi + t)) + t * (v - t / 2)


def _gap_rate(phi, v, eps, t):
    return v - t + eps * mp.sin(phi + t)


def lower_bound_iterates(phi, v, eps, steps=ITERATE_STEPS, dps=ITERATE_DPS):
    """The paper's iterates t_0 = 0, t_{k+1} = t_k + s_k, s_k the larger root of
    d_k + d'_k s - (1 + |eps|) s^2/2 = 0 (the form without cancellation for the sign of d'_k),
    at ``dps`` digits; stops when the gap is no longer positive."""
    with mp.workdps(dps):
        phi, v, eps = mp.mpf(phi), mp.mpf(v), mp.mpf(eps)
        a = (1 + abs(eps)) / 2
        t, out = mp.mpf(0), [mp.mpf(0)]
        for _ in range(steps):
            d, r = _gap(phi, v, eps, t), _gap_rate(phi, v, eps, t)
            if d < 0 or (d == 0 and t > 0):
                break
            root = mp.sqrt(r * r + 4 * a * d)
            s = (r + root) / (2 * a) if r >= 0 else 2 * d / (root - r)
            if s <= 0:
                break
            t += s
            out.append(+t)
        return out


def convergence_order(phi, v, eps):
    """Median over the iterates of log(e_{k+1}/e_k) / log(e_k/e_{k-1}), e_k = tau - t_k the
    distance to the root (tau: the iterates' limit), over errors between 10^-60 and 10^-2:
    the order p of e_{k+1} ~ C e_k^p; NaN with fewer than three such errors."""
    t = lower_bound_iterates(phi, v, eps)
    with mp.workdps(ITERATE_DPS):
        tau = t[-1]
        e = [float(mp.log10(tau - x)) for x in t[:-1] if tau - x > 0]
    e = [x for x in e if -60 < x < -2]
    if len(e) < 3:
        return math.nan
    ratios = [(e[k + 1] - e[k]) / (e[k] - e[k - 1]) for k in range(1, len(e) - 1)
              if e[k] != e[k - 1]]
    return float(np.median(ratios)) if ratios else math.nan


def quadratic_claim(quick=False):
    n = SIZES[bool(quick)]["iterates"]
    holds = R.relative_band(QUADRATIC, R.SAME)
    fails = R.relative_band(QUADRATIC, R.SAME_FAILS)
    members = []
    for name, (phi, v) in samples(quick).items():
        pick = np.random.default_rng(SAMPLING_SEED).choice(len(phi), min(n, len(phi)),
                                                           replace=False)
        orders = np.array([convergence_order(float(phi[i]), float(v[i]), EPS) for i in pick])
        orders = orders[np.isfinite(orders)]
        if len(orders) < 10:
            members.append(F.too_few(name, "order of convergence"))
            continue
        rng = np.random.default_rng(SAMPLING_SEED)
        boot = [float(np.median(rng.choice(orders, len(orders))))
                for _ in range(INTERVAL_REPLICATES)]
        members.append(F.band_member(
            f"{name}: {len(orders)} flights, median order {np.median(orders):.3f} (5-95% "
            f"{np.percentile(orders, 5):.2f}-{np.percentile(orders, 95):.2f})",
            "order of convergence", float(np.median(orders)), float(np.percentile(boot, 2.5)),
            float(np.percentile(boot, 97.5)), holds, fails))
    return make_claim("sec2-quadratic", f"The lower-bound iterates at {ITERATE_DPS} digits, "
                      f"eps = 0.6: {F.family_text(members)}.", analyses=members)


def _overstep_count(cases):
    """(oversteps, cases judged) of fastpath's lower-bound method against verify."""
    from reports.precision.evaluate import overstepped, reference

    count = judged = 0
    for case in cases:
        ref = reference(case)
        if ref is None:
            continue
        res = fastpath.flight(case.phi, case.v, case.eps, method="lower_bound")
        if not math.isfinite(float(res.tau)):
            continue
        judged += 1
        with mp.workdps(60):
            count += bool(overstepped(case, ref, mpmath.mpf(float(res.tau))))
    return count, judged


def never_overstepped_claim(quick=False):
    from reports.precision.cases import Case, grazing_cases, hard_cases

    n = SIZES[bool(quick)]["overstep"]
    sets = {}
    for name, (phi, v) in samples(quick).items():
        pick = np.random.default_rng(SAMPLING_SEED).choice(len(phi), min(n, len(phi)),
                                                           replace=False)
        sets[name] = [Case(float(phi[i]), float(v[i]), EPS, name, "random") for i in pick]
    sets["close root pairs"] = grazing_cases(n // 4 if quick else 60)
    sets["hard cases"] = [c for c in hard_cases(quick) if c.v + c.eps * math.sin(c.phi) > 0]
    members = []
    for name, cases in sets.items():
        k, m = _overstep_count(cases)
        members.append(F.threshold_member(f"{name}: {k} of {m} flights past the first root",
                                          "flights overstepped", k, k, k, 0.5, True)
                       if m else F.too_few(name, "flights overstepped"))
    return make_claim("sec2-never-overstepped", "fastpath.flight(method='lower_bound') against "
                      "verify (a final time past a later root counts, the rounding of the last "
                      f"step does not): {F.family_text(members)}.", analyses=members)


def method_claims(quick=False):
    return [five_steps_claim(quick), quadratic_claim(quick), never_overstepped_claim(quick)]
