"""manifest.json and provenance.json of a run directory: what each holds, their schemas, the
one place where they are read (and validated) and where the manifest is built.

manifest.json states what the run claims about its outputs, and nothing else. ``build`` makes
it from the plan (scene.toml, seed, particles) and the merged counts (the checkpoint), so
``bouncer verify`` (``reports.runs.recheck``) audits every field by building it again from
what produced the outputs and comparing field by field:

    status           partial, complete or failed (the audit wants complete)
    scene            name, kind, eps, horizon, physics: a copy of scene.toml, compared with it
    seed             the random seed: the sample rows are replayed from the starts drawn from
                     it (``reports.runs.replay``)
    particles        starts per curve: every curve's escapes + censored + stuck must add up
                     to it (counts.csv, the checkpoint); particles_total = particles x curves
    chunk_size, chunks, chunks_done   the plan's chunking and the checkpoint's finished chunks
    collisions       the checkpoint's total
    verification     the summary of the verified sample, from the checkpoint's rows and
                     recomputed by verify
    curves           per curve the particles done, escaped, censored and stuck (velocity
                     scenes: moving, stuck, mean velocity), from the checkpoint
    bins             the histogram bins, as the plan builds them for counts.csv
    survival_band    the band of survival.csv (``survival.BAND``)
    hashes           SHA-256 of every other file of the run directory
    failure          (failed runs only) why the run stopped

How and when the run was made (package versions, the git commit, threads, the cluster,
timestamps, compile and compute time, the rate) does not follow from the outputs and cannot
be audited: it is provenance.json, a record whose hash the manifest holds like any output's.

``SCHEMA`` and ``PROVENANCE_SCHEMA`` are JSON Schemas (validated with ``jsonschema``; integers
must be JSON integers, not 3.0 or "3"). ``load_manifest`` and ``load_provenance`` are the only
readers: a file that is not valid JSON of that shape is a ``ValueError`` with one line naming
the file and the field.
"""

from __future__ import annotations

import json
from pathlib import Path

from jsonschema import Draft202012Validator, validators
from jsonschema.exceptions import best_match

from reports.runs.chunk import OVERSTEP_TOLERANCE, VERIFY_DPS
from reports.runs.echo import clip, integer
from reports.runs.joint_file import JOINT_FILE
from reports.runs.plan import COLLISION_DECADES, TIME_DECADES, TIME_FIRST
from reports.runs.rundir import (
    CARRIED_COLUMNS,
    CHECKPOINT,
    MANIFEST,
    MAX_JSON_BYTES,
    PROVENANCE,
    SAMPLE_COLUMNS,
    read_input_text,
    sample_columns,
)
from reports.runs.scenes import DENSITIES, DRAG_LAWS, KINDS
from reports.runs.survival import BAND

STATUSES = ("partial", "complete", "failed")
OUTPUTS = {"phase-space": ("portrait.npy",), "velocity": ("velocity.csv",)}
SURVIVAL_OUTPUTS = ("survival.csv", "counts.csv")
ERROR_UNIT = "condition number x unit roundoff (kappa * 2**-53)"

# the fields built from the plan alone, and those that need the merged counts (the checkpoint)
PLAN_FIELDS = ("scene", "seed", "particles", "particles_total", "chunk_size", "chunks", "bins",
               "survival_band")
COUNT_FIELDS = ("chunks_done", "collisions", "verification", "curves")


def output_files(scene):
    """The result files a run of ``scene`` writes (besides sample.csv)."""
    return OUTPUTS.get(scene.kind, SURVIVAL_OUTPUTS) + record_files(scene)


def record_files(scene):
    """The files of what a scene asks to record besides its histograms: joint.csv
    (``[record] joint``, ``reports.runs.joint_file``)."""
    return (JOINT_FILE,) if scene.joint else ()


def hashed_files(scene):
    """Every file whose SHA-256 a complete run's manifest records."""
    return ("scene.toml", "sample.csv", CHECKPOINT, PROVENANCE, *output_files(scene))


