"""Exact event times: real algebraic numbers, closed-form scenes, dense sampling."""

from __future__ import annotations

import warnings
from fractions import Fraction as F

import flint
import mpmath
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from quadric_contact import Quadric
from quadric_contact.exact.algebraic import RealAlgebraic, real_roots, sign_at
from quadric_contact.exact.errors import SceneError
from quadric_contact.exact.precision import working_precision
from quadric_contact.exact.rational import simplest_between
from quadric_contact.scenes.composite import Composite
from quadric_contact.scenes.events import PieceTrack
from quadric_contact.scenes.ledger import Ledger
from quadric_contact.scenes.scene_model import MovingEllipsoid, Scene
from quadric_contact.scenes.simulate import simulate
from quadric_contact.scenes.trajectory import PolynomialMotion
from quadric_contact.testing.strategies import ellipsoids, quadrics, rationals
from quadric_contact.theory.contact import decide_transversal
from quadric_contact.theory.pencil import characteristic_polynomial
from quadric_contact.theory.plane import plane_side_exact as plane_side
from quadric_contact.theory.regions import decide_region
from quadric_contact.theory.results import Region

# -- real algebraic numbers ---------------------------------------------------------------


def test_real_roots_are_exact_and_refine_to_any_precision():
    p = flint.fmpq_poly([-14, 0, 1]) * flint.fmpq_poly([-2, 3]) * flint.fmpq_poly([-5, 0, 1])
    roots = real_roots(p, F(-10), F(10))
    with working_precision(dps=80):
        expected = sorted(
            [-mpmath.sqrt(14), -mpmath.sqrt(5), mpmath.mpf(2) / 3, mpmath.sqrt(5), mpmath.sqrt(14)]
        )
        assert len(roots) == 5
        for r, e in zip(roots, expected, strict=True):
            assert abs(mpmath.mpf(r.decimal(60)) - e) < mpmath.mpf(10) ** -59
        assert roots[2].is_rational and roots[2].value == F(2, 3)
        # open interval by default, closed on request
        assert [float(r) for r in real_roots(p, F(2, 3), F(3))] == pytest.approx([5**0.5])
        assert len(real_roots(p, F(2, 3), F(3), closed=True)) == 2


def test_compare_and_signs_at_algebraic_numbers():
    (r,) = real_roots(flint.fmpq_poly([-2, 0, 1]), F(0), F(2))  # sqrt 2
    assert r.compare(F(141421356, 100000000)) == 1 and r.compare(F(141421357, 100000000)) == -1
    (s,) = real_roots(flint.fmpq_poly([-8, 0, 1]), F(0), F(3))  # 2 sqrt 2
    assert r.compare(s) == -1 and s.compare(r) == 1
    (s2,) = real_roots(flint.fmpq_poly([-2, 0, 1]) * flint.fmpq_poly([-7, 1]), F(1), F(2))
    assert r.compare(s2) == 0 and r == s2
    assert sign_at(flint.fmpq_poly([-2, 0, 1]) * flint.fmpq_poly([1, 1]), r) == 0
    # sign of x - 1.41421356237 at sqrt 2: decided by refinement
    led = Ledger()
    q = flint.fmpq_poly([flint.fmpq(-141421356237, 10**11), 1])
    assert sign_at(q, r, led) == 1
    assert sign_at(-q, r, led) == -1


def test_sign_at_a_root_escalates_only_when_needed():
    """From the wide isolating interval [1, 2] of sqrt 2, the sign of t + 1 is read at
    once; that of t - 1.41421356 needs the interval refined (one escalation)."""
    led = Ledger()
    r = RealAlgebraic.root_in(flint.fmpz_poly([-2, 0, 1]), F(1), F(2))
    assert sign_at(flint.fmpq_poly([1, 1]), r, led) == 1 and led.done["escalations"] == 0
    assert sign_at(flint.fmpq_poly([flint.fmpq(-141421356, 10**8), 1]), r, led) == 1
    assert led.done["escalations"] == 1 and r.hi - r.lo < F(1, 10**8)


