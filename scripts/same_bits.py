"""Fingerprints of fastpath's results, to show that a change of the code leaves every bit alone.

    python scripts/same_bits.py [--out FILE] [--compare FILE] [--no-scenes] [--no-steps]

Two groups of SHA-256 digests (16 hex digits each), printed one per line and written as JSON to
``--out``; ``--compare`` reads such a file and lists what differs (exit status 1 if anything does):

* scenes: every built-in scene (``bouncer scenes``) and a few dissipative ones (drag, restitution,
  sticking, |eps| > 1 with flags settled by verify) run with ``bouncer run`` at small particle
  counts and fixed random seeds; the digests of ``survival.csv``, ``counts.csv``, ``sample.csv``,
  ``velocity.csv`` and ``portrait.npy`` where a scene writes them (``manifest.json`` holds
  timings and is left out). Takes a minute or two on two cores.
* steps: 100,000 ``fastpath.step`` results (elastic; restitution; linear and quadratic drag;
  random departures and the hard-case table of ``verify.hard_cases``), each as the bits of
  (phi1, v1, tau) or the name of the exception raised; ``fastpath.flight`` (tau, iterations,
  status, both methods; the drag of each physics, restitution acting only at impacts) on the
  same departures; ``carried_step``, ``holmes_step``; orbits
  (exact, Holmes, dissipative: phi, v, t, iterations, status, sticking episodes) and velocity
  moments (``fastpath.moments``).

Only public entry points are called, so the script runs unchanged across a reorganisation of the
package's modules. Inputs are drawn from fixed random seeds.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

SCENE_PARTICLES = {
    "paper-escape": 3000,
    "paper-transport": 1500,
    "paper-phase-space": 400,
    "dissipation-saturation": 60,
}
SCENE_SEED = 12345
RUN_FILES = ("survival.csv", "counts.csv", "sample.csv", "velocity.csv", "portrait.npy")

# scenes beyond the built-in ones: the dissipative kernels and the flags of |eps| > 1
EXTRA_SCENES = {
    "drag-escape": """
name = "drag-escape"
kind = "escape"
eps = 0.6
particles = 3000
seed = 7
[start]
phi = [3.85, 4.15]
v = [2.0, 4.0]
[holes]
centres = [2.0, 5.0]
widths = [0.3]
[horizon]
collisions = 3000
[record]
verify_samples = 40
[physics]
drag = 0.01
drag_law = "linear"
restitution = 0.9
""",
    "quadratic-transport": """
name = "quadratic-transport"
kind = "transport"
eps = 1.5
particles = 1500
seed = 8
[start]
v = [2.0, 4.0]
[holes]
centres = [0.0, 3.141592653589793]
widths = [0.4]
[horizon]
collisions = 2000
[record]
verify_samples = 40
[physics]
drag = 0.002
drag_law = "quadratic"
""",
    "stick": """
name = "stick"
kind = "escape"
eps = 0.6
particles = 2000
seed = 5
[start]
phi = [3.85, 4.15]
v = [2.0, 4.0]
[holes]
centres = [2.0]
widths = [0.3]
[horizon]
collisions = 2000
time = 1e5
[record]
verify_samples = 40
[physics]
restitution = 0.5
""",
    "detach-escape": """
name = "detach-escape"
kind = "escape"
eps = 1.5
particles = 1500
seed = 6
[start]
phi = [3.85, 4.15]
v = [2.0, 4.0]
[holes]
centres = [2.0]
widths = [0.2]
[horizon]
collisions = 1500
[record]
verify_samples = 40
[physics]
restitution = 0.7
drag = 0.001
drag_law = "quadratic"
""",
    "elastic-eps3": """
name = "elastic-eps3"
kind = "escape"
eps = 3.0
particles = 2000
seed = 9
[start]
phi = [3.85, 4.15]
v = [4.0, 6.0]
[holes]
centres = [2.0]
widths = [0.2]
[horizon]
collisions = 2000
time = 1e6
[record]
verify_samples = 40
""",
    "drag-velocity": """
