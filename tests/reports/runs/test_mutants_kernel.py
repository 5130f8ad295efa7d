"""Mutation tests of ``chunk.kernel``'s dissipative branch (scripts/mutation.sh kernel): the
stuck accumulators add over passes like the escape ones (test_mutants_plan.py), and the
dissipative kernel gets the scene's physics (drag, its law, restitution)."""

import numpy as np
import pytest
from scene_texts import PORTRAIT, TINY, TINY_VELOCITY
from scene_texts import STICK as STICK_400

from reports.runs.chunk import kernel
from reports.runs.counts import Counts
from reports.runs.plan import chunk_starts, make_plan
from reports.runs.scenes import parse_scene

STICK = STICK_400.replace("particles = 400", "particles = 200")
VELOCITY = TINY_VELOCITY.replace("verify_samples = 6\n", "")


def _pass(plan, out):
    exp = plan.experiments[0]
    phi, v, _, _, _ = chunk_starts(plan, 0, 0)
    m = len(phi)
    return kernel(plan, exp, (phi, v, np.zeros(m), np.zeros(m, np.int64)), np.full(m, -1),
                  np.zeros(m, np.int64), np.zeros((0, 6)), out)


def test_a_second_dissipative_pass_adds_to_every_count():
    plan = make_plan(parse_scene(STICK))
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
    plan = make_plan(parse_scene(STICK.replace("collisions = 2000", "collisions = 30")))
    out = Counts.zeros(plan, 1)
    _pass(plan, out)
    beyond = plan.n_edges > 30
    assert out.cens_n.sum() > 0 and out.esc_n[0, beyond].sum() == 0
    assert out.stuck_n[beyond].sum() == 0 and out.cens_n[beyond].sum() == 0
    assert out.esc_n.sum() + out.cens_n.sum() + out.stuck_n.sum() == 200
    plan = make_plan(parse_scene(STICK.replace("time = 1e5", "time = 10.0")))
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
    base = _counts_for(STICK)
    linear = _counts_for(STICK.replace("restitution = 0.5", "restitution = 0.5\ndrag = 0.05"))
    quadratic = _counts_for(STICK.replace("restitution = 0.5", "restitution = 0.5\ndrag = 0.05"
                                          '\ndrag_law = "quadratic"'))
    r8 = _counts_for(STICK.replace("restitution = 0.5", "restitution = 0.8"))
    for other in (linear, quadratic, r8):
        assert not np.array_equal(other.esc_n, base.esc_n) or other.collisions != base.collisions
    assert (not np.array_equal(linear.esc_n, quadratic.esc_n)
            or linear.collisions != quadratic.collisions)


# ---- Counts.zeros ----------------------------------------------------------------------------




def _int_zeros(a, shape):
    assert a.dtype == np.int64 and a.shape == shape and not a.any()


def test_zeros_are_integer_counts_of_the_plans_shape():
    """Counts are int64 (the checkpoint and counts.csv hold integers); the portrait is drawn
    only by phase-space scenes, the velocity arrays only exist for velocity scenes."""
    plan = make_plan(parse_scene(STICK))
    nb, tb = len(plan.n_edges), len(plan.t_edges)
    for lead in ((), (3,)):
        c = Counts.zeros(plan, 2, experiments=lead[0] if lead else None)
        _int_zeros(c.esc_n, (*lead, 2, nb))
        _int_zeros(c.esc_t, (*lead, 2, tb))
        _int_zeros(c.cens_n, (*lead, nb))
        _int_zeros(c.cens_t, (*lead, tb))
        _int_zeros(c.stuck_n, (*lead, nb))
        _int_zeros(c.stuck_t, (*lead, tb))
        _int_zeros(c.portrait, (0, 0))
        assert c.moving is None and c.sum_v is None
    plan = make_plan(parse_scene(PORTRAIT))
    _int_zeros(Counts.zeros(plan, 1).portrait, (4, 3))
    plan = make_plan(parse_scene(VELOCITY))
    for lead in ((), (2,)):
        c = Counts.zeros(plan, 1, experiments=lead[0] if lead else None)
        grid = (*lead, len(plan.n_grid))
        _int_zeros(c.moving, grid)
        _int_zeros(c.stuck_at, grid)
        _int_zeros(c.portrait, (0, 0))
        for a in (c.sum_v, c.sum_v2):
            assert a.shape == grid and all(x == 0 and type(x).__name__ == "Fraction"
                                           for x in a.flat)


