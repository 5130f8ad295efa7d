"""fastpath on the "chattering-graze" rows of ``verify.hard_cases``.

Near-grazes of a chattering departure (small w0 just before theta* = 2*pi - arccos(1/eps)):
a dip right after the departure, tangent to the plate up to the row's clearance. Elastic rows
(drag 0) are judged as the elastic hard cases (``fastpath_reference.flight_outcome``: CONVERGED
within K*kappa*u of verify's certified first root, UNCERTAIN only at a dip within a few
gap_error of zero); drag rows as the drag flights (``test_drag_reference.judge``: CONVERGED within
the tolerance of the solver's own gap bound of the 60-digit first root, UNCERTAIN only at a dip
within 16 gap bounds of zero). Every answer is positive and never past verify's certified first
root (``case.tau``) by more than that tolerance; the statuses and worst errors are recorded.
``test_random_chattering_grazes_are_never_wrong`` draws more members of the class (tuned by
``scripts/chattering_grazes.py``) and holds fastpath to verify on them the same way.
"""

import math

import drag_reference as ref
import numpy as np
import pytest
from fastpath_figures import record
from fastpath_reference import flight_outcome
from fastpath_tolerances import K, tau_error_units
from mpmath import mp
from test_drag_reference import judge

import fastpath
import verify
from fastpath.arithmetic.phase import centre_phase
from fastpath.dissipative.drag import gap_state
from fastpath.physics import LAWS
from scripts.chattering_grazes import WORK_DPS, tune
from verify.hard_cases import CHATTERING_GRAZES

ELASTIC = [c for c in CHATTERING_GRAZES if c.drag == 0.0]
DRAG = [c for c in CHATTERING_GRAZES if c.drag > 0.0]
METHODS = ["auto", "lower_bound"]


def _drag_units(case, tau):
    """|tau - verify's tau| in units of kappa*u*tau (drag_reference's kappa)."""
    code = LAWS[case.drag_law]
    with mp.workdps(ref.DPS):
        root = mp.mpf(case.tau)
        kappa = ref.kappa(case.phi, case.v, case.eps, case.drag, code, root)
        return float(abs(mp.mpf(tau) - root) / (kappa * ref.U * root))


# Known limitation (not a wrong answer): w0 = 1e-9, clearance +1e-16, 1000 gap bounds above
# zero, so float64 can decide it, and the flight is well conditioned (kappa ~ 11). The
# lower-bound steps crawl past the shallow dip (their curvature model is much more negative
# than the dip's d'' ~ 3e-5) and run out of their 60 iterations at t = 2.18, before the
# landing at 3.566: MAX_ITERATIONS, which the orchestrator settles with verify like UNCERTAIN.
# The suite's judge (flight_outcome) counts MAX_ITERATIONS away from any near-zero dip as a
# problem; test_out_of_iterations_is_decided below says so and is expected to fail.
OUT_OF_ITERATIONS = {"chatter-graze-elastic-eps=1.5-w=1e-09-c=1e-16"}


@pytest.mark.parametrize("case", ELASTIC, ids=[c.id for c in ELASTIC])
def test_elastic_chattering_graze(case):
    out = flight_outcome(case.phi, case.v, case.eps)
    if case.id in OUT_OF_ITERATIONS:  # past the dip, short of the landing, and says so
        assert out.status == "MAX_ITERATIONS" and case.contact < out.tau_fast < case.tau
        return
    assert out.problem is None, f"{out.problem}: {out.describe()}"
    assert out.tau_fast > 0
    if out.status == "CONVERGED":
        assert tau_error_units(out.tau_fast, case.tau, case.phi, case.v, case.eps) <= K
    else:  # stopped by lower-bound steps before the dip: never past the first root
        assert out.tau_fast <= case.tau


@pytest.mark.xfail(strict=True, reason="lower-bound steps run out of iterations past a shallow "
                   "dip with clearance 1e-16 (OUT_OF_ITERATIONS)")
@pytest.mark.parametrize("case_id", sorted(OUT_OF_ITERATIONS))
def test_out_of_iterations_is_decided(case_id):
    case = next(c for c in ELASTIC if c.id == case_id)
    out = flight_outcome(case.phi, case.v, case.eps)
    assert out.problem is None, f"{out.problem}: {out.describe()}"


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("case", DRAG, ids=[c.id for c in DRAG])
def test_drag_chattering_graze(case, method):
    status, _, _ = judge(case.phi, case.v, case.eps, case.drag, case.drag_law, method)
    res = fastpath.flight(case.phi, case.v, case.eps, method=method, drag=case.drag,
                          drag_law=case.drag_law)
    assert res.tau > 0
    if status == "converged":  # and against verify's certified first root, same tolerance
        code = LAWS[case.drag_law]
        d_error = gap_state(centre_phase(case.phi), case.v, case.eps, case.drag, code, res.tau)[3]
        tol = ref.tau_tolerance(d_error, case.phi, case.v, case.eps, case.drag, code, case.tau)
        assert abs(res.tau - case.tau) <= tol
    else:
        assert res.tau <= case.tau


