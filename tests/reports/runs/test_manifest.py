"""manifest.json and provenance.json: the writer writes exactly ``manifest.build``; one schema
refuses every other shape with one line naming the file and the field; fields compare by type
and value."""

import json

import pytest
from scene_texts import TINY

from reports.runs import driver
from reports.runs.counts import Tally
from reports.runs.manifest import (
    PROVENANCE_SCHEMA,
    SCHEMA,
    build,
    check,
    differences,
    load_manifest,
    load_provenance,
)
from reports.runs.plan import make_plan
from reports.runs.scenes import parse_scene


def test_the_written_manifest_is_the_one_built_from_the_checkpoint(run):
    manifest = json.loads((run / "manifest.json").read_text())
    plan = make_plan(parse_scene(TINY))
    tally = Tally.load(run / "checkpoint.npz")
    assert build(plan, tally, "complete", manifest["hashes"]) == manifest
    assert load_manifest(run) == manifest == load_manifest(run / "manifest.json")
    record = load_provenance(run)
    assert set(record) == set(PROVENANCE_SCHEMA["properties"])
    assert not set(record) & set(manifest)  # nothing is stated twice


@pytest.mark.parametrize("edit, message", [
    (lambda m: m.__setitem__("particles", True), "field particles: True is not of type"),
    (lambda m: m.__setitem__("seed", 3.0), "field seed: 3.0 is not of type 'integer'"),
    (lambda m: m.__setitem__("seed", -1), "field seed: -1 is less than the minimum of 0"),
    (lambda m: m["scene"].__setitem__("eps", "0.6"), "field scene.eps: '0.6' is not of type"),
    (lambda m: m["scene"].__setitem__("kind", "orbit"), "field scene.kind: 'orbit' is not one"),
    (lambda m: m.__setitem__("status", "done"), "field status: 'done' is not one of"),
    (lambda m: m["hashes"].__setitem__("counts.csv", "00"), "field hashes.counts.csv: '00'"),
    (lambda m: m.__setitem__("wall_time_s", 3.0), "('wall_time_s' was unexpected)"),
    (lambda m: m.pop("bins"), "'bins' is a required property"),
    (lambda m: m["curves"].clear(), "field curves: {} should be non-empty"),
])
def test_the_schema_names_the_file_and_the_field(run, edit, message):
    manifest = json.loads((run / "manifest.json").read_text())
    edit(manifest)
    (run / "manifest.json").write_text(json.dumps(manifest))
    with pytest.raises(ValueError) as err:
        load_manifest(run)
    assert str(err.value).startswith(f"{run / 'manifest.json'}: ")
    assert message in str(err.value) and "\n" not in str(err.value)


def test_a_long_value_is_cut_in_the_message():
    """The message keeps its start and its end (what is wrong) and says how much was cut."""
    with pytest.raises(ValueError) as err:
        check(list(range(10_000)), SCHEMA, "m.json")
    text = str(err.value)
    assert len(text) < 300 and " characters) ..." in text
    assert text.startswith("m.json: [0, 1, 2") and text.endswith("is not of type 'object'")


def test_an_integer_of_thousands_of_digits_names_its_file_and_field(run):
    """Python refuses to convert integers of more than 4300 digits; the reader keeps such a
    literal as text, so the schema names the field, and the message clips it."""
    text = (run / "manifest.json").read_text()
    (run / "manifest.json").write_text(text.replace('"particles": 200', '"particles": '
                                                    + "7" * 5000))
    with pytest.raises(ValueError) as err:
        load_manifest(run)
    line = str(err.value)
    assert line.startswith(f"{run / 'manifest.json'}: field particles: an integer of 5000"
                           " digits") and len(line) < 300


def test_differences_compare_type_and_value():
    assert differences({"a": 1, "b": {"c": 2.0}}, {"a": 1, "b": {"c": 2.0}}, "m") == []
    assert differences({"a": 1.0}, {"a": 1}, "m") == [("m.a", 1.0, 1)]
    assert differences({"a": True}, {"a": 1}, "m") == [("m.a", True, 1)]
    assert differences({}, {"a": {"b": 1}}, "m") == [("m.a", None, {"b": 1})]
    assert differences({"x": 1}, {}, "m") == [("m.x", 1, None)]
    assert differences(float("nan"), float("nan"), "w") != []


def test_a_provenance_record_of_another_shape_is_refused(run):
    (run / "provenance.json").write_text(json.dumps({"git": "abc"}))
    with pytest.raises(ValueError, match="provenance.json: "):
        load_provenance(run)


def test_the_manifest_of_a_failed_run_keeps_its_failure(tmp_path, monkeypatch):
    from reports.runs import chunk

    real = chunk.check_sample
    monkeypatch.setattr(chunk, "check_sample", lambda *a: (*real(*a)[:2], True))
    with pytest.raises(driver.RunFailed):
        driver.run(parse_scene(TINY), tmp_path / "r", progress=False)
    manifest = load_manifest(tmp_path / "r")
    assert manifest["status"] == "failed" and manifest["failure"].startswith("OVERSTEP")
    assert manifest["verification"]["overstepped"] > 0
