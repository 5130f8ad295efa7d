"""A scene's experiments and curves have names of their own, or the scene is refused.

The experiments are the product holes.centres x holes.widths (one per restitution in a velocity
scene) and their names are built from the values, rounded to NAME_DIGITS significant digits;
counts.csv, survival.csv and the manifest key everything by these names, so two experiments of
one name would merge their counts and the run's own audit would fail. Every way to collapse two
experiments is refused in one line naming the key and the values: a value listed twice however
it is written (0.2 and 0.20000000000000001 are one float), 0 and -0.0, a centre and the same
centre plus 2*pi, values that differ only beyond the digits a name shows, and transport pairs
(P1-11 and P11-1 with 10 holes or more). Any scene the parser accepts has distinct names.
"""

import math

import pytest
from hypothesis import example, given
from hypothesis import strategies as st

from reports.runs.scenes import NAME_DIGITS, TWO_PI, parse_scene

ESCAPE = """
name = "t"
kind = "escape"
eps = 0.6
particles = 100
seed = 1
[start]
phi = [3.85, 4.15]
v = [2.0, 4.0]
[holes]
centres = {centres}
widths = {widths}
[horizon]
collisions = 100
"""

TRANSPORT = """
name = "t"
kind = "transport"
eps = 0.6
particles = 100
seed = 1
[start]
v = [2.0, 4.0]
[holes]
centres = {centres}
widths = {widths}
[horizon]
collisions = 100
"""

VELOCITY = """
name = "t"
kind = "velocity"
eps = 2.0
particles = 100
seed = 1
[start]
phi = [3.85, 4.15]
v = [2.0, 4.0]
[horizon]
collisions = 100
[physics]
restitution = {restitutions}
"""


def refusal(text):
    with pytest.raises(ValueError) as err:
        parse_scene(text, "s.toml")
    line = str(err.value)
    assert "\n" not in line and line.startswith("s.toml: ")
    return line


@pytest.mark.parametrize(("template", "values", "message"), [
    (ESCAPE, dict(centres="[0.0]", widths="[0.2, 0.2]"),
     "holes.widths lists 0.2 twice (the experiments are holes.centres x holes.widths, each"
     " centre with each width: list each value once)"),
    (ESCAPE, dict(centres="[0.0]", widths="[0.2, 0.20000000000000001]"),
     "holes.widths lists 0.2 twice"),
    (ESCAPE, dict(centres="[0.0]", widths="[0.2, 2e-1]"), "holes.widths lists 0.2 twice"),
    (ESCAPE, dict(centres="[0.0, 0.0]", widths="[0.3]"), "holes.centres lists 0.0 twice"),
    (ESCAPE, dict(centres="[0, 0.0]", widths="[0.3]"), "holes.centres lists 0.0 twice"),
    (ESCAPE, dict(centres="[0.0, -0.0]", widths="[0.3]"),
     "holes.centres 0.0 and -0.0 are the same hole (mod 2*pi)"),
    (ESCAPE, dict(centres=f"[0.5, {0.5 + TWO_PI!r}]", widths="[0.3]"),
     f"holes.centres 0.5 and {0.5 + TWO_PI!r} are the same hole (mod 2*pi)"),
    (ESCAPE, dict(centres="[0.0]", widths="[0.2, 0.20001]"),
     f"holes.widths 0.2 and 0.20001 both show as 0.2 in curve names ({NAME_DIGITS} significant"
     f" digits): make them differ within {NAME_DIGITS} digits"),
    (ESCAPE, dict(centres="[1.0, 1.00004]", widths="[0.3]"),
     "holes.centres 1.0 and 1.00004 both show as 1 in curve names"),
    (ESCAPE, dict(centres="[12341.0, 12342.0]", widths="[0.3]"),
     "holes.centres 12341.0 and 12342.0 both show as 1.234e+04"),
    (TRANSPORT, dict(centres="[0.0, 3.141592653589793]", widths="[0.4, 0.4]"),
     "holes.widths lists 0.4 twice"),
    (VELOCITY, dict(restitutions="[0.9, 0.90001]"),
     "physics.restitution 0.9 and 0.90001 both show as 0.9 in curve names"),
    (VELOCITY, dict(restitutions="[0.9, 0.90000000000000001]"),
     "physics.restitution lists a value twice"),
])
def test_experiments_that_would_share_a_name_are_refused_naming_the_values(template, values,
                                                                           message):
    assert message in refusal(template.format(**values))


def test_the_product_of_centres_and_widths_names_each_experiment():
    scene = parse_scene(ESCAPE.format(centres="[0.0, 0.5]", widths="[0.2, 0.3]"))
    assert [x.name for x in scene.experiments()] == [
        "phi_c=0/h=0.2", "phi_c=0.5/h=0.2", "phi_c=0/h=0.3", "phi_c=0.5/h=0.3"]


