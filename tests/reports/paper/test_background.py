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


def test_a_worker_runs_its_jobs_in_order_in_one_thread_with_numba_on_one_thread():
    import numba

    from reports.paper.studies.background import Worker

    caller_threads = numba.get_num_threads()
    worker = Worker()
    seen = []

    def job(k):
        seen.append((k, threading.current_thread(), numba.get_num_threads()))
        return k * k

    finishes = [worker.submit(job, k) for k in range(5)]
    assert [f() for f in finishes] == [0, 1, 4, 9, 16]
    assert [k for k, _, _ in seen] == list(range(5))
    assert len({t for _, t, _ in seen}) == 1 and seen[0][1].daemon
    assert {n for _, _, n in seen} == {1}
    assert numba.get_num_threads() == caller_threads


def test_a_failed_job_does_not_stop_the_worker():
    from reports.paper.studies.background import Worker

    worker = Worker()

    def broken():
        raise LookupError("gone")

    failed, fine = worker.submit(broken), worker.submit(lambda: 7)
    with pytest.raises(LookupError, match="gone"):
        failed()
    assert fine() == 7


@pytest.mark.slow
def test_diffusion_ensembles_begun_ahead_give_the_checks_the_same_numbers(monkeypatch):
    from reports.paper.checks import diffusion as d
    from reports.paper.studies.background import Worker

    monkeypatch.setattr(d, "_BEGUN", {})
    eps = d.DIFFUSION_EPS[True][0]
    alone = [d.diffusion(eps, model, True) for model in ("exact", "holmes")]
    d.begin_ensembles(True, Worker().submit)
    assert set(d._BEGUN) == {(e, m, True) for e in d.DIFFUSION_EPS[True]
                             for m in ("exact", "holmes")}
    ahead = [d.diffusion(eps, model, True) for model in ("exact", "holmes")]
    assert d._BEGUN == {}  # each taken once
    assert [vars(r) for r in ahead] == [vars(r) for r in alone]
