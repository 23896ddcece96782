"""Exact conversion of user numbers and matrices to rationals.

Every number that enters the package is turned into a :class:`fractions.Fraction`
*exactly*: a float is the dyadic rational it stores (``0.1`` is
``3602879701896397/36028797018963968``), a decimal string is the decimal it
spells (``"0.1"`` is ``1/10``; strings are read by the package's parser,
:mod:`quadric_contact.exact.reading`, never evaluated), a sympy ``Rational`` is
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

import flint
import mpmath
import numpy as np

from quadric_contact.exact.bounds import MAX_DIGITS
from quadric_contact.exact.errors import (
    NonFiniteError,
    NotANumberError,
    NotRationalError,
    ShapeError,
)
from quadric_contact.exact.reading import parse_number

__all__ = [
    "as_square_matrix",
    "common_denominator",
    "dyadic_between",
    "fmpq_of",
    "fmpq_poly_of",
    "fraction_of",
    "monic",
    "near_midpoint",
    "sign",
    "simplest_between",
    "to_fraction",
]


_LIMIT = 10**MAX_DIGITS
_LIMIT_BITS = _LIMIT.bit_length()


def _from_string(s: str) -> Fraction:
    """A number written as text, read by the package's own parser
    (:func:`~quadric_contact.exact.reading.parse_number`): never evaluated."""
    low = s.strip().lower().lstrip("+-")
    if low in {"nan", "inf", "infinity"}:
        raise NonFiniteError(f"{s!r} is not finite", s)
    return parse_number(s)


def _from_sympy(expr: Any, original: Any = None) -> Fraction:
    import sympy  # sympy is heavy: only for sympy input

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
        read by :func:`~quadric_contact.exact.reading.parse_number` as exact
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
    return _bounded(_to_fraction(value), value)


def _bounded(x: Fraction, value: Any) -> Fraction:
    """``x``, a plain Fraction, if its numerator and denominator have at most
    :data:`~quadric_contact.exact.bounds.MAX_DIGITS` digits (compared by bit
    length first: no conversion to text)."""
    big = x.numerator.bit_length() >= _LIMIT_BITS - 1 or x.denominator.bit_length() >= _LIMIT_BITS - 1
    if big and (abs(x.numerator) >= _LIMIT or x.denominator >= _LIMIT):
        raise NotANumberError(
            f"a number of type {type(value).__name__} with more than {MAX_DIGITS} digits in its "
            "numerator or denominator (MAX_DIGITS)",
            value,
        )
    return x


def _plain_int(n: Any) -> int:
    """An ``int`` (or subclass) as a plain int, read by ``int``'s own method: a
    subclass cannot change its value through ``__int__`` or ``numerator``."""
    return int.__int__(n)


def _to_fraction(value: Any) -> Fraction:
    # Subclasses of the built-in types are read through the base type's own methods
    # and become plain values: their overrides (a lying __len__, their own
    # comparisons or as_integer_ratio) never reach the package.
    if isinstance(value, bool):
        raise NotANumberError("a boolean is not accepted as a number", value)
    if isinstance(value, Fraction):
        if type(value) is Fraction:
            return value
        num, den = Fraction.numerator.fget(value), Fraction.denominator.fget(value)  # type: ignore[attr-defined]
        return Fraction(_plain_int(num), _plain_int(den))
    if isinstance(value, int):
        return Fraction(_plain_int(value))
    if isinstance(value, float):
        f = float.__float__(value)
        if not math.isfinite(f):
            raise NonFiniteError(f"{f!r} is not finite", f)
        return Fraction(*float.as_integer_ratio(f))
    if isinstance(value, str):
        return _from_string(str.__str__(value))
    if isinstance(value, Decimal):
        if not Decimal.is_finite(value):
            raise NonFiniteError(f"{Decimal.__str__(value)!r} is not finite", value)
        sign, digits, exponent = Decimal.as_tuple(value)
        if len(digits) > MAX_DIGITS or not -2 * MAX_DIGITS <= int(exponent) <= MAX_DIGITS:
            raise NotANumberError(
                f"a Decimal with {len(digits)} digits and exponent {int(exponent)}: more than {MAX_DIGITS} "
                "digits (MAX_DIGITS)",
                value,
            )
        return Fraction(*Decimal.as_integer_ratio(value))
    if isinstance(value, complex) or (
        isinstance(value, numbers.Complex) and not isinstance(value, numbers.Real)
    ):
        raise NotANumberError(f"{value!r} is complex, not real", value)
    mod = type(value).__module__ or ""
    if mod.startswith("numpy"):
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
        if isinstance(value, mpmath.mpf):
            if not mpmath.isfinite(value):
                raise NonFiniteError(f"{value!r} is not finite", value)
            man, exp = value.man_exp
            if abs(int(exp)) > _LIMIT_BITS:  # refused before 2**exp is formed
                message = f"an mpf of binary exponent {int(exp)}: more than {MAX_DIGITS} digits (MAX_DIGITS)"
                raise NotANumberError(message, value)
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
    if not np.isfinite(value):
        raise NonFiniteError(f"{value!r} is not finite", value)
    num, den = value.as_integer_ratio()
    return Fraction(int(num), int(den))


def _rows(matrix: Any) -> list[list[Any]]:
    """Turn a matrix-like object into a list of rows without losing exactness."""
    mod = type(matrix).__module__ or ""
    if mod.startswith("numpy"):
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


def sign(x: Any) -> int:
    """-1, 0 or 1: the sign of an exactly ordered number (Fraction, int, fmpq, ...).

    Examples
    --------
    >>> sign(Fraction(-1, 3)), sign(0), sign(7)
    (-1, 0, 1)
    """
    return (x > 0) - (x < 0)


# -- exact flint numbers -----------------------------------------------------------------


def fmpq_of(x: Any) -> Any:
    """A rational as ``flint.fmpq`` (an ``fmpq`` is returned as it is).

    Parameters
    ----------
    x : Fraction, int, flint.fmpz or flint.fmpq

    Examples
    --------
    >>> fmpq_of(Fraction(-3, 4))
    -3/4
    """
    if type(x) is Fraction:  # the common case first, without building a new Fraction
        return flint.fmpq(x.numerator, x.denominator)
    if isinstance(x, flint.fmpq):
        return x
    if isinstance(x, flint.fmpz):
        return flint.fmpq(x)
    x = Fraction(x)
    return flint.fmpq(x.numerator, x.denominator)


def fraction_of(x: Any) -> Fraction:
    """An exact flint number (``fmpq``, ``fmpz``, or an exact ``arb``/``arf``) as a Fraction.

    Examples
    --------
    >>> fraction_of(flint.fmpq(3, 4)), fraction_of(flint.arb(0.75).mid())
    (Fraction(3, 4), Fraction(3, 4))
    """
    if isinstance(x, flint.fmpq):
        return Fraction(int(x.p), int(x.q))
    if isinstance(x, flint.fmpz):
        return Fraction(int(x))
    if isinstance(x, flint.arb):
        if not x.is_exact():
            raise ValueError(f"the ball {x} is not an exact number")
        x = x.mid()
    man, exp = x.man_exp()
    man, exp = int(man), int(exp)
    return Fraction(man * 2**exp) if exp >= 0 else Fraction(man, 2**-exp)


def fmpq_poly_of(coeffs: Sequence[Any]) -> Any:
    """``flint.fmpq_poly`` from exact coefficients ``c0, c1, ...`` (lowest degree first).

    Examples
    --------
    >>> fmpq_poly_of([Fraction(-1, 2), 0, 1])
    x^2 + (-1/2)
    """
    return flint.fmpq_poly([fmpq_of(c) for c in coeffs])


def monic(p: Any) -> Any:
    """The monic multiple of a nonzero polynomial over Q (``fmpq_poly``).

    Examples
    --------
    >>> monic(fmpq_poly_of([1, 2]))
    x + 1/2
    """
    p = flint.fmpq_poly(p)
    return p / p.leading_coefficient()


# -- simple rationals in an interval ---------------------------------------------------


def simplest_between(a: Fraction, b: Fraction) -> Fraction:
    """The rational with the smallest denominator in the open interval ``(a, b)``.

    Examples
    --------
    >>> simplest_between(Fraction(31, 10), Fraction(33, 10)), simplest_between(Fraction(1, 3), Fraction(1, 2))
    (Fraction(13, 4), Fraction(2, 5))
    """
    if not a < b:
        raise ValueError(f"empty interval ({a}, {b})")
    if a < 0 < b:
        return Fraction(0)
    if b <= 0:
        return -simplest_between(-b, -a)
    n = math.floor(a) + 1  # smallest integer > a
    if n < b:
        return Fraction(n)
    fl = n - 1
    lo, hi = a - fl, b - fl  # 0 <= lo < hi <= 1
    if lo == 0:
        return fl + Fraction(1, math.floor(1 / hi) + 1)
    return fl + 1 / simplest_between(1 / hi, 1 / lo)


def dyadic_between(lo: Fraction, hi: Fraction) -> Fraction:
    """A short dyadic rational ``m / 2^k`` (smallest ``k``) in the open interval ``(lo, hi)``.

    Examples
    --------
    >>> dyadic_between(Fraction(31, 10), Fraction(33, 10)), dyadic_between(Fraction(1, 3), Fraction(2))
    (Fraction(13, 4), Fraction(1, 1))
    """
    if not lo < hi:
        raise ValueError(f"empty interval ({lo}, {hi})")
    w = hi - lo
    k = max(0, w.denominator.bit_length() - w.numerator.bit_length() + 1)  # 2^-k < w
    best = None
    while k >= 0:
        m = math.floor(lo * (1 << k)) + 1
        x = Fraction(m, 1 << k)
        if not x < hi:
            break
        best = x
        k -= 1
    assert best is not None
    return best


def near_midpoint(lo: Fraction, hi: Fraction) -> Fraction:
    """A rational with a small (power-of-two) denominator strictly inside ``(lo, hi)``,
    within a quarter of the width from the middle (the middle itself if none is).

    Bisecting at it halves an interval about as well as the midpoint does while
    keeping the sizes of the ends small.

    Examples
    --------
    >>> near_midpoint(Fraction(1, 3), Fraction(2, 3)), near_midpoint(Fraction(0), Fraction(1, 1000))
    (Fraction(1, 2), Fraction(1, 2048))
    """
    w = hi - lo
    # a power-of-two grid finer than a quarter of the width (floor(log2 w) from the bit
    # lengths: w may be far below the smallest float)
    if w > 0:
        e = w.numerator.bit_length() - w.denominator.bit_length()
        if Fraction(2) ** e > w:
            e -= 1
        k = max(0, -e + 2)
    else:
        k = 0
    den = 2**k
    mid = (lo + hi) / 2
    cand = Fraction(round(mid * den), den)
    if lo < cand < hi:
        return cand
    return mid


def coprime_fraction(n: int, d: int) -> Fraction:
    """``Fraction(n, d)`` for integers already in lowest terms with ``d > 0`` (as
    ``float.as_integer_ratio`` gives them), without the gcd: a fifth of the time, which the
    exact path pays twenty times a pair on binary64 input.

    >>> coprime_fraction(3, 4) == Fraction(3, 4), hash(coprime_fraction(-1, 8)) == hash(Fraction(-1, 8))
    (True, True)
    """
    if _FROM_COPRIME is not None:
        return _FROM_COPRIME(n, d)
    f = object.__new__(Fraction)
    f._numerator = n  # type: ignore[attr-defined]
    f._denominator = d  # type: ignore[attr-defined]
    return f


_FROM_COPRIME = getattr(Fraction, "_from_coprime_ints", None)
