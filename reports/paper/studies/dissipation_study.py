"""Dissipation suppresses Fermi acceleration: <v_n> saturates, V_sat against (1 - r).

The study (``STUDY``): eps = 2 (at eps = 0.6 particles with r < 1 fall onto the v = pi attractor
or stick, so there is no plateau to measure), starts uniform in the paper's escape box
3.85 < phi < 4.15, 2 < v < 4, no holes; the same starts for every physics:

* restitution r < 1 (docs/model.md: v1 - u = -r*(v_in - u)) for several 1 - r;
* linear drag eta = k*v and quadratic drag eta = k*v*|v| with elastic impacts;
* the elastic, drag-free model as the reference that keeps growing (Fermi acceleration);
* the stuck fraction at eps = 0.6 (|eps| <= 1: a particle whose impacts accumulate never
  leaves the plate) for a few r, from ``Moments.stuck_n``.

<v_n> over the particles that reached collision n comes from ``fastpath.kernels.moments`` (64 blocks
of consecutive particles). The built-in scene ``dissipation-saturation`` (kind "velocity",
``reports.runs.velocity``) runs r = 1 and three of these r through the trusted run engine
(verification sample, ``bouncer verify``), with the same convention: stuck particles are
counted apart, not in the means. The plateau V_sat is the mean of <v_n> over the grid points (log
spaced) in the last decade of n, [n_max/10, n_max], and the saturation test is the slope of
log<v_n> against log n over that window. The exponent beta of V_sat ~ (1 - r)^beta is the
least-squares slope of log V_sat against log(1 - r).

Published values: E. D. Leonel and co-workers study exactly this (A. L. P. Livorati,
D. G. Ladeira, E. D. Leonel, Phys. Rev. E 78, 056205 (2008), inelastic impacts; F. A. de Souza,
L. E. A. Simoes, M. R. da Silva, E. D. Leonel, Math. Probl. Eng. 2009, 409857 (2009), linear
drag; A. M. Cespedes, UNESP dissertation (2015), V_rms exponents "from the analytical
expression of the mean square velocity"). From this workplace we could read only their
abstracts, none with a number; the second says "the average velocity starts growing at
first and then bends towards a regime of constant value, thus confirming that the introduction
of drag force is a sufficient condition to suppress Fermi acceleration". We found no published
value of beta, so beta is compared with our own random-phase estimate, not with a citation:
with v_in ~ -v at large v, an impact gives v1 = r*v + (1 + r)*u with u = -eps*sin(phase);
uncorrelated phases (<u> = 0, <u^2> = eps^2/2) make the stationary second moment
<v^2> = r^2 <v^2> + (1 + r)^2 eps^2/2, i.e. <v^2> = (1 + r)*eps^2/(2*(1 - r)), and a fixed
shape of the velocity distribution gives V_sat ~ (1 - r)^(-1/2).

The committed study. The full study takes about 3 minutes on 2 cores (1000 orbits of 10^4
collisions at eps = 2 per physics, mostly the paper's lower-bound steps); it is committed as
package data (``COMMITTED``, written by ``scripts/dissipation_study.py``). A report reads it and
re-checks it (``recheck``): one curve of each kind of physics (``RECHECKED``), the verify spot
check and the velocity strip are recomputed and must equal the committed numbers bit for bit;
if anything differs the whole study is computed instead, and the report says so
(``Dissipation.source``). The re-check's moments run in a background thread beside the
report's other work (``start_dissipation_study``). ``--quick`` sizes are always computed.

The velocity strip (``velocity_strip``; claim ``dissipation-velocity-strip``). The one
published scaling statement with numbers we could read: J. J. Barroso, M. V. Carneiro,
E. E. N. Macau, Phys. Rev. E 79, 026206 (2009), abstract: chaotic orbits of the inelastic
bouncer are "bounded by a velocity strip v = +-Gamma/(1 - r)" (Gamma the nondimensional shaking
acceleration; the symbols are garbled in the stored copy and restored here). In our units the
strip follows from the model alone. In flight the energy v**2/2 + y is constant and the plate
height |y| <= |eps|, so the landing speed obeys v_in**2 <= v**2 + 4|eps|; an impact gives
v1 = (1 + r)*u - r*v_in with |u| <= |eps| and v_in < u (an approach): for v_in <= 0,
v1 <= (1 + r)|eps| + r*sqrt(v**2 + 4|eps|), for 0 < v_in < u, v1 < (1 + r)|eps|; and
v1 > u >= -|eps|. So |v| <= V implies |v1| <= g(V) = (1 + r)|eps| + r*sqrt(V**2 + 4|eps|) for
V >= |eps|, and g is increasing with slope < r < 1: its fixed point

    V*(r) = (|eps| + r*sqrt(eps**2 + 4|eps|*(1 - r)/(1 + r)))/(1 - r)  ~  2|eps|/(1 - r)

bounds every later velocity of an orbit that starts with |v| <= V* (a particle riding the
plate has |v| = |u| <= |eps|). The strip's width scales as (1 - r)^-1, Barroso et al.'s law; it
is a bound, not the plateau (V_sat grows only as (1 - r)^beta, beta = -0.6 here). The check is
that no velocity of the study's orbits leaves it, and by how much the orbits stay inside.
"""

