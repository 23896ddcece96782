"""Exact real algebraic numbers (quadric_contact.exact.algebraic) and the doctests
of the smallness, geometric, Segre and contact-kind modules."""

from __future__ import annotations

import doctest
import importlib
from fractions import Fraction

import pytest
import sympy
from hypothesis import given
from hypothesis import strategies as st

from quadric_contact.exact.algebraic import (
    QuadraticNumber,
    RealAlgebraic,
    algebraic_sqrt,
    algebraic_value,
    as_real_algebraic,
    compile_expression,
    real_roots,
    sign_at,
)

MODULES = [
    "exact.algebraic",
    "model.invariants",
    "theory.smallness",
    "theory.geometric",
    "theory.segre",
    "theory.contact_kind",
]


@pytest.mark.parametrize("name", MODULES)
def test_doctests(name):
    module = importlib.import_module(f"quadric_contact.{name}")
    result = doctest.testmod(module, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert result.failed == 0 and result.attempted > 0


def test_roots_and_equality():
    r2, r3, r6 = RealAlgebraic.sqrt(2), RealAlgebraic.sqrt(3), RealAlgebraic.sqrt(6)
    assert r2 * r3 == r6 and r2 * r2 == 2 and r2 + r3 != r6
    # (1 + sqrt 2)^2 = 3 + 2 sqrt 2, an equality between numbers built differently
    assert (1 + r2) ** 2 == 3 + 2 * r2
    assert (r2 + r3) ** 2 == 5 + 2 * r6
    assert algebraic_sqrt(3 + 2 * r2) == 1 + r2
    assert Fraction(140, 99) < r2 < Fraction(99, 70)  # 1.41414.. < sqrt 2 < 1.41428..
    assert r2 != Fraction(99, 70)


def test_cubic_roots_and_values():
    roots = real_roots([-1, -3, 0, 1])  # 2 cos(2 pi k / 9)-type roots
    assert len(roots) == 3 and roots[0] < roots[1] < roots[2]
    # the sum of the roots is 0 and their product is 1: exactly
    assert algebraic_value(lambda a, b, c: a + b + c, roots) == 0
    assert algebraic_value(lambda a, b, c: a * b * c, roots) == 1
    # a symmetric function of two of them: a b + a c + b c = -3
    assert algebraic_value(lambda a, b, c: a * b + a * c + b * c, roots) == -3
    x = sympy.Symbol("x")
    for r, k in zip(roots, range(3), strict=True):
        assert r.to_sympy() == sympy.CRootOf(x**3 - 3 * x - 1, k)


def test_sign_at_and_multiplicities():
    (r,) = [z for z in real_roots([-2, 0, 1]) if z > 0]
    assert sign_at([-2, 0, 1], r) == 0
    assert sign_at([0, 1], r) == 1 and sign_at([3, -2], r) == 1  # 3 - 2 sqrt 2 > 0
    assert sign_at([-3, 2], r) == -1
    pairs = real_roots([0, 0, -2, 0, 1], multiplicities=True)  # x^2 (x^2 - 2)
    assert [(str(p), m) for p, m in pairs if p.is_rational] == [("0", 2)]


def test_compile_expression_runs_on_several_types():
    a, b = sympy.symbols("a b")
    f = compile_expression((a + b) ** 2 / (2 * a) - sympy.Rational(1, 3), [a, b])
    assert f(Fraction(1), Fraction(2)) == Fraction(9, 2) - Fraction(1, 3)
    v = algebraic_value(f, [RealAlgebraic.sqrt(2), RealAlgebraic(1)])
    assert v == algebraic_value(lambda s: (s + 1) ** 2 / (2 * s) - Fraction(1, 3), [RealAlgebraic.sqrt(2)])


def test_tiny_and_huge_numbers():
    tiny = RealAlgebraic.sqrt(Fraction(2, 10**40))
    assert tiny.sign() == 1 and tiny > 0 and tiny < Fraction(1, 10**19)
    assert tiny.approx(5) == "1.4142e-20"
    assert algebraic_sqrt(tiny * tiny) == tiny


@given(st.fractions(-50, 50, max_denominator=20), st.fractions(0, 50, max_denominator=20))
def test_quadratic_numbers_against_real_algebraic(a, b):
    q = QuadraticNumber(a, b, 7)
    r = as_real_algebraic(q)
    assert q.sign() == r.sign()
    assert as_real_algebraic(q * q) == r * r
    if q:
        assert as_real_algebraic(q.inverse()) == 1 / r


def test_quadratic_number_errors():
    with pytest.raises(ValueError):
        QuadraticNumber(0, 1, 2) + QuadraticNumber(0, 1, 3)
    with pytest.raises(ZeroDivisionError):
        QuadraticNumber(0).inverse()
    with pytest.raises(ValueError):
        RealAlgebraic.sqrt(-1)


def test_a_ball_is_read_at_its_own_precision():
    """A ball computed at 300 bits around 1/3 does not meet a number 2^-200 away from 1/3 (read
    at 53 bits, its bounds would be 2^-52 apart and meet it)."""
    import flint

    from quadric_contact.exact.algebraic import _overlaps
    from quadric_contact.exact.precision import working_precision

    with working_precision(300):
        ball = flint.arb(1) / 3
    assert not _overlaps(RealAlgebraic(Fraction(1, 3) + Fraction(1, 2**200)), ball)
    assert _overlaps(RealAlgebraic(Fraction(1, 3)), ball)


def test_a_value_between_two_close_conjugates_is_found():
    """``1 + sqrt(2) / 2^80`` has the conjugate ``1 - sqrt(2) / 2^80``, 2^-78.5 away: the value is
    told from it by narrowing both candidates to the enclosure's width (with the candidates
    shrinking by a constant factor per doubling of the precision this took ~2^40 bits)."""
    r = algebraic_value(lambda x: 1 + x / 2**80, [RealAlgebraic.sqrt(Fraction(2))])
    t = sympy.Symbol("t")
    minpoly = sympy.Poly(sympy.expand((t - 1) ** 2 - sympy.Rational(2, 2**160)), t)
    assert r.minpoly == tuple(Fraction(int(c.p), int(c.q)) for c in reversed(minpoly.all_coeffs()))
    assert algebraic_value(lambda y: y - 1, [r]).sign() == 1


def test_algebraic_value_with_a_ball_holding_zero_in_a_power():
    # (x - x)^2 is 0: its ball holds 0, where arb's real power is NaN; the value is still found
    from quadric_contact.exact.algebraic import algebraic_value

    s2 = RealAlgebraic.sqrt(2)
    assert algebraic_value(lambda x: (x - x) ** 2 + x, [s2]) == s2
    assert algebraic_value(lambda x: (x - 1) ** 3, [s2]).compare(0) > 0


def test_integer_polynomial_numbers_equal_the_classic_ones():
    import flint

    # a number made from its primitive integer polynomial (the monic rational coefficients
    # formed only when read) is the same number as one made from them
    z = flint.fmpz_poly([-1, 0, 2])  # 2 x^2 - 1: the root 1/sqrt(2)
    x = RealAlgebraic._from_integer_polynomial(z, Fraction(1, 2), Fraction(1))
    y = RealAlgebraic.root_in([Fraction(-1, 2), 0, 1], Fraction(1, 2), Fraction(1))
    assert x.degree == 2 and not x.is_rational and x.sign() > 0 and x.decimal(8) == "0.70710678"
    assert x == y and hash(x) == hash(y) and x.minpoly == y.minpoly
    assert x.integer_poly == z == y.integer_poly and x.poly == y.poly
