"""The distance of any ellipsoid from a curved quadric (the contact system's critical points
isolated by the Krawczyk operator) against independent computations: the brute-force ray
minimiser at high precision for separated pairs of every type; for a penetration, the gap after
moving ``E`` by the depth and a little more along the normal, by the same minimiser; the
sphere's secular equation; and the witnesses on the surfaces."""

from __future__ import annotations

from fractions import Fraction

import flint
import mpmath
import numpy as np
import pytest

import quadric_contact as qc
from brute_distance import surface_gap
from quadric_contact import Quadric, QuadricKind
from quadric_contact.exact.errors import UndecidedError
from quadric_contact.exact.precision import working_precision
from quadric_contact.model.motions import RigidMotion
from quadric_contact.modes.distance.certified import distance_certified
from quadric_contact.theory.distance import CONVEX_SOLIDS, distance_exact
from quadric_contact.theory.distance_critical import critical_distance
from quadric_contact.theory.overlap import solid_of

DIGITS = 28
MOTION = RigidMotion.from_quaternion(3, 1, -2, 1, (Fraction(1, 3), Fraction(-2, 5), Fraction(1, 7)))
TURN = RigidMotion.from_quaternion(1, 2, 0, -1, (0, 0, 0))

TYPES = {
    QuadricKind.ELLIPSOID: Quadric.ellipsoid(2, Fraction(3, 2), 1),
    QuadricKind.HYPERBOLOID_ONE_SHEET: Quadric.hyperboloid_one_sheet(2, 1, Fraction(3, 2)),
    QuadricKind.HYPERBOLOID_TWO_SHEETS: Quadric.hyperboloid_two_sheets(2, Fraction(3, 2), 1),
    QuadricKind.ELLIPTIC_PARABOLOID: Quadric.elliptic_paraboloid(2, 1),
    QuadricKind.HYPERBOLIC_PARABOLOID: Quadric.hyperbolic_paraboloid(2, 1),
    QuadricKind.ELLIPTIC_CYLINDER: Quadric.elliptic_cylinder(2, 1),
    QuadricKind.HYPERBOLIC_CYLINDER: Quadric.hyperbolic_cylinder(2, 1),
    QuadricKind.PARABOLIC_CYLINDER: Quadric.parabolic_cylinder(1),
    QuadricKind.PARALLEL_PLANES: Quadric.parallel_planes(2),
}

# centres of E at which the solids are apart (SEPARATE) or cross (a convex solid), per type
APART = {
    QuadricKind.ELLIPSOID: (Fraction(5, 2), Fraction(7, 3), Fraction(-3, 2)),
    QuadricKind.HYPERBOLOID_ONE_SHEET: (Fraction(-4), Fraction(1, 2), Fraction(3)),
    QuadricKind.HYPERBOLOID_TWO_SHEETS: (Fraction(1, 5), Fraction(-1, 3), Fraction(1, 4)),
    QuadricKind.ELLIPTIC_PARABOLOID: (Fraction(5, 2), Fraction(7, 3), Fraction(-3, 2)),
    QuadricKind.HYPERBOLIC_PARABOLOID: (Fraction(5, 2), Fraction(7, 3), Fraction(-3, 2)),
    QuadricKind.ELLIPTIC_CYLINDER: (Fraction(-4), Fraction(1, 2), Fraction(3)),
    QuadricKind.HYPERBOLIC_CYLINDER: (Fraction(0), Fraction(0), Fraction(5)),
    QuadricKind.PARABOLIC_CYLINDER: (Fraction(5, 2), Fraction(7, 3), Fraction(-3, 2)),
    QuadricKind.PARALLEL_PLANES: (Fraction(0), Fraction(0), Fraction(5)),
}
CROSSING = {
    QuadricKind.ELLIPSOID: (Fraction(1, 5), Fraction(-1, 3), Fraction(1, 4)),
    QuadricKind.ELLIPTIC_PARABOLOID: (Fraction(1, 5), Fraction(-1, 3), Fraction(1, 4)),
    QuadricKind.ELLIPTIC_CYLINDER: (Fraction(5, 2), Fraction(7, 3), Fraction(-3, 2)),
    QuadricKind.PARABOLIC_CYLINDER: (Fraction(1, 5), Fraction(-1, 3), Fraction(1, 4)),
    QuadricKind.PARALLEL_PLANES: (Fraction(5, 2), Fraction(7, 3), Fraction(-3, 2)),
}
FAST = {QuadricKind.ELLIPSOID, QuadricKind.HYPERBOLOID_TWO_SHEETS}


