"""Exact linear algebra over a field: one Gauss-Jordan elimination for the
kernels and linear solves of the geometric decision (rationals) and of the
contact kinds (numbers ``a + b sqrt(d)``).

The field is given by two functions, ``is_zero`` and ``inverse``; the
defaults are those of :class:`fractions.Fraction` (and of ``int`` entries,
which the elimination turns into Fractions).

Examples
--------
>>> from fractions import Fraction as F
>>> nullspace([[F(1), F(2), F(3)], [F(2), F(4), F(6)]], zero=F(0), one=F(1))
[[Fraction(-2, 1), Fraction(1, 1), Fraction(0, 1)], [Fraction(-3, 1), Fraction(0, 1), Fraction(1, 1)]]
>>> solve([[F(2), F(0)], [F(0), F(0)]], [F(4), F(0)])
[Fraction(2, 1), Fraction(0, 1)]
>>> solve([[F(2), F(0)], [F(0), F(0)]], [F(4), F(1)]) is None
True
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from fractions import Fraction
from typing import Any

__all__ = ["nullspace", "row_reduce", "solve"]


def _is_zero(v: Any) -> bool:
    return bool(v == 0)


def _inverse(v: Any) -> Any:
    return Fraction(1) / v


def row_reduce(
    A: Sequence[Sequence[Any]],
    *,
    is_zero: Callable[[Any], bool] = _is_zero,
    inverse: Callable[[Any], Any] = _inverse,
) -> tuple[list[list[Any]], list[int]]:
    """The reduced row echelon form of ``A`` and its pivot columns."""
    m, n = len(A), len(A[0])
    R = [list(r) for r in A]
    pivots: list[int] = []
    row = 0
    for col in range(n):
        if row == m:
            break
        piv = next((i for i in range(row, m) if not is_zero(R[i][col])), None)
        if piv is None:
            continue
        R[row], R[piv] = R[piv], R[row]
        inv = inverse(R[row][col])
        R[row] = [v * inv for v in R[row]]
        for i in range(m):
            if i != row and not is_zero(R[i][col]):
                f = R[i][col]
                R[i] = [a - f * b for a, b in zip(R[i], R[row], strict=True)]
        pivots.append(col)
        row += 1
    return R, pivots


def nullspace(
    A: Sequence[Sequence[Any]],
    *,
    zero: Any,
    one: Any,
    is_zero: Callable[[Any], bool] = _is_zero,
    inverse: Callable[[Any], Any] = _inverse,
) -> list[list[Any]]:
    """A basis of the kernel of ``A``, one vector per free column."""
    n = len(A[0])
    R, pivots = row_reduce(A, is_zero=is_zero, inverse=inverse)
    basis = []
    for free in (c for c in range(n) if c not in pivots):
        v = [zero] * n
        v[free] = one
        for i, pc in enumerate(pivots):
            v[pc] = -R[i][free]
        basis.append(v)
    return basis


def solve(A: Sequence[Sequence[Fraction]], b: Sequence[Fraction]) -> list[Fraction] | None:
    """One rational solution of ``A y = b`` (free unknowns 0), or None if there is none."""
    n = len(A[0])
    R, pivots = row_reduce([[*A[i], b[i]] for i in range(len(A))])
    if n in pivots:  # a row 0 = 1
        return None
    y = [Fraction(0)] * n
    for i, pc in enumerate(pivots):
        y[pc] = R[i][n]
    return y
