"""Smallness (Tables 1, 2): exact decisions, Example 17, the errata pinned."""

from __future__ import annotations

from fractions import Fraction

import pytest
import sympy
from hypothesis import given
from hypothesis import strategies as st

from quadric_contact import (
    ExcludedQuadricError,
    NotAnEllipsoidError,
    Quadric,
    QuadricContactError,
    QuadricKind,
    characteristic_polynomial,
    paper,
)
from quadric_contact.model.classification import TABLE_1_KINDS
from quadric_contact.paper.printed_tables import printed_table_2
from quadric_contact.testing.strategies import rigid_motions
from quadric_contact.theory.smallness import smallness, table_1

K = QuadricKind
P = paper.PRINTED


def _erratum(key):
    return next(e for e in paper.ERRATA if e.key == key)


def _agree(value: str, printed: str) -> bool:
    """``value`` (a long decimal) rounds to ``printed`` at the printed number of decimals."""
    from decimal import ROUND_HALF_EVEN, Decimal

    p = Decimal(printed)
    return Decimal(value).quantize(p, rounding=ROUND_HALF_EVEN) == p


# -- Example 17 ---------------------------------------------------------------------------


@pytest.mark.parametrize("piece", ["S1", "S2"])
def test_example_17_smallness_numbers(piece):
    r = smallness(P["Example 17 E"], P[f"Example 17 {piece}"])
    assert r.small and r.paper_small and r.table_4_applies
    printed = P[f"Example 17 smallness {piece}"].split()
    size, curv = r.conditions[0], r.conditions[1]
    got = [size.decimal("lhs", 20), size.decimal("rhs", 20), curv.decimal("lhs", 20), curv.decimal("rhs", 20)]
    for g, p in zip(got, printed, strict=True):
        assert _agree(g, p), (g, p)
    # Exactly: S1 has c = sqrt(20/3) and a/c^2 = 3/sqrt(20); the bee gamma/alpha^2 = sqrt(10/3).
    if piece == "S1":
        assert sympy.simplify(size.lhs - sympy.sqrt(sympy.Rational(20, 3))) == 0
        assert sympy.simplify(curv.lhs - 3 / sympy.sqrt(20)) == 0
    assert sympy.simplify(curv.rhs - sympy.sqrt(sympy.Rational(10, 3))) == 0


def test_example_17_s2_corrected_condition_still_holds():
    r = smallness(P["Example 17 E"], P["Example 17 S2"])
    added = [c for c in r.conditions if c.erratum == "table-1-h1-curvature"]
    assert len(added) == 1 and added[0].holds and added[0].lhs == 1


# -- Table 2 reduces to Table 1 under rigid motions (exactly, on random pairs) -------------

pos = st.fractions(Fraction(1, 4), 6, max_denominator=6).filter(lambda v: v > 0)


@st.composite
def standard_pairs(draw, kind=None):
    k = draw(st.sampled_from(TABLE_1_KINDS)) if kind is None else kind
    params = [draw(pos) for _ in range(len(Quadric.standard_parameters(k)))]
    names = dict(zip("abc", params, strict=False))
    axes = [
        draw(st.fractions(Fraction(1, 8), 3, max_denominator=8).filter(lambda v: v > 0)) for _ in range(3)
    ]
    q = Quadric.standard(k, **names)
    e = Quadric.ellipsoid(*axes)
    mq, me = draw(rigid_motions()), draw(rigid_motions())
    k_scale = draw(st.sampled_from([Fraction(1), Fraction(-3, 2), Fraction(7, 3)]))
    return k, names, axes, q.moved(mq).scaled(k_scale), e.moved(me).scaled(draw(st.sampled_from([1, -2])))


