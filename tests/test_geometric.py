"""The exact geometric decision: constructions with known answers, the
degenerate critical sets, Remark 9, float sampling, and its use by the
predicates when E is not small (or Q is a type the theory excludes)."""

from __future__ import annotations

from fractions import Fraction

import pytest
from hypothesis import given, note
from hypothesis import strategies as st
from tests.sampling import sampled

from quadric_contact import (
    ExcludedQuadricError,
    NotAnEllipsoidError,
    Quadric,
    QuadricKind,
    Region,
    RigidMotion,
    characteristic_polynomial,
    relative_position,
    transversal_contact,
)
from quadric_contact.model.classification import TABLE_1_KINDS
from quadric_contact.testing.strategies import ellipsoids, quadrics, rigid_motions, tangent_pairs
from quadric_contact.theory.decision import Roots
from quadric_contact.theory.geometric import decide_geometrically

F = Fraction
R_MINUS, R_PLUS, CONTACT = Region.R_MINUS, Region.R_PLUS, Region.CONTACT

CASES = [
    # name, E, Q, (transversal, region, tangent points, tangent curve, curves)
    ("sphere inside sphere", Quadric.sphere(1), Quadric.sphere(2), (False, R_MINUS, 0, False, None)),
    ("sphere around sphere", Quadric.sphere(2), Quadric.sphere(1), (False, R_PLUS, 0, False, None)),
    ("tangent outside", Quadric.sphere(1, (3, 0, 0)), Quadric.sphere(2), (False, R_PLUS, 1, False, None)),
    ("tangent inside", Quadric.sphere(1, (1, 0, 0)), Quadric.sphere(2), (False, R_MINUS, 1, False, None)),
    ("two spheres crossing", Quadric.sphere(1, (2, 0, 0)), Quadric.sphere(2), (True, CONTACT, 0, False, 1)),
    (
        "between parallel planes",
        Quadric.sphere(1),
        Quadric.parallel_planes(1),
        (False, R_MINUS, 2, False, None),
    ),
    ("across parallel planes", Quadric.sphere(2), Quadric.parallel_planes(1), (True, CONTACT, 0, False, 2)),
    (
        "in a cylinder, circle",
        Quadric.sphere(1),
        Quadric.elliptic_cylinder(1, 1),
        (False, R_MINUS, 0, True, None),
    ),
    (
        "through a thin cylinder",
        Quadric.sphere(1),
        Quadric.elliptic_cylinder(F(1, 2), F(1, 2)),
        (True, CONTACT, 0, False, 2),
    ),
    (
        "in a circular H1 throat",
        Quadric.sphere(1),
        Quadric.hyperboloid_one_sheet(1, 1, 3),
        (False, R_MINUS, 0, True, None),
    ),
    (
        "pancake in the H1 throat",
        Quadric.ellipsoid(F(1, 10), 1, 1, center=(F(17, 20), 0, 0)),
        Quadric.hyperboloid_one_sheet(1, 1, 10),
        (True, CONTACT, 0, False, 2),
    ),
    ("sphere on a plane", Quadric.sphere(1), Quadric.plane((0, 0, 1), 1), (False, R_MINUS, 1, False, None)),
    (
        "sphere in a cone",
        Quadric.sphere(1, (0, 0, 3)),
        Quadric.from_equation("x**2 + y**2 - z**2"),
        (False, R_MINUS, 0, False, None),
    ),
    (
        "sphere at a cone's vertex",
        Quadric.sphere(1),
        Quadric.from_equation("x**2 + y**2 - z**2"),
        (True, CONTACT, 0, False, 2),
    ),
    (
        "sphere across intersecting planes",
        Quadric.sphere(1),
        Quadric.from_equation("x*y"),
        (True, CONTACT, 2, False, None),
    ),  # two great circles crossing at the two points of the axis
    (
        "example 11",
        Quadric.from_equation("2*x**2 + 2*y**2 + 3*z**2 - 1"),
        Quadric.from_equation("x**2 + y**2 + 8*z"),
        (True, CONTACT, 0, False, 1),
    ),
]


