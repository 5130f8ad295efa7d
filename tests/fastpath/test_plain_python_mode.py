"""With ``NUMBA_DISABLE_JIT=1`` numba compiles nothing and the kernels run as plain Python (the
mode of the mutation driver, ``scripts/mutation/ensemble.py``): fastpath still imports, and a
flight and a step give the compiled code's numbers bit for bit."""

import json
import os
import subprocess
import sys
from pathlib import Path

import fastpath

ROOT = Path(__file__).resolve().parents[2]

SCRIPT = """
import json, fastpath
print(json.dumps([fastpath.flight_time(4.0, 3.0, 0.6), *map(float, fastpath.step(4.0, 3.0, 0.6)),
                  fastpath.flight_time(1.0, 2.0, 2.5)]))
"""


def test_fastpath_runs_as_plain_python_with_the_compiled_numbers(tmp_path):
    env = dict(os.environ, NUMBA_DISABLE_JIT="1", PYTHONPATH=str(ROOT))
    done = subprocess.run([sys.executable, "-c", SCRIPT], cwd=tmp_path, env=env,
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr[-3000:]
    plain = json.loads(done.stdout.splitlines()[-1])
    compiled = [fastpath.flight_time(4.0, 3.0, 0.6), *map(float, fastpath.step(4.0, 3.0, 0.6)),
                fastpath.flight_time(1.0, 2.0, 2.5)]
    assert plain == compiled
