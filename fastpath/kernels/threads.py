"""The ensemble kernels' parallelism: groups of blocks, one Python thread each.

An ensemble kernel fills one row of counts per block of consecutive particles
(``fastpath.kernels.arrays``), so its numbers do not depend on how the blocks are shared out.
``over_threads`` splits the blocks into ``numba.get_num_threads()`` groups of consecutive
blocks and runs the compiled group function on each in its own thread; the group functions are
``jit`` (nogil), so the threads run at once. A parallel ``prange`` loop would do the same work,
but it compiles a parallel loop around the group function (seconds more on first use), and
numba's ``workqueue`` threading layer must not be entered by two Python threads at once
(``fastpath.arithmetic.jit``); plain threads have neither cost.
"""

from concurrent.futures import ThreadPoolExecutor

from numba import get_num_threads


def groups_of(blocks, groups):
    """(first block, end block) of each of ``groups`` groups of consecutive blocks (at least
    one group, at most one per block, the larger groups first)."""
    groups = max(1, min(blocks, groups))
    per_group = (blocks + groups - 1) // groups
    return [(g * per_group, min(blocks, (g + 1) * per_group)) for g in range(groups)
            if g * per_group < blocks]


def over_threads(run_group, blocks):
    """run_group(first, end) for the groups of ``groups_of(blocks, threads)`` (numba's thread
    count), each in its own thread, the first in the calling thread."""
    spans = groups_of(blocks, get_num_threads())
    if len(spans) == 1:
        run_group(*spans[0])
        return
    with ThreadPoolExecutor(max_workers=len(spans) - 1) as pool:
        futures = [pool.submit(run_group, *span) for span in spans[1:]]
        run_group(*spans[0])
        for future in futures:
            future.result()
