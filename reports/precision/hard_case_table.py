"""Stability on hard cases: each method's error, iterations and status on departures that break
naive solvers.

The cases are ``verify.hard_cases.HARD_CASES``, the one table the property tests also check:
small departure speeds w0 = 1e-3..1e-12, huge v up to 1e6, eps across {1e-8, 0.2429, 0.6,
0.999999, 1, 1.000001, 3, 100}, phases at and next to 0 and pi, unreduced phases, and eps > 1
near-grazing pairs at several clearances (negative clearance: two close roots just before the
contact time T; positive: the particle passes above the plate at T and lands later).
"""

from __future__ import annotations

import math
from pathlib import Path

from reports.precision.cases import hard_cases
from reports.precision.methods import default_methods
from reports.precision.work_precision import Error, evaluate


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