def test_sign_of_a_huge_polynomial_with_cancellation():
    """g = 10^40 (t^2 - 2 - 10^-20)^9 (t - 3) at sqrt 2 is about 1.6e-140 (positive),
    next to coefficients of size 1e40: ball arithmetic alone would need 600 bits."""
    (r,) = real_roots(flint.fmpq_poly([-2, 0, 1]), F(1), F(2))
    near = flint.fmpq_poly([flint.fmpq(-2 * 10**20 - 1, 10**20), 0, 1])
    g = near**9 * flint.fmpq_poly([-3, 1]) * 10**40
    assert sign_at(g, r) == 1
    assert sign_at(-g, r) == -1


def test_simplest_between():
    assert simplest_between(F(-1, 2), F(1, 3)) == 0
    assert simplest_between(F(2), F(3)) == F(5, 2)
    assert simplest_between(F(-3), F(-2)) == F(-5, 2)
    assert simplest_between(F(314, 100), F(315, 100)) == F(22, 7)
    with pytest.raises(ValueError):
        simplest_between(F(1), F(1))


# -- helpers ------------------------------------------------------------------------------


def run(E, obj, motion, span, effects=("zone", "contact", "relative_position", "first_contact")):
    """Simulate one ellipsoid against one object; pairs that are not small are kept
    (their contacts with all roots real are then undecided)."""
    scene = Scene(
        "test",
        (obj,),
        (MovingEllipsoid("e", E.as_ellipsoid(), motion),),
        span,
        tuple(effects),
        source="<test>",
        on_not_small="warn",
    )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return simulate(scene, effects=effects)


def times(result, obj="o"):
    return [ev.time for ev in result.pair("e", obj).events]


# -- closed forms -------------------------------------------------------------------------


def test_sphere_towards_a_plane_linear_motion_rational_times():
    """Unit sphere, centre z = -5 + 2t, plane z = 0: transversal contact exactly for 2 < t < 3."""
    E = Quadric.sphere(1, (0, 0, -5))
    obj = Composite.single("o", Quadric.plane((0, 0, 1), 0))
    res = run(E, obj, PolynomialMotion.linear((0, 0, 2)), (F(0), F(5)))
    ts = times(res)
    assert [t.value for t in ts] == [F(2), F(3)]
    pair = res.pair("e", "o")
    ev_in, ev_out = pair.events
    assert dict(ev_in.before.pieces)["o"].region is Region.R_MINUS
    assert dict(ev_in.at.pieces)["o"].contact is False  # tangent at the instant (Theorem 14)
    assert dict(ev_in.after.pieces)["o"].contact is True
    assert dict(ev_out.after.pieces)["o"].region is Region.R_PLUS
    assert pair.first_contact[0].value == 2


def test_sphere_towards_a_separating_plane_quadratic_motion_irrational_times():
    """Centre z = t^2 - 4: the zone of z = 0 is Zone 0 exactly for sqrt 3 < t < sqrt 5."""
    E = Quadric.sphere(1, (0, 0, -4))
    obj = Composite.separated("o", "z", plus=None, minus=None)
    res = run(E, obj, PolynomialMotion(((0,), (0,), (0, 0, 1))), (F(0), F(3)), effects=("zone",))
    ts = times(res)
    assert len(ts) == 2
    with working_precision(dps=50):
        assert abs(mpmath.mpf(ts[0].decimal(45)) - mpmath.sqrt(3)) < mpmath.mpf(10) ** -44
        assert abs(mpmath.mpf(ts[1].decimal(45)) - mpmath.sqrt(5)) < mpmath.mpf(10) ** -44
        assert (
            ts[0].poly_str("t", integer=True) == "t**2 - 3"
            and ts[1].poly_str("t", integer=True) == "t**2 - 5"
        )
        zones = [dict(ep.state.zones)["z"].region for ep in res.pair("e", "o").episodes]
        assert zones[0] is Region.R_MINUS and Region.CONTACT in zones and zones[-1] is Region.R_PLUS


