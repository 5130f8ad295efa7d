"""fastpath's array calls from several Python threads at once, under every threading layer.

numba's workqueue layer aborts the process (SIGABRT) when two threads enter parallel code at
once; fastpath holds a lock around its parallel kernels while that layer runs
(``fastpath.arithmetic.jit``). The layer is chosen once per process, so the workqueue case runs
in a subprocess with NUMBA_THREADING_LAYER=workqueue.
"""

import os
import subprocess
import sys
import textwrap
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pytest

import fastpath

ROOT = Path(__file__).resolve().parents[2]

SCRIPT = textwrap.dedent("""
    import numpy as np, numba
    from concurrent.futures import ThreadPoolExecutor
    import fastpath
    rng = np.random.default_rng(1)
    phi, v = rng.uniform(-3, 3, 20000), rng.uniform(1, 10, 20000)
    want = fastpath.step(phi, v, 0.6)
    def work(k):
        for _ in range(5):
            got = fastpath.step(phi, v, 0.6)
            assert all(np.array_equal(a, b) for a, b in zip(got, want))
            fastpath.flight(phi, v, 0.6, drag=0.01)
            fastpath.holmes_step(phi, v, 0.6)
        return k
    with ThreadPoolExecutor(4) as pool:
        done = sorted(pool.map(work, range(8)))
    print(done, numba.threading_layer())
""")


@pytest.mark.slow
def test_array_calls_from_four_threads_under_the_workqueue_layer():
    """Four threads, eight tasks of step/flight/holmes_step on 20,000 states: the process
    survives, every result equals the single-threaded one, and the layer was workqueue."""
    env = dict(os.environ, NUMBA_THREADING_LAYER="workqueue")
    done = subprocess.run([sys.executable, "-c", SCRIPT], cwd=ROOT, env=env,
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout.strip().endswith("[0, 1, 2, 3, 4, 5, 6, 7] workqueue")


def test_array_calls_from_four_threads_give_the_single_threaded_results():
    """In this process's layer (OpenMP or TBB where available): concurrent array calls
    agree bit for bit with one call alone."""
    rng = np.random.default_rng(2)
    phi, v = rng.uniform(-3, 3, 5000), rng.uniform(1, 10, 5000)
    want = fastpath.step(phi, v, 0.6)

    def work(_):
        return fastpath.step(phi, v, 0.6)

    with ThreadPoolExecutor(4) as pool:
        for got in pool.map(work, range(8)):
            for a, b in zip(got, want, strict=True):
                np.testing.assert_array_equal(a, b)
