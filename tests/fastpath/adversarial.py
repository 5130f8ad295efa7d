"""A fixed adversarial set of flights and its judge; run it for the figures:

    python tests/fastpath/adversarial.py

Families (all float64 inputs, references from ``verify`` at 60+ digits or exact):

* ``triple``: phi = -x, v = x with eps in [1 - 1e-3, 1] (exactly 1 included), x over decades.
  The exact flight time is 2x; near eps = 1 it is a near-triple root.
* ``triple-perturbed``: the same with phi and v moved by relative 1e-6 (verify reference).
* ``eps-one``: eps = 1 exactly, departures spread over phase and w0.
* ``graze``: eps = 1 + 10**-k just above 1, ``verify.grazing_contact`` dips of several clearances.
* ``huge-phase``: |phi| from 1e12 to 1e300, v chosen so that w0 is 1e-8, 1 or 3.

A CONVERGED answer is wrong when tau is not finite, not > 0, or off the reference by more than
K*kappa*u (K = 16, ``fastpath_tolerances``). For grazes the error in kappa*u is reported too.

``python tests/fastpath/adversarial.py SEED [PER_FAMILY]`` judges a held-out random set of the
same families instead (``held_out_set``).
"""

import math

import numpy as np
from fastpath_tolerances import K, U
from mpmath import mp

import fastpath

REF_DPS = 60


def triple_family():
    xs = 10.0 ** np.linspace(-6.0, 0.5, 27)
    epss = (1 - 1e-3, 1 - 1e-4, 1 - 1e-6, 1 - 1e-8, 1 - 1e-11, math.nextafter(1.0, 0.0), 1.0)
    return [("triple", -float(x), float(x), eps, 2.0 * float(x)) for eps in epss for x in xs]


def _triple_perturbed():
    out = []
    for x in 10.0 ** np.linspace(-4.0, 0.0, 9):
        for eps in (1.0 - 1e-6, 1.0):
            for a, b in ((1e-6, 0.0), (-1e-6, 0.0), (0.0, 1e-6), (1e-6, 1e-6)):
                out.append(("triple-perturbed", -float(x) * (1 + a), float(x) * (1 + b), eps, None))
    return out


def _eps_one():
    rng = np.random.default_rng(12)
    out = []
    for _ in range(40):
        phi = float(rng.uniform(-math.pi, math.pi))
        w0 = float(10.0 ** rng.uniform(-8.0, 1.0))
        v = w0 - math.sin(phi)
        out.append(("eps-one", phi, v, 1.0, None))
    return out


def _grazes():
    import verify

    out = []
    for k in range(1, 11):
        eps = 1.0 + 10.0**-k
        for sign in (1.0, -1.0):
            psi = sign * math.acos((1.0 + 0.5 * (eps - 1.0)) / eps)
            for t_guess in (1.0, 3.0):
                for clearance in (1e-2, 1e-6, 1e-10, -1e-10, -1e-6):
                    try:
                        c = verify.grazing_contact(eps, psi, t_guess, clearance)
                    except ValueError:
                        continue
                    out.append(("graze", float(c.phi), float(c.v), eps, None))
    return out


def _huge_phases():
    out = []
    for phi in (1e12, -1e12, 1e15, 1e17, 1e20, 1e100, 1e300, -1e300):
        for eps in (0.6, 3.0):
            for w0 in (1e-8, 1.0, 3.0):
                with mp.workdps(REF_DPS):
                    v = float(w0 - eps * mp.sin(mp.mpf(phi)))
                out.append(("huge-phase", phi, v, eps, None))
    return out


def adversarial_set():
    """[(family, phi, v, eps, exact tau or None)] (fixed, deterministic)."""
    return triple_family() + _triple_perturbed() + _eps_one() + _grazes() + _huge_phases()


