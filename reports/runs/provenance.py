"""Provenance of a run: package versions, the git commit, timestamps."""

import platform
import subprocess
from datetime import UTC, datetime
from importlib import metadata
from pathlib import Path


def now():
    return datetime.now(UTC).isoformat(timespec="seconds")


def versions():
    out = {"python": platform.python_version()}
    for dist in ("bouncer-verify", "numpy", "numba", "mpmath", "scipy"):
        try:
            out[dist] = metadata.version(dist)
        except metadata.PackageNotFoundError:
            out[dist] = None
    return out


def git():
    here = Path(__file__).resolve().parent
    try:
        commit = subprocess.run(["git", "rev-parse", "HEAD"], cwd=here, capture_output=True,
                                text=True, timeout=10, check=True).stdout.strip()
        dirty = subprocess.run(["git", "status", "--porcelain"], cwd=here, capture_output=True,
                               text=True, timeout=10, check=True).stdout.strip() != ""
    except (OSError, subprocess.SubprocessError):
        return None
    return {"commit": commit, "dirty": dirty}