# ------------------------------------------------------------------------------ the schemas

def _obj(required, optional=None, **extra):
    """A JSON Schema object with exactly these properties (``optional`` may be left out)."""
    optional = optional or {}
    return {"type": "object", "properties": {**required, **optional},
            "required": list(required), "additionalProperties": False, **extra}


_INT = {"type": "integer", "minimum": 0}
_POSITIVE_INT = {"type": "integer", "minimum": 1}
_NUMBER = {"type": "number"}
_SECONDS = {"type": ["number", "null"], "minimum": 0}
_TEXT = {"type": "string"}
_NAME = {"type": "string", "minLength": 1}
_PHYSICS = _obj({"drag": {"type": "number", "minimum": 0}, "drag_law": {"enum": list(DRAG_LAWS)},
                 "restitution": {"type": "number", "exclusiveMinimum": 0, "maximum": 1}})
_SURVIVAL_CURVE = _obj({"particles_done": _INT, "censored": _INT, "stuck": _INT,
                        "escaped": {"type": "object", "additionalProperties": _INT}})
_VELOCITY_CURVE = _obj({"particles_done": _INT, "moving": _INT, "stuck": _INT,
                        "mean_v_at_horizon": {"type": ["number", "null"]}})
_ALL_FILES = sorted({"scene.toml", "sample.csv", CHECKPOINT, PROVENANCE, *SURVIVAL_OUTPUTS,
                     *(name for names in OUTPUTS.values() for name in names), JOINT_FILE})

# the manifest's scene fields of the start density and the records (``_scene_records``): only
# where a scene departs from the defaults, so a manifest of a scene without them is unchanged
_RECORD_FIELDS = {"density": {"enum": [d for d in DENSITIES if d != "uniform"]},
                  "joint": {"const": True}}

SCHEMA = _obj({
    "status": {"enum": list(STATUSES)},
    "scene": _obj(
        {"name": _NAME, "kind": {"enum": list(KINDS)}, "file": {"const": "scene.toml"},
         "eps": _NUMBER,
         "horizon": _obj({"collisions": {"type": ["integer", "null"], "minimum": 1},
                          "time": {"type": ["number", "null"], "exclusiveMinimum": 0}})},
        {"physics": _PHYSICS,
         "physics_per_curve": {"type": "object",
                               "additionalProperties": {"anyOf": [_PHYSICS, _obj({})]}},
         **_RECORD_FIELDS}),
    "seed": _INT,
    "particles": _POSITIVE_INT,
    "particles_total": _POSITIVE_INT,
    "chunk_size": _POSITIVE_INT,
    "chunks": _POSITIVE_INT,
    "chunks_done": _INT,
    "collisions": _INT,
    "verification": _obj(
        {"sampled": _INT, "worst_error": {"type": "number", "minimum": 0},
         "uncertain_settled": _INT, "overstepped": _INT, "error_unit": _TEXT,
         "overstep_tolerance": _NUMBER, "verify_dps": _POSITIVE_INT},
        {"worst_at": {"type": "object", "additionalProperties": _NUMBER,
                      "propertyNames": {"enum": [*SAMPLE_COLUMNS, *CARRIED_COLUMNS]}}}),
    "curves": {"type": "object", "minProperties": 1,
               "additionalProperties": {"anyOf": [_SURVIVAL_CURVE, _VELOCITY_CURVE]}},
    "bins": _obj({
        "collisions": _obj({"first": _NUMBER, "decades": _POSITIVE_INT,
                            "per_decade": _POSITIVE_INT, "integer": {"type": "boolean"}}),
        "time": _obj({"first": _NUMBER, "decades": _POSITIVE_INT, "per_decade": _POSITIVE_INT,
                      "below_first": {"type": "array", "items": _NUMBER, "minItems": 2,
                                      "maxItems": 2}})}),
    "survival_band": _TEXT,
    "hashes": {"type": "object", "propertyNames": {"enum": _ALL_FILES},
               "additionalProperties": {"type": "string", "pattern": "^[0-9a-f]{64}$"}},
}, {"failure": _TEXT})

