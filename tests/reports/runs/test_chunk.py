"""One chunk of a run (``reports.runs.chunk``): ``simulate_chunk`` (the settled path of
phase-space scenes, the time horizon of a settled flight, which sample rows are kept),
``run_chunk`` (its arguments, the failure result, threads, seconds), ``verify_rows``,
``check_sample`` and ``settle`` (verify's view of the sampled collisions), and ``kernel``: a
second pass adds to the counts, the dissipative kernel stops at each horizon and gets the
scene's physics.
"""

import dataclasses
import time

import numba
import numpy as np
import pytest
from scene_texts import ESCAPE_300, PORTRAIT_300, STICK_200

import fastpath
import verify
from fastpath.arithmetic.phase import TWO_PI
from fastpath.kernels.arrays import Flags, Sample, Starts
from reports.runs import chunk
from reports.runs.chunk import kernel
from reports.runs.counts import Counts
from reports.runs.plan import chunk_starts, make_plan
from reports.runs.scenes import parse_scene


def fast_settle(phi, v, eps):
    """``settle`` with the kernel's own arithmetic (fastpath.step)."""
    phi1, v1, tau = fastpath.step(phi, v, eps)
    return float(phi1), float(v1), float(tau)


def flagging_portrait(real, choose):
    """A stand-in for ``portrait_chunk`` that flags the next collision of the particles picked
    by ``choose(n)`` (before the horizon) and runs the real kernel on the others."""

    def kernel(physics, starts, max_collisions, sample, portrait, flags):
        flag = choose(starts.n) & (starts.n < max_collisions)
        rest = ~flag
        sub_flags = Flags.zeros(int(rest.sum()))
        real(physics, Starts(*(a[rest] for a in starts)), max_collisions,
             Sample(slot=sample.slot[rest], target=sample.target[rest], rows=sample.rows),
             portrait, sub_flags)
        flags.status[rest] = sub_flags.status
        flags.state[rest] = sub_flags.state
        flags.status[flag] = 1
        flags.state[flag] = np.column_stack(starts)[flag]

    return kernel


