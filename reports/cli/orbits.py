"""``bouncer orbits PHI V --eps E --period P [--winding M] [--shift L] [--model M]
[--certify] [--dps D] [--json]``.

Find a periodic orbit of the collision map near the guess (PHI, V) by Newton's method on
F^p - id (``fastpath.periodic_orbit``), print its states, residue R = (2 - trace)/4 and stability,
and with ``--certify`` prove it (``verify.periodic_orbit``, exact map only): enclosures of the
residue and of the first state, the stability decided in interval arithmetic, the digits used.
The period printed is the orbit's minimal one (proved with ``--certify``): a guess asked at
``--period 2`` that lands on a fixed point is reported as period 1, with a note.
``--shift L``: an accelerator mode, v grows by pi*L every P collisions (for the exact map only
period-1 modes with L > 0 exist as orbits; other blocks are refused). ``--json`` prints one
JSON object (enclosures as [lo, hi] strings of 20 digits; "asked_period" the --period given).
Exit status: 0 ok, 1 no orbit found or not certified (one line on stderr), 2 bad input.
"""

from __future__ import annotations

import json
import sys
import time

import mpmath

import fastpath
import verify
from fastpath.dynamics import OrbitNotFound


def add_parser(subparsers):
    """Register ``orbits`` on an argparse subparsers object."""
    p = subparsers.add_parser("orbits", help="find (and certify) a periodic orbit",
                              description=__doc__.split("\n\n")[1])
    p.add_argument("phi", type=float, metavar="PHI", help="guess: phase of a collision")
    p.add_argument("v", type=float, metavar="V", help="guess: velocity after it")
    p.add_argument("--eps", type=float, required=True, help="plate amplitude")
    p.add_argument("--period", type=int, default=1, help="collisions per period (default 1)")
    p.add_argument("--winding", type=int, help="total time 2*pi*M (default: from the guess)")
    p.add_argument("--shift", type=int, default=0, help="velocity shift pi*L per period")
    p.add_argument("--model", choices=("exact", "holmes"), default="exact",
                   help="the map: exact (default) or the Holmes approximation")
    p.add_argument("--certify", action="store_true", help="prove it with verify (exact map)")
    p.add_argument("--dps", type=int, default=50, help="digits of the certificate (>= 15)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=main)
    return p


def _interval(e):
    return [mpmath.nstr(e.lo, 20), mpmath.nstr(e.hi, 20)]


def find(args) -> dict:
    """The orbit as a JSON-ready dict; raises ValueError, OrbitNotFound, verify.NotCertified."""
    if args.certify and args.model != "exact":
        raise ValueError("--certify proves orbits of the exact map only (--model exact)")
    orbit = fastpath.periodic_orbit(args.phi, args.v, args.eps, args.period,
                                    winding=args.winding, velocity_shift=args.shift,
                                    model=args.model)
    out = {"eps": args.eps, "asked_period": args.period, "period": orbit.period,
           "winding": orbit.winding,
           "velocity_shift": orbit.velocity_shift, "model": orbit.model,
           "phi": orbit.phi.tolist(), "v": orbit.v.tolist(), "trace": orbit.trace,
           "determinant": orbit.determinant, "residue": orbit.residue,
           "residue_error": orbit.residue_error, "stability": orbit.stability,
           "newton_iterations": orbit.iterations}
    if args.certify:
        start = time.perf_counter()
        proved = verify.periodic_orbit(float(orbit.phi[0]), float(orbit.v[0]), args.eps,
                                       orbit.period, dps=args.dps, winding=orbit.winding,
                                       velocity_shift=orbit.velocity_shift)
        out["certified"] = {"period": proved.period, "winding": proved.winding,
                            "phi": _interval(proved.box[0]), "v": _interval(proved.box[1]),
                            "trace": _interval(proved.trace),
                            "residue": _interval(proved.residue),
                            "determinant": _interval(proved.determinant),
                            "stability": proved.stability, "dps_used": proved.dps_used,
                            "seconds": time.perf_counter() - start}
    return out


def _print(out):
    print(f"periodic orbit: period {out['period']}, winding {out['winding']}, velocity shift "
          f"{out['velocity_shift']}, eps={out['eps']!r} ({out['model']} map)")
    if out["period"] != out["asked_period"]:
        print(f"  (asked for period {out['asked_period']}: the orbit found has the shorter "
              f"period {out['period']})")
    for k, (phi, v) in enumerate(zip(out["phi"], out["v"], strict=True)):
        print(f"  {k:4d}  phi = {phi:.17g}  v = {v:.17g}")
    print(f"residue R = {out['residue']:.15g} (rounding <= {out['residue_error']:.2g}), "
          f"trace {out['trace']:.15g}: {out['stability']}")
    if "certified" in out:
        c = out["certified"]
        print(f"certified ({c['dps_used']} digits, {c['seconds']:.2f} s): minimal period "
              f"{c['period']}, R in [{c['residue'][0]}, {c['residue'][1]}]: {c['stability']}")


def main(args):
    try:
        out = find(args)
    except (OrbitNotFound, verify.NotCertified, fastpath.UncertainCollision) as err:
        print(f"bouncer orbits: {err}", file=sys.stderr)
        return 1
    if args.json:
        print(json.dumps(out))
    else:
        _print(out)
    return 0
