"""Two crossing ellipsoids in the ``certified`` mode, one pair a call: the depth kernel's global
lower bound, one root of the support system isolated on a box, and a covering of the rest of the
sphere (``proofs/depth_of_crossing_ellipsoids.py``, "the cap").  Every enclosure holds the
tests' brute-force minimiser's depth and agrees with the general route (every critical point of
the contact system isolated); pairs the route cannot settle go to the general route."""

from __future__ import annotations

import math
from fractions import Fraction

import flint
import mpmath
import numpy as np
import pytest
from tests.test_depth_kernel import _brute_depth, _mirrored, _shallow, _two_minima
from tests.test_distance_apart import agrees_with_the_general_route

import quadric_contact as qc
from quadric_contact import Quadric, RigidMotion
from quadric_contact.exact.precision import working_precision
from quadric_contact.modes.distance.certified import (
    MAX_BITS,
    _inverse3,
    _rounding_gap,
    apart_ellipsoids,
    crossing_ellipsoids,
)
from quadric_contact.modes.distance.depth_kernel import covered_outside_cap, depth_and_minimiser
from quadric_contact.testing.samples import ellipsoid_matrix, random_rotations
from quadric_contact.theory.contact_scale import centred_form
from quadric_contact.theory.distance_critical import critical_distance
from quadric_contact.theory.overlap import solid_of


def _pair(rng, spread=0.5):
    R1, R2 = random_rotations(2, rng)
    return tuple(
        ellipsoid_matrix(rng.uniform(0.3, 1.5, 3), R, rng.uniform(-spread, spread, 3)) for R in (R1, R2)
    )


def _quadrics(E, K):
    return Quadric.from_matrix(E).as_ellipsoid(), solid_of(Quadric.from_matrix(K))


def _holds(ball, value):
    mid, rad = (mpmath.mpf(x.str(60, radius=False)) for x in (ball.mid(), ball.rad()))
    return mid - rad <= value <= mid + rad


@pytest.mark.parametrize("digits", [12, 15, 30])
def test_each_enclosure_holds_the_brute_force_depth(digits):
    rng = np.random.default_rng(digits)
    answered = 0
    for _ in range(6):
        E, K = _pair(rng)
        e, k = _quadrics(E, K)
        r = crossing_ellipsoids(e, k, digits)
        if r is None:
            continue
        answered += 1
        with working_precision(dps=digits + 20):
            assert _holds(r.distance, -_brute_depth(E, K, digits=digits + 8))
        assert r.distance.rad() <= abs(r.distance.mid()) * flint.arb(10) ** -digits
        # the witnesses: point_E = point_Q + distance * normal, the normal a unit vector
        for i in range(3):
            assert (r.point_Q[i] + r.distance * r.normal[i]).overlaps(r.point_E[i])
        assert sum((x * x for x in r.normal), flint.arb(0)).overlaps(flint.arb(1))
    assert answered >= 5


@pytest.mark.parametrize("depth", [1e-2, 1e-4, 1e-6, 1e-9])
def test_shallow_pairs_the_kernel_cannot_enclose_to_1e_12_are_answered(depth):
    """The kernel only locates the minimum (at ``1e-6``, or ``1e-3``, relative): the digits come
    from the root, so a depth far below the ellipsoids' size keeps its relative accuracy."""
    E, K = _shallow(np.random.default_rng(1), depth)
    e, k = _quadrics(E, K)
    r = crossing_ellipsoids(e, k, 15)
    assert r is not None
    with working_precision(dps=70):
        assert _holds(r.distance, -_brute_depth(E, K, digits=50))
    assert r.distance < 0 and r.distance.rad() <= abs(r.distance.mid()) * flint.arb(10) ** -15
    # the float mode, a pair and a stack of one, rounds the same route's balls outwards
    f = qc.distance(E, K, mode="float")
    assert not f.uncertain
    for lo, hi in (f.bounds, tuple(qc.distance(E[None], K[None], mode="float")[0])):
        assert Fraction(lo) <= Fraction(float(r.distance.mid())) <= Fraction(hi)
        assert hi - lo <= 1e-15 * abs(hi)  # a few units in the last place


def test_it_agrees_with_the_general_route_and_is_what_the_predicate_runs():
    rng = np.random.default_rng(4)
    for _ in range(2):
        E, K = _pair(rng)
        e, k = _quadrics(E, K)
        fast = crossing_ellipsoids(e, k, 20)
        assert fast is not None
        agrees_with_the_general_route(fast, e, k, 20)
        r = qc.distance(E, K, digits=20)
        assert r.method == "crossing ellipsoids" and r.distance.overlaps(fast.distance)
        # the same number as the stack of one, which the kernel encloses at 1e-12
        lo, hi = qc.distance(E[None], K[None])[0]
        assert Fraction(lo) <= Fraction(float(r.distance.mid())) <= Fraction(hi)


def test_two_equal_minima_are_left_to_the_general_route():
    """Mirror images and identical ellipsoids shifted along an axis have two minima of equal
    depth: the covering finds the other one below the root's value, and the route declines."""
    rng = np.random.default_rng(2)
    for E, K in (_mirrored(rng), _two_minima(rng)):
        found = depth_and_minimiser(E, K)
        assert found is not None  # the kernel encloses the depth ...
        e, k = _quadrics(E, K)
        assert crossing_ellipsoids(e, k, 15) is None  # ... but the minimiser is not isolated


