"""The certified broad phase: its bounds enclose what they claim, it never prunes a
contact (the timelines with and without it are the same, and agree with the static
algorithms), it saves pencils, and the many-body scene runs on several processes."""

from __future__ import annotations

import random
from fractions import Fraction as F

import flint
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from tests.scene_oracle import check_timeline

from quadric_contact import Quadric
from quadric_contact.scenes.broadphase import (
    ellipsoid_extents,
    plane_sign_on_box,
    poly_range,
    quadric_sign_on_box,
    swept_box,
)
from quadric_contact.scenes.manybody import many_body_scene, totem
from quadric_contact.scenes.scene_toml import builtin_scene, builtin_scene_names
from quadric_contact.scenes.simulate import simulate
from quadric_contact.scenes.trajectory import PolynomialMotion
from quadric_contact.testing.strategies import ellipsoids, quadrics, rationals
from quadric_contact.theory.plane import plane_side_exact as plane_side
from quadric_contact.theory.results import Region


def _value(Q, x):
    X = (*x, 1)
    M = Q.matrix
    return sum(M[i][j] * X[i] * X[j] for i in range(4) for j in range(4))


@settings(max_examples=40, deadline=None)
@given(
    coeffs=st.lists(rationals(min_value=-5, max_value=5, max_denominator=7), min_size=1, max_size=5),
    a=rationals(min_value=-3, max_value=3, max_denominator=5),
    w=rationals(min_value=0, max_value=3, max_denominator=5),
)
def test_poly_range_encloses_the_values(coeffs, a, w):
    p = flint.fmpq_poly([flint.fmpq(c.numerator, c.denominator) for c in coeffs])
    b = a + w
    lo, hi = poly_range(p, a, b)
    for k in range(21):
        t = a + w * F(k, 20)
        v = p(flint.fmpq(t.numerator, t.denominator))
        assert lo <= F(int(v.p), int(v.q)) <= hi


@settings(max_examples=40, deadline=None)
@given(Q=quadrics(bound=3), corner=st.tuples(*[rationals(min_value=-4, max_value=4, max_denominator=4)] * 3))
def test_a_certified_sign_holds_on_the_whole_box(Q, corner):
    """Whenever the box test claims a sign, X^T Q X has it at every grid point of the box."""
    rng = random.Random(str(corner))
    widths = [F(rng.randrange(1, 9), 4) for _ in range(3)]
    box = tuple((corner[i], corner[i] + widths[i]) for i in range(3))
    s = quadric_sign_on_box(Q, box)
    if s != 0:
        for i in range(5):
            for j in range(5):
                for k in range(5):
                    x = tuple(
                        box[d][0] + widths[d] * F(idx, 4) for d, idx in zip(range(3), (i, j, k), strict=True)
                    )
                    assert (_value(Q, x) > 0) == (s > 0) and _value(Q, x) != 0


def test_plane_sign_and_extents():
    box = ((F(0), F(1)), (F(0), F(1)), (F(6), F(7)))
    assert plane_sign_on_box(Quadric.plane((0, 0, 1), 5), box) == 1
    assert plane_sign_on_box(Quadric.plane((0, 0, 1), 8), box) == -1
    assert plane_sign_on_box(Quadric.plane((0, 0, 1), 13), box) == -1
    assert plane_sign_on_box(Quadric.plane((1, 0, 1), 7), box) == 0
    (rx, ry, rz), rho = ellipsoid_extents(Quadric.ellipsoid(1, 2, 3).rotated((1, 1, 0, 0)))
    # turned a quarter about x: y and z swap
    assert 1 <= rx < 1 + F(1, 10**6) and 3 <= ry < 3 + F(1, 10**6) and 2 <= rz < 2 + F(1, 10**6)
    assert 3 <= rho < 3 + F(1, 10**6)


