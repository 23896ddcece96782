"""The depth of an ellipsoid into a solid that is not convex (hyperboloids, hyperbolic paraboloid
and cylinder), between an inscribed ellipsoid's depth and an exactly checked free translation
(:mod:`quadric_contact.modes.distance.nonconvex`): a closed form, the tests' brute force of
`proofs/_brute_depth.py` (no inscribed ellipsoid, no exact predicate) on every type, the float
mode, and the pairs left undecided.  That the inscribed ellipsoid lies in the solid is checked
exactly by ``proofs/depth_into_non_convex_solids.py``, which the proofs' test runs."""

from __future__ import annotations

from fractions import Fraction

import flint
import numpy as np
import pytest
from proofs._brute_depth import depth as brute_depth

import quadric_contact as qc
from quadric_contact import Quadric
from quadric_contact.exact.errors import UndecidedError
from quadric_contact.theory.overlap import overlap_exact, solid_of
from quadric_contact.theory.results import OverlapCode


def _pair(e, q):
    return Quadric.from_equation(e).as_ellipsoid(), solid_of(Quadric.from_equation(q))


def test_a_ball_in_the_cap_of_a_hyperboloid_of_two_sheets_closed_form():
    """The solid of ``x^2 + y^2 - z^2 + 1`` is the inside of the two caps, ``z^2 >= 1 + x^2 + y^2``.
    A ball of radius 1/5 at ``(0, 0, 11/10)`` leaves it downwards by ``11/10 + 1/5 - 1 = 3/10``:
    centred at height ``4/5``, its squared distance from the sheet, ``r^2 + (sqrt(1 + r^2) -
    4/5)^2``, increases with ``r^2`` from ``1/25`` (it touches at the vertex only); sideways the
    cap widens, so no shorter move frees it."""
    E, K = _pair("x^2 + y^2 + (z - 11/10)^2 - 1/25", "x^2 + y^2 - z^2 + 1")
    assert overlap_exact(E, K).code is OverlapCode.OVERLAPPING
    r = qc.distance(E, K, digits=20)
    assert r.method == "inscribed ellipsoid"
    lo, hi = r.bounds
    assert lo <= Fraction(-3, 10) <= hi and hi - lo <= Fraction(1, 10**20)
    assert r.point_Q is None and r.normal is None  # the contact is K's only where the bounds are equal
    f = qc.distance(E, K, mode="float")
    assert not f.uncertain and Fraction(f.bounds[0]) <= Fraction(-3, 10) <= Fraction(f.bounds[1])


NONCONVEX = [
    (
        "ball inside the tube of a hyperboloid of one sheet",
        "(x - 4/5)^2 + y^2 + (z - 1/2)^2 - 9/100",
        "x^2 + y^2 - z^2 - 1",
    ),
    (
        "ball outside the tube, crossing its wall",
        "(x - 13/10)^2 + y^2 + (z - 1/2)^2 - 9/100",
        "x^2 + y^2 - z^2 - 1",
    ),
    (
        "tilted ellipsoid crossing an elliptic tube",
        "(x - 9/10)^2/(1/25) + (y - 1/10)^2/(9/100) + (z - 3/10)^2/(1/100) + 3/10*(x - 9/10)*(z - 3/10) - 1",
        "x^2 + y^2/2 - z^2 - 1",
    ),
    (
        "ellipsoid crossing a hyperbolic paraboloid",
        "(x - 1/5)^2/(1/25) + y^2/(9/100) + (z - 1/20)^2/(1/100) - 1",
        "z - x^2 + y^2",
    ),
    (
        "ellipsoid crossing a hyperbolic cylinder",
        "(x - 6/5)^2/(1/25) + (y - 1/5)^2/(1/16) + z^2/(1/9) - 1",
        "x^2 - y^2 - 1",
    ),
]


@pytest.mark.parametrize(
    ("name", "e", "q"),
    [
        pytest.param(*c, marks=pytest.mark.slow, id=c[0].split(",")[0])  # about 20 s each
        for c in NONCONVEX
    ],
)
def test_the_enclosure_holds_the_brute_force_depth(name, e, q):
    E, K = _pair(e, q)
    assert K.kind.value in name or "tube" in name
    assert overlap_exact(E, K).code is OverlapCode.OVERLAPPING
    r = qc.distance(E, K)
    assert r.method == "inscribed ellipsoid" and r.distance < 0
    assert r.distance.rad() <= abs(r.distance.mid()) * flint.arb(10) ** -15
    want = -brute_depth(E.to_numpy(), K.to_numpy(), 2.0)
    assert abs(float(r.distance.mid()) - want) <= 1e-8 * abs(want), (r.distance, want)


@pytest.mark.slow
def test_a_ball_in_the_waist_of_a_tube_is_answered_right_or_left_undecided():
    """Outside the tube ``x^2 + y^2 <= 1 + z^2`` at its waist, a large ball crossing the wall
    is freed by a move after which it touches the flaring wall above and below: no single
    inscribed ellipsoid meets that, and the pair may be left undecided, never answered wrong."""
    E, K = _pair("(x - 1.6)^2 + y^2 + z^2 - 0.49", "x^2 + y^2 - z^2 - 1")
    assert overlap_exact(E, K).code is OverlapCode.OVERLAPPING
    try:
        r = qc.distance(E, K)
    except UndecidedError as exc:
        assert "not convex" in str(exc) and "two points" in str(exc)
        return
    want = -brute_depth(E.to_numpy(), K.to_numpy(), 2.0)
    assert abs(float(r.distance.mid()) - want) <= 1e-8 * abs(want)


def test_a_stack_holds_the_pair_enclosure():
    """A float64 stack answers its binary64 pair: a ball of radius 1/4 at ``(0, 0, 9/8)`` (binary64
    entries), freed downwards by ``9/8 + 1/4 - 1 = 3/8`` as in the closed form above."""
    E, K = _pair("x^2 + y^2 + (z - 9/8)^2 - 1/16", "x^2 + y^2 - z^2 + 1")
    assert all(Fraction(float(E[i, j])) == E[i, j] for i in range(4) for j in range(4))
    lo, hi = qc.distance(np.array([E.to_numpy()]), np.array([K.to_numpy()]))[0]
    assert Fraction(lo) <= Fraction(-3, 8) <= Fraction(hi) and hi - lo <= 1e-15


def test_entries_beyond_binary64_are_refused_with_the_reason_not_a_crash():
    """The bracket's search runs in binary64: a solid whose entries binary64 cannot hold is left
    undecided (the reason names it), never an ``OverflowError``."""
    E, K = _pair("x^2 + y^2 + (z - 11/10)^2 - 1/25", "10^400*x^2 + y^2 - z^2 + 1")
    with pytest.raises(UndecidedError):
        qc.distance(E, K)
