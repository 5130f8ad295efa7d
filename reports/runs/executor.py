"""Where the chunks of a run are computed: here, one after another, or on a Dask cluster."""

from contextlib import ExitStack

from reports.runs import cluster
from reports.runs.chunk import run_chunk


def local(jobs):
    for key, args in jobs:
        yield key, run_chunk(*args)


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