@settings(max_examples=25, deadline=None)
@given(
    E=ellipsoids(max_axis=1, bound=3),
    v=st.tuples(*[rationals(min_value=-2, max_value=2, max_denominator=4)] * 3),
    q=st.tuples(*[rationals(min_value=-1, max_value=1, max_denominator=3)] * 4),
)
def test_swept_box_contains_the_moving_ellipsoid(E, v, q):
    """At sample times of the interval, the moved ellipsoid's centre is in the swept box
    and no face of the box crosses it (Corollary 15, exactly)."""
    quat = ((3, q[0]), (0, q[1]), (q[2],), (q[3],))  # w >= 1 on [0, 2]: never vanishes
    motion = PolynomialMotion(tuple((0, v[i], v[(i + 1) % 3] / 2) for i in range(3)), quat)
    (seg,) = motion.segments(F(0), F(2), E.center())
    half, rho = ellipsoid_extents(E)
    a, b = F(1, 3), F(3, 2)
    box = swept_box(seg, half, rho, a, b)
    for k in range(5):
        t = a + (b - a) * F(k, 4)
        Et = motion.placed(E, t, F(0), F(2))
        ct = Et.center()
        for i in range(3):
            assert box[i][0] < ct[i] < box[i][1]
            for face in box[i]:
                normal = tuple(1 if j == i else 0 for j in range(3))
                assert plane_side(Et, Quadric.plane(normal, face)).zone is not Region.CONTACT


def _events(result):
    """Each pair's events: exact times (compared as algebraic numbers) and what changed."""
    return [
        (
            p.ellipsoid,
            p.object.name,
            [_Exact(e.time) for e in p.events],
            [c for e in p.events for c in e.changes()],
        )
        for p in result.pairs
    ]


class _Exact:
    """An event time compared exactly (RealAlgebraic.compare), not by its printed digits."""

    def __init__(self, root):
        self.root = root

    def __eq__(self, other):
        return self.root.compare(other.root) == 0

    def __repr__(self):
        return self.root.decimal(20)


@pytest.mark.parametrize("name", builtin_scene_names())
def test_broad_phase_never_changes_a_builtin_timeline(name):
    scene = builtin_scene(name)
    plain = simulate(scene)
    broad = simulate(scene, broad_phase=True)
    assert _events(plain) == _events(broad)
    assert [p.first_contact is None for p in plain.pairs] == [p.first_contact is None for p in broad.pairs]
    assert broad.ledger.done["characteristic_polynomials"] <= plain.ledger.done["characteristic_polynomials"]


@pytest.fixture(scope="module")
def small_swarm():
    return many_body_scene(40, 16, seed=3)


def test_broad_phase_never_prunes_a_contact_of_the_many_body_scene(small_swarm):
    plain = simulate(small_swarm)
    broad = simulate(small_swarm, broad_phase=True)
    assert _events(plain) == _events(broad)
    events = sum(len(p.events) for p in broad.pairs)
    assert events > 20
    # it saves pencils and says so
    led = broad.ledger
    assert led.done["characteristic_polynomials"] < plain.ledger.done["characteristic_polynomials"] / 2
    assert led.done["pruned_pairs"] > 0 and led.done["broad_phase_tests"] > 0
    assert "pruned_pairs" in led.format() and "pruned_pairs" not in plain.ledger.format()


def test_many_body_timelines_agree_with_the_static_algorithms(small_swarm):
    broad = simulate(small_swarm, broad_phase=True)
    sub = broad
    sub.pairs = [p for p in broad.pairs if p.events][:6]
    assert check_timeline(sub, samples=24) > 0


def test_workers_give_the_same_timelines(small_swarm):
    one = simulate(small_swarm, broad_phase=True)
    two = simulate(small_swarm, broad_phase=True, workers=2)
    assert _events(one) == _events(two)
    assert one.ledger.done == two.ledger.done
    assert [p.object is small_swarm.objects[0] for p in two.pairs] == [True] * len(two.pairs)


def test_generated_scene_is_reproducible_and_checked_once_per_shape():
    a = many_body_scene(30, 8, seed=5)
    b = many_body_scene(30, 8, seed=5)
    assert [e.quadric for e in a.ellipsoids] == [e.quadric for e in b.ellipsoids]
    assert len(a.smallness) == 30 * 8
    assert a.work.done["smallness_checks"] <= 4 * 8  # four shapes
    assert len(totem(16).pieces) == 16 and len(totem(16).splits()) == 15


@pytest.mark.slow
def test_thousand_bodies_with_and_without_the_broad_phase():
    scene = many_body_scene(1000, 16)
    plain = simulate(scene)
    broad = simulate(scene, broad_phase=True, workers=2)
    assert _events(plain) == _events(broad)
    assert sum(len(p.events) for p in broad.pairs) > 1000
