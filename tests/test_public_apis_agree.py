"""The two public APIs speak alike: ``fastpath`` and ``verify`` take the state positionally and
everything after it by keyword, and a function of the same name in both takes its keywords under
the same names with the same defaults (read from ``inspect.signature``, so the test follows the
code)."""

import inspect

import pytest

import fastpath
import verify

ENGINES = {"fastpath": fastpath, "verify": verify}

# the positional parameters of every public function: the state (phi, v, eps), and where it
# applies the number of collisions, the period, the time of a gap or the carried state of a step
POSITIONAL = {
    "fastpath": {
        "carried_step": ("phi", "v", "eps", "carried"),
        "flight": ("phi", "v", "eps"),
        "flight_time": ("phi", "v", "eps"),
        "holmes_step": ("phi", "v", "eps"),
        "lyapunov": ("phi", "v", "eps", "n"),
        "moments": ("phi0", "v0", "eps", "n_grid"),
        "orbit": ("phi0", "v0", "eps", "n"),
        "periodic_orbit": ("phi", "v", "eps", "period"),
        "step": ("phi", "v", "eps"),
    },
    "verify": {
        "assert_integrator": ("flight_time",),
        "certify_flight": ("phi", "v", "eps"),
        "check_integrator": ("flight_time",),
        "condition_number": ("phi", "v", "eps", "tau"),
        "flight_time": ("phi", "v", "eps"),
        "gap": ("phi", "v", "eps", "tau"),
        "grazing_contact": ("eps", "psi", "T", "clearance"),
        "grazing_departure": ("eps", "psi", "T", "clearance"),
        "jacobian": ("phi", "v", "eps"),
        "orbit": ("phi0", "v0", "eps", "n"),
        "periodic_orbit": ("phi", "v", "eps", "period"),
        "step": ("phi", "v", "eps"),
    },
}

# keywords of a shared function that only one engine has, for what only that engine does:
# verify's precision, fastpath's models, solver and failure mode
ENGINE_ONLY = {
    "fastpath": {"model", "method", "on_uncertain", "max_iterations"},
    "verify": {"dps", "max_dps", "tolerance"},
}


def _functions(module):
    return {name: getattr(module, name) for name in module.__all__
            if inspect.isfunction(getattr(module, name))}


SHARED = sorted(_functions(fastpath).keys() & _functions(verify).keys())


def _split(function):
    """(positional names, {keyword-only name: default}, other kinds) of the signature."""
    params = inspect.signature(function).parameters.values()
    positional = tuple(p.name for p in params
                       if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD))
    keywords = {p.name: p.default for p in params if p.kind is p.KEYWORD_ONLY}
    other = [p.name for p in params if p.kind is p.VAR_POSITIONAL]
    return positional, keywords, other


def test_the_shared_functions_are_the_map_the_flight_the_orbit_and_periodic_orbits():
    assert SHARED == ["flight_time", "orbit", "periodic_orbit", "step"]


@pytest.mark.parametrize("engine", sorted(ENGINES))
def test_every_public_function_takes_only_its_state_positionally(engine):
    functions = _functions(ENGINES[engine])
    assert sorted(functions) == sorted(POSITIONAL[engine])
    for name, function in functions.items():
        positional, _, var_positional = _split(function)
        assert positional == POSITIONAL[engine][name], f"{engine}.{name}"
        assert not var_positional, f"{engine}.{name} takes *args"
        state = [p for p in inspect.signature(function).parameters.values()
                 if p.name in positional]
        assert all(p.default is p.empty for p in state), f"{engine}.{name}: a state default"


@pytest.mark.parametrize("name", SHARED)
def test_a_shared_function_takes_the_same_state_and_keywords_in_both_engines(name):
    (fast_state, fast, _), (ref_state, ref, _) = (_split(getattr(ENGINES[e], name))
                                                  for e in ("fastpath", "verify"))
    assert fast_state == ref_state
    assert fast.keys() - ref.keys() <= ENGINE_ONLY["fastpath"], f"fastpath.{name}"
    assert ref.keys() - fast.keys() <= ENGINE_ONLY["verify"], f"verify.{name}"
    for keyword in fast.keys() & ref.keys():
        assert fast[keyword] == ref[keyword], f"{name}({keyword}=...) defaults differ"
