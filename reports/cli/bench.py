"""``bouncer bench``: ns per collision against the Holmes map, ensemble throughput, memory."""

from reports.precision.bench import (
    dissipative_section,
    ensemble_throughput,
    orbit_table,
    peak_memory_mib,
    time_orbits,
)


def bench_command(args):
    """Entry point of ``bouncer bench``."""
    if args.collisions < 1 or args.repeats < 1 or args.particles < 0:
        raise ValueError("--collisions and --repeats must be >= 1, --particles >= 0")
    best = time_orbits(args.eps, args.collisions, args.repeats)
    print(orbit_table(best, args.collisions, args.eps, args.repeats))
    if args.particles:
        per_s, particles_s, wall, manifest = ensemble_throughput(args.particles,
                                                                 threads=args.threads)
        v = manifest["verification"]
        print(f"\npaper-escape, {manifest['particles']:,} particles per curve x "
              f"{len(manifest['curves'])} curves, {manifest['collisions']:,} collisions in "
              f"{wall:.1f} s: {per_s:.3g} collisions/s, {particles_s:.3g} particles/s "
              f"(all cores, verification included: {v['sampled']} sampled, worst error "
              f"{v['worst_error']:.3g} kappa*u, {v['overstepped']} overstepped)")
    print(f"\npeak memory: {peak_memory_mib():.0f} MiB")
    print("\n" + dissipative_section(args.collisions, args.repeats))
    return 0


def add_parser(subparsers):
    bench = subparsers.add_parser(
        "bench", help="ns per collision vs the Holmes map, ensemble throughput, memory")
    bench.add_argument("--eps", type=float, default=0.6)
    bench.add_argument("--collisions", type=int, default=10_000_000,
                       help="orbit length for the per-collision timing (default 10^7)")
    bench.add_argument("--repeats", type=int, default=5)
    bench.add_argument("--particles", type=int, default=100_000,
                       help="paper-escape particles per curve for the throughput (default 10^5;"
                       " 0 skips it)")
    bench.add_argument("--threads", type=int, default=None)
    bench.set_defaults(func=bench_command)
