"""docs/claims.md's two generated sections, written from a report's ``report.json``:

* "The verdicts as they stand": the count of the paper's verdicts and one row per claim (its
  verdict, the kind of an inconclusive one, how many analyses of its family agree, our reading);
* "What moved and why": every claim whose rule changed after its verdict had been recorded,
  with that verdict (``BEFORE``: the report of commit ``BEFORE_COMMIT``, whose
  ``docs/report/report.json`` holds the old rules verbatim), what changed (``CHANGES``) and its
  verdict now; then the claims new to the register.

``python -m reports.paper.claims.page [REPORT_JSON [PAGE]]`` (defaults
docs/report/report.json and docs/claims.md) rewrites the two sections in place, leaving the
hand-written rest of the page as it is; run it after the report is rebuilt.
"""

from __future__ import annotations

import json
import sys
from collections import Counter
from pathlib import Path

from reports.runs import rundir

ROOT = Path(__file__).resolve().parents[3]
VERDICTS_HEADING = "## The verdicts as they stand"
MOVED_HEADING = "## What moved and why"
BEFORE_COMMIT = "dbd6435"

# The verdicts of the report before the families (report.json of BEFORE_COMMIT, 77 claims).
BEFORE = {
    "fig2-hole-phi_c=0": "confirmed", "fig2-hole-phi_c=0.5": "confirmed",
    "fig2-hole-phi_c=1": "confirmed", "fig2-hole-phi_c=1.5": "confirmed",
    "fig2-hole-phi_c=2": "confirmed", "fig2-hole-phi_c=2.5": "confirmed",
    "fig2-n-phi_c=0": "confirmed", "fig2-n-phi_c=0.5": "confirmed",
    "fig2-n-phi_c=1": "confirmed", "fig2-n-phi_c=1.5": "confirmed",
    "fig2-n-phi_c=2": "inconclusive", "fig2-n-phi_c=2.5": "inconclusive",
    "fig2-n-tail-phi_c=0": "inconclusive", "fig2-t-phi_c=0": "confirmed",
    "fig2-n-tail-phi_c=0.5": "confirmed", "fig2-t-phi_c=0.5": "confirmed",
    "fig2-n-tail-phi_c=1": "inconclusive", "fig2-t-phi_c=1": "confirmed",
    "fig2-n-tail-phi_c=1.5": "confirmed", "fig2-t-phi_c=1.5": "confirmed",
    "fig2-same-power-phi_c=0": "inconclusive", "fig2-bounded-velocity-phi_c=0": "inconclusive",
    "fig2-same-power-phi_c=0.5": "inconclusive",
    "fig2-bounded-velocity-phi_c=0.5": "inconclusive",
    "fig2-same-power-phi_c=1": "inconclusive", "fig2-bounded-velocity-phi_c=1": "inconclusive",
    "fig2-same-power-phi_c=1.5": "inconclusive",
    "fig2-bounded-velocity-phi_c=1.5": "inconclusive",
    "fig2-same-power-phi_c=2": "inconclusive", "fig2-bounded-velocity-phi_c=2": "confirmed",
    "fig2-same-power-phi_c=2.5": "inconclusive", "fig2-bounded-velocity-phi_c=2.5": "confirmed",
    "fig2-stages-phi_c=0": "confirmed", "fig2-stages-phi_c=0.5": "confirmed",
    "fig2-stages-phi_c=1": "confirmed", "fig2-stages-phi_c=1.5": "confirmed",
    "fig2-sea-slowed-phi_c=2": "confirmed", "fig2-sea-slowed-phi_c=2.5": "confirmed",
    "sec3-n-sqrt-t-phi_c=0": "inconclusive", "sec3-n-sqrt-t-phi_c=0.5": "inconclusive",
    "sec3-n-sqrt-t-phi_c=1": "inconclusive", "sec3-n-sqrt-t-phi_c=1.5": "inconclusive",
    "fermi-n": "confirmed", "fermi-t": "confirmed", "sec3-other-box": "refuted",
    "sec3-other-density": "inconclusive", "sec3-island-start": "confirmed",
    "sec3-destruction": "inconclusive", "intro-universal": "inconclusive",
    "sec4-holes": "confirmed", "sec4-hole-2": "inconclusive",
    "sec4-eventual-h=0.1": "confirmed", "sec4-eventual-h=0.4": "confirmed",
    "sec4-eventual-h=1": "confirmed", "sec4-eventual-h=2.2": "confirmed",
    "fig3-h=0.4": "confirmed", "fig3-trap-h=0.4": "confirmed", "fig3-h=1": "confirmed",
    "fig3-trap-h=1": "confirmed", "fig3-h=0.1": "confirmed", "fig3-h=2.2": "confirmed",
    "fig4-P11-time": "confirmed", "fig4-P11-collisions": "confirmed",
    "fig4-fewer-collisions": "inconclusive", "fig4-large-velocities": "inconclusive",
    "conclusion-asymmetry": "confirmed", "fig4-other-h=0.1": "refuted",
    "fig4-other-h=0.4": "inconclusive", "fig4-other-h=2.2": "confirmed",
    "sec2-fixed-elliptic": "confirmed", "sec2-fixed-hyperbolic": "confirmed",
    "sec2-period-two": "confirmed", "sec2-fermi-transition": "confirmed",
    "sec2-small-eps-bounded": "confirmed", "sec2-accelerator-modes": "confirmed",
    "sec2-normal-diffusion": "confirmed", "intro-lyapunov": "confirmed",
}

