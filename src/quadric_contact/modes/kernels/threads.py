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

import numpy as np

from quadric_contact.modes.kernels._jit import HAVE_NUMBA

__all__ = ["MIN_PER_THREAD", "THREADS", "kernel_stack", "run_parallel", "single_threaded"]

THREADS = max(1, min(os.cpu_count() or 1, int(os.environ.get("QUADRIC_CONTACT_THREADS", "0") or 0) or 64))
"""Threads used by default (all cores, or ``QUADRIC_CONTACT_THREADS``)."""
MIN_PER_THREAD = 16384
"""A slice is never shorter than this: below it one thread does the work."""
SLICES_PER_THREAD = 8
"""Sets the share of what is left that each slice of one call takes (see :func:`_slices`)."""

_local = threading.local()
_pool: ThreadPoolExecutor | None = None
_pool_lock = threading.Lock()


def kernel_stack(a: np.ndarray) -> np.ndarray:
    """``a`` as the kernels that only read a stack of matrices take it: float64, C-contiguous,
    ``(n, 4, 4)`` and read-only, whatever the caller's array (a copy only where the dtype or
    the layout differ).  numba compiles one version of a kernel for each writeable flag of its
    arguments; given the one form, it compiles (and the native library holds) one."""
    a = np.ascontiguousarray(a, dtype=np.float64).reshape(-1, 4, 4).view()
    a.flags.writeable = False
    return a


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


def _slices(n: int, t: int) -> list[int]:
    """Bounds of the slices of ``range(n)`` for ``t`` threads, shrinking as they go (guided
    scheduling): each takes a share of what is left, ``1 / (SLICES_PER_THREAD / 2 * t)`` of it
    and never under :data:`MIN_PER_THREAD`, so the threads start on long slices and end on short
    ones: the last thread to finish waits for a short slice, not an eighth of the batch."""
    bounds = [0]
    share = max(1, SLICES_PER_THREAD * t // 2)
    while bounds[-1] < n:
        rest = n - bounds[-1]
        size = max(MIN_PER_THREAD, rest // share)
        bounds.append(bounds[-1] + min(size, rest))
    return bounds


def run_parallel(kernel: Callable[[int, int], object], n: int, threads: int | None = None) -> None:
    """Call ``kernel(lo, hi)`` on slices of ``range(n)``, on several threads when it pays (the
    calling thread works too).  One thread inside :func:`single_threaded`.

    The range is cut into slices (:func:`_slices`) taken in turn by whichever thread is free: a
    thread slowed down by the rest of the machine takes fewer of them, so the call does not
    wait for the slowest half."""
    t = threads_for(n, threads)
    if t <= 1 or not HAVE_NUMBA:
        kernel(0, n)
        return
    bounds = _slices(n, t)
    k = len(bounds) - 1
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
