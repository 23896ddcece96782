from decimal import Decimal
from fractions import Fraction

import mpmath
import numpy as np
import pytest
import sympy

from quadric_contact.exact.errors import NonFiniteError, NotANumberError, NotRationalError, ShapeError
from quadric_contact.exact.rational import as_square_matrix, common_denominator, to_fraction


@pytest.mark.parametrize(
    "value, expected",
    [
        (3, Fraction(3)),
        (Fraction(2, 7), Fraction(2, 7)),
        (0.5, Fraction(1, 2)),
        (0.1, Fraction(3602879701896397, 36028797018963968)),
        ("8.36291", Fraction(836291, 100000)),
        (" -1/3 ", Fraction(-1, 3)),
        ("1e-5", Fraction(1, 100000)),
        ("1/3 + 2/7", Fraction(13, 21)),
        (Decimal("0.25"), Fraction(1, 4)),
        (np.float64(0.75), Fraction(3, 4)),
        (np.float32(0.1), Fraction(float(np.float32(0.1)))),
        (np.int64(-4), Fraction(-4)),
        (np.array(2.5), Fraction(5, 2)),
        (sympy.Rational(5, 3), Fraction(5, 3)),
        (sympy.Integer(-2), Fraction(-2)),
        (sympy.Float(0.1), Fraction(0.1)),
        (sympy.sqrt(4), Fraction(2)),
        (mpmath.mpf("0.5"), Fraction(1, 2)),
    ],
)
def test_exact_conversion(value, expected):
    assert to_fraction(value) == expected


def test_float_is_taken_exactly_not_as_decimal():
    assert to_fraction(0.1) != Fraction(1, 10)
    assert to_fraction(0.1) == Fraction(*(0.1).as_integer_ratio())


@pytest.mark.parametrize(
    "value",
    [
        float("nan"),
        float("inf"),
        -float("inf"),
        "nan",
        "-inf",
        np.nan,
        Decimal("NaN"),
        sympy.oo,
        sympy.nan,
        mpmath.inf,
    ],
)
def test_non_finite(value):
    with pytest.raises(NonFiniteError) as info:
        to_fraction(value)
    assert isinstance(info.value, ValueError)


@pytest.mark.parametrize(
    "value", [True, np.bool_(False), 1j, "abc", "", "sqrt(2)", object(), None, [1], sympy.Symbol("x")]
)
def test_not_a_number(value):
    with pytest.raises(NotANumberError) as info:
        to_fraction(value)
    assert isinstance(info.value, TypeError)
    assert info.value.value is value


@pytest.mark.parametrize("value", [sympy.sqrt(2), sympy.pi])
def test_not_rational(value):
    with pytest.raises(NotRationalError):
        to_fraction(value)


def test_matrix_shape_and_entry_position():
    with pytest.raises(ShapeError):
        as_square_matrix([[1, 2], [3, 4]])
    with pytest.raises(ShapeError):
        as_square_matrix(np.zeros((4, 5)))
    with pytest.raises(ShapeError):
        as_square_matrix("not a matrix")
    bad = np.eye(4)
    bad[2, 1] = np.nan
    with pytest.raises(NonFiniteError) as info:
        as_square_matrix(bad)
    assert info.value.details["entry"] == (2, 1)


def test_common_denominator():
    nums, d = common_denominator([Fraction(1, 2), Fraction(1, 3), Fraction(5)])
    assert d == 6 and nums == (3, 2, 30)
