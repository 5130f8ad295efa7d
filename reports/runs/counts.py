"""Integer histograms of a chunk or of a whole run: ``Counts``, and the run's ``Tally``.

One type holds the counts wherever they are summed: a chunk fills a ``Counts`` of shape
(holes, bins); the run's ``Tally`` is a ``Counts`` with a leading experiment axis plus the
bookkeeping of the checkpoint (finished chunks, verified sample rows, elapsed time).

    esc_n[e, j, b], esc_t[e, j, b]   escapes through hole j in collision / time bin b
    cens_n[e, b], cens_t[e, b]       particles censored at the horizon, by bin
    portrait[p, q]                   phase-space visits (phase-space scenes only)

Merging (``Tally.merge``) is keyed by the chunk index (curve, chunk): a chunk already merged is
ignored, counts are integer sums, and the sample rows and the list of finished chunks are kept
sorted by index, so the merged state is a function of the *set* of finished chunks only.
"""

from __future__ import annotations

import bisect
import json
from dataclasses import dataclass, field

import numpy as np

from reports.runs import rundir
from reports.runs.provenance import now


@dataclass
class Counts:
    """Escape and censoring histograms, phase-space visits, collisions, settled flights."""

    esc_n: np.ndarray
    esc_t: np.ndarray
    cens_n: np.ndarray
    cens_t: np.ndarray
    portrait: np.ndarray
    collisions: int = 0
    settled: int = 0

    @classmethod
    def zeros(cls, plan, holes, experiments=None, **extra):
        """Zero counts for ``holes`` holes; with ``experiments`` a leading axis of that size."""
        lead = () if experiments is None else (experiments,)
        nb, tb = len(plan.n_edges), len(plan.t_edges)
        sc = plan.scene
        shape = (sc.phi_bins, sc.v_bins) if sc.kind == "phase-space" else (0, 0)
        return cls(np.zeros((*lead, holes, nb), np.int64), np.zeros((*lead, holes, tb), np.int64),
                   np.zeros((*lead, nb), np.int64), np.zeros((*lead, tb), np.int64),
                   np.zeros(shape, np.int64), **extra)

    def add(self, other, at=(), portrait=True):
        """Add ``other``'s counts into row ``at`` (the experiment index, or () for all)."""
        holes = len(other.esc_n)
        self.esc_n[at][:holes] += other.esc_n
        self.esc_t[at][:holes] += other.esc_t
        self.cens_n[at] += other.cens_n
        self.cens_t[at] += other.cens_t
        if portrait:
            self.portrait += other.portrait
        self.collisions += other.collisions
        self.settled += other.settled


def _sample_key(row):
    return (int(row[0]), int(row[1]), int(row[2]))


@dataclass
class Tally(Counts):
    """The run's merged counts (one row per experiment) and the checkpoint's bookkeeping."""

    finished: list = field(default_factory=list)
    samples: list = field(default_factory=list)
    elapsed: float = 0.0
    started: str = ""

    @classmethod
    def empty(cls, plan):
        holes = max([len(x.hole_lo) for x in plan.experiments] + [1])
        return cls.zeros(plan, holes, experiments=len(plan.experiments), started=now())

    def save(self, path):
        meta = {"collisions": self.collisions, "settled": self.settled,
                "finished": self.finished, "samples": self.samples, "elapsed": self.elapsed,
                "started": self.started}
        rundir.save_npz_atomic(path, esc_n=self.esc_n, esc_t=self.esc_t, cens_n=self.cens_n,
                               cens_t=self.cens_t, portrait=self.portrait,
                               meta=np.array(json.dumps(meta)))

    @classmethod
    def load(cls, path):
        with np.load(path) as z:
            meta = json.loads(str(z["meta"]))
            return cls(z["esc_n"], z["esc_t"], z["cens_n"], z["cens_t"], z["portrait"],
                       meta["collisions"], meta["settled"],
                       sorted(tuple(c) for c in meta["finished"]),
                       sorted(meta["samples"], key=_sample_key), meta["elapsed"],
                       meta["started"])

    def merge(self, result, kind):
        """Add a finished chunk's ``ChunkResult``; False (and nothing changes) if its index
        (curve, chunk) is merged already. Keyed and sorted by index, so any completion order
        gives the same state."""
        key = (result.curve, result.chunk)
        at = bisect.bisect_left(self.finished, key)
        if at < len(self.finished) and self.finished[at] == key:
            return False
        self.add(result.counts, at=result.curve, portrait=kind == "phase-space")
        for row in result.rows:
            bisect.insort(self.samples, list(row), key=_sample_key)
        self.finished.insert(at, key)
        return True
