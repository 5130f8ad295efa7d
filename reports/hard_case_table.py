"""Stability on hard cases: each method's error, iterations and status on departures that break
naive solvers.

The cases (built here, from the issue's description): small departure speeds w0 = 1e-3..1e-12,
huge v up to 1e6, eps across {1e-8, 0.2429, 0.6, 0.999999, 1, 1.000001, 3, 100}, phases at and
next to 0 and pi, unreduced phases (1e6 + 0.3), and eps > 1 near-grazing pairs at several
clearances (``verify.grazing_contact``; negative clearance: two close roots just before the
contact time T, positive: the particle passes above the plate at T and lands later).
"""

from __future__ import annotations

import math
from pathlib import Path

from reports.methods import default_methods
from reports.work_precision import (
    Case,
    Error,
    departure_with_w0,
    evaluate,
    grazing_case,
)

EPS_SWEEP = (1e-8, 0.2429, 0.6, 0.999999, 1.0, 1.000001, 3.0, 100.0)


def hard_cases(quick: bool = False) -> list[Case]:
    """The hard cases (about 60; a dozen with ``quick``)."""
    cases: list[Case] = []

    def add(phi, v, eps, label):
        cases.append(Case(float(phi), float(v), float(eps), label, "hard"))

    small_w0 = (1e-3, 1e-12) if quick else (1e-3, 1e-6, 1e-9, 1e-12)
    for w0 in small_w0:
        add(4.0, departure_with_w0(4.0, w0, 0.6), 0.6, f"w0={w0:.0e}, phi=4, eps=0.6")
        add(0.0, w0, 0.6, f"w0={w0:.0e}, phi=0, eps=0.6")
        if not quick:
            add(4.0, departure_with_w0(4.0, w0, 3.0), 3.0, f"w0={w0:.0e}, phi=4, eps=3")
    huge = ((1e6, 0.6), (1e6, 3.0)) if quick else (
        (1e5, 0.6), (1e6, 0.6), (1e6, 1e-8), (1e6, 3.0), (1e6, 100.0), (1e5, 0.999999))
    for v, eps in huge:
        add(1.0, v, eps, f"v={v:.0e}, eps={eps!r}")
    sweep = (0.6, 1.0, 3.0) if quick else EPS_SWEEP
    for eps in sweep:
        add(0.5, 0.5, eps, f"eps={eps!r}, phi=0.5, v=0.5")
        if not quick:
            add(2.0, 3.0, eps, f"eps={eps!r}, phi=2, v=3")
    phases = {"phi=0": 0.0, "phi=pi": math.pi, "phi=nextafter(pi,0)": math.nextafter(math.pi, 0),
              "phi=nextafter(pi,4)": math.nextafter(math.pi, 4),
              "phi=nextafter(2pi,0)": math.nextafter(2 * math.pi, 0),
              "phi=5e-324": 5e-324}
    for label, phi in list(phases.items())[: 2 if quick else None]:
        add(phi, 1.0, 0.6, f"{label}, v=1, eps=0.6")
        if not quick:
            add(phi, 1.0, 3.0, f"{label}, v=1, eps=3")
    for phi in (1e6 + 0.3,) if quick else (1e3 + 0.3, 1e6 + 0.3, -1e6 + 0.3):
        add(phi, 2.5, 0.6, f"phi={phi:g}, v=2.5, eps=0.6")
        if not quick:
            add(phi, 2.5, 3.0, f"phi={phi:g}, v=2.5, eps=3")
    clearances = (-1e-2, -1e-8, 1e-8) if quick else (-1e-2, -1e-5, -1e-8, -1e-11, -1e-14, 1e-14,
                                                     1e-11, 1e-8, 1e-5)
    for eps, psi, t_guess in ((3.0, 0.1, 6.0),) if quick else ((3.0, 0.1, 6.0), (1.5, 0.2, 6.0),
                                                               (100.0, 0.5, 20.0)):
        for c in clearances:
            case = grazing_case(eps, psi, t_guess, c, f"graze eps={eps:g}, clearance={c:+.0e}")
            if case is not None:
                cases.append(Case(case.phi, case.v, case.eps, case.label, "hard", case.contact,
                                  case.clearance))
    return cases


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
