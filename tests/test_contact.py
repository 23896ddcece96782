"""Transversal contact against numeric root finders away from tangency, and
against the exact geometry of constructed configurations."""

from fractions import Fraction

import pytest
from hypothesis import assume, given
from tests.oracles import mpmath_nonreal, numpy_nonreal

from quadric_contact import Quadric, characteristic_polynomial, transversal_contact
from quadric_contact.testing.strategies import ellipsoids, quadrics, tangent_pairs


@given(e=ellipsoids(), q=quadrics())
def test_nonreal_roots_agree_with_mpmath_and_numpy(e, q):
    P = characteristic_polynomial(e, q)
    exact = not P.structure.all_real
    numeric = mpmath_nonreal(P)
    assume(numeric is not None)
    assert exact == numeric
    eig = numpy_nonreal(P.E.to_numpy(), q.to_numpy())
    if eig is not None:
        assert exact == eig


@given(pair=tangent_pairs())
def test_exact_tangency_is_never_transversal(pair):
    e, q = pair
    P = characteristic_polynomial(e, q)
    assert P.deltas()[2] == 0  # tangency: a multiple root
    assert P.structure.all_real
    r = transversal_contact(e, q, small=True)
    assert r.decided and not r


def test_sphere_crossing_and_clear_of_an_ellipsoid():
    q = Quadric.ellipsoid(4, 3, 2)
    crossing = transversal_contact(Quadric.sphere(Fraction(1, 2), (4, 0, 0)), q)
    assert bool(crossing) and crossing.decided_by == "Remark 9"
    inside = transversal_contact(Quadric.sphere(Fraction(1, 2)), q, small=True)
    assert not inside and inside.decided_by == "Corollary 10"


def test_plane_uses_theorem_14_without_smallness():
    E = Quadric.ellipsoid(5, 1, 1)  # large: no smallness needed for a plane
    r = transversal_contact(E, "x - 6")
    assert r.decided_by == "signature sequence" and not r
    assert str(r.geometric).startswith("the member") and "negative definite" in r.reason  # x < 6 on E
    assert transversal_contact(E, "x - 6", method="theory").decided_by == "Theorem 14"
    r = transversal_contact(E, "x - 4")
    assert bool(r) and r.decided_by == "Remark 9"
    # touching: all roots real and no definite member; Theorem 14 names it
    r = transversal_contact(E, "x - 5")
    assert not r and r.decided_by == "Theorem 14"


@pytest.mark.parametrize("eq", ["x**2 + y**2 + z**2 + 1", "x**2 + y**2 + 1", "x**2 + 4"])
def test_quadrics_without_real_points_are_never_touched(eq):
    r = transversal_contact(Quadric.sphere(1), eq)
    # no common point, so some member of the pencil is definite (Finsler-Calabi)
    assert r.decided and not r and r.decided_by == "signature sequence"
    assert transversal_contact(Quadric.sphere(1), eq, method="theory").decided_by == "no real points"


def test_result_reports_what_it_looked_at():
    r = transversal_contact("2*x**2 + 2*y**2 + 3*z**2 - 1", "x**2 + y**2 + 8*z")
    d = r.to_dict()
    assert d["transversal_contact"] is True and d["delta4"] == 0 and d["delta3"] == -13790208
    assert d["coefficients"] == [-16, -64, -67, -12, -12]
    assert "non-real" in r.reason
