"""Exact conversion of user numbers and matrices to rationals.

Every number that enters the package is turned into a :class:`fractions.Fraction`
*exactly*: a float is the dyadic rational it stores (``0.1`` is
``3602879701896397/36028797018963968``), a decimal string is the decimal it
spells (``"0.1"`` is ``1/10``; strings are read by the package's parser,
:mod:`quadric_contact.parsing`, never evaluated), a sympy ``Rational`` is
itself.  Nothing is
rounded, so every answer the exact layer gives is exact *for the numbers the
caller passed*.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Iterable, Sequence
from decimal import Decimal
from fractions import Fraction
from typing import Any

from .errors import NonFiniteError, NotANumberError, NotRationalError, ShapeError

__all__ = [
    "as_square_matrix",
    "common_denominator",
    "to_fraction",
]


def _from_string(s: str) -> Fraction:
    """A number written as text, read by the package's own parser
    (:func:`~quadric_contact.parsing.parse_number`): never evaluated."""
    from .parsing import parse_number

    low = s.strip().lower().lstrip("+-")
    if low in {"nan", "inf", "infinity"}:
        raise NonFiniteError(f"{s!r} is not finite", s)
    return parse_number(s)


def _from_sympy(expr: Any, original: Any = None) -> Fraction:
    import sympy

    original = expr if original is None else original
    if expr.has(sympy.nan) or expr.has(sympy.zoo) or expr.has(sympy.oo) or expr.has(-sympy.oo):
        raise NonFiniteError(f"{original!r} is not finite", original)
    if isinstance(expr, sympy.Rational):
        return Fraction(int(expr.p), int(expr.q))
    if isinstance(expr, sympy.Float):
        # A sympy Float is a binary floating-point number: take it exactly.
        exact = sympy.Rational(expr)
        return Fraction(int(exact.p), int(exact.q))
    if getattr(expr, "is_number", False):
        if expr.is_real is False:
            raise NotANumberError(f"{original!r} is not a real number", original)
        simplified = sympy.simplify(expr)
        if isinstance(simplified, sympy.Rational):
            return Fraction(int(simplified.p), int(simplified.q))
        raise NotRationalError(f"{original!r} is a real number but not a rational one", original)
    raise NotANumberError(f"{original!r} is not a number (free symbols?)", original)


def to_fraction(value: Any) -> Fraction:
    """Convert one real number to an exact :class:`~fractions.Fraction`.

    Parameters
    ----------
    value : int, Fraction, float, Decimal, str, numpy scalar, sympy number, mpmath mpf, flint fmpq
        Floats are taken as the exact dyadic rationals they store; strings are
        read by :func:`~quadric_contact.parsing.parse_number` as exact
        decimals, fractions or small exact expressions (``"8.36291"``,
        ``"1/3"``, ``"1e-5"``, ``"1/3 + 2/7"``), never evaluated.

    Returns
    -------
    Fraction

    Raises
    ------
    NotANumberError
        For booleans, complex numbers, strings the parser refuses (the
        message names the offending text and its position) and other objects.
    NonFiniteError
        For NaN and infinities.
    NotRationalError
        For exact irrationals such as ``sympy.sqrt(2)``.

    Examples
    --------
    >>> to_fraction("8.36291")
    Fraction(836291, 100000)
    >>> to_fraction(0.5)
    Fraction(1, 2)
    >>> to_fraction(0.1) == Fraction(1, 10)
    False
    """
    if isinstance(value, Fraction):
        return value
    if isinstance(value, bool):
        raise NotANumberError("a boolean is not accepted as a number", value)
    if isinstance(value, int):
        return Fraction(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            raise NonFiniteError(f"{value!r} is not finite", value)
        return Fraction(value)
    if isinstance(value, str):
        return _from_string(value)
    if isinstance(value, Decimal):
        if not value.is_finite():
            raise NonFiniteError(f"{value!r} is not finite", value)
        return Fraction(value)
    if isinstance(value, complex) or (
        isinstance(value, numbers.Complex) and not isinstance(value, numbers.Real)
    ):
        raise NotANumberError(f"{value!r} is complex, not real", value)
    mod = type(value).__module__ or ""
    if mod.startswith("numpy"):
        import numpy as np

        if isinstance(value, np.bool_) or getattr(value, "dtype", None) == np.bool_:
            raise NotANumberError("a boolean is not accepted as a number", value)
        if isinstance(value, np.ndarray):
            if value.shape != ():
                raise NotANumberError(f"an array of shape {value.shape} is not a number", value)
            return to_fraction(value.item())
        if isinstance(value, np.integer):
            return Fraction(int(value))
        if isinstance(value, np.floating):
            return to_fraction(float(value)) if value.dtype.itemsize <= 8 else _longdouble(value)
        if isinstance(value, np.complexfloating):
            raise NotANumberError(f"{value!r} is complex, not real", value)
        return to_fraction(value.item())
    if mod.startswith("sympy"):
        return _from_sympy(value)
    if mod.startswith("mpmath"):
        import mpmath

        if isinstance(value, mpmath.mpf):
            if not mpmath.isfinite(value):
                raise NonFiniteError(f"{value!r} is not finite", value)
            man, exp = value.man_exp
            return Fraction(int(man)) * Fraction(2) ** int(exp)
        raise NotANumberError(f"{value!r} is not a real mpmath number", value)
    if mod.startswith("flint"):
        name = type(value).__name__
        if name == "fmpz":
            return Fraction(int(value))
        if name == "fmpq":
            return Fraction(int(value.p), int(value.q))
        raise NotANumberError(f"{value!r} ({name}) is not an exact rational", value)
    if isinstance(value, numbers.Rational):
        return Fraction(int(value.numerator), int(value.denominator))
    if isinstance(value, numbers.Real):
        f = float(value)
        if not math.isfinite(f):
            raise NonFiniteError(f"{value!r} is not finite", value)
        return Fraction(f)
    raise NotANumberError(f"{value!r} of type {type(value).__name__} is not a number", value)


def _longdouble(value: Any) -> Fraction:
    import numpy as np

    if not np.isfinite(value):
        raise NonFiniteError(f"{value!r} is not finite", value)
    num, den = value.as_integer_ratio()
    return Fraction(int(num), int(den))


def _rows(matrix: Any) -> list[list[Any]]:
    """Turn a matrix-like object into a list of rows without losing exactness."""
    mod = type(matrix).__module__ or ""
    if mod.startswith("numpy"):
        import numpy as np

        arr = np.asarray(matrix)
        if arr.ndim != 2:
            raise ShapeError(f"expected a 2-d matrix, got shape {arr.shape}", matrix)
        if arr.dtype.kind == "c":
            raise NotANumberError("a complex array is not a real matrix", matrix)
        return [list(row) for row in arr.tolist()] if arr.dtype.kind in "biuf" else [list(row) for row in arr]
    if mod.startswith("sympy"):
        shape = getattr(matrix, "shape", None)
        if shape is None or len(shape) != 2:
            raise ShapeError("expected a sympy Matrix", matrix)
        return [[matrix[i, j] for j in range(shape[1])] for i in range(shape[0])]
    if mod.startswith("flint"):
        return [[matrix[i, j] for j in range(matrix.ncols())] for i in range(matrix.nrows())]
    if isinstance(matrix, str) or not isinstance(matrix, Iterable):
        raise ShapeError(f"expected a matrix (nested sequences), got {type(matrix).__name__}", matrix)
    rows = []
    for row in matrix:
        if isinstance(row, str) or not isinstance(row, Iterable):
            raise ShapeError("expected a matrix (a sequence of rows)", matrix)
        rows.append(list(row))
    return rows


def as_square_matrix(matrix: Any, n: int = 4) -> tuple[tuple[Fraction, ...], ...]:
    """Convert a matrix-like object to an ``n x n`` tuple of Fractions.

    Raises :class:`ShapeError` when the shape is wrong and the errors of
    :func:`to_fraction` for bad entries (their ``details['entry']`` is the
    position).
    """
    rows = _rows(matrix)
    if len(rows) != n or any(len(r) != n for r in rows):
        shape = (len(rows), *sorted({len(r) for r in rows}))
        raise ShapeError(f"expected a {n}x{n} matrix, got shape {shape}", matrix)
    out = []
    for i, row in enumerate(rows):
        conv = []
        for j, entry in enumerate(row):
            try:
                conv.append(to_fraction(entry))
            except (NotANumberError, NonFiniteError, NotRationalError) as exc:
                raise type(exc)(f"entry ({i}, {j}): {exc}", matrix, entry=(i, j)) from exc
        out.append(tuple(conv))
    return tuple(out)


def common_denominator(values: Sequence[Fraction]) -> tuple[tuple[int, ...], int]:
    """Return ``(numerators, d)`` with ``values[k] == numerators[k] / d`` and ``d > 0``
    the least common denominator.

    Examples
    --------
    >>> common_denominator([Fraction(1, 2), Fraction(1, 3), Fraction(5)])
    ((3, 2, 30), 6)
    """
    d = math.lcm(*(v.denominator for v in values)) if values else 1
    return tuple(v.numerator * (d // v.denominator) for v in values), d
