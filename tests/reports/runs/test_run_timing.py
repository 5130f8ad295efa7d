"""How a run reports its time: the kernels' compilation (or loading from numba's cache) is
timed apart from the chunks, said on stderr as soon as numba starts to compile (with the time it
is expected to take), and recorded in provenance.json next to the compute time and the rate,
which excludes it."""

import json
import os
import subprocess
import sys
import time
from pathlib import Path

import numba.core.event as numba_event
import pytest
from scene_texts import TINY

from reports.runs import driver
from reports.runs.manifest import load_provenance
from reports.runs.scenes import parse_scene

ROOT = Path(__file__).resolve().parents[3]
SLOW_COMPILE_S = 1.5


def slow_first_call(monkeypatch, compiles=False):
    """The compiling call (the first kernel call of the run) takes SLOW_COMPILE_S longer; with
    ``compiles``, during a numba compile event (as numba signals a compilation)."""
    real = driver.run_chunk

    def compiling(*args):
        if compiles:
            with numba_event.trigger_event("numba:compile", data={"dispatcher": None}):
                time.sleep(SLOW_COMPILE_S)
        else:
            time.sleep(SLOW_COMPILE_S)
        return real(*args)

    monkeypatch.setattr(driver, "run_chunk", compiling)


@pytest.mark.slow
def test_the_rate_excludes_the_compile_time(tmp_path, monkeypatch):
    slow_first_call(monkeypatch)
    manifest = driver.run(parse_scene(TINY), tmp_path / "r", progress=False)
    record = load_provenance(tmp_path / "r")
    assert record["compile_s"] >= SLOW_COMPILE_S
    assert 0 < record["compute_s"] < SLOW_COMPILE_S
    assert record["collisions_per_s"] == round(manifest["collisions"] / record["compute_s"])


@pytest.mark.slow
def test_a_compile_is_said_on_stderr_with_its_expected_time(tmp_path, monkeypatch, capsys):
    """Said when numba starts to compile, before the progress bar, with the reference time the
    first time and this machine's last time afterwards; a run that compiles nothing says
    nothing."""
    monkeypatch.setattr(driver, "COMPILE_TIMES", tmp_path / "compile_times.json")
    monkeypatch.setitem(driver.REFERENCE_COMPILE_S, "escape kernel, elastic model", 14.0)
    real = driver.run_chunk
    slow_first_call(monkeypatch, compiles=True)
    driver.run(parse_scene(TINY), tmp_path / "r", progress=True)
    first = capsys.readouterr().err.splitlines()[0]
    assert first.startswith("tiny: compiling the numba kernels (escape kernel, elastic model:"
                            " about 14 s on 2 cores")
    assert first.endswith(" s") and "tiny:   0%|" not in first  # before the bar, not under it
    took = json.loads((tmp_path / "compile_times.json").read_text())["escape kernel, elastic model"]
    assert took >= SLOW_COMPILE_S
    driver.run(parse_scene(TINY), tmp_path / "s", progress=True)
    assert capsys.readouterr().err.startswith(
        f"tiny: compiling the numba kernels (escape kernel, elastic model: about {took:.0f} s,"
        " as the last time on this machine")
    monkeypatch.setattr(driver, "run_chunk", real)  # the kernels are loaded from the cache
    driver.run(parse_scene(TINY), tmp_path / "q", progress=True)
    assert "compiling" not in capsys.readouterr().err


def test_a_quick_compile_is_not_mentioned(tmp_path, capsys):
    driver.run(parse_scene(TINY), tmp_path / "r", progress=True)  # the kernels are loaded
    assert "compiling" not in capsys.readouterr().err


@pytest.mark.slow
def test_an_empty_numba_cache_compiles_apart_from_the_run(tmp_path):
    """A fresh process with an empty numba cache: the compilation (tens of seconds on 2 cores)
    is announced, and the run's rate is that of the chunks alone."""
    (tmp_path / "tiny.toml").write_text(TINY)
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "cache"), PYTHONPATH=str(ROOT))
    proc = subprocess.run([sys.executable, "-m", "reports.cli", "run", "tiny.toml", "--out", "r"],
                          cwd=tmp_path, env=env, capture_output=True, text=True, timeout=900)
    assert proc.returncode == 0, proc.stderr
    assert proc.stderr.startswith("tiny: compiling the numba kernels")
    record = load_provenance(tmp_path / "r")
    print(f"compile {record['compile_s']} s, compute {record['compute_s']} s")
    assert record["compile_s"] > 10 * record["compute_s"]
    assert f"kernels compiled in {record['compile_s']:.1f} s" in proc.stdout


def test_every_builtin_scene_has_an_expected_first_compile_time():
    """A new user's first run of any built-in scene says how long compiling will take (the
    2-core reference), not only that it is a first run."""
    from reports.runs.scenes import builtin_scenes, load_scene

    for name in builtin_scenes():
        key = driver._compile_key(load_scene(name))
        assert key in driver.REFERENCE_COMPILE_S, (name, key)
        assert driver.REFERENCE_COMPILE_S[key] > 0
