"""The dynamics study behind the paper's Section 2 and its Lyapunov remark, as plain data.

Parts (each a function returning a JSON-ready dict with its cost: wall seconds, orbits,
collisions):

- ``fixed_points``: the family (0, pi*m), certified, trace against 2 - 4*eps;
- ``period_two``: the orbits born at eps = 1, (s, pi*m - s) and (-s, pi*m + s) with
  eps*sin(s) = s (on the symmetry line phi + v = pi*m), followed in eps until their residue
  passes 1; certified at sample amplitudes;
- ``critical_amplitudes``: Greene's eps_c of noble curves per velocity band: the crossings of
  the critical residue R_c = 0.2500888 in float64 up to period 987, their Aitken extrapolation
  with its uncertainty (``fastpath.dynamics.greene.extrapolate``; the basis is written there),
  and for the rows of ``precise_rows`` the last levels (to period 1597) again in
  multiprecision (``verify.dynamics.residue``), where float64's rounding of the residue runs
  out; the Holmes map's value, and the high-velocity fit eps_c = a + b/v + c/v**2;
- ``certified_crossings``: the residue of one approximant per band certified on both sides of
  its crossing of R_c;
- ``crossing_simulation``: direct simulation across each band (from the hyperbolic point
  (pi, pi*j) to v = pi*(j + 1)) below and above the band's eps_c;
- ``lyapunov_study``: the largest exponent in both clocks at eps = 0.6 over the paper's start
  box, with the tangent map checked against ``verify.jacobian`` and the separation method;
- ``accelerator_study``: the exact map's period-1 accelerator mode certified, a search for
  accelerator blocks of the Holmes map by period, and velocity diffusion exponents.

Sizes: ``QUICK`` (seconds, for tests) and ``FULL`` (minutes; ``scripts/dynamics_study.py``
writes it to ``reports/paper/studies/dynamics_study.json``).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from pathlib import Path

import mpmath
import numpy as np
from mpmath.libmp import from_float, from_int, mpf_mul, mpf_sub
from scipy.optimize import brentq

import fastpath
import verify
from fastpath import dynamics as fd
from fastpath.dynamics.greene import (
    CRITICAL_RESIDUE,
    STANDARD_MAP_K_C,
    approximants,
    extrapolate,
    noble,
    tail_uncertainty,
)
from reports.paper.studies.sampling import ESCAPE_BOX
from reports.paper.studies.seeds import DYNAMICS_SEED
from verify.dynamics import residue as precise

K_C_QUARTER = STANDARD_MAP_K_C / 4.0  # the standard map's K_c in the bouncer's eps (K = 4 eps)
PAPER_EPS = 0.6
NOBLES = ((), (2,), (3,), (4,), (5,), (1, 2), (2, 2), (1, 3), (3, 2), (1, 4))
GOLDEN_PAIR = ((), (2,))
PRECISE_DPS = 40  # digits of the multiprecision crossings (their error is measured at +20)
HOLMES_SPEED = 1e4  # the standard map does not depend on v: started high, |v| never reaches 0
BAND_EDGES = (0.0, 4.0, 8.0, 16.0, 32.0, 64.0, 128.0, 256.0, 512.0, 1024.0, 4096.0)
DIFFUSION_STARTS = (10, 100, 1_000, 3_000, 10_000)  # first n of the diffusion fit windows
DIFFUSION_FAMILY_FROM = 1_000  # windows from here on: past the transient (the claim's family)


@dataclass(frozen=True)
class Sizes:
    """How much of each part to compute. ``certify_level`` and ``deep_level`` index the
    approximants of a band (periods 3, 5, 8, 13, 21, 34, 55, 89, 144, 233, ...: level 7 is
    period 89, level 9 period 233); ``search_eps`` is (first, last, step)."""

    fixed_m: tuple
    fixed_eps: tuple
    two_m: tuple
    two_points: int
    two_certify: tuple
    noble_bands: tuple
    golden_bands: tuple
    levels: int
    precise_rows: tuple
    precise_levels: int
    precise_last: int
    certify_bands: tuple
    certify_level: int
    certify_deep: tuple
    deep_level: int
    sim_bands: tuple
    sim_particles: int
    sim_collisions: int
    lyap_orbits: int
    lyap_collisions: int
    separation_orbits: int
    separation_collisions: int
    jacobian_states: int
    search_periods: tuple
    search_grid: int
    search_eps: tuple
    diffusion_eps: tuple
    diffusion_particles: int
    diffusion_collisions: int


# the committed FULL study, package data beside this module (docs/report/dynamics/study.json
# links to it); ``scripts/dynamics_study.py`` writes it, the report's dynamics section reads it
COMMITTED = Path(__file__).resolve().with_name("dynamics_study.json")

QUICK = Sizes(
    fixed_m=(1,), fixed_eps=(-0.2, 0.3, 0.99, 1.01), two_m=(1,), two_points=12,
    two_certify=(1.01,), noble_bands=(0, 1), golden_bands=(10, 30, 100), levels=8,
    precise_rows=((1, (2,), "exact"),), precise_levels=8, precise_last=2, certify_bands=(1,),
    certify_level=4, certify_deep=(), deep_level=4, sim_bands=(1,),
    sim_particles=4, sim_collisions=20_000, lyap_orbits=4, lyap_collisions=10_000,
    separation_orbits=2, separation_collisions=5_000, jacobian_states=3,
    search_periods=(1, 2), search_grid=12, search_eps=(1.0, 1.65, 0.05),
    diffusion_eps=(0.6, 1.6), diffusion_particles=32, diffusion_collisions=5_000)

FULL = Sizes(
    fixed_m=(1, 2, 3), fixed_eps=(-0.5, -0.1, 0.1, 0.3, 0.6, 0.9, 0.99, 1.01, 1.2, 2.0),
    two_m=(1, 2, 3, 10), two_points=60, two_certify=(1.001, 1.01, 1.05),
    noble_bands=(0, 1, 2, 5, 10), golden_bands=(10, 20, 30, 50, 100, 200), levels=13,
    precise_rows=((1, (), "holmes"), (1, (2,), "holmes"), (1, (), "exact"), (1, (2,), "exact"),
                  (10, (), "exact"), (10, (2,), "exact")),
    precise_levels=14, precise_last=3, certify_bands=(0, 1, 2, 5, 10), certify_level=7,
    certify_deep=(1, 10), deep_level=9,
    sim_bands=(1, 2, 5, 10), sim_particles=16, sim_collisions=1_000_000, lyap_orbits=64,
    lyap_collisions=1_000_000, separation_orbits=8, separation_collisions=100_000,
    jacobian_states=20, search_periods=(1, 2, 3, 4, 5, 6, 7, 8), search_grid=32,
    search_eps=(0.40, 1.60, 0.01), diffusion_eps=(0.6, 1.6), diffusion_particles=256,
    diffusion_collisions=100_000)


def _enclosure(e):
    """An Enclosure as JSON: float ends rounded outward by one ulp, and 20-digit strings."""
    return {"lo": math.nextafter(float(e.lo), -math.inf), "hi": math.nextafter(float(e.hi),
                                                                               math.inf),
            "lo_str": mpmath.nstr(e.lo, 20), "hi_str": mpmath.nstr(e.hi, 20)}


def _certified(o, seconds):
    return {"residue": _enclosure(o.residue), "trace": _enclosure(o.trace),
            "determinant": _enclosure(o.determinant), "stability": o.stability,
            "point": [_enclosure(o.points[0][0]), _enclosure(o.points[0][1])],
            "winding": o.winding, "dps": o.dps_used, "radius": o.radius,
            "seconds": seconds}


def _certify(phi, v, eps, period, **kw):
    start = time.perf_counter()
    orbit = verify.periodic_orbit(phi, v, eps, period, **kw)
    return orbit, time.perf_counter() - start


# --- fixed points ------------------------------------------------------------------------------

def exact_fixed_point_trace(eps):
    """2 - 4*eps exactly (mpf arithmetic at precision 0 is exact; no global precision used)."""
    raw = mpf_sub(from_int(2), mpf_mul(from_int(4), from_float(float(eps)), 0), 0)
    return mpmath.mp.make_mpf(raw)


def fixed_points(sizes: Sizes) -> dict:
    """The fixed points (0, pi*m), certified: trace enclosure, stability, 2 - 4*eps inside."""
    start = time.perf_counter()
    rows = []
    for m in sizes.fixed_m:
        for eps in sizes.fixed_eps:
            orbit, seconds = _certify(0.0, math.pi * m, eps, 1)
            row = _certified(orbit, seconds)
            row.update(m=m, eps=eps, expected_trace=2 - 4 * eps,
                       trace_contains=bool(exact_fixed_point_trace(eps) in orbit.trace),
                       expected=("elliptic" if 0 < eps < 1 else "hyperbolic"))
            rows.append(row)
    return {"rows": rows, "seconds": time.perf_counter() - start, "orbits": len(rows)}


# --- period two --------------------------------------------------------------------------------

def period_two_start(eps):
    """s > 0 with eps*sin(s) = s (eps > 1): the period-2 orbit is (s, pi*m - s), (-s, pi*m + s)."""
    return brentq(lambda s: eps * math.sin(s) - s, 1e-12, math.pi)


def _two_orbit(eps, m, model):
    """The float period-2 orbit (s, pi*m - s) or None where Newton lands on another orbit (the
    symmetric flight is not the first collision there)."""
    s = period_two_start(eps)
    try:
        orbit = fd.periodic_orbit(s, math.pi * m - s, eps, 2, winding=2 * m, model=model)
    except (fd.OrbitNotFound, fastpath.UncertainCollision):
        return None
    if abs(orbit.v[0] - (math.pi * m - s)) > 1e-9 * math.pi * m:
        return None
    return orbit


def _two_residue(eps, m, model):
    orbit = _two_orbit(eps, m, model)
    return math.nan if orbit is None else orbit.residue


def _stability_changes(eps, residue, m, model):
    """The amplitudes where the residue crosses 0 or 1 between grid points, by bisection to
    1e-12 (a bracket whose orbit is lost inside is reported with ``exact: False``)."""
    changes = []
    for level in (0.0, 1.0):
        d = np.asarray(residue) - level
        for i in np.nonzero(np.isfinite(d[:-1]) & np.isfinite(d[1:])
                            & (np.sign(d[:-1]) != np.sign(d[1:])))[0]:
            a, b, da = eps[i], eps[i + 1], d[i]
            found = True
            while b - a > 1e-12:
                mid = 0.5 * (a + b)
                dm = _two_residue(mid, m, model) - level
                if not math.isfinite(dm):
                    found = False
                    break
                if np.sign(dm) == np.sign(da):
                    a, da = mid, dm
                else:
                    b = mid
            changes.append({"eps": 0.5 * (a + b), "bracket": [a, b], "exact": found,
                            "level": level, "direction": "up" if d[i + 1] > d[i] else "down"})
    return sorted(changes, key=lambda c: c["eps"])


def period_two(sizes: Sizes) -> dict:
    """Residue of the period-2 orbits against eps, where they change stability (R = 0 or 1),
    and certified samples on both sides of their first loss of stability."""
    start = time.perf_counter()
    branches = []
    near = sizes.two_points // 3  # resolve the birth at eps = 1, then the branch evenly
    grid = np.concatenate([1.0 + np.geomspace(1e-4, 0.04, near),
                           np.linspace(1.05, 1.8, sizes.two_points - near)])
    for m, model in [(m, "exact") for m in sizes.two_m] + [(sizes.two_m[-1], "holmes")]:
        curve = [_two_residue(e, m, model) for e in grid]
        changes = _stability_changes(grid, curve, m, model)
        loss = changes[0]["eps"] if changes else None
        branch = {"m": m, "model": model, "changes": changes, "loss_of_stability": loss,
                  "exists_up_to": float(grid[np.isfinite(curve)][-1]),
                  "eps": grid.tolist(), "residue": curve, "certified": []}
        if model == "exact":
            sample = sizes.two_certify + ((loss - 1e-3, loss + 1e-3) if loss else ())
            for eps in sample:
                s = period_two_start(eps)
                orbit, seconds = _certify(s, math.pi * m - s, eps, 2)
                row = _certified(orbit, seconds)
                row.update(eps=eps, float_residue=_two_residue(eps, m, "exact"))
                branch["certified"].append(row)
        branches.append(branch)
    fixed = {"eps": np.linspace(-0.3, 1.5, 19).tolist()}
    fixed["residue"] = fixed["eps"]  # R = (2 - (2 - 4 eps))/4 = eps, certified in fixed_points
    return {"branches": branches, "fixed_point_residue": fixed,
            "seconds": time.perf_counter() - start,
            "orbits": sum(len(b["certified"]) for b in branches)}


# --- Greene's eps_c per band -------------------------------------------------------------------

def _amplitude(band, prefix, levels, model="exact"):
    """One curve's crossings of R_c in float64, the last crossing with its geometric tail, and
    the Aitken extrapolation (eps_c) with its uncertainty."""
    c = fd.critical_amplitude(band, prefix, model=model, levels=levels)
    last = c.crossings[-1]
    eps = [x.eps for x in c.crossings]
    errors = [x.eps_error for x in c.crossings]
    value, uncertainty = extrapolate(eps, errors)
    return {"band": band, "prefix": list(prefix), "omega": band + noble(prefix),
            "v": math.pi * (band + noble(prefix)), "model": model, "target": c.target,
            "eps_c": value, "uncertainty": uncertainty,
            "last_crossing": c.eps_c, "tail_uncertainty": c.uncertainty,
            "ratio": c.ratio, "tail_ratio": c.tail_ratio,
            "periods": [x.approximant.period for x in c.crossings],
            "windings": [x.approximant.winding for x in c.crossings],
            "crossings": eps, "eps_errors": errors, "v_start": [x.v for x in c.crossings],
            "brackets": [list(x.bracket) for x in c.crossings],
            "last_residue_error": last.residue_error, "last_eps_error": last.eps_error,
            "orbits": sum(x.orbits for x in c.crossings), "precise": None}


def _precise(band, prefix, model, sizes):
    """The curve's crossings to ``precise_levels``, the last ``precise_last`` of them again in
    multiprecision (``verify.dynamics.residue.crossing`` from the float64 bracket widened by
    four times its stated error); eps_c = the Aitken extrapolation of the mixed sequence.
    Records the float64 - multiprecision differences where both exist (float64's measured
    error)."""
    start = time.perf_counter()
    row = _amplitude(band, prefix, sizes.precise_levels, model)
    eps, errors = list(row["crossings"]), list(row["eps_errors"])
    done = []
    for level in range(len(eps) - sizes.precise_last, len(eps)):
        a = approximants(band, prefix, level + 1)[-1]
        lo, hi = row["brackets"][level]
        margin = 4 * errors[level] + 1e-12
        found = precise.crossing(a.period, a.winding, (lo - margin, hi + margin),
                                 (row["v_start"][level],) * 2, target=row["target"],
                                 model=model, dps=PRECISE_DPS)
        mp_eps = float(found.eps)
        done.append({"period": a.period, "float": eps[level], "multiprecision": mp_eps,
                     "difference": eps[level] - mp_eps, "float_error": errors[level],
                     "eps_error": float(found.eps_error),
                     "residue_error": float(found.residue_error), "orbits": found.orbits})
        eps[level], errors[level] = mp_eps, float(found.eps_error)
        slope = float(found.slope)
    row.update(float_crossings=row["crossings"], crossings=eps, eps_errors=errors,
               precise={"levels": done, "seconds": time.perf_counter() - start,
                        "last_slope": slope})
    return _with_estimates(row)


def _with_estimates(row):
    """A precise row's estimates from its (mixed) crossings: the extrapolation, the last
    crossing with its geometric tail, the ratios."""
    eps, errors = row["crossings"], row["eps_errors"]
    value, uncertainty = extrapolate(eps, errors)
    tail, ratio, tail_ratio, _ = tail_uncertainty(eps, errors[-1], row["precise"]["last_slope"],
                                                  row["target"])
    d = np.diff(eps)
    row.update(eps_c=value, uncertainty=uncertainty, last_crossing=eps[-1],
               tail_uncertainty=tail, ratio=ratio, tail_ratio=tail_ratio)
    row["precise"]["ratios"] = (d[1:] / d[:-1]).tolist()
    return row


def _fit_limit(rows):
    """Weighted least squares eps_c = a + b/v + c/v**2; a with its standard error."""
    v = np.array([r["v"] for r in rows])
    y = np.array([r["eps_c"] for r in rows])
    w = 1.0 / np.array([r["uncertainty"] for r in rows])
    design = np.vstack([np.ones_like(v), 1 / v, 1 / v**2]).T
    coef, *_ = np.linalg.lstsq(design * w[:, None], y * w, rcond=None)
    resid = (y - design @ coef) * w
    dof = max(1, len(y) - 3)
    scale = max(1.0, float(resid @ resid) / dof)
    cov = np.linalg.inv((design * w[:, None]).T @ (design * w[:, None])) * scale
    return {"a": float(coef[0]), "b": float(coef[1]), "c": float(coef[2]),
            "a_error": float(math.sqrt(cov[0, 0])), "chi2_dof": float(resid @ resid) / dof}


def critical_amplitudes(sizes: Sizes) -> dict:
    """eps_c by Greene's criterion: every noble of NOBLES in the low bands, the golden pair in
    the high bands, the Holmes map for reference, and the high-velocity limit."""
    start = time.perf_counter()
    precise_rows = {(b, tuple(p), m): _precise(b, p, m, sizes) for b, p, m in sizes.precise_rows}

    def row(b, p, model="exact"):
        return precise_rows.get((b, tuple(p), model)) or _amplitude(b, p, sizes.levels, model)

    rows = [row(b, p) for b in sizes.noble_bands for p in NOBLES]
    rows += [row(b, p) for b in sizes.golden_bands for p in GOLDEN_PAIR
             if b not in sizes.noble_bands]
    holmes = [row(1, p, "holmes") for p in GOLDEN_PAIR]
    bands = {}
    for r in rows:
        best = bands.get(r["band"])
        if best is None or r["eps_c"] > best["eps_c"]:
            bands[r["band"]] = r
    limits = {}
    for prefix in GOLDEN_PAIR:
        high = [r for r in rows if r["prefix"] == list(prefix)
                and r["band"] in sizes.golden_bands]
        if len(high) >= 3:
            limits["golden" if not prefix else "golden2"] = _fit_limit(high)
    float_errors = [lv for r in precise_rows.values() for lv in r["precise"]["levels"]]
    return {"rows": rows, "holmes": holmes, "target": CRITICAL_RESIDUE,
            "float_vs_multiprecision": {
                "largest_difference": max((abs(lv["difference"]) for lv in float_errors),
                                          default=None),
                "levels": len(float_errors)},
            "band_max": [{"band": b, "eps_c": r["eps_c"], "uncertainty": r["uncertainty"],
                          "omega": r["omega"], "prefix": r["prefix"]}
                         for b, r in sorted(bands.items())],
            "limits": limits, "k_c_quarter": K_C_QUARTER,
            "seconds": time.perf_counter() - start,
            "orbits": sum(r["orbits"] for r in rows + holmes)}


def certified_crossings(sizes: Sizes, critical: dict) -> list:
    """The residue of the approximant at ``certify_level`` (and at ``deep_level`` for the last
    curve, prefix (2,), of the bands in ``certify_deep``) certified just below and just above
    its float crossing of the target residue R_c."""
    out = []
    for r in critical["rows"]:
        if r["band"] not in sizes.certify_bands or r["prefix"] not in ([], [2]):
            continue
        deep = r["band"] in sizes.certify_deep and r["prefix"] == [2]  # the band's last curve
        levels = [sizes.certify_level] + ([sizes.deep_level] if deep else [])
        for level in levels:
            if level >= len(r["periods"]):
                continue
            q, m = r["periods"][level], r["windings"][level]
            lo, hi = r["brackets"][level]
            for side, eps in (("below", lo - 1e-7), ("above", hi + 1e-7)):
                guess = fd.symmetric_orbit(r["v_start"][level], eps, q, m)
                orbit, seconds = _certify(float(guess.phi[0]), float(guess.v[0]), eps, q,
                                          winding=m)
                row = _certified(orbit, seconds)
                row.update(band=r["band"], prefix=r["prefix"], period=q, eps=eps, side=side,
                           float_residue=guess.residue,
                           target=r["target"],
                           decided=(orbit.residue.hi < r["target"] if side == "below"
                                    else orbit.residue.lo > r["target"]))
                out.append(row)
    return out


def crossing_simulation(sizes: Sizes, critical: dict) -> list:
    """Orbits from near the hyperbolic point (pi, pi*j): do they reach v >= pi*(j + 1) within
    ``sim_collisions``, at 0.95 and 1.10 times the band's largest eps_c?"""
    rng = np.random.default_rng(DYNAMICS_SEED)
    best = {b["band"]: b for b in critical["band_max"]}
    out = []
    for band in sizes.sim_bands:
        if band not in best:
            continue
        for factor in (0.95, 1.10):
            eps = best[band]["eps_c"] * factor
            phi = math.pi + rng.uniform(-0.05, 0.05, sizes.sim_particles)
            v = math.pi * band + rng.uniform(0.02, 0.08, sizes.sim_particles)
            start = time.perf_counter()
            passage, status = fd.first_passage(phi, v, eps, math.pi * (band + 1),
                                               sizes.sim_collisions)
            crossed = passage[passage > 0]
            out.append({"band": band, "factor": factor, "eps": eps,
                        "particles": sizes.sim_particles, "collisions": sizes.sim_collisions,
                        "crossed": int(len(crossed)),
                        "median_passage": float(np.median(crossed)) if len(crossed) else None,
                        "stopped": int((status != 0).sum()),
                        "seconds": time.perf_counter() - start})
    return out


