"""Files of a run directory, all written atomically (temporary file + ``os.replace``).

    manifest.json    what the run states about its outputs (``reports.runs.manifest``):
                     scene, seed, particles, collisions, curves, bins, verification summary,
                     status (partial, complete or failed), the SHA-256 of every other file
    provenance.json  how and when it was made: versions, git commit, threads, cluster, times
    scene.toml       the scene text the run used (rerun: ``bouncer run RUN/scene.toml``)
    survival.csv     curve,clock,x,p,p_lo,p_hi     (escape and transport scenes)
    counts.csv       experiment,curve,clock,outcome,lower_edge,count   (the raw histograms)
    joint.csv        experiment,outcome,n_lower_edge,t_lower_edge,count (``[record] joint``:
                     the joint histogram of (n, t), ``reports.runs.joint_file``)
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
import stat
from pathlib import Path

import numpy as np

MANIFEST = "manifest.json"
PROVENANCE = "provenance.json"
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
    what = err.strerror or str(err) or type(err).__name__
    return f"{' -> '.join(paths)}: {what}" if paths else what


SAMPLE_COLUMNS = ("experiment", "chunk", "particle", "n", "phi", "v", "phi1", "v1", "tau",
                  "tau_ref", "error")
# after those, scenes with restitution < 1 record the departure's carried state, the argument
# ``carried`` of ``fastpath.carried_step`` in its order
CARRIED_COLUMNS = ("base_phase", "s", "sin", "cos", "w", "detached")


def sample_columns(scene):
    """The columns of ``scene``'s sample rows (sample.csv, the checkpoint)."""
    return SAMPLE_COLUMNS + (CARRIED_COLUMNS if scene.carries else ())


# The largest file each reader takes: far above what a run writes (a scene is a few hundred
# bytes, a manifest a few kilobytes for hundreds of curves; counts.csv, survival.csv and
# sample.csv hold at most a few megabytes per curve; a checkpoint or portrait.npy at most the
# 4e6 bins of a portrait), so that a file swapped for something huge is refused before it is
# read into memory.
MAX_SCENE_BYTES = 1 << 20
MAX_JSON_BYTES = 64 << 20
MAX_DATA_BYTES = 2 << 30


class InputError(ValueError):
    """A file the command reads is not a regular file of bounded size: one line naming it."""


def _kind_of(mode):
    for test, name in ((stat.S_ISDIR, "a directory"), (stat.S_ISFIFO, "a FIFO (named pipe)"),
                       (stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"),
                       (stat.S_ISSOCK, "a socket")):
        if test(mode):
            return name
    return "not a regular file"


def _open_input(path, limit):
    """A file descriptor of ``path`` opened for reading, after checking that it is a regular
    file of at most ``limit`` bytes (``read_input``)."""
    path = Path(path)
    fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0))
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise InputError(f"{path}: {_kind_of(info.st_mode)}, not a regular file")
        if info.st_size > limit:
            raise InputError(f"{path}: {info.st_size} bytes, more than the {limit} this file"
                             " may hold")
    except BaseException:
        os.close(fd)
        raise
    return fd


def _blocks(fd, path, limit):
    """The file's content in blocks; ``InputError`` once more than ``limit`` bytes came (a file
    that grows while it is read)."""
    size = 0
    while block := os.read(fd, 1 << 20):
        size += len(block)
        if size > limit:
            raise InputError(f"{path}: more than the {limit} bytes this file may hold")
        yield block


def read_input(path, limit=MAX_DATA_BYTES):
    """The bytes of ``path``, which must be a regular file (a symbolic link to one is followed)
    of at most ``limit`` bytes; ``InputError`` naming it otherwise (a FIFO, a device, a
    directory, a file too large), before anything is read. The file is opened without
    blocking, so a FIFO in its place cannot hang the reader. A missing file is
    ``FileNotFoundError``."""
    fd = _open_input(path, limit)
    try:
        return b"".join(_blocks(fd, path, limit))
    finally:
        os.close(fd)


def read_input_text(path, limit=MAX_DATA_BYTES, bom=False):
    """``read_input`` decoded as UTF-8; ``InputError`` naming the file if it is not UTF-8 text.
    With ``bom`` a leading UTF-8 byte-order mark (a spreadsheet's export) is dropped."""
    data = read_input(path, limit)
    try:
        return data.decode("utf-8-sig" if bom else "utf-8")
    except UnicodeDecodeError as err:
        raise InputError(f"{path}: not UTF-8 text (byte {err.start})") from None


def check_input(path, limit=MAX_DATA_BYTES):
    """``InputError`` unless ``path`` is a regular file of at most ``limit`` bytes: for readers
    that open the file themselves (``numpy.load``)."""
    os.close(_open_input(path, limit))


def sha256_bytes(data):
    """SHA-256 (hex) of text (as UTF-8) or bytes: what ``write_atomic`` writes."""
    return hashlib.sha256(data.encode() if isinstance(data, str) else data).hexdigest()


