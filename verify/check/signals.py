"""Signals to the checking process while a check runs: ``watch_signals``.

The checked code runs in a worker process (:mod:`.worker`), but it can still signal the
checker: ``os.kill(os.getppid(), signal.SIGTERM)``. Without this guard the checker would die
there, with no report and its worker left running. While ``watch_signals()`` is active,
SIGINT, SIGTERM and SIGHUP are blocked in every thread and taken by one thread with
``sigtimedwait``, which learns who sent each:

* sent by a worker, or by a process in a worker's process group: that worker is killed, and
  the call it was making fails its property ("it sent SIGTERM to the checking process");
  the check goes on;
* sent by anyone else (Ctrl-C at the terminal, ``kill``, a closed terminal): it is raised in
  the main thread, SIGINT as ``KeyboardInterrupt`` and the others as :class:`Terminated`, so
  the check unwinds and stops its worker on the way out.

It changes the process's signal handling, so it is for a command (``bouncer check``), not for
a library call inside someone else's program. Needs ``signal.sigtimedwait`` (POSIX, not
macOS) and the main thread; elsewhere it does nothing.
"""

from __future__ import annotations

import _thread
import os
import signal
import threading
from contextlib import contextmanager

from . import worker as workers

WATCHED = tuple(getattr(signal, name) for name in ("SIGINT", "SIGTERM", "SIGHUP")
                if hasattr(signal, name))
WAIT_S = 0.1  # the watching thread looks whether the check has ended this often


class Terminated(BaseException):  # noqa: N818 - a signal, not an error (as KeyboardInterrupt)
    """The checking process was sent ``signum`` (SIGTERM, SIGHUP) from outside the check."""

    def __init__(self, signum: int) -> None:
        super().__init__(f"terminated by {signal.Signals(signum).name}")
        self.signum = signum


def _raise(signum, frame):
    if signum == signal.SIGINT:
        raise KeyboardInterrupt
    raise Terminated(signum)


def _sender_worker(pid: int):
    """The live worker whose process group ``pid`` belongs to, or None."""
    if pid <= 0:
        return None
    if pid in workers.LIVE:
        return workers.LIVE[pid]
    try:
        group, session = os.getpgid(pid), os.getsid(pid)
    except OSError:  # gone already: its group is unknown
        return None
    return workers.LIVE.get(group) or workers.LIVE.get(session)


def _watch(stop: threading.Event) -> None:
    while not stop.is_set():
        info = signal.sigtimedwait(WATCHED, WAIT_S)
        if info is None:
            continue
        culprit = _sender_worker(info.si_pid)
        if culprit is not None and culprit.proc is not None:
            name = signal.Signals(info.si_signo).name
            culprit.fault_note = (f"it sent {name} to the checking process (pid {os.getpid()});"
                                  " its worker process was killed")
            workers.kill_group(culprit.proc.pid)
            continue
        _thread.interrupt_main(info.si_signo)


@contextmanager
def watch_signals():
    """Within the block, signals from the checked code stop its worker, and signals from
    anywhere else end the check (module docstring)."""
    if (not hasattr(signal, "sigtimedwait")
            or threading.current_thread() is not threading.main_thread()):
        yield
        return
    before = {s: signal.signal(s, _raise) for s in WATCHED}
    mask = signal.pthread_sigmask(signal.SIG_BLOCK, WATCHED)
    stop = threading.Event()
    watcher = threading.Thread(target=_watch, args=(stop,), name="bouncer-signals",
                               daemon=True)
    watcher.start()
    try:
        yield
    finally:
        stop.set()
        watcher.join()
        signal.pthread_sigmask(signal.SIG_SETMASK, mask)  # a signal pending now arrives here
        for s, handler in before.items():
            signal.signal(s, handler)
