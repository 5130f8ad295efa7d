"""The verification sample replayed from the run's seed: how ``bouncer verify`` checks ``seed``.

A row of sample.csv (experiment e, chunk k, particle i, collision n, state (phi, v), ...) states
that particle i of chunk (e, k) carries a verification pick, and that (phi, v) is its state
just before its n-th collision. Everything about the pick follows from the seed alone
(``plan.chunk_starts``: ``SeedSequence(seed, spawn_key=(e, k))``): its start (phi_0, v_0) and
its target collision T, with n = min(T, the last collision the particle made) <= T. So each row
is replayed from its start:

* particle i must be a pick of chunk (e, k) under the seed, with n <= T;
* n - 1 collisions from (phi_0, v_0) must land on (phi, v) bit for bit, computed as the run
  computed them: for the elastic model the step ``fastpath.step`` (the kernels' arithmetic),
  with a collision float64 cannot decide settled by ``verify.step`` (``chunk.settle``), as the
  run settles it; with drag or restitution r < 1 the run's kernel is
  ``fastpath.kernels.particle.advance`` (a step with r < 1 reads a carried state beyond
  (phi, v)), so the replay is ``fastpath.orbit`` with the curve's physics, settled and restarted
  the same way at an undecided flight. The kernels built on ``advance`` (dissipative and
  velocity scenes) start from the start phase reduced to [0, 2*pi).

The cost is the sum of n over the rows, ~4 us a collision (a scalar ``fastpath.step``).

A run made with another seed draws other picks and starts, so an edited seed fails the first
check at almost every row and the second at every row.
"""

from __future__ import annotations

from collections import defaultdict
from dataclasses import dataclass

import fastpath
from fastpath.arithmetic.phase import reduce_phase
from reports.runs.chunk import settle
from reports.runs.plan import chunk_starts


@dataclass(frozen=True)
class SampleRow:
    """The fields of a sample row the replay needs; ``line`` is its line in sample.csv."""

    line: int
    experiment: int
    chunk: int
    particle: int
    n: int
    phi: float
    v: float


def replay_problems(plan, rows, progress=None):
    """Discrepancies (``"sample.csv:LINE: ..."``) of ``rows`` (``SampleRow``) against the picks
    and starts drawn from ``plan.seed``; ``progress(count)`` after each replayed row."""
    out, starts = [], defaultdict(list)
    n_exp, per = len(plan.experiments), plan.chunks_per_experiment
    for row in rows:
        if not (0 <= row.experiment < n_exp and 0 <= row.chunk < per):
            out.append(f"sample.csv:{row.line}: chunk ({row.experiment}, {row.chunk}) is not a"
                       f" chunk of this run ({n_exp} curves x {per} chunks)")
            continue
        starts[row.experiment, row.chunk].append(row)
    for (e, k), chunk_rows in sorted(starts.items()):
        phi0, v0, slot, target, _ = chunk_starts(plan, e, k)
        physics = plan.scene.curve_physics(e)
        for row in chunk_rows:
            i = row.particle
            if not (0 <= i < len(slot) and slot[i] >= 0):
                out.append(f"sample.csv:{row.line}: particle {i} of chunk ({e}, {k}) is not a"
                           f" verification pick drawn from seed {plan.seed}")
            elif not 1 <= row.n <= target[i]:
                out.append(f"sample.csv:{row.line}: collision {row.n} is not in 1 .."
                           f" {int(target[i])}, the target collision of this pick drawn from"
                           f" seed {plan.seed}")
            else:
                try:
                    state = replay(plan.scene, float(phi0[i]), float(v0[i]), row.n - 1,
                                   physics)
                except (ValueError, ArithmeticError, fastpath.UncertainCollision) as err:
                    out.append(f"sample.csv:{row.line}: the replay from its start drawn from"
                               f" seed {plan.seed} fails: {err}")
                else:
                    if state != (row.phi, row.v):
                        out.append(f"sample.csv:{row.line}: {row.n - 1} collisions from its"
                                   f" start drawn from seed {plan.seed} give (phi, v) = {state},"
                                   f" the file ({row.phi!r}, {row.v!r})")
            if progress is not None:
                progress(1)
    return out


def replay(scene, phi, v, steps, physics):
    """The state (phi, v) after ``steps`` collisions from the start (phi, v) of a particle of
    ``scene`` with the keywords ``physics`` (its curve's), as the run's kernel computes it
    (module docstring); floats."""
    eps = scene.eps
    if physics:
        return _replay_carried(phi, v, eps, steps, physics)
    if scene.kind == "velocity":  # its kernel starts from the reduced phase, as advance does
        phi = reduce_phase(phi)
    for _ in range(steps):
        try:
            phi, v, _tau = fastpath.step(phi, v, eps, **physics)
        except fastpath.UncertainCollision:
            phi, v, _tau = settle(phi, v, eps, physics)
    return float(phi), float(v)


def _replay_carried(phi, v, eps, steps, physics):
    phi = reduce_phase(phi)  # the departure state of ``fastpath.kernels.particle.begin``
    while steps > 0:
        orb = fastpath.orbit(phi, v, eps, steps, on_uncertain="stop", **physics)
        done = len(orb.phi) - 1
        phi, v = float(orb.phi[-1]), float(orb.v[-1])
        steps -= done
        if steps == 0:
            break
        if orb.status == fastpath.FlightStatus.CONVERGED:  # stuck on the plate for good
            raise ValueError(f"the particle sticks to the plate after {done} more collisions,"
                             f" {steps} before the sampled one")
        phi, v, _tau = settle(phi, v, eps, physics)
        steps -= 1
    return phi, v

