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

An output goes back as itself only if it is made of numbers, text and short tuples or lists of
the standard library's, numpy's or mpmath's types: unpickling anything else would import the
checked code's own module into the checking process (pickle names a class by its module). Any
other output goes back as its repr, which fails the property that called.

The import has its own timeout (``import_timeout``): a module that hangs or waits while it
is imported is refused (:class:`Unavailable`, a ``ValueError`` for the caller) naming the
import. After loading, the worker calls each callable once at the fixed point ``(0, pi, 0.5)``
(a valid departure) so that import-time work and JIT compilation are not charged to the first
input's call timeout. A call that does not answer within the call timeout, or a worker that
dies, is reported as :class:`Bad` with ``fault`` "timeout" or "crash"; the worker is stopped
and a fresh one starts on the next call.

Containment. The worker runs in a session and process group of its own: a terminal's Ctrl-C
does not reach it, and ``stop`` kills the whole group (and, on Linux, every process left in
its session), so whatever the checked code forked dies with it, on every way out of the check
(the end, an error, a timeout, Ctrl-C, a signal to the checker: ``verify.check.signals``). On
Linux the worker, and every child it forks, is killed when its parent dies, even by SIGKILL.
Its stdout and stderr go to a pipe of which the last ``OUTPUT_TAIL`` bytes are kept
(``Worker.output``): a traceback or a print of the checked code never reaches the caller's
terminal. A process forked by the checked code that returns into the worker's loop exits at
once, so only the worker answers.
"""

from __future__ import annotations

import collections
import math
import numbers
import os
import pickle
import signal
import socket
import subprocess
import sys
import threading
import time
from multiprocessing.connection import Connection
from pathlib import Path

from .budget import Budget, BudgetSpent
from .calling import Bad, one_line
from .loading import load_callable

IMPORT_TIMEOUT = 60.0  # seconds for a worker to import the callables
START_TIMEOUT = 60.0  # seconds for the warm-up calls after the import
WARM_UP = (0.0, math.pi, 0.5)  # the fixed point (0, pi) at eps = 0.5: tau = 2*pi
POLL_S = 0.05  # a wait for an answer also looks this often whether the worker still lives
OUTPUT_TAIL = 4096  # bytes of the worker's stdout and stderr kept
SIGNALS_TO_FREE = tuple(getattr(signal, name) for name in ("SIGINT", "SIGTERM", "SIGHUP")
                        if hasattr(signal, name))  # unblocked in the worker
_CHILD = ("import sys; from verify.check.worker import serve_fd;"
          " serve_fd(int(sys.argv[1]), int(sys.argv[2]))")
_ROOT = str(Path(__file__).resolve().parents[2])  # the folder holding the verify package
_PR_SET_PDEATHSIG = 1  # prctl(2) option (Linux)

LIVE: dict[int, Worker] = {}  # process group -> the worker running in it (``signals``)


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

    def __init__(self, how: dict, call_timeout: float, budget: Budget,
                 import_timeout: float = IMPORT_TIMEOUT) -> None:
        self.how = how
        self.call_timeout = float(call_timeout)
        self.import_timeout = float(import_timeout)
        self.budget = budget
        self.proc: subprocess.Popen | None = None
        self.conn: Connection | None = None
        self.faults = 0
        self.restarts = 0
        self.warm_up_note = ""
        self.fault_note = ""  # why the worker was stopped from outside (``signals``)
        self._output: collections.deque = collections.deque(maxlen=OUTPUT_TAIL)

    @property
    def output(self) -> str:
        """The last ``OUTPUT_TAIL`` bytes the worker wrote to its stdout and stderr."""
        return bytes(self._output).decode("utf-8", "replace")

    def _what(self) -> str:
        return ", ".join(value if kind == "spec" else name
                         for name, (kind, value) in self.how.items())

    # -- lifecycle
    def start(self) -> None:
        """Start a worker and load the callables. Raises :class:`Unavailable` if they do not
        load there (an import that raises, exits or kills the process), :class:`Bad` if the
        warm-up call kills it or it does not get ready in time, :class:`BudgetSpent`."""
        parent, child = socket.socketpair()
        env = dict(os.environ)
        env["PYTHONPATH"] = os.pathsep.join(filter(None, (_ROOT, env.get("PYTHONPATH"))))
        self._output.clear()
        self.fault_note = ""
        try:
            self.proc = subprocess.Popen(
                [sys.executable, "-c", _CHILD, str(child.fileno()), str(os.getpid())],
                pass_fds=(child.fileno(),), env=env, cwd=os.getcwd(), stdin=subprocess.DEVNULL,
                stdout=subprocess.PIPE, stderr=subprocess.STDOUT, start_new_session=True,
            )
        finally:
            child.close()
        LIVE[self.proc.pid] = self
        threading.Thread(target=_keep_tail, args=(self.proc.stdout, self._output),
                         daemon=True).start()
        self.conn = Connection(parent.detach())
        self.conn.send(("load", list(sys.path), self.how))
        try:  # importing: a death here is the import's (an exit or crash at import time)
            reply = self._receive(min(self.import_timeout, self.budget.remaining()))
        except Bad as bad:
            raise Unavailable(f"{bad.text} while importing {self._what()}") from None
        if reply is None and self.budget.remaining() > 0.0:
            self.stop()
            raise Unavailable(f"importing {self._what()} did not finish within"
                              f" {self.import_timeout:g} s (a module to check must not hang or"
                              " wait for input when it is imported)")
        if reply is not None and reply[0] == "load-failed":
            self.stop()
            raise Unavailable(reply[1])
        if reply is not None:  # loaded: now the warm-up call
            try:
                reply = self._receive(min(START_TIMEOUT, self.budget.remaining()))
            except Bad as bad:
                raise Bad(bad.text, "the worker died in its warm-up call at (phi, v, eps) = "
                          "(0.0, pi, 0.5)", "crash") from None
        if reply is None:
            self.stop()
            if self.budget.remaining() <= 0.0:
                raise BudgetSpent
            self.faults += 1
            raise Bad(f"no answer within {START_TIMEOUT:g} s",
                      "the worker did not get ready: the warm-up calls at (phi, v, eps) = "
                      f"(0.0, pi, 0.5) took over {START_TIMEOUT:g} s", "timeout")
        self.warm_up_note = reply[1] or ""

    def stop(self) -> None:
        """Kill the worker and every process it started (its process group and, on Linux, its
        session), and wait for the worker. Safe to call at any time, more than once."""
        if self.conn is not None:
            self.conn.close()
            self.conn = None
        if self.proc is not None:
            kill_group(self.proc.pid)
            self.proc.wait()
            LIVE.pop(self.proc.pid, None)
            self.proc = None

    def _receive(self, wait: float):
        """The next message, None if none came within ``wait`` seconds; raises :class:`Bad`
        (fault "crash") if the worker died (also while a process it forked holds the socket)."""
        deadline = time.monotonic() + wait
        try:
            while True:
                left = deadline - time.monotonic()
                if self.conn.poll(max(0.0, min(POLL_S, left))):
                    return self.conn.recv()
                if self.proc.poll() is not None:
                    if self.conn.poll(0.0):  # its last message, sent before it died
                        return self.conn.recv()
                    raise EOFError
                if left <= 0.0:
                    return None
        except (EOFError, OSError):
            raise Bad(self._ended(), "", "crash") from None
        except Exception as err:  # noqa: BLE001 - not a message of the worker's: a fault
            self._ended()
            raise Bad(f"the worker process sent something that is not an answer"
                      f" ({one_line(err)})", "", "crash") from None

    def _ended(self) -> str:
        """Stop a worker that stopped answering (it died, or closed its end); why, in words."""
        try:
            self.proc.wait(timeout=1.0)
        except subprocess.TimeoutExpired:
            pass
        text = self.fault_note or _death(self.proc.poll())
        self.stop()
        self.faults += 1
        return text

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
            raise Bad(self._ended(), f"{name} crashed the worker process", "crash") from None
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
        kind, value = reply if isinstance(reply, tuple) and len(reply) == 2 else ("", reply)
        if kind == "ok":
            return value
        if kind == "raised":
            raise Bad(f"exception {value}", f"{name} raised on a valid departure")
        if kind == "unpicklable":
            return _Unpicklable(value)
        self._ended()
        raise Bad("the worker process sent something that is not an answer",
                  f"{name} disturbed the worker's messages", "crash")

    def callable(self, name: str):
        """A stand-in for the user's callable ``name`` that calls it in the worker."""
        return _Remote(self, name)


