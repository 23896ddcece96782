"""The first-contact scale against independent computations: ray casting at high precision
(every type of ``Q``), the Perram-Wertheim formula (two ellipsoids), flint's own
discriminant (the candidate polynomial), and exact constructions."""

from __future__ import annotations

from fractions import Fraction

import flint
import mpmath
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import quadric_contact as qc
from brute_distance import perram_wertheim, ray_scale
from quadric_contact import Quadric, QuadricKind
from quadric_contact.exact.errors import ExcludedQuadricError, NotAnEllipsoidError
from quadric_contact.exact.precision import working_precision
from quadric_contact.model.motions import RigidMotion
from quadric_contact.testing.strategies import tangent_pairs
from quadric_contact.theory.contact_scale import (
    contact_scale_exact,
    scale_polynomial,
    scaled,
)

DIGITS = 30
"""Digits compared with the brute-force minimiser (computed at 40)."""

MOTION = RigidMotion.from_quaternion(3, 1, -2, 1, (Fraction(1, 3), Fraction(-2, 5), Fraction(1, 7)))
E = Quadric.ellipsoid(Fraction(1, 2), Fraction(3, 4), Fraction(1, 3)).moved(
    RigidMotion.from_quaternion(2, -1, 1, 3, (Fraction(5, 2), Fraction(7, 3), Fraction(-3, 2)))
)
"""A tilted ellipsoid; each type below is tilted by another rational motion."""

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


def _mp(x, digits=45):
    return mpmath.mpf(x.decimal(digits))


@pytest.mark.parametrize("kind", list(TYPES), ids=lambda k: k.name.lower())
def test_scale_equals_ray_casting_for_every_type(kind):
    q = TYPES[kind].moved(MOTION)
    assert q.kind is kind
    got = contact_scale_exact(E, q)
    with working_precision(dps=50):
        want = ray_scale(E, q, digits=40)
        assert mpmath.isfinite(want)
        assert abs(_mp(got.scale) - want) <= mpmath.mpf(10) ** (-DIGITS) * max(1, abs(want))
    # the sign of s* - 1 is what the overlap-like reading says: E already reaches the surface iff s* <= 1
    lo, hi = got.bracket
    assert lo < hi and got.squared.compare(lo) > 0 and got.squared.compare(hi) < 0


def test_scale_both_equals_perram_wertheim():
    q = TYPES[QuadricKind.ELLIPSOID].moved(MOTION).translated((3, -1, 2))
    got = contact_scale_exact(E, q, scale="both")
    with working_precision(dps=50):
        want = perram_wertheim(E, q, digits=40)
        assert abs(_mp(got.scale) - want) <= mpmath.mpf(10) ** (-DIGITS) * want


def test_one_sided_scale_is_not_perram_wertheim():
    # two unit spheres 4 apart: E alone must grow to 3, both only to 2 (F = 4)
    e, q = Quadric.sphere(1), Quadric.sphere(1, (4, 0, 0))
    assert contact_scale_exact(e, q).scale == 3
    assert contact_scale_exact(e, q, scale="both").scale == 2


@settings(max_examples=15, deadline=None)
@given(pair=tangent_pairs(inside=False))
def test_a_pair_tangent_from_outside_has_scale_one(pair):
    e, q = pair
    assert contact_scale_exact(e, q).scale == 1


@settings(max_examples=15, deadline=None)
@given(pair=tangent_pairs(inside=True))
def test_a_pair_tangent_from_inside_has_scale_one(pair):
    e, q = pair
    assert contact_scale_exact(e, q).scale == 1


def test_scaled_pair_is_tangent_exactly_at_rational_scale():
    # E scaled by 1/2 about its centre first touches Q: then E itself has scale 2
    e, q = Quadric.ellipsoid(1, 2, 3, (0, 0, 8)), Quadric.elliptic_paraboloid(1, 1)
    s = contact_scale_exact(e, q).squared
    e2 = scaled(e, Fraction(1, 4))
    assert contact_scale_exact(e2, q).squared.compare(s * 4) == 0


def test_centre_on_the_surface_gives_zero():
    assert contact_scale_exact(Quadric.sphere(1, (2, 0, 0)), "x - 2").scale == 0
    # both scaled: two ellipsoids with one centre share it at every scale
    e, q = Quadric.sphere(1, (1, 2, 3)), Quadric.ellipsoid(1, 2, 3, (1, 2, 3))
    assert contact_scale_exact(e, q, scale="both").scale == 0
    assert contact_scale_exact(e, q).scale == 1  # E alone reaches q's nearest vertex at radius 1