def sha256_file(path, limit=MAX_DATA_BYTES):
    """SHA-256 (hex) of the file's bytes; the file as ``read_input`` takes it (a regular file of
    at most ``limit`` bytes)."""
    h = hashlib.sha256()
    fd = _open_input(path, limit)
    try:
        for block in _blocks(fd, path, limit):
            h.update(block)
    finally:
        os.close(fd)
    return h.hexdigest()


def temporary(path):
    """The temporary file ``write_atomic`` writes before replacing ``path``."""
    path = Path(path)
    return path.with_name(f".{path.name}.tmp{os.getpid()}")


def write_atomic(path, data):
    """Write text or bytes to ``path`` via a temporary file in the same folder + os.replace;
    returns the SHA-256 of what was written. On any failure (a full disk, Ctrl-C) the
    temporary file is removed and ``path`` is as it was; an OSError names ``path``."""
    path = Path(path)
    tmp = temporary(path)
    mode = "wb" if isinstance(data, bytes) else "w"
    try:
        with open(tmp, mode, **({} if mode == "wb" else {"encoding": "utf-8",
                                                          "newline": ""})) as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException as err:
        tmp.unlink(missing_ok=True)
        if isinstance(err, OSError) and err.filename is None:  # a write's error names no file
            raise OSError(err.errno, err.strerror or str(err), str(path)) from None
        raise
    return sha256_bytes(data)


def write_json(path, obj):
    """``obj`` as indented JSON via ``write_atomic``; returns its SHA-256."""
    return write_atomic(path, json.dumps(obj, indent=2, sort_keys=False) + "\n")


def read_json(path):
    return json.loads(read_input_text(path, MAX_JSON_BYTES))


def csv_text(header, rows):
    buf = io.StringIO()
    writer = csv.writer(buf, lineterminator="\n")
    writer.writerow(header)
    writer.writerows(rows)
    return buf.getvalue()


def write_csv(path, header, rows):
    return write_atomic(path, csv_text(header, rows))


def read_csv(path):
    return list(csv.DictReader(io.StringIO(read_input_text(path), newline="")))


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


def check_out(out, resume, force, resumable=True):
    """Check the run directory without touching it: returns True when resuming a run.

    A directory that exists and is not empty is used only with ``resume`` (it must hold a run)
    or replaced with ``force`` (only if it holds a run: never deletes other folders).
    Raises ValueError otherwise, and for a path that is a file. ``resumable``: False for a
    sweep, which has no --resume.
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
        if not resumable:
            raise ValueError(f"sweep directory {out} exists; use --force to overwrite it")
        raise ValueError(f"run directory {out} exists; use --resume to continue it or"
                         " --force to overwrite it")
    if exists and not is_run:
        raise ValueError(f"--force: {out} exists and is not a run directory; not deleting it")
    return False


def prepare(out, resume, force, resumable=True):
    """``check_out``, then create the directory, or empty it (but for its lock) with ``force``."""
    out = Path(out)
    resuming = check_out(out, resume, force, resumable)
    if not resuming and out.is_dir():
        for path in _entries(out):
            if path.is_dir() and not path.is_symlink():
                shutil.rmtree(path)
            else:
                path.unlink()
    out.mkdir(parents=True, exist_ok=True)
    return resuming


def missing_folders(out):
    """``out`` and its ancestors that do not exist yet, deepest first: what creating ``out``
    makes (``remove_new_folders`` removes them again)."""
    out, missing = Path(out).absolute(), []
    while not out.exists() and out != out.parent:
        missing.append(out)
        out = out.parent
    return missing


RUN_FILES = (MANIFEST, PROVENANCE, "scene.toml", CHECKPOINT, "sample.csv", "survival.csv",
             "counts.csv", "portrait.npy", "velocity.csv", "joint.csv")


def remove_run_files(out, names=RUN_FILES):
    """Remove the files a run writes in ``out`` (``names``, and their temporaries), nothing
    else: for a run that stopped before its first chunk was saved. Returns the names it could
    not remove (a folder made read-only)."""
    left = []
    for name in names:
        for path in (Path(out) / name, temporary(Path(out) / name)):
            try:
                path.unlink(missing_ok=True)
            except OSError:
                left.append(path.name)
    return left


def remove_new_folders(out, new):
    """Remove the folders ``missing_folders`` listed, if still empty but for the lock files of
    ``out`` (a run that never started leaves nothing)."""
    if not new:
        return
    for name in LOCK_FILES:
        try:
            (Path(out) / name).unlink(missing_ok=True)
        except OSError:
            pass
    for folder in new:
        try:
            folder.rmdir()
        except OSError:
            return  # not empty (or not ours to remove): keep it and its parents


def default_out(root, name):
    """``root/name``, the default directory of a run (or sweep) of the scene ``name``; a
    ValueError unless it resolves (symbolic links followed) to a folder inside ``root``."""
    out = Path(root) / name
    inside = Path(root).resolve()
    where = out.resolve()
    if where == inside or not where.is_relative_to(inside):
        raise ValueError(f"the default run directory {out} of scene {name!r} resolves to {where},"
                         f" outside {inside}; give --out DIR")
    return out

