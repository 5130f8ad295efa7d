"""Where the chunks of a run are computed: here, one after another, or on a Dask cluster."""

from collections import deque
from concurrent.futures import ThreadPoolExecutor
from contextlib import ExitStack

from reports.runs import cluster
from reports.runs.chunk import run_chunk


def local(jobs):
    """The chunks here, two in flight, yielded in order.

    ``run_chunk`` is a pure function of its arguments; numba's kernels run one at a time
    (``chunk._KERNEL_LOCK``), and so do the sample checks (``chunk._SAMPLE_LOCK``: their own
    arithmetic uses mpmath's process-wide precision; verify itself is safe from any thread).
    So one chunk's verification sample (Python, holding the GIL)
    runs while the next chunk's kernel runs (numba threads, without the GIL), and the results
    are those of the chunks one after another.
    """
    with ThreadPoolExecutor(max_workers=2) as pool:
        pending = deque()
        try:
            for key, args in jobs:
                pending.append((key, pool.submit(run_chunk, *args)))
                if len(pending) == 2:
                    first, future = pending.popleft()
                    yield first, future.result()
            while pending:
                first, future = pending.popleft()
                yield first, future.result()
        finally:
            for _, future in pending:
                future.cancel()


class Executor:
    """Context manager giving ``execute(jobs) -> iterator of (key, ChunkResult)``: here, or on
    the Dask cluster of ``scheduler`` (closing what it opened on exit)."""

    def __init__(self, scheduler, session):
        self.scheduler, self.session, self.stack = scheduler, session, None

    def __enter__(self):
        if self.scheduler is None:
            return local
        self.stack = ExitStack()
        client = self.stack.enter_context(cluster.connect(self.scheduler))
        self.session.update(cluster.describe(client))
        return lambda jobs: cluster.map_chunks(client, jobs)

    def __exit__(self, *exc):
        if self.stack is not None:
            self.stack.close()
        return False
