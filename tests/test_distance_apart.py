"""Two ellipsoids whose solids are apart, in the ``certified`` mode: the isolated root of the
support system (``proofs/distance_of_separated_ellipsoids.py``) against the general route (every
critical point of the contact system isolated), closed forms on an axis, many digits, and the
pairs it leaves to the general route.  The brute-force comparison of every type is in
``tests/test_distance_critical.py``."""

from __future__ import annotations

from fractions import Fraction

import flint
import numpy as np
import pytest

import quadric_contact as qc
from quadric_contact import Quadric
from quadric_contact.modes.distance.certified import apart_ellipsoids
from quadric_contact.testing.samples import ellipsoid_matrix, random_rotations
from quadric_contact.theory.distance_critical import critical_distance
from quadric_contact.theory.overlap import solid_of


def _pairs(n, seed):
    rng = np.random.default_rng(seed)
    out = []
    for k in range(n):
        R1, R2 = random_rotations(2, rng)
        axes1, axes2 = rng.uniform(0.2, 1.5, (2, 3))
        if k % 3 == 1:
            axes1 = np.array([1.0, 0.1, 0.05]) * rng.uniform(0.8, 1.2, 3)  # a needle
        d = rng.normal(size=3)
        d /= np.linalg.norm(d)
        centre = d * (axes1.max() + axes2.max() + rng.uniform(0.01, 3))
        E = Quadric.from_matrix(ellipsoid_matrix(axes1, R1, np.zeros(3))).as_ellipsoid()
        out.append((E, solid_of(Quadric.from_matrix(ellipsoid_matrix(axes2, R2, centre)))))
    return out


def agrees_with_the_general_route(fast, e, k, digits):
    """The distance and the three witnesses overlap the balls of the general route (every
    critical point of the contact system isolated)."""
    general = critical_distance(e, k, convex=True, digits=digits)
    assert fast.distance.overlaps(general.distance)
    for a, b in (
        (fast.point_E, general.point_E),
        (fast.point_Q, general.point_Q),
        (fast.normal, general.normal),
    ):
        assert all(x.overlaps(y) for x, y in zip(a, b, strict=True))


@pytest.mark.parametrize("seed", [0, 1])
def test_the_isolated_root_agrees_with_the_general_route(seed):
    answered = 0
    for e, k in _pairs(4, seed):
        fast = apart_ellipsoids(e, k, 20)
        if fast is None:
            continue
        answered += 1
        agrees_with_the_general_route(fast, e, k, 20)
        assert fast.distance.rad() <= abs(fast.distance.mid()) * flint.arb(10) ** -20
        r = qc.distance(e, k, digits=20)
        assert r.method == "ellipsoid-ellipsoid" and r.distance.overlaps(fast.distance)
    assert answered >= 3


@pytest.mark.parametrize("gap", [Fraction(3), Fraction(1, 10**9), Fraction(1, 10**15)])
def test_two_ellipsoids_on_an_axis_at_many_digits(gap):
    """Tips 2 and ``2 + gap`` on the x axis, both surfaces curving away: the tips are the
    nearest points (their tangent planes separate the solids), the distance is ``gap``."""
    E = "x**2/4 + y**2 + z**2 - 1"
    K = Quadric.from_matrix(
        [[1, 0, 0, -(3 + gap)], [0, 4, 0, 0], [0, 0, 4, 0], [-(3 + gap), 0, 0, (3 + gap) ** 2 - 1]]
    )
    r = qc.distance(E, K, digits=60)
    assert r.method == "ellipsoid-ellipsoid"
    lo, hi = r.bounds
    assert lo <= gap <= hi
    assert r.distance.rad() <= abs(r.distance.mid()) * flint.arb(10) ** -60
    assert all(p.contains(v) for p, v in zip(r.point_E, (2, 0, 0), strict=True))
    assert all(n.contains(v) for n, v in zip(r.normal, (-1, 0, 0), strict=True))


def test_crossing_and_touching_pairs_go_to_the_general_route():
    E = Quadric.from_equation("x**2/4 + y**2 + z**2 - 1").as_ellipsoid()
    crossing = solid_of(Quadric.from_equation("(x - 2)**2 + y**2 + z**2 - 1"))
    touching = solid_of(Quadric.from_equation("(x - 3)**2 + y**2 + z**2 - 1"))
    assert apart_ellipsoids(E, crossing, 15) is None
    assert apart_ellipsoids(E, touching, 15) is None
    assert qc.distance(E, touching).distance.contains(0)
    assert qc.distance(E, crossing).distance < 0
