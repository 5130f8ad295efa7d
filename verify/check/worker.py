"""Run the user's callables in a separate Python process, so that a hang, an exception, or a
crash (``os._exit``, a segfault) in them becomes a finding that names the input instead of
taking the checker down.

The worker is ``python -c "...serve_fd(FD)"``: a fresh interpreter (it does not re-run the
caller's ``__main__``), talking pickled messages over a socket pair:

    parent -> child   ("load", sys_path, {"flight_time": how, "step": how})
                      how = ("spec", "MODULE:FUNCTION") or ("pickle", bytes)
    child -> parent   ("loaded", None) | ("load-failed", text)
    child -> parent   ("ready", warm_up_note)
    parent -> child   (name, (phi, v, eps))
    child -> parent   ("ok", output) | ("raised", text) | ("unpicklable", repr of output)

After loading, the worker calls each callable once at the fixed point ``(0, pi, 0.5)`` (a
valid departure) so that import-time work and JIT compilation are not charged to the first
input's call timeout. A call that does not answer within the call timeout, or a worker that
dies, is reported as :class:`Bad` with ``fault`` "timeout" or "crash"; the worker is stopped
and a fresh one starts on the next call.
"""

from __future__ import annotations

import math
import os
import pickle
import signal
import socket
import subprocess
import sys
from multiprocessing.connection import Connection
from pathlib import Path

from .budget import Budget, BudgetSpent
from .calling import Bad, one_line
from .loading import load_callable

START_TIMEOUT = 60.0  # seconds for a worker to import the callables and warm them up
WARM_UP = (0.0, math.pi, 0.5)  # the fixed point (0, pi) at eps = 0.5: tau = 2*pi
_CHILD = "import sys; from verify.check.worker import serve_fd; serve_fd(int(sys.argv[1]))"
_ROOT = str(Path(__file__).resolve().parents[2])  # the folder holding the verify package


class Unavailable(Exception):  # noqa: N818
    """The callables cannot be loaded in a worker process (the reason is the message)."""


def how_to_load(fn, spec: str | None) -> tuple[str, object]:
    """How a worker gets ``fn``: by its ``MODULE:FUNCTION`` spec, else by pickling it.
    Raises :class:`Unavailable` when it cannot be pickled (a lambda, a closure)."""
    if spec is not None:
        return ("spec", spec)
    try:
        return ("pickle", pickle.dumps(fn))
    except Exception as err:  # noqa: BLE001 - pickling may fail in many ways
        raise Unavailable(f"cannot pickle {fn!r} ({one_line(err)})") from None


def _death(returncode) -> str:
    if returncode is None:
        return "the worker process stopped answering"
    if returncode < 0:
        try:
            return f"the worker process died (signal {signal.Signals(-returncode).name})"
        except ValueError:
            return f"the worker process died (signal {-returncode})"
    return f"the worker process died (exit code {returncode})"