# Claims of the old register split in two (old id -> the ids now).
SPLIT = {"sec3-destruction": ("sec3-destroy-all", "sec3-effective-destruction"),
         "fig4-fewer-collisions": ("fig4-fewer-collisions-P12", "fig4-fewer-collisions-P21"),
         "fig4-large-velocities": ("fig4-large-velocities-P12", "fig4-large-velocities-P21")}

WIDENED = ("one window's interval widened by the half-range over its window family (start x "
           "10^(+-1/4), end x 10^(-1/4)) -> ")
# (claim ids starting with any of these, what changed in the rule)
CHANGES = (
    (("fig2-hole-", "sec4-holes", "sec4-hole-2"),
     "one strip of the phase space -> the hole's strip in two velocity periods (around (0, pi) "
     "and (0, 2 pi)), each a member"),
    (("fig2-n-phi_c=0", "fig2-n-phi_c=1", "fig2-t-"),
     WIDENED + "each window inside the intermediate regime (the regime's, its start a quarter "
     "decade later, its end a quarter decade earlier, both) a member with its own interval; "
     "the stretched law's chi^2/dof and p beside each"),
    (("fig2-n-phi_c=2",),
     WIDENED + "the late tail's windows only (starts moving later by quarter decades, never "
     "back into the transient), each a member"),
    (("fig2-n-tail-",),
     WIDENED + "'eventually' read as a limit: the latest three late-tail windows with 100 "
     "escapes, each a member"),
    (("fig2-same-power-",),
     "alpha_n against alpha_t on one matched window, widened -> level windows moving later, "
     "two metrics each (the exponents; the slope of matched quantiles against 1); where the "
     "intermediate continuous-time decay is itself algebraic (beta in the power-law cell) the "
     "matched levels start at the late tail's level (before: never, a power law extrapolated "
     "explaining every survivor)"),
    (("fig2-bounded-velocity-",),
     "one slope of t/n on n (sampled study) -> late windows from n_half, median and mean of t/n "
     "each, from the run's joint (n, t) record where it has one"),
    (("fig2-stages-",),
     "P against the sea holes with disjoint 95% bands at two points -> two parts ('slower at "
     "first', 'faster at intermediate times'), the escape-rate ratios at two points and the "
     "survival where the stage ends, against each sea hole"),
    (("fig2-sea-slowed-",),
     "one conjunction at one n -> two parts, each at n_tail and half a decade later, the "
     "ordering against each island hole"),
    (("sec3-n-sqrt-t-",),
     WIDENED + "a large-t statement: windows from later starts (the latest three with 100 "
     "escapes), median and mean of n each, from the run's joint record where it has one"),
    (("fermi-",), WIDENED + "each window inside the diffusive regime a member with its own "
     "bootstrap interval"),
    (("sec3-other-",),
     "every hazard ratio over the late tail, one interval outside the bounds refuting -> 'at "
     "long times' read as a limit: the late tail's later windows, one part per hole and clock"),
    (("sec3-island-start",),
     "one conjunction over the last two decades -> two parts, each over the last two decades "
     "and the last two half decades"),
    (("sec3-destruction",),
     "one conjunction -> two claims: 'may destroy all' (sec3-destroy-all) and 'effective "
     "destruction' (sec3-effective-destruction), each with its own family"),
    (("intro-universal",),
     "pairs of exponents on windows reaching back to the transient -> the late-tail windows of "
     "every hole compared rank by rank"),
    (("sec4-eventual-",), "both entry holes together -> one part per entry hole, each read in "
     "both clocks' records"),
    (("fig3-h=0.4", "fig3-h=1"),
     "the time ratio at one level -> two metrics (the same level, the same time) at two levels"),
    (("fig3-trap-", "fig3-h=0.1"),
     "the share at the long-lived time -> the long-lived time and later times a quarter decade "
     "apart while 381 entrants of hole 1 remain"),
    (("fig3-h=2.2",), "one decay -> both entry holes, the decay's end read from 10^-1 and from "
     "10^-2"),
    (("fig4-P11-",),
     "one window: the selection and the residual excess -> the long-lived regime's late "
     "windows, each with the selection, the residual excess and Pearson's chi-squared"),
    (("fig4-fewer-collisions",),
     "the transporting curves pooled, one metric -> per curve (P_12, P_21), at the same level "
     "(top decades, tail) and at the same time, from the run's joint record where it has one"),
    (("fig4-large-velocities",),
     "the transporting curves pooled -> per curve (P_12, P_21), a sampled study and its "
     "replica, with the orbits expected beyond the threshold at the sample's size"),
    (("conclusion-asymmetry",),
     "the selection alone for the form -> each late window's selection and Pearson's "
     "chi-squared (a likelihood ratio does not say the law fits); the asymmetry as fig3-h=W"),
    (("fig4-other-h=",),
     "D over the top four decades -> the clocks' difference read in the top decades and at "
     "the tail levels 100/N and 1000/N, each a member"),
    (("sec2-normal-diffusion",),
     "|mu - 1| within 0.1 + 1.96 sigma + the window half-range -> each window past the "
     "transient (n0 >= the study's family_from) within 10% of 1 by its own 1.96 sigma; "
     "decided in the register"),
    (("sec2-", "intro-lyapunov"),
     "decided inline in the dynamics section -> through the register: each certified orbit, "
     "band, simulation, checkpoint or window a member"),
)


