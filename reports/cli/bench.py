"""``bouncer bench``: ns per collision against the Holmes map, ensemble throughput, cold start,
memory."""

import argparse
import math

from reports.cli.threads import set_threads
from reports.precision.bench import (
    cold_start_table,
    dissipative_section,
    ensemble_table,
    headline_ratios,
    orbit_table,
    peak_memory_mib,
    time_cold_start,
    time_ensembles,
    time_orbits,
)


def bench_command(args):
    """Entry point of ``bouncer bench``."""
    if args.collisions < 1 or args.repeats < 1 or args.particles < 0:
        raise ValueError("--collisions and --repeats must be >= 1, --particles >= 0")
    if not math.isfinite(args.eps):
        raise ValueError(f"--eps must be a finite number, got {args.eps}")
    set_threads(args.threads)
    if args.cold_start:  # first: a fresh interpreter per command, so nothing here is warm yet
        print(cold_start_table(time_cold_start()) + "\n")
    if args.particles:
        ensembles = time_ensembles(args.particles, repeats=args.repeats, threads=args.threads)
        print(ensemble_table(ensembles))
        ratio, kernel = headline_ratios(ensembles)
        print(f"\nheadline: the exact escape ensemble end to end takes {ratio:.2f} x the time of"
              f" the bare Holmes-map loop on the same starts ({kernel:.2f} x kernel only)\n")
    best = time_orbits(args.eps, args.collisions, args.repeats)
    print(orbit_table(best, args.collisions, args.eps, args.repeats))
    # dissipative orbits cost ~1-3 us a collision at eps = 2: at most 10^6 of them
    print("\n" + dissipative_section(min(args.collisions, 1_000_000), min(args.repeats, 3)))
    print(f"\npeak memory: {peak_memory_mib():.0f} MiB")
    return 0


def add_parser(subparsers):
    bench = subparsers.add_parser(
        "bench", help="ensemble and orbit speed against the Holmes map, cold start, memory")
    bench.add_argument("--eps", type=float, default=0.6,
                       help="eps of the timed orbits (default 0.6)")
    bench.add_argument("--collisions", type=int, default=10_000_000,
                       help="orbit length for the per-collision timing (default 10^7)")
    bench.add_argument("--repeats", type=int, default=5,
                       help="timed repetitions; the fastest counts (default 5)")
    bench.add_argument("--particles", type=int, default=1_000_000,
                       help="paper-escape particles per curve for the ensemble timings (default"
                       " 10^6; 0 skips them)")
    bench.add_argument("--threads", type=int, default=None,
                       help="numba threads of the ensemble timings (default: all)")
    bench.add_argument("--cold-start", action=argparse.BooleanOptionalAction, default=True,
                       help="time the README's quick start and a first bouncer run with an"
                       " empty numba cache, then warm (default: on; a minute or two)")
    bench.set_defaults(func=bench_command)
