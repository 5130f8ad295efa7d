"""Ensemble chunks as tasks on a Dask distributed cluster (``bouncer run ... --scheduler ADDR``).

Optional: needs ``distributed`` (``pip install "bouncer-verify[cluster]"``) on the client and on
every worker, with the same bouncer-verify sources (a result computed by other sources is
refused: ``chunk.CODE_DIGEST``).

Each task is ``reports.runs.chunk.run_chunk(scene, seed, curve, chunk, particles, threads)``: it
draws the chunk's starts from ``SeedSequence(seed, spawn_key=(curve, chunk))``, runs the numba
kernel, settles the flagged collisions with ``verify`` *inside the task* (they are rare and
their particles must resume in the kernel, so the worker finishes them), recomputes the
chunk's verification sample with ``verify``, and returns a small ``ChunkResult`` (histograms,
verified sample rows). The client merges results as they complete, keyed by (curve, chunk)
(``counts.Tally.merge``: integer sums, rows sorted by index, a chunk merged twice is ignored)
and checkpoints after each, so the result does not depend on the number of workers or the
completion order, and ``--resume`` works across local and cluster runs.

Lost workers: a task whose worker dies is rescheduled by the scheduler on another worker (up
to ``distributed.scheduler.allowed-failures`` deaths, default 3, then ``KilledWorker``); a task
that raises is retried ``RETRIES`` times. A chunk counts once: only a returned result is
merged, and only the first for its index. At most ``window`` tasks are in flight, so the
client's and scheduler's memory does not grow with the number of chunks.
"""

from __future__ import annotations

import hashlib
from contextlib import contextmanager

from reports.runs.chunk import CODE_DIGEST, run_chunk
from reports.runs.rundir import RunFailed

RETRIES = 3
CONNECT_TIMEOUT = "30s"
WORKER_WAIT_S = 120
INSTALL_HINT = "pip install 'bouncer-verify[cluster]'"


def check_available():
    """ValueError (exit 2) with the install hint when ``distributed`` is missing."""
    try:
        import distributed  # noqa: F401
    except ImportError:
        raise ValueError(f"--scheduler needs the optional dependency distributed: {INSTALL_HINT}"
                         ) from None


@contextmanager
def connect(scheduler, timeout=None, wait_s=None):
    """A ``distributed.Client`` for ``scheduler``: an address ("tcp://host:8786"), a cluster
    object (``LocalCluster``, ...) or a ``Client`` (used as is and left open). Waits up to
    ``wait_s`` (default ``WORKER_WAIT_S``) for a first worker. ValueError if it cannot connect
    within ``timeout`` (default ``CONNECT_TIMEOUT``) or no worker comes."""
    check_available()
    timeout = CONNECT_TIMEOUT if timeout is None else timeout
    wait_s = WORKER_WAIT_S if wait_s is None else wait_s
    from distributed import Client

    if isinstance(scheduler, Client):
        yield scheduler
        return
    address = getattr(scheduler, "scheduler_address", scheduler)
    if not isinstance(address, str) or not address:
        raise ValueError(f"--scheduler must be an address like tcp://host:8786, got {scheduler!r}")
    try:
        client = Client(address, timeout=timeout, set_as_default=False)
    except (OSError, TimeoutError, ValueError) as err:
        raise ValueError(f"cannot connect to the Dask scheduler at {address}: {err}") from None
    try:
        try:
            client.wait_for_workers(1, timeout=wait_s)
        except (TimeoutError, OSError):
            raise ValueError(f"the Dask scheduler at {address} has no workers after {wait_s} s"
                             " (start some: dask worker ADDRESS --nthreads 1)") from None
        yield client
    finally:
        client.close()


def describe(client):
    """The scheduler address, number of workers and their threads (for the manifest)."""
    try:
        info = client.scheduler_info(n_workers=-1)  # all of them (newer versions list 5)
    except TypeError:
        info = client.scheduler_info()
    workers = info["workers"]
    return {"scheduler": client.scheduler.address, "workers": len(workers),
            "worker_threads": sum(w.get("nthreads", 1) for w in workers.values())}


def task_key(key, args):
    """A readable, deterministic Dask key for the task ``run_chunk(*args)`` of job ``key``."""
    scene, seed, curve, chunk, particles = args[:5]
    token = hashlib.sha256(repr((scene.source, seed, curve, chunk, particles, CODE_DIGEST))
                           .encode()).hexdigest()[:16]
    label = "-".join(map(str, key)) if isinstance(key, tuple) else str(key)
    return f"bouncer-chunk-{scene.name}-{label}-{token}"


def map_chunks(client, jobs, window=None, retries=RETRIES, function=None):
    """Run ``function(*args)`` (default ``chunk.run_chunk``) for each job (key, args) on the
    cluster; yields (key, result) in completion order. Outstanding tasks are cancelled when
    the caller stops early. A task that fails for good raises RunFailed."""
    from distributed import as_completed

    function = function or run_chunk
    if window is None:
        window = max(8, 2 * describe(client)["worker_threads"])
    pending = iter(jobs)
    futures = {}
    done = as_completed(loop=client.loop)

    def submit_next():
        for key, args in pending:
            future = client.submit(function, *args, key=task_key(key, args), retries=retries)
            futures[future.key] = (key, future)
            done.add(future)
            return

    for _ in range(window):
        submit_next()
    try:
        for future in done:
            key, _ = futures.pop(future.key)
            try:
                result = future.result()
            except Exception as err:  # KilledWorker, retries spent, scheduler lost, ...
                raise RunFailed(f"chunk {key} failed on the cluster: {type(err).__name__}:"
                                f" {err}") from None
            future.release()
            submit_next()
            yield key, result
    finally:
        if futures:
            client.cancel([f for _, f in futures.values()])
