"""Fixtures shared by the run tests: the tiny transport run of ``scene_texts.TINY`` (built once
per module) and a fresh copy of it per test, to tamper with."""

import shutil
from pathlib import Path

import pytest
from scene_texts import TINY

from reports.runs import driver
from reports.runs.scenes import parse_scene


@pytest.fixture(scope="module")
def tiny_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("tiny") / "run"
    driver.run(parse_scene(TINY), out, progress=False)
    return out


@pytest.fixture
def run(tiny_run, tmp_path):
    return Path(shutil.copytree(tiny_run, tmp_path / "run"))
