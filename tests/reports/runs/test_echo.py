"""Values in messages: clipped, and numbers as plain numbers (never ``np.float64(...)``)."""

import numpy as np
import pytest

from reports.runs.chunk import settle
from reports.runs.echo import LongInteger, clip, integer, plain, plain_text, shown
from reports.runs.rundir import RunFailed


def test_a_long_value_keeps_its_ends_and_says_how_long_it_was():
    text = "a" * 10 + "b" * 1000 + "c" * 10
    cut = clip(text, 60)
    assert len(cut) < 80 and cut.startswith("a" * 10) and cut.endswith("c" * 10)
    assert "(1020 characters)" in cut
    assert clip("short") == "short"


def test_numpy_scalars_are_shown_as_the_numbers_they_hold():
    assert plain(np.float64(3.5)) == 3.5 and type(plain(np.float64(3.5))) is float
    assert shown(np.float64(0.1)) == "0.1" and shown(np.int64(7)) == "7"
    assert plain_text("phi=np.float64(3.96), n=np.int64(3), ok=np.True_") == \
        "phi=3.96, n=3, ok=np.True_"
    assert plain_text("phi=np.float64(-1e-300), b=np.bool_(False)") == "phi=-1e-300, b=False"


def test_an_integer_too_long_to_convert_is_described_not_converted():
    assert integer("123") == 123
    long = integer("9" * 5000)
    assert isinstance(long, LongInteger)
    assert repr(long).startswith("an integer of 5000 digits (9999") and len(repr(long)) < 80
    assert shown(10 ** 5000).startswith("an integer of about 5000 digits")


def test_a_collision_verify_cannot_settle_is_named_by_plain_numbers():
    """A state that is no departure (w0 < 0), given as the numpy scalars a kernel returns."""
    with pytest.raises(RunFailed) as err:
        settle(np.float64(3.9640511223498582), np.float64(-0.45431268057730967), 0.6)
    assert "np.float64" not in str(err.value)
    assert "from phi=3.9640511223498582, v=-0.45431268057730967: no departure" in str(err.value)
