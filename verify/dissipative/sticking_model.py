"""What the orbit loop needs to know of chattering and sticking: the :class:`StickingModel`.

With restitution ``r < 1`` the impacts after a slow landing pile up: :func:`verify.orbit` asks
the model after each impact whether the rest of the chattering run can be summed
(``accumulation``); if so the particle rides the plate from the accumulation point, either for
good (``leaves_plate()`` false) or for ``riding_time(phase)`` up to the detachment phase, and
the next impact is the one ending the flight from detachment (``detachment_step()``, an
:class:`verify.dissipative.impact.Impact`). Where no
tail is summed, ``check_chattering`` may stop a run that crawls
(:class:`verify.ChatteringDetected`). The two models: :class:`verify.dissipative.sticking.
RestitutionSticking` (no drag) and :class:`verify.dissipative.drag_sticking.DragSticking`.
"""

from __future__ import annotations

from typing import Protocol

from .drag_sticking import DragSticking
from .impact import Impact
from .physics import Physics
from .sticking import Accumulation, RestitutionSticking


class StickingModel(Protocol):
    """The interface of a sticking model (module docstring); phases and times are ``mpf``."""

    def accumulation(self, phi, v) -> Accumulation | None:
        """The summed tail after the impact state ``(phi, v)``, or None (impact by impact)."""

    def leaves_plate(self) -> bool:
        """A particle riding the plate ever leaves it."""

    def riding_time(self, phase):
        """Time riding the plate from the accumulation ``phase`` to the detachment phase."""

    def detachment_step(self) -> Impact:
        """The impact ending the flight from detachment."""

    def check_chattering(self, n: int, t, phi, v) -> None:
        """Raise :class:`verify.ChatteringDetected` if the run after impact ``n`` crawls."""


def sticking_model(eps, phys: Physics, dps: int) -> StickingModel | None:
    """The model for ``phys`` at ``dps`` digits, or None for ``r = 1`` (impacts never pile up)."""
    if phys.restitution == 1:
        return None
    if phys.drag == 0:
        return RestitutionSticking(eps, phys.restitution, dps)
    return DragSticking(eps, phys.drag, phys.drag_law, phys.restitution, dps)
