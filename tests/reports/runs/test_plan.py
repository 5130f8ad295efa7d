"""The plan of a run (``reports.runs.plan``): ``make_plan``'s seed override and its bounds, its
refusals, how many collisions are sampled and from which chunks, the bin edges, and
``chunk_starts``' verification picks (distinct particles, log-uniform collision indices)."""

import math

import numpy as np
import pytest
from scene_texts import ESCAPE_300, PORTRAIT_300, STICK_200, TINY

from reports.runs.plan import SAMPLE_DEPTH, chunk_starts, make_plan
from reports.runs.scenes import parse_scene


def test_seed_override_and_its_bounds():
    scene = parse_scene(ESCAPE_300)
    assert make_plan(scene).seed == 5
    assert make_plan(scene, seed=0).seed == 0  # 0 is a seed
    assert make_plan(scene, seed=7).seed == 7
    a, b = chunk_starts(make_plan(scene, seed=7), 0, 0), chunk_starts(make_plan(scene), 0, 0)
    assert not np.array_equal(a[0], b[0])  # the override draws other starts
    with pytest.raises(ValueError, match=r"--seed must be >= 0, got -1"):
        make_plan(scene, seed=-1)
    with pytest.raises(ValueError, match=r"--particles must be >= 1, got 0"):
        make_plan(scene, particles=0)


def test_picks_are_distinct_particles():
    """Every start of a small chunk is picked (samples_per_chunk >= chunk size): the picks are
    a permutation of the chunk, never a particle twice."""
    plan = make_plan(parse_scene(PORTRAIT_300), particles=12)
    plan.samples_per_chunk = 12
    phi, v, slot, target, picks = chunk_starts(plan, 0, 0)
    assert sorted(picks.tolist()) == list(range(12))
    assert sorted(slot.tolist()) == list(range(12)) and (target >= 1).all()


def test_sampled_collision_indices_are_log_uniform():
    """targets = floor(depth**U), U uniform: log-uniform in [1, depth]. For depth = 10**6
    (escape horizon without a collision limit) P(target < 1000) = 1/2; 2000 picks give
    1000 +- 22.4 (binomial sd); an accepted range of +-5 sd."""
    text = PORTRAIT_300.replace('kind = "phase-space"', 'kind = "escape"').replace(
        "phi = [0.0, 6.283185307179586]", "phi = [3.0, 5.0]").replace(
        "[horizon]\ncollisions = 12", "[holes]\ncentres = [1.0]\nwidths = [0.1]\n[horizon]\n"
        "time = 1e6").replace("[record]\nphi_bins = 36\nv_bins = 24\nv_range = [0.0, 8.0]",
                              "[record]\nverify_samples = 2000")
    plan = make_plan(parse_scene(text), particles=20000)
    assert plan.scene.max_collisions is None and plan.samples_per_chunk == 2000
    _, _, slot, target, picks = chunk_starts(plan, 0, 0)
    t = target[picks]
    assert t.min() >= 1 and t.max() <= SAMPLE_DEPTH
    assert len(np.unique(t)) > 500
    below = int((t < math.sqrt(SAMPLE_DEPTH)).sum())
    assert abs(below - 1000) <= 5 * math.sqrt(2000 * 0.25)


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


ONE = STICK_200.replace("[physics]\nrestitution = 0.5\n", "").replace(
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