@pytest.mark.parametrize(("name", "E", "Q", "expected"), CASES, ids=[c[0] for c in CASES])
def test_constructions(name, E, Q, expected):
    g = decide_geometrically(E, Q)
    assert (g.transversal, g.region, g.tangent_points, g.tangent_curve, g.curves) == expected, str(g)
    # the same pair moved rigidly gives the same answer (values are invariant)
    m = RigidMotion.from_quaternion(1, 2, -1, 3, (F(1, 3), -2, 5))
    g2 = decide_geometrically(E.moved(m), Q.moved(m))
    assert (g2.transversal, g2.region, g2.tangent_points, g2.tangent_curve, g2.curves) == expected
    assert g2.minimum == g.minimum and g2.maximum == g.maximum


def test_degenerate_critical_sets():
    # concentric spheres: f is constant on E (the whole surface is critical)
    g = decide_geometrically(Quadric.sphere(1), Quadric.sphere(3))
    assert g.minimizers == g.maximizers == "surface" and g.minimum == F(-8, 9)
    # Q a multiple of E: the same surface
    g = decide_geometrically(Quadric.ellipsoid(1, 2, 3), Quadric.ellipsoid(1, 2, 3).scaled(-7))
    assert g.coincident and not g.transversal
    # coaxial: the maxima form a circle, the minima two points
    g = decide_geometrically(Quadric.sphere(1), Quadric.elliptic_cylinder(F(1, 2), F(1, 2)))
    assert g.maximizers == "circle" and g.minimizers == "2 points"
    # a spheroid inside a coaxial cylinder touching along its equator
    g = decide_geometrically(Quadric.ellipsoid(1, 1, 3), Quadric.elliptic_cylinder(1, 1))
    assert g.tangent_curve and g.region is R_MINUS and not g.transversal


def test_tangent_points_on_a_curve_are_reported():
    """Viviani's curve: the unit sphere and the cylinder (x - 1/2)^2 + y^2 = 1/4
    meet in a figure eight that crosses itself at (1, 0, 0), where the
    surfaces are tangent: a saddle of X^T Q X at level 0."""
    g = decide_geometrically(Quadric.sphere(1), Quadric.from_equation("(x - 1/2)**2 + y**2 - 1/4"))
    assert g.transversal and g.tangent_points == 1 and g.curves is None
    saddle = next(c for c in g.critical_sets if c.index == 1)
    assert saddle.value == 0 and saddle.multiplier == F(1, 2)
    # a degenerate minimum (f = -1 + y^2 + z^4/4 + ... near (1, 0, 0)): curves are not counted
    g = decide_geometrically(Quadric.sphere(1), Quadric.from_equation("(x - 1)**2 + y**2 - 1"))
    assert g.transversal and g.curves is None
    assert any(c.index is None and c.value == -1 for c in g.critical_sets)


@given(st.data())
def test_tangent_pairs(data):
    inside = data.draw(st.booleans())
    e, q = data.draw(tangent_pairs(inside=inside))
    g = decide_geometrically(e, q)
    assert not g.transversal and g.tangent_points == 1 and not g.tangent_curve
    assert g.region is (R_MINUS if inside else R_PLUS)
    assert (g.maximum if inside else g.minimum) == 0


def _pairs():
    kinds = st.sampled_from(
        [*TABLE_1_KINDS, QuadricKind.CONE, QuadricKind.INTERSECTING_PLANES, QuadricKind.PLANE]
    )

    @st.composite
    def build(draw):
        kind = draw(kinds)
        if kind is QuadricKind.CONE:
            a, b, c = (draw(st.integers(1, 4)) for _ in range(3))
            q = Quadric.diagonal(F(1, a * a), F(1, b * b), -F(1, c * c), 0).moved(
                draw(rigid_motions(bound=2))
            )
        elif kind is QuadricKind.INTERSECTING_PLANES:
            q = Quadric.from_equation(
                f"({draw(st.integers(1, 3))}*x - y + 1)*(x + {draw(st.integers(1, 3))}*z)"
            )
        else:
            q = draw(quadrics(kind, moved=True, bound=2))
        e = draw(ellipsoids(min_axis=F(1, 2), max_axis=3, bound=4))
        return e, q

    return build()


