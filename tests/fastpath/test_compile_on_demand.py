"""Compiled on demand: nothing at import, and a loop compiled for one model compiles no other
model's code (``fastpath.arithmetic.jit``, ``fastpath.kernels.particle``).

The checks that count what numba compiles run in a fresh interpreter with an empty numba cache
(a kernel loaded from the cache compiles nothing, so in this process they could not fail).
"""

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numba
import numpy as np
import pytest

import fastpath
from fastpath.arithmetic.jit import PARALLEL_MIN, typed_overload
from fastpath.physics import dissipative, elastic

ROOT = Path(__file__).resolve().parents[2]


def _model_number(physics):
    """1 for an elastic description, 2 for a dissipative one (overload below)."""


@typed_overload(_model_number)
def _model_number_of(physics):
    if physics.instance_class is type(elastic(0.0)):
        return lambda physics: 1

    def dissipative_number(physics):  # numba cannot type this: compiling it would fail
        return _plain_python()
    return dissipative_number


def _plain_python():
    """Not compiled by numba: a compiled function that calls it fails to type."""
    return 2


@numba.njit
def _number(physics):
    return _model_number(physics)


def test_an_overload_compiles_only_the_implementation_of_the_description_class():
    """The elastic call compiles; the dissipative implementation, which numba cannot compile,
    is never typed for it (a branch on the model would type both sides)."""
    assert _number(elastic(0.6)) == 1
    with pytest.raises(numba.core.errors.TypingError):
        _number(dissipative(0.6, 0.01, 1, 0.9))


def test_small_array_calls_run_serially_with_the_parallel_kernels_numbers():
    """Below PARALLEL_MIN elements the array calls run the serial compilation of the same
    kernel: the same numbers as the parallel one, bit for bit."""
    rng = np.random.default_rng(8)
    phi, v = rng.uniform(-3.0, 3.0, PARALLEL_MIN), rng.uniform(0.5, 8.0, PARALLEL_MIN)
    eps = rng.choice([0.3, 0.6, 1.0, 2.5], PARALLEL_MIN)
    for call in (lambda p, w, e: fastpath.flight(p, w, e).tau,
                 lambda p, w, e: fastpath.flight(p, w, e, drag=0.01).tau):
        whole, part = call(phi, v, eps), call(phi[:100], v[:100], eps[:100])
        np.testing.assert_array_equal(part, whole[:100])
    good = fastpath.flight(phi, v, eps).status == 0
    whole = fastpath.step(phi[good], v[good], eps[good])
    part = fastpath.step(phi[good][:100], v[good][:100], eps[good][:100])
    for a, b in zip(part, whole, strict=True):
        np.testing.assert_array_equal(a, b[:100])


SCRIPT = textwrap.dedent("""
    import json, sys
    import numba.core.event as event
    compiled = []

    class Record(event.Listener):
        def on_start(self, e):
            d = e.data["dispatcher"]  # a kernel's dispatcher for compiled callers by its name
            name = d.py_func.__qualname__.removesuffix("_for_compiled_callers")
            compiled.append(f"{d.py_func.__module__}.{name}")

        def on_end(self, e):
            pass

    event.register("numba:compile", Record())
    import fastpath, verify, reports.cli
    reports.cli.build_parser()  # imports every command's module
    result = {"import": list(compiled)}
    import numpy as np
    from fastpath.kernels.arrays import Bins, EscapeCounts, Flags, Holes, Horizon, Sample, Starts
    from fastpath.kernels.escape import escape_chunk
    from fastpath.physics import elastic
    del compiled[:]
    fastpath.orbit(4.0, 3.0, 0.6, 10, model="holmes")
    result["holmes orbit"] = list(compiled)
    del compiled[:]
    m = 8
    escape_chunk(elastic(0.6), Starts(phi=np.full(m, 4.0), v=np.full(m, 3.0), t=np.zeros(m),
                                      n=np.zeros(m, np.int64)),
                 Holes(lo=np.array([1.85]), width=np.array([0.3])),
                 Horizon(max_collisions=50, max_time=1e7),
                 Bins(n_edges=np.arange(5.0), t_edges=np.arange(5.0), record_n=True,
                      record_t=True), Sample.none(m), EscapeCounts.zeros(2, 1, 5, 5),
                 Flags.zeros(m))
    result["elastic escape"] = list(compiled)
    print(json.dumps(result))
""")

# the solvers of the other models (prefixes of compiled functions' names); a loop may still
# compile small helpers of their modules (the departure check, the state array's entries)
DISSIPATIVE_SOLVERS = ("fastpath.dissipative.laws.", "fastpath.dissipative.special.",
                       "fastpath.dissipative.drag.", "fastpath.dissipative.drag_flight.",
                       "fastpath.dissipative.short_flight.", "fastpath.dissipative.impact.",
                       "fastpath.dissipative.carried.advance",
                       "fastpath.dissipative.carried.inelastic_advance",
                       "fastpath.dissipative.sticking.detachment",
                       "fastpath.dissipative.sticking.drag_", "fastpath.dissipative.sticking.accu")
