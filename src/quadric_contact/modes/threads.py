"""Threads for the compiled kernels: split a range of pairs, run the slices at once.

The numba kernels release the GIL, so the slices of one call run in parallel on a
pool of threads kept for the life of the process (starting threads for every call
costs more than a small batch).  :func:`single_threaded` turns the splitting off for
the calling thread (dask runs its blocks on threads of its own); a call made from a
thread of the pool runs in that thread, so that nested calls cannot wait on each other.
``QUADRIC_CONTACT_THREADS`` caps the number of threads (default: every core).
"""

from __future__ import annotations

import contextlib
import itertools
import os
import threading
from collections.abc import Callable, Iterator
from concurrent.futures import Future, ThreadPoolExecutor

from quadric_contact.modes._jit import HAVE_NUMBA

__all__ = ["MIN_PER_THREAD", "THREADS", "run_parallel", "single_threaded"]

THREADS = max(1, min(os.cpu_count() or 1, int(os.environ.get("QUADRIC_CONTACT_THREADS", "0") or 0) or 64))
"""Threads used by default (all cores, or ``QUADRIC_CONTACT_THREADS``)."""
MIN_PER_THREAD = 16384
"""A slice is never shorter than this: below it one thread does the work."""
SLICES_PER_THREAD = 8
"""Slices per thread of one call (the threads take them in turn)."""

_local = threading.local()
_pool: ThreadPoolExecutor | None = None
_pool_lock = threading.Lock()


@contextlib.contextmanager
def single_threaded() -> Iterator[None]:
    """Run the kernels of this thread on this thread only (dask provides the parallelism)."""
    old = getattr(_local, "threads", None)
    _local.threads = 1
    try:
        yield
    finally:
        _local.threads = old


def _worker_init() -> None:
    _local.in_pool = True


def _get_pool() -> ThreadPoolExecutor:
    global _pool
    if _pool is None:
        with _pool_lock:
            if _pool is None:
                _pool = ThreadPoolExecutor(
                    max_workers=max(1, THREADS - 1),
                    thread_name_prefix="quadric-contact",
                    initializer=_worker_init,
                )
    return _pool


def threads_for(n: int, threads: int | None = None) -> int:
    """How many threads :func:`run_parallel` uses for ``n`` items."""
    t = THREADS if threads is None else max(1, threads)
    t = min(t, getattr(_local, "threads", None) or t)
    if getattr(_local, "in_pool", False):
        t = 1
    return max(1, min(t, n // MIN_PER_THREAD))


def run_parallel(kernel: Callable[[int, int], object], n: int, threads: int | None = None) -> None:
    """Call ``kernel(lo, hi)`` on slices of ``range(n)``, on several threads when it pays (the
    calling thread works too).  One thread inside :func:`single_threaded`.

    The range is cut into :data:`SLICES_PER_THREAD` slices per thread, taken in turn by whichever
    thread is free: a thread slowed down by the rest of the machine takes fewer of them, so the
    call does not wait for the slowest half."""
    t = threads_for(n, threads)
    if t <= 1 or not HAVE_NUMBA:
        kernel(0, n)
        return
    k = max(t, min(t * SLICES_PER_THREAD, n // MIN_PER_THREAD))
    bounds = [n * i // k for i in range(k + 1)]
    slices = itertools.count()  # next() on a count is atomic under the GIL

    def work() -> None:
        while (i := next(slices)) < k:
            kernel(bounds[i], bounds[i + 1])

    pool = _get_pool()
    futures: list[Future[object]] = [pool.submit(work) for _ in range(1, t)]
    try:
        work()
    finally:
        for f in futures:
            f.result()
