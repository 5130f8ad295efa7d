"""Hash a fixed set of ``verify`` results, to show that a change of code leaves them bit for bit.

Every value is hashed by its exact binary content (an ``mpf``'s sign, mantissa and exponent), so
two runs print the same hashes only when every result is identical. The set: flight times and
steps of seeded random departures, of the hard-case table and of the dissipative table (drag,
departures at rest, chattering grazes), Jacobians and condition numbers, and orbits: elastic,
with restitution (sticking for good and detaching), with linear and quadratic drag and
restitution (sticking and detaching). Errors are hashed by type.

    python scripts/verify_same_results.py            # one hash per group and a total
    python scripts/verify_same_results.py --quick    # a smaller set (~1 minute less)
"""

from __future__ import annotations

import argparse
import hashlib
import math
import random
import sys
import time

import mpmath

import verify
from verify.hard_cases import DISSIPATIVE_CASES, HARD_CASES


def _bits(x) -> str:
    if isinstance(x, mpmath.matrix):
        return "[" + ",".join(_bits(x[i, j]) for i in range(x.rows) for j in range(x.cols)) + "]"
    if isinstance(x, tuple | list):
        return "(" + ",".join(_bits(y) for y in x) + ")"
    if hasattr(x, "_mpf_"):
        return repr(x._mpf_)
    return repr(x)


def _result(fn, *args, **kwargs) -> str:
    try:
        return _bits(fn(*args, **kwargs))
    except (ValueError, ArithmeticError) as err:  # the kind of refusal is part of the result
        return type(err).__name__


def _departures(count: int, seed: int = 20240611):
    rng = random.Random(seed)
    out = []
    while len(out) < count:
        eps = rng.choice([rng.uniform(0.0, 1.0), rng.uniform(1.0, 10.0), -rng.uniform(0, 3)])
        phi = rng.uniform(0.0, 2 * math.pi) if rng.random() < 0.8 else rng.uniform(-1e3, 1e6)
        w0 = 10 ** rng.uniform(-8, 1.5)
        v = w0 - eps * math.sin(phi)
        if v + eps * math.sin(phi) > 0:
            out.append((phi, v, eps))
    return out


def groups(quick: bool):
    """(name, list of thunks) for each group of results."""
    random_cases = _departures(40 if quick else 120)
    hard = [(c.phi, c.v, c.eps) for c in HARD_CASES]
    drag = [(c.phi, c.v, c.eps, c.drag, c.drag_law) for c in DISSIPATIVE_CASES if c.drag > 0]
    out = []
    for dps in (30, 50):
        out.append((f"flight_time random dps={dps}",
                    [lambda c=c, d=dps: _result(verify.flight_time, *c, dps=d)
                     for c in random_cases]))
    out.append(("flight_time hard dps=50",
                [lambda c=c: _result(verify.flight_time, *c, dps=50) for c in hard]))
    out.append(("certify_flight drag dps=30",
                [lambda c=c: _result(lambda *a: verify.certify_flight(
                    *a[:3], dps=30, drag=a[3], drag_law=a[4]).enclosure, *c) for c in drag]))
    out.append(("step random dps=30",
                [lambda c=c: _result(verify.step, *c, dps=30) for c in random_cases]))
    out.append(("step hard dps=30",
                [lambda c=c: _result(verify.step, *c, dps=30) for c in hard]))
    out.append(("step drag+restitution dps=30",
                [lambda c=c: _result(verify.step, *c[:3], dps=30, drag=c[3], drag_law=c[4],
                                     restitution=0.7) for c in drag]))
    out.append(("jacobian random dps=30",
                [lambda c=c: _result(verify.jacobian, *c, dps=30) for c in random_cases[:40]]))
    out.append(("condition_number random",
                [lambda c=c: _result(lambda *a: verify.condition_number(
                    *a, verify.flight_time(*a, dps=30)), *c) for c in random_cases]))
    orbits = [
        ("elastic", (4.0, 3.0, 0.6, 30), {}),
        ("elastic eps=3", (1.0, 2.0, 3.0, 20), {}),
        ("elastic huge phase", (1e12, 3.0, 0.6, 10), {}),
        ("stuck r=0.5", (4.0, 3.0, 0.5, 400), {"restitution": 0.5}),
        ("detach r=0.8 eps=1.5", (math.pi, 1e-3, 1.5, 200), {"restitution": 0.8}),
        ("detach r=0.3 eps=-3", (1.0, 3.0, -3.0, 200), {"restitution": 0.3}),
        ("drag linear", (1.0, 2.0, 0.6, 20), {"drag": 0.05}),
        ("drag quadratic r=0.9", (1.0, 2.0, 0.6, 20),
         {"drag": 0.05, "drag_law": "quadratic", "restitution": 0.9}),
        ("drag stuck", (1.0, 1.0, 0.5, 400), {"drag": 0.01, "restitution": 0.5}),
        ("drag linear detach", (math.pi, 1e-3, 1.5, 230),
         {"drag": 0.1, "drag_law": "linear", "restitution": 0.8}),
        ("drag quadratic detach", (math.pi, 1e-3, -1.5, 40),
         {"drag": 0.3, "drag_law": "quadratic", "restitution": 0.3}),
    ]
    if quick:
        orbits = orbits[:4] + orbits[6:9]
    out.append(("orbit dps=30",
                [lambda a=a, k=k: _result(lambda: _orbit_bits(verify.orbit(*a, dps=30, **k)))
                 for _, a, k in orbits]))
    return out


def _orbit_bits(orb):
    return (orb.phi, orb.v, orb.t, tuple(orb.sticking), orb.stopped)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="a smaller set of results")
    args = parser.parse_args(argv)
    total = hashlib.sha256()
    for name, thunks in groups(args.quick):
        start = time.perf_counter()
        digest = hashlib.sha256()
        for thunk in thunks:
            digest.update(thunk().encode() + b"\n")
        total.update(digest.digest())
        print(f"{digest.hexdigest()[:16]}  {len(thunks):4d}  {name}  "
              f"({time.perf_counter() - start:.1f} s)", flush=True)
    print(f"{total.hexdigest()[:16]}  total")
    return 0


if __name__ == "__main__":
    sys.exit(main())
