"""The signed distance against independent computations: the brute-force minimiser at high
precision for every type of ``Q`` (ray casting from the centre of a sphere; the lowest point
of an ellipsoid over a plane), and the witnesses checked on the surfaces."""

from __future__ import annotations

from fractions import Fraction

import mpmath
import numpy as np
import pytest

import quadric_contact as qc
from brute_distance import plane_gap, ray_scale
from quadric_contact import Quadric, QuadricKind
from quadric_contact.exact.errors import UndecidedError
from quadric_contact.exact.precision import working_precision
from quadric_contact.model.motions import RigidMotion
from quadric_contact.modes.distance.certified import distance_certified
from quadric_contact.theory.distance import CONVEX_SOLIDS, distance_exact
from quadric_contact.theory.overlap import solid_of

DIGITS = 30
MOTION = RigidMotion.from_quaternion(3, 1, -2, 1, (Fraction(1, 3), Fraction(-2, 5), Fraction(1, 7)))

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
    QuadricKind.PLANE: Quadric.plane((1, 2, -2), Fraction(1, 2)),
}

CENTRES = [
    (Fraction(5, 2), Fraction(7, 3), Fraction(-3, 2)),
    (Fraction(1, 5), Fraction(-1, 3), Fraction(1, 4)),
    (Fraction(-4), Fraction(1, 2), Fraction(3)),
]


def _mp(x):
    return mpmath.mpf(x.decimal(45))


def _value(q, p):
    """``X^T Q X`` at a point of mpf coordinates."""
    M = [[mpmath.mpf(v.numerator) / v.denominator for v in row] for row in q.matrix]
    X = [*p, mpmath.mpf(1)]
    return sum(X[i] * M[i][j] * X[j] for i in range(4) for j in range(4))


def _gradient(q, p):
    M = [[mpmath.mpf(v.numerator) / v.denominator for v in row] for row in q.matrix]
    X = [*p, mpmath.mpf(1)]
    return [2 * sum(M[i][j] * X[j] for j in range(4)) for i in range(3)]


def _check_witnesses(r, e, q, rho, centre):
    K = solid_of(q)
    with working_precision(dps=50):
        pq = [_mp(x) for x in r.point_Q]
        pe = [_mp(x) for x in r.point_E]
        n = [_mp(x) for x in r.normal]
        tol = mpmath.mpf(10) ** (-DIGITS)
        assert abs(_value(K, pq)) < tol  # on the surface of Q
        assert abs(mpmath.fsum(x * x for x in n) - 1) < tol  # a unit normal
        g = _gradient(K, pq)
        gn = mpmath.sqrt(mpmath.fsum(x * x for x in g))
        assert all(abs(g[i] / gn - n[i]) < tol for i in range(3))  # the outward normal of K
        d = _mp(r.distance)
        assert all(abs(pe[i] - pq[i] - d * n[i]) < tol for i in range(3))
        c = [mpmath.mpf(v.numerator) / v.denominator for v in centre]
        rho_mp = mpmath.mpf(rho.numerator) / rho.denominator
        assert abs(mpmath.sqrt(mpmath.fsum((pe[i] - c[i]) ** 2 for i in range(3))) - rho_mp) < tol  # on E


@pytest.mark.parametrize("kind", list(TYPES), ids=lambda k: k.name.lower())
@pytest.mark.parametrize(
    "which", [0, *(pytest.param(k, marks=pytest.mark.slow) for k in range(1, len(CENTRES)))]
)
def test_sphere_distance_equals_ray_casting_for_every_type(kind, which):
    q = TYPES[kind].moved(MOTION)
    centre = CENTRES[which]
    rho = Fraction(1, 3)
    e = Quadric.sphere(rho, centre)
    K = solid_of(q)
    inside = K.value_at(centre) < 0
    with working_precision(dps=50):
        d_centre = ray_scale(Quadric.sphere(1, centre), q, digits=40)  # the nearest point, by rays
        want = (-d_centre if inside else d_centre) - mpmath.mpf(rho.numerator) / rho.denominator
    if kind not in CONVEX_SOLIDS and (inside or want < 0):
        with pytest.raises(UndecidedError, match="not convex"):
            distance_exact(e, q)
        return
    r = distance_exact(e, q)
    with working_precision(dps=50):
        assert abs(_mp(r.distance) - want) <= mpmath.mpf(10) ** (-DIGITS) * max(1, abs(want))
    assert r.unique
    _check_witnesses(r, e, q, rho, centre)


@pytest.mark.parametrize("offset", [Fraction(-3), Fraction(1, 2), Fraction(4), Fraction(9)])
@pytest.mark.parametrize("flip", [False, True])
def test_ellipsoid_plane_distance_equals_the_lowest_point(offset, flip):
    e = Quadric.ellipsoid(Fraction(1, 2), Fraction(3, 4), Fraction(1, 3)).moved(
        RigidMotion.from_quaternion(2, -1, 1, 3, (Fraction(5, 2), Fraction(7, 3), Fraction(-3, 2)))
    )
    normal = (Fraction(1), Fraction(2), Fraction(-2))
    plane = Quadric.plane(normal, offset)
    if flip:  # the other half-space: the solid n . x >= d
        plane, normal, offset = -plane, tuple(-x for x in normal), -offset
    r = distance_exact(e, plane)
    with working_precision(dps=50):
        # the solid n . x <= d lies below; E's signed distance is min over E of (n . x - d) / |n|
        want = plane_gap(e, normal, offset, digits=40)
        assert abs(_mp(r.distance) - want) <= mpmath.mpf(10) ** (-DIGITS) * max(1, abs(want))
        pe = [_mp(x) for x in r.point_E]
        assert abs(_value(e, pe)) < mpmath.mpf(10) ** (-DIGITS)  # on E
    assert r.unique and r.method == "ellipsoid-plane"