name = "drag-velocity"
kind = "velocity"
eps = 2.0
particles = 60
seed = 4
[start]
phi = [3.85, 4.15]
v = [2.0, 4.0]
[horizon]
collisions = 3000
[record]
bins_per_decade = 5
verify_samples = 30
[physics]
drag = 0.001
drag_law = "linear"
restitution = [1.0, 0.9]
""",
}


def digest(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()[:16]


class Hasher:
    """A running SHA-256 of floats (their bits), ints and short strings."""

    def __init__(self):
        self.h = hashlib.sha256()
        self.count = 0

    def floats(self, *values):
        self.h.update(np.asarray(values, dtype=np.float64).tobytes())

    def array(self, a):
        a = np.ascontiguousarray(a)
        self.h.update(str(a.dtype).encode() + str(a.shape).encode() + a.tobytes())

    def text(self, s):
        self.h.update(s.encode() + b"\0")

    def hexdigest(self):
        return self.h.hexdigest()[:16]


# ---- scenes ---------------------------------------------------------------------------------

def builtin_scenes():
    out = subprocess.run(["bouncer", "scenes"], capture_output=True, text=True, check=True)
    return [line.split()[0] for line in out.stdout.splitlines() if line.strip()]


def run_scene(scene, particles, workdir, name):
    out = workdir / name
    cmd = ["bouncer", "run", scene, "--out", str(out), "--quiet", "--threads", "1", "--force"]
    if particles is not None:
        cmd += ["--particles", str(particles), "--seed", str(SCENE_SEED)]
    done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode:
        raise SystemExit(f"{' '.join(cmd)} failed: {done.stderr.strip()}")
    return {f"scene {name} {f}": digest((out / f).read_bytes())
            for f in RUN_FILES if (out / f).exists()}


def scene_digests():
    result = {}
    with tempfile.TemporaryDirectory() as tmp:
        workdir = Path(tmp)
        for scene in builtin_scenes():
            result.update(run_scene(scene, SCENE_PARTICLES.get(scene, 500), workdir, scene))
        for name, text in EXTRA_SCENES.items():
            path = workdir / f"{name}.toml"
            path.write_text(text)
            result.update(run_scene(str(path), None, workdir, name))
    return result


# ---- steps, flights, orbits ------------------------------------------------------------------

STEP_PHYSICS = (
    {},
    {"restitution": 0.9},
    {"restitution": 0.5},
    {"drag": 0.01, "drag_law": "linear"},
    {"drag": 0.5, "drag_law": "linear", "restitution": 0.8},
    {"drag": 0.01, "drag_law": "quadratic"},
    {"drag": 0.3, "drag_law": "quadratic", "restitution": 0.7},
)


def random_departures(rng, m):
    """m departures (phi, v, eps): phases over several turns, speeds from 1e-3 to 1e4."""
    phi = rng.uniform(-20.0, 20.0, m)
    v = 10.0 ** rng.uniform(-3.0, 4.0, m)
    eps = rng.choice([0.1, 0.6, 1.0, 1.0000001, 1.5, 3.0, -0.6, -2.0], m)
    return phi, v, eps


def hard_departures():
    from verify.hard_cases import ALL_CASES

    return [(c.phi, c.v, c.eps, {"drag": c.drag, "drag_law": c.drag_law}
             if getattr(c, "drag", 0.0) else {}) for c in ALL_CASES]


def hash_step(h, fastpath, phi, v, eps, physics):
    try:
        h.floats(*fastpath.step(phi, v, eps, **physics))
    except Exception as err:  # noqa: BLE001  (the exception's type is part of the result)
        h.text(type(err).__name__)


def hash_flight(h, fastpath, phi, v, eps, physics, method):
    physics = {k: x for k, x in physics.items() if k != "restitution"}  # it acts at impacts
    try:
        res = fastpath.flight(phi, v, eps, method=method, **physics)
        h.floats(res.tau, float(res.iterations), float(int(res.status)))
    except Exception as err:  # noqa: BLE001
        h.text(type(err).__name__)


def step_digests():
    import fastpath

    rng = np.random.default_rng(20240601)
    result = {}
    hard = hard_departures()

    steps = Hasher()
    flights = Hasher()
    n_steps = 0
    per_physics = 14000
    for physics in STEP_PHYSICS:
        phi, v, eps = random_departures(rng, per_physics)
        for i in range(per_physics):
            hash_step(steps, fastpath, float(phi[i]), float(v[i]), float(eps[i]), physics)
            n_steps += 1
            if i % 7 == 0:
                for method in ("auto", "lower_bound"):
                    hash_flight(flights, fastpath, float(phi[i]), float(v[i]), float(eps[i]),
                                physics, method)
    for phi, v, eps, physics in hard:
        for extra in ({}, {"restitution": 0.6}):
            hash_step(steps, fastpath, phi, v, eps, {**physics, **extra})
            n_steps += 1
        for method in ("auto", "lower_bound"):
            hash_flight(flights, fastpath, phi, v, eps, physics, method)
    # the remainder up to 100,000: elastic departures near |eps| = 1 and at large speeds
    rest = 100_000 - n_steps
    phi = rng.uniform(-4.0, 4.0, rest)
    v = 10.0 ** rng.uniform(-1.0, 9.0, rest)
    eps = rng.choice([0.999999, 1.0, 1.000001, 0.6, 2.0], rest)
    for i in range(rest):
        hash_step(steps, fastpath, float(phi[i]), float(v[i]), float(eps[i]), {})
        n_steps += 1
    result[f"steps ({n_steps})"] = steps.hexdigest()
    result["flights"] = flights.hexdigest()

    # the array path of step and flight (the parallel kernels), elastic and with drag
    arrays = Hasher()
    phi, v, eps = random_departures(rng, 20000)
    good = fastpath.flight(phi, v, eps).status == 0
    arrays.array(np.array(fastpath.step(phi[good], v[good], eps[good])))
    for physics in STEP_PHYSICS[1:]:
        res = fastpath.flight(phi, v, eps, **{k: x for k, x in physics.items()
                                             if k != "restitution"})
        arrays.array(res.tau)
        arrays.array(res.iterations)
        arrays.array(np.asarray(res.status, dtype=np.int64))
    arrays.array(np.array(fastpath.holmes_step(phi[good], v[good], eps[good])))
    result["array calls"] = arrays.hexdigest()

    carried = Hasher()
    for physics in ({"restitution": 0.5}, {"restitution": 0.9, "drag": 0.05},
                    {"restitution": 0.8, "drag": 0.05, "drag_law": "quadratic"}):
        phi, v, eps = random_departures(rng, 3000)
        for i in range(3000):
            p, s, e = float(phi[i]) % (2 * np.pi), float(v[i]), float(eps[i])
            sin, cos = np.sin(p), np.cos(p)
            state = (p, 0.0, sin, cos, s + e * sin, 0.0)
            try:
                carried.floats(*fastpath.carried_step(p, s, e, state, **physics))
            except Exception as err:  # noqa: BLE001
                carried.text(type(err).__name__)
    result["carried_step"] = carried.hexdigest()

    holmes = Hasher()
    phi, v, eps = random_departures(rng, 5000)
    for i in range(5000):
        try:
            holmes.floats(*fastpath.holmes_step(float(phi[i]), float(v[i]), float(eps[i])))
        except Exception as err:  # noqa: BLE001
            holmes.text(type(err).__name__)
    result["holmes_step"] = holmes.hexdigest()

    orbits = Hasher()
    orbit_cases = [
        ((4.0, 3.0, 0.6, 5000), {}),
        ((1.0, 20.0, 3.0, 3000), {"on_uncertain": "stop"}),
        ((1.0, 20.0, 3.0, 3000), {"on_uncertain": "stop", "method": "lower_bound"}),
        ((4.0, 3.0, 0.6, 5000), {"model": "holmes"}),
        ((4.0, 3.0, 1.5, 3000), {"restitution": 0.5, "on_uncertain": "stop"}),
        ((4.0, 3.0, 0.6, 3000), {"restitution": 0.5, "on_uncertain": "stop"}),
        ((4.0, 3.0, 0.6, 3000), {"drag": 0.01, "on_uncertain": "stop"}),
        ((4.0, 3.0, 1.5, 3000), {"drag": 0.01, "drag_law": "quadratic", "restitution": 0.7,
                                 "on_uncertain": "stop"}),
        ((4.0, 3.0, 0.8, 3000), {"drag": 0.8, "restitution": 0.6, "on_uncertain": "stop"}),
    ]
    for args, kwargs in orbit_cases:
        try:
            orb = fastpath.orbit(*args, **kwargs)
        except Exception as err:  # noqa: BLE001
            orbits.text(type(err).__name__)
            continue
        for a in (orb.phi, orb.v, orb.t, orb.sticking):
            orbits.array(np.asarray(a, dtype=np.float64))
        if orb.iterations is not None:
            orbits.array(np.asarray(orb.iterations, dtype=np.int64))
        orbits.text(f"{int(orb.status)} {orb.stopped}")
    result["orbits"] = orbits.hexdigest()

    mom = Hasher()
    phi0 = rng.uniform(3.85, 4.15, 300)
    v0 = rng.uniform(2.0, 4.0, 300)
    for eps, kwargs in ((0.6, {}), (1.2, {}), (0.6, {"model": "holmes"}),
                        (2.0, {"restitution": 0.9}), (0.6, {"restitution": 0.5}),
                        (2.0, {"drag": 0.01, "restitution": 0.9})):
        m = fastpath.moments(phi0, v0, eps, [0, 1, 10, 200], t_grid=[0.0, 5.0, 300.0],
                             blocks=7, max_collisions=2000, **kwargs)
        for a in (m.count_n, m.sum_v_n, m.sum_v2_n, m.sum_dv2_n, m.count_t, m.sum_v_t,
                  m.stuck_n, m.stuck_t):
            mom.array(np.asarray(a, dtype=np.float64))
        mom.text(f"{m.collisions} {m.flagged}")
    result["moments"] = mom.hexdigest()
    return result


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, help="write the digests here (JSON)")
    parser.add_argument("--compare", type=Path, help="a JSON file of digests to compare with")
    parser.add_argument("--no-scenes", action="store_true", help="skip the scene runs")
    parser.add_argument("--no-steps", action="store_true", help="skip steps, flights, orbits")
    args = parser.parse_args(argv)
    result = {}
    if not args.no_steps:
        result.update(step_digests())
    if not args.no_scenes:
        result.update(scene_digests())
    for key, value in result.items():
        print(f"{value}  {key}")
    if args.out:
        args.out.write_text(json.dumps(result, indent=1) + "\n")
    if args.compare:
        old = json.loads(args.compare.read_text())
        differ = [k for k in result if k in old and old[k] != result[k]]
        missing = [k for k in old if k not in result]
        for k in differ:
            print(f"DIFFERS: {k}: {old[k]} -> {result[k]}")
        print(f"{len(differ)} differ, {len(result) - len(differ)} the same,"
              f" {len(missing)} not computed")
        return 1 if differ else 0
    return 0


if __name__ == "__main__":
    sys.exit(main())
