"""Hand-rolled mutation driver for numba kernels (mutmut cannot), in two groups.

    python scripts/mutation/ensemble.py [--group ensemble|solver] [--files F,...] SCRATCH_COPY
        [FUNCTION,...]
    python scripts/mutation/ensemble.py --list [--group G] [--files F,...] ROOT [FUNCTION,...]

``ensemble`` (the default): ``fastpath/kernels/`` and ``fastpath/elastic/lockstep.py``, the
functions of ``TARGETS`` (the escape/censor accounting, the lanes and the lockstep flight).
``solver``: every
top-level function of the scalar flight solvers of ``SOLVER_TARGETS`` (``concave``, ``tight_gap``,
``lower_bound``, ``flight``, ``gap``, ``short_flight``, ``phase``, ``collision``), run against
``SOLVER_TESTS``.
``--files`` restricts a group to some of its files, a comma-separated FUNCTION list to some
functions; ``--list`` prints the mutants (index, function, line, operator) without running them.

Operators, applied one at a time inside the selected functions:

* comparison: ``<`` <-> ``<=``, ``>`` <-> ``>=``, ``==`` <-> ``!=``;
* arithmetic: ``+`` <-> ``-`` (binary and augmented assignment);
* integer constant ``c`` -> ``c + 1``.

Each mutant replaces its file in the scratch copy (via ``ast.unparse``) and runs the ensemble
and lockstep tests with ``NUMBA_DISABLE_JIT=1``: the kernels run as plain Python (no compile per
mutant), where they pass as compiled given the pytest plugin ``nopython_shims`` (``sin_cos`` of
NaN is NaN, as compiled). Two tests are deselected: one compares thread counts
(meaningless without numba) and one takes ~40 s; both are run by the normal suite. A mutant is
killed when pytest exits non-zero, a timeout when it runs past ``TIMEOUT`` seconds. The solver
group's deselections (``SOLVER_DESELECT``) are tests that take > 30 s without jit or that fail
only as plain Python (a float division by zero raises where compiled code gives inf, an
``np.float64`` repr in a message, ``math.sqrt`` of a negative overflow); every one of them runs
in the normal suite.
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
    "fastpath/kernels/histogram.py": ("exit_hole", "in_hole", "bin_index", "censor", "escape",
                                      "stuck"),
    "fastpath/kernels/escape.py": ("_escape_groups", "lane_collide", "_escape_lanes", "_load",
                                   "_load_next"),
    "fastpath/elastic/lockstep.py": ("lane_evaluation", "lane_start", "lane_answer",
                                     "lane_running", "moderate_bracket", "lockstep_collide",
                                     "lockstep_flight_one"),
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
SOLVER_TARGETS = {
    path: None  # None: every top-level function of the file
    for path in ("fastpath/elastic/concave.py", "fastpath/elastic/tight_gap.py",
                 "fastpath/elastic/lower_bound.py", "fastpath/elastic/flight.py",
                 "fastpath/elastic/gap.py", "fastpath/dissipative/short_flight.py",
                 "fastpath/arithmetic/phase.py", "fastpath/elastic/collision.py")
}
SOLVER_TIMEOUT = 240
SOLVER_TESTS = [
    "tests/fastpath/test_lockstep.py",  # the lanes against the general (concave) solver
    "tests/fastpath/test_fastpath_hard_cases.py",
    "tests/fastpath/test_fastpath_adversarial.py",
    "tests/fastpath/test_tight_gap.py",
    "tests/fastpath/test_fastpath_no_overstep.py",
    "tests/fastpath/test_fastpath_phase.py",
    "tests/fastpath/test_fastpath_api.py",
    "tests/fastpath/test_fastpath_energy.py",
    "tests/fastpath/test_fastpath_fixed_points.py",
    "tests/fastpath/test_fastpath_symmetry.py",
    "tests/fastpath/test_fastpath_holmes.py",
    "tests/fastpath/test_sincos.py",
    "tests/fastpath/test_carried_step.py",
    "tests/fastpath/test_sticking_orbit.py",  # short_flight (chattering impacts)
    "tests/fastpath/test_sticking_accumulation.py",
]
SOLVER_DESELECT = [
    # > 30 s each without jit (159 s and 66 s)
    "tests/fastpath/test_fastpath_invariants.py::test_invariants_over_a_million_collisions",
    # 4-11 s each without jit, 45 s in all
    "tests/fastpath/test_sticking_accumulation.py::test_accumulation_time_matches_reference",
    # plain Python only: 2*w0/(1 - eps*cos_phi) at eps = cos_phi = 1 raises ZeroDivisionError
    # (compiled: inf, then the bracket's midpoint)
    "tests/fastpath/test_fastpath_adversarial.py::test_eps_exactly_one_takes_the_concave_path",
    # plain Python only: the message shows np.float64(...), and sqrt of an overflowed v*v raises
    "tests/fastpath/test_fastpath_api.py::test_message_states_the_computed_w0",
    "tests/fastpath/test_fastpath_api.py::test_overflow_is_a_value_error_saying_overflow",
]
GROUPS = {  # name: (targets, tests, deselected, glob of its own tests, timeout, environment)
    # both groups: hypothesis derandomized and without its database (``nopython_shims``), so
    # that an example stored by one mutant's run is not replayed into the next
    "ensemble": (TARGETS, TESTS, DESELECT, (), TIMEOUT, {"HYPOTHESIS_PROFILE": "mutation"}),
    "solver": (SOLVER_TARGETS, SOLVER_TESTS, SOLVER_DESELECT,
               ("tests/fastpath/test_concave_flight.py", "tests/fastpath/test_concave_loops.py",
                "tests/fastpath/test_lower_bound_flight.py",
                "tests/fastpath/test_short_flight.py"),
               SOLVER_TIMEOUT, {"HYPOTHESIS_PROFILE": "mutation"}),
}
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
    return ast.unparse(tree), f"{fn} line {line}:{node.col_offset}: {what}"


def functions_of(source, functions):
    """``functions``, or every top-level function of ``source`` where it is None."""
    if functions is not None:
        return tuple(functions)
    return tuple(n.name for n in ast.parse(source).body if isinstance(n, ast.FunctionDef))


def run_tests(root, group="ensemble"):
    _, tests, deselect, pattern, timeout, environment = GROUPS[group]
    patterns = (pattern,) if isinstance(pattern, str) else pattern
    extra = sorted({p for g in patterns
                    for p in glob.glob(os.path.join(root, g), recursive=True)})
    if os.environ.get("MUTATION_NO_NEW_TESTS"):  # the score without the group's own test files
        extra = []
    cmd = [sys.executable, "-m", "pytest", "-x", "-q", "-p", "no:cacheprovider",
           *(os.path.relpath(p, root) for p in extra), *tests,
           *(f"--deselect={d}" for d in deselect)]
    cmd[3:3] = ["-p", "nopython_shims"]
    shims = os.path.join(root, "scripts", "mutation")
    env = dict(os.environ, NUMBA_DISABLE_JIT="1", **environment,
               PYTHONPATH=os.pathsep.join(filter(None, [shims, os.environ.get("PYTHONPATH")])))
    try:
        return subprocess.run(cmd, cwd=root, env=env, capture_output=True,
                              timeout=timeout).returncode
    except subprocess.TimeoutExpired:
        return None


def selected(root, group, files, only):
    """[(file, functions)] of the group, restricted to ``files`` and to the functions ``only``."""
    out = []
    for target, functions in GROUPS[group][0].items():
        if files is not None and target not in files:
            continue
        functions = functions_of(open(os.path.join(root, target)).read(), functions)
        functions = tuple(f for f in functions if only is None or f in only)
        if functions:
            out.append((target, functions))
    return out


def main(root, only=None, group="ensemble", files=None):
    t0 = time.monotonic()
    if run_tests(root, group) != 0:
        sys.exit(f"{group}: the tests fail on the unmutated code; no score")
    print(f"== {group}: unmutated tests pass in {time.monotonic() - t0:.0f} s", flush=True)
    for target, functions in selected(root, group, files, only):
        mutate_file(root, target, functions, group)
    print(f"== {group}: wall {time.monotonic() - t0:.0f} s")


def mutate_file(root, target, functions, group="ensemble"):
    path = os.path.join(root, target)
    original = open(path).read()
    n = len(sites(copy.deepcopy(ast.parse(original)), functions))
    tally = {"killed": 0, "survived": 0, "timeout": 0}
    t0 = time.monotonic()
    try:
        for k in range(n):
            mutated, what = mutate(original, functions, k)
            with open(path, "w") as f:
                f.write(mutated)
            t1 = time.monotonic()
            rc = run_tests(root, group)
            status = "timeout" if rc is None else "killed" if rc != 0 else "survived"
            tally[status] += 1
            print(f"   {status:10s} {target} mutant {k}: {what} ({time.monotonic() - t1:.0f} s)",
                  flush=True)
    finally:
        with open(path, "w") as f:
            f.write(original)
    print(f"{target} ({', '.join(functions)}): {n} mutants, {tally['killed']} killed, "
          f"{tally['survived']} survived, {tally['timeout']} timeouts; "
          f"score {100 * tally['killed'] / max(n, 1):.1f}%; wall {time.monotonic() - t0:.0f} s",
          flush=True)


def list_mutants(root, group, files, only):
    for target, functions in selected(root, group, files, only):
        original = open(os.path.join(root, target)).read()
        n = len(sites(ast.parse(original), functions))
        for k in range(n):
            print(f"{target} mutant {k}: {mutate(original, functions, k)[1]}")


if __name__ == "__main__":
    import argparse

    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("root")
    parser.add_argument("functions", nargs="?")
    parser.add_argument("--group", choices=sorted(GROUPS), default="ensemble")
    parser.add_argument("--files", help="comma-separated paths, e.g. fastpath/elastic/concave.py")
    parser.add_argument("--list", action="store_true")
    args = parser.parse_args()
    only = None if args.functions is None else set(args.functions.split(","))
    files = None if args.files is None else set(args.files.split(","))
    if args.list:
        list_mutants(args.root, args.group, files, only)
    else:
        main(args.root, only, args.group, files)