# a dissipative loop's handling of the carried state, which an elastic loop never runs
DISSIPATIVE_STATE = ("fastpath.dissipative.carried.", "fastpath.kernels.records.store_carried",
                     "fastpath.kernels.particle.step_advance",
                     "fastpath.kernels.particle.departure_point")
EXACT_SOLVERS = ("fastpath.elastic.concave.", "fastpath.elastic.lower_bound.",
                 "fastpath.elastic.lockstep.", "fastpath.elastic.collision.",
                 "fastpath.elastic.flight.solve_flight", "fastpath.elastic.flight.flight_from",
                 "fastpath.elastic.flight.certified_flight")


@pytest.mark.slow
def test_imports_compile_nothing_and_each_model_compiles_its_own_code_only(tmp_path):
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "numba"), PYTHONPATH=str(ROOT))
    done = subprocess.run([sys.executable, "-c", SCRIPT], cwd=tmp_path, env=env,
                          capture_output=True, text=True, timeout=1200)
    assert done.returncode == 0, done.stderr[-3000:]
    compiled = json.loads(done.stdout.splitlines()[-1])
    assert compiled["import"] == []
    holmes = compiled["holmes orbit"]
    assert "fastpath.kernels.orbit.orbit_loop" in holmes
    assert not [name for name in holmes if name.startswith(EXACT_SOLVERS + DISSIPATIVE_SOLVERS)]
    escape = compiled["elastic escape"]
    assert "fastpath.kernels.escape._escape_lanes" in escape
    assert "fastpath.elastic.concave.concave_flight" in escape  # the lanes' fallback
    assert not [name for name in escape if name.startswith(DISSIPATIVE_SOLVERS)]
    assert not [name for name in escape if name.startswith(DISSIPATIVE_STATE)]


TWO_WAYS = textwrap.dedent("""
    import json, os
    import numba.core.event as event
    compiled = []

    class Record(event.Listener):
        def on_start(self, e):
            d = e.data["dispatcher"]
            compiled.append(f"{d.py_func.__module__}.{d.py_func.__qualname__}")

        def on_end(self, e):
            pass

    event.register("numba:compile", Record())
    import fastpath
    from fastpath.arithmetic.jit import CACHE_DIR
    from fastpath.elastic import collision, concave
    result = {"tau": fastpath.flight_time(4.0, 3.0, 0.6)}  # runs step's collision
    result["first"] = list(compiled)
    result["python signatures"] = {"collide": len(collision.collide.signatures),
                                   "concave_flight": len(concave.concave_flight.signatures)}
    twin = concave.concave_flight.for_compiled_callers
    try:
        twin.get_overload(twin.signatures[0])(4.0, 0.0, 1.0, 3.0, 0.6, 0.0)
        result["twin called"] = "returned"
    except TypeError as error:
        result["twin called"] = str(error)
    del compiled[:]
    fastpath.step([0.0, 1.0, 2.0], 3.0, 0.6)  # compiled code that calls collide
    result["second"] = list(compiled)
    result["cached"] = sorted(name for _, _, names in os.walk(CACHE_DIR) for name in names
                              if name.endswith(".nbi"))
    print(json.dumps(result))
""")


@pytest.mark.slow
def test_helpers_compile_for_compiled_callers_only_and_a_python_kernel_serves_both(tmp_path):
    """A kernel called only from compiled code gets no CPython wrapper, no machine code and no
    cache file (its compiled callers hold it), cannot be called from Python, and gives the same
    flight; one compiled for Python first is what compiled callers then use (no second
    compilation)."""
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "numba"), PYTHONPATH=str(ROOT))
    done = subprocess.run([sys.executable, "-c", TWO_WAYS], cwd=tmp_path, env=env,
                          capture_output=True, text=True, timeout=1200)
    assert done.returncode == 0, done.stderr[-3000:]
    result = json.loads(done.stdout.splitlines()[-1])
    assert result["tau"] == fastpath.flight_time(4.0, 3.0, 0.6)
    assert "fastpath.elastic.collision.collide" in result["first"]
    assert ("fastpath.elastic.concave.concave_flight_for_compiled_callers"
            in result["first"])
    assert result["python signatures"] == {"collide": 1, "concave_flight": 0}
    assert "compiled callers only" in result["twin called"]
    assert "fastpath.api._steps_serial" in result["second"]
    assert not [name for name in result["second"] if ".collide" in name]
    assert any(name.startswith("collision.collide-") for name in result["cached"])
    assert not [name for name in result["cached"] if "compiled_callers" in name]
    assert not [name for name in result["cached"] if name.startswith("concave.")]
