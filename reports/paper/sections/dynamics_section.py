r"""The report's dynamics section: the paper's Section 2 statements and its Lyapunov remark.

``dynamics_section(out_dir, quick, echo)`` reads the committed study
``reports/paper/studies/dynamics_study.json``, installed with the package
(``scripts/dynamics_study.py`` writes it, in about 25 minutes; ``docs/report/dynamics/study.json``
links to it), and re-checks a sample of it here (certified orbits recomputed, float crossings
and the first collisions of the Lyapunov orbits recomputed bit for bit); without the file it
computes the
study (``QUICK`` sizes with ``quick``). A failed re-check turns the claims resting on that part
``inconclusive``. It writes four figures and returns the markdown and the claims (``Claim``s of
the register, decided in ``reports.paper.claims.dynamics_claims``).
"""

from __future__ import annotations

import json
import math
import time
from dataclasses import asdict
from pathlib import Path

import numpy as np

import verify
from fastpath import dynamics as fd
from reports.paper.claims.claim import verdict_text
from reports.paper.claims.dynamics_claims import dynamics_claims
from reports.paper.figures.dynamics_diffusion import diffusion_figure
from reports.paper.figures.dynamics_eps_c import eps_c_figure
from reports.paper.figures.dynamics_lyapunov import lyapunov_figure
from reports.paper.figures.dynamics_residue import residue_figure
from reports.paper.studies.dynamics_study import (
    COMMITTED,
    FULL,
    K_C_QUARTER,
    QUICK,
    period_two_start,
    run,
)
from reports.paper.studies.sampling import ESCAPE_BOX

STUDY = COMMITTED
RUN = STUDY.relative_to(STUDY.parents[3]).as_posix()  # as the report names it

# --- loading and re-checking -------------------------------------------------------------------

def load_study(quick, echo):
    """(study, source): the committed study, or one computed now."""
    if STUDY.exists():
        return json.loads(STUDY.read_text(encoding="utf-8")), RUN
    echo("dynamics: no committed study; computing the "
         + ("quick" if quick else "full (~10 min)") + " one")
    return run(QUICK if quick else FULL, echo), None


def recheck(study, quick):
    """Recompute a sample of the study; {part: (ok, text)}."""
    out = {}
    start = time.perf_counter()
    row = study["fixed_points"]["rows"][0]
    orbit = verify.periodic_orbit(0.0, math.pi * row["m"], row["eps"], 1)
    ok = _overlaps(orbit.trace, row["trace"]) and orbit.stability == row["stability"]
    out["fixed_points"] = (ok, f"fixed point m={row['m']}, eps={row['eps']} re-certified")
    branch = study["period_two"]["branches"][0]
    cert = branch["certified"][0]
    s = period_two_start(cert["eps"])
    orbit = verify.periodic_orbit(s, math.pi * branch["m"] - s, cert["eps"], 2)
    ok = _overlaps(orbit.residue, cert["residue"]) and orbit.stability == cert["stability"]
    out["period_two"] = (ok, f"period-2 orbit m={branch['m']}, eps={cert['eps']} re-certified")
    row = next(r for r in study["critical"]["rows"] if r["band"] == 1 and r["prefix"] == [2])
    stored = row.get("float_crossings", row["crossings"])  # the float64 ones
    levels = min(len(stored), 8 if quick else len(stored))
    again = fd.critical_amplitude(1, (2,), levels=levels)
    diffs = [abs(a.eps - b) for a, b in zip(again.crossings, stored, strict=False)]
    ok = max(diffs) <= 1e-9
    out["critical"] = (ok, f"band 1 (omega = 1.382) crossings of {levels} approximants "
                           f"recomputed, largest difference {max(diffs):.1e}")
    lyap = study["lyapunov"]
    rng = np.random.default_rng(lyap["seed"])
    (p0, p1), (v0, v1) = ESCAPE_BOX
    early = np.array(lyap["first_orbits_early"])
    phi, v = rng.uniform(p0, p1, lyap["orbits"] + lyap["stopped"]), None
    v = rng.uniform(v0, v1, len(phi))
    points = lyap["checkpoints"][: early.shape[1]]
    n_early = points[-1]
    mine = fd.lyapunov(phi[: len(early)], v[: len(early)], lyap["eps"], n_early,
                       checkpoints=points)
    got = mine.running_per_collision
    worst = float(np.max(np.abs(got - early)))
    out["lyapunov"] = (worst <= 1e-8, f"first {n_early} collisions of {len(early)} Lyapunov "
                                      f"orbits recomputed, largest difference {worst:.1e}")
    if not quick:
        cc = study["certified_crossings"]
        if cc:
            c = min(cc, key=lambda r: r["period"])
            guess = fd.symmetric_orbit(c["point"][1]["lo"], c["eps"], c["period"], c["winding"])
            orbit = verify.periodic_orbit(float(guess.phi[0]), float(guess.v[0]), c["eps"],
                                          c["period"], winding=c["winding"])
            ok = _overlaps(orbit.residue, c["residue"])
            out["certified_crossings"] = (ok, f"period-{c['period']} orbit of band {c['band']} "
                                              f"at eps={c['eps']:.9f} re-certified")
    out["seconds"] = (True, f"{time.perf_counter() - start:.1f} s")
    return out


def _overlaps(enclosure, stored):
    return float(enclosure.lo) <= stored["hi"] and stored["lo"] <= float(enclosure.hi)


# --- claims ------------------------------------------------------------------------------------

def claims_of(study, run_name, checks):
    """All claims, through the register (``reports.paper.claims.dynamics_claims``); those resting
    on a part whose re-check failed cannot be decided."""
    return dynamics_claims(study, run_name, checks)


