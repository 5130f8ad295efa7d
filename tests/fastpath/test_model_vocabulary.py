"""One model vocabulary: the public names "exact" and "holmes" become a physics description
(``fastpath.physics``) in one validator, ``fastpath.inputs.model_physics``, which every public
function with a ``model`` argument uses."""

import numba
import numpy as np
import pytest

import fastpath
import fastpath.dynamics as fd
from fastpath.api import moments
from fastpath.dynamics.kernels import step_tangent
from fastpath.inputs import model_physics
from fastpath.physics import LINEAR, MODELS, Dissipative, Elastic, Holmes, dissipative, model_name


def test_the_public_model_names_are_the_description_classes():
    assert MODELS == {"exact": Elastic, "holmes": Holmes}
    assert type(model_physics("exact", 0.6)) is Elastic
    assert type(model_physics("holmes", 0.6)) is Holmes
    assert type(model_physics("exact", 0.6, 0.01, LINEAR, 0.9)) is Dissipative
    assert model_physics("holmes", 0.25).eps == 0.25
    for name in MODELS:
        assert model_name(model_physics(name, 0.6)) == name
    assert model_name(model_physics("exact", 0.6, 0.01, LINEAR, 1.0)) == "exact"


@pytest.mark.parametrize("model", ["holmez", "Exact", "elastic", 1, None])
def test_an_unknown_model_is_refused_naming_the_public_names(model):
    with pytest.raises(ValueError, match=r"model must be one of \['exact', 'holmes'\]"):
        model_physics(model, 0.6)


def test_the_holmes_map_takes_no_drag_and_no_restitution():
    with pytest.raises(ValueError, match="needs model='exact'"):
        model_physics("holmes", 0.6, 0.01, LINEAR, 1.0)
    with pytest.raises(ValueError, match="needs model='exact'"):
        model_physics("holmes", 0.6, 0.0, LINEAR, 0.9)


PUBLIC_MODEL_CALLS = {
    "orbit": lambda model: fastpath.orbit(4.0, 3.0, 0.6, 10, model=model),
    "moments": lambda model: moments([4.0], [3.0], 0.6, [1], model=model),
    "lyapunov": lambda model: fd.lyapunov(4.0, 3.0, 0.6, 10, model=model),
    "separation": lambda model: fd.separation(4.0, 3.0, 0.6, 10, model=model),
    "lyapunov_by_band": lambda model: fd.lyapunov_by_band(4.0, 3.0, 0.6, 10, [0, 5], model=model),
    "periodic_orbit": lambda model: fd.periodic_orbit(0.0, np.pi, 0.3, 1, model=model),
    "symmetric_orbit": lambda model: fd.symmetric_orbit(2.0, 0.2, 3, 1, model=model),
    "critical_amplitude": lambda model: fd.critical_amplitude(0, model=model),
    "accelerator_search": lambda model: fd.accelerator_search(1.2, 1, model=model),
    "velocities": lambda model: fd.velocities([4.0], [3.0], 0.6, [1], model=model),
    "first_passage": lambda model: fd.first_passage([4.0], [3.0], 0.6, 5.0, 10, model=model),
    "step_jacobian": lambda model: fd.step_jacobian(4.0, 3.0, 0.6, model=model),
}


@pytest.mark.parametrize("name", sorted(PUBLIC_MODEL_CALLS))
def test_every_public_model_argument_is_checked_by_the_one_validator(name):
    """The same refusal, word for word, from every public function that takes ``model``."""
    with pytest.raises(ValueError) as caught:
        PUBLIC_MODEL_CALLS[name]("holmez")
    with pytest.raises(ValueError) as expected:
        model_physics("holmez", 0.6)
    assert str(caught.value) == str(expected.value)


def test_the_dynamics_kernels_have_no_map_for_a_dissipative_description():
    """``step_tangent`` compiles the map of the description's class; drag and restitution have
    no Jacobian there, so a dissipative description does not type (it is not run as elastic)."""
    with pytest.raises(numba.core.errors.TypingError):
        step_tangent(0.5, np.sin(0.5), np.cos(0.5), 3.0, dissipative(0.6, 0.01, LINEAR, 0.9))
