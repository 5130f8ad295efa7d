"""Physics checks against published results, as a Markdown table for the report.

Rows (quantity, measured +- uncertainty, expected, method, agrees?):

1. Fermi acceleration at eps = 0.6 from chaotic-sea starts (the paper's escape box
   3.85 < phi < 4.15, 2 < v < 4, no holes): <v_n> ~ n**(1/2) per collision and <v(t)> ~ t**(1/3)
   in continuous time (v(t) = the velocity after the last collision at or before t). Slopes of
   log<v> against log n (log t) over a window at large n (t), the uncertainty the standard
   deviation over a bootstrap of the particle blocks of ``fastpath.kernels.moments``.
The stretched exponent of the escape survival is not here: it is a claim of the paper, decided
on its regime by maximum likelihood (claims fig2-t-*, ``reports.paper.claims.escape_claims``).

2. The rotation angle of small oscillations around the elliptic fixed point (phi, v) = (0, pi):
   cos(theta) = 1 - 2*eps (the linearisation of the fixed point, docs/model.md). From an orbit
   started 1e-5 above the fixed point, the 2x2 matrix M with x_{k+1} = M x_k is fitted to the
   deviations by least squares and cos(theta) = tr(M)/2; the uncertainty is the change when the
   start is moved 2e-5 away (nonlinear terms), plus rounding.
3. Velocity diffusion at large eps: <(v_n - v_0)**2>/n -> 2 eps**2 C(4 eps) with the
   Rechester-White factor C(K) = 1 - 2 J2 - 2 J1**2 + 2 J2**2 + 2 J3**2 (the Holmes map is the
   standard map in I = 2v with K = 4 eps; the exact map approaches it as v grows), for the exact
   and the Holmes map, random phases and v0 in [1000, 1000 + pi). Uncertainty: the spread over
   particle blocks. The formula drops terms of third order in the Bessel functions, relative size
   about (2/(pi K))**1.5; "agrees" allows 3 sigma plus that. eps values are checked to lie outside
   the period-1 accelerator-mode windows 2 pi m <= K <= sqrt((2 pi m)**2 + 16) and D(n) to be flat
   in n (an accelerator mode makes it grow linearly).

Collisions of the moment ensembles are spot-checked by ``verify``
(``reports.runs.chunk.check_sample`` from the same float64 states).
"""

from __future__ import annotations

import math
import time
from pathlib import Path

from reports.paper.checks.diffusion import DIFFUSION_V0, diffusion_checks, rechester_white
from reports.paper.checks.fermi import fermi_checks
from reports.paper.checks.physics_table import physics_table
from reports.paper.checks.rotation import rotation_checks
from reports.paper.studies.fermi_ensemble import fermi_ensemble
from reports.paper.studies.paper_runs import say_nothing
from reports.paper.studies.sampling import verified_text


def physics_checks_section(out_dir, quick=False, echo=None) -> str:
    """Markdown with the physics-check table."""
    echo = echo or say_nothing
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    echo("physics checks: Fermi acceleration ensemble (eps = 0.6)")
    fermi = fermi_ensemble(bool(quick))
    rows = fermi_checks(fermi)
    echo("physics checks: rotation angle at the elliptic fixed point")
    rows += rotation_checks()
    diff_rows, diff_results = diffusion_checks(quick, echo)
    rows += diff_rows
    seconds = time.perf_counter() - t0
    md = [
        "## Physics checks against published results",
        "",
        "Measured quantities against the values the literature (and the paper) predict. "
        "`+-` is one standard error (method column says how it is estimated); \"agrees\" means "
        "within 3 standard errors (plus, for the diffusion coefficient, a rough estimate "
        "(2/(pi K))^1.5 of the Rechester-White formula's truncation error).",
        "",
        physics_table(rows),
        "",
        f"Fermi ensemble: {fermi.particles} particles, {fermi.collisions} collisions, "
        f"{fermi.flagged} stopped at undecidable flights; {verified_text(fermi.verification)}.",
        "",
    ]
    devs = ", ".join(f"{100 * (r.d / (2 * r.eps**2 * rechester_white(4 * r.eps)) - 1):+.1f}% "
                     f"(+- {100 * r.d_err / (2 * r.eps**2 * rechester_white(4 * r.eps)):.1f}%) "
                     f"at K = {4 * r.eps:g}" for r in diff_results if r.model == "holmes")
    resolve = []
    for e, h in zip(diff_results[::2], diff_results[1::2], strict=True):
        rel = math.hypot(e.d_err, h.d_err) / h.d  # relative uncertainty of D(exact) - D(Holmes)
        resolve.append(f"{rel:.1%} at eps = {e.eps:g} (v below about {e.eps / rel:.0f})")
    md += [f"Diffusion: the Holmes map is the standard map in I = 2v, so its D tests "
           "Rechester and White's C(K) = 1 - 2 J2(K) - 2 J1(K)^2 + 2 J2(K)^2 + 2 J3(K)^2 (five "
           f"terms, K = 4 eps) directly: {devs}. Where those deviations exceed the rough "
           "truncation estimate the \"no\" is the formula's (terms of higher order in the "
           "Bessel functions), not the integrator's; the integrator is judged by the "
           "D(exact) - D(Holmes) rows. Those rows can tell the exact map from Holmes's only "
           "where their O(eps/v) relative difference exceeds the relative uncertainty of "
           f"D(exact) - D(Holmes): {', '.join(resolve)}; at v0 = {DIFFUSION_V0:g} they agree "
           "within it, as they should.", ""]
    md.append(f"(physics checks: {seconds:.0f} s)")
    md.append("")
    return "\n".join(md)
