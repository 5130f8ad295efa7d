"""Precision comparison (work-precision): error against ``verify`` versus time per collision.

One fixed, seeded set of states (random states, the hard cases of :mod:`reports.hard_case_table`,
and eps > 1 departures that nearly graze the plate) is solved by every method of
:mod:`reports.methods`. Each flight is compared with ``verify.step`` at ``REFERENCE_DPS`` digits:

- relative error of tau, also in units of kappa*u (kappa = ``verify.condition_number`` at the
  reference tau, u = 2**-53): a float64 method that is as good as the data allows scores O(1);
- error of the collision: |phi1 - phi1_ref| (mod 2*pi) and |v1 - v1_ref| / max(1, |v1_ref|);
- overstepped ("missed") collisions: the method's tau lies past the certified first root *and*
  past a later one's start, i.e. the gap rises back to zero in between (a positive gap on a fine
  grid between the two times, or a rising gap d'(tau) > 0 at the method's tau, which a first root
  never has). Counted on the near-grazing set, where two roots lie close together;
- time per collision, all methods in the same process, interleaved, best of a few repeats, numba
  on one thread so that it compares with the single-threaded Python methods.

The Holmes map's tau = 2v is compared with the exact map: its "error" is the model's.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from pathlib import Path

import mpmath
import numpy as np
from mpmath import mp

import verify
from reports.methods import Method, Outcome, default_methods

UNIT_ROUNDOFF = 2.0**-53
REFERENCE_DPS = 60
SEED = 20240604
TWO_PI = 2.0 * math.pi


@dataclass(frozen=True)
class Case:
    """A departure (float64 phi, v, eps) with a label; ``contact`` is the graze time T of a
    near-grazing departure (the bottom of the dip between its two close roots), else None."""

    phi: float
    v: float
    eps: float
    label: str
    group: str  # "random", "hard" or "grazing"
    contact: float | None = None
    clearance: float | None = None


@dataclass(frozen=True)
class Reference:
    """verify at REFERENCE_DPS: tau with its enclosure, (phi1, v1) and kappa."""

    tau: mpmath.mpf
    upper: mpmath.mpf
    phi1: mpmath.mpf
    v1: mpmath.mpf
    kappa: mpmath.mpf


@dataclass(frozen=True)
class Error:
    """One method on one case. NaN errors where the method failed."""

    tau_rel: float
    tau_units: float  # tau_rel / (kappa*u)
    phi1_abs: float
    v1_rel: float
    iterations: int | None
    status: str  # "ok", "uncertain", "missed" or "error: ..."


@dataclass
class MethodSummary:
    name: str
    kind: str
    model: str
    median_units: float
    max_units: float
    median_rel: float
    max_rel: float
    max_collision: float  # max over states of max(|dphi1|, |dv1|/max(1, |v1|))
    seconds: float  # per collision
    timed_on: int
    x_holmes: float
    missed: int  # on the near-grazing pairs
    grazing: int
    missed_random: int
    failures: int
    worst_hard_units: float


@dataclass
class WorkPrecisionResult:
    methods: list[Method]
    cases: list[Case]
    references: list[Reference | None]
    errors: dict[str, list[Error]]
    summaries: list[MethodSummary]
    skipped: list[str] = field(default_factory=list)
    elapsed: float = 0.0

    def group(self, name: str, group: str) -> list[Error]:
        """Errors of method ``name`` on the cases of one group (with a reference)."""
        return [e for c, r, e in zip(self.cases, self.references, self.errors[name], strict=True)
                if c.group == group and r is not None]


# ---------------------------------------------------------------------------------------------
# cases


def random_states(n: int, seed: int = SEED) -> list[Case]:
    """n seeded departures: a quarter from the seed's box (eps = 0.6, 3.85 < phi < 4.15,
    2 < v < 4); the rest with eps uniform in (0, 10] or log-uniform in [1e-3, 10] (half each),
    phi uniform, v log-uniform in [0.1, 1e4], resampled until w0 = v + eps*sin(phi) > 0."""
    rng = np.random.default_rng(seed)
    cases = []
    n_box = n // 4
    for _ in range(n_box):
        cases.append(Case(float(rng.uniform(3.85, 4.15)), float(rng.uniform(2.0, 4.0)), 0.6,
                          "seed box", "random"))
    for i in range(n - n_box):
        eps = float(10.0 - rng.uniform(0.0, 10.0)) if i % 2 else float(10 ** rng.uniform(-3, 1))
        phi = float(rng.uniform(0.0, TWO_PI))
        while True:
            v = float(10 ** rng.uniform(-1, 4))
            if v + eps * math.sin(phi) > 0.0:
                break
        cases.append(Case(phi, v, eps, "random", "random"))
    order = rng.permutation(len(cases))
    return [cases[i] for i in order]


def grazing_case(eps, psi, t_guess, clearance, label="grazing pair") -> Case | None:
    """A near-grazing departure (float64) from ``verify.grazing_contact``, or None."""
    try:
        g = verify.grazing_contact(eps, psi, t_guess, clearance)
    except ValueError:
        return None
    phi, v = float(g.phi), float(g.v)
    if not v + eps * math.sin(phi) > 0.0:
        return None
    return Case(phi, v, float(eps), label, "grazing", float(g.T), float(clearance))


def grazing_cases(n: int, seed: int = SEED + 1) -> list[Case]:
    """n departures of eps > 1 whose first two roots form a close pair: clearance -1e-2..-1e-8
    (log-uniform) at a contact time T, with no earlier collision (checked with ``verify``)."""
    rng = np.random.default_rng(seed)
    cases: list[Case] = []
    tries = 0
    while len(cases) < n and tries < 40 * n:
        tries += 1
        eps = float(rng.choice([1.5, 3.0, 10.0]))
        half = 0.8 * math.acos(1.0 / eps)
        psi, t_guess = float(rng.uniform(-half, half)), float(rng.uniform(2.0, 12.0))
        clearance = -float(10 ** rng.uniform(-8, -2))
        case = grazing_case(eps, psi, t_guess, clearance)
        if case is None:
            continue
        ref = reference(case)
        if ref is None:
            continue
        curvature = eps * math.cos(psi) - 1.0
        separation = 2.0 * math.sqrt(2.0 * -clearance / curvature)
        if not case.contact - 1.5 * separation < float(ref.tau) < case.contact:
            continue  # an earlier collision: not a close-pair test
        cases.append(case)
    return cases


# ---------------------------------------------------------------------------------------------
# reference and errors

COSTS: dict[str, float] = {}  # wall seconds spent per method (evaluation and timing), diagnostics
_REFERENCES: dict[tuple[float, float, float], Reference | None] = {}


def reference(case: Case) -> Reference | None:
    """verify.step at REFERENCE_DPS with its enclosure and kappa (cached); None if undecidable."""
    key = (case.phi, case.v, case.eps)
    if key not in _REFERENCES:
        try:
            cert = verify.certify_flight(case.phi, case.v, case.eps, dps=REFERENCE_DPS)
            phi1, v1, tau = verify.step(case.phi, case.v, case.eps, dps=REFERENCE_DPS)
            with mp.workdps(REFERENCE_DPS):
                kappa = verify.condition_number(case.phi, case.v, case.eps, tau)
            _REFERENCES[key] = Reference(tau, cert.enclosure[1], phi1, v1, kappa)
        except verify.UndecidableCollision:
            _REFERENCES[key] = None
    return _REFERENCES[key]


def _gap_rate(case: Case, t) -> mpmath.mpf:
    with mp.workdps(40):
        t = mp.mpf(t)
        return mp.mpf(case.v) - t + mp.mpf(case.eps) * mp.sin(mp.mpf(case.phi) + t)


def overstepped(case: Case, ref: Reference, tau) -> bool:
    """True if ``tau`` lies past a later root: past the first root, with the gap rising at tau or
    positive somewhere between the first root and tau (a fine float64 grid, step <= 0.005)."""
    if not tau > ref.upper:
        return False
    if _gap_rate(case, tau) > 0:
        return True
    lo, hi = float(ref.upper), float(tau)
    with mp.workdps(40):
        phi = float(mp.mpf(case.phi) % (2 * mp.pi))
    n = int(min(200_000, max(64, (hi - lo) / 0.005)))
    s = np.linspace(lo, hi, n)
    eps, v = case.eps, case.v
    d = 2.0 * eps * np.sin(phi + 0.5 * s) * np.sin(0.5 * s) + s * (v - 0.5 * s)
    err = 4.0 * UNIT_ROUNDOFF * (abs(eps) * np.minimum(s, 2.0) * (phi + s + 3.0) + s * (abs(v) + s))
    return bool(np.any(d > 8.0 * err))


def _mp(x):
    return mp.mpf(x) if not isinstance(x, mpmath.mpf) else x


def compare(method: Method, case: Case, ref: Reference, out: Outcome) -> Error:
    """Errors of one outcome against the reference (Holmes: against the exact map)."""
    bad = out.status.startswith("error") or out.status.startswith("uncertain")
    try:
        finite = mp.isfinite(_mp(out.tau))
    except (TypeError, ValueError):
        finite = False
    if bad or not finite:
        status = out.status if bad else "error: no flight time (NaN)"
        return Error(math.nan, math.nan, math.nan, math.nan, out.iterations, status)
    with mp.workdps(REFERENCE_DPS):
        tau = _mp(out.tau)
        rel = abs(tau - ref.tau) / ref.tau
        units = rel / (ref.kappa * UNIT_ROUNDOFF)
        dphi = (_mp(out.phi1) - ref.phi1 + mp.pi) % (2 * mp.pi) - mp.pi
        dv = abs(_mp(out.v1) - ref.v1) / max(1, abs(ref.v1))
    status = "ok"
    if method.model == "exact" and overstepped(case, ref, tau):
        status = "missed"
    return Error(float(rel), float(units), float(abs(dphi)), float(dv), out.iterations, status)


def evaluate(methods: list[Method], cases: list[Case]):
    """(references, {method name: [Error per case]}); cases without a reference get None."""
    start = time.perf_counter()
    refs = [reference(c) for c in cases]
    COSTS["reference"] = COSTS.get("reference", 0.0) + time.perf_counter() - start
    errors: dict[str, list[Error]] = {m.name: [] for m in methods}
    for case, ref in zip(cases, refs, strict=True):
        for m in methods:
            if ref is None:
                errors[m.name].append(Error(math.nan, math.nan, math.nan, math.nan, None,
                                            "no reference (undecidable)"))
                continue
            start = time.perf_counter()
            out = m.safe_solve(case.phi, case.v, case.eps)
            COSTS[m.name] = COSTS.get(m.name, 0.0) + time.perf_counter() - start
            errors[m.name].append(compare(m, case, ref, out))
    return refs, errors


# ---------------------------------------------------------------------------------------------
# timing


def time_methods(methods: list[Method], cases: list[Case], repeats: int = 3,
                 min_batch: int = 200_000) -> dict[str, tuple[float, int]]:
    """{name: (seconds per collision, states timed)}: batches, methods interleaved, best of
    ``repeats``; numba on one thread. Vectorised methods run the states tiled to at least
    ``min_batch`` collisions in one call."""
    import numba

    arrays = {}
    for m in methods:
        sub = cases if m.timing_states is None else cases[: m.timing_states]
        phi = np.array([c.phi for c in sub])
        v = np.array([c.v for c in sub])
        eps = np.array([c.eps for c in sub])
        if m.vectorised:
            reps = max(1, -(-min_batch // len(sub)))
            phi, v, eps = np.tile(phi, reps), np.tile(v, reps), np.tile(eps, reps)
        arrays[m.name] = (phi, v, eps, len(sub))
    threads = numba.get_num_threads()
    best = {m.name: math.inf for m in methods}
    try:
        numba.set_num_threads(1)
        for m in methods:  # warm-up: compilation and caches
            phi, v, eps, _ = arrays[m.name]
            m.batch(phi[:4], v[:4], eps[:4])
        for _ in range(repeats):
            for m in methods:
                phi, v, eps, _ = arrays[m.name]
                start = time.perf_counter()
                m.batch(phi, v, eps)
                spent = time.perf_counter() - start
                best[m.name] = min(best[m.name], spent / len(phi))
                COSTS["timing " + m.name] = COSTS.get("timing " + m.name, 0.0) + spent
    finally:
        numba.set_num_threads(threads)
    return {m.name: (best[m.name], arrays[m.name][3]) for m in methods}


# ---------------------------------------------------------------------------------------------
# the whole comparison


def _nanmedian(x):
    x = np.asarray(x, float)
    return float(np.nanmedian(x)) if np.isfinite(x).any() else math.nan


def _nanmax(x):
    x = np.asarray(x, float)
    return float(np.nanmax(x)) if np.isfinite(x).any() else math.nan


def run_work_precision(n_states: int = 400, quick: bool = False, n_grazing: int = 50,
                       methods: list[Method] | None = None, seed: int = SEED,
                       echo=None) -> WorkPrecisionResult:
    """Evaluate and time every method on the fixed case set; see the module docstring."""
    from reports.hard_case_table import hard_cases

    start = time.perf_counter()
    say = echo or (lambda msg: None)
    methods = default_methods() if methods is None else methods
    if quick:
        n_states, n_grazing = min(n_states, 16), min(n_grazing, 8)
    say(f"work-precision: building {n_states} random states, hard cases, {n_grazing} grazing "
        "pairs")
    cases = random_states(n_states, seed) + hard_cases(quick) + grazing_cases(n_grazing, seed + 1)
    say(f"work-precision: {len(cases)} cases x {len(methods)} methods against verify "
        f"(dps {REFERENCE_DPS})")
    refs, errors = evaluate(methods, cases)
    skipped = [c.label for c, r in zip(cases, refs, strict=True) if r is None]
    randoms = [c for c, r in zip(cases, refs, strict=True) if c.group == "random" and r]
    say(f"work-precision: timing on {len(randoms)} random states")
    timing = time_methods(methods, randoms, repeats=2 if quick else 3,
                          min_batch=5_000 if quick else 200_000)
    holmes = next((timing[m.name][0] for m in methods if m.model == "holmes"), math.nan)
    result = WorkPrecisionResult(methods, cases, refs, errors, [], skipped)
    for m in methods:
        rand, hard = result.group(m.name, "random"), result.group(m.name, "hard")
        graze = result.group(m.name, "grazing")
        seconds, timed_on = timing[m.name]
        failures = sum(1 for e in rand + hard + graze
                       if e.status.startswith("error") or e.status.startswith("uncertain"))
        result.summaries.append(MethodSummary(
            name=m.name, kind=m.kind, model=m.model,
            median_units=_nanmedian([e.tau_units for e in rand]),
            max_units=_nanmax([e.tau_units for e in rand]),
            median_rel=_nanmedian([e.tau_rel for e in rand]),
            max_rel=_nanmax([e.tau_rel for e in rand]),
            max_collision=_nanmax([max(e.phi1_abs, e.v1_rel) for e in rand]),
            seconds=seconds, timed_on=timed_on, x_holmes=seconds / holmes,
            missed=sum(e.status == "missed" for e in graze), grazing=len(graze),
            missed_random=sum(e.status == "missed" for e in rand),
            failures=failures, worst_hard_units=_nanmax([e.tau_units for e in hard]),
        ))
    result.elapsed = time.perf_counter() - start
    say(f"work-precision: done in {result.elapsed:.1f} s")
    return result


# ---------------------------------------------------------------------------------------------
# figure and table

_ERROR_FLOOR = 1e-64


def plot_work_precision(result: WorkPrecisionResult, stem: Path) -> list[Path]:
    """Log-log error of tau (x) against time per collision (y): median (filled) and worst
    (open) marker per method, joined. Writes stem.png and stem.pdf; returns the paths."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(9, 5.6), constrained_layout=True)
    markers = "osD^v<>ph*XP"
    palette = [*plt.get_cmap("tab10").colors, "black", "gold"]
    for i, s in enumerate(result.summaries):
        color = palette[i % len(palette)]
        y = s.seconds * 1e9
        med, worst = max(s.median_rel, _ERROR_FLOOR), max(s.max_rel, _ERROR_FLOOR)
        marker = markers[i % len(markers)]
        ax.plot([med, worst], [y, y], color=color, lw=1.2, alpha=0.8)
        ax.plot(med, y, marker=marker, color=color, ms=9, ls="none",
                label=f"{s.name} ({s.kind})")
        ax.plot(worst, y, marker=marker, mfc="white", mec=color, mew=1.5, ms=9, ls="none")
    ax.axvline(UNIT_ROUNDOFF, color="0.6", ls=":", lw=1)
    ax.text(UNIT_ROUNDOFF, 0.01, " u = 2^-53", color="0.4", fontsize=8, va="bottom",
            transform=ax.get_xaxis_transform())
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("relative error of the flight time tau against verify (dps "
                  f"{REFERENCE_DPS}); filled: median, open: worst")
    ax.set_ylabel("time per collision [ns] (one thread)")
    n = sum(1 for c, r in zip(result.cases, result.references, strict=True)
            if c.group == "random" and r)
    ax.set_title(f"Work-precision on {n} random states (Holmes map: error of the model)")
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), frameon=False)
    stem.parent.mkdir(parents=True, exist_ok=True)
    paths = [stem.with_suffix(".png"), stem.with_suffix(".pdf")]
    fig.savefig(paths[0], dpi=130)
    fig.savefig(paths[1])
    plt.close(fig)
    return paths


