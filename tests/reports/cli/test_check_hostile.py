"""``bouncer check`` against checked code that fights back: it forks, at import or in a call;
it signals the checker; it raises KeyboardInterrupt; it hangs while imported; it answers with
text. Each gives its documented exit status and a right report (or one line), nothing of it
reaches the terminal, and nothing it started is left running, however the check ends (the
checker itself killed by SIGTERM, SIGINT, SIGHUP or SIGKILL included).

Each case runs ``bouncer check`` in its own process (the checked code signals its parent),
in a folder holding the checked module; what the module forks writes its pid to pids.txt, so
that the test can see that every one of them is gone.
"""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

pytestmark = pytest.mark.slow  # a fresh bouncer process per case (seconds each)

ROOT = Path(__file__).resolve().parents[3]
QUICK = ["--suite", "fixed_points", "--max-examples", "3", "--no-progress"]

RECORD = """
import os, time

def record():
    with open("pids.txt", "a") as f:
        f.write(f"{os.getpid()}\\n")
"""

MODULES = {
    "forks": RECORD + """
def flight_time(phi, v, eps):
    if os.fork() == 0:
        record()
        time.sleep(600)
        os._exit(0)
    return 2.0 * v
""",
    "forks_and_returns": RECORD + """
def flight_time(phi, v, eps):
    if os.fork() == 0:  # the child returns too, into the worker's loop
        record()
    return 2.0 * v
""",
    "forks_at_import": RECORD + """
if os.fork() == 0:
    record()
    time.sleep(600)
    os._exit(0)

def flight_time(phi, v, eps):
    return 2.0 * v
""",
    "leaves_its_group": RECORD + """
def flight_time(phi, v, eps):
    if os.fork() == 0:
        os.setpgid(0, 0)  # a group of its own, in the worker's session
        record()
        time.sleep(600)
        os._exit(0)
    return 2.0 * v
""",
    "kills_its_parent": """
import os, signal

def flight_time(phi, v, eps):
    os.kill(os.getppid(), signal.SIGTERM)
    return 2.0 * v
""",
    "interrupts": """
def flight_time(phi, v, eps):
    raise KeyboardInterrupt
""",
    "hangs_at_import": """
import time
time.sleep(600)

def flight_time(phi, v, eps):
    return 2.0 * v
""",
    "answers_text": """
def flight_time(phi, v, eps):
    return "1.0"
""",
    "prints": """
import sys

def flight_time(phi, v, eps):
    print("chatter on stdout")
    print("Traceback (most recent call last): chatter on stderr", file=sys.stderr)
    return 2.0 * v
""",
    "own_number_type": RECORD + """
record()  # at import: only the worker may import this module

class Tau(float):
    pass

def flight_time(phi, v, eps):
    return Tau(2.0 * v)
""",
    "own_object": """
class Box:
    def __init__(self, x):
        self.x = x

def flight_time(phi, v, eps):
    return Box(2.0 * v)
""",
    "slow_and_forks": RECORD + """
def flight_time(phi, v, eps):
    record()
    if os.fork() == 0:
        record()
        time.sleep(600)
        os._exit(0)
    time.sleep(0.5)
    return 2.0 * v
""",
}


@pytest.fixture
def folder(tmp_path):
    for name, text in MODULES.items():
        (tmp_path / f"{name}.py").write_text(text)
    return tmp_path


def command(target, *options):
    return [sys.executable, "-m", "reports.cli", "check", f"{target}:flight_time", *options]


def check(folder, target, *options, timeout=300):
    return subprocess.run(command(target, *options), cwd=folder, capture_output=True,
                          text=True, timeout=timeout,
                          env=dict(os.environ, PYTHONPATH=str(ROOT)))