# --- Lyapunov exponents ------------------------------------------------------------------------

def _paper_starts(count, rng):
    (p0, p1), (v0, v1) = ESCAPE_BOX
    return rng.uniform(p0, p1, count), rng.uniform(v0, v1, count)


def _bootstrap_slope(x, y, window, rng, draws=400):
    """Slope of mean(y) against mean(x) over the columns in ``window`` with its bootstrap
    standard error over rows (orbits)."""
    def slope(rows):
        return float(np.polyfit(x[rows][:, window].mean(0), y[rows][:, window].mean(0), 1)[0])
    n = len(x)
    best = slope(np.arange(n))
    draws_ = [slope(rng.integers(0, n, n)) for _ in range(draws)]
    return best, float(np.std(draws_, ddof=1))


def lyapunov_study(sizes: Sizes) -> dict:
    """lambda per collision and per unit time at eps = 0.6, with cross-checks."""
    rng = np.random.default_rng(DYNAMICS_SEED)
    phi, v = _paper_starts(sizes.lyap_orbits, rng)
    start = time.perf_counter()
    lyap = fd.lyapunov(phi, v, PAPER_EPS, sizes.lyap_collisions, checkpoints=48)
    seconds = time.perf_counter() - start
    ok = lyap.status == 0
    per_n, per_t = lyap.running_per_collision[ok], lyap.running_per_time[ok]
    times = lyap.time[ok]
    n = lyap.collisions
    mean_n = per_n.mean(0)
    se_n = per_n.std(0, ddof=1) / math.sqrt(len(per_n))
    late = (n >= n[-1] / 100) & np.all(per_t > 0, axis=0)
    decades = np.log10(n[-1] / n[late][0]) if late.any() else 0.0
    fits = {}
    with np.errstate(invalid="ignore", divide="ignore"):  # early lambda_t may be <= 0
        log_t, log_per_t = np.log(times), np.log(per_t)
    for name, sel in (("late", late), ("last_decade", late & (n >= n[-1] / 10))):
        if sel.sum() >= 3:
            fits[name] = _bootstrap_slope(log_t, log_per_t, sel, rng)
    alpha, alpha_se = fits.get("late", (math.nan, math.nan))
    systematic = abs(fits["late"][0] - fits["last_decade"][0]) if len(fits) == 2 else math.nan
    # cross-check 1: the tangent map against verify.jacobian at states along one orbit
    orbit = fastpath.orbit(float(phi[0]), float(v[0]), PAPER_EPS, sizes.jacobian_states * 37)
    worst = 0.0
    for k in range(0, sizes.jacobian_states * 37, 37):
        ours = fd.step_jacobian(orbit.phi[k], orbit.v[k], PAPER_EPS)
        ref = verify.jacobian(float(orbit.phi[k]), float(orbit.v[k]), PAPER_EPS, dps=30)
        ref = np.array([[float(ref[i, j]) for j in range(2)] for i in range(2)])
        worst = max(worst, float(np.max(np.abs(ours - ref)) / np.max(np.abs(ref))))
    # cross-check 2: the separation of nearby orbits (no Jacobian)
    sep = []
    for i in range(sizes.separation_orbits):
        a = fd.separation(float(phi[i]), float(v[i]), PAPER_EPS, sizes.separation_collisions)
        b = fd.lyapunov(float(phi[i]), float(v[i]), PAPER_EPS,
                        sizes.separation_collisions).per_collision
        sep.append((a, b))
    sep = np.array(sep)
    diff = sep[:, 0] - sep[:, 1]
    # where the orbits are when lambda is read, and lambda by velocity band (the low-velocity
    # part of the chaotic component included), and the standard map's value (Holmes model,
    # from the same phases at v + HOLMES_SPEED: at low v its absolute value would act)
    speeds = lyap.velocity[ok]
    bands = fd.lyapunov_by_band(phi, v, PAPER_EPS, sizes.lyap_collisions, BAND_EDGES)
    holmes = fd.lyapunov(phi, v + HOLMES_SPEED, PAPER_EPS, sizes.lyap_collisions,
                         model="holmes", checkpoints=8)
    holmes_ok = holmes.status == 0
    return {
        "eps": PAPER_EPS, "orbits": int(ok.sum()), "stopped": int((~ok).sum()),
        "collisions_per_orbit": sizes.lyap_collisions, "checkpoints": n.tolist(),
        "mean_per_collision": mean_n.tolist(), "se_per_collision": se_n.tolist(),
        "mean_per_time": per_t.mean(0).tolist(),
        "se_per_time": (per_t.std(0, ddof=1) / math.sqrt(len(per_t))).tolist(),
        "mean_time": times.mean(0).tolist(),
        "mean_log_time": np.log(times).mean(0).tolist(),
        "mean_log_per_time": np.where(np.all(per_t > 0, axis=0),
                                      np.log(np.abs(per_t)).mean(0), np.nan).tolist(),
        "final_per_collision": per_n[:, -1].tolist(),
        "first_orbits_early": per_n[: min(4, len(per_n)), : _early_index(n)].tolist(),
        "alpha": alpha, "alpha_se": alpha_se, "alpha_systematic": systematic,
        "fit_decades": float(decades), "fits": {k: list(f) for k, f in fits.items()},
        "jacobian_worst_relative": worst, "jacobian_states": sizes.jacobian_states,
        "separation": sep.tolist(),
        "separation_mean_difference": float(diff.mean()),
        "separation_se_difference": float(diff.std(ddof=1) / math.sqrt(len(diff)))
        if len(diff) > 1 else math.nan,
        "separation_collisions": sizes.separation_collisions,
        "seconds": seconds, "total_collisions": int(sizes.lyap_orbits * sizes.lyap_collisions),
        "seed": DYNAMICS_SEED,
        "median_velocity": np.median(np.abs(speeds), axis=0).tolist(),
        "final_velocity_quartiles": np.percentile(np.abs(speeds[:, -1]), [25, 50, 75]).tolist(),
        "bands": {"edges": list(BAND_EDGES), "per_collision": bands.per_collision.tolist(),
                  "standard_error": bands.standard_error.tolist(),
                  "collisions": bands.collisions.tolist(), "orbits": bands.orbits.tolist()},
        "holmes_per_collision": float(np.mean(holmes.per_collision[holmes_ok])),
        "holmes_se": float(np.std(holmes.per_collision[holmes_ok], ddof=1)
                           / math.sqrt(holmes_ok.sum())) if holmes_ok.sum() > 1 else math.nan,
        "holmes_orbits": int(holmes_ok.sum()),
    }