def test_the_covering_fails_where_phi_dips_below_the_target_outside_the_cap():
    """Unit balls at 0 and (1, 0, 0): ``phi(u) = 2 - u_x`` (depth 1 at ``u = x``), below the target
    ``2 - cos b`` exactly within the angle ``b`` of ``x``.  With a cap of half-angle ``a``, the
    covering proves a target whose region below lies well inside the cap (``b = a / 2``) and
    none whose region below reaches out of it (``b = 2 a``), nor any above the depth with the cap
    on the wrong side."""
    E = np.diag([1.0, 1.0, 1.0, -1.0])
    K = E.copy()
    K[0, 3] = K[3, 0] = -1.0
    K[3, 3] = 0.0
    x = np.array([1.0, 0.0, 0.0])
    a = 0.1
    assert covered_outside_cap(E, K, 1.0, x, math.cos(a))
    assert covered_outside_cap(E, K, 2 - math.cos(a / 2), x, math.cos(a))
    assert not covered_outside_cap(E, K, 2 - math.cos(2 * a), x, math.cos(a))
    assert not covered_outside_cap(E, K, 1.0 + 1e-9, -x, math.cos(a))
    with pytest.raises(ValueError):
        covered_outside_cap(E, K, math.nan, x, math.cos(a))


def test_entries_that_are_not_binary64_run_the_kernel_on_the_rounded_pair():
    """The kernel covers the pair rounded to binary64, within the rounding gap of the pair; the
    root is the exact pair's: the same balls as the general route."""
    e = Quadric.ellipsoid(Fraction(1, 3), Fraction(1, 2), Fraction(2, 3))
    k = solid_of(
        Quadric.ellipsoid(
            Fraction(2, 5), Fraction(1, 3), Fraction(3, 7), center=(Fraction(1, 5), 0, Fraction(1, 7))
        )
    )
    assert _rounding_gap(k, k.to_numpy()) > 0  # 49/9 is not a binary64 number
    r = crossing_ellipsoids(e, k, 20)
    assert r is not None and r.distance < 0
    assert r.distance.overlaps(critical_distance(e, k, convex=True, digits=20).distance)
    assert qc.distance(e, k, digits=20).method == "crossing ellipsoids"


def test_the_rounding_gap_bounds_the_support_functions_apart():
    """``|h_Q(u) - h_Q'(u)|`` at 400 directions, in 200-bit balls, for rational ellipsoids and
    their binary64 roundings: never above the gap, which is not far above the largest seen."""
    rng = np.random.default_rng(9)
    for _ in range(6):
        axes = [Fraction(int(x), 97) for x in rng.integers(20, 150, 3)]
        centre = [Fraction(int(x), 89) for x in rng.integers(-60, 60, 3)]
        q = solid_of(Quadric.ellipsoid(*axes, center=centre).moved(_TURN))
        rounded = Quadric.from_matrix([[Fraction(float(x)) for x in row] for row in q.to_numpy()])
        gap = _rounding_gap(q, q.to_numpy())
        assert gap > 0
        with working_precision(200):
            worst = flint.arb(0)
            for u in rng.normal(size=(400, 3)):
                u = [flint.arb(float(x)) for x in u / np.linalg.norm(u)]
                d = _support(q, u) - _support(rounded, u)
                worst = max(worst, abs(d).upper())
                assert abs(d) < flint.arb(gap.numerator) / gap.denominator
        assert worst.upper() * 100 >= flint.arb(gap.numerator) / gap.denominator  # not a vacuous bound


_TURN = RigidMotion.from_quaternion(3, 1, -2, 1)


def _support(q, u):
    """``h(u) = u . c + sqrt(r u^T A^-1 u)`` of an ellipsoid, in balls."""
    A, c, r = centred_form(q)
    B = [[flint.arb(x.numerator) / x.denominator for x in row] for row in _inverse3(A)]
    quad = sum((u[i] * B[i][j] * u[j] for i in range(3) for j in range(3)), flint.arb(0))
    return (
        sum((u[i] * flint.arb(c[i].numerator) / c[i].denominator for i in range(3)), flint.arb(0))
        + (flint.arb(r.numerator) / r.denominator * quad).sqrt()
    )


def test_more_digits_than_the_precision_bound_are_enclosed_at_the_bound():
    """Digits beyond ``MAX_BITS`` give the enclosure at ``MAX_BITS``, as the general route does,
    within the same bounded work, rather than a fall back to the general route."""
    E, K = _pair(np.random.default_rng(4))
    e, k = _quadrics(E, K)
    r = crossing_ellipsoids(e, k, 10**5)
    assert r is not None and r.bits == MAX_BITS and r.method == "crossing ellipsoids"
    assert r.distance.rad() <= abs(r.distance.mid()) * flint.arb(10) ** -1200
    far = Quadric.from_matrix(K).moved(RigidMotion.from_quaternion(1, 0, 0, 0, (6, 0, 0)))
    a = apart_ellipsoids(e, solid_of(far), 10**5)
    assert a is not None and a.bits == MAX_BITS and a.distance > 0