class _Remote:
    def __init__(self, worker: Worker, name: str) -> None:
        self.worker, self.name = worker, name

    def __call__(self, phi, v, eps):
        return self.worker.call(self.name, phi, v, eps)


class _Unpicklable:
    """An output that was not sent back (not made of numbers; or pickle cannot carry it);
    vetting it fails with its repr."""

    description = "an object of a type the check does not take back: numbers only"

    def __init__(self, text: str) -> None:
        self.text = text

    def __repr__(self) -> str:
        return self.text

    def __float__(self) -> float:
        raise TypeError("an object that cannot be pickled")

    def __iter__(self):
        raise TypeError("an object that cannot be pickled")


def _keep_tail(pipe, tail) -> None:
    """Read the worker's output to its end, keeping the last bytes in ``tail`` (a deque)."""
    try:
        while block := pipe.read1(OUTPUT_TAIL):
            tail.extend(block)
    except (OSError, ValueError):
        pass
    finally:
        pipe.close()


def kill_group(pid: int) -> None:
    """SIGKILL to the process group ``pid`` leads and, on Linux, to every process still in its
    session (one that left the group with setpgid); the leader itself in any case."""
    if not hasattr(os, "killpg"):  # not POSIX: the worker alone
        try:
            os.kill(pid, signal.SIGTERM)
        except OSError:
            pass
        return
    for kill in (lambda: os.killpg(pid, signal.SIGKILL), lambda: os.kill(pid, signal.SIGKILL)):
        try:
            kill()
        except (ProcessLookupError, PermissionError):
            pass
    for member in _session_members(pid):
        try:
            os.kill(member, signal.SIGKILL)
        except (ProcessLookupError, PermissionError):
            pass


