"""Start densities (``[start] density``) and the scene keys of the records: validation, the
draws (the uniform ones exactly as before, the sine density's law), a run of a non-uniform
density audited from its seed."""

import json
import math
from pathlib import Path

import numpy as np
import pytest
from scipy import stats

from reports.runs import driver, rundir
from reports.runs.plan import chunk_starts, draw_starts, make_plan
from reports.runs.recheck import recheck
from reports.runs.scenes import load_scene, parse_scene

SINE = """
name = "sine"
kind = "escape"
eps = 0.6
particles = 300
seed = 4
chunk_size = 100
[start]
phi = [3.85, 4.15]
v = [2.0, 4.0]
density = "sine"
[holes]
centres = [2.5]
widths = [0.3]
[horizon]
collisions = 300
[record]
verify_samples = 30
"""


def sine_cdf(x):
    """Distribution function of the density (pi/2) sin(pi x) on [0, 1]."""
    return (1.0 - np.cos(math.pi * np.clip(x, 0.0, 1.0))) / 2.0


# ---- scene keys -----------------------------------------------------------------------------

def test_density_defaults_to_uniform_and_takes_sine():
    assert parse_scene(SINE.replace('density = "sine"\n', "")).density == "uniform"
    assert parse_scene(SINE).density == "sine"
    assert parse_scene(SINE.replace('"sine"', '"uniform"')).density == "uniform"


@pytest.mark.parametrize(("text", "message"), [
    ('density = "gaussian"', "start.density must be one of uniform, sine, got 'gaussian'"),
    ("density = 3", "start.density must be one of uniform, sine, got 3"),
    ('density = ["sine"]', r"start.density must be one of uniform, sine, got \['sine'\]"),
])
def test_an_unknown_density_is_refused(text, message):
    with pytest.raises(ValueError, match=message):
        parse_scene(SINE.replace('density = "sine"', text))


@pytest.mark.parametrize(("record", "message"), [
    ('joint = "yes"', "record.joint must be true or false, got 'yes'"),
    ("joint = 1", "record.joint must be true or false, got 1"),
    ('joint = true\nclocks = ["time"]', r"record.joint needs both clocks"),
])
def test_the_joint_key_is_validated(record, message):
    with pytest.raises(ValueError, match=message):
        parse_scene(SINE.replace("[record]", f"[record]\n{record}"))


def test_a_phase_space_scene_takes_no_joint_record():
    text = """
name = "p"
kind = "phase-space"
eps = 0.6
particles = 10
seed = 1
[start]
phi = [3.85, 4.15]
v = [2.0, 4.0]
[horizon]
collisions = 10
[record]
joint = true
"""
    with pytest.raises(ValueError, match="record.joint belongs to escape and transport scenes"):
        parse_scene(text)


def test_the_records_are_part_of_the_scene():
    plain = parse_scene(SINE)
    assert not plain.joint and parse_scene(SINE + "joint = true\n").joint
    assert parse_scene(SINE + "joint = false\n") == plain
    assert parse_scene(SINE + "joint = true\n") != plain


def test_the_other_density_scene_compares_with_paper_escape_bin_by_bin():
    other, paper = load_scene("escape-other-density"), load_scene("paper-escape")
    assert other.density == "sine" and paper.density == "uniform"
    for key in ("eps", "start_phi", "start_v", "hole_centres", "hole_widths", "max_collisions",
                "max_time", "clocks", "bins_per_decade"):
        assert getattr(other, key) == getattr(paper, key), key
    assert other.seed != paper.seed


# ---- the draws --------------------------------------------------------------------------------

def test_uniform_starts_are_drawn_as_they_always_were():
    plan = make_plan(parse_scene(SINE.replace('density = "sine"\n', "")))
    phi, v, *_ = chunk_starts(plan, 0, 1)
    rng = np.random.default_rng(np.random.SeedSequence(plan.seed, spawn_key=(0, 1)))
    assert phi.tobytes() == rng.uniform(3.85, 4.15, 100).tobytes()
    assert v.tobytes() == rng.uniform(2.0, 4.0, 100).tobytes()


def test_sine_starts_follow_their_law_inside_the_box():
    phi, v = draw_starts(np.random.default_rng(7), (3.85, 4.15), (2.0, 4.0), 20000, "sine")
    assert phi.min() >= 3.85 and phi.max() < 4.15 and v.min() >= 2.0 and v.max() < 4.0
    x, y = (phi - 3.85) / 0.3, (v - 2.0) / 2.0
    assert stats.kstest(x, sine_cdf).pvalue > 1e-3
    assert stats.kstest(y, sine_cdf).pvalue > 1e-3
    assert abs(np.corrcoef(x, y)[0, 1]) < 4 / math.sqrt(20000)  # independent coordinates
    # the test tells the laws apart: uniform starts fail it
    u, _ = draw_starts(np.random.default_rng(7), (0.0, 1.0), (0.0, 1.0), 20000, "uniform")
    assert stats.kstest(u, sine_cdf).pvalue < 1e-6


def test_sine_starts_are_determined_by_the_seed():
    plan = make_plan(parse_scene(SINE))
    first = chunk_starts(plan, 0, 2)
    again = chunk_starts(plan, 0, 2)
    for a, b in zip(first, again, strict=True):
        assert a.tobytes() == b.tobytes()
    other = chunk_starts(make_plan(parse_scene(SINE), seed=5), 0, 2)
    assert first[0].tobytes() != other[0].tobytes()


def test_an_unknown_density_cannot_be_drawn():
    with pytest.raises(ValueError, match="unknown start density 'beta'"):
        draw_starts(np.random.default_rng(1), (0, 1), (0, 1), 3, "beta")


# ---- a run -------------------------------------------------------------------------------------

def test_a_sine_density_run_is_audited_from_its_seed(tmp_path):
    out = tmp_path / "run"
    manifest = driver.run(parse_scene(SINE), out, progress=False)
    assert manifest["scene"]["density"] == "sine"
    assert recheck(out)[0]
    # the same run claimed as uniform: the sample no longer replays from the seed's starts
    text = (out / "scene.toml").read_text().replace('density = "sine"\n', "")
    (out / "scene.toml").write_text(text)
    data = json.loads((out / "manifest.json").read_text())
    data["hashes"]["scene.toml"] = rundir.sha256_file(out / "scene.toml")
    del data["scene"]["density"]
    Path(out / "manifest.json").write_text(json.dumps(data))
    ok, lines = recheck(out)
    assert not ok and any("collisions from its start drawn from seed 4 give" in x
                          for x in lines), lines
