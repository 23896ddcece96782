"""Which matrices of a binary64 stack lie in the range of the binary64 programs: every entry
zero or of magnitude in ``[INPUT_MIN, INPUT_MAX]`` (:mod:`quadric_contact.modes.kernels.errorbounds`;
a NaN fails).  The plain modes decide the others exactly (:mod:`quadric_contact.modes.decision.pipeline`);
one pass over the stack, where numpy's masks took a dozen (about 150 ns a pair of a million)."""

from __future__ import annotations

from typing import Any

import numpy as np

from quadric_contact.modes.kernels import errorbounds as eb
from quadric_contact.modes.kernels._jit import HAVE_NUMBA, njit
from quadric_contact.modes.kernels.threads import run_parallel

__all__ = ["rows_in_range"]

_IN_MIN = eb.INPUT_MIN
_IN_MAX = eb.INPUT_MAX


@njit
def _rows_in_range_kernel(M: Any, lo: int, hi: int, out: Any) -> None:
    """``out[p]``: every entry of the flat matrix ``M[p]`` is zero or in range, ``lo <= p < hi``."""
    for p in range(lo, hi):
        ok = True
        for k in range(M.shape[1]):
            a = abs(M[p, k])
            ok &= (a == 0.0) | ((a >= _IN_MIN) & (a <= _IN_MAX))
        out[p] = ok


def rows_in_range(floats: np.ndarray) -> np.ndarray:
    """Per matrix of a ``(n, 4, 4)`` binary64 stack: every entry is zero or of magnitude in
    ``[INPUT_MIN, INPUT_MAX]``.

    >>> rows_in_range(np.stack([np.eye(4), 1e300 * np.eye(4)])).tolist()
    [True, False]
    """
    M = np.ascontiguousarray(floats, dtype=np.float64).reshape(len(floats), -1)
    out = np.empty(len(M), dtype=np.bool_)
    if HAVE_NUMBA:
        run_parallel(lambda lo, hi: _rows_in_range_kernel(M, lo, hi, out), len(M))
    else:  # pragma: no cover - without numba
        a = np.abs(M)
        out[:] = ((a == 0) | ((a >= _IN_MIN) & (a <= _IN_MAX))).all(axis=1)
    return out