def test_transport_pairs_with_ten_holes_or_more_are_named_apart():
    """P1-11 (hole 1 to hole 11) and P11-1 would both be P111 without the dash."""
    centres = [0.5 * i for i in range(12)]
    scene = parse_scene(TRANSPORT.format(centres=centres, widths="[0.1]"))
    curves = [c for x in scene.experiments() for c in x.curves]
    assert len(curves) == 144 == len(set(curves))
    assert "P1-11" in curves and "P11-1" in curves and "P111" not in curves
    nine = parse_scene(TRANSPORT.format(centres=centres[:9], widths="[0.1]"))
    assert nine.experiments()[0].curves[:2] == ("P11", "P12")  # as before for up to 9 holes


# ---- the invariant, on values that are written alike or print alike -------------------------

BASE = (0.0, 0.3, 0.5, 1.0, 1.7, 3.141592653589793)  # 0.3, 1.7: x + 2*pi mod 2*pi is not x
# the same float written another way, and floats close enough to print alike in a name
WRITTEN = (repr, lambda x: f"{x:.17g}", lambda x: f"{x:.20f}", lambda x: f"{x:.3e}")


@st.composite
def near_values(draw, base, lo=None, hi=None):
    x = draw(st.sampled_from(base))
    shift = draw(st.sampled_from((0.0, 0.0, -0.0, 1e-5, -3e-5, 1e-17, TWO_PI, -TWO_PI, TWO_PI)))
    value = x + shift if shift else x * draw(st.sampled_from((1.0, -1.0)))
    if lo is not None:
        value = min(max(value, lo), hi)
    return value


def toml_list(draw, values):
    return "[" + ", ".join(draw(st.sampled_from(WRITTEN))(v) for v in values) + "]"


@st.composite
def scene_texts(draw):
    kind = draw(st.sampled_from(("escape", "transport", "velocity")))
    if kind == "velocity":
        rs = draw(st.lists(near_values((0.5, 0.9, 0.95, 1.0), 0.01, 1.0), min_size=1,
                           max_size=4))
        return VELOCITY.format(restitutions=toml_list(draw, rs))
    centres = draw(st.lists(near_values(BASE), min_size=1, max_size=4))
    widths = draw(st.lists(near_values((0.1, 0.2, 0.3), 0.05, 0.3), min_size=1, max_size=3))
    template = ESCAPE if kind == "escape" else TRANSPORT
    return template.format(centres=toml_list(draw, centres), widths=toml_list(draw, widths))


@given(scene_texts())
@example(ESCAPE.format(centres=f"[0.3, {0.3 + TWO_PI!r}]", widths="[0.3]"))  # not exact mod 2pi
@example(TRANSPORT.format(centres=[0.5 * i for i in range(11)], widths="[0.1]"))
def test_an_accepted_scene_has_distinct_experiments_and_curve_names(text):
    try:
        scene = parse_scene(text, "s.toml")
    except ValueError as err:
        assert "\n" not in str(err) and str(err).startswith("s.toml: ")
        return
    experiments = scene.experiments()
    names = [x.name for x in experiments]
    curves = [c for x in experiments for c in x.curves]
    assert len(set(names)) == len(names) and len(set(curves)) == len(curves)
    holes = [(round(lo, 12) % round(TWO_PI, 12), w) for x in experiments
             for lo, w in zip(x.hole_lo, x.hole_width, strict=True)]
    if scene.kind == "escape":  # no hole run twice (0 and 2*pi, 0 and -0.0 are one hole)
        assert len(set(holes)) == len(holes)
    assert all(math.isfinite(lo) for lo, _ in holes)


def test_a_scene_of_more_curves_than_a_run_holds_is_refused_before_they_are_built():
    centres = [round(0.0003 * i, 4) for i in range(20_000)]
    line = refusal(ESCAPE.format(centres=centres, widths="[0.0001]"))
    assert line.endswith("20000 holes.centres and 1 holes.widths make 20000 curves, more than"
                         " the 10000 a run holds")
    line = refusal(TRANSPORT.format(centres=[0.1 * i for i in range(60)], widths="[0.01, 0.02,"
                                    " 0.03]"))
    assert "make 10800 curves" in line  # every hole to every hole, per width


def test_long_lists_are_compared_by_neighbours_not_by_every_pair():
    """9000 distinct centres are checked at once; a repeat among them is found and named."""
    centres = [1.0 + 0.001 * i for i in range(9000)]
    values = [float(f"{c:.4g}") for c in centres]
    assert len(set(values)) == 9000
    assert "holes.centres lists 1.5 twice" in refusal(
        ESCAPE.format(centres=values + [1.5], widths="[0.0001]"))