class Worker:
    """A worker process for ``how`` (name -> how_to_load(...)), restarted after each fault.

    ``call(name, phi, v, eps)`` returns what the callable returned, or raises :class:`Bad`
    (an exception, a timeout, a crash) or :class:`BudgetSpent`. ``faults`` counts timeouts
    and crashes, ``restarts`` the fresh workers started after one.
    """

    def __init__(self, how: dict, call_timeout: float, budget: Budget) -> None:
        self.how = how
        self.call_timeout = float(call_timeout)
        self.budget = budget
        self.proc: subprocess.Popen | None = None
        self.conn: Connection | None = None
        self.faults = 0
        self.restarts = 0
        self.warm_up_note = ""

    # -- lifecycle
    def start(self) -> None:
        """Start a worker and load the callables. Raises :class:`Unavailable` if they do not
        load there (an import that raises, exits or kills the process), :class:`Bad` if the
        warm-up call kills it or it does not get ready in time, :class:`BudgetSpent`."""
        parent, child = socket.socketpair()
        env = dict(os.environ)
        env["PYTHONPATH"] = os.pathsep.join(filter(None, (_ROOT, env.get("PYTHONPATH"))))
        try:
            self.proc = subprocess.Popen(
                [sys.executable, "-c", _CHILD, str(child.fileno())],
                pass_fds=(child.fileno(),), env=env, cwd=os.getcwd(), stdin=subprocess.DEVNULL,
            )
        finally:
            child.close()
        self.conn = Connection(parent.detach())
        self.conn.send(("load", list(sys.path), self.how))
        deadline = self.budget.elapsed() + START_TIMEOUT
        try:  # importing: a death here is the import's (an exit or crash at import time)
            reply = self._receive(min(START_TIMEOUT, self.budget.remaining()))
        except Bad as bad:
            what = ", ".join(value if kind == "spec" else name
                             for name, (kind, value) in self.how.items())
            raise Unavailable(f"{bad.text} while importing {what}") from None
        if reply is not None and reply[0] == "load-failed":
            self.stop()
            raise Unavailable(reply[1])
        if reply is not None:  # loaded: now the warm-up call
            wait = max(0.0, min(deadline - self.budget.elapsed(), self.budget.remaining()))
            try:
                reply = self._receive(wait)
            except Bad as bad:
                raise Bad(bad.text, "the worker died in its warm-up call at (phi, v, eps) = "
                          "(0.0, pi, 0.5)", "crash") from None
        if reply is None:
            self.stop()
            if self.budget.remaining() <= 0.0:
                raise BudgetSpent
            self.faults += 1
            raise Bad(f"no answer within {START_TIMEOUT:g} s",
                      "the worker did not get ready: importing the callables and one warm-up "
                      f"call at (phi, v, eps) = (0.0, pi, 0.5) took over {START_TIMEOUT:g} s",
                      "timeout")
        self.warm_up_note = reply[1] or ""

    def stop(self) -> None:
        if self.conn is not None:
            self.conn.close()
            self.conn = None
        if self.proc is not None:
            if self.proc.poll() is None:
                self.proc.kill()
            self.proc.wait()
            self.proc = None

    def _receive(self, wait: float):
        """The next message, None if none came within ``wait`` seconds; raises :class:`Bad`
        (fault "crash") if the worker died."""
        try:
            if not self.conn.poll(None if math.isinf(wait) else wait):
                return None
            return self.conn.recv()
        except (EOFError, OSError):
            self.proc.wait()
            text = _death(self.proc.returncode)
            self.stop()
            self.faults += 1
            raise Bad(text, "", "crash") from None

    # -- calls
    def call(self, name: str, phi: float, v: float, eps: float):
        self.budget.check()
        if self.proc is None:
            self.restarts += 1
            try:
                self.start()
            except Unavailable as why:
                raise Bad(str(why), "a fresh worker could not load the callables",
                          "crash") from None
        try:
            self.conn.send((name, (phi, v, eps)))
        except OSError:
            self.proc.wait()
            text = _death(self.proc.returncode)
            self.stop()
            self.faults += 1
            raise Bad(text, f"{name} crashed the worker process", "crash") from None
        wait = min(self.call_timeout, self.budget.remaining())
        try:
            reply = self._receive(wait)
        except Bad as bad:
            raise Bad(bad.text, f"{name} crashed the worker process on a valid departure",
                      "crash") from None
        if reply is None:
            self.stop()
            if wait < self.call_timeout:
                raise BudgetSpent
            self.faults += 1
            raise Bad(f"no answer within {self.call_timeout:g} s",
                      f"{name} did not return within the call timeout of "
                      f"{self.call_timeout:g} s (it hangs, or is too slow)", "timeout")
        kind, value = reply
        if kind == "ok":
            return value
        if kind == "raised":
            raise Bad(f"exception {value}", f"{name} raised on a valid departure")
        return _Unpicklable(value)

    def callable(self, name: str):
        """A stand-in for the user's callable ``name`` that calls it in the worker."""
        return _Remote(self, name)


class _Remote:
    def __init__(self, worker: Worker, name: str) -> None:
        self.worker, self.name = worker, name

    def __call__(self, phi, v, eps):
        return self.worker.call(self.name, phi, v, eps)


class _Unpicklable:
    """An output that could not be sent back; vetting it fails with its repr."""

    def __init__(self, text: str) -> None:
        self.text = text

    def __repr__(self) -> str:
        return self.text

    def __float__(self) -> float:
        raise TypeError("an object that cannot be pickled")

    def __iter__(self):
        raise TypeError("an object that cannot be pickled")


# --------------------------------------------------------------------------- the child


def _load(how):
    kind, value = how
    if kind == "spec":
        return load_callable(value, search_cwd=True)
    return pickle.loads(value)


def serve(conn: Connection) -> None:
    """The worker's loop (in the child process)."""
    _, sys_path, hows = conn.recv()
    sys.path[:] = sys_path + [p for p in sys.path if p not in sys_path]
    try:
        fns = {name: _load(how) for name, how in hows.items()}
    except KeyboardInterrupt:
        raise
    except BaseException as err:  # noqa: BLE001 - sys.exit() too: report it to the parent
        conn.send(("load-failed", str(err) if isinstance(err, ValueError) else one_line(err)))
        return
    conn.send(("loaded", None))
    notes = []
    for name, fn in fns.items():
        try:
            fn(*WARM_UP)
        except KeyboardInterrupt:
            raise
        except BaseException as err:  # noqa: BLE001 - judged later, on the drawn inputs
            notes.append(f"the warm-up call of {name} at (0.0, pi, 0.5) raised {one_line(err)}")
    conn.send(("ready", "; ".join(notes)))
    while True:
        try:
            name, args = conn.recv()
        except EOFError:
            return
        try:
            out = fns[name](*args)
        except KeyboardInterrupt:
            raise
        except BaseException as err:  # noqa: BLE001 - the user's code (sys.exit() too): report
            conn.send(("raised", one_line(err)))
            continue
        try:
            conn.send(("ok", out))
        except Exception:  # noqa: BLE001 - an output pickle cannot carry
            conn.send(("unpicklable", repr(out)))


def serve_fd(fd: int) -> None:
    """The worker's entry point: serve on the socket inherited as file descriptor ``fd``."""
    serve(Connection(fd))
