"""Every number worked in Examples 11 and 17, reproduced exactly."""

from fractions import Fraction

import sympy as sp

from quadric_contact import (
    Quadric,
    Region,
    characteristic_polynomial,
    paper,
    plane_side,
    relative_position,
    transversal_contact,
)

P = paper.PRINTED
lam = sp.Symbol("lambda")


def _coeffs(text):
    poly = sp.Poly(sp.sympify(text.replace("lambda", "lam"), locals={"lam": lam}, rational=True), lam)
    return tuple(Fraction(str(poly.coeff_monomial(lam**k))) for k in range(5))


def test_example_11():
    poly = characteristic_polynomial(P["Example 11 E"], P["Example 11 Q"])
    assert poly.coefficients == _coeffs(P["Example 11 P"])
    d2, d3, d4 = poly.deltas()
    assert d4 == int(P["Example 11 Delta4"]) == 0
    # The paper prints Delta3 = -400; the printed Delta3 formula gives -13790208.
    delta3 = sp.sympify(
        P["Delta3"], locals={f"c{k}": sp.Integer(int(c)) for k, c in enumerate(poly.coefficients)}
    )
    assert d3 == int(delta3) == -13790208 != int(P["Example 11 Delta3"])
    assert any(e.key == "example-11-delta3" for e in paper.ERRATA)
    assert (d3 < 0) == (int(P["Example 11 Delta3"]) < 0)
    # A real double root -1/2 and the pair +-4i/sqrt(3).
    assert (poly.structure.real, poly.structure.nonreal) == ((2,), (1,))
    assert poly(Fraction(-1, 2)) == 0
    r = transversal_contact(P["Example 11 E"], P["Example 11 Q"])
    assert bool(r) and r.decided_by == "Remark 9"


def test_example_17_zone():
    side = plane_side(P["Example 17 E"], P["Example 17 plane"])
    assert side.polynomial.coefficients == _coeffs(P["Example 17 P0"])
    assert side.polynomial.deltas()[1] == Fraction(P["Example 17 P0 Delta3"]) == Fraction(39, 320)
    assert side.c3 == Fraction(-3, 2) < 0
    assert side.zone is Region.R_MINUS and side.algorithm_1_zone == 2


def test_example_17_contact_with_s2():
    poly = characteristic_polynomial(P["Example 17 E"], P["Example 17 S2"])
    assert poly.coefficients == _coeffs(P["Example 17 P2"])
    d4 = poly.deltas()[2]
    assert d4 == Fraction(113207742980122401, 163840000)
    assert f"{float(d4):.5e}" == "6.90965e+08"
    r = transversal_contact(P["Example 17 E"], P["Example 17 S2"], small=True)
    assert bool(r) is False and r.decided_by == "Corollary 10"
    pos = relative_position(P["Example 17 E"], P["Example 17 S2"], small=True)
    # "c3 > 0, c2 > 0 and c1 < 0, according to Table 4": the bee is outside (R+).
    c0, c1, c2, c3, c4 = poly.coefficients
    assert c3 > 0 and c2 > 0 and c1 < 0
    assert pos == Region.R_PLUS and pos.polynomial.signs.pattern == "-+++"


def test_example_17_s1_same_quadratic_part():
    # The bee and the crown S1 have proportional quadratic parts: Delta4 vanishes.
    poly = characteristic_polynomial(P["Example 17 E"], P["Example 17 S1"])
    assert poly.deltas()[2] == 0
    assert Quadric.from_equation(P["Example 17 S1"]).kind.value == "ellipsoid"
