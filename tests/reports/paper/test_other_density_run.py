"""sec3-other-density is decided on a run of the other start density where one is given."""

from pathlib import Path

import pytest

from reports.paper.start_claims import curves_by_key, other_density_claim
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
