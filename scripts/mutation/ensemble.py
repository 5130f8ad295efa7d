"""Hand-rolled mutation driver for numba kernels (mutmut cannot): ``fastpath/ensemble.py`` and
``fastpath/lockstep.py``.

    python scripts/mutation/ensemble.py SCRATCH_COPY [FUNCTION,...]

Operators, applied one at a time inside the functions of ``TARGETS`` (the escape/censor
accounting, the lanes and the lockstep flight; a comma-separated list restricts the run):

* comparison: ``<`` <-> ``<=``, ``>`` <-> ``>=``, ``==`` <-> ``!=``;
* arithmetic: ``+`` <-> ``-`` (binary and augmented assignment);
* integer constant ``c`` -> ``c + 1``.

Each mutant replaces its file in the scratch copy (via ``ast.unparse``) and runs the ensemble
and lockstep tests with ``NUMBA_DISABLE_JIT=1``: the kernels run as plain Python (no compile per
mutant), where they pass as compiled given the pytest plugin ``nopython_shims`` (``sin_cos`` of
NaN is NaN, as compiled). Two tests are deselected: one compares thread counts
(meaningless without numba) and one takes ~40 s; both are run by the normal suite. A mutant is
killed when pytest exits non-zero, a timeout when it runs past ``TIMEOUT`` seconds.
"""

from __future__ import annotations

import ast
import copy
import glob
import os
import subprocess
import sys
import time

TARGETS = {
    "fastpath/ensemble.py": ("exit_hole", "in_hole", "bin_index", "_escape_groups",
                             "lane_collide", "_escape_lanes", "_load"),
    "fastpath/lockstep.py": ("_evaluation", "_start", "_answer", "_running", "moderate_bracket",
                             "lockstep_collide", "lockstep_flight_one"),
}
TIMEOUT = 300
TESTS = [
    "tests/fastpath/test_lockstep.py",
    "tests/fastpath/test_ensemble.py",
    "tests/reports/runs/test_hole_edges.py",
    "tests/reports/runs/test_censoring.py",
    "tests/reports/runs/test_settled_path.py",
]
DESELECT = [
    "tests/fastpath/test_ensemble.py::test_counts_do_not_depend_on_the_number_of_threads",
    "tests/reports/runs/test_settled_path.py::"
    "test_settled_collisions_give_the_fast_histograms_bin_for_bin[every]",
]
_SWAP = {ast.Lt: ast.LtE, ast.LtE: ast.Lt, ast.Gt: ast.GtE, ast.GtE: ast.Gt,
         ast.Eq: ast.NotEq, ast.NotEq: ast.Eq, ast.Add: ast.Sub, ast.Sub: ast.Add}


def sites(tree, functions):
    """(function, line, kind, node, index) for every mutable node, in a fixed order."""
    out = []
    for fn in tree.body:
        if not (isinstance(fn, ast.FunctionDef) and fn.name in functions):
            continue
        for node in ast.walk(fn):
            if isinstance(node, ast.Compare):
                for i, op in enumerate(node.ops):
                    if type(op) in _SWAP:
                        out.append((fn.name, node.lineno, "compare", node, i))
            elif isinstance(node, (ast.BinOp, ast.AugAssign)) and type(node.op) in _SWAP:
                out.append((fn.name, node.lineno, "arith", node, None))
            elif isinstance(node, ast.Constant) and type(node.value) is int:
                out.append((fn.name, node.lineno, "const", node, None))
    return out


def mutate(source, functions, index):
    """The module source with mutation ``index`` applied, and a description of it."""
    tree = ast.parse(source)
    fn, line, kind, node, i = sites(tree, functions)[index]
    if kind == "compare":
        old = type(node.ops[i])
        node.ops[i] = _SWAP[old]()
        what = f"{old.__name__} -> {_SWAP[old].__name__}"
    elif kind == "arith":
        old = type(node.op)
        node.op = _SWAP[old]()
        what = f"{old.__name__} -> {_SWAP[old].__name__}"
    else:
        what = f"{node.value} -> {node.value + 1}"
        node.value += 1
    return ast.unparse(tree), f"{fn} line {line}: {what}"


def run_tests(root):
    extra = sorted(glob.glob(os.path.join(root, "tests/**/test_mutants_ensemble*.py"),
                             recursive=True))
    cmd = [sys.executable, "-m", "pytest", "-x", "-q", "-p", "no:cacheprovider", *TESTS,
           *(os.path.relpath(p, root) for p in extra), *(f"--deselect={d}" for d in DESELECT)]
    cmd[3:3] = ["-p", "nopython_shims"]
    shims = os.path.join(root, "scripts", "mutation")
    env = dict(os.environ, NUMBA_DISABLE_JIT="1",
               PYTHONPATH=os.pathsep.join(filter(None, [shims, os.environ.get("PYTHONPATH")])))
    try:
        return subprocess.run(cmd, cwd=root, env=env, capture_output=True,
                              timeout=TIMEOUT).returncode
    except subprocess.TimeoutExpired:
        return None


def main(root, only=None):
    t0 = time.monotonic()
    if run_tests(root) != 0:
        sys.exit("ensemble: the tests fail on the unmutated code; no score")
    for target, functions in TARGETS.items():
        functions = tuple(f for f in functions if only is None or f in only)
        if functions:
            mutate_file(root, target, functions)
    print(f"== ensemble: wall {time.monotonic() - t0:.0f} s")


def mutate_file(root, target, functions):
    path = os.path.join(root, target)
    original = open(path).read()
    n = len(sites(copy.deepcopy(ast.parse(original)), functions))
    tally = {"killed": 0, "survived": 0, "timeout": 0}
    try:
        for k in range(n):
            mutated, what = mutate(original, functions, k)
            with open(path, "w") as f:
                f.write(mutated)
            rc = run_tests(root)
            status = "timeout" if rc is None else "killed" if rc != 0 else "survived"
            tally[status] += 1
            if status != "killed":
                print(f"   {status:10s} {target} mutant {k}: {what}", flush=True)
    finally:
        with open(path, "w") as f:
            f.write(original)
    print(f"{target} ({', '.join(functions)}): {n} mutants, {tally['killed']} killed, "
          f"{tally['survived']} survived, {tally['timeout']} timeouts; "
          f"score {100 * tally['killed'] / max(n, 1):.1f}%", flush=True)


if __name__ == "__main__":
    main(sys.argv[1], None if len(sys.argv) < 3 else set(sys.argv[2].split(",")))