def _portrait_plan():
    """The scene with v_range's ends set to two velocities the orbits actually take: the lower
    end is a collision velocity (counted: lo <= v), the upper one another (not counted)."""
    plan = make_plan(parse_scene(PORTRAIT_300))
    phi, v, *_ = chunk_starts(plan, 0, 0)
    velocities = []
    for p, w in zip(phi[:40], v[:40], strict=True):
        for _ in range(12):
            p, w, _tau = fast_settle(p, w, 0.6)
            velocities.append(w)
    velocities.sort()
    lo, hi = velocities[len(velocities) // 10], velocities[-len(velocities) // 10]
    plan.scene = dataclasses.replace(plan.scene, v_range=(lo, hi))
    return plan, lo, hi


@pytest.mark.parametrize("which", ["every", "random half"])
def test_settled_portrait_equals_the_fast_portrait_bin_for_bin(monkeypatch, which):
    plan, lo, hi = _portrait_plan()
    base, _ = chunk.simulate_chunk(plan, 0, 0)
    assert base.portrait.sum() > 1000 and base.settled == 0
    rng = np.random.default_rng(1)
    choose = {"every": lambda n: np.ones(len(n), bool),
              "random half": lambda n: rng.random(len(n)) < 0.5}[which]
    monkeypatch.setattr(chunk, "portrait_chunk", flagging_portrait(chunk.portrait_chunk, choose))
    monkeypatch.setattr(chunk, "settle", fast_settle)
    settled, _ = chunk.simulate_chunk(plan, 0, 0)
    np.testing.assert_array_equal(settled.portrait, base.portrait)
    assert settled.collisions == base.collisions == 300 * 12
    assert settled.settled > 0


def test_portrait_edges_are_hit_by_the_settled_path(monkeypatch):
    """The precondition of the bin-for-bin test: some collision lands exactly on v_range's
    lower end (counted in the first v bin) and some on its upper end (not counted)."""
    plan, lo, hi = _portrait_plan()
    hits = {"lo": 0, "hi": 0}
    real = fast_settle

    def watching(phi, v, eps):
        out = real(phi, v, eps)
        hits["lo"] += out[1] == lo
        hits["hi"] += out[1] == hi
        return out

    monkeypatch.setattr(chunk, "portrait_chunk",
                        flagging_portrait(chunk.portrait_chunk, lambda n: np.ones(len(n), bool)))
    monkeypatch.setattr(chunk, "settle", watching)
    chunk.simulate_chunk(plan, 0, 0)
    assert hits["lo"] >= 1 and hits["hi"] >= 1


def _one_particle_plan(horizon, eps=0.0):
    """One particle from (phi, v) = (0, 1) (a start box of zero width) with ``eps``; with
    eps = 0 every flight is exactly tau = 2 and phi advances by 2 into the hole [1.9, 2.1)."""
    text = f"""
name = "one"
kind = "escape"
eps = 0.6
particles = 1
seed = 1
[start]
phi = [3.0, 4.0]
v = [1.0, 2.0]
[holes]
centres = [2.0]
widths = [0.2]
[horizon]
{horizon}
"""
    plan = make_plan(parse_scene(text))
    plan.scene = dataclasses.replace(plan.scene, eps=eps)
    plan.experiments[0] = dataclasses.replace(plan.experiments[0], phi=(0.0, 0.0), v=(1.0, 1.0))
    return plan


def test_settled_collision_exactly_at_the_time_horizon_is_made(monkeypatch):
    """As in the kernel, censoring needs t1 > max_time: the flight lands at t1 = 2 = max_time
    in the hole [1.9, 2.1) and escapes."""
    plan = _one_particle_plan("time = 2.0")
    monkeypatch.setattr(chunk, "escape_chunk", _flag_everything)
    monkeypatch.setattr(chunk, "settle", fast_settle)
    out, _ = chunk.simulate_chunk(plan, 0, 0)
    assert out.esc_n.sum() == 1 and out.cens_n.sum() == 0 and out.collisions == 1


def _flag_everything(physics, starts, holes, horizon, bins, sample, counts, flags):
    flags.status[:] = 1
    flags.state[:] = np.column_stack(starts)


def test_rows_are_the_reached_samples_only():
    """max_collisions = 1: every pick's target is collision 1; all rows have n = 1. With a
    time horizon before the first landing no particle makes a collision: no rows at all."""
    one = make_plan(parse_scene(PORTRAIT_300.replace("collisions = 12", "collisions = 1")))
    _, rows = chunk.simulate_chunk(one, 0, 0)
    assert len(rows) == one.samples_per_chunk > 0
    assert all(row[3] == 1 for row in rows)
    none = _one_particle_plan("time = 1.0", eps=0.6)
    out, rows = chunk.simulate_chunk(none, 0, 0)
    assert out.cens_n.sum() == 1 and out.collisions == 0 and rows == []


# --- run_chunk ------------------------------------------------------------------------------

def test_run_chunk_passes_particles_and_seed():
    sc = parse_scene(PORTRAIT_300)
    result = chunk.run_chunk(sc, 11, 0, 0, particles=40)
    counts, rows = chunk.simulate_chunk(make_plan(sc, 40, 11), 0, 0)
    assert result.failure is None and result.code == chunk.CODE_DIGEST
    np.testing.assert_array_equal(result.counts.portrait, counts.portrait)
    assert result.counts.collisions == 40 * 12 and [r[:9] for r in result.rows] == rows


@pytest.mark.parametrize(("curve", "chunk_index", "needle"), [
    (1, 0, "no chunk \\(1, 0\\) in a run of 1 curves x 1 chunks"),
    (0, 1, "no chunk \\(0, 1\\)"), (-1, 0, "no chunk"), (0, -1, "no chunk"),
])
def test_run_chunk_refuses_a_chunk_outside_the_run(curve, chunk_index, needle):
    with pytest.raises(ValueError, match=needle):
        chunk.run_chunk(parse_scene(PORTRAIT_300), 1, curve, chunk_index, particles=10)


def test_run_chunk_failure_is_data(monkeypatch):
    """A collision verify cannot settle: the result carries the message, empty integer counts,
    no rows, the elapsed seconds and the code digest."""

    def undecidable(phi, v, eps, dps=50):
        raise verify.UndecidableCollision(phi, v, eps, dps, "forced")

    monkeypatch.setattr(chunk, "portrait_chunk",
                        flagging_portrait(chunk.portrait_chunk, lambda n: np.ones(len(n), bool)))
    monkeypatch.setattr(verify, "step", undecidable)
    t0 = time.perf_counter()
    result = chunk.run_chunk(parse_scene(PORTRAIT_300), 1, 0, 0, particles=10)
    wall = time.perf_counter() - t0
    assert (result.curve, result.chunk) == (0, 0)
    assert result.failure.startswith("verify could not settle the flagged collision from phi=")
    assert "forced" in result.failure
    assert result.rows == [] and result.bad == [] and result.code == chunk.CODE_DIGEST
    assert 0 <= result.seconds <= wall
    for name in ("esc_n", "esc_t", "cens_n", "cens_t", "portrait"):
        a = getattr(result.counts, name)
        assert a.shape == (0,) and a.dtype == np.int64, name
    assert (result.counts.collisions, result.counts.settled) == (0, 0)
    with pytest.raises(chunk.RunFailed, match="forced"):
        chunk.check_result(result)


def test_run_chunk_seconds_are_its_wall_time():
    t0 = time.perf_counter()
    result = chunk.run_chunk(parse_scene(PORTRAIT_300), 1, 0, 0, particles=10)
    assert 0 <= result.seconds <= time.perf_counter() - t0


@pytest.mark.parametrize(("threads", "expected"), [
    (1, 1), (0, 1), (10**6, numba.config.NUMBA_NUM_THREADS), (1.0, 1)])
def test_run_chunk_sets_the_numba_threads(threads, expected):
    before = numba.get_num_threads()
    try:
        result = chunk.run_chunk(parse_scene(PORTRAIT_300), 1, 0, 0, particles=10, threads=threads)
        assert numba.get_num_threads() == expected
    finally:
        numba.set_num_threads(before)
    assert result.failure is None


def test_verify_rows_failure_names_the_sampled_collision(monkeypatch):
    def undecidable(phi, v, tau, eps):
        raise verify.UndecidableCollision(phi, v, eps, 30, "forced")

    monkeypatch.setattr(chunk, "check_sample", undecidable)
    row = [0, 0, 3, 7.0, 0.25, 1.5, 1.0, 2.0, 0.5]
    with pytest.raises(chunk.RunFailed) as info:
        chunk.verify_rows([row], 0.6)
    assert str(info.value).startswith(
        "verify could not decide sampled collision 7 from phi=0.25, v=1.5 that fastpath"
        " converged: ")
    assert "forced" in str(info.value)


# --- chunk_starts: the verification picks ---------------------------------------------------


# --- Tally.load ---------------------------------------------------------------------------------


def test_settled_states_on_the_portrait_edges_land_in_the_last_bins(monkeypatch):
    """verify's phase is rounded to float64 and may be TWO_PI itself (a phase just below 2*pi),
    and (v - lo)/(hi - lo) may round to 1 for v < hi: both are clamped into the last bin, as in
    the kernel. Every collision is settled here at (TWO_PI, 2.0), with v_range = (-2**60, the
    float after 2.0)."""
    plan = make_plan(parse_scene(PORTRAIT_300), particles=5)
    plan.scene = dataclasses.replace(plan.scene, v_range=(-(2.0**60), np.nextafter(2.0, 3.0)))
    monkeypatch.setattr(chunk, "portrait_chunk",
                        flagging_portrait(chunk.portrait_chunk, lambda n: np.ones(len(n), bool)))
    monkeypatch.setattr(chunk, "settle", lambda phi, v, eps: (TWO_PI, 2.0, 1.0))
    out, _ = chunk.simulate_chunk(plan, 0, 0)
    assert out.portrait[-1, -1] == out.portrait.sum() == 5 * 12


def test_a_sample_departing_at_phase_zero_is_kept():
    """The sample row of a particle that departs at phi = 0.0 exactly (eps = 0: tau = 2, the
    landing at phase 2 is in the hole [1.9, 2.1)): rows are kept by their collision index."""
    plan = _one_particle_plan("time = 10.0")
    out, rows = chunk.simulate_chunk(plan, 0, 0)
    assert out.esc_n.sum() == 1
    assert rows == [[0, 0, 0, 1.0, 0.0, 1.0, 2.0, 1.0, 2.0]]


def test_settle_rounds_verify_at_the_recorded_precision():
    """``settle`` returns the floats of ``verify.step`` at ``VERIFY_DPS`` (30 digits, recorded
    in the run manifest as ``verify_dps``): the settled state, hence the rest of a particle's
    orbit, depends on it. eps = 0, phi = 2**-53*(1 + 2**-52), v = 1/2: tau = 1 and the exact
    phi1 = 1 + 2**-53 + 2**-105 lies 2**-105 above a float64 rounding midpoint; at 30 digits
    (103 bits) it rounds to the midpoint first and then to 1.0 (ties to even), at 50 digits to
    1 + 2**-52. (So the settled phi1 can be 1 ulp from the correctly rounded value: a double
    rounding within 2**-103 relative of a midpoint.)"""
    phi, v, eps = 2.0**-53 * (1 + 2.0**-52), 0.5, 0.0
    assert chunk.VERIFY_DPS == 30
    assert chunk.settle(phi, v, eps) == (1.0, 0.5, 1.0)
    assert float(verify.step(phi, v, eps, dps=50)[0]) == 1.0 + 2.0**-52


def _sample_by_hand(phi, v, tau, eps, physics=None):
    """``check_sample``'s definition from verify at ``VERIFY_DPS``: tau_ref = verify.step's
    tau, error = |tau - tau_ref|/tau_ref/(kappa*u), overstep = rel > 16*kappa*u."""
    u = 2.0**-53
    if physics:
        phi1, v1, tau_ref = verify.step(phi, v, eps, dps=chunk.VERIFY_DPS, **physics)
        kappa = chunk.dissipative_kappa(phi, v, eps, tau_ref, phi1, v1, physics["restitution"])
    else:
        tau_ref = verify.step(phi, v, eps, dps=chunk.VERIFY_DPS)[2]
        kappa = verify.condition_number(phi, v, eps, tau_ref)
    rel = (tau - tau_ref) / tau_ref
    return float(tau_ref), float(abs(rel) / (kappa * u)), bool(rel > 16 * kappa * u), kappa


@pytest.mark.parametrize("physics", [None, {"drag": 0.1, "drag_law": "linear",
                                            "restitution": 1.0}], ids=["elastic", "drag"])
def test_check_sample_error_and_overstep_in_units_of_kappa_u(physics):
    """A fast tau moved off verify's by k*kappa*u (k = 0, 3, -3, 40): the recorded error is |k|
    (to the rounding of tau), the overstep flag is set only for k = 40 > 16; and the values are
    those of verify at VERIFY_DPS, bit for bit (``bouncer verify`` re-derives them: at k = 0,
    tau = float(tau_ref), the error is the rounding of tau_ref, whose bits depend on the 30
    digits of tau_ref, not only on its float64). The drag
    flight's tau_ref is the drag flight's (not the elastic one, 0.6% longer here)."""
    phi, v, eps = 0.4, 1.3, 0.6
    tau_ref, _, _, kappa = _sample_by_hand(phi, v, 1.0, eps, physics)
    if physics:
        assert abs(tau_ref / float(verify.flight_time(phi, v, eps)) - 1) > 1e-3
    u = 2.0**-53
    for k in (0.0, 3.0, -3.0, 40.0):
        tau = tau_ref * (1 + k * float(kappa) * u)
        got = chunk.check_sample(phi, v, tau, eps, physics) if physics else chunk.check_sample(
            phi, v, tau, eps)
        assert got == _sample_by_hand(phi, v, tau, eps, physics)[:3]
        assert got[0] == tau_ref
        # tau, 1 + k*kappa*u and tau_ref each rounded to float64 (u relative): 3/kappa
        assert abs(got[1] - abs(k)) <= 3 / float(kappa)
        assert got[2] == (k > 16)


def test_check_sample_overstep_is_strictly_beyond_16_kappa_u():
    """eps = 0, phi = 0, v = 1/2: tau_ref = 1 and kappa = (v + tau)/|v - tau| = 3 exactly, so
    rel = tau - 1 is exact: tau = 1 + 16*3*u is at the tolerance (not an overstep), the next
    float beyond it is."""
    at = 1.0 + 16 * 3 * 2.0**-53
    assert chunk.OVERSTEP_TOLERANCE == 16
    assert verify.condition_number(0.0, 0.5, 0.0, 1.0) == 3
    assert chunk.check_sample(0.0, 0.5, at, 0.0) == (1.0, 16.0, False)
    assert chunk.check_sample(0.0, 0.5, np.nextafter(at, 2.0), 0.0)[2]


def test_a_second_kernel_pass_adds_to_the_counts():
    plan = make_plan(parse_scene(ESCAPE_300))
    exp = plan.experiments[0]
    phi, v, slot, target, _ = chunk_starts(plan, 0, 0)
    m = len(phi)

    def one_pass(out):
        kernel(plan, exp, (phi, v, np.zeros(m), np.zeros(m, np.int64)), np.full(m, -1),
               np.zeros(m, np.int64), np.zeros((0, 6)), out)

    once, twice = Counts.zeros(plan, 1), Counts.zeros(plan, 1)
    one_pass(once)
    one_pass(twice)
    one_pass(twice)
    assert once.cens_t.sum() > 0 and once.esc_t.sum() > 0  # the time clock is exercised
    for name in ("esc_n", "esc_t", "cens_n", "cens_t"):
        np.testing.assert_array_equal(getattr(twice, name), 2 * getattr(once, name))
    assert twice.collisions == 2 * once.collisions


def _pass(plan, out):
    exp = plan.experiments[0]
    phi, v, _, _, _ = chunk_starts(plan, 0, 0)
    m = len(phi)
    return kernel(plan, exp, (phi, v, np.zeros(m), np.zeros(m, np.int64)), np.full(m, -1),
                  np.zeros(m, np.int64), np.zeros((0, 6)), out)


def test_a_second_dissipative_pass_adds_to_every_count():
    plan = make_plan(parse_scene(STICK_200))
    once, thrice = Counts.zeros(plan, 1), Counts.zeros(plan, 1)
    _pass(plan, once)
    for _ in range(3):
        _pass(plan, thrice)
    assert once.stuck_n.sum() > 0 and once.stuck_t.sum() > 0 and once.esc_n.sum() > 0
    for name in ("esc_n", "esc_t", "cens_n", "cens_t", "stuck_n", "stuck_t"):
        np.testing.assert_array_equal(getattr(thrice, name), 3 * getattr(once, name), name)
    assert thrice.collisions == 3 * once.collisions
    # every particle ends once on each clock: escaped, censored or stuck (per bin, not the
    # total added to every bin)
    for esc, cens, stuck in ((once.esc_n, once.cens_n, once.stuck_n),
                             (once.esc_t, once.cens_t, once.stuck_t)):
        assert esc.sum() + cens.sum() + stuck.sum() == 200


def test_the_dissipative_kernel_stops_at_each_horizon():
    """A short collision horizon (then a short time horizon) censors particles there: no
    escape or sticking is counted beyond it on its clock."""
    plan = make_plan(parse_scene(STICK_200.replace("collisions = 2000", "collisions = 30")))
    out = Counts.zeros(plan, 1)
    _pass(plan, out)
    beyond = plan.n_edges > 30
    assert out.cens_n.sum() > 0 and out.esc_n[0, beyond].sum() == 0
    assert out.stuck_n[beyond].sum() == 0 and out.cens_n[beyond].sum() == 0
    assert out.esc_n.sum() + out.cens_n.sum() + out.stuck_n.sum() == 200
    plan = make_plan(parse_scene(STICK_200.replace("time = 1e5", "time = 10.0")))
    out = Counts.zeros(plan, 1)
    _pass(plan, out)
    beyond = plan.t_edges > 10.0  # (a censored particle's time is its first beyond 10)
    assert out.cens_t.sum() > 0 and out.esc_t[0, beyond].sum() == 0
    assert out.stuck_t[beyond].sum() == 0
    # censored per bin, not the chunk's total added to every bin
    assert out.esc_t.sum() + out.cens_t.sum() + out.stuck_t.sum() == 200


def _counts_for(text):
    plan = make_plan(parse_scene(text))
    out = Counts.zeros(plan, 1)
    _pass(plan, out)
    return out


def test_the_dissipative_kernel_gets_the_scenes_physics():
    """Drag on or off, and its law, change the counts: the kernel is given sc.drag and
    _law_code(sc.drag_law), not defaults."""
    base = _counts_for(STICK_200)
    linear = _counts_for(STICK_200.replace("restitution = 0.5", "restitution = 0.5\ndrag = 0.05"))
    quadratic = _counts_for(STICK_200.replace("restitution = 0.5", "restitution = 0.5\ndrag = 0.05"
                                          '\ndrag_law = "quadratic"'))
    r8 = _counts_for(STICK_200.replace("restitution = 0.5", "restitution = 0.8"))
    for other in (linear, quadratic, r8):
        assert not np.array_equal(other.esc_n, base.esc_n) or other.collisions != base.collisions
    assert (not np.array_equal(linear.esc_n, quadratic.esc_n)
            or linear.collisions != quadratic.collisions)