@given(standard_pairs())
def test_table_2_agrees_with_table_1_after_motions(pair):
    kind, names, axes, q, e = pair
    t1 = table_1(kind, alpha=axes[0], beta=axes[1], gamma=axes[2], **names)
    t2 = smallness(e, q)
    assert t2.kind is kind
    assert [c.holds for c in t2.conditions] == [c.holds for c in t1.conditions]
    assert [c.holds for c in t2.alternative] == [c.holds for c in t1.alternative]
    assert (t2.small, t2.paper_small, t2.table_4_applies) == (t1.small, t1.paper_small, t1.table_4_applies)
    for name in t1.parameters:
        assert t2.parameters[name].exact() == t1.parameters[name].exact()


def test_irrational_eigenvalues_general_position():
    """Q00 with eigenvalues 2 - sqrt 2, 2, 2 + sqrt 2: the decision goes through
    exact algebraic numbers and agrees with the parameters computed by hand."""
    A = [[2, 1, 0], [1, 2, 1], [0, 1, 2]]
    q = Quadric.from_coefficients(A, [0, 0, 0], -1)  # X^T A X = 1: semi-axes 1/sqrt(eigenvalues)
    r = smallness(Quadric.sphere(Fraction(1, 4)), q)
    a2, c2 = r.parameters["a"].exact(), r.parameters["c"].exact()
    s2 = sympy.sqrt(2)
    assert sympy.simplify(a2.to_sympy() - 1 / (2 - s2)) == 0
    assert sympy.simplify(c2.to_sympy() - 1 / (2 + s2)) == 0
    # c = 1/sqrt(2 + sqrt 2) ~ 0.541 >= 1/4, a/c^2 = (2 + sqrt2)/sqrt(2 - sqrt2) ~ 4.46 > 4 = gamma/alpha^2
    assert r.conditions[0].holds and not r.conditions[1].holds and not r.small
    assert smallness(Quadric.sphere(Fraction(1, 5)), q).small  # 4.46 <= 5


# -- exact boundary cases ------------------------------------------------------------------


def test_equal_spheres_are_a_tie_decided_exactly():
    q = Quadric.sphere(Fraction(3, 2), center=(1, 2, 3)).rotated((1, 2, 3, 4))
    e = Quadric.sphere(Fraction(3, 2), center=(-5, 0, 7))
    r = smallness(e, q)
    assert r.small and r.table_4_applies and all(c.holds for c in r.conditions)
    assert all(c.lhs == c.rhs for c in r.conditions)
    bigger = Quadric.sphere(Fraction(3, 2) + Fraction(1, 10**30))
    r2 = smallness(bigger, q)
    assert not r2.paper_small and not r2.table_4_applies
    assert r2.small  # Definition 1 is symmetric for two ellipsoids: q is small w.r.t. bigger


def test_boundary_of_the_curvature_condition_is_exact():
    # elliptic cylinder a = 2, b = 1: a/b^2 = 2; E with gamma/alpha^2 = 2 exactly, then slightly less.
    q = Quadric.elliptic_cylinder(2, 1).rotated((3, 1, 4, 1), about=(1, 1, 1))
    e = Quadric.ellipsoid(Fraction(1, 2), Fraction(1, 2), Fraction(1, 2))  # 1/r = 2
    assert smallness(e, q).small
    e2 = Quadric.ellipsoid(Fraction(1, 2) + Fraction(1, 10**40), Fraction(1, 2), Fraction(1, 2))
    r = smallness(e2, q)
    assert not r.small and r.failed[0].name == "a/b^2 <= gamma/alpha^2"


# -- the corrected rows: counterexamples to the printed tables ----------------------------


