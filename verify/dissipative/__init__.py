"""Dissipation: the physics description (:mod:`.physics`), the drag laws and their closed-form
flights (:mod:`.drag`), the drag gap and its certificate (:mod:`.drag_gap`), and chattering,
accumulation and sticking with restitution ``r < 1`` (:mod:`.sticking` without drag,
:mod:`.drag_sticking` with drag, both behind the :mod:`.sticking_model` interface the orbit loop
takes)."""
