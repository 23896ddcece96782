"""Theorem 14, eq. (12), Corollary 15 (with its misprint) and Remark 16."""

from fractions import Fraction

import pytest
import sympy as sp
from hypothesis import given

from quadric_contact import Quadric, Region, characteristic_polynomial, paper, plane_side
from quadric_contact.testing.strategies import ellipsoids, planes


def test_eq_12_symbolically():
    r, zc, lam = sp.symbols("r z_c lambda", positive=True)
    S = sp.Matrix([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, -zc], [0, 0, -zc, zc**2 - r**2]]) / r**2
    P0 = sp.Matrix([[0, 0, 0, 0], [0, 0, 0, 0], [0, 0, 0, sp.Rational(1, 2)], [0, 0, sp.Rational(1, 2), 0]])
    printed = sp.sympify(
        paper.PRINTED["eq. (12)"].replace("lambda", "lam"), locals={"lam": lam, "r": r, "z_c": zc}
    )
    assert sp.simplify((lam * S + P0).det() - printed) == 0


@given(e=ellipsoids(), p=planes())
def test_corollary_15_agrees_with_remark_16_and_root_classification(e, p):
    side = plane_side(e, p)
    P = side.polynomial
    assert P[0] == 0 and P[1] == 0
    # Transversal contact iff non-real roots (Theorem 14) iff c3^2 < 4 c4 c2 (corrected Corollary 15).
    assert (side.zone is Region.CONTACT) == (not P.structure.all_real) == (side.discriminant < 0)
    if side.zone is not Region.CONTACT:
        # Remark 16: the sign of the plane's equation at the centre decides, and agrees.
        assert (side.center_value > 0) == (side.zone is Region.R_PLUS)
        assert side.center_value != 0


@given(e=ellipsoids(), p=planes())
def test_corollary_15_misprint(e, p):
    side = plane_side(e, p)
    c0, c1, c2, c3, c4 = side.polynomial.coefficients
    printed_condition = c3 * c3 < 4 * c1 * c2  # as printed: never true, c1 = 0
    assert printed_condition is False
    assert any(x.key == "corollary-15-c1" for x in paper.ERRATA)


def test_remark_16_c3_formula():
    a, b, c, d, al, be, ga, xc, yc, zc = (Fraction(v) for v in (1, -2, 3, 5, 2, 3, Fraction(1, 2), 1, 1, -1))
    E = Quadric.ellipsoid(al, be, ga, center=(xc, yc, zc))
    P = characteristic_polynomial(E, Quadric.plane((a, b, c), d))
    assert P[3] == (a * xc + b * yc + c * zc - d) / (al**2 * be**2 * ga**2)


@pytest.mark.parametrize(
    "offset, zone, tangent",
    [
        (3, Region.R_MINUS, True),
        (Fraction(5, 2), Region.CONTACT, False),
        (-3, Region.R_PLUS, True),
        (4, Region.R_MINUS, False),
    ],
)
def test_tangent_and_sides(offset, zone, tangent):
    side = plane_side(Quadric.ellipsoid(3, 2, 1), Quadric.plane((1, 0, 0), offset))
    assert side.zone is zone and side.tangent is tangent
