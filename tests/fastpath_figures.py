"""Figures the suite measures (worst errors, iteration counts, UNCERTAIN counts).

Tests record them here; ``tests/conftest.py`` prints them in pytest's terminal summary, so they
show without ``-s``, also when the run is split over pytest-xdist workers (each worker hands its
figures to the controller). Values are plain strings or numbers keyed by a short name; the
counters of ``bump`` are summed over the workers.
"""

FIGURES: dict[str, object] = {}
COUNTERS: set[str] = set()  # the names kept by ``bump``


def record(name, value):
    """Store a figure and print it (visible with ``pytest -s``)."""
    FIGURES[name] = value
    print(f"[fastpath figure] {name}: {value}")


def bump(name, by=1):
    """Add to a counter figure."""
    COUNTERS.add(name)
    FIGURES[name] = FIGURES.get(name, 0) + by
