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

import cmath
from decimal import Decimal
from fractions import Fraction
from typing import Any

import numpy as np

from quadric_contact.exact.entries import ENTRY_INDICES
from quadric_contact.exact.errors import SYMMETRIZE_HINT, NonFiniteError, NotSymmetricError, ShapeError
from quadric_contact.exact.rational import to_fraction

__all__ = ["Packed", "pack", "symmetrize", "unpack"]

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
    NonFiniteError
        If an entry is NaN or an infinity (with ``check``, the default).
    NotSymmetricError
        If a matrix is not symmetric (with ``check``, the default).
    """
    arr = np.asarray(M)
    if arr.ndim < 2 or arr.shape[-2:] != (4, 4):
        raise ShapeError(f"pack needs (..., 4, 4) matrices, got shape {arr.shape}", M)
    if check:
        _check_finite(arr, M)
    if check and not (arr == np.swapaxes(arr, -1, -2)).all():
        bad = np.argwhere(~(arr == np.swapaxes(arr, -1, -2)).all(axis=(-1, -2)).reshape(-1))
        raise NotSymmetricError(
            f"matrix {int(bad[0, 0])} of the stack is not symmetric; {SYMMETRIZE_HINT}",
            M,
            index=int(bad[0, 0]),
        )
    return np.ascontiguousarray(arr[..., _I, _J])


def _check_finite(arr: np.ndarray, M: Any) -> None:
    """Raise :class:`NonFiniteError` naming the first NaN or infinite entry of ``arr``
    (``(..., 4, 4)``): its matrix in the flattened stack and its ``(i, j)``."""
    if arr.dtype.kind in "fc":
        bad = ~np.isfinite(arr)
    elif arr.dtype.kind == "O":
        bad = np.frompyfunc(_non_finite, 1, 1)(arr).astype(bool)
    else:
        return
    if not bad.any():
        return
    k, i, j = (int(v) for v in np.argwhere(bad.reshape(-1, 4, 4))[0])
    value = arr.reshape(-1, 4, 4)[k, i, j]
    value = value.item() if isinstance(value, np.generic) else value
    where = "the matrix" if arr.ndim == 2 else f"matrix {k} of the stack"
    raise NonFiniteError(f"{where} has a non-finite entry at ({i}, {j}): {value!r}", M, entry=(i, j), index=k)


def _non_finite(x: Any) -> bool:
    """A NaN or an infinity among the numbers an object array may hold."""
    if isinstance(x, (float, complex, np.floating, np.complexfloating)):
        return not cmath.isfinite(x)
    if isinstance(x, Decimal):
        return not x.is_finite()
    return False


def symmetrize(M: Any) -> np.ndarray:
    """The symmetric part ``(M + M^T) / 2`` of a matrix or a stack ``(..., 4, 4)``, exactly.

    The symmetric part has the same quadratic form ``X^T M X`` as ``M``.  Nothing is
    symmetrised unless this is called (or ``Quadric.from_matrix(M, symmetrize=True)``
    for one matrix): an asymmetric input is refused with :class:`NotSymmetricError`.

    Parameters
    ----------
    M : array-like, shape (4, 4) or (..., 4, 4)
        Numbers of any form the predicates take (binary64, integers, Fractions,
        decimal strings).

    Returns
    -------
    numpy.ndarray, shape of ``M``
        float64 when ``M`` is binary64 and every mean is a binary64 number (always the
        case for a symmetric stack); otherwise an object array of exact
        :class:`~fractions.Fraction` means, which the predicates read exactly.  The mean
        of two neighbouring binary64 numbers (``R @ D @ R.T`` differing in the last bit)
        lies halfway between them and is not binary64: it stays exact.

    Raises
    ------
    ShapeError
        If ``M`` is not ``(..., 4, 4)``.
    NotANumberError, NonFiniteError, NotRationalError
        For an entry that is not a finite rational number (non-binary64 input).

    Examples
    --------
    >>> import numpy as np
    >>> M = np.array([[1.0, 2.0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, -1]])
    >>> symmetrize(M)[0]
    array([1., 1., 0., 0.])
    >>> a = 0.1
    >>> b = np.nextafter(a, 1.0)
    >>> S = symmetrize(np.array([[1, a, 0, 0], [b, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, -1]]))
    >>> S.dtype, S[0, 1] == S[1, 0] == (Fraction(a) + Fraction(b)) / 2
    (dtype('O'), True)
    """
    arr = np.asarray(M)
    if arr.ndim < 2 or arr.shape[-2:] != (4, 4):
        raise ShapeError(f"symmetrize needs (..., 4, 4) matrices, got shape {arr.shape}", M)
    if arr.dtype.kind == "f" and arr.dtype.itemsize <= 8:
        floats = arr.astype(np.float64)
        transposed = np.swapaxes(floats, -1, -2)
        differ = (floats != transposed) & np.isfinite(floats) & np.isfinite(transposed)
        out = floats.copy()
        if not differ.any():
            return out
        where = np.argwhere(differ)
        means = [(Fraction(floats[tuple(k)]) + Fraction(transposed[tuple(k)])) / 2 for k in where]
        if all(Fraction(float(m)) == m for m in means):
            for k, m in zip(where, means, strict=True):
                out[tuple(k)] = float(m)
            return out
        exact = out.astype(object)
        for k, m in zip(where, means, strict=True):
            exact[tuple(k)] = m
        return exact
    exact = np.frompyfunc(to_fraction, 1, 1)(arr.astype(object) if arr.dtype.kind != "O" else arr)
    exact = np.asarray(exact, dtype=object)
    return (exact + np.swapaxes(exact, -1, -2)) / 2


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
