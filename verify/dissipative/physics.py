"""The physics description: one value that says which bouncer is simulated.

``Physics(drag, drag_law, restitution)``: the drag ``k >= 0`` with its law (a name in
:data:`verify.dissipative.drag.LAWS`: the force ``eta(V)`` in ``y'' = -1 - eta(y')``) and the
coefficient of restitution ``r`` in ``(0, 1]`` of the impact law ``v1 - u = -r*(v_in - u)``
(``u`` the plate's velocity). ``check_physics()`` is the elastic, friction-free bouncer of the
paper.
The flight certificate (:func:`verify.certify_flight`), the map (:func:`verify.step`) and the
orbit loop (:func:`verify.orbit`, through :func:`verify.dissipative.sticking_model.
sticking_model`) all take this one value, so a new drag law added to
:mod:`verify.dissipative.drag` reaches every one of them.

The fields are fastpath's physics keywords under the same names; the plate's amplitude ``eps``
is not one of them (fastpath's description carries it for its compiled kernels): here it is
part of the state ``(phi, v, eps)``, validated with ``phi`` and ``v`` as exact values by
:func:`verify.numerics.inputs.check_state` after this value (whose :attr:`Physics.is_default`
decides whether ``w0 = 0`` is a departure), and passed beside it to every certificate.
"""

from __future__ import annotations

from typing import NamedTuple

import mpmath

from ..numerics.inputs import exact_real
from .drag import LAWS, check_drag


class Physics(NamedTuple):
    """Validated physics: ``drag`` k as an exact ``mpf``, the law's name, restitution r."""

    drag: mpmath.mpf
    drag_law: str
    restitution: mpmath.mpf

    @property
    def is_default(self) -> bool:
        """The elastic, friction-free model (the paper's bouncer)."""
        return self.drag == 0 and self.restitution == 1

    @property
    def law(self):
        """The drag law's class (:data:`verify.dissipative.drag.LAWS`)."""
        return LAWS[self.drag_law]

    def keywords(self) -> dict:
        """The keyword arguments of the public functions that give this physics."""
        return {"drag": self.drag, "drag_law": self.drag_law, "restitution": self.restitution}


def check_physics(drag=0.0, drag_law="linear", restitution=1.0) -> Physics:
    """Validate the keyword-only physics of the public functions; ``ValueError`` naming the value.

    ``drag`` finite ``>= 0``; ``drag_law`` a name in :data:`verify.dissipative.drag.LAWS`;
    ``restitution`` in ``(0, 1]``.
    """
    k, law = check_drag(drag, drag_law)
    r = exact_real("restitution", restitution)
    if not 0 < r <= 1:
        raise ValueError(f"restitution must be in (0, 1], got restitution={restitution!r}")
    return Physics(k, law, r)
