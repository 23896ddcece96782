"""Classification by exact inertia: minor sums, Sylvester's law, the types of Table 1."""

from __future__ import annotations

from fractions import Fraction as F

import sympy as sp
from hypothesis import given
from hypothesis import strategies as st

from quadric_contact import Quadric
from quadric_contact.model.classification import (
    TABLE_1_KINDS,
    QuadricKind,
    classify,
    inertia_from_minor_sums,
    principal_minor_sums_3,
    principal_minor_sums_4,
)
from quadric_contact.testing.strategies import quadrics, rationals

UPPER = [(i, j) for i in range(4) for j in range(i, 4)]
small = rationals(min_value=-3, max_value=3, max_denominator=4)


def _rational(v):
    return F(int(v.p), int(v.q))


@given(st.lists(small, min_size=10, max_size=10))
def test_minor_sums_are_the_characteristic_polynomial(upper):
    """``det(t I + M) = t^4 + E1 t^3 + E2 t^2 + E3 t + E4`` (sympy's determinant)."""
    M = sp.zeros(4, 4)
    for (i, j), v in zip(UPPER, upper, strict=True):
        M[i, j] = M[j, i] = sp.Rational(v.numerator, v.denominator)
    t = sp.Symbol("t")
    coeffs = sp.Poly((t * sp.eye(4) + M).det(), t).all_coeffs()  # t^4, t^3, ...
    assert list(principal_minor_sums_4(upper)) == [_rational(c) for c in coeffs[1:]]
    a = [upper[k] for k in (0, 1, 2, 4, 5, 7)]
    c3 = sp.Poly((t * sp.eye(3) + M[:3, :3]).det(), t).all_coeffs()
    assert list(principal_minor_sums_3(a)) == [_rational(c) for c in c3[1:]]


@given(
    st.lists(st.sampled_from([-2, -1, 0, 1, 3]), min_size=4, max_size=4),
    st.lists(st.integers(-3, 3), min_size=16, max_size=16),
)
def test_inertia_is_sylvesters(diagonal, entries):
    """``P^T D P`` has the inertia of ``D`` for every invertible ``P`` (Sylvester's law)."""
    P = sp.Matrix(4, 4, entries)
    if P.det() == 0:
        P = P + 7 * sp.eye(4)
    if P.det() == 0:
        return
    M = P.T * sp.diag(*diagonal) * P
    upper = [F(int(M[i, j])) for i, j in UPPER]
    ia = inertia_from_minor_sums(principal_minor_sums_4(upper))
    expected = (sum(d > 0 for d in diagonal), sum(d < 0 for d in diagonal), sum(d == 0 for d in diagonal))
    assert (ia.positive, ia.negative, ia.zero) == expected
    assert ia.rank == 4 - expected[2]


@given(st.sampled_from(TABLE_1_KINDS).flatmap(lambda k: st.tuples(st.just(k), quadrics(kind=k))))
def test_every_table_1_type_is_recognised_moved_and_negated(pair):
    kind, q = pair
    found, sign = classify(q.upper)
    assert found is kind
    found_neg, sign_neg = classify((-q).upper)
    assert found_neg is kind
    if kind in (QuadricKind.HYPERBOLIC_PARABOLOID, QuadricKind.PLANE):
        assert sign == sign_neg == 1  # congruent to its own negative: the sign is +1 by convention
    else:
        assert sign_neg == -sign


def test_the_standard_forms_have_canonical_sign_one():
    for kind in TABLE_1_KINDS:
        if kind is QuadricKind.PLANE:
            q = Quadric.plane((0, 0, 1), 0)
        else:
            names = Quadric.standard_parameters(kind)
            q = Quadric.standard(kind, **dict(zip(names, (3, 2, 1), strict=False)))
        assert classify(q.upper) == (kind, 1), kind


def test_degenerate_and_imaginary_types():
    cases = {
        "x**2 + y**2 - z**2": QuadricKind.CONE,
        "x**2 + y**2 + z**2 + 1": QuadricKind.IMAGINARY_ELLIPSOID,
        "x**2 - y**2": QuadricKind.INTERSECTING_PLANES,
        "x**2": QuadricKind.COINCIDENT_PLANES,
        "x**2 + y**2 + 1": QuadricKind.IMAGINARY_ELLIPTIC_CYLINDER,
    }
    for eq, kind in cases.items():
        assert classify(Quadric.from_equation(eq).upper)[0] is kind, eq