def _g(x, digits=2):
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "-"
    return f"{x:.{digits}g}"


def _ns(seconds):
    ns = seconds * 1e9
    return f"{ns:,.0f}" if ns >= 10 else f"{ns:.2g}"


def markdown_table(result: WorkPrecisionResult) -> str:
    """The work-precision table (Markdown)."""
    head = ("| method | kind | median err [kappa u] | max err [kappa u] | median rel. err tau "
            "| max err (phi1, v1) | ns/collision | x Holmes | missed: grazing pairs; random "
            "| failures | worst on hard cases [kappa u] |")
    lines = [head, "|" + "---|" * 11]
    n_random = len(result.group(result.summaries[0].name, "random")) if result.summaries else 0
    for s in result.summaries:
        timed = "" if s.timed_on >= len(result.group(s.name, "random")) else f" ({s.timed_on})"
        missed = ("n/a (model)" if s.model == "holmes"
                  else f"{s.missed} / {s.grazing}; {s.missed_random} / {n_random}")
        lines.append(
            f"| {s.name} | {s.kind} | {_g(s.median_units)} | {_g(s.max_units)} "
            f"| {_g(s.median_rel)} | {_g(s.max_collision)} | {_ns(s.seconds)}{timed} "
            f"| {_g(s.x_holmes, 3)} | {missed} | {s.failures} | {_g(s.worst_hard_units)} |"
        )
    return "\n".join(lines)