def change_of(claim_id):
    """What changed in the rule of an old claim (``CHANGES``); ValueError if none is recorded."""
    for prefixes, text in CHANGES:
        if claim_id.startswith(prefixes):
            return text
    raise ValueError(f"{claim_id}: no change recorded for a claim of the old register")


def _cell(text):
    return str(text).replace("|", "&#124;").replace("\n", " ")


def _now(claims, claim_id):
    ids = SPLIT.get(claim_id, (claim_id,))
    out = []
    for i in ids:
        c = claims.get(i)
        if c is None:
            out.append(f"{i}: not in the report")
            continue
        kind = f" ({c['inconclusive']})" if c.get("inconclusive") else ""
        out.append((f"{i}: " if len(ids) > 1 else "") + f"{c['verdict']}{kind}")
    return "; ".join(out)


def _agree(c):
    members = c.get("analyses") or []
    same = sum(a["verdict"] == c["verdict"] for a in members)
    return f"{same} of {len(members)}"


def verdicts_section(report):
    """The verdict table of the paper's claims in ``report`` (report.json's dict)."""
    paper = [c for c in report["claims"] if c["source"] == "paper"]
    counts = Counter(c["verdict"] for c in paper)
    kinds = Counter(c["inconclusive"] for c in paper if c.get("inconclusive"))
    rows = [f"| {c['id']} | **{c['verdict']}** | {c.get('inconclusive') or ''} | {_agree(c)} "
            f"| {_cell(c['statement'])} |" for c in paper]
    return "\n".join([
        VERDICTS_HEADING, "",
        f"From `docs/report/report.json` (built {report.get('built', 'unknown')}): "
        f"{len(paper)} claims of the paper, {counts['confirmed']} confirmed, "
        f"{counts['refuted']} refuted, {counts['inconclusive']} inconclusive ("
        + ", ".join(f"{kinds[k]} {k}" for k in ("data", "between-bounds", "analysis"))
        + "). A verdict is the agreement of the claim's family of analyses; 'agree' counts "
        "the members that give the claim's verdict. Each claim's quote, family, rule, "
        "members and evidence are in `docs/report/report.md`.", "",
        "| claim | verdict | inconclusive | agree | our reading |", "|---|---|---|---|---|",
        *rows, ""])