def _session_members(sid: int) -> list[int]:
    """The processes of session ``sid`` (Linux: from /proc; elsewhere none)."""
    members = []
    try:
        entries = os.listdir("/proc")
    except OSError:
        return members
    for entry in entries:
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat", "rb") as f:
                fields = f.read().rpartition(b")")[2].split()
        except OSError:
            continue
        if len(fields) > 3 and int(fields[3]) == sid and int(entry) != os.getpid():
            members.append(int(entry))
    return members


# --------------------------------------------------------------------------- the child


def _load(how):
    kind, value = how
    if kind == "spec":
        return load_callable(value, search_cwd=True)
    return pickle.loads(value)


def serve(conn: Connection) -> None:
    """The worker's loop (in the child process). Everything the checked code raises, a
    KeyboardInterrupt and sys.exit() included, is reported to the parent as its result; a
    process it forked that comes back here exits at once."""
    me = os.getpid()

    def only_the_worker():
        if os.getpid() != me:
            os._exit(0)

    _, sys_path, hows = conn.recv()
    sys.path[:] = sys_path + [p for p in sys.path if p not in sys_path]
    try:
        fns = {name: _load(how) for name, how in hows.items()}
    except BaseException as err:  # noqa: BLE001 - sys.exit() too: report it to the parent
        only_the_worker()
        conn.send(("load-failed", str(err) if isinstance(err, ValueError) else one_line(err)))
        return
    only_the_worker()
    conn.send(("loaded", None))
    notes = []
    for name, fn in fns.items():
        try:
            fn(*WARM_UP)
        except BaseException as err:  # noqa: BLE001 - judged later, on the drawn inputs
            notes.append(f"the warm-up call of {name} at (0.0, pi, 0.5) raised {one_line(err)}")
        only_the_worker()
    conn.send(("ready", "; ".join(notes)))
    while True:
        try:
            name, args = conn.recv()
        except EOFError:
            return
        try:
            out = fns[name](*args)
        except BaseException as err:  # noqa: BLE001 - the user's code (sys.exit() too): report
            only_the_worker()
            conn.send(("raised", one_line(err)))
            continue
        only_the_worker()
        try:
            out = _portable(out)
        except (TypeError, ValueError, OverflowError):
            conn.send(("unpicklable", _repr(out)))
            continue
        try:
            conn.send(("ok", out))
        except Exception:  # noqa: BLE001 - an output pickle cannot carry
            conn.send(("unpicklable", _repr(out)))


