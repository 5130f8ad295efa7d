"""Files of a run directory, all written atomically (temporary file + ``os.replace``).

    manifest.json    scene, seed, particles, versions, git commit, times, collisions,
                     verification summary, status (partial, complete or failed)
    scene.toml       the scene text the run used (rerun: ``bouncer run RUN/scene.toml``)
    survival.csv     curve,clock,x,p,p_lo,p_hi     (escape and transport scenes)
    counts.csv       experiment,curve,clock,outcome,lower_edge,count   (the raw histograms)
    portrait.npy     phase-space histogram counts[phi_bin, v_bin]     (phase-space scenes)
    sample.csv       the verification sample, recomputed by ``bouncer verify``
    checkpoint.npz   merged counts and the finished chunks (``--resume``)
    .bouncer.lock    the writer's lock, .bouncer.lock.json its holder (``reports.runs.lock``)

``manifest.json`` records the SHA-256 of every other file under ``hashes``.
"""

from __future__ import annotations

import csv
import hashlib
import io
import json
import os
import shutil
from pathlib import Path

import numpy as np

MANIFEST = "manifest.json"
CHECKPOINT = "checkpoint.npz"


class RunFailed(Exception):
    """The run could not be trusted (an overstep, an unsettled collision): exit status 1."""


class RunInterrupted(Exception):
    """Ctrl-C: the checkpoint holds ``done`` of ``total`` chunks of the run in ``out``."""

    def __init__(self, out, done, total):
        super().__init__(f"interrupted: {done} of {total} chunks are checkpointed in {out}")
        self.out, self.done, self.total = out, done, total


def os_error_text(err):
    """One line for an OSError, naming its path(s): "PATH: Permission denied"."""
    paths = [str(p) for p in (err.filename, err.filename2) if p is not None]
    what = err.strerror or type(err).__name__
    return f"{' -> '.join(paths)}: {what}" if paths else f"{what}: {err}"


SAMPLE_COLUMNS = ("experiment", "chunk", "particle", "n", "phi", "v", "phi1", "v1", "tau",
                  "tau_ref", "error")
# after those, scenes with restitution < 1 record the departure's carried state, the argument
# ``carried`` of ``fastpath.carried_step`` in its order
CARRIED_COLUMNS = ("base_phase", "s", "sin", "cos", "w", "detached")


def sample_columns(scene):
    """The columns of ``scene``'s sample rows (sample.csv, the checkpoint)."""
    return SAMPLE_COLUMNS + (CARRIED_COLUMNS if scene.carries else ())


def sha256_bytes(data):
    """SHA-256 (hex) of text (as UTF-8) or bytes: what ``write_atomic`` writes."""
    return hashlib.sha256(data.encode() if isinstance(data, str) else data).hexdigest()


def sha256_file(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def write_atomic(path, data):
    """Write text or bytes to ``path`` via a temporary file in the same folder + os.replace;
    returns the SHA-256 of what was written."""
    path = Path(path)
    tmp = path.with_name(f".{path.name}.tmp{os.getpid()}")
    mode = "wb" if isinstance(data, bytes) else "w"
    with open(tmp, mode, **({} if mode == "wb" else {"encoding": "utf-8", "newline": ""})) as f:
        f.write(data)
        f.flush()
        os.fsync(f.fileno())
    os.replace(tmp, path)
    return sha256_bytes(data)


def write_json(path, obj):
    write_atomic(path, json.dumps(obj, indent=2, sort_keys=False) + "\n")


def read_json(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def csv_text(header, rows):
    buf = io.StringIO()
    writer = csv.writer(buf, lineterminator="\n")
    writer.writerow(header)
    writer.writerows(rows)
    return buf.getvalue()


def write_csv(path, header, rows):
    return write_atomic(path, csv_text(header, rows))


def read_csv(path):
    with open(path, encoding="utf-8", newline="") as f:
        return list(csv.DictReader(f))


def save_npz_atomic(path, **arrays):
    buf = io.BytesIO()
    np.savez(buf, **arrays)
    return write_atomic(path, buf.getvalue())


def save_npy_atomic(path, array):
    buf = io.BytesIO()
    np.save(buf, array)
    return write_atomic(path, buf.getvalue())


LOCK_FILES = (".bouncer.lock", ".bouncer.lock.json")  # reports.runs.lock: kept by --force


def _entries(out):
    return [p for p in out.iterdir() if p.name not in LOCK_FILES]


def check_out(out, resume, force):
    """Check the run directory without touching it: returns True when resuming a run.

    A directory that exists and is not empty is used only with ``resume`` (it must hold a run)
    or replaced with ``force`` (only if it holds a run: never deletes other folders).
    Raises ValueError otherwise, and for a path that is a file.
    """
    out = Path(out)
    if out.exists() and not out.is_dir():
        raise ValueError(f"--out {out} is a file, not a directory")
    exists = out.is_dir() and bool(_entries(out))
    is_run = (out / MANIFEST).is_file()
    if resume:
        if not is_run:
            raise ValueError(f"--resume: {out} holds no run (no {MANIFEST})")
        return True
    if exists and not force:
        raise ValueError(f"run directory {out} exists; use --resume to continue it or"
                         " --force to overwrite it")
    if exists and not is_run:
        raise ValueError(f"--force: {out} exists and is not a run directory; not deleting it")
    return False


def prepare(out, resume, force):
    """``check_out``, then create the directory, or empty it (but for its lock) with ``force``."""
    out = Path(out)
    resuming = check_out(out, resume, force)
    if not resuming and out.is_dir():
        for path in _entries(out):
            if path.is_dir() and not path.is_symlink():
                shutil.rmtree(path)
            else:
                path.unlink()
    out.mkdir(parents=True, exist_ok=True)
    return resuming