PROVENANCE_SCHEMA = _obj({
    "versions": {"type": "object", "additionalProperties": {"type": ["string", "null"]}},
    "git": {"anyOf": [{"type": "null"},
                      _obj({"commit": _TEXT, "dirty": {"type": "boolean"}},
                           {"changed": {"type": "array", "items": _TEXT}})]},
    "threads": {"type": ["integer", "null"], "minimum": 1},
    "session": _obj({"scheduler": {"type": ["string", "null"]},
                     "workers": {"type": ["integer", "null"], "minimum": 0},
                     "worker_threads": {"type": ["integer", "null"], "minimum": 0},
                     "chunks_computed": _INT}),
    "started": _TEXT,
    "updated": _TEXT,
    "finished": {"type": ["string", "null"]},
    "compile_s": _SECONDS,
    "compute_s": _SECONDS,
    "collisions_per_s": _SECONDS,
})


def _is_integer(checker, value):
    return isinstance(value, int) and not isinstance(value, bool)


def _is_number(checker, value):
    return isinstance(value, int | float) and not isinstance(value, bool)


# JSON integers only: 3.0, "3" and true are not integers (jsonschema's default takes 3.0)
_Validator = validators.extend(
    Draft202012Validator,
    type_checker=Draft202012Validator.TYPE_CHECKER.redefine_many(
        {"integer": _is_integer, "number": _is_number}))

MAX_MESSAGE = 200  # characters of the schema's message (which shows the offending value)


def check(obj, schema, where):
    """ValueError (one line: ``where: field a.b: what is wrong``) unless ``obj`` fits
    ``schema``; the field's path and the message are clipped."""
    error = best_match(_Validator(schema).iter_errors(obj))
    if error is None:
        return
    field = clip(".".join(map(str, error.absolute_path)))
    message = clip(error.message, MAX_MESSAGE)
    raise ValueError(f"{where}: {'field ' + field + ': ' if field else ''}{message}"
                     .replace("\n", " "))


def _json_of(path):
    """The JSON value in ``path``; ValueError naming the file if it is not a regular file of
    at most ``MAX_JSON_BYTES`` holding UTF-8 JSON (an integer of more digits than Python
    converts, JSON nested too deeply for the parser included)."""
    path = Path(path)
    try:
        text = read_input_text(path, MAX_JSON_BYTES)
    except FileNotFoundError:
        raise ValueError(f"{path}: no such file") from None
    try:
        return json.loads(text, parse_int=integer)
    except json.JSONDecodeError as err:
        raise ValueError(f"{path}: not valid JSON ({err})") from None
    except RecursionError:
        raise ValueError(f"{path}: not valid JSON (nested too deeply)") from None


def load_manifest(path):
    """The manifest at ``path`` (a manifest.json or the run directory holding it), validated
    against ``SCHEMA``; ValueError with one line otherwise."""
    path = Path(path)
    if path.is_dir() and path.name != MANIFEST:
        path = path / MANIFEST
    manifest = _json_of(path)
    check(manifest, SCHEMA, path)
    return manifest


def load_provenance(run_dir):
    """provenance.json of ``run_dir``, validated against ``PROVENANCE_SCHEMA``."""
    path = Path(run_dir) / PROVENANCE
    record = _json_of(path)
    check(record, PROVENANCE_SCHEMA, path)
    return record


# ------------------------------------------------------------------------- the manifest


def verification_summary(tally, scene):
    """The manifest's ``verification``: the verified sample's size and worst error."""
    worst = max(tally.samples, key=lambda r: r[10], default=None)
    out = {"sampled": len(tally.samples),
           "worst_error": worst[10] if worst else 0.0,
           "uncertain_settled": tally.settled,
           "overstepped": 0,
           "error_unit": ERROR_UNIT,
           "overstep_tolerance": OVERSTEP_TOLERANCE,
           "verify_dps": VERIFY_DPS}
    if worst:
        out["worst_at"] = dict(zip(sample_columns(scene), worst, strict=True))
    return out