def test_sphere_through_a_cylinder():
    """Sphere of radius 1/2, centre (t - 4, 1/2, 0), cylinder x^2 + y^2 = 4.

    Transversal contact iff 3/2 < dist < 5/2, i.e. (t-4)^2 in (2, 6): events at
    4 - sqrt 6, 4 - sqrt 2, 4 + sqrt 2, 4 + sqrt 6; inside (R-) in between."""
    E = Quadric.sphere(F(1, 2), (-4, F(1, 2), 0))
    cyl = Quadric.elliptic_cylinder(2, 2)
    obj = Composite.single("o", cyl)
    res = run(E, obj, PolynomialMotion.linear((1, 0, 0)), (F(0), F(8)))
    ts = times(res)
    with working_precision(dps=40):
        closed = [4 - mpmath.sqrt(6), 4 - mpmath.sqrt(2), 4 + mpmath.sqrt(2), 4 + mpmath.sqrt(6)]
        assert len(ts) == 4
        for t, c in zip(ts, closed, strict=True):
            assert abs(mpmath.mpf(t.decimal(35)) - c) < mpmath.mpf(10) ** -34
        regions = [dict(ep.state.pieces)["o"].region for ep in res.pair("e", "o").episodes]
        assert regions == [
            Region.R_PLUS,  # [0, 4 - sqrt 6]: outside, touching at the end instant
            Region.CONTACT,
            Region.R_MINUS,
            Region.CONTACT,
            Region.R_PLUS,
        ]


def test_sphere_through_a_sphere_with_delta_4_identically_zero():
    """Two spheres: the pencil has a persistent double root, so Delta_4(t) vanishes
    identically and the events come from the rest of the discrimination system.
    Radius 1, centre (t - 5, 2, 0) against radius 3 at the origin: contact iff
    2 < dist < 4 with dist^2 = (t-5)^2 + 4, i.e. 0 < |t - 5| < 2 sqrt 3; at t = 5
    (dist = 2) the small sphere touches the big one from inside for an instant."""
    E = Quadric.sphere(1, (-5, 2, 0))
    Q = Quadric.sphere(3)
    res = run(E, Composite.single("o", Q), PolynomialMotion.linear((1, 0, 0)), (F(0), F(10)))
    seg = PolynomialMotion.linear((1, 0, 0)).segments(F(0), F(10), E.center())[0]
    track = PieceTrack(
        "o", seg.moved_upper(E, E.center()), Q, F(0), F(10), Ledger(), small=True, region=False, kind=False
    )
    assert track.D[3].is_zero() and not track.D[2].is_zero()
    ts = times(res)
    with working_precision(dps=30):
        assert len(ts) == 3 and ts[1].value == 5
        assert abs(mpmath.mpf(ts[0].decimal(25)) - (5 - 2 * mpmath.sqrt(3))) < mpmath.mpf(10) ** -24
        assert abs(mpmath.mpf(ts[2].decimal(25)) - (5 + 2 * mpmath.sqrt(3))) < mpmath.mpf(10) ** -24
        touch = res.pair("e", "o").events[1]
        assert dict(touch.before.pieces)["o"].contact and dict(touch.after.pieces)["o"].contact
        assert dict(touch.at.pieces)["o"].contact is False
        assert dict(touch.at.pieces)["o"].region is Region.R_MINUS  # inside, tangent


def test_a_candidate_is_not_always_an_event():
    """An ellipsoid grazing a sphere from outside: Delta_4(t) has a root at t = 5
    where they touch (semi-axes 1/2, 1/3, 1/3, centre (t - 5, 7/3, 0); sphere of
    radius 2 at the origin), but there is no transversal contact on either side,
    so the contact state does not change and no event is reported."""
    E = Quadric.ellipsoid(F(1, 2), F(1, 3), F(1, 3), center=(-5, F(7, 3), 0))
    Q = Quadric.sphere(2)
    obj = Composite.single("o", Q)
    res = run(E, obj, PolynomialMotion.linear((1, 0, 0)), (F(0), F(10)), effects=("contact",))
    seg = PolynomialMotion.linear((1, 0, 0)).segments(F(0), F(10), E.center())[0]
    track = PieceTrack(
        "o", seg.moved_upper(E, E.center()), Q, F(0), F(10), Ledger(), small=True, region=False, kind=False
    )
    assert any(r.compare(F(5)) == 0 for r in real_roots(track.D[3], F(0), F(10)))  # a root of D4
    assert any(r.compare(F(5)) == 0 for r in track.roots)  # t = 5 is a candidate
    assert times(res) == []
    assert res.pair("e", "o").first_contact is None