EARLY = 30  # collisions up to which two runs of a chaotic orbit agree to ~1e-9


def _early_index(n):
    return int(np.searchsorted(n, EARLY, side="right"))


# --- accelerator modes and diffusion -----------------------------------------------------------

def accelerator_study(sizes: Sizes) -> dict:
    """The exact period-1 accelerator mode certified; the lowest eps of accelerator blocks
    found per period (Holmes map); velocity diffusion exponents."""
    start = time.perf_counter()
    certified = []
    for eps, m in ((1.6, 4), (1.6, 1), (1.7, 10)):
        phi = -math.asin(math.pi / (2 * eps))  # -2 eps sin(phi) = pi: l = 1, cos(phi) > 0
        orbit, seconds = _certify(phi, math.pi * m, eps, 1, velocity_shift=1)
        row = _certified(orbit, seconds)
        row.update(eps=eps, m=m, expected_determinant=(2 * m - 1) / (2 * m + 1))
        certified.append(row)
    lo, hi, step = sizes.search_eps
    grid = np.round(np.arange(lo, hi + step / 2, step), 10)
    search = []
    for p in sizes.search_periods:
        first_any = first_elliptic = None
        for eps in grid:
            found = fd.accelerator_search(float(eps), p, grid=sizes.search_grid)
            if found and first_any is None:
                first_any = {"eps": float(eps), "residues": [o.residue for o in found],
                             "shifts": [o.velocity_shift for o in found]}
            elliptic = [o for o in found if o.stability == "elliptic"]
            if elliptic:
                first_elliptic = {"eps": float(eps), "residue": elliptic[0].residue,
                                  "shift": elliptic[0].velocity_shift,
                                  "phi": float(elliptic[0].phi[0]),
                                  "v": float(elliptic[0].v[0])}
                break
        search.append({"period": p, "first": first_any, "first_elliptic": first_elliptic})
    search_seconds = time.perf_counter() - start
    diffusion = [_diffusion(eps, sizes) for eps in sizes.diffusion_eps]
    return {"certified": certified, "search": search, "search_grid": sizes.search_grid,
            "search_eps": list(sizes.search_eps), "search_seconds": search_seconds,
            "diffusion": diffusion, "half_pi": math.pi / 2}


