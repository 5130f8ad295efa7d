"""Dissipation: air drag during the flights, restitution r < 1 at the impacts, and what follows
from them (chattering, sticking to the plate, detachment). The description ``Dissipative``
(``fastpath.physics``) selects this code; the elastic loops compile none of it.

Reading order:

``laws``          one module per drag law eta(V) (``none``, ``linear``, ``quadratic``) with every
                  formula that depends on the law, and the one dispatch on the law code.
``special``       cancellation-free special functions of the laws' closed forms.
``drag``          the particle's motion under drag with its rounding bounds; the gap.
``drag_flight``   one flight with drag: the first root of that gap.
``short_flight``  a short flight from a small relative velocity, in relative coordinates.
``impact``        impacts with restitution; the collision map with drag.
``sticking``      chattering, the accumulation of impacts, riding the plate and detachment.
``carried``       the carried state of a dissipative orbit and its step (``fastpath.carried_step``).

Nothing is imported here: a module compiles its kernels when they are first called.
"""
