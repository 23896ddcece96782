"""The one way to change the working precision of certified arithmetic.

python-flint's ``flint.ctx.prec`` (the precision of ``arb`` balls) and
mpmath's ``mp.prec`` are *process-global*: a thread that changes them changes
them for every other thread.  Dask's threaded scheduler runs many tasks of one
sweep at the same time, so a bare ``flint.ctx.prec = bits`` in one task can
shrink the balls of another task's computation in the middle of it.

Every change of precision in the package goes through :func:`working_precision`,
which holds one process-wide re-entrant lock for the whole ``with`` block: code
that depends on a precision runs with the precision it asked for, and the old
values are restored before another thread may set its own.  Blocks of one
thread nest freely (the lock is re-entrant); blocks of different threads are
serialised (a forked worker process starts with a fresh lock).  The choice
favours correctness over parallel speed: a ball computed at another thread's
precision would not give a wrong sign, but a slower or an undecided one.

Examples
--------
>>> import flint
>>> before = flint.ctx.prec
>>> with working_precision(200):
...     flint.ctx.prec
200
>>> flint.ctx.prec == before
True
"""

from __future__ import annotations

import contextlib
import os
import threading
from collections.abc import Iterator

import flint
import mpmath

__all__ = ["working_precision"]

_LOCK = threading.RLock()


def _fresh_lock_in_child() -> None:
    """A process forked while another thread held the lock would inherit it held forever."""
    global _LOCK
    _LOCK = threading.RLock()


os.register_at_fork(after_in_child=_fresh_lock_in_child)


@contextlib.contextmanager
def working_precision(bits: int | None = None, *, dps: int | None = None) -> Iterator[None]:
    """Scoped working precision for flint balls (``bits``) and mpmath (``dps``).

    Parameters
    ----------
    bits : int, optional
        Precision in bits of ``flint.arb`` arithmetic inside the block.
    dps : int, optional
        Decimal digits of mpmath arithmetic inside the block.

    Notes
    -----
    Holds a process-wide re-entrant lock while the block runs (thread-safe
    under dask's threaded scheduler); restores both precisions on exit, also
    when the block raises.

    Examples
    --------
    >>> import mpmath
    >>> with working_precision(dps=40):
    ...     mpmath.mp.dps
    40
    """
    with _LOCK:
        old_bits = flint.ctx.prec
        old_prec = mpmath.mp.prec
        try:
            if bits is not None:
                flint.ctx.prec = bits
            if dps is not None:
                mpmath.mp.dps = dps
            yield
        finally:
            flint.ctx.prec = old_bits
            mpmath.mp.prec = old_prec
