"""Mutation tests of ``plan.make_plan`` and of ``chunk.kernel``'s accumulation (issue 12's last
survivors of the kernel group): the seed override and its bounds, the error messages, and a
second kernel pass adding to the counts rather than replacing them."""

import numpy as np
import pytest

from reports.runs.chunk import kernel
from reports.runs.counts import Counts
from reports.runs.plan import chunk_starts, make_plan
from reports.runs.scenes import parse_scene

SCENE = """
name = "plan-small"
kind = "escape"
eps = 0.6
particles = 300
seed = 5
chunk_size = 128
[start]
phi = [3.85, 4.15]
v = [2.0, 4.0]
[holes]
centres = [2.0]
widths = [0.3]
[horizon]
collisions = 40
time = 60.0
[record]
verify_samples = 20
"""


def test_seed_override_and_its_bounds():
    scene = parse_scene(SCENE)
    assert make_plan(scene).seed == 5
    assert make_plan(scene, seed=0).seed == 0  # 0 is a seed
    assert make_plan(scene, seed=7).seed == 7
    a, b = chunk_starts(make_plan(scene, seed=7), 0, 0), chunk_starts(make_plan(scene), 0, 0)
    assert not np.array_equal(a[0], b[0])  # the override draws other starts
    with pytest.raises(ValueError, match=r"--seed must be >= 0, got -1"):
        make_plan(scene, seed=-1)
    with pytest.raises(ValueError, match=r"--particles must be >= 1, got 0"):
        make_plan(scene, particles=0)


def test_phase_space_with_physics_is_refused_with_its_reason():
    text = (SCENE.replace('kind = "escape"', 'kind = "phase-space"')
            .replace("[holes]\ncentres = [2.0]\nwidths = [0.3]\n", "")
            .replace("time = 60.0", "").replace("[record]", "[record]\nv_range = [0.0, 10.0]")
            + "[physics]\nrestitution = 0.9\n")
    with pytest.raises(ValueError, match=r"phase-space run with \[physics\].*dissipative"
                                          r" portrait kernel"):
        make_plan(parse_scene(text))


def test_a_second_kernel_pass_adds_to_the_counts():
    plan = make_plan(parse_scene(SCENE))
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
