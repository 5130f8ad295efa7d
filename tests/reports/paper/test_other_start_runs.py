"""Claims decided on other runs where they are given: the other start density (sec3-other-density)
and the island holes alone with more starts (fig2-n-tail-phi_c=H)."""

from pathlib import Path

import pytest

from reports.paper.claims.start_claims import curves_by_key, other_density_claim
from reports.runs import driver
from reports.runs.scenes import parse_scene

SCENE = """
name = "NAME"
kind = "escape"
eps = 0.6
particles = 3000
seed = SEED
chunk_size = 1024
[start]
phi = [3.85, 4.15]
v = [2.0, 4.0]
DENSITY
[holes]
centres = [1.0, 2.5]
widths = [0.3]
[horizon]
collisions = 2000
[record]
verify_samples = 10
"""


def _run(tmp, name, seed, density):
    text = (SCENE.replace("NAME", name).replace("SEED", str(seed))
            .replace("DENSITY", 'density = "sine"' if density else ""))
    out = Path(tmp) / name
    driver.run(parse_scene(text), out, progress=False)
    return out


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("density")
    return _run(tmp, "reference", 1, False), _run(tmp, "other-density", 2, True)


def test_a_run_of_the_other_density_is_compared_hole_by_hole_and_clock_by_clock(runs):
    ref, other = runs
    levels = {c[0]: 0.1 for c in curves_by_key(ref)}
    claim = other_density_claim(ref, {}, levels, density_run=other)
    assert claim.run == "other-density"
    assert claim.evidence.startswith("Run other-density (3,000 per hole)")
    parts = {a["part"] for a in claim.analyses}
    assert parts == {f"{e} ({u})" for e in levels for u in ("n", "t")}


def test_the_island_holes_tail_is_decided_on_the_run_of_that_hole_alone(runs, tmp_path):
    """fig2-n-tail-phi_c=H reads the run of the hole alone (scene escape-tail-phi_c=H) where
    one is given; the other claims stay on the paper-scale run."""
    from reports.paper.claims.escape_claims import escape_analysis, escape_claims

    ref, _ = runs
    alone = Path(tmp_path) / "alone"
    text = (SCENE.replace("NAME", "escape-tail-phi_c=1").replace("SEED", "3")
            .replace("DENSITY", "").replace("centres = [1.0, 2.5]", "centres = [1.0]"))
    driver.run(parse_scene(text), alone, progress=False)
    analysis = escape_analysis(ref, 10.0)
    tail = escape_analysis(alone, 10.0)
    claims = {c.id: c for c in escape_claims(analysis, ref, tails={"1": (tail["1"], alone)})}
    assert claims["fig2-n-tail-phi_c=1"].run == "alone"
    assert claims["fig2-n-phi_c=1"].run == "reference"
    plain = {c.id: c for c in escape_claims(analysis, ref)}
    assert plain["fig2-n-tail-phi_c=1"].run == "reference"
