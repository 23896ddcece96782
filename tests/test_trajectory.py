"""Trajectories: the polynomial matrix of the moving ellipsoid equals the exactly moved one."""

from __future__ import annotations

from fractions import Fraction as F

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from quadric_contact import Quadric
from quadric_contact.exact.errors import SceneError, ShapeError
from quadric_contact.scenes.trajectory import Keyframes, PolynomialMotion, Stationary, poly_eval
from quadric_contact.testing.strategies import ellipsoids, rationals


def proportional_positive(upper_polys, t, Q):
    vals = [poly_eval(p, t) for p in upper_polys]
    ratios = {v / q for v, q in zip(vals, Q.upper, strict=True) if q != 0}
    assert all((v == 0) == (q == 0) for v, q in zip(vals, Q.upper, strict=True))
    assert len(ratios) == 1 and next(iter(ratios)) > 0


@settings(max_examples=30, deadline=None)
@given(
    E=ellipsoids(bound=3),
    d=st.tuples(*[st.lists(rationals(min_value=-2, max_value=2, max_denominator=5), max_size=3)] * 3),
    q=st.tuples(*[st.lists(st.integers(-3, 3), min_size=1, max_size=2)] * 4),
    t=rationals(min_value=0, max_value=2, max_denominator=7),
)
def test_moved_upper_is_a_positive_multiple_of_the_moved_quadric(E, d, q, t):
    from hypothesis import assume

    try:
        motion = PolynomialMotion(d, quaternion=q)
        seg = motion.segments(F(0), F(2), E.center())[0]
    except SceneError:
        assume(False)
    upper = seg.moved_upper(E, E.center())
    proportional_positive(upper, t, motion.placed(E, t, F(0), F(2)))


def test_keyframes_interpolate_and_rest():
    E = Quadric.ellipsoid(1, F(1, 2), F(1, 3), center=(1, 2, 3))
    k = Keyframes([(1, (0, 0, 0)), (3, (4, 2, 0), (1, 0, 0, 1)), (4, (4, 2, 2), (1, 0, 0, -1))])
    segs = k.segments(F(0), F(5), E.center())
    assert [(s.t0, s.t1) for s in segs] == [(0, 1), (1, 3), (3, 4), (4, 5)]
    assert segs[0].center_at(F(1, 2)) == (0, 0, 0)  # resting before the first key
    assert segs[1].center_at(2) == (2, 1, 0)
    assert segs[3].center_at(5) == (4, 2, 2)
    # (1,0,0,1) and (1,0,0,-1): dot product 0, the path never passes through a zero quaternion
    placed = k.placed(E, F(3), F(0), F(5))
    assert placed.center() == (4, 2, 0)
    # 90 degrees about z: the long axis (x) now points along y
    assert placed.value_at((4, 3, 0)) == 0 and placed.value_at((5, 2, 0)) != 0
    for seg in segs:
        for t in (seg.t0, (seg.t0 + seg.t1) / 2, seg.t1):
            proportional_positive(seg.moved_upper(E, E.center()), t, k.placed(E, t, F(0), F(5)))


def test_keyframes_take_the_short_way():
    k = Keyframes([(0, (0, 0, 0), (1, 0, 0, 0)), (1, (0, 0, 0), (-1, 0, 0, 0))])
    seg = k.segments(F(0), F(1), (F(0),) * 3)[0]
    assert seg.quaternion_at(F(1, 2)) == (1, 0, 0, 0)  # -q is the same rotation: no turn at all


def test_bad_trajectories():
    with pytest.raises(ShapeError):
        Keyframes([])
    with pytest.raises(ShapeError, match="increase"):
        Keyframes([(1, (0, 0, 0)), (1, (1, 0, 0))])
    with pytest.raises(ShapeError):
        PolynomialMotion(((0,), (0,)))
    with pytest.raises(SceneError, match="vanishes"):
        PolynomialMotion(((0,),) * 3, quaternion=((-1, 1), (0,), (0,), (0,))).segments(
            F(0), F(2), (F(0),) * 3
        )
    assert Stationary().describe() == "stationary"
    with pytest.raises(ValueError):
        Stationary().segment_at(5, F(0), F(1), (F(0),) * 3)