def test_h1_counterexample():
    """A flat ellipsoid pressed against the inside of the throat of a one-sheet
    hyperboloid: the printed Table 1 calls it small, yet the surfaces meet in two
    curves and P has four real roots, so Corollary 10 says 'no contact'."""
    q = Quadric.hyperboloid_one_sheet(1, 1, 10)
    e = Quadric.ellipsoid(Fraction(1, 10), 1, 1, center=(Fraction(17, 20), 0, 0))
    r = smallness(e, q)
    assert r.paper_small and not r.small
    assert [c.holds for c in r.conditions] == [True, True, False]
    # Two points of E on either side of Q: the surfaces cross (transversal contact).
    inside, outside = (Fraction(19, 20), 0, 0), (Fraction(17, 20), 1, 0)
    assert e.value_at(inside) == 0 == e.value_at(outside)
    assert q.value_at(inside) < 0 < q.value_at(outside)
    # ... and P is real-rooted: Corollary 10 would say there is no contact.
    Pl = characteristic_polynomial(e, q)
    assert Pl.structure.all_real and Pl.delta_signs()[2] > 0
    # Two curves: on E, f = X^T Q X < 0 on the whole slice y = 0, while f > 0 at
    # (17/20, +-1, 0): {f > 0} has a component on each side of y = 0.
    # On the slice, x = 17/20 + s/10, z^2 = 1 - s^2: f(s) = x^2 - (1 - s^2)/100 - 1.
    s = sympy.Symbol("s")
    f = (Fraction(17, 20) + s / 10) ** 2 - (1 - s**2) / 100 - 1
    assert max(f.subs(s, v) for v in (-1, 1, *sympy.solve(sympy.diff(f, s), s))) < 0
    assert q.value_at((Fraction(17, 20), -1, 0)) > 0
    assert "test_h1_counterexample" in _erratum("table-1-h1-curvature").evidence


def test_enclosing_spheres_are_small_but_table_4_fails():
    """Two spheres meet in a circle, a point or nothing: never two curves, so a
    sphere of radius 2 is small w.r.t. a sphere of radius 1 (Definition 1),
    which Table 1 denies.  Around the small sphere, Table 4 reads R- although the
    surface of E lies in R+: Theorem 13 needs the non-enclosing condition."""
    e, q = Quadric.sphere(2), Quadric.sphere(1)
    r = smallness(e, q)
    assert r.small and not r.paper_small and not r.table_4_applies
    assert all(c.holds for c in r.alternative)
    Pl = characteristic_polynomial(e, q)
    assert Pl.signs.pattern == "----"  # Table 4: R- for an ellipsoid
    assert q.value_at((2, 0, 0)) > 0  # but every point of E is in R+
    assert (
        "test_enclosing_spheres_are_small_but_table_4_fails"
        in _erratum("table-1-ellipsoid-enclosing").evidence
    )


def test_hyperbolic_cylinder_printed_size_condition():
    """x^2 - y^2/100 = 1 (gap 2) and a sphere of radius 3/2 at the centre: it
    crosses both branches (two curves), Table 1 says not small (a = 1 < 3/2) but
    Table 2 as printed (M b' >= delta' alpha', b' = 10) says small."""
    q = Quadric.hyperbolic_cylinder(1, 10).rotated((1, 1, 0, 2))
    e = Quadric.sphere(Fraction(3, 2))
    printed = printed_table_2(e, q)
    assert printed.small is True
    r = smallness(e, q)
    assert not r.small and not r.conditions[0].holds
    assert r.conditions[0].erratum == "table-2-hyperbolic-cylinder-size"
    # Unrotated: f = x^2 - y^2/100 - 1 < 0 on the slice x = 0 of E, > 0 at (+-3/2, 0, 0):
    # two caps of E beyond the two branches, two curves; P is real-rooted, so
    # Corollary 10 would say 'no contact'.
    q0 = Quadric.hyperbolic_cylinder(1, 10)
    assert all(q0.value_at((0, y, 0)) < 0 for y in (0, Fraction(3, 2)))
    assert q0.value_at((Fraction(3, 2), 0, 0)) > 0 and q0.value_at((Fraction(-3, 2), 0, 0)) > 0
    assert characteristic_polynomial(e, q).structure.all_real
    assert (
        "test_hyperbolic_cylinder_printed_size_condition"
        in _erratum("table-2-hyperbolic-cylinder-size").evidence
    )