# ---- make_plan -------------------------------------------------------------------------------



def test_sample_picks_are_spread_over_every_chunk_of_every_curve():
    """Two curves of 200 particles in chunks of 64: 8 chunks, all sampled (stride 1), and
    min(verify_samples, 400 // 10) = 40 picks make 5 a chunk."""
    plan = make_plan(parse_scene(TINY))
    assert (plan.chunks_per_experiment, plan.n_chunks) == (4, 8)
    assert plan.sample_stride == 1 and plan.samples_per_chunk == 5 and plan.sampled_chunks == 8


def test_more_chunks_than_sampled_chunks_gives_a_stride():
    from reports.runs.plan import MAX_SAMPLED_CHUNKS

    scene = parse_scene(TINY.replace("chunk_size = 64", "chunk_size = 16"))
    plan = make_plan(scene, particles=16 * MAX_SAMPLED_CHUNKS // 2 + 16)
    assert plan.n_chunks == MAX_SAMPLED_CHUNKS + 2 and plan.sample_stride == 2
    assert plan.sampled_chunks == MAX_SAMPLED_CHUNKS // 2 + 1 and plan.samples_per_chunk == 1


def test_phase_space_physics_refusal_names_what_does_take_physics():
    with pytest.raises(ValueError) as err:
        make_plan(parse_scene(PORTRAIT + "[physics]\nrestitution = 0.9\n"))
    assert str(err.value).endswith("needs a dissipative portrait kernel, which fastpath does not"
                                   " have; escape and transport scenes take [physics]")


ONE = STICK.replace("[physics]\nrestitution = 0.5\n", "").replace(
    "chunk_size = 200", "chunk_size = 64").replace("verify_samples = 20", "")  # 1000 wanted


@pytest.mark.parametrize(("particles", "per_chunk"), [(5, 1), (19, 1), (205, 5), (260, 6)])
def test_samples_a_chunk_from_a_tenth_of_the_particles(particles, per_chunk):
    """One curve: wanted = min(verify_samples, max(1, particles // 10)) picks over its chunks,
    rounded up: 5 or 19 particles in one chunk want 1 (not 2); 205 particles (4 chunks) want
    20 (not 20.5, which would give 6 a chunk): 5; 260 (5 chunks) want 26: 6."""
    plan = make_plan(parse_scene(ONE), particles=particles)
    assert len(plan.experiments) == 1 and plan.sample_stride == 1
    assert plan.samples_per_chunk == per_chunk


def test_many_picks_over_strided_chunks():
    """verify_samples 30000 over 16386 chunks sampled every other one (8193): 26217 wanted
    (a tenth of 262176) make 4 a sampled chunk."""
    from reports.runs.plan import MAX_SAMPLED_CHUNKS

    scene = parse_scene(TINY.replace("chunk_size = 64", "chunk_size = 16").replace(
        "[horizon]", "[record]\nverify_samples = 30000\n[horizon]"))
    plan = make_plan(scene, particles=16 * MAX_SAMPLED_CHUNKS // 2 + 16)
    assert plan.sample_stride == 2 and plan.samples_per_chunk == 4


def test_bin_edges():
    plan = make_plan(parse_scene(TINY))
    assert plan.n_edges[:5].tolist() == [1.0, 2.0, 3.0, 4.0, 5.0]
    assert np.array_equal(plan.n_edges, np.unique(np.round(plan.n_edges)))
    assert plan.t_edges[0] == 0.0 and plan.t_edges[1] > 0.0
