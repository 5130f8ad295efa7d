"""Ctrl-C at a safe point: ``deferred_interrupt`` holds SIGINT back while a block runs.

The driver merges a chunk, writes the checkpoint and then the manifest inside this block, so an
interrupt never leaves the in-memory tally half-merged or a file half-written; the
KeyboardInterrupt is raised as soon as the block ends. Outside the main thread (where signal
handlers cannot be set) the block runs unprotected; each file is still replaced atomically.
"""

from __future__ import annotations

import signal
import threading
from contextlib import contextmanager


@contextmanager
def deferred_interrupt():
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    pending = []
    previous = signal.signal(signal.SIGINT, lambda signum, frame: pending.append(signum))
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
    if pending and callable(previous):  # the default handler raises KeyboardInterrupt
        previous(signal.SIGINT, None)