# --- markdown ----------------------------------------------------------------------------------

def _table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(lines)


def markdown(study, claims, checks, images, source):
    crit = study["critical"]
    lines = ["## Dynamics: periodic orbits, stability, Lyapunov exponents, Fermi acceleration",
             "",
             "Certified (interval proofs, `verify.periodic_orbit`): the fixed points, the period-2 "
             "orbits, the accelerator modes and the Greene orbits in the table of certified "
             "crossings. Computed in float64 (not proved): the residue curves, Greene's eps_c "
             "(approximants up to period "
             f"{max(max(r['periods']) for r in crit['rows'])}), the Lyapunov exponents, the "
             "diffusion exponents and the accelerator search.",
             "",
             f"Data: {source or 'computed for this report'}; study time "
             f"{study['seconds']:.0f} s. Re-checked here: "
             + "; ".join(f"{text} ({'ok' if ok else 'FAILED'})"
                         for part, (ok, text) in checks.items() if part != "seconds")
             + f" [{checks['seconds'][1]}].", ""]
    lines += [f"![residue against eps]({images['residue']})", ""]
    rows = []
    for b in study["period_two"]["branches"]:
        changes = ", ".join(f"R={c['level']:g} {c['direction']} at {c['eps']:.6f}"
                            for c in b["changes"])
        cert = ", ".join(f"{c['eps']:.4g}: {c['stability']}" for c in b["certified"])
        rows.append([b["model"], b["m"], changes or "-", cert or "-"])
    lines += ["Period-2 orbits (s, pi m - s), (-s, pi m + s), eps sin s = s:", "",
              _table(["map", "m", "stability changes (float64)", "certified"], rows), ""]
    lines += [f"![eps_c against velocity band]({images['eps_c']})", ""]
    best = {b["band"]: b for b in crit["band_max"]}
    rows = []
    for j in sorted({r["band"] for r in crit["rows"]}):
        g = next((r for r in crit["rows"] if r["band"] == j and r["prefix"] == []), None)
        g2 = next((r for r in crit["rows"] if r["band"] == j and r["prefix"] == [2]), None)
        sim = [s for s in study["crossing_simulation"] if s["band"] == j]
        sim_text = ", ".join(f"{s['factor']:g}: {s['crossed']}/{s['particles']}" for s in sim)
        rows.append([j, f"{g['eps_c']:.9f} +- {g['uncertainty']:.1e}" if g else "-",
                     f"{g2['eps_c']:.9f} +- {g2['uncertainty']:.1e}" if g2 else "-",
                     f"{best[j]['eps_c']:.9f} (omega {best[j]['omega']:.3f})",
                     f"{K_C_QUARTER:.9f}", sim_text or "-"])
    lines += ["eps_c per velocity band j (Greene's criterion with the critical residue R_c, "
              "the crossings' Aitken extrapolation; float64 to period 987, the last levels of "
              "the golden pairs of bands 1 and 10 and of the Holmes map in multiprecision); "
              "Holmes map = standard map, "
              "K_c/4 in every band (computed: "
              + ", ".join(f"{h['eps_c']:.10f} +- {h['uncertainty']:.1e}" for h in crit["holmes"])
              + "); simulation: orbits crossing the band within the stated collisions at "
              "factor x the band's largest eps_c:", "",
              _table(["band j", "omega = j+0.618", "omega = j+0.382", "largest found",
                      "Holmes map", "crossed (factor: k/N)"], rows), ""]
    cc = study["certified_crossings"]
    if cc:
        rows = [[c["band"], "j+" + ("0.618" if c["prefix"] == [] else "0.382"), c["period"],
                 f"{c['eps']:.9f}", c["side"],
                 f"[{c['residue']['lo_str'][:14]}, {c['residue']['hi_str'][:14]}]",
                 "yes" if c["decided"] else "**no**", c["dps"], f"{c['seconds']:.1f}"]
                for c in cc]
        lines += ["Greene orbits certified on both sides of their crossing of R_c:", "",
                  _table(["band", "omega", "period", "eps", "side", "residue enclosure",
                          "decided", "digits", "s"], rows), ""]
    lines += [f"![Lyapunov exponents]({images['lyapunov']})", "",
              f"![velocity diffusion]({images['diffusion']})", ""]
    acc = study["accelerator"]
    rows = [[s["period"], s["first"]["eps"] if s["first"] else "none",
             f"{s['first_elliptic']['eps']} (R = {s['first_elliptic']['residue']:.3f})"
             if s["first_elliptic"] else "none"] for s in acc["search"]]
    lines += ["Accelerator blocks of the Holmes map (standard-map form) found by Newton from a "
              f"{acc['search_grid']}^2 grid, eps scanned {acc['search_eps']} (first eps found):",
              "", _table(["period", "any", "elliptic"], rows), "", "### Claims", ""]
    for c in claims:
        lines += [f"- **{c.id}** ({verdict_text(asdict(c))}): {c.statement}. {c.evidence}"]
    return "\n".join(lines) + "\n"


def dynamics_section(out_dir, quick=False, echo=print):
    """Write the figures into ``out_dir``; return (markdown, claims)."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    study, source = load_study(quick, echo)
    checks = recheck(study, quick)
    echo(f"dynamics: re-checks {'ok' if all(ok for ok, _ in checks.values()) else 'FAILED'}")
    images = {}
    for name, draw in (("residue", residue_figure), ("lyapunov", lyapunov_figure),
                       ("eps_c", eps_c_figure), ("diffusion", diffusion_figure)):
        images[name] = draw(study, out_dir)[0].name
    claims = claims_of(study, source, checks)
    return markdown(study, claims, checks, images, source), claims


__all__ = ["dynamics_section"]
