"""Figures the suite measures (worst errors, iteration counts, UNCERTAIN counts).

Tests record them here; ``conftest.py`` prints them in pytest's terminal summary, so they show
without ``-s``. Values are plain strings or numbers keyed by a short name.
"""

FIGURES: dict[str, object] = {}


def record(name, value):
    """Store a figure and print it (visible with ``pytest -s``)."""
    FIGURES[name] = value
    print(f"[fastpath figure] {name}: {value}")


def bump(name, by=1):
    """Add to a counter figure."""
    FIGURES[name] = FIGURES.get(name, 0) + by