def test_chattering_graze_figures():
    """Statuses and worst errors over the class (the report's sub-table shows them per row)."""
    rows = []
    for case in ELASTIC:
        out = flight_outcome(case.phi, case.v, case.eps)
        rows.append((case, out.status, out.units, out.iterations))
    for case in DRAG:
        res = fastpath.flight(case.phi, case.v, case.eps, drag=case.drag, drag_law=case.drag_law)
        status = fastpath.FlightStatus(res.status).name
        units = _drag_units(case, res.tau) if status == "CONVERGED" else None
        rows.append((case, status, units, int(res.iterations)))
    converged = [r for r in rows if r[1] == "CONVERGED"]
    assert {r[0].id for r in rows if r[1] == "MAX_ITERATIONS"} == OUT_OF_ITERATIONS
    worst = max(converged, key=lambda r: r[2])
    record("chattering grazes: CONVERGED / UNCERTAIN or MAX_ITERATIONS",
           f"{len(converged)} / {len(rows) - len(converged)} of {len(rows)}")
    record("chattering grazes: worst CONVERGED error [kappa*u]",
           f"{worst[2]:.3g} at {worst[0].id}")
    record("chattering grazes: max iterations", max(r[3] for r in rows))
    # positive clearances >= 1e-14 and negative ones <= -1e-10 are decided by float64
    for case, status, _, _ in rows:
        if case.clearance >= 1e-14 or case.clearance <= -1e-10:
            assert status == "CONVERGED", case.id
        if abs(case.clearance) < 1e-16:
            assert status == "UNCERTAIN", case.id
    assert worst[2] <= K


def _random_chattering_grazes(n, seed):
    """n departures of the class with random eps, drag, w0 = 1e-9..1e-3 and clearance
    -+(1e-18..1e-5, capped at a quarter of the hump), tuned at 60 digits by the table's script."""
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < n:
        eps = float(rng.choice([1.05, 1.5, 3.0, 10.0]))
        k = float(rng.choice([0.0, 1e-8, 1e-4]))
        law = str(rng.choice(sorted(LAWS)))
        w = 10 ** rng.uniform(-9, -3)
        with mp.workdps(WORK_DPS):
            e = mp.mpf(eps)
            a = mp.sqrt(e**2 - 1)
            delta = mp.sqrt(8 * mp.mpf(w) / (3 * a))
            phi = float(2 * mp.pi - mp.acos(1 / e) - delta)
            c = rng.choice([-1.0, 1.0]) * min(10 ** rng.uniform(-18, -5), a * delta**3 / 48)
            try:
                v = float(tune(mp.mpf(phi), e, mp.mpf(k), law, mp.mpf(w), delta, mp.mpf(c))[0])
            except ArithmeticError:
                continue  # the tangency's Newton did not converge: draw again
        if v + eps * math.sin(phi) > 0:
            out.append((phi, v, eps, k, law))
    return out


@pytest.mark.slow
def test_random_chattering_grazes_are_never_wrong():
    """fastpath on random members of the class: CONVERGED within the suite's tolerance of
    verify's certified first root, else (UNCERTAIN, MAX_ITERATIONS) short of that root."""
    statuses = {}
    for phi, v, eps, k, law in _random_chattering_grazes(24, 1606):
        cert = verify.certify_flight(phi, v, eps, drag=k, drag_law=law)
        res = fastpath.flight(phi, v, eps, drag=k, drag_law=law)
        status = fastpath.FlightStatus(res.status).name
        statuses[status] = statuses.get(status, 0) + 1
        state = (phi, v, eps, k, law, status, res.tau, cert.tau)
        assert status in ("CONVERGED", "UNCERTAIN", "MAX_ITERATIONS"), state
        assert 0 < res.tau
        if status != "CONVERGED":
            assert res.tau <= cert.enclosure[1], state
        elif k == 0.0:
            assert tau_error_units(res.tau, cert.tau, phi, v, eps) <= K, state
        else:
            code = LAWS[law]
            d_error = gap_state(centre_phase(phi), v, eps, k, code, res.tau)[3]
            assert abs(res.tau - cert.tau) <= ref.tau_tolerance(d_error, phi, v, eps, k, code,
                                                                cert.tau), state
    record("random chattering grazes (24): statuses", dict(sorted(statuses.items())))