def _diffusion(eps, sizes):
    rng = np.random.default_rng(DYNAMICS_SEED)
    phi, v = _paper_starts(sizes.diffusion_particles, rng)
    n = np.unique(np.round(np.geomspace(1, sizes.diffusion_collisions, 40)).astype(np.int64))
    start = time.perf_counter()
    vel, status = fd.velocities(phi, v, eps, n)
    seconds = time.perf_counter() - start
    ok = status == 0
    sq = (vel[ok] - v[ok, None]) ** 2
    msd = sq.mean(0)
    fits = {}
    for start in DIFFUSION_STARTS:  # windows [start, n_max]; the family: start >= 10^3
        sel = n >= min(start, n[-1] / 10)
        best = float(np.polyfit(np.log(n[sel]), np.log(msd[sel]), 1)[0])
        draws = []
        for _ in range(400):
            rows = rng.integers(0, len(sq), len(sq))
            draws.append(np.polyfit(np.log(n[sel]), np.log(sq[rows][:, sel].mean(0)), 1)[0])
        fits[str(start)] = (best, float(np.std(draws, ddof=1)))
    family = [fits[str(s)][0] for s in DIFFUSION_STARTS if s >= DIFFUSION_FAMILY_FROM]
    first = fits[str(DIFFUSION_FAMILY_FROM)]
    return {"eps": eps, "particles": int(ok.sum()), "stopped": int((~ok).sum()),
            "collisions": int(n[-1]), "n": n.tolist(), "msd": msd.tolist(),
            "mu": first[0], "mu_se": first[1],
            "mu_systematic": float(max(family) - min(family)), "fits": fits,
            "family_from": DIFFUSION_FAMILY_FROM,
            "family_starts": [s for s in DIFFUSION_STARTS if s >= DIFFUSION_FAMILY_FROM],
            "seconds": seconds}


def run(sizes: Sizes, echo=print) -> dict:
    """All parts, in order, with progress lines through ``echo``."""
    started = time.perf_counter()
    out = {"sizes": {k: list(x) if isinstance(x, tuple) else x
                     for k, x in sizes.__dict__.items()}}
    steps = [("fixed_points", lambda: fixed_points(sizes)),
             ("period_two", lambda: period_two(sizes)),
             ("critical", lambda: critical_amplitudes(sizes)),
             ("certified_crossings", lambda: certified_crossings(sizes, out["critical"])),
             ("crossing_simulation", lambda: crossing_simulation(sizes, out["critical"])),
             ("lyapunov", lambda: lyapunov_study(sizes)),
             ("accelerator", lambda: accelerator_study(sizes))]
    for name, part in steps:
        t0 = time.perf_counter()
        out[name] = part()
        echo(f"dynamics: {name} done in {time.perf_counter() - t0:.1f} s")
    out["seconds"] = time.perf_counter() - started
    return out
