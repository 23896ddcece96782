"""Exact rational rigid motions: rotations of rational quaternions, composition, inversion."""

from __future__ import annotations

from fractions import Fraction as F

import pytest
from hypothesis import given
from hypothesis import strategies as st

from quadric_contact import Quadric
from quadric_contact.exact.errors import NotANumberError, ShapeError
from quadric_contact.model.motions import RigidMotion, rotation_from_quaternion
from quadric_contact.testing.strategies import points, rationals, rigid_motions

quaternions = st.tuples(*[st.integers(-4, 4)] * 4).filter(any)


def matmul(a, b):
    return tuple(
        tuple(sum((a[i][k] * b[k][j] for k in range(len(b))), F(0)) for j in range(len(b[0])))
        for i in range(len(a))
    )


def det3(a):
    return (
        a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
        - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
        + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0])
    )


def hamilton(p, q):
    w1, x1, y1, z1 = p
    w2, x2, y2, z2 = q
    return (
        w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
        w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
        w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
        w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2,
    )


IDENTITY = tuple(tuple(F(int(i == j)) for j in range(3)) for i in range(3))


@given(quaternions)
def test_rotations_are_exactly_orthogonal_with_determinant_one(q):
    R = rotation_from_quaternion(*q)
    Rt = tuple(zip(*R, strict=True))
    assert matmul(Rt, R) == IDENTITY and det3(R) == 1


@given(quaternions, st.integers(1, 5))
def test_only_the_direction_of_the_quaternion_matters(q, k):
    assert rotation_from_quaternion(*q) == rotation_from_quaternion(*(k * c for c in q))
    assert rotation_from_quaternion(*q) == rotation_from_quaternion(*(-c for c in q))  # q and -q


@given(quaternions, quaternions)
def test_the_rotation_of_a_product_is_the_product_of_the_rotations(p, q):
    Rp, Rq = rotation_from_quaternion(*p), rotation_from_quaternion(*q)
    assert rotation_from_quaternion(*hamilton(p, q)) == matmul(Rp, Rq)


@given(quaternions)
def test_the_axis_is_fixed(q):
    w, x, y, z = q
    if (x, y, z) == (0, 0, 0):
        return
    axis = (F(x), F(y), F(z))
    assert RigidMotion.from_quaternion(*q).apply(axis) == axis


@given(rigid_motions(), rigid_motions(), points())
def test_composition_and_inverse(m1, m2, p):
    assert (m1 @ m2).apply(p) == m1.apply(m2.apply(p))
    assert m1.inverse().apply(m1.apply(p)) == tuple(F(v) for v in p)
    H, Hinv = m1.homogeneous(), m1.inverse_homogeneous()
    I4 = tuple(tuple(F(int(i == j)) for j in range(4)) for i in range(4))
    assert matmul(H, Hinv) == I4


@given(rigid_motions(), points(bound=3), rationals(min_value=F(1, 4), max_value=3))
def test_a_moved_quadric_holds_the_moved_points(m, c, r):
    """Q.moved(m) vanishes at m(p) exactly where Q vanishes at p (here: the pole of a sphere)."""
    sphere = Quadric.sphere(r, c)
    pole = (c[0], c[1], c[2] + r)
    assert sphere.value_at(pole) == 0
    moved = sphere.moved(m)
    assert moved.value_at(m.apply(pole)) == 0
    assert moved.value_at(m.apply(c)) == sphere.value_at(c)  # the centre's value is kept too


def test_quarter_turn_and_refusals():
    assert rotation_from_quaternion(1, 0, 0, 1) == ((0, -1, 0), (1, 0, 0), (0, 0, 1))
    with pytest.raises(NotANumberError):
        rotation_from_quaternion(0, 0, 0, 0)
    with pytest.raises(ShapeError):
        RigidMotion.from_matrix([[1, 0, 0], [0, 1, 0], [0, 0, -1]])  # a reflection
    with pytest.raises(ShapeError):
        RigidMotion.from_matrix([[2, 0, 0], [0, 1, 0], [0, 0, 1]])
