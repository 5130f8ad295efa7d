"""What the model cannot run is refused by the scene check, before anything is compiled.

Drag k stops a particle of speed V within 1/k (linear) or 1/(k*V) (quadratic); below the phase
resolution of one step (PHASE_ERROR, 4 ulps of 2*pi) float64 cannot run the flights (a
quadratic drag of 1e300 used to compile for minutes and then fail on a state that is no
departure). The bound follows from the scene: V is the fastest start plus 2*|eps|.
"""

import math

import pytest

from reports.runs.driver import run
from reports.runs.recheck import recheck
from reports.runs.scenes import PHASE_ERROR, TWO_PI, parse_scene

DRAG = """
name = "drag"
kind = "escape"
eps = 0.6
particles = 40
seed = 3
chunk_size = 20
[start]
phi = [3.85, 4.15]
v = [2.0, 4.0]
[holes]
centres = [0.0]
widths = [0.3]
[horizon]
collisions = 200
[record]
verify_samples = 20
[physics]
drag = {drag!r}
drag_law = "{law}"
"""

SPEED = 4.0 + 2 * 0.6  # the fastest start plus 2*|eps|


def test_the_phase_error_is_four_ulps_of_two_pi():
    assert PHASE_ERROR == 4 * math.ulp(TWO_PI) and 3.5e-15 < PHASE_ERROR < 3.6e-15


@pytest.mark.parametrize(("law", "largest"), [("linear", 1 / PHASE_ERROR),
                                              ("quadratic", 1 / (PHASE_ERROR * SPEED))])
def test_drag_beyond_the_resolution_of_a_step_is_refused_in_one_line(law, largest):
    parse_scene(DRAG.format(drag=largest, law=law))  # at the bound: accepted
    for drag in (math.nextafter(largest, math.inf), 1e300, 1.7976931348623157e308):
        with pytest.raises(ValueError) as err:
            parse_scene(DRAG.format(drag=drag, law=law), "d.toml")
        line = str(err.value)
        assert line.startswith(f"d.toml: physics.drag = {drag:.6g} ({law}) stops a particle"
                               " of speed 5.2 (the fastest start plus 2*|eps|) within ")
        assert line.endswith(f"float64 cannot run these flights; drag must be <= {largest:.3g}"
                             " here") and "\n" not in line


def test_the_quadratic_bound_follows_the_fastest_start():
    """k*V is the rate: starts ten times faster allow a ten times smaller drag."""
    fast = DRAG.replace("v = [2.0, 4.0]", "v = [2.0, 40.0]")
    largest = 1 / (PHASE_ERROR * (40.0 + 1.2))
    parse_scene(fast.format(drag=largest, law="quadratic"))
    with pytest.raises(ValueError, match="drag must be <= "):
        parse_scene(fast.format(drag=2 * largest, law="quadratic"))
    parse_scene(fast.format(drag=2 * largest, law="linear"))  # the linear rate has no speed


@pytest.mark.slow
@pytest.mark.parametrize("law", ["linear", "quadratic"])
def test_a_run_at_the_largest_admissible_drag_completes_and_passes_its_audit(law, tmp_path):
    """At the bound the particles ride the plate in hops of ~PHASE_ERROR: the run completes,
    and its own audit (sample recomputed by verify, replay from the seed) holds."""
    largest = 1 / PHASE_ERROR if law == "linear" else 1 / (PHASE_ERROR * SPEED)
    manifest = run(parse_scene(DRAG.format(drag=largest, law=law)), tmp_path / "r",
                   progress=False)
    assert manifest["status"] == "complete"
    ok, lines = recheck(tmp_path / "r")
    assert ok, lines
