"""Work begun in a background thread: its result, its exception and its thread."""

import threading

import pytest

from reports.paper.studies.background import begin


def test_the_caller_gets_the_result_computed_in_another_daemon_thread():
    started = threading.Event()
    seen = {}

    def work(x, y=0):
        seen["thread"] = threading.current_thread()
        started.set()
        return x + y

    finish = begin(work, 2, y=3, name="adding")
    assert started.wait(10)
    assert finish() == 5
    assert seen["thread"] is not threading.current_thread()
    assert seen["thread"].daemon and seen["thread"].name == "adding"


def test_an_exception_in_the_background_is_raised_by_finish():
    def broken():
        raise ArithmeticError("no")

    finish = begin(broken)
    with pytest.raises(ArithmeticError, match="no"):
        finish()