@given(_pairs())
def test_against_remark_9_and_sampling(pair):
    e, q = pair
    g = decide_geometrically(e, q)
    note(str(g))
    P = characteristic_polynomial(e, q)
    if not P.structure.all_real:
        assert g.transversal  # Remark 9: non-real roots always mean transversal contact
    s = sampled(e, q)
    tol = 1e-9 * s["scale"]
    lo, hi = float(g.minimum), float(g.maximum)
    assert lo <= s["min"] + tol and s["max"] <= hi + tol  # exact extremes bound every sample
    assert s["min"] - lo <= 0.02 * (hi - lo) + tol and hi - s["max"] <= 0.02 * (hi - lo) + tol
    robust = all(abs(float(c.value)) > 0.05 * s["scale"] for c in g.critical_sets)
    if g.curves is not None and robust:
        assert s.get("curves") == g.curves, (s, str(g))


def test_used_by_the_predicates_when_not_small():
    """The counterexample to Table 1: not small, real-rooted P; the decision needs no
    smallness (four simple roots, no definite member) and says so, and the geometric decision
    agrees and counts the two curves."""
    q = Quadric.hyperboloid_one_sheet(1, 1, 10)
    e = Quadric.ellipsoid(F(1, 10), 1, 1, center=(F(17, 20), 0, 0))
    r = transversal_contact(e, q)
    assert r.transversal is True and r.decided_by == "signature sequence"
    assert r.smallness is None and r.geometric.facts.roots is Roots.SIMPLE
    geo = decide_geometrically(e, q)
    assert geo.transversal is True and geo.curves == 2
    pos = relative_position(e, q)
    assert pos.region is CONTACT and pos.decided_by == "signature sequence"
    assert transversal_contact(e, q, method="theory").transversal is None
    # the paper's route, told the pair is not small, falls back on the separation certificate
    r = transversal_contact(e, q, small=False)
    assert r.transversal is True and r.decided_by == "separation certificate" and r.geometric.simple


def test_used_for_excluded_quadrics():
    cone = Quadric.from_equation("x**2 + y**2 - z**2")
    inside = Quadric.sphere(1, (0, 0, 3))
    r = transversal_contact(inside, cone)
    assert r.transversal is False and r.decided_by == "signature sequence"
    assert decide_geometrically(inside, cone).region is R_MINUS
    assert relative_position(inside, cone).region is R_MINUS
    assert relative_position(inside, -cone).region is R_PLUS
    with pytest.raises(ExcludedQuadricError):
        relative_position(inside, cone, method="theory")


def test_enclosing_case_uses_a_smallness_free_region():
    pos = relative_position(Quadric.sphere(2), Quadric.sphere(1))
    assert pos.region is R_PLUS and pos.decided_by == "signature sequence"
    # the paper's route: Corollary 10 holds (Q small w.r.t. E), Table 4 does not apply there
    paper = transversal_contact(Quadric.sphere(2), Quadric.sphere(1), method="theory")
    assert paper.decided_by == "Corollary 10"
    assert relative_position(Quadric.sphere(2), Quadric.sphere(1), method="theory").region is None
    assert decide_geometrically(Quadric.sphere(2), Quadric.sphere(1)).region is R_PLUS


def test_errors():
    with pytest.raises(NotAnEllipsoidError):
        decide_geometrically("x**2 + y**2 - 1", "x**2 - 1")
    with pytest.raises(ExcludedQuadricError):
        decide_geometrically("x**2 + y**2 + z**2 - 1", [[0] * 4] * 4)


def test_presentation():
    g = decide_geometrically(Quadric.sphere(1), Quadric.parallel_planes(1))
    assert "tangent to Q at 2 point(s)" in str(g)
    d = g.to_dict()
    assert d["region"] == "R-" and d["tangent_points"] == 2 and d["maximizers"] == "2 points"
    assert any("circle" in c for c in d["critical_sets"])
