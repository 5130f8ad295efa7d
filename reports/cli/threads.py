"""The ``--threads`` option shared by ``bouncer run`` and ``bouncer sweep``."""


def set_threads(threads):
    if threads is None:
        return None
    import numba

    limit = numba.config.NUMBA_NUM_THREADS
    if not 1 <= threads <= limit:
        raise ValueError(f"--threads must be between 1 and {limit}, got {threads}")
    numba.set_num_threads(threads)
    return threads


def threads_option(args):
    """--threads: numba threads here; on a cluster, of each task (the workers check it)."""
    if args.threads is not None and args.scheduler is not None:
        if args.threads < 1:
            raise ValueError(f"--threads must be >= 1, got {args.threads}")
        return args.threads
    return set_threads(args.threads)
