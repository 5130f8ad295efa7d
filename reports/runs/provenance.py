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


SHOWN_CHANGES = 20  # changed paths a dirty record lists


def git(exclude=None):
    """{commit, dirty} of the git work tree this package is imported from (None outside one):
    ``dirty`` when ``git status`` lists any change, untracked files included, except inside
    the folder ``exclude`` (the run's own directory, which the run writes). A dirty record adds
    ``changed``: the first ``SHOWN_CHANGES`` changed paths, relative to the tree's root."""
    here = Path(__file__).resolve().parent
    try:
        commit = _git(here, "rev-parse", "HEAD").strip()
        root = Path(_git(here, "rev-parse", "--show-toplevel").strip())
        status = _git(here, "status", "--porcelain=v1", "-z", "--untracked-files=all")
    except (OSError, subprocess.SubprocessError):
        return None
    changed = sorted(set(_changed_paths(status)))
    if exclude is not None:
        skip = Path(exclude).resolve()
        changed = [p for p in changed if not (root / p).resolve().is_relative_to(skip)]
    record = {"commit": commit, "dirty": bool(changed)}
    if changed:
        record["changed"] = changed[:SHOWN_CHANGES]
    return record


def _git(cwd, *args):
    return subprocess.run(["git", *args], cwd=cwd, capture_output=True, text=True, timeout=10,
                          check=True).stdout


def _changed_paths(status):
    """The paths of ``git status --porcelain=v1 -z`` (a rename gives its new and old path)."""
    entries = status.split("\0")
    i = 0
    while i < len(entries):
        entry = entries[i]
        i += 1
        if len(entry) < 4:
            continue
        yield entry[3:]
        if entry[0] in "RC":  # the rename's source follows as its own entry
            yield entries[i]
            i += 1


def dirty_text(record):
    """One line on a dirty (or unknown) git state of a run, or None when it is clean."""
    if record is None:
        return "the sources are not in a git work tree: provenance.json records no commit"
    if not record["dirty"]:
        return None
    first = ", ".join(record["changed"][:3])
    return (f"the git tree at {record['commit'][:12]} has uncommitted changes (first: {first}):"
            " provenance.json records \"dirty\": true; commit them (or move them out of the"
            " tree) for a run whose provenance names its code")