def held_out_set(seed, per_family=200):
    """Fresh random members of the same families (nothing here was tuned against them):

    ``triple``: x log-uniform in [1e-6, 3], eps = 1 - 10**-U(3, 16) or 1 exactly (exact 2x);
    ``triple-perturbed``: the same with phi, v moved by relative +-10**-U(3, 12);
    ``eps-one``: eps = 1, phi uniform, w0 log-uniform in [1e-10, 10];
    ``graze``: eps = 1 + 10**-U(1, 11), contact phase +-acos(...), contact time U(0.5, 4),
    clearance +-10**-U(1, 12) (``verify.grazing_contact``);
    ``huge-phase``: |phi| = 10**U(12, 307) with a random sign, eps in {0.6, 1, 3}, w0
    log-uniform in [1e-8, 3].
    """
    import verify

    rng = np.random.default_rng(seed)
    out = []
    for _ in range(per_family):
        x = float(10.0 ** rng.uniform(-6.0, 0.5))
        eps = 1.0 if rng.random() < 0.2 else 1.0 - float(10.0 ** -rng.uniform(3.0, 16.0))
        out.append(("triple", -x, x, eps, 2.0 * x))
        a, b = (float(rng.choice((-1.0, 1.0)) * 10.0 ** -rng.uniform(3.0, 12.0))
                for _ in range(2))
        out.append(("triple-perturbed", -x * (1 + a), x * (1 + b), eps, None))
        phi = float(rng.uniform(-math.pi, math.pi))
        out.append(("eps-one", phi, float(10.0 ** rng.uniform(-10.0, 1.0)) - math.sin(phi),
                    1.0, None))
        geps = 1.0 + float(10.0 ** -rng.uniform(1.0, 11.0))
        psi = float(rng.choice((-1.0, 1.0))) * math.acos((1.0 + 0.5 * (geps - 1.0)) / geps)
        clearance = float(rng.choice((-1.0, 1.0)) * 10.0 ** -rng.uniform(1.0, 12.0))
        try:
            c = verify.grazing_contact(geps, psi, float(rng.uniform(0.5, 4.0)), clearance)
            out.append(("graze", float(c.phi), float(c.v), geps, None))
        except ValueError:
            pass
        hphi = float(rng.choice((-1.0, 1.0)) * 10.0 ** rng.uniform(12.0, 307.0))
        heps = float(rng.choice((0.6, 1.0, 3.0)))
        with mp.workdps(REF_DPS + 320):
            hv = float(mp.mpf(10.0 ** rng.uniform(-8.0, 0.5)) - heps * mp.sin(mp.mpf(hphi)))
        out.append(("huge-phase", hphi, hv, heps, None))
    return out


def judge(family, phi, v, eps, exact):
    """(status name, iterations, error in kappa*u or None, problem or None) for one flight."""
    import verify

    res = fastpath.flight(phi, v, eps)
    status = fastpath.FlightStatus(int(res.status)).name
    iterations = int(res.iterations)
    with mp.workdps(REF_DPS):
        w0 = mp.mpf(v) + mp.mpf(eps) * mp.sin(mp.mpf(phi))
    if not w0 > 0:
        return status, iterations, None, None if status == "NOT_DEPARTING" else "not a departure"
    if status == "NOT_DEPARTING":
        return status, iterations, None, "NOT_DEPARTING for a departure (w0 > 0)"
    if status != "CONVERGED":
        return status, iterations, None, None
    tau = float(res.tau)
    if not (math.isfinite(tau) and tau > 0.0):
        return status, iterations, None, f"CONVERGED tau = {tau!r}"
    if exact is None:
        try:
            exact = verify.flight_time(phi, v, eps, dps=REF_DPS)
        except verify.UndecidableCollision:
            return status, iterations, None, None  # graze-or-miss: nothing to hold it to
    with mp.workdps(400):  # 1e308 / (2*pi) has 308 digits before the point
        # kappa at the exactly reduced phase: fastpath must reduce any phase exactly
        reduced = mp.mpf(phi) % (2 * mp.pi) if abs(phi) > 2 * math.pi else mp.mpf(phi)
    with mp.workdps(REF_DPS):
        kappa = verify.condition_number(reduced, v, eps, exact)
        units = float(abs(mp.mpf(tau) - mp.mpf(exact)) / (kappa * U * mp.mpf(exact)))
    if not units <= K:
        return status, iterations, units, f"CONVERGED off by {units:.3g} kappa*u"
    return status, iterations, units, None


def figures(cases=None):
    """Counts of wrong CONVERGED per family, worst error, max iterations."""
    rows = [(case[0], judge(*case), case) for case in (cases or adversarial_set())]
    fams = sorted({r[0] for r in rows})
    for fam in fams:
        mine = [r for r in rows if r[0] == fam]
        wrong = [r for r in mine if r[1][3] is not None and r[1][0] == "CONVERGED"]
        rejected = [r for r in mine if r[1][3] is not None and r[1][0] != "CONVERGED"]
        statuses = {}
        for r in mine:
            statuses[r[1][0]] = statuses.get(r[1][0], 0) + 1
        units = [r[1][2] for r in mine if r[1][2] is not None]
        print(
            f"{fam:17s} n={len(mine):4d} wrong CONVERGED={len(wrong):3d}"
            f" wrongly rejected={len(rejected)} statuses={statuses}"
            f" max_iter={max(r[1][1] for r in mine)}"
            f" worst={max(units) if units else float('nan'):.3g} kappa*u"
        )
        for r in (wrong + rejected)[:3]:
            print("    ", r[2][1:4], r[1])
    return rows


if __name__ == "__main__":
    import sys

    # python tests/fastpath/adversarial.py [SEED [PER_FAMILY]]: a held-out random set instead
    figures(held_out_set(int(sys.argv[1]), int(sys.argv[2]) if len(sys.argv) > 2 else 200)
            if len(sys.argv) > 1 else None)
