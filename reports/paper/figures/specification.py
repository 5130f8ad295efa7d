"""Specification plots: the family of analyses of each contested claim, one PNG per claim.

A claim is contested when it is not confirmed by every member of its family: its verdict is
refuted or inconclusive, or its members do not all give the same verdict. Its plot shows, per
part of the claim and per measured quantity, every member's figure with its interval (a dot and
a bar, coloured by the member's verdict), over the word's zones: where the word clearly holds
(green) and where it clearly fails (red); between them the word is fuzzy. Drawn from the claims'
JSON form (``report.json``), so the plot shows exactly what decided each verdict.
"""

from __future__ import annotations

import math
from pathlib import Path

from reports.paper.claims.claim import CONFIRMED, INCONCLUSIVE, REFUTED, verdict_text
from reports.paper.figures.style import pyplot

FOLDER = "specification"
COLOURS = {CONFIRMED: "tab:green", REFUTED: "tab:red", INCONCLUSIVE: "tab:grey"}
LABEL_CHARS = 70


def contested(claim):
    """True if a claim (JSON form) is not confirmed by every member of its family."""
    said = {a["verdict"] for a in claim["analyses"]}
    return claim["verdict"] != CONFIRMED or len(said) > 1


def file_stem(claim_id):
    return "spec_" + "".join(ch if ch.isalnum() or ch in "-." else "_" for ch in claim_id)


def _finite(x):
    try:
        return math.isfinite(float(x))
    except (TypeError, ValueError):
        return False


def _groups(claim):
    """{(part, quantity): [members]} in order."""
    out = {}
    for a in claim["analyses"]:
        out.setdefault((a.get("part", ""), a["figure"]["quantity"]), []).append(a)
    return out


def _label(text):
    return text if len(text) <= LABEL_CHARS else text[:LABEL_CHARS - 3] + "..."


def _limits(members):
    values = []
    for a in members:
        values += [v for v in (a["figure"]["value"], *a["figure"]["interval"]) if _finite(v)]
        values += [v for v in a["bounds"]["holds"] if _finite(v)]
        for zone in a["bounds"]["fails"]:
            values += [v for v in zone if _finite(v)]
    if not values:
        return -1.0, 1.0, False
    lo, hi = min(values), max(values)
    log = lo > 0 and hi / lo > 100
    if log:
        return lo / 2, hi * 2, True
    pad = 0.1 * (hi - lo) if hi > lo else max(abs(hi), 1.0) * 0.1
    return lo - pad, hi + pad, False


def _draw_group(ax, members, title):
    lo, hi, log = _limits(members)
    if log:
        ax.set_xscale("log")
    a0 = members[0]
    h0, h1 = (float(v) for v in a0["bounds"]["holds"])
    if h0 < h1:
        ax.axvspan(max(h0, lo), min(h1, hi), color="tab:green", alpha=0.12, lw=0)
    for z0, z1 in a0["bounds"]["fails"]:
        z0, z1 = float(z0), float(z1)
        if z0 < z1:
            ax.axvspan(max(z0, lo), min(z1, hi), color="tab:red", alpha=0.12, lw=0)
    for bound in {h0, h1} | {float(v) for z in a0["bounds"]["fails"] for v in z}:
        if _finite(bound) and lo < bound < hi:
            ax.axvline(bound, color="k", lw=0.6, ls="--")
    for i, a in enumerate(members):
        f = a["figure"]
        y = len(members) - 1 - i
        colour = COLOURS[a["verdict"]]
        v0, v1 = f["interval"]
        if _finite(v0) and _finite(v1):
            ax.plot([max(float(v0), lo), min(float(v1), hi)], [y, y], color=colour, lw=2)
        if _finite(f["value"]):
            ax.plot([min(max(float(f["value"]), lo), hi)], [y], "o", color=colour, ms=4)
        else:
            ax.text(lo, y, " " + (a.get("note") or "not measured"), fontsize=6, va="center",
                    color=colour)
    ax.set_xlim(lo, hi)
    ax.set_ylim(-0.7, len(members) - 0.3)
    ax.set_yticks(range(len(members)))
    ax.set_yticklabels([_label(a["variant"]) for a in reversed(members)], fontsize=6)
    ax.set_title(title, fontsize=8)


def specification_figure(claim, out_dir):
    """The specification plot of one claim (JSON form) as ``out_dir/specification/<stem>.png``
    and ``.pdf`` (like every figure of the report); returns the PNG's path relative to
    ``out_dir``."""
    plt = pyplot()
    groups = _groups(claim)
    heights = [0.8 + 0.28 * len(m) for m in groups.values()]
    fig, axes = plt.subplots(len(groups), 1, figsize=(9, 0.9 + sum(heights)), squeeze=False,
                             gridspec_kw={"height_ratios": heights})
    for ax, ((part, quantity), members) in zip(axes[:, 0], groups.items(), strict=True):
        _draw_group(ax, members, f"{part + ': ' if part else ''}{quantity}")
    fig.suptitle(f"{claim['id']}: {verdict_text(claim)} (green: the word holds, red: it "
                 "fails; dots: members, coloured by their verdicts)", fontsize=8)
    fig.tight_layout(rect=(0, 0, 1, 0.97))
    folder = Path(out_dir) / FOLDER
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / f"{file_stem(claim['id'])}.png"
    fig.savefig(path, dpi=110)
    fig.savefig(path.with_suffix(".pdf"))
    plt.close(fig)
    return f"{FOLDER}/{path.name}"


def specification_markdown(claims, out_dir):
    """Draw the plot of every contested claim with analyses; return the Markdown that shows
    them (a line per claim with its verdict and image)."""
    lines = []
    for c in claims:
        if c["analyses"] and contested(c):
            image = specification_figure(c, out_dir)
            lines += [f"**{c['id']}** ({verdict_text(c)}, {len(c['analyses'])} analyses):", "",
                      f"![family of {c['id']}]({image})", ""]
    if not lines:
        return ""
    return "\n".join(["### The families of the contested claims", "",
                      "Every claim that is not confirmed by all of its analyses, with each "
                      "analysis's figure and interval over the word's bounds "
                      "(`reports/paper/figures/specification.py`).", "", *lines])
