"""The physics description that every solver, orbit loop and kernel takes.

A particle bounces on a plate whose position is eps*cos(t) (velocity -eps*sin(t)) under gravity 1
(docs/model.md: the paper's units). Between impacts it may feel air drag eta(V); at an impact
the relative velocity reverses and shrinks by the restitution r:

    V' = -1 - eta(V),      eta(V) = 0 (NONE), k*V (LINEAR), k*V*|V| (QUADRATIC),  k = drag,
    v1 - u = -r*(v_in - u),    u = -eps*sin(phi + tau) the plate's velocity at the impact.

A description is a named tuple with the four fields (eps, drag, drag_law, restitution), the
field set of ``verify``'s physics description too. ``drag_law`` is an int code here, so that
compiled code can take it: NONE = 0 (no drag), LINEAR = 1, QUADRATIC = 2; ``LAWS`` maps the
public names "linear" and "quadratic" (the ``drag_law`` keyword of ``fastpath.step``,
``fastpath.orbit``, ...) to their codes. The public model names ("exact", "holmes": the
``model`` keyword) are ``MODELS``, one class each:

``Elastic``      the paper's exact map (drag 0, restitution 1): equations (1)-(2).
``Holmes``       the Holmes map: the plate's displacement neglected, its velocity kept.
``Dissipative``  drag and/or restitution r < 1 (the fields as given).

The class is the model: numba compiles a loop once per class, and ``model_of`` is a constant in
the compiled code, so the elastic loops carry no dissipative branch. All three classes have all
four fields (an ``Elastic`` one has drag 0, drag_law NONE, restitution 1), so that one loop body
type-checks for every class. Build descriptions with ``elastic``, ``holmes``, ``dissipative`` or
``describe`` (which picks the class from the values).

Where a new physics goes: a drag law gets a code and public name here and one module in
``fastpath.dissipative.laws`` with every formula that depends on it (its deceleration, closed-form
motion, short-flight offsets, solver bounds, riding and detachment), registered in that
package's dispatch (its docstring lists the functions); every flight solver, orbit loop and
kernel then takes it through the description.
"""

from typing import NamedTuple

from numba.extending import overload

# drag laws (ints, so that compiled code can take them)
NONE = 0
LINEAR = 1
QUADRATIC = 2
LAWS = {"linear": LINEAR, "quadratic": QUADRATIC}  # the public drag_law names

# models: the value of ``model_of`` for each class
ELASTIC = 0
HOLMES = 1
DISSIPATIVE = 2


class Elastic(NamedTuple):
    """The paper's bouncer: elastic impacts, no drag (drag 0, drag_law NONE, restitution 1)."""

    eps: float
    drag: float
    drag_law: int
    restitution: float


class Holmes(NamedTuple):
    """The Holmes map: flight time 2*v, v1 = |v - 2*eps*sin(phi1)| (no drag, elastic)."""

    eps: float
    drag: float
    drag_law: int
    restitution: float


class Dissipative(NamedTuple):
    """Drag k = ``drag`` >= 0 with law code ``drag_law`` and restitution r in (0, 1]."""

    eps: float
    drag: float
    drag_law: int
    restitution: float


_MODELS = {Elastic: ELASTIC, Holmes: HOLMES, Dissipative: DISSIPATIVE}

# the public model names (``fastpath.orbit``, ``fastpath.dynamics``: model="exact" or "holmes")
# and the class of each; a Dissipative description is model "exact" with drag or restitution
MODELS = {"exact": Elastic, "holmes": Holmes}


def elastic(eps):
    return Elastic(float(eps), 0.0, NONE, 1.0)


def holmes(eps):
    return Holmes(float(eps), 0.0, NONE, 1.0)


def dissipative(eps, drag, drag_law, restitution):
    return Dissipative(float(eps), float(drag), int(drag_law), float(restitution))


def describe(eps, drag=0.0, drag_law=NONE, restitution=1.0):
    """``Elastic`` where drag == 0 and restitution == 1, else ``Dissipative``."""
    if drag == 0.0 and restitution == 1.0:
        return elastic(eps)
    return dissipative(eps, drag, drag_law, restitution)


def model_name(physics):
    """The public model name of a description: "holmes" for ``Holmes``, else "exact"."""
    return "holmes" if type(physics) is Holmes else "exact"


def model_of(physics):
    """ELASTIC, HOLMES or DISSIPATIVE: the class of the description (a constant when compiled)."""
    return _MODELS[type(physics)]


@overload(model_of)
def _model_of_compiled(physics):
    code = _MODELS[physics.instance_class]
    return lambda physics: code


def with_eps(physics, eps):
    """The description with the plate amplitude eps (the same class)."""
    return physics._replace(eps=eps)


@overload(with_eps)
def _with_eps_compiled(physics, eps):
    cls = physics.instance_class
    return lambda physics, eps: cls(eps, physics.drag, physics.drag_law, physics.restitution)