def test_touching_is_zero_and_sign_follows_the_overlap_decision():
    e = Quadric.sphere(1, (0, 0, 3))
    assert distance_exact(e, "z - 2").distance == 0
    for q in ("z - 2", "z - 1", "z - 5", "x**2 + y**2 + z**2 - 1", "x**2 + y**2 - 4"):
        d = distance_exact(e, q).distance.sign()
        code = qc.overlap(e, q, mode="exact").code.name
        assert {1: "SEPARATE", 0: "TOUCHING", -1: "OVERLAPPING"}[d] == code


def test_symmetric_configurations_have_no_single_witness():
    r = distance_exact(Quadric.sphere(1), "x**2 + y**2 - 9")  # on the axis of a cylinder
    assert r.distance == -4 and not r.unique and r.point_Q is None and r.normal is None


def test_other_pairs_are_refused_with_the_reason():
    with pytest.raises(UndecidedError, match="not a sphere"):
        distance_exact("x**2 + 2*y**2 + z**2 - 1", "x**2 + y**2 + (z - 5)**2 - 1")


def test_stack_of_one_encloses_the_scalar_answer():
    e, q = Quadric.sphere(Fraction(1, 2), (1, 2, 3)), TYPES[QuadricKind.ELLIPSOID]
    exact = qc.distance(e, q, mode="exact").distance
    lo, hi = qc.distance([e], q)[0]
    assert exact.compare(Fraction(lo)) >= 0 and exact.compare(Fraction(hi)) <= 0
    assert hi - lo <= 4 * np.spacing(abs(hi))


@pytest.mark.parametrize("kind", list(TYPES), ids=lambda k: k.name.lower())
def test_certified_encloses_the_exact_distance_to_the_digits_asked(kind):
    q = TYPES[kind].moved(MOTION)
    for centre in CENTRES:
        e = Quadric.sphere(Fraction(1, 3), centre)
        try:
            exact = distance_exact(e, q)
        except UndecidedError:
            # the depth into a solid that is not convex has no exact path: the certified mode
            # brackets it (tests/test_distance_nonconvex.py holds it to a brute force) or refuses
            try:
                ball = distance_certified(e, q, digits=40)
            except UndecidedError as exc:
                assert "not convex" in str(exc)
                continue
            assert ball.method == "inscribed ellipsoid" and ball.distance < 0
            lo, hi = ball.bounds
            assert hi - lo <= 2 * abs(hi) * Fraction(1, 10**40)
            continue
        ball = distance_certified(e, q, digits=40)
        lo, hi = ball.bounds
        assert exact.distance.compare(lo) >= 0 and exact.distance.compare(hi) <= 0
        assert hi - lo <= 2 * abs(hi) * Fraction(1, 10**40)
        # the witnesses enclose the exact ones
        for got, want in (
            (ball.point_Q, exact.point_Q),
            (ball.normal, exact.normal),
            (ball.point_E, exact.point_E),
        ):
            for g, w in zip(got, want, strict=True):
                w.refine(Fraction(1, 10**45))
                assert g.overlaps(_ball_of(w))


def _ball_of(w):
    """An arb ball holding the real algebraic number ``w`` (its isolating interval)."""
    import flint

    lo, hi = w.interval
    mid, rad = (lo + hi) / 2, (hi - lo) / 2
    return flint.arb(flint.fmpq(mid.numerator, mid.denominator), float(rad) * 2 + 1e-300)


def test_certified_symmetric_configuration_falls_back_to_exact():
    r = qc.distance(Quadric.sphere(1), "x**2 + y**2 - 9")  # the nearest points form a circle
    assert r.distance.contains(-4) and r.distance.rad() == 0 and r.point_Q is None


def test_float_mode_answers_symmetric_sphere_pairs_in_both_forms():
    """Two balls on an axis (a symmetric configuration the balls of the certified search leave
    to the exact path): the float mode answers a pair as it answers the stack of one, around
    the exact value, instead of abstaining."""
    E = np.diag([1.0, 1.0, 1.0, -1.0])
    Q = np.diag([1.0, 1.0, 1.0, 5.25])
    Q[0, 3] = Q[3, 0] = -2.5  # the unit ball at (2.5, 0, 0): gap 1/2
    one = qc.distance(E, Q, mode="float")
    ((lo, hi),) = qc.distance(E[None], Q[None], mode="float")
    assert not one.uncertain and one.bounds[0] <= 0.5 <= one.bounds[1]
    assert lo <= 0.5 <= hi and one.bounds[0] <= lo and hi <= one.bounds[1]
