"""Files of a run directory, all written atomically (temporary file + ``os.replace``).

    manifest.json    scene, seed, particles, versions, git commit, times, collisions,
                     verification summary, status (partial, complete or failed)
    scene.toml       the scene text the run used (rerun: ``bouncer run RUN/scene.toml``)
    survival.csv     curve,clock,x,p,p_lo,p_hi     (escape and transport scenes)
    counts.csv       experiment,curve,clock,outcome,lower_edge,count   (the raw histograms)
    portrait.npy     phase-space histogram counts[phi_bin, v_bin]     (phase-space scenes)
    sample.csv       the verification sample, recomputed by ``bouncer verify``
    checkpoint.npz   merged counts and the finished chunks (``--resume``)
"""

from __future__ import annotations

import csv
import io
import json
import os
import shutil
from pathlib import Path

import numpy as np

MANIFEST = "manifest.json"


class RunFailed(Exception):
    """The run could not be trusted (an overstep, an unsettled collision): exit status 1."""


SAMPLE_COLUMNS = ("experiment", "chunk", "particle", "n", "phi", "v", "phi1", "v1", "tau",
                  "tau_ref", "error")


def write_atomic(path, data):
    """Write text or bytes to ``path`` via a temporary file in the same folder + os.replace."""
    path = Path(path)
    tmp = path.with_name(f".{path.name}.tmp{os.getpid()}")
    mode = "wb" if isinstance(data, bytes) else "w"
    with open(tmp, mode, **({} if mode == "wb" else {"encoding": "utf-8", "newline": ""})) as f:
        f.write(data)
        f.flush()
        os.fsync(f.fileno())
    os.replace(tmp, path)


def write_json(path, obj):
    write_atomic(path, json.dumps(obj, indent=2, sort_keys=False) + "\n")


def read_json(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def write_csv(path, header, rows):
    buf = io.StringIO()
    writer = csv.writer(buf, lineterminator="\n")
    writer.writerow(header)
    writer.writerows(rows)
    write_atomic(path, buf.getvalue())


def read_csv(path):
    with open(path, encoding="utf-8", newline="") as f:
        return list(csv.DictReader(f))


def save_npz_atomic(path, **arrays):
    buf = io.BytesIO()
    np.savez(buf, **arrays)
    write_atomic(path, buf.getvalue())


def save_npy_atomic(path, array):
    buf = io.BytesIO()
    np.save(buf, array)
    write_atomic(path, buf.getvalue())


def prepare(out, resume, force):
    """Check the run directory: returns True when resuming an existing run.

    A directory that exists and is not empty is used only with ``resume`` (it must hold a run)
    or replaced with ``force`` (only if it holds a run: never deletes other folders).
    Raises ValueError otherwise.
    """
    out = Path(out)
    exists = out.exists() and (not out.is_dir() or any(out.iterdir()))
    is_run = (out / MANIFEST).is_file()
    if resume:
        if not is_run:
            raise ValueError(f"--resume: {out} holds no run (no {MANIFEST})")
        return True
    if exists:
        if not force:
            raise ValueError(f"run directory {out} exists; use --resume to continue it or"
                             " --force to overwrite it")
        if not is_run:
            raise ValueError(f"--force: {out} exists and is not a run directory; not deleting it")
        shutil.rmtree(out)
    out.mkdir(parents=True, exist_ok=True)
    return False
