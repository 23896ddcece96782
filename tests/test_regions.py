"""Table 4 re-derived, and checked on random placements; R-/R+ swap with -Q."""

from fractions import Fraction

import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

from quadric_contact import (
    ROOT_SIGN_TABLE,
    Quadric,
    QuadricKind,
    Region,
    characteristic_polynomial,
    relative_position,
)
from quadric_contact.model.classification import TABLE_1_KINDS
from quadric_contact.testing.strategies import points, rigid_motions, rotations
from quadric_contact.theory.regions import derive_root_sign_table


def test_table_is_rederived_by_construction():
    assert derive_root_sign_table() == ROOT_SIGN_TABLE


@given(
    kind=st.sampled_from(TABLE_1_KINDS),
    center=points(bound=12),
    rot=rotations(),
    m=rigid_motions(),
    flip=st.booleans(),
)
def test_small_probe_anywhere_clear_of_q_matches_table(kind, center, rot, m, flip):
    """A tiny ellipsoid placed anywhere: when the exact centre test and the
    absence of non-real roots show it clear of Q, Table 4 must agree with the
    sign of Q at its centre."""
    params = {"a": 5, "b": 4, "c": 3}
    n = (
        3
        if kind
        in (QuadricKind.ELLIPSOID, QuadricKind.HYPERBOLOID_ONE_SHEET, QuadricKind.HYPERBOLOID_TWO_SHEETS)
        else 1
        if kind in (QuadricKind.PARABOLIC_CYLINDER, QuadricKind.PARALLEL_PLANES)
        else 2
    )
    q = Quadric.standard(kind, **dict(list(params.items())[:n])).moved(m)
    if flip:
        q = -q
    e = Quadric.ellipsoid(
        Fraction(1, 20), Fraction(1, 30), Fraction(1, 40), center=m.apply(center), rotation=rot
    )
    P = characteristic_polynomial(e, q)
    value = q.value_at(m.apply(center))
    assume(P.structure.all_real and value != 0)
    r = relative_position(e, q, small=True)
    assert r.region is (Region.R_MINUS if value < 0 else Region.R_PLUS)
    assert r.decided_by == "Theorem 13 / Table 4"


def test_negated_q_swaps_regions():
    e = Quadric.sphere(Fraction(1, 4), (0, 0, 0))
    q = Quadric.hyperboloid_one_sheet(2, 2, 1)
    assert relative_position(e, q, small=True) == Region.R_MINUS
    assert relative_position(e, -q, small=True) == Region.R_PLUS
    # For the one-sheet hyperboloid the patterns are symmetric under negation and swap ...
    assert relative_position(e, -q, small=True).expected == {"R+": "-+++", "R-": "---+"}
    # ... for an ellipsoid they are not: inside -Q (its R+) every root is positive.
    ell = Quadric.ellipsoid(2, 2, 2)
    r = relative_position(e, -ell, small=True)
    assert r == Region.R_PLUS and r.polynomial.signs.pattern == "++++"
    assert r.expected == {"R+": "++++", "R-": "--++"}


@pytest.mark.parametrize("z, region", [(-1, Region.R_MINUS), (1, Region.R_PLUS), (0, Region.CONTACT)])
def test_plane_regions_by_theorem_14(z, region):
    r = relative_position(Quadric.sphere(Fraction(1, 2), (0, 0, z)), "z")
    assert r == region
    assert r.decided_by in ("signature sequence", "Remark 9")
    paper = relative_position(Quadric.sphere(Fraction(1, 2), (0, 0, z)), "z", method="theory")
    assert paper == region and paper.decided_by in ("Theorem 14", "Remark 9")


def test_contact_reported_as_region():
    r = relative_position(Quadric.sphere(1, (2, 0, 0)), Quadric.ellipsoid(2, 2, 2))
    assert r == Region.CONTACT and r.decided_by == "Remark 9"