PLAIN_MODULES = ("builtins", "numpy", "mpmath", "fractions", "decimal")
PLAIN_ITEMS = 16  # items of a tuple or list sent back (a step returns three)


def _plain(value, depth: int = 0) -> bool:
    """Whether ``value`` can go back to the checker without importing anything of the checked
    code there: an object of the standard library's, numpy's or mpmath's types (numpy arrays of
    numbers only), or a short tuple or list of them."""
    kind = type(value)
    if kind.__module__.partition(".")[0] not in PLAIN_MODULES:
        return False
    if kind in (tuple, list):
        return (depth < 2 and len(value) <= PLAIN_ITEMS
                and all(_plain(x, depth + 1) for x in value))
    if isinstance(value, dict | set | frozenset):
        return False
    dtype = getattr(value, "dtype", None)
    return dtype is None or getattr(dtype, "kind", "O") in "biufc"


def _portable(value, depth: int = 0):
    """``value`` as it goes back to the checker: itself if ``_plain``; a real number of the
    checked code's own type as the float it converts to (a float subclass is a number); a
    short tuple or list element by element. TypeError for anything else."""
    if _plain(value, depth):
        return value
    if isinstance(value, numbers.Real) and not isinstance(value, bool):
        return float(value)
    if isinstance(value, tuple | list) and depth < 2 and len(value) <= PLAIN_ITEMS:
        return tuple(_portable(x, depth + 1) for x in value)
    raise TypeError(type(value).__name__)


def _repr(value, limit: int = 200) -> str:
    try:
        text = repr(value)
    except Exception as err:  # noqa: BLE001 - the checked code's repr
        text = f"<{type(value).__name__} whose repr raised {one_line(err)}>"
    return text if len(text) <= limit else text[:limit - 3] + "..."


def _die_with_parent(parent: int) -> None:
    """Linux: SIGKILL this process when its parent dies (prctl PR_SET_PDEATHSIG), and every
    process it forks when that one's parent dies; exit at once if the parent is gone already.
    Elsewhere nothing: ``Worker.stop`` still kills the process group."""
    try:
        import ctypes

        prctl = ctypes.CDLL(None, use_errno=True).prctl
    except (OSError, AttributeError, TypeError):  # not Linux
        return

    def arm():
        prctl(_PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)

    arm()
    os.register_at_fork(after_in_child=arm)
    if os.getppid() != parent:
        os._exit(0)


def serve_fd(fd: int, parent: int) -> None:
    """The worker's entry point: serve on the socket inherited as file descriptor ``fd``;
    ``parent`` is the checking process."""
    _die_with_parent(parent)
    if hasattr(signal, "pthread_sigmask"):  # the checker may block them (``signals``)
        signal.pthread_sigmask(signal.SIG_UNBLOCK, SIGNALS_TO_FREE)
    try:
        serve(Connection(fd))
    except (KeyboardInterrupt, EOFError, OSError):  # the checker went away: nothing to say
        os._exit(1)