def _ellipsoid(centre):
    """A tilted ellipsoid with semi-axes 1/2, 1/3, 1/5 (not a sphere) about ``centre``."""
    return (
        Quadric.ellipsoid(Fraction(1, 2), Fraction(1, 3), Fraction(1, 5))
        .moved(TURN)
        .moved(RigidMotion.from_quaternion(1, 0, 0, 0, centre))
    )


def _mp(ball):
    return mpmath.mpf(ball.mid().str(60, radius=False))


def _close(ball, want):
    """``want`` within the ball widened by ``10^-DIGITS`` relative (the reference's accuracy)."""
    lo, hi = _mp(ball) - _mp(ball.rad()), _mp(ball) + _mp(ball.rad())
    slack = mpmath.mpf(10) ** (-DIGITS) * max(1, abs(want))
    return lo - slack <= want <= hi + slack


def _marks(kind):
    return () if kind in FAST else (pytest.mark.slow,)


@pytest.mark.parametrize("kind", [pytest.param(k, marks=_marks(k), id=k.name.lower()) for k in APART])
def test_separated_distance_equals_the_brute_force_minimum(kind):
    q = TYPES[kind].moved(MOTION)
    e = _ellipsoid(APART[kind])
    r = qc.distance(e, q, digits=DIGITS + 4)
    # two ellipsoids apart: the isolated root of the support system (no critical point search)
    assert r.method == ("ellipsoid-ellipsoid" if kind is QuadricKind.ELLIPSOID else "ellipsoid-quadric")
    with working_precision(dps=DIGITS + 20):
        want = surface_gap(e, q, digits=DIGITS + 4)
        assert want > 0
        assert _close(r.distance, want), (r.distance, want)
    assert r.distance.rad() <= abs(r.distance.mid()) * flint.arb(10) ** (-DIGITS - 4)


@pytest.mark.parametrize(
    "kind",
    [
        pytest.param(k, marks=() if k is QuadricKind.ELLIPSOID else (pytest.mark.slow,), id=k.name.lower())
        for k in CROSSING
    ],
)
def test_depth_moves_e_to_touch(kind):
    """Moving ``E`` by ``depth + delta`` along the normal leaves it ``delta`` apart from the
    solid (the brute-force minimum): the depth and the normal are exact to the digits."""
    q = TYPES[kind].moved(MOTION)
    e = _ellipsoid(CROSSING[kind])
    r = qc.distance(e, q, digits=DIGITS + 4)
    assert r.distance < 0
    delta = mpmath.mpf(1) / 10
    with working_precision(dps=DIGITS + 20):
        depth = -_mp(r.distance)
        shift = [(depth + delta) * _mp(n) for n in r.normal]
        gap = surface_gap(e, q, digits=DIGITS + 4, shift=shift)
        assert abs(gap - delta) <= mpmath.mpf(10) ** (-DIGITS + 2), (gap, delta)


@pytest.mark.parametrize("kind", list(TYPES), ids=lambda k: k.name.lower())
def test_sphere_through_the_contact_system_equals_the_secular_equation(kind):
    q = TYPES[kind].moved(MOTION)
    K = solid_of(q)
    for centre in (APART[kind], CROSSING.get(kind)):
        if centre is None:
            continue
        e = Quadric.sphere(Fraction(1, 3), centre)
        try:
            exact = distance_exact(e, q)
        except UndecidedError:
            continue
        if kind not in CONVEX_SOLIDS and exact.distance.sign() <= 0:
            continue
        got = critical_distance(e, K, convex=kind in CONVEX_SOLIDS, digits=30).distance
        exact.distance.refine(Fraction(1, 10**40))
        lo, hi = exact.distance.interval
        assert got.overlaps(
            flint.arb(flint.fmpq(lo.numerator, lo.denominator)).union(
                flint.arb(flint.fmpq(hi.numerator, hi.denominator))
            )
        )
        assert got.rad() < 1e-29 * max(1, abs(float(got.mid())))


