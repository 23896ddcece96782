"""Composite objects and Algorithms 1-2 (Section 5.2), on Example 17 and on trees of planes."""

from __future__ import annotations

from fractions import Fraction as F

import pytest
import sympy

from quadric_contact import Quadric
from quadric_contact.exact.errors import NotAPlaneError, QuadricContactError
from quadric_contact.paper import PRINTED
from quadric_contact.scenes.composite import Composite, Piece, Split, algorithm_1, algorithm_2
from quadric_contact.scenes.ledger import Ledger
from quadric_contact.theory.pencil import characteristic_polynomial
from quadric_contact.theory.results import Region

BEE = PRINTED["Example 17 E"]


def printed_coefficients(key):
    """c0..c4 of a printed polynomial in lambda, decimals read exactly."""
    lam = sympy.Symbol("lam")
    expr = sympy.sympify(PRINTED[key].replace("lambda", "lam"), rational=True)
    return [F(str(c)) for c in reversed(sympy.Poly(expr, lam).all_coeffs())]


@pytest.fixture
def tree():
    return Composite.separated(
        "tree",
        PRINTED["Example 17 plane"],
        plus=Piece("crown", Quadric.from_equation(PRINTED["Example 17 S1"])),
        minus=Piece("trunk", Quadric.from_equation(PRINTED["Example 17 S2"])),
    )


def test_example_17_algorithm_1_zone_2(tree):
    """P0 = lambda^2 (-0.3 lambda^2 - 1.5 lambda - 0.25), Delta_3 = 0.121875 > 0, c3 < 0: Zone 2."""
    led = Ledger()
    r = algorithm_1(BEE, tree, ledger=led)
    assert r.zones == {"z - 6": 2}
    assert [p.name for p in r.pieces] == ["trunk"]
    side = r.sides["z - 6"]
    assert printed_coefficients("Example 17 P0") == list(side.polynomial.coefficients)
    # the paper's Delta_3 of P0 is c2^2 (c3^2 - 4 c4 c2), the quantity Algorithm 1 tests
    _, d3, _ = side.polynomial.deltas()
    assert d3 == F(str(PRINTED["Example 17 P0 Delta3"])) == side.c2**2 * side.discriminant
    assert led.done["characteristic_polynomials"] == 1 and led.cost("tree/crown") == 0


def test_example_17_algorithm_2_computes_only_the_trunk(tree):
    """Zone 2: only P2 is formed; Delta_4 = 6.90965e8 > 0, no contact; R+ (outside)."""
    led = Ledger()
    r = algorithm_2(BEE, tree, small=True, region=True, ledger=led)
    assert r.contact is False and list(r.contacts) == ["trunk"]
    assert led.cost("crown") == 0 and led.cost("trunk") == 2
    P2 = r.contacts["trunk"].polynomial
    assert printed_coefficients("Example 17 P2") == list(P2.coefficients)
    d4 = P2.deltas()[2]
    assert float(d4) == pytest.approx(float(PRINTED["Example 17 P2 Delta4"]), rel=1e-5)
    assert r.regions["trunk"].region is Region.R_PLUS
    c0, c1, c2, c3, c4 = P2.coefficients
    assert c3 > 0 and c2 > 0 and c1 < 0  # the paper's reading of Table 4


def test_zone_0_checks_both_pieces(tree):
    """An ellipsoid straddling z = 6 is in Zone 0: both pencils are formed."""
    E = Quadric.ellipsoid(F(1, 2), F(1, 2), F(1, 2), center=(4, 0, 6))
    led = Ledger()
    r = algorithm_2(E, tree, small=True, ledger=led)
    assert r.zone.zones == {"z - 6": 0}
    assert sorted(r.contacts) == ["crown", "trunk"]
    assert led.cost("crown") == 2 and led.cost("trunk") == 2
    assert r.contact is False  # the crown's radius is below 3.1 for z <= 6.5
    # nearer, the crown (which widens fast above z = 6) is cut
    near = algorithm_2(Quadric.sphere(F(1, 2), (3, 0, 6)), tree, small=True)
    assert near.zone.zones == {"z - 6": 0} and near.touching == ["crown"]


def test_algorithm_2_agrees_with_corollary_10_reading_on_the_transversal_side(tree):
    E = Quadric.ellipsoid(
        F(1, 2), F(1, 2), F(1, 3), center=(F(19, 5), 0, 7)
    )  # crosses the crown (radius 3.8 at z = 7)
    r = algorithm_2(E, tree, small=True)
    assert r.zone.zones == {"z - 6": 1}
    assert r.contact is True and r.touching == ["crown"]
    _, s3, s4 = r.contacts["crown"].polynomial.delta_signs()
    assert s4 < 0 or (s4 == 0 and s3 < 0)


