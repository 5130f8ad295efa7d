"""Scenes: small TOML files describing an ensemble run, validated into a frozen dataclass.

A scene gives its ``name`` (a plain file name: it names the run directory), the model
parameter ``eps``, the initial measure (a density on a box in phi and v: ``[start] density``),
the holes (arcs of collision phase mod 2*pi, each ``[c - w/2, c + w/2)`` for centre c and width w),
the horizon (a collision count and/or a time), the particle count per curve, the seed and what
to record. Four kinds:

``escape``       one curve per (width, centre): a single hole open, starts in ``[start]`` (phi, v),
                 which must not overlap the hole (the paper's Section 3).
``transport``    for each width, all holes open at once; curve P_ij starts uniform on hole i in
                 phase (``[start]`` gives only v) and leaves through hole j (Section 4).
``phase-space``  no holes: a (phi, v) histogram of ``horizon.collisions`` collisions per start.
``velocity``     no holes: the mean velocity <v_n> and <v_n**2> over the particles still moving
                 at collision n, on a log grid of n up to ``horizon.collisions`` (collisions
                 only); one curve per restitution: ``physics.restitution`` may be a list there.

An optional ``[physics]`` table sets the dissipation (phase-space scenes are elastic only): air
drag ``drag`` = k >= 0 with ``drag_law`` "linear" (eta(v) = k*v) or "quadratic" (eta(v) = k*v*|v|),
and the coefficient of restitution ``restitution`` = r in (0, 1] (impacts v1 - u = -r*(v_in - u)).
Left out, it is the elastic, drag-free model (drag = 0, "linear", r = 1), and ``Scene.elastic``
is True: the scene runs the elastic kernels unchanged.

The starts. ``[start] density = "uniform"`` (the default) draws them uniformly on the box;
``"sine"`` with the density proportional to sin(pi*x) * sin(pi*y), where x and y in [0, 1] are
the box's scaled coordinates (x = (phi - phi_lo) / (phi_hi - phi_lo), likewise y for v): smooth,
largest at the centre, zero on the edges. Both are drawn from the chunk's own random generator
(``plan.chunk_starts``), so they are determined by the seed.

What to record besides the histograms of the clocks: ``[record] joint = true`` (escape and
transport scenes, both clocks) records the joint histogram of (n, t) of every curve's escapes,
censored and stuck particles on the two clocks' bins (``reports.runs.joint_file``).

Built-in scenes live in ``reports/runs/builtin_scenes/*.toml`` (package data): ``paper-escape``,
``paper-transport``, ``paper-phase-space``, ``dissipation-saturation``. ``load_scene`` takes a
built-in name or a path.
"""

from __future__ import annotations

import math
import numbers
import re
import sys
import tomllib
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path

from fastpath.arithmetic.phase import TWO_PI
from fastpath.physics import LAWS
from reports.runs.echo import clip
from reports.runs.rundir import MAX_SCENE_BYTES, InputError, read_input

KINDS = ("escape", "transport", "phase-space", "velocity")
CLOCKS = ("collisions", "time")
MAX_CHUNK = 2**20

_TOP = {"name", "kind", "description", "eps", "particles", "seed", "chunk_size", "start",
        "holes", "horizon", "record", "physics"}
_TABLES = {
    "start": {"phi", "v", "density"},
    "holes": {"centres", "widths"},
    "horizon": {"collisions", "time"},
    "record": {"clocks", "bins_per_decade", "verify_samples", "phi_bins", "v_bins", "v_range",
               "joint"},
    "physics": {"restitution", "drag", "drag_law"},
}
DRAG_LAWS = tuple(LAWS)  # the drag_law names fastpath takes
DENSITIES = ("uniform", "sine")  # [start] density: the law of the starts on their box


@dataclass(frozen=True)
class Experiment:
    """One set of starts with its holes; it gives one curve per exit hole (``curves``).

    Hole j is the arc [hole_lo[j], hole_lo[j] + hole_width[j]) mod 2*pi, hole_lo in [0, 2*pi).
    """

    name: str
    curves: tuple[str, ...]
    hole_lo: tuple[float, ...]
    hole_width: tuple[float, ...]
    phi: tuple[float, float]
    v: tuple[float, float]