def alive(pid):
    """Whether ``pid`` runs (a zombie waiting for its reaper counts as gone)."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rpartition(")")[2].split()[0] != "Z"
    except FileNotFoundError:
        return False


def left_running(folder, wait=5.0):
    """The recorded pids still running after up to ``wait`` seconds."""
    path = folder / "pids.txt"
    pids = [int(x) for x in path.read_text().split()] if path.exists() else []
    deadline = time.monotonic() + wait
    while any(alive(p) for p in pids) and time.monotonic() < deadline:
        time.sleep(0.1)
    return [p for p in pids if alive(p)]


needs_proc = pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="needs /proc")


@needs_proc
@pytest.mark.parametrize("target", ["forks", "forks_and_returns", "forks_at_import",
                                    "leaves_its_group"])
def test_what_the_checked_code_forks_is_gone_when_the_check_ends(folder, target):
    proc = check(folder, target, *QUICK)
    assert proc.returncode == 0, proc.stdout + proc.stderr  # 2*v holds at the fixed points
    assert "PASS  fixed_points" in proc.stdout and proc.stderr == ""
    assert (folder / "pids.txt").exists()
    assert left_running(folder) == []


def test_a_checked_function_that_signals_the_checker_fails_its_property(folder):
    proc = check(folder, "kills_its_parent", *QUICK)
    assert proc.returncode == 1, proc.stdout + proc.stderr
    assert "FAIL  fixed_points" in proc.stdout and proc.stderr == ""
    assert "obtained it sent SIGTERM to the checking process" in proc.stdout


def test_a_keyboard_interrupt_raised_by_the_checked_code_is_its_failure(folder):
    proc = check(folder, "interrupts", *QUICK)
    assert proc.returncode == 1
    assert "FAIL  fixed_points" in proc.stdout and "obtained exception KeyboardInterrupt" in \
        proc.stdout
    assert proc.stderr == ""  # no worker traceback


def test_a_module_that_hangs_while_imported_is_bad_input_naming_the_import(folder):
    started = time.monotonic()
    proc = check(folder, "hangs_at_import", *QUICK, "--import-timeout", "2")
    assert time.monotonic() - started < 60
    assert proc.returncode == 2 and proc.stdout == ""
    assert proc.stderr == ("bouncer: error: importing hangs_at_import:flight_time did not"
                           " finish within 2 s (a module to check must not hang or wait for"
                           " input when it is imported)\n")


def test_text_is_not_a_flight_time(folder):
    proc = check(folder, "answers_text", *QUICK)
    assert proc.returncode == 1
    assert "obtained '1.0'" in proc.stdout
    assert "the flight time is not a real number (a str)" in proc.stdout


def test_the_checked_code_prints_nothing_to_the_terminal(folder):
    proc = check(folder, "prints", *QUICK)
    assert proc.returncode == 0 and proc.stderr == ""
    assert "chatter" not in proc.stdout


@needs_proc
@pytest.mark.parametrize(("sig", "status", "line"), [
    (signal.SIGTERM, 143, "bouncer: terminated by SIGTERM: the check was stopped with its"
                          " worker process\n"),
    (signal.SIGHUP, 129, "bouncer: terminated by SIGHUP: the check was stopped with its worker"
                         " process\n"),
    (signal.SIGINT, 130, "bouncer: interrupted\n"),
    (signal.SIGKILL, -9, ""),
])
def test_a_checker_stopped_from_outside_leaves_nothing_running(folder, sig, status, line):
    """The worker and what it forked are killed on every way out; after SIGKILL, which the
    checker cannot handle, the worker dies with its parent and its children with theirs."""
    proc = subprocess.Popen(command("slow_and_forks", "--suite", "fixed_points",
                                    "--no-progress"),
                            cwd=folder, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, env=dict(os.environ, PYTHONPATH=str(ROOT)))
    try:
        deadline = time.monotonic() + 120
        while time.monotonic() < deadline and len(
                (folder / "pids.txt").read_text().split() if (folder / "pids.txt").exists()
                else []) < 4:
            time.sleep(0.1)
        proc.send_signal(sig)
        out, err = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    assert proc.returncode == status
    assert err == line
    assert left_running(folder) == []


def test_the_checked_module_is_imported_by_the_worker_only(folder):
    """An answer of the module's own type would make pickle import the module into the
    checker: a number of its own type goes back as the float it is, anything else as text."""
    proc = check(folder, "own_number_type", *QUICK)
    assert proc.returncode == 0 and "PASS  fixed_points" in proc.stdout
    (worker,) = (folder / "pids.txt").read_text().split()  # one import, in one process
    proc = check(folder, "own_object", *QUICK)
    assert proc.returncode == 1
    assert "obtained <own_object.Box object at" in proc.stdout
    assert "not a real number (an object of a type the check does not take back" in proc.stdout
