"""Exact linear algebra over Q (row reduction, kernels, one solution), checked against sympy."""

from __future__ import annotations

from fractions import Fraction as F

import sympy as sp
from hypothesis import given
from hypothesis import strategies as st

from quadric_contact.exact.linalg import nullspace, row_reduce, solve
from quadric_contact.testing.strategies import rationals


@st.composite
def matrices(draw, max_rows: int = 4, max_cols: int = 5):
    """Rational matrices, often rank-deficient (a row is a combination of others)."""
    m = draw(st.integers(1, max_rows))
    n = draw(st.integers(1, max_cols))
    small = rationals(min_value=-3, max_value=3, max_denominator=4)
    rows = [draw(st.lists(small, min_size=n, max_size=n)) for _ in range(m)]
    if m >= 2 and draw(st.booleans()):
        a, b = draw(small), draw(small)
        rows[-1] = [a * x + b * y for x, y in zip(rows[0], rows[1], strict=True)]
    return rows


def _sympy(rows):
    return sp.Matrix([[sp.Rational(v.numerator, v.denominator) for v in r] for r in rows])


@given(matrices())
def test_row_reduce_is_sympys_rref(A):
    R, pivots = row_reduce(A)
    S, spivots = _sympy(A).rref()
    assert list(pivots) == list(spivots)
    assert _sympy(R) == S


@given(matrices())
def test_nullspace_is_a_basis_of_the_kernel(A):
    basis = nullspace(A, zero=F(0), one=F(1))
    n = len(A[0])
    assert len(basis) == n - _sympy(A).rank()  # rank-nullity
    for v in basis:
        assert all(sum((a * x for a, x in zip(row, v, strict=True)), F(0)) == 0 for row in A)
    if basis:
        assert _sympy([list(v) for v in basis]).rank() == len(basis)  # independent


@given(matrices(), st.data())
def test_solve_finds_a_solution_exactly_when_there_is_one(A, data):
    m = len(A)
    b = data.draw(st.lists(rationals(min_value=-3, max_value=3), min_size=m, max_size=m))
    y = solve(A, b)
    consistent = _sympy(A).rank() == _sympy([[*A[i], b[i]] for i in range(m)]).rank()  # Rouche-Capelli
    assert (y is not None) == consistent
    if y is not None:
        assert [sum((a * x for a, x in zip(row, y, strict=True)), F(0)) for row in A] == list(b)


def test_kernel_of_a_known_matrix():
    # x + 2y + 3z = 0 and 2x + 4y + 6z = 0: a plane through 0, spanned by (-2, 1, 0), (-3, 0, 1)
    A = [[F(1), F(2), F(3)], [F(2), F(4), F(6)]]
    assert nullspace(A, zero=F(0), one=F(1)) == [[F(-2), F(1), F(0)], [F(-3), F(0), F(1)]]
    assert solve(A, [F(1), F(3)]) is None
