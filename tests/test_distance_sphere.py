"""The sphere's exact distance from the certified secular root, and the plane's closed form,
against the previous routes on random pairs of every type.

The previous route of a sphere against a curved quadric reads ``|c - p*|`` off the
first-contact scale (the roots of the pencil's discriminant, chosen by the exact overlap
decision) and then picks the root of the secular equation at that distance; the previous plane
formula is real algebraic arithmetic on ``(n . c - d - sqrt(r k)) / |n|``.  Both must give the
same numbers as the fast paths: the distance, the witness ``point_Q`` and, on a few pairs, the
normal and ``point_E``.  A few pairs a type by default; the ``slow`` profile draws more.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

from quadric_contact import Quadric, QuadricKind
from quadric_contact.exact.algebraic import RealAlgebraic
from quadric_contact.exact.errors import UndecidedError
from quadric_contact.model.motions import RigidMotion
from quadric_contact.model.quadric import as_quadric
from quadric_contact.testing.references import plane_distance_reference
from quadric_contact.testing.samples import SAMPLE_KINDS, _moved, _standard_forms, random_pairs
from quadric_contact.theory.distance import _sphere_quadric_general, distance_exact
from quadric_contact.theory.distance_sphere import sphere_distance, sphere_pair
from quadric_contact.theory.overlap import solid_of

CURVED = [k for k in SAMPLE_KINDS if k is not QuadricKind.PLANE]
ROTATED = (QuadricKind.ELLIPSOID, QuadricKind.HYPERBOLOID_ONE_SHEET, QuadricKind.HYPERBOLOID_TWO_SHEETS)


def _sphere(rng, rational_radius=False):
    c = rng.uniform(-3, 3, 3)
    rho = rng.uniform(0.1, 1.0)
    if rational_radius:  # rho rational: the distance has a polynomial of half the degree
        return Quadric.sphere(Fraction(1, int(rng.integers(2, 9))), [Fraction(float(x)) for x in c])
    E = np.eye(4)
    E[:3, 3] = E[3, :3] = -c
    E[3, 3] = c @ c - rho * rho  # rounded: rho^2 a dyadic rational, rho irrational
    return as_quadric(E)


def _quadric(kind, rng, placement):
    """Binary64 entries (a rotation rounded to binary64 where the type survives it, the axes
    permuted otherwise) or rational ones (a rotation from an integer quaternion)."""
    p = np.sort(rng.uniform(1.0, 4.0, size=(1, 3)), axis=1)[:, ::-1]
    S = _standard_forms(np.array([SAMPLE_KINDS.index(kind)]), p)
    sign = -1 if rng.random() < 0.5 else 1
    if placement == "rational":
        w = (0, 0, 0, 0)
        while not any(w):
            w = tuple(int(x) for x in rng.integers(-4, 5, 4))
        t = [Fraction(float(x)) for x in rng.uniform(-3, 3, 3)]
        return Quadric.from_matrix(S[0]).moved(RigidMotion.from_quaternion(*w, translation=t)).scaled(sign)
    while True:
        if kind in ROTATED:
            _, Q, _ = random_pairs(1, rng, kinds=(kind,))
        else:
            P = np.eye(3)[rng.permutation(3)]
            P[0] *= np.linalg.det(P)
            Q = _moved(S, P[None], rng.uniform(-3, 3, size=(1, 3))) * sign
        q = as_quadric(Q[0])
        if q.kind is kind:
            return q


def _answered(kind, rng, placement, rational_radius=False):
    """A pair the fast path certifies (the sphere outside a non-convex solid)."""
    for _ in range(500):
        e, q = _sphere(rng, rational_radius), _quadric(kind, rng, placement)
        K = solid_of(q)
        try:
            r = distance_exact(e, q)
        except UndecidedError:
            continue
        assert sphere_distance(sphere_pair(e.as_ellipsoid(), K)) is not None
        return e.as_ellipsoid(), K, r
    raise AssertionError(f"no answered pair of {kind.value}")  # pragma: no cover


def _check_against_previous(e, K, r, witnesses):
    old = _sphere_quadric_general(e, K)
    assert r.distance == old.distance
    assert r.unique and old.unique and r.method == old.method
    assert r.point_Q == old.point_Q
    if witnesses:
        assert r.normal == old.normal
        assert r.point_E == old.point_E


@pytest.mark.parametrize("placement", ["binary64", "rational"])
@pytest.mark.parametrize("kind", CURVED, ids=lambda k: k.name.lower())
def test_sphere_fast_path_equals_the_previous_route(kind, placement):
    rng = np.random.default_rng([SAMPLE_KINDS.index(kind), placement == "rational"])
    e, K, r = _answered(kind, rng, placement)
    _check_against_previous(e, K, r, witnesses=placement == "binary64")


@pytest.mark.slow
@pytest.mark.parametrize("placement", ["binary64", "rational"])
@pytest.mark.parametrize("kind", CURVED, ids=lambda k: k.name.lower())
def test_sphere_fast_path_equals_the_previous_route_many(kind, placement):
    rng = np.random.default_rng([SAMPLE_KINDS.index(kind), placement == "rational", 1])
    for k in range(6):
        e, K, r = _answered(kind, rng, placement, rational_radius=k % 3 == 2)
        _check_against_previous(e, K, r, witnesses=k % 2 == 0)


@pytest.mark.parametrize(
    "kind", [QuadricKind.ELLIPSOID, QuadricKind.PARALLEL_PLANES], ids=lambda k: k.name.lower()
)
def test_rational_radius_and_square_distances(kind):
    """A rational radius (the distance polynomial of half the degree) and the slab of two
    planes at irrational offsets (the squared distance a square in its field: the path
    through the factors of ``m(x^2)``)."""
    rng = np.random.default_rng([7, SAMPLE_KINDS.index(kind)])
    e, K, r = _answered(kind, rng, "binary64", rational_radius=True)
    _check_against_previous(e, K, r, witnesses=False)


@pytest.mark.parametrize("seed", [0, 1, *(pytest.param(s, marks=pytest.mark.slow) for s in range(2, 12))])
def test_plane_closed_form_equals_the_previous_formula(seed, monkeypatch):
    rng = np.random.default_rng(seed)
    E = _sphere(rng) if seed % 2 else as_quadric(random_pairs(1, rng)[0][0])
    _, Q, _ = random_pairs(1, rng, kinds=(QuadricKind.PLANE,))
    e, K = E.as_ellipsoid(), solid_of(Q[0])
    want = plane_distance_reference(e, K)

    def refuse(*args):  # the fast closed form takes no square root by real algebraic arithmetic
        raise AssertionError("the general arithmetic was used")

    monkeypatch.setattr(RealAlgebraic, "sqrt", refuse)
    r = distance_exact(e, K)
    got = (r.distance, r.point_Q, r.normal, r.point_E)
    monkeypatch.undo()
    assert got == want


def test_plane_closed_form_special_values():
    for E, Q, want in [
        ("x**2 + y**2 + z**2 - 1", "x - 3", RealAlgebraic(-4)),
        ("x**2 + y**2 + z**2 - 1", "3 - x", RealAlgebraic(2)),
        ("x**2/4 + y**2 + z**2 - 1", "x - 3", RealAlgebraic(-5)),
        ("(x - 1)**2 + y**2 + z**2 - 1", "x - 2", RealAlgebraic(-2)),
        ("(z - 3)**2 + x**2 + y**2 - 1", "z - 2", RealAlgebraic(0)),
    ]:
        assert distance_exact(E, Q).distance == want


@pytest.mark.parametrize("centre", [(0, 0, 0), (1, 0, 0)])
def test_symmetric_configurations_take_the_general_route(centre):
    """Inside an ellipsoid with three axes, on a plane of symmetry, the nearest points come in
    pairs: the secular root sits where ``I + mu A`` is singular, no definite multiplier
    certifies one point, and the general route answers (no single witness)."""
    e, K = Quadric.sphere(Fraction(1, 2), centre), solid_of(Quadric.ellipsoid(3, 2, 1))
    assert sphere_distance(sphere_pair(e, K)) is None
    r = distance_exact(e, K)
    assert r.distance == _sphere_quadric_general(e, K).distance and not r.unique and r.point_Q is None
