"""Hypothesis profiles, and the figures the suite measured in pytest's terminal summary.

Profiles: ``default`` is quick, ``ci`` (HYPOTHESIS_PROFILE=ci, .ci/run) heavier. deadline=None
everywhere: the first call of a numba kernel compiles it.

Figures (``fastpath_figures``): printed after the run. Under pytest-xdist each worker sends its
figures to the controller when it finishes; counters are summed, other figures taken as given.
"""

import os

import pytest
from fastpath_figures import COUNTERS, FIGURES
from hypothesis import HealthCheck, settings

settings.register_profile(
    "default", max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow]
)
settings.register_profile(
    "ci", max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow],
    print_blob=True,
)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "default"))


def pytest_sessionfinish(session):
    output = getattr(session.config, "workeroutput", None)
    if output is not None:  # an xdist worker: hand the figures over (plain types only)
        output["fastpath_counters"] = {name: int(FIGURES[name]) for name in COUNTERS}
        output["fastpath_figures"] = {name: str(value) for name, value in FIGURES.items()
                                      if name not in COUNTERS}


@pytest.hookimpl(optionalhook=True)
def pytest_testnodedown(node, error):
    """xdist's controller: collect a finished worker's figures."""
    output = getattr(node, "workeroutput", {})
    for name, count in output.get("fastpath_counters", {}).items():
        COUNTERS.add(name)
        FIGURES[name] = FIGURES.get(name, 0) + count
    FIGURES.update(output.get("fastpath_figures", {}))


def pytest_terminal_summary(terminalreporter):
    if not FIGURES:
        return
    terminalreporter.section("fastpath figures")
    for name in sorted(FIGURES):
        terminalreporter.write_line(f"{name}: {FIGURES[name]}")
