"""Speed of fastpath: ns per scalar flight_time call and orbit ns/collision at eps = 0.6.

    python examples/fastpath_speed.py [PACKAGE ...]

Each PACKAGE (default: fastpath) is an importable copy of fastpath, so that two versions (e.g.
an old one exported as ``fastpath_before``) are measured in one process; best of 5 repeats.
"""

import importlib
import sys
import time

CALLS = 20_000
COLLISIONS = 1_000_000


def best_of(fn, repeats=5):
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return min(times)


def measure(name):
    fp = importlib.import_module(name)
    fp.flight_time(4.0, 3.0, 0.6)  # compile
    fp.orbit(4.0, 3.0, 0.6, 10)

    def scalar_calls():
        for _ in range(CALLS):
            fp.flight_time(4.0, 3.0, 0.6)

    scalar = best_of(scalar_calls) / CALLS * 1e9
    orbit = best_of(lambda: fp.orbit(4.0, 3.0, 0.6, COLLISIONS)) / COLLISIONS * 1e9
    print(f"{name:16s} scalar flight_time {scalar:9.0f} ns/call,"
          f" orbit eps=0.6 {orbit:6.1f} ns/collision")


if __name__ == "__main__":
    for package in sys.argv[1:] or ["fastpath"]:
        measure(package)
