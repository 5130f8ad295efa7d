"""Stability on hard cases: each method's error, iterations and status on departures that break
naive solvers.

The cases are ``verify.hard_cases.HARD_CASES``, the one table the property tests also check:
small departure speeds w0 = 1e-3..1e-12, huge v up to 1e6, eps across {1e-8, 0.2429, 0.6,
0.999999, 1, 1.000001, 3, 100}, phases at and next to 0 and pi, unreduced phases, and eps > 1
near-grazing pairs at several clearances (negative clearance: two close roots just before the
contact time T; positive: the particle passes above the plate at T and lands later).

The dissipative cases (``verify.hard_cases.DISSIPATIVE_CASES``: drag grazes, departures at rest,
chattering grazes) get a sub-table of their own (``dissipative_case_markdown``): only fastpath
and verify support drag, so they are not in the methods' table and its counted figures.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from pathlib import Path

from mpmath import mp

import fastpath
import verify
from reports.precision.cases import hard_cases
from reports.precision.evaluate import REFERENCE_DPS, UNIT_ROUNDOFF
from reports.precision.methods import default_methods
from reports.precision.work_precision import Error, evaluate
from verify.dissipative.drag import motion
from verify.hard_cases import DISSIPATIVE_CASES, HardCase


def _cell(err: Error, with_iterations: bool) -> str:
    if err.status.startswith("error"):
        msg = err.status[len("error: "):].replace("|", "/")
        return f"error: {msg[:48]}"
    if err.status.startswith("uncertain") or err.status.startswith("no reference"):
        return err.status.split(" (")[0]
    units = "0" if err.tau_units == 0 else f"{err.tau_units:.2g}"
    text = units
    if with_iterations and err.iterations is not None:
        text += f" ({err.iterations})"
    if err.status == "missed":
        text += " **missed**"
    return text


def hard_case_markdown(cases, references, errors, methods) -> str:
    names = [m.name for m in methods]
    lines = [
        "## Stability on hard cases",
        "",
        "Each cell: error of tau in units of kappa*u against verify (dps 60), the method's "
        "iteration count in parentheses where it reports one (fastpath: Halley gap evaluations "
        "or lower-bound steps; solve_ivp: RHS evaluations; brentq/findroot: scan points plus "
        "solver calls; verify: interval boxes), then **missed** if the method jumped past the "
        "first root, `uncertain` where the method says it cannot decide, or the error message. "
        "Holmes's error is the model's (against the exact map). kappa is given per case.",
        "",
        "| case | phi | v | eps | tau (verify) | kappa | " + " | ".join(names) + " |",
        "|" + "---|" * (6 + len(names)),
    ]
    for i, case in enumerate(cases):
        ref = references[i]
        tau = f"{float(ref.tau):.6g}" if ref is not None else "undecidable"
        kappa = f"{float(ref.kappa):.2g}" if ref is not None else "-"
        cells = [_cell(errors[m.name][i], m.model == "exact") for m in methods]
        lines.append(f"| {case.label} | {case.phi:.17g} | {case.v:.17g} | {case.eps:.17g} "
                     f"| {tau} | {kappa} | " + " | ".join(cells) + " |")
    lines.append("")
    counts = []
    for m in methods:
        errs = [errors[m.name][i] for i in range(len(cases)) if references[i] is not None]
        missed = sum(e.status == "missed" for e in errs)
        bad = sum(e.status.startswith(("error", "uncertain")) for e in errs)
        worst = max((e.tau_units for e in errs if not math.isnan(e.tau_units)), default=math.nan)
        counts.append(f"| {m.name} | {worst:.2g} | {missed} | {bad} |")
    lines += ["| method | worst err [kappa u] | missed | uncertain / errors |", "|---|---|---|---|",
              *counts, ""]
    return "\n".join(lines)


def hard_case_section(out_dir, quick: bool = False, methods=None) -> str:
    """Markdown table of the hard cases (``out_dir`` is accepted for symmetry; no files)."""
    Path(out_dir).mkdir(parents=True, exist_ok=True)
    methods = default_methods() if methods is None else methods
    cases = hard_cases(quick)
    refs, errors = evaluate(methods, cases)
    return hard_case_markdown(cases, refs, errors, methods)


# --- the dissipative cases: fastpath against verify, with drag ----------------------------------

_MISS_GRID_STEP = 0.005  # grid step of the search for a positive gap between two roots
_MISS_GRID_POINTS = 2_000  # at most (a wrong answer far past the first root is slow to judge)


@dataclass(frozen=True)
class DissipativeRow:
    """fastpath (method "auto") on one dissipative case, judged against verify.

    ``tau``/``upper``: verify's certified flight time and the upper end of its enclosure
    (None where verify cannot decide); ``seconds``: verify's certification time; ``kappa``:
    (|v| + tau + |eps|*(1 + |phi| + tau)) / |d'(tau)| with the drag flight's velocity in d'
    (the scale of tests/fastpath/drag_reference.py ``kappa``; verify.condition_number is its
    elastic case); ``units``: |tau_fast - tau|/(kappa*u*tau), NaN unless CONVERGED; ``status``:
    fastpath's FlightStatus name; ``missed``: fastpath's tau lies past verify's first root and
    past a later root's start (the gap rising there, or positive on a grid in between).
    """

    case: HardCase
    tau: object
    upper: object
    seconds: float
    kappa: float
    tau_fast: float
    iterations: int
    status: str
    units: float
    missed: bool


def _drag_point(case: HardCase, t):
    """(d(t), d'(t)) of the case's gap at REFERENCE_DPS digits (verify.dissipative.drag.motion)."""
    with mp.workdps(REFERENCE_DPS):
        t = mp.mpf(t)
        y, vel = motion(case.v, t, case.drag, case.drag_law, dps=REFERENCE_DPS)
        phi, eps = mp.mpf(case.phi), mp.mpf(case.eps)
        return y + eps * (mp.cos(phi) - mp.cos(phi + t)), vel + eps * mp.sin(phi + t)


def _drag_kappa(case: HardCase, tau) -> float:
    with mp.workdps(REFERENCE_DPS):
        slope = abs(_drag_point(case, tau)[1])
        num = abs(case.v) + tau + abs(case.eps) * (1 + abs(case.phi) + tau)
        return float(num / slope) if slope else math.inf


def _passed_a_root(case: HardCase, upper, tau_fast) -> bool:
    """tau_fast past the certified first root (``upper``) and past a later root's start: the gap
    rising at tau_fast, or positive at a grid point strictly between (exact mpf points)."""
    with mp.workdps(REFERENCE_DPS):
        if not tau_fast > upper:
            return False
        if _drag_point(case, tau_fast)[1] > 0:
            return True
        span = mp.mpf(tau_fast) - upper
        n = int(min(_MISS_GRID_POINTS, max(16, float(span) / _MISS_GRID_STEP)))
        return any(_drag_point(case, upper + span * j / n)[0] > 0 for j in range(1, n))


def dissipative_rows(cases=DISSIPATIVE_CASES) -> list[DissipativeRow]:
    """fastpath and verify on each case (module docstring); verify at REFERENCE_DPS."""
    rows = []
    for case in cases:
        physics = {"drag": case.drag, "drag_law": case.drag_law}
        start = time.perf_counter()
        try:
            cert = verify.certify_flight(case.phi, case.v, case.eps, dps=REFERENCE_DPS, **physics)
            tau, upper = cert.tau, cert.enclosure[1]
        except verify.UndecidableCollision:
            tau = upper = None
        seconds = time.perf_counter() - start
        res = fastpath.flight(case.phi, case.v, case.eps, **physics)
        status = fastpath.FlightStatus(res.status).name
        kappa = units = math.nan
        missed = False
        if tau is not None:
            kappa = _drag_kappa(case, tau)
            if status == "CONVERGED":
                with mp.workdps(REFERENCE_DPS):
                    units = float(abs(mp.mpf(res.tau) - tau) / (kappa * UNIT_ROUNDOFF * tau))
            if math.isfinite(res.tau):
                missed = _passed_a_root(case, upper, float(res.tau))
        rows.append(DissipativeRow(case, tau, upper, seconds, kappa, float(res.tau),
                                   int(res.iterations), status, units, missed))
    return rows


_UNDECIDED = ("UNCERTAIN", "MAX_ITERATIONS")


def _physics(case: HardCase) -> str:
    return "elastic" if case.drag == 0.0 else f"{case.drag_law} {case.drag:g}"


def _fast_cell(row: DissipativeRow) -> str:
    if row.missed:
        return "**missed**"
    if row.status == "CONVERGED":
        return "0" if row.units == 0 else f"{row.units:.2g}"
    return "-"


def dissipative_case_markdown(rows: list[DissipativeRow]) -> str:
    lines = [
        "### Dissipative hard cases (fastpath and verify only)",
        "",
        "Flights with drag or from a chattering sequence: drag grazes (the elastic grazes under "
        "drag 1e-8), departures at rest (w0 = 0 exactly), and chattering grazes (a small-w0 "
        "departure just before theta* = 2*pi - arccos(1/eps), where d'' changes sign: a dip "
        "right after the departure tuned at 60 digits to a clearance, `c=0+` / `c=0-` the "
        "float64 neighbours of the exact tangency). Only fastpath and verify model drag, so these "
        "rows are not in the table above or its figures. tau: verify.certify_flight at "
        f"{REFERENCE_DPS} digits (its time in seconds); kappa = (|v| + tau + |eps|*(1 + |phi| + "
        "tau))/|d'(tau)| with the drag flight's velocity in d' (verify.condition_number's scale, "
        "as tests/fastpath/drag_reference.py); fastpath (method auto): error of tau in units of "
        "kappa*u where CONVERGED, its iterations and status, **missed** if its tau lies past the "
        "first root and a later root's start.",
        "",
        "| case | class | phi | v | eps | physics | tau (verify) | verify [s] | kappa "
        "| fastpath err [kappa u] | iterations | status |",
        "|" + "---|" * 12,
    ]
    for row in rows:
        c = row.case
        tau = f"{float(row.tau):.10g}" if row.tau is not None else "undecidable"
        kappa = f"{row.kappa:.2g}" if math.isfinite(row.kappa) else "-"
        lines.append(
            f"| {c.id} | {c.kind} | {c.phi:.17g} | {c.v:.17g} | {c.eps:.17g} | {_physics(c)} "
            f"| {tau} | {row.seconds:.2f} | {kappa} | {_fast_cell(row)} | {row.iterations} "
            f"| {row.status} |")
    lines += ["", "| class | rows | CONVERGED | UNCERTAIN or MAX_ITERATIONS | other status "
              "| missed | worst err [kappa u] | verify undecidable | verify max [s] |",
              "|" + "---|" * 9]
    for kind in sorted({r.case.kind for r in rows}):
        group = [r for r in rows if r.case.kind == kind]
        done = [r.units for r in group if r.status == "CONVERGED" and math.isfinite(r.units)]
        worst = f"{max(done):.2g}" if done else "-"
        converged = sum(r.status == "CONVERGED" for r in group)
        uncertain = sum(r.status in _UNDECIDED for r in group)
        lines.append(
            f"| {kind} | {len(group)} | {converged} | {uncertain} "
            f"| {len(group) - converged - uncertain} | {sum(r.missed for r in group)} "
            f"| {worst} | {sum(r.tau is None for r in group)} "
            f"| {max(r.seconds for r in group):.2f} |")
    lines += ["", "NOT_DEPARTING on the departures at rest is by design: `fastpath.flight` takes "
              "w0 > 0 only (w0 = 0 is not a departure for it); a particle leaving "
              "the plate from rest is started inside the sticking kernels from a certified "
              "point (`fastpath.dissipative.sticking`). UNCERTAIN is fastpath "
              "saying that float64 cannot decide (verify settles those); on the chattering "
              "grazes it comes where the dip's clearance is within a few of fastpath's gap "
              "rounding bounds of zero (the c=0+/0- neighbours of the tangency, and c=-1e-14 or "
              "-1e-15: a shallow dip, d'' ~ sqrt(eps**2 - 1)*delta/2, lets a small slope pass "
              "for a graze). MAX_ITERATIONS (as UNCERTAIN) at w = 1e-9, c = 1e-16: the "
              "lower-bound steps crawl past the shallow dip and run out of their 60 iterations "
              "before the landing, on a flight float64 could decide (a known limitation, not a "
              "wrong answer).", ""]
    return "\n".join(lines)


def dissipative_case_section(cases=DISSIPATIVE_CASES) -> str:
    """The dissipative sub-table of the hard-case section."""
    return dissipative_case_markdown(dissipative_rows(cases))
