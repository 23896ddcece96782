"""The matrices of a stack as integers, exactly: each matrix times its own positive scale (a
power of two for binary64 input, the least common denominator for exact input).  A positive
scale keeps every sign the package reads (of the pencil's coefficients, of a quadric at a
point), so the exact stages compute on integers."""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np

from quadric_contact.exact.entries import ENTRY_INDICES
from quadric_contact.modes.stacks.pairs import MatrixStack

__all__ = ["dyadic_integers", "dyadic_rows", "integer_rows"]


def integer_rows(stack: MatrixStack, rows: np.ndarray) -> list[np.ndarray]:
    """Each matrix as integers with its own positive scale (exact).

    Float input: every entry is ``m 2^e`` with an integer mantissa ``|m| < 2^53``;
    one power of two per matrix (the smallest exponent of its non-zero entries)
    makes all ten integers, found with ``numpy.frexp`` for the whole stack.
    Exact input: the least common denominator of each matrix.
    """
    if stack.exact is not None:
        out = [np.empty(len(rows), dtype=object) for _ in range(10)]
        for r, row in enumerate(stack.exact[rows]):
            fr = [Fraction(v) for v in row]
            d = 1
            for v in fr:
                d = d * v.denominator // math.gcd(d, v.denominator)
            for k, v in enumerate(fr):
                out[k][r] = v.numerator * (d // v.denominator)
        return out
    return dyadic_integers(*dyadic_rows(stack, rows))


def dyadic_integers(m: np.ndarray, shift: np.ndarray) -> list[np.ndarray]:
    """The ten columns of Python integers ``m * 2^shift``."""
    small = (shift <= 10).all(axis=1)
    ints = np.empty(m.shape, dtype=object)
    if small.any():  # 53 + 10 bits fit in int64
        ints[small] = (m[small] << shift[small]).astype(object)
    big = ~small
    if big.any():
        ints[big] = m[big].astype(object) << shift[big].astype(object)
    return [ints[:, k] for k in range(10)]


def dyadic_rows(stack: MatrixStack, rows: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The integers of :func:`integer_rows` for a binary64 stack as ``m * 2^shift``:
    two ``(k, 10)`` int64 arrays, ``|m| < 2^53`` and ``shift >= 0`` (``0`` where ``m = 0``)."""
    f = stack.rows_floats(np.asarray(rows))
    upper = np.stack([f[:, i, j] for i, j in ENTRY_INDICES], axis=1)
    mant, ex = np.frexp(upper)
    m = (mant * 2.0**53).astype(np.int64)  # exact: |mant| in [1/2, 1)
    e = np.where(m == 0, np.iinfo(np.int32).max, ex.astype(np.int64) - 53)
    emin = e.min(axis=1, keepdims=True)
    emin = np.where(emin == np.iinfo(np.int32).max, 0, emin)
    shift = np.where(m == 0, 0, e - emin)
    return m, shift