@dataclass(frozen=True)
class Scene:
    """A validated scene; see the module docstring. ``source`` is the TOML text it came from."""

    name: str
    kind: str
    eps: float
    particles: int
    seed: int
    start_phi: tuple[float, float] | None
    start_v: tuple[float, float]
    hole_centres: tuple[float, ...]
    hole_widths: tuple[float, ...]
    max_collisions: int | None
    max_time: float | None
    clocks: tuple[str, ...] = CLOCKS
    bins_per_decade: int = 20
    verify_samples: int = 1000
    chunk_size: int = 2**16
    phi_bins: int = 720
    v_bins: int = 480
    v_range: tuple[float, float] = (0.0, 12.0)
    description: str = ""
    restitution: float = 1.0
    drag: float = 0.0
    drag_law: str = "linear"
    restitutions: tuple[float, ...] = ()
    density: str = "uniform"
    joint: bool = False
    source: str = field(default="", compare=False, repr=False)

    @property
    def elastic(self) -> bool:
        """True for the elastic, drag-free model (no ``[physics]``, or its defaults)."""
        return self.restitution == 1.0 and self.drag == 0.0

    @property
    def carries(self) -> bool:
        """True for restitution < 1: a step of the dissipative kernel then reads a carried state
        beyond (phi, v) (``fastpath.carried_step``), which the sample records."""
        return self.restitution < 1.0

    def physics(self) -> dict:
        """The keywords of ``fastpath``/``verify`` for this scene's physics (empty if elastic).
        A velocity scene with several restitutions has one per curve: ``curve_physics``."""
        if self.elastic:
            return {}
        return {"drag": self.drag, "drag_law": self.drag_law, "restitution": self.restitution}

    def curve_physics(self, e) -> dict:
        """The physics keywords of experiment e (empty for the elastic model): a velocity
        scene's restitutions[e], the scene's ``physics()`` for the other kinds."""
        if self.kind != "velocity":
            return self.physics()
        r = self.restitutions[e]
        if r == 1.0 and self.drag == 0.0:
            return {}
        return {"drag": self.drag, "drag_law": self.drag_law, "restitution": r}

    def experiments(self) -> list[Experiment]:
        """The experiments of the run in their fixed order (it fixes the chunk numbering)."""
        if self.kind == "phase-space":
            return [Experiment("portrait", (), (), (), self.start_phi, self.start_v)]
        if self.kind == "velocity":
            names = [f"r={_num(r)}" for r in self.restitutions]
            return [Experiment(x, (x,), (), (), self.start_phi, self.start_v) for x in names]
        out = []
        many = len(self.hole_widths) > 1
        for w in self.hole_widths:
            tag = f"h={_num(w)}"
            los = tuple(_hole_lo(c, w) for c in self.hole_centres)
            if self.kind == "escape":
                for c, lo in zip(self.hole_centres, los, strict=True):
                    name = f"phi_c={_num(c)}" + (f"/{tag}" if many else "")
                    out.append(Experiment(name, (name,), (lo,), (w,), self.start_phi,
                                          self.start_v))
            else:
                for i, c in enumerate(self.hole_centres, start=1):
                    curves = tuple(
                        (f"{tag}/" if many else "") + _pair(i, j, len(self.hole_centres))
                        for j in range(1, len(self.hole_centres) + 1)
                    )
                    name = (f"{tag}/" if many else "") + f"from hole {i}"
                    box = (c - w / 2, c + w / 2)
                    out.append(Experiment(name, curves, los, (w,) * len(los), box, self.start_v))
        return out


NAME_DIGITS = 4  # significant digits of a number in a curve name


def _num(x):
    """Short text of a number for curve names: 1 not 1.0, pi to 4 digits."""
    return f"{x:.{NAME_DIGITS}g}"


def _pair(i, j, holes):
    """The transport curve from hole i to hole j: P12; with 10 holes or more P1-12 (P112 would
    also be hole 11 to hole 2)."""
    return f"P{i}{j}" if holes < 10 else f"P{i}-{j}"


def _hole_lo(centre, width):
    return (centre - width / 2) % TWO_PI


