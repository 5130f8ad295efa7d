"""How an error message shows a value it was given: clipped, and numbers as plain numbers.

A message names the file and the field and shows the offending value, but a value from a
hostile file may be a 5000-digit integer or a megabyte of text: ``shown`` keeps its first and
last characters and says how long it was. ``plain`` turns numpy scalars into the Python
numbers they hold, so that a message says 3.96, never ``np.float64(3.96)``.
"""

from __future__ import annotations

import re

SHOWN_CHARACTERS = 80  # of a value echoed in a message
MAX_DIGITS = 20  # an integer with more digits is no count of a run (counts are < 2**63)


def plain(value):
    """A numpy scalar as the Python number it holds (``item()``); anything else unchanged."""
    if hasattr(value, "item") and getattr(value, "shape", None) == ():
        return value.item()
    return value


def clip(text, limit=SHOWN_CHARACTERS):
    """``text`` itself if it has at most ``limit`` characters, else its start and end around
    "... (N characters) ..."."""
    text = str(text)
    if len(text) <= limit:
        return text
    keep = max(limit // 2 - 10, 1)
    return f"{text[:keep]}... ({len(text)} characters) ...{text[-keep:]}"


def shown(value, limit=SHOWN_CHARACTERS):
    """The repr of a value for a message: plain numbers, clipped to ``limit`` characters. An
    integer too long for ``repr`` (Python refuses more than 4300 digits) is described."""
    value = plain(value)
    if isinstance(value, int) and not isinstance(value, bool) and value.bit_length() > 14000:
        return f"an integer of about {int(value.bit_length() * 0.30103)} digits"
    return clip(repr(value), limit)


class LongInteger:
    """An integer literal of more than ``MAX_DIGITS`` digits, kept as its text: what a JSON
    reader returns for one (``json.loads(..., parse_int=integer)``), so that the schema check
    names the field that holds it (it is no JSON integer of this format)."""

    def __init__(self, digits: str) -> None:
        self.digits = digits

    def __repr__(self) -> str:
        return f"an integer of {len(self.digits.lstrip('-'))} digits ({clip(self.digits, 30)})"


def integer(digits: str):
    """``parse_int`` for ``json.loads``: an int, or a ``LongInteger`` beyond ``MAX_DIGITS``."""
    if len(digits.lstrip("-")) > MAX_DIGITS:
        return LongInteger(digits)
    return int(digits)


_NUMPY_SCALAR = re.compile(r"np\.(?:float|int|uint|bool_?)\d*\(([^()]*)\)")


def plain_text(message: str) -> str:
    """A message with numpy scalar reprs, ``np.float64(3.96)``, written as the numbers they
    hold: the last guard of the rule that messages show plain numbers."""
    return _NUMPY_SCALAR.sub(r"\1", message)