def velocity_curve(plan, tally, e):
    """The manifest's figures of velocity curve e: particles done, and at the horizon the
    particles moving, stuck and their mean velocity (None if none moves)."""
    moving = int(tally.moving[e, -1])
    return {"particles_done": tally.finished.particles_done(plan, e), "moving": moving,
            "stuck": int(tally.stuck_at[e, -1]),
            "mean_v_at_horizon": float(tally.sum_v[e, -1] / moving) if moving else None}


def _curves(plan, tally):
    sc, curves = plan.scene, {}
    for e, exp in enumerate(plan.experiments):
        if sc.kind == "velocity":
            curves[exp.name] = velocity_curve(plan, tally, e)
            continue
        # (a phase-space scene records no clock: its curve's figures are the zeros of esc_t,
        # cens_t and stuck_t)
        clock = "esc_n" if "collisions" in sc.clocks else "esc_t"
        esc = getattr(tally, clock)[e]
        cens = tally.cens_n[e] if clock == "esc_n" else tally.cens_t[e]
        stuck = tally.stuck_n[e] if clock == "esc_n" else tally.stuck_t[e]
        curves[exp.name] = {"particles_done": tally.finished.particles_done(plan, e),
                            "censored": int(cens.sum()), "stuck": int(stuck.sum()),
                            "escaped": {c: int(esc[j].sum()) for j, c in enumerate(exp.curves)}}
    return curves


def _scene(plan):
    sc = plan.scene
    out = {"name": sc.name, "kind": sc.kind, "file": "scene.toml", "eps": sc.eps,
           "horizon": {"collisions": sc.max_collisions, "time": sc.max_time}}
    if sc.kind == "velocity":
        out["physics_per_curve"] = {x.name: sc.curve_physics(e)
                                    for e, x in enumerate(plan.experiments)}
    elif not sc.elastic:
        out["physics"] = sc.physics()
    out.update(_scene_records(sc))
    return out


def _scene_records(scene):
    """The manifest's scene fields of a non-uniform start density and of a joint record."""
    out = {}
    if scene.density != "uniform":
        out["density"] = scene.density
    if scene.joint:
        out["joint"] = True
    return out


def bins(plan):
    """The manifest's ``bins``: how ``plan.make_plan`` builds the histogram edges."""
    per = plan.scene.bins_per_decade
    return {"collisions": {"first": 1, "decades": COLLISION_DECADES, "per_decade": per,
                           "integer": True},
            "time": {"first": TIME_FIRST, "decades": TIME_DECADES, "per_decade": per,
                     "below_first": [0.0, TIME_FIRST]}}


def build(plan, tally, status, hashes, verification=None, failure=None):
    """The manifest of the run of ``plan`` whose merged counts are ``tally``; ``hashes``: the
    SHA-256 of the files written so far; ``verification`` replaces the summary of the
    sample (a failed run records its overstepped rows)."""
    manifest = {
        "status": status,
        "scene": _scene(plan),
        "seed": plan.seed,
        "particles": plan.particles,
        "particles_total": plan.particles_total,
        "chunk_size": plan.scene.chunk_size,
        "chunks": plan.n_chunks,
        "chunks_done": len(tally.finished),
        "collisions": tally.collisions,
        "verification": verification or verification_summary(tally, plan.scene),
        "curves": _curves(plan, tally),
        "bins": bins(plan),
        "survival_band": BAND,
        "hashes": dict(sorted(hashes.items())),
    }
    if failure:
        manifest["failure"] = failure
    return manifest


def differences(recorded, expected, field):
    """[(field path, recorded value, expected value)] where they differ: dicts key by key,
    other values by type and value (3 is not 3.0, absent is None)."""
    if isinstance(recorded, dict) and isinstance(expected, dict):
        out = []
        for key in sorted(set(recorded) | set(expected), key=str):
            out += differences(recorded.get(key), expected.get(key), f"{field}.{key}")
        return out
    if type(recorded) is not type(expected) or recorded != expected:
        return [(field, recorded, expected)]
    return []
