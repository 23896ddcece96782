"""The signature decision of ``proofs/twmw_2009_signature_decision.py`` (its plain exact implementation,
``proofs/_signatures.py``): where ``E`` is small the paper's criterion agrees with it (Theorem 2,
Corollary 10), and both agree with the exact extremes of ``X^T Q X`` on ``E``; exact pairs pin its rows."""

from __future__ import annotations

import importlib
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, event, given, settings
from hypothesis import strategies as st

from quadric_contact import Quadric, corollary_10
from quadric_contact.model.classification import TABLE_1_KINDS
from quadric_contact.modes import CriterionCode
from quadric_contact.paper.proving import PACKAGE_NAME, load_proofs
from quadric_contact.testing.strategies import points, quadrics, rationals, rotations
from quadric_contact.theory.results import Region
from quadric_contact.theory.smallness import smallness

F = Fraction
load_proofs(Path(__file__).resolve().parents[1] / "proofs")
S = importlib.import_module(f"{PACKAGE_NAME}._signatures")
P = importlib.import_module(f"{PACKAGE_NAME}.twmw_2009_signature_decision")


@st.composite
def small_pairs(draw):
    """A Table 1 quadric in standard form and an ellipsoid of semi-axes 1/20 .. 1/4 centred near its
    surface (a float Newton step from a drawn point, rounded to a rational; only where to look is
    chosen in floating point), kept when it is small (Definition 1, Tables 1-2 corrected)."""
    kind = draw(st.sampled_from(TABLE_1_KINDS))
    Q = draw(quadrics(kind, min_param=2, max_param=6, moved=False))
    axes = [draw(rationals(min_value=F(1, 20), max_value=F(1, 4), max_denominator=20)) for _ in range(3)]
    M = np.array([[float(v) for v in row] for row in Q.matrix])
    x = np.array([float(v) for v in draw(points(bound=4))])
    for _ in range(3):
        X = np.append(x, 1.0)
        g = 2 * (M @ X)[:3]
        if float(g @ g) > 1e-12:
            x = x - (X @ M @ X) * g / float(g @ g)
    offset = draw(points(bound=F(1, 4), max_denominator=16))
    centre = tuple(F(round(v * 64), 64) + o for v, o in zip(x, offset, strict=True))
    E = Quadric.ellipsoid(*axes, center=centre, rotation=draw(rotations()))
    assume(smallness(E, Q).small)
    return E, Q


@settings(max_examples=25, suppress_health_check=[HealthCheck.filter_too_much, HealthCheck.too_slow])
@given(pair=small_pairs())
def test_where_e_is_small_the_criterion_and_the_signatures_agree(pair):
    E, Q = pair
    d, truth = S.agree(E, Q)  # the signatures equal the exact extremes of X^T Q X on E
    code = corollary_10(E, Q, mode="exact").code
    event(f"{code.name}, {d.contact}")
    if code is CriterionCode.NON_REAL:
        assert d.contact == S.TRANSVERSAL and d.row == S.ROWS[3], d
    else:
        assert code is CriterionCode.ALL_REAL
        assert d.contact != S.TRANSVERSAL, (d, truth)  # Theorem 2: all roots real and small, no crossing
    # the package's decision table and exact predicates say the same
    problem = P.package_disagreement(E, Q)
    assert problem in (None, P.REFUSED), problem


def test_a_small_sphere_on_the_axis_of_a_cylinder_is_inside_it():
    d = S.signature_decision(Quadric.sphere(F(1, 10)), Quadric.from_equation("x**2 + y**2 - 1"))
    assert (d.contact, d.region, d.row) == (S.NONE, Region.R_MINUS, S.ROWS[0])
    assert d.pattern == "1,2,1" and d.signatures == (1, 0, 2, 3)
    # the witness is a negative definite member
    member = S._member(S.normalised_ellipsoid(Quadric.sphere(F(1, 10))), _m("x**2 + y**2 - 1"), d.witness)
    assert S.inertia(member) == (0, 4, 0)


def _m(text):
    return [[F(v) for v in row] for row in Quadric.from_equation(text).matrix]


@pytest.mark.parametrize(
    ("E", "Q", "contact", "region", "row"),
    [
        (Quadric.sphere(1), "x**2 + y**2 - 1", S.TOUCHING, Region.R_MINUS, 1),  # circle of tangency
        (Quadric.sphere(2), "x**2 + y**2 - 1", S.TRANSVERSAL, Region.CONTACT, 4),  # structural root, crossing
        (
            Quadric.sphere(1, (0, 0, 1)),
            "x**2 + y**2 - z**2",
            S.TRANSVERSAL,
            Region.CONTACT,
            5,
        ),  # through the apex
        (
            Quadric.ellipsoid(3, 1, F(1, 2)),
            "x**2 + y**2 + z**2 - 4",
            S.TRANSVERSAL,
            Region.CONTACT,
            2,
        ),  # Remark 9
        (Quadric.sphere(1, (2, 0, 0)), "x**2 + y**2 + z**2 - 1", S.TOUCHING, Region.R_PLUS, 1),
    ],
)
def test_rows_on_exact_pairs(E, Q, contact, region, row):
    d, _ = S.agree(E, Quadric.from_equation(Q))
    assert (d.contact, d.region, d.row) == (contact, region, S.ROWS[row])


def test_an_irrational_double_root_is_decided_in_its_quadratic_field():
    # P = -(l^2 + l - 1)^2: the members at (-1 +- sqrt 5)/2 have a two-dimensional kernel
    Q = Quadric.from_matrix([[0, 1, 0, 0], [1, 1, 0, 0], [0, 0, 2, 1], [0, 0, 1, 1]])
    d, _ = S.agree(Quadric.sphere(1), Q)
    assert d.pattern == "2,2" and d.contact == S.TOUCHING and not d.witness.is_Rational


@pytest.mark.parametrize("name", sorted(P.ROW_EXAMPLES))
def test_the_package_decision_table_agrees_on_every_row(name):
    E, Q = P.ROW_EXAMPLES[name]
    for q in (Q, -Q):
        problem = P.package_disagreement(E, q)
        assert problem in (None, P.REFUSED), problem
