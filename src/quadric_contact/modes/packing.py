"""The packed layout of symmetric 4x4 matrices: their ten upper entries.

A symmetric matrix is determined by ``(m00, m01, m02, m03, m11, m12, m13, m22, m23,
m33)`` (:data:`~quadric_contact.exact.entries.ENTRY_INDICES`, the order of the generated
formulas).  A stack kept packed, ``(..., 10)`` float64, is 80 bytes a matrix instead
of 128, needs no symmetry check, and is what the fast kernels read directly: pass
it to any array predicate wrapped as :class:`Packed` (``qc.transversal_contact(
qc.Packed(P), Q)``), or convert with :func:`unpack`.

>>> import numpy as np
>>> M = np.diag([1.0, 2.0, 3.0, -1.0])[None]
>>> pack(M)
array([[ 1.,  0.,  0.,  0.,  2.,  0.,  0.,  3.,  0., -1.]])
>>> bool((unpack(pack(M)) == M).all())
True
"""

from __future__ import annotations

from typing import Any

import numpy as np

from quadric_contact.exact.entries import ENTRY_INDICES
from quadric_contact.exact.errors import NotSymmetricError, ShapeError

__all__ = ["Packed", "pack", "unpack"]

_I = np.array([i for i, _ in ENTRY_INDICES])
_J = np.array([j for _, j in ENTRY_INDICES])
# for every entry (i, j) of a 4x4 matrix, row-major, the packed entry that holds it: unpacking
# is then one contiguous gather along the last axis (np.take), not a scatter
_FULL = np.array(
    [ENTRY_INDICES.index((min(i, j), max(i, j))) for i in range(4) for j in range(4)], dtype=np.intp
)


def pack(M: Any, *, check: bool = True) -> np.ndarray:
    """The ten upper entries of every symmetric matrix of ``M`` (``(..., 4, 4)`` -> ``(..., 10)``).

    Raises
    ------
    ShapeError
        If ``M`` is not ``(..., 4, 4)``.
    NotSymmetricError
        If a matrix is not symmetric (with ``check``, the default).
    """
    arr = np.asarray(M)
    if arr.ndim < 2 or arr.shape[-2:] != (4, 4):
        raise ShapeError(f"pack needs (..., 4, 4) matrices, got shape {arr.shape}", M)
    if check and not (arr == np.swapaxes(arr, -1, -2)).all():
        bad = np.argwhere(~(arr == np.swapaxes(arr, -1, -2)).all(axis=(-1, -2)).reshape(-1))
        raise NotSymmetricError(
            f"matrix {int(bad[0, 0])} of the stack is not symmetric", M, index=int(bad[0, 0])
        )
    return np.ascontiguousarray(arr[..., _I, _J])


def unpack(P: Any) -> np.ndarray:
    """The symmetric matrices of packed entries (``(..., 10)`` -> ``(..., 4, 4)``)."""
    arr = np.asarray(P)
    if arr.ndim < 1 or arr.shape[-1] != 10:
        raise ShapeError(f"unpack needs (..., 10) packed matrices, got shape {arr.shape}", P)
    return np.take(arr, _FULL, axis=-1).reshape(*arr.shape[:-1], 4, 4)


class Packed:
    """A stack of packed symmetric matrices, ``(..., 10)`` (see :func:`pack`), as input to the
    array predicates: the batch shape is ``array.shape[:-1]``.

    >>> import quadric_contact as qc, numpy as np
    >>> E = qc.pack(np.diag([1.0, 1.0, 1.0, -1.0])[None])
    >>> qc.transversal_contact(qc.Packed(E), np.diag([1.0, 1.0, 1.0, -4.0]))
    array([0], dtype=int8)
    """

    __slots__ = ("array",)

    def __init__(self, array: Any) -> None:
        arr = np.asarray(array)
        if arr.ndim < 1 or arr.shape[-1] != 10:
            raise ShapeError(f"Packed needs (..., 10) packed matrices, got shape {arr.shape}", array)
        self.array = arr

    @property
    def shape(self) -> tuple[int, ...]:
        """The batch shape."""
        return tuple(self.array.shape[:-1])

    def __len__(self) -> int:
        return int(np.prod(self.shape, dtype=np.int64))

    def __repr__(self) -> str:
        return f"Packed(shape={self.shape})"
