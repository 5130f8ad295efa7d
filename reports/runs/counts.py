"""Integer histograms of a chunk or of a whole run: ``Counts``, and the run's ``Tally``.

One type holds the counts wherever they are summed: a chunk fills a ``Counts`` of shape
(holes, bins); the run's ``Tally`` is a ``Counts`` with a leading experiment axis plus the
bookkeeping of the checkpoint (finished chunks, verified sample rows, elapsed time).

    esc_n[e, j, b], esc_t[e, j, b]   escapes through hole j in collision / time bin b
    cens_n[e, b], cens_t[e, b]       particles censored at the horizon, by bin
    stuck_n[e, b], stuck_t[e, b]     particles stuck on the plate for good (restitution < 1,
                                     |eps| <= 1), by the collision index / time of sticking;
                                     zero for the elastic model
    portrait[p, q]                   phase-space visits (phase-space scenes only)
    moving[e, j], stuck_at[e, j]     velocity scenes only (else None): particles still moving
                                     at collision n_grid[j], and stuck for good before it
    sum_v[e, j], sum_v2[e, j]        velocity scenes only: the exact sums of v_n and v_n**2 over
                                     the particles moving at n_grid[j], ``fractions.Fraction``
                                     in object arrays (see below)
    joint[e, o, b, c]                scenes with ``[record] joint`` only (else None): particles
                                     that ended with outcome o (exit hole j < holes, then
                                     censored, then stuck) in collision bin b and time bin c
                                     (``reports.runs.joint_file``)

Exact velocity sums. A chunk's kernel adds v_n in float64 within fixed blocks of particles (the
same for any thread count); each block sum is then converted exactly to a Fraction (a float is
a dyadic rational) and from there on every sum is exact rational arithmetic. Addition of
rationals is associative, so the merged sums, and the means rounded once from them, do not
depend on the order in which chunks are merged (a Dask cluster returns them out of order).

Merging (``Tally.merge``) is keyed by the chunk index (curve, chunk): a chunk already merged is
ignored, counts are integer sums, and the sample rows are kept sorted by index, so the merged
state is a function of the *set* of finished chunks only. That set is held compactly
(``Finished``: per curve the length of the finished prefix 0..p-1, plus the few chunks that
finished out of order), so memory does not grow with the number of chunks.

The checkpoint (``Tally.save``) embeds a SHA-256 digest of its arrays and bookkeeping;
``Tally.load`` refuses (``CheckpointError``) a file that is unreadable, truncated or whose digest
does not match its content.
"""

from __future__ import annotations

import bisect
import hashlib
import json
import math
import zipfile
from dataclasses import dataclass, field
from fractions import Fraction

import numpy as np

from reports.runs import rundir
from reports.runs.provenance import now


@dataclass
class Counts:
    """Escape, censoring and sticking histograms, phase-space visits, collisions, settled
    flights. ``stuck_n``/``stuck_t`` default to zeros shaped like ``cens_n``/``cens_t``."""

    esc_n: np.ndarray
    esc_t: np.ndarray
    cens_n: np.ndarray
    cens_t: np.ndarray
    portrait: np.ndarray
    collisions: int = 0
    settled: int = 0
    stuck_n: np.ndarray | None = None
    stuck_t: np.ndarray | None = None
    moving: np.ndarray | None = None
    stuck_at: np.ndarray | None = None
    sum_v: np.ndarray | None = None
    sum_v2: np.ndarray | None = None
    joint: np.ndarray | None = None

    def __post_init__(self):
        if self.stuck_n is None:
            self.stuck_n = np.zeros_like(self.cens_n)
        if self.stuck_t is None:
            self.stuck_t = np.zeros_like(self.cens_t)

    @classmethod
    def zeros(cls, plan, holes, experiments=None, **extra):
        """Zero counts for ``holes`` holes; with ``experiments`` a leading axis of that size."""
        lead = () if experiments is None else (experiments,)
        nb, tb = len(plan.n_edges), len(plan.t_edges)
        sc = plan.scene
        shape = (sc.phi_bins, sc.v_bins) if sc.kind == "phase-space" else (0, 0)
        if sc.joint:
            extra.update(joint=np.zeros((*lead, holes + 2, nb, tb), np.int64))
        if sc.kind == "velocity":
            grid = (*lead, len(plan.n_grid))
            extra.update(moving=np.zeros(grid, np.int64), stuck_at=np.zeros(grid, np.int64),
                         sum_v=exact_zeros(grid), sum_v2=exact_zeros(grid))
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
        self.stuck_n[at] += other.stuck_n
        self.stuck_t[at] += other.stuck_t
        if portrait:
            self.portrait += other.portrait
        if self.moving is not None:
            for name in _VELOCITY + _EXACT:
                getattr(self, name)[at] += getattr(other, name)
        if self.joint is not None:
            self.joint[at] += other.joint
        self.collisions += other.collisions
        self.settled += other.settled


