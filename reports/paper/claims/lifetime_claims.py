"""Transport claims beyond the paper's four widths (Section 4): the hole in the elliptic region
traps the long-lived orbits "while reducing the lifetime of orbits near the large island", for
h = 0.4 and 1 "(and many not shown)".

* Reducing the lifetime: starts on the large island (the box of scene escape-island-start,
  classified by their orbits, ``reports.paper.studies.islands``; and the same box a period pi
  higher, around (0, 2 pi)) followed with the two holes of width h at 0 and pi
  (``reports.paper.studies.follow``) up to the long-lived time of the transport run (its entrants of
  hole 1 fall to ``rules.LONG_LIVED_LEVEL``): the share still inside. Without a hole an island
  orbit never leaves.
* Many not shown: the trapping and the "very strong P_11" rules (``transport_claims``) on a
  sweep of widths between the paper's 0.1 and 2.2 (``SWEEP_WIDTHS``, scene text
  ``sweep_scene``); the share of widths that give each.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from fastpath.arithmetic.phase import TWO_PI
from reports.paper.claims import family as F
from reports.paper.claims import rules as R
from reports.paper.claims.register import make_claim
from reports.paper.studies.follow import follow
from reports.paper.studies.followed_samples import MAX_COLLISIONS, SIZES, _rng, hole_lo
from reports.paper.studies.islands import classify
from reports.paper.studies.sampling import EPS
from reports.paper.studies.seeds import FOLLOWED_SEED
from reports.runs.scenes import load_scene
from reports.runs.survival import wilson
from reports.stats.hazard import all_cause_survival, first_below

SWEEP_WIDTHS = (0.2, 0.3, 0.6, 0.8, 1.4, 1.8)
SWEEP_PARTICLES = 4_000_000  # per entry hole: 381 entrants left at the long-lived level 1e-4
MANY = 0.5         # "many": at least half of the widths not shown
MANY_FAILS = 1 / 6  # ... not many: at most one in six


def sweep_scene():
    """The TOML text of the sweep: the paper's transport scene with the widths not shown."""
    text = load_scene("paper-transport").source
    old = "widths = [0.1, 0.4, 1.0, 2.2]"
    if old not in text:
        raise ValueError("the paper-transport scene no longer lists the paper's four widths")
    return (text.replace('name = "paper-transport"', 'name = "transport-width-sweep"')
            .replace(old, "widths = [" + ", ".join(f"{w:g}" for w in SWEEP_WIDTHS) + "]"))


def long_lived_time(tr):
    """The time at which the entrants of hole 1 still inside fall to LONG_LIVED_LEVEL (None)."""
    c = tr[1]["time"]["P11"]
    k = first_below(all_cause_survival(c), R.LONG_LIVED_LEVEL)
    return None if k is None else float(c.x[k])


@functools.lru_cache(maxsize=8)
def island_lifetimes(width, t_end, order, quick=False):
    """(starts on the island of (0, order pi), of them still inside at t_end) with the holes of
    ``width`` at 0 and pi."""
    scene = load_scene("escape-island-start")
    m = SIZES[bool(quick)]["island"]
    rng = _rng("island-lifetime", f"{width:g}", order)
    shift = math.pi * (order - 1)
    phi = np.mod(rng.uniform(*scene.start_phi, m), TWO_PI)
    v = rng.uniform(*scene.start_v, m) + shift
    large = classify(phi, v, EPS, m=order).large
    fol = follow(phi[large], v[large], EPS, [hole_lo(0.0, width), hole_lo(math.pi, width)],
                 [width, width], MAX_COLLISIONS, t_end, seed=FOLLOWED_SEED)
    return int(large.sum()), int((fol.exit < 0).sum())


def reducing_lifetime_claim(h, tr, quick=False):
    cid = f"fig3-reducing-lifetime-h={h}"
    t_end = long_lived_time(tr)
    if t_end is None:
        return make_claim(cid, "The transport run does not reach the long-lived level.")
    members = []
    for order in (1, 2):
        m, left = island_lifetimes(float(h), t_end, order, quick)
        if m == 0:
            members.append(F.too_few(f"island of (0, {order} pi): no start on it", "share left"))
            continue
        lo, hi = (float(x) for x in wilson(left, m))
        members.append(F.word_member(f"island of (0, {order} pi): {left} of {m} still inside",
                                     "share left", left / m, lo, hi, R.DESTROYED,
                                     R.DESTROYED_FAILS))
    return make_claim(cid, f"Holes of width {h} at 0 and pi, followed to the long-lived time "
                      f"t = {t_end:.4g} of the transport run: {F.family_text(members)}.",
                      analyses=members)


def many_not_shown_claim(sweep, run):
    """``sweep``: ``transport_claims.transport_analysis`` of the sweep's run."""
    from reports.paper.claims.transport_claims import strong_claim, trap_claim

    got = {"trapping": [], "very strong P_11": []}
    for w, tr in sorted(sweep.items(), key=lambda kv: float(kv[0])):
        got["trapping"].append((w, trap_claim("fig3-trap-h=1", tr, run, True)))
        got["very strong P_11"].append((w, strong_claim("1", tr, run)))
    members = []
    for name, rows in got.items():
        if not rows:
            members.append(F.too_few(name, "share of the widths"))
            continue
        # a width that decides neither way may give the effect or not: the share's interval
        # runs from the widths confirmed to those not refuted
        yes = sum(c.verdict == "confirmed" for _, c in rows) / len(rows)
        not_no = sum(c.verdict != "refuted" for _, c in rows) / len(rows)
        members.append(F.word_member(
            f"{name}: " + ", ".join(f"h = {w}: {c.verdict}"
                                    + (f" ({c.inconclusive})" if c.inconclusive else "")
                                    for w, c in rows),
            "share of the widths", yes, yes, not_no, MANY, MANY_FAILS))
    n = next(iter(next(iter(sweep.values()))[1]["time"].values())).particles if sweep else None
    return make_claim("fig3-many-not-shown", f"Sweep run {run}: {F.family_text(members)}.",
                      analyses=members, particles_per_curve=n, run=run)