def test_a_plane_touched_for_an_instant_is_reported_as_such():
    """A unit sphere with centre z = 2t^2 - 4t comes down to z = -2 at t = 1, touches
    the plane z = -3 from above (R+) at that instant only, and rises again."""
    E = Quadric.sphere(1, (0, 0, 0))
    obj = Composite.separated("o", "z + 3", plus=None, minus=None)
    res = run(E, obj, PolynomialMotion(((0,), (0,), (0, -4, 2))), (F(0), F(2)), effects=("zone",))
    (ev,) = res.pair("e", "o").events
    assert ev.time.value == 1  # z_c = 2t^2 - 4t reaches -2 at t = 1, touching z = -3
    z = dict(ev.at.zones)["z + 3"]
    assert z.tangent and z.region is Region.R_PLUS
    assert dict(ev.before.zones)["z + 3"] == dict(ev.after.zones)["z + 3"]
    assert "at the instant only" in ev.changes()[0]


# -- dense sampling against the static predicates ---------------------------------------


def static_state(E, Q, check=None):
    """(transversal contact, region) by the static predicates; ``check`` is the
    scene's smallness check of the pair (None: a plane)."""
    if Q.kind.value == "plane":
        side = plane_side(E, Q)
        return side.zone is Region.CONTACT, side.zone
    P = characteristic_polynomial(E, Q)
    small = check.small
    c = decide_transversal(P, small=small, method="theory")
    if c.transversal is False and not check.table_4_applies:
        return False, None
    if c.transversal is None:
        return None, None
    return c.transversal, decide_region(P, small=small, method="theory").region


def check_of(result):
    return next(iter(result.scene.smallness.values()), None)


@settings(max_examples=25, deadline=None)
@given(
    E=ellipsoids(max_axis=1, bound=4),
    Q=quadrics(bound=3),
    v=st.tuples(*[rationals(min_value=-3, max_value=3, max_denominator=4)] * 3),
    a=st.tuples(*[rationals(min_value=-1, max_value=1, max_denominator=4)] * 3),
)
def test_event_timeline_matches_dense_sampling(E, Q, v, a):
    """Polynomial motion of degree 2: the state at 41 rational times (decided by the
    static predicates on the exactly moved ellipsoid) equals the timeline's, and
    every reported event is a change of the static state just before/after."""
    motion = PolynomialMotion(tuple((0, v[i], a[i]) for i in range(3)))
    obj = Composite.single("o", Q)
    res = run(E, obj, motion, (F(0), F(4)), effects=("contact", "relative_position"))
    pair = res.pair("e", "o")
    scene = res.scene
    ell = scene.ellipsoids[0]
    for i in range(41):
        t = F(i, 10)
        state = dict(pair.state_at(t).pieces)["o"]
        Et = ell.trajectory.placed(ell.quadric, t, *scene.span)
        contact, region = static_state(Et, Q, check_of(res))
        assert (state.contact, state.region) == (contact, region), t
    for ev in pair.events:
        before = ev.before
        after = ev.after
        assert before != after or before != ev.at
        if before != after:
            # just around the event (within the isolating interval, refined) the static states differ
            eps = F(1, 10**9)
            t = ev.time.rational_near(12)
            lo, hi = t - eps, t + eps
            if (
                lo > 0
                and hi < 4
                and all(e2 is ev or abs(float(e2.time) - float(t)) > 1e-6 for e2 in pair.events)
            ):
                s_lo = static_state(ell.trajectory.placed(ell.quadric, lo, *scene.span), Q, check_of(res))
                s_hi = static_state(ell.trajectory.placed(ell.quadric, hi, *scene.span), Q, check_of(res))
                assert s_lo != s_hi


def test_rotating_ellipsoid_matches_dense_sampling():
    """Rotation by the quaternion (2, t, 0, 1 - t): rational in t; a thin ellipsoid
    sweeping through a hyperboloid of one sheet."""
    E = Quadric.ellipsoid(F(3, 2), F(1, 5), F(1, 4), center=(F(-3, 2), 0, 0))
    Q = Quadric.hyperboloid_one_sheet(2, 2, 3)
    motion = PolynomialMotion(((0, 1), (0,), (0, F(1, 4))), quaternion=((2,), (0, 1), (0,), (1, -1)))
    obj = Composite.single("o", Q)
    res = run(E, obj, motion, (F(0), F(3)), effects=("contact", "relative_position"))
    pair = res.pair("e", "o")
    assert len(pair.events) >= 2
    ell = res.scene.ellipsoids[0]
    for i in range(61):
        t = F(i, 20)
        Et = ell.trajectory.placed(ell.quadric, t, *res.scene.span)
        state = dict(pair.state_at(t).pieces)["o"]
        assert (state.contact, state.region) == static_state(Et, Q, check_of(res)), t


