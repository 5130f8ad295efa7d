"""One writer per run directory: an OS file lock (``filelock``) with the holder written beside it.

``RunLock(out)`` creates ``out`` if needed and takes ``out/.bouncer.lock`` without waiting. The
holder's pid, host, start time and command line go into ``out/.bouncer.lock.json`` so that a second
``bouncer run`` (``--resume`` or ``--force`` included) is refused with a message naming it. The OS
releases the lock when its process dies (even by kill -9), so a stale sidecar never blocks a run:
the next holder overwrites it.
"""

from __future__ import annotations

import json
import os
import socket
import sys
from pathlib import Path

from filelock import FileLock, Timeout

from reports.runs.echo import clip
from reports.runs.provenance import now
from reports.runs.rundir import read_input_text

LOCK_NAME = ".bouncer.lock"
HOLDER_NAME = ".bouncer.lock.json"
MAX_HOLDER_BYTES = 4096  # characters of the holder's record read and shown


class RunBusy(ValueError):
    """Another process writes this run directory: exit status 2."""


def holder(out):
    """The recorded holder of ``out``'s lock as a phrase (or "another process")."""
    try:
        info = json.loads(read_input_text(Path(out) / HOLDER_NAME, MAX_HOLDER_BYTES))
        return clip(f"pid {info['pid']} on {info['host']} since {info['started']}"
                    f" ({info['command']})", MAX_HOLDER_BYTES)
    except (OSError, ValueError, KeyError, TypeError, RecursionError):
        return "another process"


class RunLock:
    """Context manager: the lock of run directory ``out`` for the duration of the block."""

    def __init__(self, out):
        self.out = Path(out)
        self.lock = None

    def __enter__(self):
        self.out.mkdir(parents=True, exist_ok=True)
        self.lock = FileLock(self.out / LOCK_NAME, timeout=0)
        try:
            self.lock.acquire()
        except Timeout:
            raise RunBusy(f"{self.out} is being written by {holder(self.out)}; wait for it to"
                          " finish or stop it, then use --resume") from None
        info = {"pid": os.getpid(), "host": socket.gethostname(), "started": now(),
                "command": " ".join(["bouncer", *sys.argv[1:]])}
        holder_file = self.out / HOLDER_NAME
        try:
            holder_file.unlink(missing_ok=True)  # a fresh file: never a FIFO left in its place
            holder_file.write_text(json.dumps(info) + "\n", encoding="utf-8")
        except OSError as err:  # a full disk: no lock held, no half-written holder left
            holder_file.unlink(missing_ok=True)
            self.lock.release()
            raise OSError(err.errno, err.strerror, str(holder_file)) from None
        return self

    def __exit__(self, *exc):
        try:
            (self.out / HOLDER_NAME).unlink(missing_ok=True)
        except OSError:
            pass  # a directory made read-only mid-run: the lock itself still goes
        self.lock.release()
        return False