def exact_zeros(shape):
    """An object array of Fraction(0): exact sums (module docstring)."""
    out = np.empty(shape, object)
    out.fill(Fraction(0))
    return out


def exact_block_sums(block_sums):
    """Column sums of a float64 array (blocks, k), each block sum taken exactly: an object array
    of k Fractions."""
    out = exact_zeros(block_sums.shape[1:])
    for row in block_sums:
        out += np.array([Fraction(float(x)) for x in row], object)
    return out


def _load_joint(arrays, meta):
    """The dense joint record of a loaded checkpoint, None if it has none; ValueError if only
    part of it is there or its arrays do not fit its shape."""
    present = [name for name in _JOINT if name in arrays] + (
        ["joint_shape"] if "joint_shape" in meta else [])
    if not present:
        return None
    if len(present) != len(_JOINT) + 1:
        raise ValueError(f"a joint record with only {present}")
    return joint_from_arrays(arrays["joint_index"], arrays["joint_count"], meta["joint_shape"])


def _sample_key(row):
    return (int(row[0]), int(row[1]), int(row[2]))


class CheckpointError(ValueError):
    """A checkpoint that cannot be trusted (unreadable, edited, inconsistent): exit status 2."""


@dataclass
class Finished:
    """The set of finished chunks (e, k): k < prefix[e], or (e, k) in ``extra`` (chunks that
    finished before an earlier one of their curve; Dask completes out of order)."""

    prefix: list
    extra: set = field(default_factory=set)

    @classmethod
    def none(cls, curves):
        return cls([0] * curves)

    def __contains__(self, key):
        e, k = key
        return k < self.prefix[e] or (e, k) in self.extra

    def __len__(self):
        return sum(self.prefix) + len(self.extra)

    def add(self, key):
        """Mark (e, k) finished; False if it was already."""
        if key in self:
            return False
        e, k = key
        self.extra.add((e, k))
        while (e, self.prefix[e]) in self.extra:
            self.extra.remove((e, self.prefix[e]))
            self.prefix[e] += 1
        return True

    def particles_done(self, plan, e):
        """Starts of experiment e in its finished chunks."""
        return plan.prefix_particles(self.prefix[e]) + sum(
            plan.chunk_particles(k) for ee, k in self.extra if ee == e)

    def to_json(self):
        return {"prefix": list(self.prefix), "extra": sorted([e, k] for e, k in self.extra)}

    @classmethod
    def from_json(cls, obj):
        if isinstance(obj, list):  # the list format of a checkpoint: the finished (e, k)
            curves = 1 + max((e for e, _ in obj), default=0)
            out = cls.none(curves)
            for e, k in obj:
                out.add((int(e), int(k)))
            return out
        return cls([int(p) for p in obj["prefix"]], {(int(e), int(k)) for e, k in obj["extra"]})


_ARRAYS = ("esc_n", "esc_t", "cens_n", "cens_t", "portrait")
_STUCK = ("stuck_n", "stuck_t")  # saved only when a particle stuck: elastic checkpoints unchanged
_VELOCITY = ("moving", "stuck_at")  # velocity scenes only, as are the exact sums:
_EXACT = ("sum_v", "sum_v2")  # in the bookkeeping JSON as "numerator/denominator" strings
MAX_JOINT_BINS = 2**28  # refuse a checkpoint's joint shape beyond this (2 GiB of counts)
_JOINT = ("joint_index", "joint_count")  # the joint record's non-zero bins (``joint_arrays``)


def joint_arrays(joint):
    """The checkpoint's arrays of a joint record: the flat indices of its non-zero bins
    (increasing) and their counts; ``joint.shape`` goes into the bookkeeping."""
    index = np.flatnonzero(joint)
    return {"joint_index": index.astype(np.int64), "joint_count": joint.ravel()[index]}


def joint_from_arrays(index, count, shape):
    """The dense joint record from ``joint_arrays``; ValueError unless the indices increase
    strictly inside ``shape`` and each count is positive."""
    shape = tuple(int(x) for x in shape)
    if len(shape) != 4 or min(shape) < 1 or math.prod(shape) > MAX_JOINT_BINS:
        raise ValueError(f"joint record shape {shape} is not (curves, outcomes, n bins, t bins)"
                         f" of at most {MAX_JOINT_BINS} bins")
    size = math.prod(shape)
    if (index.ndim != 1 or index.shape != count.shape or index.dtype != np.int64
            or count.dtype != np.int64):
        raise ValueError("joint record arrays of the wrong shape or type")
    if len(index) and (index[0] < 0 or index[-1] >= size or np.any(np.diff(index) <= 0)
                       or np.any(count <= 0)):
        raise ValueError("joint record indices not increasing inside its shape, or a count"
                         " that is not positive")
    joint = np.zeros(size, np.int64)
    joint[index] = count
    return joint.reshape(shape)