from __future__ import annotations

import dataclasses
import json
import math
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

import fastpath
from fastpath import moments
from reports.paper.studies.background import at_once, begin
from reports.paper.studies.sampling import (
    ESCAPE_BOX,
    bootstrap_blocks,
    slope_fit,
    uniform_box,
    verify_sample,
)
from reports.paper.studies.seeds import SAMPLING_SEED
from reports.stats.analysis import SHIFT_DECADES

BLOCKS = 64
RANDOM_PHASE_BETA = -0.5  # our estimate (module docstring), not a published value

STUDY = {
    "eps": 2.0,
    "one_minus_r": (0.005, 0.01, 0.02, 0.05, 0.1),
    "drag": {"linear": (0.001, 0.003, 0.01), "quadratic": (0.0003, 0.001)},
    "sticking_eps": 0.6,
    "sticking_r": (0.5, 0.8, 0.9, 0.95),
    False: {"particles": 1000, "n_max": 10_000, "verify": 60},
    True: {"particles": 128, "n_max": 3000, "verify": 12},
}


@dataclass
class Curve:
    """<v_n> of one physics: the block sums (for the bootstrap) and the plateau numbers."""

    label: str
    physics: dict
    mean_v: np.ndarray
    sum_v: np.ndarray  # (blocks, len(n))
    count: np.ndarray  # (blocks, len(n))
    stuck: int  # particles stuck for good by n_max
    reached: int  # particles that reached n_max
    collisions: int
    flagged: int
    plateau: float
    slope: float
    slope_err: float
    slope_sys: float


STRIP_ORBITS = {False: 64, True: 8}  # orbits per r (n_max collisions each) for the strip


def velocity_strip(r, eps):
    """V*(r): the fixed point of g(V) = (1 + r)|eps| + r*sqrt(V**2 + 4|eps|), the edge of the
    velocity strip |v| <= V* that no orbit with restitution r < 1 leaves (module docstring)."""
    e = abs(eps)
    return (e + r * math.sqrt(e * e + 4.0 * e * (1.0 - r) / (1.0 + r))) / (1.0 - r)