def _value(K, p):
    M = [[flint.arb(flint.fmpq(v.numerator, v.denominator)) for v in row] for row in K.matrix]
    X = [*p, flint.arb(1)]
    return sum(X[i] * M[i][j] * X[j] for i in range(4) for j in range(4))


@pytest.mark.parametrize(
    "kind", [QuadricKind.ELLIPSOID, QuadricKind.HYPERBOLIC_PARABOLOID], ids=lambda k: k.name.lower()
)
def test_witnesses_lie_on_the_surfaces_along_the_normal(kind):
    q = TYPES[kind].moved(MOTION)
    K = solid_of(q)
    e = _ellipsoid(APART[kind])
    r = distance_certified(e, q, digits=30)
    with working_precision(200):
        _check_witnesses(r, e, K)


def _check_witnesses(r, e, K):
    tol = flint.arb(10) ** -25
    assert abs(_value(K, r.point_Q)) < tol
    assert abs(_value(e, r.point_E)) < tol
    assert abs(sum(n * n for n in r.normal) - 1) < tol
    M = [[flint.arb(flint.fmpq(v.numerator, v.denominator)) for v in row] for row in K.matrix]
    grad = [sum(M[i][j] * x for j, x in enumerate([*r.point_Q, flint.arb(1)])) for i in range(3)]
    gn = sum(g * g for g in grad).sqrt()
    assert all(abs(grad[i] / gn - r.normal[i]) < tol for i in range(3))  # out of K
    assert all(abs(r.point_E[i] - r.point_Q[i] - r.distance * r.normal[i]) < tol for i in range(3))


def test_float_mode_encloses_the_certified_value():
    q = TYPES[QuadricKind.ELLIPTIC_PARABOLOID].moved(MOTION)
    for centre in (APART[QuadricKind.ELLIPTIC_PARABOLOID], CROSSING[QuadricKind.ELLIPTIC_PARABOLOID]):
        e = _ellipsoid(centre)
        c = qc.distance(e, q, digits=30).distance
        f = qc.distance(e, q, mode="float")
        assert not f.uncertain and f.error < 1e-13 * max(1, abs(f.distance))
        lo, hi = f.bounds
        assert c.overlaps(flint.arb(lo).union(flint.arb(hi)))
    stack = qc.distance([e, e], q, mode="float")
    assert stack.shape == (2, 2) and np.all(stack[:, 0] <= stack[:, 1])


def test_crossing_a_non_convex_solid_is_bracketed_in_every_mode_that_answers():
    """The depth into a hyperboloid's solid: the certified bracket (an inscribed ellipsoid, a
    free translation checked exactly), the float mode rounding it outwards; the exact mode,
    which has no algebraic route for an ellipsoid that is not a sphere, refuses."""
    q = TYPES[QuadricKind.HYPERBOLOID_ONE_SHEET].moved(MOTION)
    e = _ellipsoid((Fraction(5, 2), Fraction(7, 3), Fraction(-3, 2)))
    r = qc.distance(e, q)
    assert r.method == "inscribed ellipsoid" and r.distance < 0
    f = qc.distance(e, q, mode="float")
    lo, hi = r.bounds
    assert Fraction(f.bounds[0]) <= hi and lo <= Fraction(f.bounds[1])  # both hold the depth
    with pytest.raises(UndecidedError, match="not a sphere"):
        qc.distance(e, q, mode="exact")


def test_two_ellipsoids_on_an_axis():
    """Two ellipsoids on the x axis, gap 3 between the tips (semi-axes 2 and 1 along x)."""
    r = qc.distance("x**2/4 + y**2 + z**2 - 1", "(x - 6)**2 + y**2/4 + z**2/4 - 1", digits=25)
    assert r.distance.contains(3) and r.distance.rad() < 1e-24
    assert all(p.contains(v) for p, v in zip(r.point_E, (2, 0, 0), strict=True))


def test_bad_input_is_refused():
    with pytest.raises(ValueError):
        qc.distance("x**2 + y**2 - z**2 - 1", "x**2 + y**2 + z**2 - 1")  # E not an ellipsoid
    with pytest.raises(ValueError):
        qc.distance(np.full((4, 4), np.nan), "x - 1")
    with pytest.raises(ValueError):
        qc.distance("x**2 + y**2 + z**2 - 1", "x - 1", mode="fast")