def test_tree_of_planes():
    """A slab |x| <= 2 split further at y = 0: four leaves, one of them empty."""
    a = Piece("a", Quadric.sphere(10, (0, 0, 0)))
    b = Piece("b", Quadric.sphere(5, (0, 5, 0)))
    c = Piece("c", Quadric.from_equation("z = 0"))
    root = Split(
        Quadric.from_equation("x - 2"),
        plus=a,
        minus=Split(Quadric.from_equation("x + 2"), plus=Split(Quadric.from_equation("y"), plus=b, minus=c)),
    )
    obj = Composite("slab", root)
    assert [p.name for p in obj.pieces] == ["a", "b", "c"]
    assert [s.name for s in obj.splits()] == ["x - 2", "x + 2", "y"]
    far_right = Quadric.sphere(F(1, 2), (5, 1, 1))
    assert [p.name for p in algorithm_1(far_right, obj).pieces] == ["a"]
    far_left = Quadric.sphere(F(1, 2), (-5, 1, 1))
    r = algorithm_1(far_left, obj)
    assert r.pieces == () and r.zones == {"x - 2": 2, "x + 2": 2}
    middle = Quadric.sphere(F(1, 2), (0, -1, 1))
    assert [p.name for p in algorithm_1(middle, obj).pieces] == ["c"]
    straddling = Quadric.sphere(F(1, 2), (0, 0, 1))
    assert sorted(p.name for p in algorithm_1(straddling, obj).pieces) == ["b", "c"]
    # a plane piece is decided by Corollary 15
    touching_ground = Quadric.sphere(F(1, 2), (0, -1, F(1, 4)))
    res = algorithm_2(touching_ground, obj, region=True)
    assert res.contacts["c"].transversal is True and res.contacts["c"].decided_by == "Corollary 15"


def test_union_without_planes_checks_every_piece():
    obj = Composite.union("pair", [Piece("p", Quadric.sphere(1)), Piece("q", Quadric.sphere(1, (5, 0, 0)))])
    led = Ledger()
    r = algorithm_2(Quadric.sphere(F(1, 4), (F(5, 2), 0, 0)), obj, small=True, ledger=led)
    assert sorted(r.contacts) == ["p", "q"] and r.contact is False
    assert led.done["characteristic_polynomials"] == 2


def test_bad_composites():
    with pytest.raises(NotAPlaneError):
        Split(Quadric.sphere(1))
    with pytest.raises(QuadricContactError, match="unique"):
        Composite.union("x", [Piece("p", Quadric.sphere(1)), Piece("p", Quadric.sphere(2))])
    with pytest.raises(QuadricContactError):
        Piece("p", Quadric.sphere(1), Region.CONTACT)


def test_static_pencil_equals_time_pencil_at_rational_times(tree):
    """The pencil in t (generated formulas on fmpq_poly) evaluated at t equals the
    static pencil of the exactly moved ellipsoid, up to the positive factor |q|^8."""
    from quadric_contact._generated.formulas import pencil_coefficients
    from quadric_contact.scenes.trajectory import Keyframes, poly_eval

    E = Quadric.from_equation(BEE).as_ellipsoid()
    traj = Keyframes([(0, (3, 3, 5.5)), (2, (1, 0, 7), (3, 1, 0, 2))])
    seg = traj.segments(F(0), F(2), E.center())[0]
    upper = seg.moved_upper(E, E.center())
    Q = tree.pieces[1].quadric
    import flint

    coeffs = pencil_coefficients(
        *upper, *[flint.fmpq_poly([flint.fmpq(v.numerator, v.denominator)]) for v in Q.upper]
    )
    for t in (F(0), F(1, 3), F(5, 4), F(2)):
        Et = traj.placed(E, t, F(0), F(2))
        static = characteristic_polynomial(Et, Q).coefficients
        q = seg.quaternion_at(t)
        n = sum(x * x for x in q)
        for k in range(5):
            # det(lambda n^2 E + Q): c_k scales by n^(2k)
            assert poly_eval(coeffs[k], t) == static[k] * n ** (2 * k)


def test_zone_0_counts_contact_with_the_part_of_a_surface_beyond_its_plane(tree):
    """Algorithm 2 as printed: in Zone 0 a contact with the *whole* quadric S1 is a
    contact.  The crown's ellipsoid reaches below z = 6 down to its pole at
    z = 8.36291 - sqrt(20/3) = 5.78092..., inside the trunk, where it is not part
    of the tree.  A small sphere around that pole, straddling z = 6, touches no
    surface of the tree, yet Algorithm 2 reports a contact with the crown."""
    E = Quadric.sphere(F(1, 5), (0, 0, F(117, 20)))  # centre z = 5.85, spans 5.65 .. 6.05
    r = algorithm_2(E, tree, small=True, region=True)
    assert r.zone.zones == {"z - 6": 0}
    assert r.touching == ["crown"]
    assert r.regions["trunk"].region is Region.R_MINUS  # well inside the trunk
    # the contact points are all below the plane, outside Zone 1 where the crown belongs
    crown = Quadric.from_equation("x^2 + y^2 + 3*(z - 8.36291)^2 - 20")
    assert crown.value_at((0, 0, F(578, 100))) > 0 > crown.value_at((0, 0, F(579, 100)))  # pole in between