def strip_maxima(phi0, v0, eps, one_minus_r, n_max):
    """Per 1 - r, max |v_n| over ``fastpath.orbit`` of each start (n_max collisions), over the
    first and over the second half of the starts (two independent samples)."""
    out = []
    for x in one_minus_r:
        tops = []
        for p, v in zip(phi0, v0, strict=True):
            orb = fastpath.orbit(float(p), float(v), eps, n_max, on_uncertain="stop",
                                 restitution=1.0 - float(x))
            tops.append(float(np.max(np.abs(orb.v))))
        half = max(1, len(tops) // 2)
        out.append((max(tops[:half]), max(tops[half:], default=max(tops[:half]))))
    return out


@dataclass
class Dissipation:
    """The study's curves, the exponent of V_sat in (1 - r) and the stuck fractions."""

    eps: float
    particles: int
    n: np.ndarray
    window: tuple
    elastic: Curve
    restitution: list  # Curve per 1 - r, in STUDY order
    drag: list  # Curve per (law, k)
    one_minus_r: np.ndarray
    beta: float
    beta_err: float
    beta_sys: float
    amp: float
    sticking: list  # (r, stuck fraction, particles) at STUDY["sticking_eps"]
    verification: dict
    seconds: float
    strip_max: list = None  # max |v_n| over STRIP_ORBITS orbits, per 1 - r (velocity strip)
    strip_orbits: int = 0
    strip_halves: list = None  # the same over each half of the orbits, per 1 - r
    source: str = ""  # where the numbers come from (``start_dissipation_study``)


def plateau(n, mean_v, lo, hi):
    """Mean of <v_n> over the grid points lo <= n <= hi (NaN if fewer than 3 are finite)."""
    use = (n >= lo) & (n <= hi) & np.isfinite(mean_v)
    return float(np.mean(mean_v[use])) if use.sum() >= 3 else math.nan


def log_slope(x, y, lo=-math.inf, hi=math.inf):
    """Least-squares slope of log y against log x over lo <= x <= hi (NaN if < 3 points)."""
    use = (x >= lo) & (x <= hi) & np.isfinite(y) & (y > 0)
    if use.sum() < 3:
        return math.nan
    return slope_fit(np.log(x[use]), np.log(y[use]))[0]


def _window_starts(window):
    f = 10 ** SHIFT_DECADES
    return [window[0] / f, window[0], window[0] * f]


def _curve(label, physics, phi0, v0, eps, n, window):
    mom = moments(phi0, v0, eps, n, blocks=BLOCKS, **physics)
    mean_v = mom.mean_v_n
    slope = log_slope(n, mean_v, *window)
    err = bootstrap_blocks(mom.sum_v_n, mom.count_n, lambda c: log_slope(n, c, *window))
    slopes = [log_slope(n, mean_v, lo, window[1]) for lo in _window_starts(window)]
    slopes = [s for s in slopes if math.isfinite(s)]
    sys = 0.5 * (max(slopes) - min(slopes)) if slopes else math.nan
    return Curve(label, physics, mean_v, mom.sum_v_n, mom.count_n,
                 int(mom.stuck_n.sum(axis=0)[-1]), int(mom.particles_n[-1]), mom.collisions,
                 mom.flagged, plateau(n, mean_v, *window), slope, err, sys)


def exponent(x, plateaus):
    """beta and log amplitude of plateaus ~ amp * x**beta (least squares in log-log)."""
    x, y = np.asarray(x, float), np.asarray(plateaus, float)
    use = np.isfinite(y) & (y > 0)
    if use.sum() < 3:
        return math.nan, math.nan
    return slope_fit(np.log(x[use]), np.log(y[use]))


def _beta_of_stacked(n, x, window):
    """The statistic for the bootstrap: mean curves of all x side by side -> beta."""
    k = len(n)

    def stat(stacked):
        return exponent(x, [plateau(n, stacked[i * k:(i + 1) * k], *window)
                            for i in range(len(x))])[0]
    return stat


def _beta_systematic(n, x, curves, window):
    """Half-range of beta over the plateau window's start moved 10**(+-1/4) and over dropping
    the smallest or the largest 1 - r."""
    betas = []
    for lo in _window_starts(window):
        plats = [plateau(n, c.mean_v, lo, window[1]) for c in curves]
        betas.append(exponent(x, plats)[0])
        betas.append(exponent(x[1:], plats[1:])[0])
        betas.append(exponent(x[:-1], plats[:-1])[0])
    betas = [b for b in betas if math.isfinite(b)]
    return 0.5 * (max(betas) - min(betas)) if betas else math.nan


def _curves_of_study():
    """(label, physics keywords) of every curve, in the study's order: the elastic reference,
    restitution per 1 - r, drag per (law, k)."""
    return ([("elastic", {})]
            + [(f"1 - r = {x:g}", {"restitution": 1.0 - x}) for x in STUDY["one_minus_r"]]
            + [(f"{law} drag k = {k:g}", {"drag": k, "drag_law": law})
               for law, ks in STUDY["drag"].items() for k in ks])


def _starts(quick):
    """The study's starts (phi0, v0), the same for every physics."""
    return uniform_box(np.random.default_rng(SAMPLING_SEED), ESCAPE_BOX,
                       STUDY[bool(quick)]["particles"])


def _study_moments(quick, only=None):
    """The study's starts, grid, <v_n> curves, stuck fractions and velocity strip (``only``:
    just the curves of these labels, no stuck fractions): compiled code and numpy only (no
    mpmath; the GIL released while the kernels run), so that it may run in a background thread
    (``start_dissipation_study``). Returns ((phi0, v0, n, window, curves, sticking, strip),
    seconds)."""
    t0 = time.perf_counter()
    cfg = STUDY[bool(quick)]
    eps = STUDY["eps"]
    m = cfg["particles"]
    phi0, v0 = _starts(quick)
    n = np.unique(np.round(np.logspace(0, math.log10(cfg["n_max"]), 41)).astype(np.int64))
    window = (cfg["n_max"] / 10.0, float(cfg["n_max"]))
    curves = [_curve(label, physics, phi0, v0, eps, n, window)
              for label, physics in _curves_of_study() if only is None or label in only]
    sticking = []
    for r in STUDY["sticking_r"] if only is None else ():
        mom = moments(phi0, v0, STUDY["sticking_eps"], n, blocks=BLOCKS, restitution=r)
        sticking.append((r, float(mom.stuck_n.sum(axis=0)[-1]) / m, m))
    strip = _strip(phi0, v0, quick)
    return (phi0, v0, n, window, curves, sticking, strip), time.perf_counter() - t0


def _spot_check(phi0, v0, quick):
    """The verify spot check of the dissipative orbits (``verify_sample``: mpmath, whose
    precision is process-wide: never beside other mpmath code in another thread)."""
    cfg = STUDY[bool(quick)]
    omr = STUDY["one_minus_r"]
    starts = list(zip(phi0[:2], v0[:2], strict=True))
    physics_list = [{"restitution": 1.0 - omr[0]}, {"restitution": 1.0 - omr[-1]},
                    {"drag": STUDY["drag"]["linear"][-1], "drag_law": "linear"},
                    {"drag": STUDY["drag"]["quadratic"][-1], "drag_law": "quadratic"}]
    return verify_sample(starts, STUDY["eps"], min(cfg["n_max"], 3000), cfg["verify"],
                         physics_list=physics_list)


def _strip(phi0, v0, quick):
    """(orbits, max |v_n| per 1 - r over each half of them) for the velocity strip."""
    k = STRIP_ORBITS[bool(quick)]
    return k, strip_maxima(phi0[:k], v0[:k], STUDY["eps"], STUDY["one_minus_r"],
                           STUDY[bool(quick)]["n_max"])


def _finished_study(quick, parts, seconds, ver=None):
    """The study from ``_study_moments``'s parts: the exponent with its bootstrap and
    systematic errors, and the verify spot check ``ver`` (computed here if None: mpmath, in
    the calling thread)."""
    t0 = time.perf_counter()
    phi0, v0, n, window, curves, sticking, (k, halves) = parts
    elastic = curves[0]
    rest = curves[1:1 + len(STUDY["one_minus_r"])]
    drag = curves[1 + len(STUDY["one_minus_r"]):]
    nf = n.astype(float)
    omr = np.array(STUDY["one_minus_r"])
    beta, amp = exponent(omr, [c.plateau for c in rest])
    stacked_num = np.hstack([c.sum_v for c in rest])
    stacked_den = np.hstack([c.count for c in rest])
    beta_err = bootstrap_blocks(stacked_num, stacked_den, _beta_of_stacked(nf, omr, window))
    beta_sys = _beta_systematic(nf, omr, rest, window)
    if ver is None:
        ver = _spot_check(phi0, v0, quick)
    return Dissipation(STUDY["eps"], len(phi0), nf, window, elastic, rest, drag, omr, beta,
                       beta_err, beta_sys, math.exp(amp) if math.isfinite(amp) else math.nan,
                       sticking, ver, seconds + time.perf_counter() - t0,
                       [max(h) for h in halves], k, halves)


# --- the committed study ------------------------------------------------------------------------

# the full study (``STUDY[False]``), package data beside this module, written by
# scripts/dissipation_study.py; the report re-checks part of it (``recheck``) instead of
# spending its minutes on it again
COMMITTED = Path(__file__).resolve().with_name("dissipation_study.json")
# the curves a re-check recomputes: one of each kind of physics
RECHECKED = ("elastic", f"1 - r = {STUDY['one_minus_r'][-1]:g}",
             f"linear drag k = {STUDY['drag']['linear'][-1]:g}",
             f"quadratic drag k = {STUDY['drag']['quadratic'][-1]:g}")
_ARRAY = "__array__"


def _plain(value):
    """``value`` as JSON: arrays as {__array__: dtype, data: list}, tuples as lists."""
    if isinstance(value, np.ndarray):
        return {_ARRAY: str(value.dtype), "data": value.tolist()}
    if isinstance(value, (np.floating, np.integer)):
        return value.item()
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    return value


def _typed(value):
    if isinstance(value, dict) and _ARRAY in value:
        return np.array(value["data"], dtype=value[_ARRAY])
    if isinstance(value, dict):
        return {k: _typed(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_typed(v) for v in value]
    return value


def to_json(study):
    """The study as JSON text (floats written exactly, NaN as NaN; one line: most of it is the
    per-block sums)."""
    return json.dumps(_plain(dataclasses.asdict(study))) + "\n"


def _curve_of(d):
    return Curve(**_typed(d))


def from_json(text):
    """The ``Dissipation`` that ``to_json`` wrote."""
    d = json.loads(text)
    curves = {name: d.pop(name) for name in ("elastic", "restitution", "drag")}
    d = _typed(d)
    d["window"] = tuple(d["window"])
    d["sticking"] = [tuple(x) for x in d["sticking"]]
    d["strip_halves"] = [tuple(x) for x in d["strip_halves"]]
    return Dissipation(elastic=_curve_of(curves["elastic"]),
                       restitution=[_curve_of(c) for c in curves["restitution"]],
                       drag=[_curve_of(c) for c in curves["drag"]], **d)


def same_numbers(a, b):
    """Whether two values hold the same numbers bit for bit (NaN equal to NaN): arrays,
    dataclasses, containers, floats."""
    if dataclasses.is_dataclass(a):
        return type(a) is type(b) and same_numbers(dataclasses.asdict(a), dataclasses.asdict(b))
    if isinstance(a, dict):
        return isinstance(b, dict) and a.keys() == b.keys() and all(
            same_numbers(a[k], b[k]) for k in a)
    if isinstance(a, (list, tuple)):
        return isinstance(b, (list, tuple)) and len(a) == len(b) and all(
            same_numbers(x, y) for x, y in zip(a, b, strict=True))
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return np.array_equal(np.asarray(a), np.asarray(b), equal_nan=True)
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a):
        return math.isnan(b)
    return a == b


def recheck(committed, parts, ver):
    """Compare the committed study with ``parts`` recomputed now (``_study_moments`` of the
    ``RECHECKED`` curves, with the strip) and the verify spot check ``ver``: [] if every
    number is the same bit for bit, else what differs."""
    _, _, n, window, curves, _, (k, halves) = parts
    stored = {c.label: c for c in [committed.elastic, *committed.restitution, *committed.drag]}
    differ = []
    if not (same_numbers(n.astype(float), committed.n) and tuple(window) == committed.window):
        differ.append("the grid")
    for c in curves:
        if c.label not in stored or not same_numbers(c, stored[c.label]):
            differ.append(f"the curve {c.label}")
    if not same_numbers(ver, committed.verification):
        differ.append("the verify spot check")
    if not (k == committed.strip_orbits and same_numbers(halves, committed.strip_halves)):
        differ.append("the velocity strip")
    return differ


_STUDIES = {}  # quick -> Dissipation: figure and claims share one study


def _committed_for(quick):
    """The committed study's file for this size, if there is one (the full size only)."""
    return COMMITTED if not quick and COMMITTED.is_file() else None


def dissipation_study(quick=False, echo=None):
    """The study (cached; module docstring): for the full size the committed one
    (``COMMITTED``) where its re-check passes, else computed here."""
    return start_dissipation_study(quick, echo, start=at_once)()


def start_dissipation_study(quick=False, echo=None, start=begin):
    """Begin the study; returns a function that finishes it in the calling thread and
    returns the ``Dissipation``.

    At the full size with the committed study present, what begins is its re-check: the
    ``RECHECKED`` curves recomputed; ``finish`` compares them, the verify spot check and the
    strip with the committed numbers and returns the committed study (``source`` says so), or
    computes the whole study if anything differs. Otherwise the whole study begins.

    ``start`` begins the moments and the strip (``_study_moments``, most of the time): by
    default (``background.begin``) in a daemon thread while the caller goes on (a report's
    claims, mostly on one core), so an interrupted report does not wait for them; or a
    ``background.Worker``'s ``submit``; or ``background.at_once``. The verify spot check runs
    in the caller's thread when it finishes the study, beside them if they are still running
    (mpmath's precision is process-wide).
    """
    quick = bool(quick)
    echo = echo or (lambda _msg: None)
    if quick in _STUDIES:
        return lambda: _STUDIES[quick]
    path = _committed_for(quick)
    committed = None if path is None else from_json(path.read_text(encoding="utf-8"))
    only = RECHECKED if committed is not None else None
    moments_done = start(_study_moments, quick, only, name="dissipation-moments")

    def finish():
        if quick in _STUDIES:
            return _STUDIES[quick]
        t0 = time.perf_counter()
        ver = _spot_check(*_starts(quick), quick)
        spot_seconds = time.perf_counter() - t0
        parts, seconds = moments_done()
        seconds += spot_seconds
        if committed is None:
            _STUDIES[quick] = _finished_study(quick, parts, seconds, ver)
            return _STUDIES[quick]
        differ = recheck(committed, parts, ver)
        if differ:
            echo(f"dissipation: the committed study {path.name} is not what this code "
                 f"computes ({', '.join(differ)} differ): computing the whole study")
            study = _finished_study(quick, *_study_moments(quick), ver)
            study.source = (f"computed here: the committed study differs from this code's in "
                            f"{', '.join(differ)}")
        else:
            study = dataclasses.replace(committed, source=(
                f"the committed study (`{path.name}`, {committed.seconds:.0f} s to "
                f"compute), re-checked here in {seconds:.0f} s: the curves "
                f"{', '.join(RECHECKED)}, the verify spot check and the velocity strip "
                "recomputed, the same bit for bit"))
        _STUDIES[quick] = study
        return study
    return finish
