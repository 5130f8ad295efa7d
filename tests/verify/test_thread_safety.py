"""verify from several threads at once: the results are those of one thread, and mpmath's own
precision (``mpmath.mp.prec``, ``mpmath.iv.prec``) is never changed, not even for a moment."""

from __future__ import annotations

import sys
import threading
from concurrent.futures import ThreadPoolExecutor

import mpmath
import pytest

import verify

# departures of every kind the public functions meet: ordinary, |eps| > 1 with a near-graze,
# tiny w0, a huge phase, a fast particle, a near-triple root above |eps| = 1, drag of both laws
CASES = [
    (4.0, 3.0, 0.6, {}),
    (1.0, 2.0, 3.0, {}),
    (0.3, -0.6 * 0.29552020666133955 + 1e-9, 0.6, {}),
    (1e300, 3.0, 0.6, {}),
    (1.0, 1e15, 3.0, {}),
    (-1e-4, 1e-4, 1.0000000000000002, {}),
    (1.0, 2.0, 0.6, {"drag": 0.05}),
    (1.0, 2.0, 0.6, {"drag": 0.05, "drag_law": "quadratic"}),
]
PRECISIONS = (15, 30, 60)


def _calls():
    """(name, thunk) for every public function on every case and precision."""
    out = []
    for phi, v, eps, physics in CASES:
        for dps in PRECISIONS if not physics else PRECISIONS[:1]:  # drag flights are slow
            key = (phi, v, eps, tuple(physics.items()), dps)
            out.append((("flight_time",) + key,
                        lambda a=(phi, v, eps), d=dps, k=physics:
                        verify.flight_time(*a, dps=d, **k)))
            out.append((("step",) + key,
                        lambda a=(phi, v, eps), d=dps, k=physics: verify.step(*a, dps=d, **k)))
            if not physics:
                out.append((("jacobian",) + key,
                            lambda a=(phi, v, eps), d=dps: verify.jacobian(*a, dps=d)))
                out.append((("condition_number",) + key,
                            lambda a=(phi, v, eps), d=dps: verify.condition_number(
                                *a, verify.flight_time(*a, dps=d))))
    out.append((("orbit sticking",),
                lambda: verify.orbit(4.0, 3.0, 0.5, 60, dps=30, restitution=0.5)))
    out.append((("orbit drag sticking",),
                lambda: verify.orbit(1.0, 1.0, 0.5, 60, dps=15, drag=0.01, restitution=0.5)))
    return out


def _bits(x):
    """The exact content of a result (every mpf by its binary value), or the error's type."""
    if isinstance(x, verify.Orbit):
        return _bits((x.phi, x.v, x.t, x.sticking, x.stopped))
    if isinstance(x, mpmath.matrix):
        return tuple(_bits(x[i, j]) for i in range(x.rows) for j in range(x.cols))
    if isinstance(x, tuple | list):
        return tuple(_bits(y) for y in x)
    return x._mpf_ if hasattr(x, "_mpf_") else x


def _run(thunk):
    try:
        return _bits(thunk())
    except (ValueError, ArithmeticError) as err:
        return type(err).__name__


class _PrecisionWatch:
    """Samples mpmath's global precision in its own thread until stopped; records any change."""

    def __init__(self):
        self.expected = (mpmath.mp.prec, mpmath.iv.prec)
        self.seen = set()
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._watch)

    def _watch(self):
        while not self._stop.wait(1e-4):
            self.seen.add((mpmath.mp.prec, mpmath.iv.prec))

    def __enter__(self):
        self._thread.start()
        return self

    def __exit__(self, *exc):
        self._stop.set()
        self._thread.join()


@pytest.fixture
def frequent_switches():
    """Thread switches every 10 microseconds (CPython's default is 5 ms), so that two threads
    interleave inside every call."""
    old = sys.getswitchinterval()
    sys.setswitchinterval(1e-5)
    yield
    sys.setswitchinterval(old)


@pytest.fixture
def caller_precision():
    """A caller who works at 40 digits: verify must leave that alone."""
    old = mpmath.mp.prec, mpmath.iv.prec
    mpmath.mp.dps = mpmath.iv.dps = 40
    yield mpmath.mp.prec, mpmath.iv.prec
    mpmath.mp.prec, mpmath.iv.prec = old


@pytest.mark.slow
def test_a_thread_pool_gives_the_single_threaded_results(caller_precision, frequent_switches):
    """Every public function over 8 departures x 3 precisions (15 to 60 digits; the drag
    flights at 15) and two sticking orbits, in a pool of 6 threads, each call submitted twice
    in shuffled order: every result is bit for bit the single-threaded one, and mpmath's
    precision stays the caller's throughout (sampled while the pool runs) and after."""
    calls = _calls()
    serial = {name: _run(thunk) for name, thunk in calls}
    assert (mpmath.mp.prec, mpmath.iv.prec) == caller_precision
    order = calls + calls[::-1]
    order = order[::3] + order[1::3] + order[2::3]
    with _PrecisionWatch() as watch, ThreadPoolExecutor(max_workers=6) as pool:
        futures = [(name, pool.submit(_run, thunk)) for name, thunk in order]
        threaded = [(name, future.result()) for name, future in futures]
    differing = [name for name, result in threaded if result != serial[name]]
    assert differing == []
    assert watch.seen == {caller_precision}
    assert (mpmath.mp.prec, mpmath.iv.prec) == caller_precision


def test_a_high_precision_flight_beside_a_fast_loop(frequent_switches):
    """One thread certifies a flight at 300 digits while another loops on a flight at 15
    digits: the 300-digit result has its 300 digits, the loop never fails."""
    alone = verify.flight_time(4.0, 3.0, 0.6, dps=300)
    stop = threading.Event()
    loop_results = []

    def loop():
        while not stop.is_set():
            loop_results.append(_run(lambda: verify.flight_time(4.0, 3.0, 3.0, dps=15)))

    worker = threading.Thread(target=loop)
    worker.start()
    try:
        together = [verify.flight_time(4.0, 3.0, 0.6, dps=300) for _ in range(30)]
    finally:
        stop.set()
        worker.join()
    assert all(t._mpf_ == alone._mpf_ for t in together)
    assert len(set(loop_results)) == 1 and isinstance(loop_results[0], tuple)


def test_results_compute_at_the_callers_precision():
    """A returned mpf belongs to mpmath's own context: arithmetic on it runs at the caller's
    precision, not at verify's working precision."""
    tau = verify.flight_time(4.0, 3.0, 0.6, dps=50)
    assert type(tau) is mpmath.mpf
    with mpmath.workdps(50):
        assert abs(tau / 3 * 3 - tau) < mpmath.mpf(10) ** -48