def work_precision_markdown(result: WorkPrecisionResult, image: str) -> str:
    n_random = len(result.group(result.methods[0].name, "random"))
    n_hard = len(result.group(result.methods[0].name, "hard"))
    n_graze = len(result.group(result.methods[0].name, "grazing"))
    skipped = (f" {len(result.skipped)} case(s) that verify could not decide were left out."
               if result.skipped else "")
    return "\n".join([
        "## Precision comparison (work-precision)",
        "",
        f"Every method solves the same {n_random} seeded random departures (a quarter from the "
        "seed's box eps = 0.6, 3.85 < phi < 4.15, 2 < v < 4; the rest with eps in (0, 10] and "
        f"v log-uniform in [0.1, 1e4]), {n_hard} hard cases and {n_graze} eps > 1 departures "
        "whose first two roots are a close pair (clearance -1e-2..-1e-8 below a graze). The "
        f"reference is `verify.step` at {REFERENCE_DPS} digits. Errors are relative errors of "
        "the flight time tau, also in units of kappa*u (kappa = `verify.condition_number`, "
        "u = 2^-53; a float64 method as good as its input allows scores O(1)); the collision "
        "error is max(|phi1 - phi1_ref| mod 2pi, |v1 - v1_ref|/max(1, |v1_ref|)). Medians and "
        "maxima are over the random states. The Holmes map is compared with the exact map: its "
        "error is the model's, not rounding." + skipped,
        "",
        f"![work-precision]({image})",
        "",
        markdown_table(result),
        "",
        "- Time per collision: measured in one process, methods interleaved, best of 3 batches, "
        "numba on one thread (the Python methods are single-threaded too). fastpath and Holmes "
        "run the random states tiled to 200,000 collisions in one vectorised call; the other "
        "methods loop in Python over the random states (over the first N, N in parentheses, "
        "where a method caps its timed states).",
        "- Missed: the method's tau is past the certified first root and past a later one (the "
        "gap rises again in between). scipy's event detection only compares the sign of the gap "
        "at the ends of each RK step, and the brentq/findroot bracket comes from a grid of step "
        "0.1: both step over a pair of roots closer than their sampling. fastpath's lower-bound "
        "steps and verify's boxes never pass a root.",
        "- Failures: exceptions, undecided (fastpath UNCERTAIN, verify undecidable) or no root "
        "found, over all cases. The hard-case table below shows each case.",
        f"- Section built in {result.elapsed:.0f} s.",
        "",
    ])


def work_precision_section(out_dir, n_states: int = 400, quick: bool = False,
                           echo=None) -> str:
    """Run the comparison, write work_precision.png/.pdf into ``out_dir``, return Markdown whose
    image link is relative to ``out_dir``."""
    out_dir = Path(out_dir)
    result = run_work_precision(n_states=n_states, quick=quick, echo=echo)
    plot_work_precision(result, out_dir / "work_precision")
    return work_precision_markdown(result, "work_precision.png")
