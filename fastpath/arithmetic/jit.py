"""One place for the numba options every kernel uses.

``fastmath`` stays off: the rigour of the lower-bound step and the error bounds of the gap
assume IEEE round-to-nearest arithmetic, which reassociation would break.

Compiled kernels are cached on disk (``cache=True``), but numba checks only the timestamp of the
file that defines a kernel, not of the kernels it calls from other modules: an edited callee
would silently keep its old machine code. So the cache lives in a directory named by a digest of
all of fastpath's sources, under ``NUMBA_CACHE_DIR`` if set, else the user cache directory.
numba reads that setting when a kernel is decorated, so it is changed only for that moment and
other libraries' caches stay where they were.

Two limits of numba that the kernels respect (numba 0.68 loses the writes otherwise, silently):
inside a ``prange`` loop an array held in a tuple (``fastpath.kernels.arrays``) is written only
through a called function, never as ``group.array[i] = ...`` in the loop body itself; and an
``overload`` (``fastpath.physics.model_of``) is not inlined into its caller (``inline="always"``
dropped writes to arrays unpacked from a tuple). LLVM still inlines and folds it.

Threads. numba's ``workqueue`` threading layer (the fallback where neither TBB nor OpenMP can be
loaded) aborts the whole process (SIGABRT) when two Python threads enter parallel code at once.
``parallel_jit`` kernels are therefore called through a wrapper that holds one process-wide lock
while numba runs that layer (or has not chosen one yet); with TBB or OpenMP, which are safe to
enter from several threads, calls run concurrently. The kernels are entered from Python only.
"""

import functools
import hashlib
import os
import threading
from pathlib import Path

import numba


def _cache_dir():
    package = Path(__file__).resolve().parents[1]
    digest = hashlib.sha256()
    for path in sorted(package.rglob("*.py")):
        digest.update(path.relative_to(package).as_posix().encode() + b"\0" + path.read_bytes())
    root = os.environ.get("NUMBA_CACHE_DIR") or os.path.join(
        os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache"),
        "bouncer-verify",
        "numba",
    )
    return os.path.join(root, digest.hexdigest()[:16])


CACHE_DIR = _cache_dir()


def _cached_njit(**options):
    def decorate(function):
        saved = numba.config.CACHE_DIR
        numba.config.CACHE_DIR = CACHE_DIR
        try:
            return numba.njit(cache=True, nogil=True, error_model="numpy", **options)(function)
        finally:
            numba.config.CACHE_DIR = saved

    return decorate


_WORKQUEUE_LOCK = threading.Lock()


def _serialise():
    """Whether a parallel kernel must hold the lock (module docstring)."""
    try:
        return numba.threading_layer() == "workqueue"
    except ValueError:  # no parallel kernel has run yet: the layer is not chosen
        return True


def parallel_jit(function):
    """``numba.njit(parallel=True)`` (cached), called through the workqueue lock (module
    docstring); the compiled dispatcher is the wrapper's ``kernel``."""
    kernel = _cached_njit(parallel=True)(function)

    @functools.wraps(function)
    def call(*args):
        if _serialise():
            with _WORKQUEUE_LOCK:
                return kernel(*args)
        return kernel(*args)

    call.kernel = kernel
    return call


jit = _cached_njit()
# scalar helpers of the lockstep kernels: inlined into the loop so that it can be vectorised
inline_jit = _cached_njit(inline="always")