def builtin_scenes() -> dict[str, str]:
    """Names of the built-in scenes -> their TOML text."""
    folder = resources.files("reports.runs") / "builtin_scenes"
    return {
        p.name.removesuffix(".toml"): p.read_text(encoding="utf-8")
        for p in sorted(folder.iterdir(), key=lambda p: p.name)
        if p.name.endswith(".toml")
    }


def load_scene(name_or_path) -> Scene:
    """A built-in scene by name, or a TOML file by path; ValueError if missing or invalid."""
    builtin = builtin_scenes()
    key = str(name_or_path)
    if key in builtin:
        return parse_scene(builtin[key], origin=f"built-in scene {key!r}")
    path = Path(key)
    if not path.exists():
        names = ", ".join(builtin)
        raise ValueError(f"no scene {clip(repr(key))}: not a built-in ({names}) and not a file")
    return parse_scene(_scene_text(path), origin=str(path))


def _scene_text(path):
    """The text of a scene file: a regular file (a FIFO or a device could hang the reader) of
    at most ``rundir.MAX_SCENE_BYTES``, UTF-8 (a leading byte-order mark is dropped)."""
    try:
        data = read_input(path, MAX_SCENE_BYTES)
    except InputError as err:
        raise ValueError(f"scene file {err} (a scene is a small TOML file)") from None
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError:
        raise ValueError(f"scene file {path} is not UTF-8 text (is it a TOML file?)") from None


