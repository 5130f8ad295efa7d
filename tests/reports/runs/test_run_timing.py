"""How a run reports its time: the kernels' compilation (or loading from numba's cache) is
timed apart from the chunks, said on stderr when it takes a while, and recorded in
provenance.json next to the compute time and the rate, which excludes it."""

import os
import subprocess
import sys
import time
from pathlib import Path

import pytest
from scene_texts import TINY

from reports.runs import driver
from reports.runs.manifest import load_provenance
from reports.runs.scenes import parse_scene

ROOT = Path(__file__).resolve().parents[3]
SLOW_COMPILE_S = 1.5


def slow_first_call(monkeypatch):
    """The compiling call (the first kernel call of the run) takes SLOW_COMPILE_S longer."""
    real = driver.run_chunk

    def compiling(*args):
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
def test_a_slow_compile_is_said_on_stderr(tmp_path, monkeypatch, capsys):
    slow_first_call(monkeypatch)
    monkeypatch.setattr(driver, "COMPILE_NOTICE_S", 0.2)
    driver.run(parse_scene(TINY), tmp_path / "r", progress=True)
    err = capsys.readouterr().err
    first = err.splitlines()[0]
    assert first.startswith("tiny: compiling the numba kernels (a first run takes ~30 s;")
    assert first.endswith(" s") and "tiny:   0%|" not in first  # before the bar, not under it
    driver.run(parse_scene(TINY), tmp_path / "q", progress=False)
    assert capsys.readouterr().err == ""


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