def moved_section(report):
    """Every old claim's verdict before its rule changed, the change and its verdict now; the
    claims new to the register."""
    claims = {c["id"]: c for c in report["claims"]}
    rows = []
    for cid, before in BEFORE.items():
        now = _now(claims, cid)
        verdicts = {claims.get(i, {}).get("verdict") for i in SPLIT.get(cid, (cid,))}
        moved = "" if verdicts == {before} else " (moved)"
        rows.append(f"| {cid} | {before} | {_cell(now)}{moved} | {_cell(change_of(cid))} |")
    old_ids = set(BEFORE) | {i for ids in SPLIT.values() for i in ids}
    new = [c for c in report["claims"] if c["source"] == "paper" and c["id"] not in old_ids]
    new_rows = [f"| {c['id']} | **{c['verdict']}** | {c.get('inconclusive') or ''} |"
                for c in new]
    return "\n".join([
        MOVED_HEADING, "",
        "Every rule below was changed after its verdict had been recorded: a verdict became "
        "the agreement of the family of analyses the words allow, instead of one analysis "
        "(possibly widened by others). The verdict before is that of the report of commit "
        f"`{BEFORE_COMMIT}` (its `docs/report/report.json` holds the old rules verbatim); the "
        "verdict now is that of the report above. The families are declared in the register "
        "(`family`) and are the same for every hole of a figure.", "",
        "| claim | verdict before | verdict now | what changed in the rule |",
        "|---|---|---|---|", *rows, "",
        f"Claims new to the register ({len(new)}), each quoted verbatim and decided by its "
        "family from the start:", "",
        "| claim | verdict | inconclusive |", "|---|---|---|", *new_rows, ""])


def rewrite(page_text, report):
    """``page_text`` with its two generated sections replaced (appended where missing)."""
    sections = {VERDICTS_HEADING: verdicts_section(report), MOVED_HEADING: moved_section(report)}
    lines = page_text.splitlines()
    out, i, done = [], 0, set()
    while i < len(lines):
        heading = lines[i].strip()
        if heading in sections:
            out += sections[heading].splitlines()
            done.add(heading)
            i += 1
            while i < len(lines) and not lines[i].startswith("## "):
                i += 1
            continue
        out.append(lines[i])
        i += 1
    for heading, text in sections.items():
        if heading not in done:
            out += ["", *text.splitlines()]
    return "\n".join(out).rstrip("\n") + "\n"


def main(argv=None):
    args = sys.argv[1:] if argv is None else argv
    report_path = Path(args[0]) if args else ROOT / "docs" / "report" / "report.json"
    page = Path(args[1]) if len(args) > 1 else ROOT / "docs" / "claims.md"
    report = json.loads(report_path.read_text(encoding="utf-8"))
    rundir.write_atomic(page, rewrite(page.read_text(encoding="utf-8"), report))
    print(f"{page}: verdicts and what moved written from {report_path}")


if __name__ == "__main__":
    main()