def _digest(arrays, meta_json):
    """SHA-256 over each array's name, dtype, shape and bytes (``_ARRAYS``, then ``_STUCK``,
    ``_VELOCITY`` and ``_JOINT`` where present), then the bookkeeping JSON."""
    h = hashlib.sha256()
    for name in (*_ARRAYS, *(n for n in _STUCK + _VELOCITY + _JOINT if n in arrays)):
        a = np.ascontiguousarray(arrays[name])
        h.update(f"{name}|{a.dtype.str}|{a.shape}|".encode())
        h.update(a.tobytes())
    h.update(meta_json.encode())
    return h.hexdigest()


@dataclass
class Tally(Counts):
    """The run's merged counts (one row per experiment) and the checkpoint's bookkeeping."""

    finished: Finished = field(default_factory=lambda: Finished.none(0))
    samples: list = field(default_factory=list)
    elapsed: float = 0.0
    started: str = ""

    @classmethod
    def empty(cls, plan):
        holes = max([len(x.hole_lo) for x in plan.experiments] + [1])
        return cls.zeros(plan, holes, experiments=len(plan.experiments), started=now(),
                         finished=Finished.none(len(plan.experiments)))

    def save(self, path):
        """Write the checkpoint atomically; returns the SHA-256 of the file's bytes."""
        book = {"collisions": self.collisions, "settled": self.settled,
                "finished": self.finished.to_json(), "samples": self.samples,
                "elapsed": self.elapsed, "started": self.started}
        arrays = {name: getattr(self, name) for name in _ARRAYS}
        if self.stuck_n.any() or self.stuck_t.any():
            arrays.update(stuck_n=self.stuck_n, stuck_t=self.stuck_t)
        if self.moving is not None:
            arrays.update({name: getattr(self, name) for name in _VELOCITY})
            book["velocity"] = {name: [[str(x) for x in row] for row in getattr(self, name)]
                                for name in _EXACT}
        if self.joint is not None:
            arrays.update(joint_arrays(self.joint))
            book["joint_shape"] = list(self.joint.shape)
        meta = json.dumps(book)
        return rundir.save_npz_atomic(path, **arrays, meta=np.array(meta),
                                      digest=np.array(_digest(arrays, meta)))

    @classmethod
    def load(cls, path):
        """The checkpoint at ``path``; CheckpointError if it is unreadable or fails its digest."""
        try:
            with np.load(path) as z:
                arrays = {name: z[name] for name in (*_ARRAYS, *_STUCK, *_VELOCITY, *_JOINT)
                          if name in z.files}
                meta_json, digest = str(z["meta"]), str(z["digest"])
            meta = json.loads(meta_json)
            if _digest(arrays, meta_json) != digest:
                raise CheckpointError(f"checkpoint {path} fails its content hash (edited or"
                                      " corrupted)")
            exact = {name: np.array([[Fraction(x) for x in row] for row in rows], object)
                     .reshape(arrays["moving"].shape)
                     for name, rows in meta["velocity"].items()} if "velocity" in meta else {}
            joint = _load_joint(arrays, meta)
            return cls(*(arrays[name] for name in _ARRAYS), int(meta["collisions"]),
                       int(meta["settled"]), arrays.get("stuck_n"), arrays.get("stuck_t"),
                       arrays.get("moving"), arrays.get("stuck_at"), exact.get("sum_v"),
                       exact.get("sum_v2"), joint,
                       finished=Finished.from_json(meta["finished"]),
                       samples=sorted(meta["samples"], key=_sample_key),
                       elapsed=float(meta["elapsed"]), started=str(meta["started"]))
        except CheckpointError:
            raise
        except (OSError, EOFError, zipfile.BadZipFile, KeyError, TypeError, ValueError,
                ZeroDivisionError) as err:
            raise CheckpointError(f"checkpoint {path} is unreadable ({type(err).__name__}:"
                                  f" {err})") from None

    def merge(self, result, kind):
        """Add a finished chunk's ``ChunkResult``; False (and nothing changes) if its index
        (curve, chunk) is merged already. Keyed and sorted by index, so any completion order
        gives the same state."""
        if (result.curve, result.chunk) in self.finished:
            return False
        self.add(result.counts, at=result.curve, portrait=kind == "phase-space")
        for row in result.rows:
            bisect.insort(self.samples, list(row), key=_sample_key)
        self.finished.add((result.curve, result.chunk))
        return True
