"""Work begun in the background, for the report's studies on a machine of few cores.

Much of a report runs on one core (Python, numpy, mpmath); the kernels of ``fastpath`` release
the GIL. ``begin(fn, *args)`` starts ``fn(*args)`` in a daemon thread (an interrupted report
does not wait for it) and returns a function that waits for it and returns its result, or
raises its exception in the caller's thread (``at_once``: the same, computed at once). A
``Worker`` runs the jobs handed to it one after another in one daemon thread, its numba kernels
on one thread: what a report hands it while its own work runs on one core uses the other core,
and only that one. What runs in the
background must not use mpmath: its working precision is process-wide, so two threads computing
with it at once could change each other's precision.
"""

from __future__ import annotations

import queue
import threading

import numba


class _Result:
    """The outcome of one job, for the thread that waits for it."""

    def __init__(self):
        self.done = threading.Event()
        self.value = self.error = None

    def run(self, fn, args, kwargs):
        try:
            self.value = fn(*args, **kwargs)
        except BaseException as err:  # handed to the caller of finish()
            self.error = err
        finally:
            self.done.set()

    def finish(self):
        self.done.wait()
        if self.error is not None:
            raise self.error
        return self.value


def begin(fn, *args, name="background", **kwargs):
    """Start ``fn(*args, **kwargs)`` in a daemon thread; returns ``finish()``, which waits for
    it and returns its result (or raises what it raised)."""
    result = _Result()
    threading.Thread(target=result.run, args=(fn, args, kwargs), name=name, daemon=True).start()
    return result.finish


def at_once(fn, *args, name=None, **kwargs):
    """``begin``'s contract without a thread: ``fn(*args, **kwargs)`` computed now, in the
    caller's thread; returns ``finish()``, which returns the result (or raises what it
    raised)."""
    result = _Result()
    result.run(fn, args, kwargs)
    return result.finish


class Worker:
    """One daemon thread running the jobs handed to it (``submit``) in order, numba's kernels
    on ``threads`` threads (numba's setting is per thread: the caller's is unchanged)."""

    def __init__(self, threads=1, name="report-worker"):
        self._jobs = queue.SimpleQueue()
        self._threads = threads
        threading.Thread(target=self._loop, name=name, daemon=True).start()

    def _loop(self):
        numba.set_num_threads(min(self._threads, numba.config.NUMBA_NUM_THREADS))
        while True:
            result, fn, args, kwargs = self._jobs.get()
            result.run(fn, args, kwargs)

    def submit(self, fn, *args, name=None, **kwargs):
        """Queue ``fn(*args, **kwargs)``; returns ``finish()`` as ``begin`` does (``name`` is
        accepted for ``begin``'s signature and not used)."""
        result = _Result()
        self._jobs.put((result, fn, args, kwargs))
        return result.finish
