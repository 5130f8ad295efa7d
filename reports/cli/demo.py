"""The quick-start job: an orbit with ``fastpath``, a random sample of it checked by ``verify``.

For each sampled collision k, verify recomputes the flight from the same float64 state
(phi_k, v_k) at high precision with a certificate that no earlier root exists; the error of the
fast tau is reported in units of condition number x unit roundoff.
"""

import math
import time

import numpy as np

import fastpath
import verify
from fastpath.arithmetic.rounding import UNIT_ROUNDOFF

EPS, COLLISIONS, SAMPLE, SEED = 0.6, 100_000, 200, 0  # the demo's defaults


def run_demo(eps=EPS, phi0=4.0, v0=3.0, collisions=COLLISIONS, sample=SAMPLE, seed=SEED, dps=40,
             echo=print):
    """Run the demo; return a dict of the measured figures."""
    start = time.perf_counter()
    orb = fastpath.orbit(phi0, v0, eps, collisions)
    elapsed = time.perf_counter() - start
    echo(f"fastpath.orbit: {collisions} collisions at eps={eps} from (phi, v)=({phi0}, {v0}) "
         f"in {elapsed:.3f} s (incl. compile); final v={orb.v[-1]:.3f}, t={orb.t[-1]:.1f}")
    echo(f"iterations per flight: mean {orb.iterations.mean():.2f}, max {orb.iterations.max()}")
    rng = np.random.default_rng(seed)
    picks = np.sort(rng.choice(collisions, size=min(sample, collisions), replace=False))
    worst, worst_k, worst_rel = 0.0, -1, 0.0
    for k in picks:
        phi, v = float(orb.phi[k]), float(orb.v[k])
        tau_fast = fastpath.flight_time(phi, v, eps)
        tau_ref = verify.flight_time(phi, v, eps, dps=dps)
        rel = abs((tau_fast - tau_ref) / tau_ref)
        units = float(rel / (verify.condition_number(phi, v, eps, tau_ref) * UNIT_ROUNDOFF))
        if units > worst:
            worst, worst_k, worst_rel = units, int(k), float(rel)
    echo(f"verify: {len(picks)} sampled collisions recomputed at {dps} digits with certificates")
    echo(f"worst error of tau: {worst:.3g} x (condition number x unit roundoff) "
         f"(relative {worst_rel:.3g}, at collision {worst_k})")
    return {"collisions": collisions, "sampled": len(picks), "worst_error": worst,
            "mean_iterations": float(orb.iterations.mean()),
            "max_iterations": int(orb.iterations.max())}


def _demo(args):
    for option, value, least in (("--collisions", args.collisions, 1),
                                 ("--sample", args.sample, 1), ("--seed", args.seed, 0)):
        if value < least:
            raise ValueError(f"{option} must be >= {least}, got {value}")
    if not math.isfinite(args.eps):
        raise ValueError(f"--eps must be a finite number, got {args.eps}")
    run_demo(eps=args.eps, collisions=args.collisions, sample=args.sample, seed=args.seed)
    return 0


def add_parser(subparsers):
    demo = subparsers.add_parser(
        "demo", help="an orbit with fastpath, a sample of it checked by verify")
    demo.add_argument("--eps", type=float, default=EPS,
                      help="the plate's amplitude parameter eps (default %(default)s)")
    demo.add_argument("--collisions", type=int, default=COLLISIONS,
                      help="length of the orbit from (phi, v) = (4, 3) (default %(default)s)")
    demo.add_argument("--sample", type=int, default=SAMPLE,
                      help="collisions of the orbit recomputed by verify (default %(default)s)")
    demo.add_argument("--seed", type=int, default=SEED,
                      help="random seed of the sampled collisions (default %(default)s)")
    demo.set_defaults(func=_demo)
