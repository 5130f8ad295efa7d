"""Precision comparison (work-precision): error against ``verify`` versus time per collision.

One fixed, seeded set of states (random states, the hard cases of
:mod:`reports.precision.hard_case_table`, and eps > 1 departures that nearly graze the plate)
is solved by every method of :mod:`reports.precision.methods`. Each flight is compared with
``verify.step`` at ``REFERENCE_DPS`` digits:

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

import numpy as np

from reports.precision.cases import SEED, grazing_cases, hard_cases, random_states
from reports.precision.evaluate import (
    COSTS,
    REFERENCE_DPS,
    UNIT_ROUNDOFF,
    Case,
    Error,
    Reference,
    evaluate,
)
from reports.precision.methods import Method, default_methods


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
        "paper's box eps = 0.6, 3.85 < phi < 4.15, 2 < v < 4; the rest with eps in (0, 10] and "
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