def parse_scene(text: str, origin: str = "scene") -> Scene:
    """Parse and validate TOML text; ValueError with ``origin: what is wrong`` (one line, the
    values it shows clipped)."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise ValueError(f"{origin}: not valid TOML: {clip(str(err))}") from None
    except RecursionError:
        raise ValueError(f"{origin}: not valid TOML: nested too deeply") from None
    except ValueError:  # an integer of more digits than Python converts
        raise ValueError(f"{origin}: {_long_integer(text)}") from None
    try:
        return _validate(data, text)
    except ValueError as err:
        raise ValueError(f"{origin}: {clip(str(err), MESSAGE_CHARACTERS)}") from None
    except RecursionError:  # a scene's values are never nested deeply
        raise ValueError(f"{origin}: a value is nested too deeply") from None


MESSAGE_CHARACTERS = 400  # of a validation message, the values it shows included


def _long_integer(text):
    """Where a TOML text holds an integer of more digits than Python converts: its line and
    key, for the message (tomllib names neither)."""
    limit = sys.get_int_max_str_digits() or 4300
    found = re.search(rf"\d[\d_]{{{limit},}}", text)
    if found is None:
        return "not valid TOML: a number it cannot convert"
    line = text.count("\n", 0, found.start()) + 1
    key = text[text.rfind("\n", 0, found.start()) + 1:found.start()].split("=")[0].strip()
    return (f"line {line} ({clip(key, 40)}): an integer of {len(found.group())} digits, beyond"
            " any value of a scene")


def _validate(data, text):
    _keys(data, _TOP, "scene")
    for table, allowed in _TABLES.items():
        if table in data:
            if not isinstance(data[table], dict):
                raise ValueError(f"[{table}] must be a table")
            _keys(data[table], allowed, f"[{table}]")
    name = _file_name(_string(data, "name"))
    kind = _string(data, "kind")
    if kind not in KINDS:
        raise ValueError(f"kind must be one of {', '.join(KINDS)}, got {kind!r}")
    eps = _real(data.get("eps"), "eps")
    particles = _integer(data.get("particles"), "particles", 1)
    seed = _integer(data.get("seed"), "seed", 0)
    chunk = _integer(data.get("chunk_size", 2**16), "chunk_size", 1)
    if chunk > MAX_CHUNK:
        raise ValueError(f"chunk_size must be <= {MAX_CHUNK}, got {chunk}")
    description = data.get("description", "")
    if not isinstance(description, str):
        raise ValueError("description must be a string")
    start, holes = data.get("start", {}), data.get("holes", {})
    horizon, record = data.get("horizon", {}), data.get("record", {})

    v_box = _box(start.get("v"), "start.v")
    if kind == "transport":
        if "phi" in start:
            raise ValueError("start.phi is not used by a transport scene: starts lie on hole i")
        phi_box = None
    else:
        phi_box = _box(start.get("phi"), "start.phi")
        if phi_box[1] - phi_box[0] > TWO_PI:
            raise ValueError(f"start.phi spans {phi_box[1] - phi_box[0]!r} > 2*pi")

    if kind in ("phase-space", "velocity"):
        if holes:
            raise ValueError(f"a {kind} scene has no [holes]")
        centres, widths = (), ()
    else:
        centres = _reals(holes.get("centres"), "holes.centres")
        widths = _reals(holes.get("widths"), "holes.widths")
        for w in widths:
            if not 0 < w < TWO_PI:
                raise ValueError(f"hole width must be in (0, 2*pi), got {w!r}")
        _check_size(kind, centres, widths)
        if kind == "transport":
            _check_disjoint(centres, widths)

    max_n, max_t = _horizon(horizon, kind)
    physics = _physics(data.get("physics", {}), kind)
    if kind in ("phase-space", "velocity"):
        if "clocks" in record:
            raise ValueError(f"a {kind} scene records no clocks (record.clocks)")
        clocks = []
    else:
        clocks = record.get("clocks", list(CLOCKS))
        if (not isinstance(clocks, list) or not clocks or len(set(clocks)) != len(clocks)
                or any(c not in CLOCKS for c in clocks)):
            raise ValueError(
                f"record.clocks must be a non-empty list of {CLOCKS}, got {clocks!r}")
    bins = _integer(record.get("bins_per_decade", 20), "record.bins_per_decade", 1)
    if bins > 200:
        raise ValueError(f"record.bins_per_decade must be <= 200, got {bins}")
    samples = _integer(record.get("verify_samples", 1000), "record.verify_samples", 1)
    portrait = {}
    if kind == "phase-space":
        portrait["phi_bins"] = _integer(record.get("phi_bins", 720), "record.phi_bins", 1)
        portrait["v_bins"] = _integer(record.get("v_bins", 480), "record.v_bins", 1)
        portrait["v_range"] = _box(record.get("v_range", [0.0, 12.0]), "record.v_range")
        if portrait["phi_bins"] * portrait["v_bins"] > 4_000_000:
            raise ValueError("record.phi_bins * record.v_bins must be <= 4e6")
    elif any(k in record for k in ("phi_bins", "v_bins", "v_range")):
        raise ValueError("record.phi_bins, v_bins and v_range belong to phase-space scenes")

    scene = Scene(
        name=name, kind=kind, eps=eps, particles=particles, seed=seed, start_phi=phi_box,
        start_v=v_box, hole_centres=centres, hole_widths=widths, max_collisions=max_n,
        max_time=max_t, clocks=tuple(c for c in CLOCKS if c in clocks), bins_per_decade=bins,
        verify_samples=samples, chunk_size=chunk, description=description, source=text,
        **physics, **portrait, **_records(start, record, kind, clocks),
    )
    if kind == "phase-space" and not scene.elastic:
        raise ValueError(f"a phase-space scene with [physics] (restitution={scene.restitution!r},"
                         f" drag={scene.drag!r}) needs a dissipative portrait kernel, which"
                         " fastpath does not have; escape and transport scenes take [physics]")
    _check_distinct(scene)
    _check_drag(scene)
    for exp in scene.experiments():
        _check_departures(exp, eps)
        if kind == "escape":
            _check_outside(exp)
    return scene


def _records(start, record, kind, clocks):
    """{density, joint}: the law of the starts (``[start] density``) and whether the run
    records the joint histogram of (n, t) (``[record] joint``); the defaults, uniform starts
    and no joint record, leave a scene as it was without these keys."""
    density = start.get("density", "uniform")
    if not isinstance(density, str) or density not in DENSITIES:
        raise ValueError(f"start.density must be one of {', '.join(DENSITIES)}, got"
                         f" {density!r}")
    joint = record.get("joint", False)
    if not isinstance(joint, bool):
        raise ValueError(f"record.joint must be true or false, got {joint!r}")
    if joint and kind not in ("escape", "transport"):
        raise ValueError(f"record.joint belongs to escape and transport scenes, not {kind}")
    if joint and tuple(sorted(clocks)) != tuple(sorted(CLOCKS)):
        raise ValueError(f"record.joint needs both clocks (record.clocks ="
                         f" {list(CLOCKS)!r}), got {clocks!r}")
    return {"density": density, "joint": joint}


def _physics(table, kind):
    """[physics] -> {restitution, drag, drag_law, restitutions}; the defaults are the elastic
    model. A velocity scene takes a list of restitutions (one curve each; ``restitution`` is
    then the smallest, which decides ``Scene.elastic`` and ``Scene.carries``)."""
    value = table.get("restitution", 1.0)
    if isinstance(value, list) and kind == "velocity":
        values = _reals(value, "physics.restitution")
        if len(set(values)) != len(values):
            raise ValueError(f"physics.restitution lists a value twice: {value!r}")
    elif isinstance(value, list):
        raise ValueError(f"physics.restitution must be a number (a list only in velocity"
                         f" scenes), got restitution={value!r}")
    else:
        values = (_real(value, "physics.restitution"),)
    for restitution in values:
        if not 0.0 < restitution <= 1.0:
            raise ValueError(f"physics.restitution must be in (0, 1], got"
                             f" restitution={restitution!r}")
    drag = _real(table.get("drag", 0.0), "physics.drag")
    if drag < 0.0:
        raise ValueError(f"physics.drag must be >= 0, got drag={drag!r}")
    law = table.get("drag_law", "linear")
    if law not in DRAG_LAWS:
        raise ValueError(f"physics.drag_law must be one of {', '.join(DRAG_LAWS)},"
                         f" got drag_law={law!r}")
    return {"restitution": min(values), "drag": drag, "drag_law": law,
            "restitutions": values if kind == "velocity" else ()}


def _keys(table, allowed, where):
    unknown = sorted(set(table) - allowed)
    if unknown:
        raise ValueError(
            f"unknown key(s) in {where}: {', '.join(unknown)}"
            f" (allowed: {', '.join(sorted(allowed))})"
        )


def _string(data, key):
    value = data.get(key)
    if not isinstance(value, str) or not value:
        raise ValueError(f"{key} must be a non-empty string, got {value!r}")
    return value


NAME_PATTERN = re.compile(r"[A-Za-z0-9][A-Za-z0-9._+=-]{0,99}")


def _file_name(name):
    """The scene's name names its run directory (runs/NAME): a plain file name, so that a
    scene file from anyone cannot make a run write outside the output folder."""
    if not NAME_PATTERN.fullmatch(name):
        raise ValueError(f"name must be a plain file name (letters, digits and . _ + = -, not"
                         f" starting with . or -, at most 100 characters), got {name!r}")
    return name


def _real(value, name):
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ValueError(f"{name} must be a number, got {value!r}")
    if not math.isfinite(value):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return float(value)


def _integer(value, name, minimum):
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise ValueError(f"{name} must be an integer, got {value!r}")
    if value < minimum:
        raise ValueError(f"{name} must be >= {minimum}, got {value}")
    return int(value)


def _reals(value, name):
    if not isinstance(value, list) or not value:
        raise ValueError(f"{name} must be a non-empty list of numbers, got {value!r}")
    return tuple(_real(x, name) for x in value)


def _box(value, name):
    if not isinstance(value, list) or len(value) != 2:
        raise ValueError(f"{name} must be [low, high], got {value!r}")
    lo, hi = _real(value[0], name), _real(value[1], name)
    if not lo < hi:
        raise ValueError(f"{name} = [{lo!r}, {hi!r}] is empty: need low < high")
    return (lo, hi)


def _horizon(horizon, kind):
    if "collisions" not in horizon and "time" not in horizon:
        raise ValueError("[horizon] needs collisions and/or time")
    max_n = max_t = None
    if "collisions" in horizon:
        max_n = _integer(horizon["collisions"], "horizon.collisions", 1)
        if max_n > 10**8:
            raise ValueError(f"horizon.collisions must be <= 1e8 (the bins), got {max_n}")
    if "time" in horizon:
        if kind in ("phase-space", "velocity"):
            raise ValueError(f"a {kind} scene's horizon is horizon.collisions only")
        max_t = _real(horizon["time"], "horizon.time")
        if not 0 < max_t <= 1e8:
            raise ValueError(f"horizon.time must be in (0, 1e8] (the bins), got {max_t!r}")
    if kind in ("phase-space", "velocity") and max_n is None:
        raise ValueError(f"a {kind} scene needs horizon.collisions")
    return max_n, max_t


def _arcs_overlap(lo1, w1, lo2, w2):
    """Whether the arcs [lo1, lo1+w1) and [lo2, lo2+w2) mod 2*pi intersect."""
    return (lo2 - lo1) % TWO_PI < w1 or (lo1 - lo2) % TWO_PI < w2


def _check_disjoint(centres, widths):
    for w in widths:
        for a in range(len(centres)):
            for b in range(a + 1, len(centres)):
                if _arcs_overlap(_hole_lo(centres[a], w), w, _hole_lo(centres[b], w), w):
                    raise ValueError(
                        f"holes centred at {centres[a]!r} and {centres[b]!r} with width {w!r}"
                        " overlap"
                    )


def _sin_range(a, b):
    """(min, max) of sin on [a, b]."""
    vals = [math.sin(a), math.sin(b)]
    for peak, value in ((math.pi / 2, 1.0), (3 * math.pi / 2, -1.0)):
        k = math.ceil((a - peak) / TWO_PI)
        if peak + k * TWO_PI <= b:
            vals.append(value)
    return min(vals), max(vals)


def _check_departures(exp, eps):
    """Every start must leave the plate: w0 = v + eps*sin(phi) > 0 on the whole box."""
    s_min, s_max = _sin_range(*exp.phi)
    worst = exp.v[0] + min(eps * s_min, eps * s_max)
    if not worst > 0:
        raise ValueError(
            f"starts of {exp.name!r} include non-departures: min of w0 = v + eps*sin(phi) over"
            f" phi in {list(exp.phi)}, v in {list(exp.v)} is {worst!r} <= 0"
        )


def _check_outside(exp):
    """An escape start box must not overlap its hole (that is a transport problem)."""
    width = exp.phi[1] - exp.phi[0]
    for lo, w in zip(exp.hole_lo, exp.hole_width, strict=True):
        if _arcs_overlap(exp.phi[0] % TWO_PI, width, lo, w):
            raise ValueError(
                f"the start box phi in {list(exp.phi)} overlaps the hole of {exp.name!r};"
                " use a transport scene for starts on a hole"
            )


# ------------------------------------------------------------------ distinct experiments


def _check_distinct(scene):
    """Every experiment and every curve of the scene has a name of its own.

    The experiments are the product holes.centres x holes.widths (each centre with each
    width; transport: each width with all the centres), or one per restitution of a velocity
    scene, and a curve is named by the values that made it. A value listed twice (0.2 and
    0.20000000000000001 are one float; 0 and -0.0, and a centre and the same centre plus 2*pi,
    are one hole) would run one experiment twice, and values that differ only beyond the
    NAME_DIGITS significant digits a name shows would give two experiments one name: their
    counts would merge in counts.csv and survival.csv. Both are refused, naming the values;
    then, whatever made them, two experiments or two curves of one name."""
    lists = {"holes.centres": scene.hole_centres, "holes.widths": scene.hole_widths,
             "physics.restitution": scene.restitutions}
    for key, values in lists.items():
        hint = _PRODUCT if key.startswith("holes") else "one curve per restitution"
        for first, value in _pairs_alike(values, key == "holes.centres"):
            if repr(first) == repr(value):
                raise ValueError(f"{key} lists {value!r} twice ({hint})")
            if key == "holes.centres" and _same_phase(first, value):
                raise ValueError(f"{key} {first!r} and {value!r} are the same hole (mod"
                                 f" 2*pi) ({hint})")
            if first == value:
                raise ValueError(f"{key} {first!r} and {value!r} are the same value ({hint})")
            raise ValueError(f"{key} {first!r} and {value!r} both show as {_num(value)} in"
                             f" curve names ({NAME_DIGITS} significant digits): make them"
                             f" differ within {NAME_DIGITS} digits")
    experiments = scene.experiments()
    for what, names in (("experiments", [x.name for x in experiments]),
                        ("curves", [c for x in experiments for c in x.curves])):
        twice = sorted({n for n in names if names.count(n) > 1})
        if twice:
            raise ValueError(f"two {what} are named {twice[0]!r}: each needs a name of its own")


_PRODUCT = ("the experiments are holes.centres x holes.widths, each centre with each width:"
            " list each value once")


def _pairs_alike(values, phases):
    """The first pair of values (earlier, later) that are equal, print alike in a name, or
    (``phases``) are one point mod 2*pi; none if there is no such pair. Sorted, so the values
    of a long list are compared with their neighbours only."""
    def alike(a, b):
        return a == b or _num(a) == _num(b) or (phases and _same_phase(a, b))

    order = {}
    for i, value in enumerate(values):
        order.setdefault(_num(value), []).append(i)
    found = [(ii[0], ii[1]) for ii in order.values() if len(ii) > 1]
    if phases and len(values) > 1:
        ranked = sorted(range(len(values)), key=lambda i: values[i] % TWO_PI)
        found += [(min(a, b), max(a, b)) for a, b in zip(ranked, ranked[1:] + ranked[:1],
                                                          strict=True)
                  if a != b and alike(values[a], values[b])]
    if not found:
        return []
    i, j = min(found, key=lambda ij: (ij[1], ij[0]))
    return [(values[i], values[j])]


MAX_CURVES = 10_000  # curves of a scene: counts.csv, survival.csv and the manifest hold each


def _check_size(kind, centres, widths):
    """At most MAX_CURVES curves: centres x widths (escape), widths x centres**2 (transport:
    every hole to every hole), before anything is built from them."""
    curves = len(centres) * len(widths) * (len(centres) if kind == "transport" else 1)
    if curves > MAX_CURVES:
        raise ValueError(f"{len(centres)} holes.centres and {len(widths)} holes.widths make"
                         f" {curves} curves, more than the {MAX_CURVES} a run holds")


def _same_phase(a, b):
    """Whether phases a and b are one point mod 2*pi, up to the rounding of reducing them: a
    few ulps of the larger of |a|, |b| and 2*pi."""
    gap = (a - b) % TWO_PI
    return min(gap, TWO_PI - gap) <= 4 * math.ulp(max(abs(a), abs(b), TWO_PI))


# ------------------------------------------------------------------ what the model can run

PHASE_ERROR = 4 * math.ulp(TWO_PI)  # a step's bound on the error of its phase (3.6e-15)


def _check_drag(scene):
    """The drag must not stop a particle faster than one step can resolve a flight.

    Drag k slows a particle of speed V at the rate k (linear, V' = -k*V) or k*V (quadratic,
    V' = -k*V**2): it stops it within 1/rate. Once the rate is large the particle rides the
    plate in hops of about that duration (flights of order 1/k). A step's phase is good to
    PHASE_ERROR = 4 ulps of 2*pi (docs/fastpath.md), so a flight shorter than that is below the
    resolution of the collision map, and the flight solvers' error bounds no longer separate
    its root from zero (their rounding bound is relative to a phase of order 1): float64 cannot
    run such a scene. So 1/rate >= PHASE_ERROR at the scene's largest speed V, the fastest
    start (|v| at either end of start.v) plus the 2*|eps| an impact can add; for the
    quadratic law that bounds k*V."""
    if scene.drag == 0.0:
        return
    speed = max(abs(scene.start_v[0]), abs(scene.start_v[1])) + 2.0 * abs(scene.eps)
    largest = 1.0 / PHASE_ERROR if scene.drag_law == "linear" else 1.0 / (PHASE_ERROR * speed)
    if scene.drag <= largest:
        return
    rate = scene.drag if scene.drag_law == "linear" else scene.drag * speed
    raise ValueError(
        f"physics.drag = {scene.drag:.6g} ({scene.drag_law}) stops a particle of speed"
        f" {speed:.3g} (the fastest start plus 2*|eps|) within {1.0 / rate:.3g} time units,"
        f" shorter than the {PHASE_ERROR:.2g} a step resolves: float64 cannot run these"
        f" flights; drag must be <= {largest:.3g} here")
