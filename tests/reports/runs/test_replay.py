"""The seed's check in ``bouncer verify``: every sample row is a pick drawn from the seed, and
its state is the one its seeded start reaches (``reports.runs.replay``)."""

import csv
import dataclasses

import pytest
from scene_texts import PORTRAIT, STICK, TINY, TINY_VELOCITY

from reports.runs import driver
from reports.runs.plan import chunk_starts, make_plan
from reports.runs.replay import SampleRow, replay_problems
from reports.runs.scenes import parse_scene


def rows_of(run_dir):
    with open(run_dir / "sample.csv", newline="") as f:
        return [SampleRow(line, int(r["experiment"]), int(r["chunk"]), int(r["particle"]),
                          int(r["n"]), float(r["phi"]), float(r["v"]))
                for line, r in enumerate(csv.DictReader(f), start=2)]


@pytest.fixture(scope="module", params=[TINY, PORTRAIT, TINY_VELOCITY, STICK,
                                        TINY + "[physics]\ndrag = 0.05\n"],
                ids=["elastic transport", "phase-space", "velocity r=1 and 0.9",
                     "restitution 0.5", "drag, restitution 1"])
def sampled_run(request, tmp_path_factory):
    scene = parse_scene(request.param)
    out = tmp_path_factory.mktemp("replay") / "run"
    driver.run(scene, out, progress=False)
    return make_plan(scene), rows_of(out)


@pytest.mark.slow
def test_every_row_of_a_run_replays_from_its_seed(sampled_run):
    plan, rows = sampled_run
    assert len(rows) > 3 and any(r.n > 1 for r in rows)
    assert replay_problems(plan, rows) == []


def test_another_seed_fails_every_row(sampled_run):
    plan, rows = sampled_run
    other = dataclasses.replace(plan, seed=plan.seed + 1)
    problems = replay_problems(other, rows)
    assert len(problems) == len(rows)
    assert all(f"drawn from seed {plan.seed + 1}" in x for x in problems)


def test_a_state_one_collision_off_is_named(sampled_run):
    plan, rows = sampled_run
    row = next(r for r in rows if r.n > 1)
    earlier = dataclasses.replace(row, n=row.n - 1)
    (problem,) = replay_problems(plan, [earlier])
    assert problem.startswith(f"sample.csv:{row.line}: {row.n - 2} collisions from its start"
                              f" drawn from seed {plan.seed} give (phi, v) = ")
    assert problem.endswith(f", the file ({row.phi!r}, {row.v!r})")


def test_picks_and_targets_come_from_the_seed(sampled_run):
    plan, rows = sampled_run
    row = rows[0]
    _, _, slot, target, picks = chunk_starts(plan, row.experiment, row.chunk)
    not_picked = next(i for i in range(len(slot)) if slot[i] < 0)
    beyond = int(target[row.particle]) + 1
    cases = [dataclasses.replace(row, particle=not_picked),
             dataclasses.replace(row, particle=len(slot)),
             dataclasses.replace(row, n=beyond), dataclasses.replace(row, n=0),
             dataclasses.replace(row, chunk=plan.chunks_per_experiment),
             dataclasses.replace(row, experiment=-1)]
    problems = replay_problems(plan, cases)
    assert problems == [
        f"sample.csv:{row.line}: chunk ({row.experiment}, {plan.chunks_per_experiment}) is not"
        f" a chunk of this run ({len(plan.experiments)} curves x"
        f" {plan.chunks_per_experiment} chunks)",
        f"sample.csv:{row.line}: chunk (-1, {row.chunk}) is not a chunk of this run"
        f" ({len(plan.experiments)} curves x {plan.chunks_per_experiment} chunks)",
        f"sample.csv:{row.line}: particle {not_picked} of chunk ({row.experiment}, {row.chunk})"
        f" is not a verification pick drawn from seed {plan.seed}",
        f"sample.csv:{row.line}: particle {len(slot)} of chunk ({row.experiment}, {row.chunk})"
        f" is not a verification pick drawn from seed {plan.seed}",
        f"sample.csv:{row.line}: collision {beyond} is not in 1 .. {beyond - 1}, the target"
        f" collision of this pick drawn from seed {plan.seed}",
        f"sample.csv:{row.line}: collision 0 is not in 1 .. {beyond - 1}, the target"
        f" collision of this pick drawn from seed {plan.seed}"]
    assert len(picks) > 0


def test_the_progress_callback_counts_the_rows(sampled_run):
    plan, rows = sampled_run
    seen = []
    replay_problems(plan, rows, progress=seen.append)
    assert sum(seen) == len(rows)
