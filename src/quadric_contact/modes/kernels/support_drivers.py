"""Array drivers of the support kernels that the lower modules share.

:func:`check_stack` (which matrices of a stack are not finite or not symmetric: the
validation of :mod:`~quadric_contact.modes.stacks.validation`) and
:func:`region_codes_from_signs` / :func:`region_from_signs` (Table 4's reading of the
signs of ``c0 .. c4`` for a quadric known by its row or its candidate rows, the
vectorised :func:`~quadric_contact.modes.decision.answers.region_code_masked`) run the numba
kernels of :mod:`~quadric_contact.modes.kernels.support`, or numpy without numba.
They sit below :mod:`~quadric_contact.modes.numbers.binary64` (which re-exports them) so
that the validation and the object modes call them without importing the float modes.
"""

from __future__ import annotations

import numpy as np

from quadric_contact.modes.decision.answers import ROWS, region_code_masked, rows_from_masks
from quadric_contact.modes.kernels._jit import HAVE_NUMBA
from quadric_contact.modes.kernels.support import check_stack_kernel, read_all_kernel, region_codes_kernel
from quadric_contact.modes.kernels.threads import run_parallel

__all__ = ["check_stack", "read_all", "region_codes_from_signs", "region_from_signs"]


def check_stack(M: np.ndarray) -> np.ndarray:
    """Per matrix: 0 fine, 1 a non-finite entry, 2 not symmetric."""
    out = np.empty(M.shape[0], dtype=np.int8)
    if HAVE_NUMBA:
        run_parallel(lambda lo, hi: check_stack_kernel(M, lo, hi, out), M.shape[0])
        return out
    finite = np.isfinite(M).all(axis=(1, 2))
    sym = (np.swapaxes(M, 1, 2) == M).all(axis=(1, 2))
    out[:] = np.where(~finite, 1, np.where(~sym, 2, 0))
    return out


def region_codes_from_signs(
    contact: np.ndarray, csigns: np.ndarray, rows: np.ndarray, masks: np.ndarray
) -> np.ndarray:
    """Region codes from contact codes, c-signs and the rows/masks of the quadrics (per pair)."""
    out = np.empty(contact.shape[0], dtype=np.int8)
    if HAVE_NUMBA:
        region_codes_kernel(contact, csigns, rows.astype(np.int16), masks.astype(np.int64), out)
        return out
    for p in range(contact.shape[0]):
        out[p] = region_code_masked(
            int(contact[p]), *(int(v) for v in csigns[p]), int(rows[p]), int(masks[p]), ROWS
        )
    return out


def region_from_signs(contact: np.ndarray, csigns: np.ndarray, masks: np.ndarray) -> np.ndarray:
    """Vectorised :func:`~quadric_contact.modes.decision.answers.region_code_masked`: ``contact``
    (n,), ``csigns`` (n, 5) for ``c0 .. c4``, ``masks`` (n,) the candidate rows of each
    pair's quadric."""
    masks = np.ascontiguousarray(masks, dtype=np.int64)
    return region_codes_from_signs(
        np.ascontiguousarray(contact, dtype=np.int8),
        np.ascontiguousarray(csigns, dtype=np.int8),
        rows_from_masks(masks),
        masks,
    )


def read_all(*arrays: np.ndarray, threads: int | None = None) -> float:
    """Read every byte of the arrays once (a compiled, threaded streaming sum): the
    memory-bandwidth floor of any kernel that reads them."""

    def one(flat: np.ndarray) -> float:
        parts: list[float] = []
        run_parallel(lambda lo, hi: parts.append(read_all_kernel(flat, lo, hi)), flat.shape[0], threads)
        return float(sum(parts))

    return sum(one(np.ascontiguousarray(a).reshape(-1)) for a in arrays)
