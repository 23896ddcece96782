"""The distance on families and along paths, against closed forms derived here."""

from __future__ import annotations

from fractions import Fraction

import pytest

from quadric_contact import Quadric
from quadric_contact.families.family import family
from quadric_contact.families.family_distance import family_contact_scale, family_distance
from quadric_contact.scenes.path_distance import path_distance
from quadric_contact.scenes.trajectory import PolynomialMotion


def test_family_distance_and_scale_follow_the_parameter():
    # a ball of radius 1/2 at (a, 0, 0) and the unit sphere: apart by a - 3/2 for a > 3/2
    fam = family("(x - a)**2 + y**2 + z**2 - 1/4", "x**2 + y**2 + z**2 - 1", ["a"])
    points = [{"a": Fraction(k, 2)} for k in (4, 5, 7)]
    got = [r.distance for r in family_distance(fam, points, mode="exact")]
    assert got == [p["a"] - Fraction(3, 2) for p in points]
    scales = [r.scale for r in family_contact_scale(fam, points)]
    assert scales == [(p["a"] - 1) * 2 for p in points]  # E reaches the sphere when s/2 = a - 1


def test_closest_approach_of_a_ball_passing_a_sphere():
    # centre (t, 3, 0) for t in [-2, 3]: distance sqrt(t^2 + 9) - 1 - 1/4, least 7/4 at t = 0
    path = PolynomialMotion([[0, 1], [3], [0]])
    r = path_distance(
        Quadric.sphere(Fraction(1, 4)), "x**2 + y**2 + z**2 - 1", path, -2, 3, tolerance=Fraction(1, 10**3)
    )
    lo, hi = r.minimum
    assert lo <= Fraction(7, 4) <= hi and hi - lo <= Fraction(1, 10**3)
    assert any(a <= 0 <= b for a, b in r.times)
    assert all(-Fraction(1, 2) < a < b < Fraction(1, 2) for a, b in r.times)  # d - 7/4 ~ t^2 / 6


@pytest.mark.parametrize(("height", "least"), [(Fraction(3), Fraction(1)), (Fraction(3, 2), Fraction(-1, 2))])
def test_a_turning_ellipsoid_holds_the_closed_form_minimum(height, least):
    """Semi-axes (2, 1/2, 1/2) at a fixed height, turned about y by 2 atan t: its lowest point is
    at height - sqrt(4 sin^2 + cos^2 / 4) of the angle, least (height - 2) at t = 1; apart from
    the half-space z <= 0, then crossing it."""
    E0 = Quadric.ellipsoid(2, Fraction(1, 2), Fraction(1, 2), center=(0, 0, height))
    path = PolynomialMotion([[0], [0], [0]], [[1], [0], [0, 1], [0]])
    r = path_distance(E0, "z", path, 0, 2, tolerance=Fraction(1, 10**3))
    lo, hi = r.minimum
    assert lo <= least <= hi and hi - lo <= Fraction(1, 10**3)
    assert any(a <= 1 <= b for a, b in r.times)
    assert all(Fraction(3, 4) < a < b < Fraction(5, 4) for a, b in r.times)


def test_a_turning_ellipsoid_stays_above_the_enclosure_at_every_sampled_time():
    """Turning about a tilted axis and moving: the enclosure's lower end is below the exact
    distance at every sampled time (the bound on the points' displacement is sound)."""
    from quadric_contact import distance

    E0 = Quadric.ellipsoid(Fraction(3, 2), Fraction(1, 2), Fraction(1, 3), center=(0, 0, 4))
    path = PolynomialMotion([[0, 1], [0], [0, -1]], [[1], [0, Fraction(1, 2)], [0, 1], [Fraction(1, 3)]])
    r = path_distance(E0, "z", path, 0, 2, tolerance=Fraction(1, 10**2))
    lo, hi = r.minimum
    (seg,) = path.segments(Fraction(0), Fraction(2), (0, 0, 4))
    values = []
    for k in range(33):
        t = Fraction(k, 16)
        values.append(distance(E0.moved(seg.rigid_motion(t, (0, 0, 4))), "z", mode="exact").distance)
    assert all(v >= lo for v in values)
    assert min(values) <= hi + Fraction(1, 10**2)
