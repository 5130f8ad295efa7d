"""The ``stuck`` column of dissipative runs: particles stuck on the plate for good are counted
on their own (counts.csv, checkpoint, manifest), and escapes + censored + stuck = particles."""

import json

import numpy as np
from scene_texts import STICK

from reports.runs import driver
from reports.runs.counts import Tally
from reports.runs.integrity import curve_problems, parse_counts
from reports.runs.plan import make_plan
from reports.runs.scenes import parse_scene


def test_stuck_particles_are_their_own_outcome(tmp_path):
    scene = parse_scene(STICK)
    driver.run(scene, tmp_path / "run", progress=False)
    manifest = json.loads((tmp_path / "run" / "manifest.json").read_text())
    curve = manifest["curves"]["phi_c=2"]
    # eps = 0.6 <= 1, r = 0.5: chattering ends on the plate for good, so some particles stick
    assert curve["stuck"] > 0
    assert sum(curve["escaped"].values()) + curve["censored"] + curve["stuck"] == 400
    assert manifest["scene"]["physics"] == {"drag": 0.0, "drag_law": "linear",
                                            "restitution": 0.5}
    plan = make_plan(scene)
    text = (tmp_path / "run" / "counts.csv").read_text()
    counts, stuck, problems, _ = parse_counts(plan, text)
    assert problems == [] and "stuck" in text
    for clock in scene.clocks:
        assert stuck[0, clock] == curve["stuck"]
    assert curve_problems(plan, counts, [400], stuck) == []
    assert curve_problems(plan, counts, [400], {}) != []  # without them the sum falls short
    tally = Tally.load(tmp_path / "run" / "checkpoint.npz")
    assert int(tally.stuck_n.sum()) == int(tally.stuck_t.sum()) == curve["stuck"]
    # escape survival: stuck particles never escape, so they survive at every x
    rows = [r.split(",") for r in (tmp_path / "run" / "survival.csv").read_text().split()[1:]]
    last = [r for r in rows if r[1] == "collisions"][-1]
    assert float(last[3]) >= curve["stuck"] / 400


def test_elastic_checkpoint_has_no_stuck_arrays(tmp_path):
    scene = parse_scene(STICK.replace("restitution = 0.5", "restitution = 1.0"))
    assert scene.elastic
    driver.run(scene, tmp_path / "run", progress=False)
    with np.load(tmp_path / "run" / "checkpoint.npz") as z:
        assert "stuck_n" not in z.files
    manifest = json.loads((tmp_path / "run" / "manifest.json").read_text())
    assert manifest["curves"]["phi_c=2"]["stuck"] == 0 and "physics" not in manifest["scene"]
    assert "stuck" not in (tmp_path / "run" / "counts.csv").read_text()


def test_drag_with_restitution_runs_and_counts_stuck(tmp_path):
    """drag and restitution < 1 together: linear drag 0.1 at eps = 0.6 gives
    0.6*sqrt(1.01) < 1, so accumulated particles are stuck for good."""
    scene = parse_scene(STICK.replace("restitution = 0.5", "restitution = 0.5\ndrag = 0.1"))
    driver.run(scene, tmp_path / "run", progress=False)
    manifest = json.loads((tmp_path / "run" / "manifest.json").read_text())
    curve = manifest["curves"]["phi_c=2"]
    assert curve["stuck"] > 0
    assert sum(curve["escaped"].values()) + curve["censored"] + curve["stuck"] == 400
    assert manifest["scene"]["physics"] == {"drag": 0.1, "drag_law": "linear",
                                            "restitution": 0.5}