def test_parabolic_cylinder_printed_d_is_imaginary():
    q = Quadric.parabolic_cylinder(3).moved(
        __import__("quadric_contact").RigidMotion.from_quaternion(1, 2, 0, 1, (1, 0, -2))
    )
    e = Quadric.sphere(Fraction(1, 10))
    printed = printed_table_2(e, q)
    assert printed.small is None and "d'" in printed.undefined
    r = smallness(e, q)
    # corrected d'^2 = -4 K a'^2 gives a^2 = 9 back: 2/a^2 = 2/9 <= 10
    assert r.small and r.parameters["a"].exact() == 9


@given(st.sampled_from(TABLE_1_KINDS), st.data())
def test_printed_table_2_agrees_with_table_1_where_not_misprinted(kind, data):
    _, names, axes, q, e = data.draw(standard_pairs(kind))
    printed = printed_table_2(e, q)
    t1 = table_1(kind, alpha=axes[0], beta=axes[1], gamma=axes[2], **names)
    if kind is K.PARABOLIC_CYLINDER:
        assert printed.small is None
    elif kind is K.HYPERBOLIC_CYLINDER:
        # the curvature condition agrees; the size condition uses b instead of a
        assert printed.conditions[1].holds == t1.conditions[1].holds
    else:
        assert [c.holds for c in printed.conditions] == [
            c.holds for c in t1.conditions if c.source == "Table 1"
        ]


# -- input handling ----------------------------------------------------------------------------


@pytest.mark.parametrize(
    "q",
    [
        "x**2 + y**2 - z**2",  # cone
        "x**2 - y**2",  # intersecting planes
        "(x - 1)**2",  # coincident planes
        "z - 1",  # a plane
        "x**2 + y**2 + z**2 + 1",  # imaginary ellipsoid
    ],
)
def test_excluded_quadrics(q):
    with pytest.raises(ExcludedQuadricError) as info:
        smallness("x**2 + y**2 + z**2 - 1", q)
    assert info.value.details["kind"] is Quadric.from_equation(q).kind


def test_bad_ellipsoid():
    with pytest.raises(NotAnEllipsoidError):
        smallness("x**2 + y**2 - z**2 - 1", "x**2 + y**2 + z**2 - 4")


def test_table_1_parameters_and_errors():
    r = table_1(
        "hyperboloid of one sheet",
        a=1,
        b=1,
        c=2,
        alpha=sympy.sqrt(10) / 10,
        beta=sympy.sqrt(10) / 10,
        gamma=sympy.sqrt(30) / 30,
    )
    assert r.small and [c.holds for c in r.conditions] == [True, True, True]
    # parameters are sorted as Table 1 orders them
    assert table_1("ellipsoid", a=1, b=3, c=2, alpha=1, beta=1, gamma=1).parameters["a"].exact() == 9
    with pytest.raises(ExcludedQuadricError):
        table_1("cone", a=1, b=1, c=1, alpha=1, beta=1, gamma=1)
    with pytest.raises(ValueError, match="takes parameters a, b"):
        table_1("elliptic paraboloid", a=1, alpha=1, beta=1, gamma=1)
    with pytest.raises(QuadricContactError, match="positive"):
        table_1("parallel planes", a=-1, alpha=1, beta=1, gamma=1)


def test_report_presentation():
    r = smallness(P["Example 17 E"], P["Example 17 S2"])
    text = str(r)
    assert "small with respect to Q (hyperboloid of one sheet)" in text
    assert "a/b^2 <= gamma/alpha^2" in text and "table-1-h1-curvature" in text
    d = r.to_dict()
    assert d["small"] is True and d["kind"] == "hyperboloid of one sheet"
    assert d["conditions"][1]["lhs"] == "1/4" and d["conditions"][1]["rhs_decimal"].startswith("1.8257418583")
    assert bool(r) is True
    assert d["parameters"]["c"].startswith("2.0000")