def test_concentric_spheres_and_homothetic_ellipsoids():
    assert contact_scale_exact(Quadric.sphere(1), Quadric.sphere(3)).scale == 3
    e = Quadric.ellipsoid(1, 2, 3, (1, 1, 1))
    assert contact_scale_exact(
        e, Quadric.ellipsoid(Fraction(1, 2), 1, Fraction(3, 2), (1, 1, 1))
    ).scale == Fraction(1, 2)


def test_pencil_is_affine_in_the_squared_scale():
    e, q = E, TYPES[QuadricKind.HYPERBOLOID_ONE_SHEET].moved(MOTION)
    P0, B = scale_polynomial(e, q)
    for t in (Fraction(1, 3), Fraction(2), Fraction(7, 5)):
        m = scaled(e, t)
        direct = flint.fmpq_poly(
            [flint.fmpq(c.numerator, c.denominator) for c in qc.characteristic_polynomial(m, q).coefficients]
        )
        mine = P0 + flint.fmpq(t.numerator, t.denominator) * B
        # the same polynomial (the package may normalise the matrices: up to a constant factor)
        assert (
            mine.degree() == direct.degree() == 4
            and mine * direct.leading_coefficient() == direct * mine.leading_coefficient()
        )


def test_candidate_discriminant_matches_flint():
    # the package's discrimination sequence (straight-line formulas over Q[t]) against flint's
    # bivariate discriminant: the same polynomial up to a constant factor
    from quadric_contact.theory.contact_scale import _candidates

    e, q = E, TYPES[QuadricKind.ELLIPSOID].moved(MOTION)
    P0, B = scale_polynomial(e, q)
    R = _candidates(P0, B)
    ctx = flint.fmpq_mpoly_ctx.get(("l", "t"), "lex")
    lam, t = ctx.gens()
    P = lam * 0
    for k, (a, b) in enumerate(zip(_coeffs(P0, 5), _coeffs(B, 5), strict=True)):
        P = P + (a + b * t) * lam**k
    disc = P.discriminant("l")
    poly_t = flint.fmpq_poly([0])
    for (_, j), c in disc.to_dict().items():
        poly_t += flint.fmpq_poly([0] * j + [c])
    # Yang's D_n is the discriminant times the square of the leading coefficient, here c t
    ratio = R / poly_t
    assert R % poly_t == 0 and ratio.degree() == 2 and ratio.coeffs()[:2] == [0, 0]


def _coeffs(p, n):
    cs = list(p.coeffs())
    return cs + [flint.fmpq(0)] * (n - len(cs))


def test_refuses_what_it_does_not_know():
    with pytest.raises(NotAnEllipsoidError):
        contact_scale_exact("x**2 + y**2 - z**2 - 1", "x - 1")
    with pytest.raises(ExcludedQuadricError):
        contact_scale_exact("x**2 + y**2 + z**2 - 1", "x**2 + y**2 - z**2")  # a cone has no solid
    with pytest.raises(NotAnEllipsoidError):
        contact_scale_exact("x**2 + y**2 + z**2 - 1", "x - 4", scale="both")
    with pytest.raises(ValueError, match="scale must be"):
        contact_scale_exact("x**2 + y**2 + z**2 - 1", "x - 4", scale="Q")


def test_stack_of_one_encloses_the_scalar_answer():
    q = TYPES[QuadricKind.ELLIPTIC_PARABOLOID].moved(MOTION)
    exact = qc.contact_scale(E, q).scale
    one = qc.contact_scale([E], q)
    assert one.shape == (1, 2)
    lo, hi = one[0]
    assert exact.compare(Fraction(lo)) >= 0 and exact.compare(Fraction(hi)) <= 0
    assert hi - lo <= 4 * np.spacing(hi)
    two = qc.contact_scale(np.array([E.to_numpy()] * 2), q.to_numpy()[None].repeat(2, axis=0))
    assert two.shape == (2, 2) and np.all(two[:, 0] <= two[:, 1])


@settings(max_examples=6, deadline=None)
@given(kind=st.sampled_from([QuadricKind.ELLIPSOID, QuadricKind.HYPERBOLOID_ONE_SHEET, QuadricKind.PLANE]))
def test_scale_is_monotone_in_the_size_of_E(kind):
    q = TYPES[kind].moved(MOTION)
    s = contact_scale_exact(E, q).squared
    bigger = scaled(E, Fraction(9, 4))
    assert contact_scale_exact(bigger, q).squared.compare(s * Fraction(4, 9)) == 0