def test_rational_instants_agree_with_static_predicates():
    """At an event time that is rational, the exact instant state equals the static one."""
    E = Quadric.sphere(1, (0, 0, -5))
    Q = Quadric.ellipsoid(4, 4, 2, center=(0, 0, 3))  # touches from below at z_c = 0: t = 5/2
    obj = Composite.single("o", Q)
    res = run(E, obj, PolynomialMotion.linear((0, 0, 2)), (F(0), F(4)))
    pair = res.pair("e", "o")
    first = pair.events[0]
    assert first.time.value == F(5, 2)
    Et = res.scene.ellipsoids[0].trajectory.placed(res.scene.ellipsoids[0].quadric, F(5, 2), *res.scene.span)
    at = dict(first.at.pieces)["o"]
    assert (at.contact, at.region) == static_state(Et, Q, check_of(res)) == (False, Region.R_PLUS)


def test_root_of_rational_and_irrational_comparisons_mix():
    r = RealAlgebraic(F(3, 2))
    (s,) = real_roots(flint.fmpq_poly([-2, 0, 1]), F(0), F(2))
    assert s < r and r > s and r.compare(F(3, 2)) == 0
    assert r.decimal(3) == "1.500" and s.decimal(3) == "1.414"
    assert r.to_dict(5) == {"decimal": "1.50000", "exact": "3/2"}
    assert s.to_dict(5)["root_of"] == "t**2 - 2"


@settings(max_examples=15, deadline=None)
@given(
    E=ellipsoids(max_axis=1, bound=3),
    Q=quadrics(bound=3),
    v=st.tuples(*[rationals(min_value=-2, max_value=2, max_denominator=3)] * 3),
    q=st.tuples(*[st.integers(-2, 2)] * 8),
)
def test_rotating_motion_matches_dense_sampling(E, Q, v, q):
    """Linear translation and the rotation of a quaternion linear in t."""
    from hypothesis import assume

    quat = ((q[0] or 1, q[1]), (q[2], q[3]), (q[4], q[5]), (q[6], q[7]))
    motion = PolynomialMotion(tuple((0, v[i]) for i in range(3)), quaternion=quat)
    try:
        motion.segments(F(0), F(2), E.center())
    except SceneError as err:  # the quaternion vanishes somewhere on [0, 2]: no rotation there
        assert "quaternion" in str(err)
        assume(False)
    obj = Composite.single("o", Q)
    res = run(E, obj, motion, (F(0), F(2)), effects=("contact", "relative_position"))
    pair = res.pair("e", "o")
    ell = res.scene.ellipsoids[0]
    for i in range(21):
        t = F(i, 10)
        state = dict(pair.state_at(t).pieces)["o"]
        Et = ell.trajectory.placed(ell.quadric, t, *res.scene.span)
        assert (state.contact, state.region) == static_state(Et, Q, check_of(res)), t


@pytest.mark.slow
@settings(max_examples=500, deadline=None)
@given(
    E=ellipsoids(max_axis=1, bound=4),
    Q=quadrics(bound=3),
    v=st.tuples(*[rationals(min_value=-3, max_value=3, max_denominator=4)] * 3),
    a=st.tuples(*[rationals(min_value=-1, max_value=1, max_denominator=4)] * 3),
)
def test_event_timeline_matches_dense_sampling_exhaustive(E, Q, v, a):
    """The dense-sampling check on 500 random pairs and quadratic motions (slow profile)."""
    test_event_timeline_matches_dense_sampling.hypothesis.inner_test(E, Q, v, a)


@pytest.mark.slow
@settings(max_examples=200, deadline=None)
@given(
    E=ellipsoids(max_axis=1, bound=3),
    Q=quadrics(bound=3),
    v=st.tuples(*[rationals(min_value=-2, max_value=2, max_denominator=3)] * 3),
    q=st.tuples(*[st.integers(-2, 2)] * 8),
)
def test_rotating_motion_matches_dense_sampling_exhaustive(E, Q, v, q):
    """The rotating dense-sampling check on 200 random pairs (slow profile)."""
    test_rotating_motion_matches_dense_sampling.hypothesis.inner_test(E, Q, v, q)
