"""Work begun in a background thread, for the report's studies on a machine of few cores.

Much of a report runs on one core (Python, numpy, mpmath); the kernels of ``fastpath`` release
the GIL. ``begin(fn, *args)`` starts ``fn(*args)`` in a daemon thread (an interrupted report
does not wait for it) and returns a function that waits for it and returns its result, or
raises its exception in the caller's thread. What runs in the background must not use mpmath:
its working precision is process-wide, so two threads computing with it at once could change
each other's precision.
"""

from __future__ import annotations

import threading


def begin(fn, *args, name="background", **kwargs):
    """Start ``fn(*args, **kwargs)`` in a daemon thread; returns ``finish()``, which waits for
    it and returns its result (or raises what it raised)."""
    box = {}

    def work():
        try:
            box["result"] = fn(*args, **kwargs)
        except BaseException as err:  # handed to the caller of finish()
            box["error"] = err

    thread = threading.Thread(target=work, name=name, daemon=True)
    thread.start()

    def finish():
        thread.join()
        if "error" in box:
            raise box["error"]
        return box["result"]
    return finish
