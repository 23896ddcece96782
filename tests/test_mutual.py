"""Mutual contacts between moving ellipsoids: exact event times against closed forms
and against the static overlap decision, and the broad phase against the unpruned run."""

from __future__ import annotations

import random
from fractions import Fraction as F
from itertools import pairwise

import pytest
import sympy as sp

from quadric_contact.exact.algebraic import rational_between, sign_at
from quadric_contact.exact.errors import SceneError
from quadric_contact.scenes.mutual import (
    OVERLAPPING,
    SEPARATE,
    TOUCHING,
    _subresultant_1,
    mutual_contacts,
)
from quadric_contact.scenes.scene_toml import parse_scene
from quadric_contact.scenes.simulate import simulate
from quadric_contact.theory.overlap import overlap_exact

HEAD = """
[scene]
name = "meeting"
time = [0, 4]
effects = ["contact"]
{mutual}

[[object]]
name = "ground"
[[object.piece]]
name = "ground"
standard = "plane"
normal = [0, 0, 1]
offset = 0
"""

BODY = """
[[ellipsoid]]
name = "{name}"
standard = "ellipsoid"
semi_axes = ["{a}", "{b}", "{c}"]
center = ["{x}", "{y}", "{z}"]
[ellipsoid.motion]
{motion}
"""


def _scene(bodies, mutual="mutual = true"):
    text = HEAD.format(mutual=mutual) + "".join(BODY.format(**b) for b in bodies)
    return parse_scene(text, "meeting.toml")


def _linear(vx, vy, vz=0):
    return f'type = "linear"\nvelocity = ["{vx}", "{vy}", "{vz}"]'


def _code(state):
    return {SEPARATE: "SEPARATE", TOUCHING: "TOUCHING", OVERLAPPING: "OVERLAPPING"}[state]


def _static(scene, name_a, name_b, t):
    ea = next(e for e in scene.ellipsoids if e.name == name_a)
    eb = next(e for e in scene.ellipsoids if e.name == name_b)
    A = ea.trajectory.placed(ea.quadric, t, *scene.span)
    B = eb.trajectory.placed(eb.quadric, t, *scene.span)
    return overlap_exact(A, B).code.name


def test_head_on_pair_meets_at_the_closed_form_times():
    """Two equal ellipsoids (semi-axes 0.3, 0.2, 0.2) approach along x with the centres 0.1
    apart in y: they touch when the offset is on the doubled ellipsoid,
    ((4 - 2t) / 0.6)^2 + (0.1 / 0.4)^2 = 1."""
    bodies = [
        {"name": "a", "a": 0.3, "b": 0.2, "c": 0.2, "x": -2, "y": 0, "z": 1, "motion": _linear(1, 0)},
        {"name": "b", "a": 0.3, "b": 0.2, "c": 0.2, "x": 2, "y": 0.1, "z": 1, "motion": _linear(-1, 0)},
    ]
    result = simulate(_scene(bodies))
    [pair] = result.mutual
    assert [(e.before, e.at, e.after) for e in pair.events] == [
        (SEPARATE, TOUCHING, OVERLAPPING),
        (OVERLAPPING, TOUCHING, SEPARATE),
    ]
    closed = [F(-15, 16) * F(36, 100) + 16, -16, 4]  # (4 - 2t)^2 - 0.36 * 15/16 = 0
    for e in pair.events:
        assert sign_at(closed, e.time) == 0
    assert pair.first_contact.compare(pair.events[0].time) == 0
    assert "a and b: start apart" in result.format_text()


def test_states_agree_with_the_static_overlap_between_and_at_events():
    rng = random.Random(4)
    bodies = []
    for k in range(6):
        x, y = rng.randint(-3, 3), rng.randint(-3, 3)
        bodies.append({
            "name": f"b{k}", "a": F(rng.randint(2, 5), 10), "b": F(rng.randint(2, 5), 10),
            "c": F(rng.randint(2, 5), 10), "x": x, "y": y, "z": 1,
            "motion": _linear(F(-x, 2) + F(rng.randint(-2, 2), 10), F(-y, 2)),
        })  # fmt: skip
    scene = _scene(bodies)
    result = mutual_contacts(scene)
    assert result, "some bodies meet"
    t0, t1 = scene.span
    for pair in result:
        times = [t0, *(e.time for e in pair.events), t1]
        states = [pair.start] + [e.after for e in pair.events]
        for (lo, hi), state in zip(pairwise(times), states, strict=True):
            assert _static(scene, pair.a, pair.b, rational_between(lo, hi)) == _code(state)
        for e in pair.events:
            if e.time.is_rational:
                assert _static(scene, pair.a, pair.b, e.time.as_fraction()) == _code(e.at)
            assert e.at == TOUCHING or e.before != e.after


def test_a_turning_body_against_a_passing_one():
    """Not similar: the pencil's Δ4 and the first subresultant decide."""
    text = (
        HEAD.format(mutual='mutual = ["spin", "pass"]')
        + """
[[ellipsoid]]
name = "spin"
standard = "ellipsoid"
semi_axes = [0.8, 0.2, 0.2]
center = [0, 0, 1]
[ellipsoid.motion]
type = "keyframes"
keys = [
    { t = 0, at = [0, 0, 1], rotation = [1, 0, 0, 0] },
    { t = 4, at = [0, 0, 1], rotation = [1, 0, 0, 1] },
]

[[ellipsoid]]
name = "pass"
standard = "sphere"
radius = 0.2
center = [0.3, -2, 1]
[ellipsoid.motion]
type = "linear"
velocity = [0, 1, 0]
"""
    )
    scene = parse_scene(text, "spin.toml")
    [pair] = mutual_contacts(scene)
    t0, t1 = scene.span
    times = [t0, *(e.time for e in pair.events), t1]
    states = [pair.start] + [e.after for e in pair.events]
    assert OVERLAPPING in states
    for (lo, hi), state in zip(pairwise(times), states, strict=True):
        for k in (1, 2, 3):
            t = lo + (hi - lo) * F(k, 4) if not hasattr(lo, "lo") and not hasattr(hi, "lo") else None
            t = t if t is not None else rational_between(lo, hi)
            assert _static(scene, "spin", "pass", t) == _code(state)


def test_broad_phase_never_prunes_a_contact():
    rng = random.Random(9)
    bodies = []
    for k in range(14):
        x, y = F(rng.randint(-30, 30), 10), F(rng.randint(-30, 30), 10)
        bodies.append({
            "name": f"b{k}", "a": F(1, 5), "b": F(3, 20), "c": F(1, 10), "x": x, "y": y, "z": 1,
            "motion": _linear(F(rng.randint(-10, 10), 10), F(rng.randint(-10, 10), 10)),
        })  # fmt: skip
    scene = _scene(bodies)
    pruned = mutual_contacts(scene)
    every = mutual_contacts(scene, broad_phase=False)

    def key(results):
        return [
            (m.a, m.b, m.start, [(e.time.decimal(20), e.before, e.at, e.after) for e in m.events])
            for m in results
        ]

    assert key(pruned) == key(every)
    assert len(pruned) >= 2


def test_double_root_formulas():
    lam, a, p, q, s = sp.symbols("lam a p q s")
    P = sp.Poly(sp.expand(a * (lam - p) ** 2 * (lam - q) * (lam - s)), lam)
    c = [P.coeff_monomial(lam**k) for k in range(5)]
    s1, s0 = _subresultant_1()
    assert sp.simplify(-s0(*c, const=sp.Rational) / s1(*c, const=sp.Rational) - p) == 0
    k = sp.Symbol("k")
    r0, r1, r2 = sp.symbols("r0 r1 r2")
    Q = sp.Poly(sp.expand((lam + k) ** 2 * (r2 * lam**2 + r1 * lam + r0)), lam)
    c = [Q.coeff_monomial(lam**j) for j in range(5)]
    assert sp.expand(c[3] - 2 * k * c[4] - r1) == 0
    assert sp.expand(c[2] - 2 * k * r1 - k * k * r2 - r0) == 0


def test_mutual_in_a_scene_file():
    body = [{"name": "a", "a": 0.3, "b": 0.2, "c": 0.2, "x": 0, "y": 0, "z": 1, "motion": _linear(1, 0)}]
    assert _scene(body, "mutual = false").mutual == ()
    assert _scene(body, "mutual = true").mutual == ("a",)
    assert _scene(body, 'mutual = ["a"]').mutual == ("a",)
    with pytest.raises(SceneError, match=r"scene\.mutual"):
        _scene(body, 'mutual = ["z"]')
    with pytest.raises(SceneError, match=r"scene\.mutual"):
        _scene(body, "mutual = 3")


def _dense(bodies, pieces, meeting, near, samples, workers=1):
    from quadric_contact.scenes.manybody import many_body_scene
    from quadric_contact.testing.mutual_sampling import dense_check, near_pairs

    scene = many_body_scene(bodies, pieces, seed=2, check_smallness=False, mutual=True)
    found = mutual_contacts(scene)
    pairs = near_pairs(scene, found, meeting=meeting, near=near, seed=2)
    assert len(pairs) == meeting + near
    return dense_check(scene, found, pairs, samples=samples, workers=workers)


def test_no_contact_interval_missed_against_dense_exact_sampling():
    """Pairs of the generated many-body scene that meet and near misses: the timeline's state
    equals the static exact decision at every sample, so no sampled contact is missed."""
    check = _dense(120, 4, meeting=4, near=2, samples=48)
    assert check.disagreements == [] and check.missed == 0
    assert check.sampled_intervals >= 3 and check.exact_intervals >= 4


@pytest.mark.slow
def test_no_contact_interval_missed_on_the_1000_body_scene():
    check = _dense(1000, 16, meeting=40, near=20, samples=400, workers=2)
    assert check.disagreements == [] and check.missed == 0
    assert check.sampled_intervals >= 40


def test_coaxial_spheroids_along_their_axis():
    """A multiple root at every time without a constant ratio (Δ4 ≡ 0, not similar): two
    spheroids with the common axis x fly head-on along it; their tips touch when the distance
    of the centres, |4 - 2t|, is 3/10 + 1/2."""
    common = {"y": 0, "z": 1}
    bodies = [
        {"name": "a", "a": F(3, 10), "b": F(1, 5), "c": F(1, 5), "x": -2, "motion": _linear(1, 0), **common},
        {"name": "b", "a": F(1, 2), "b": F(1, 10), "c": F(1, 10), "x": 2, "motion": _linear(-1, 0), **common},
    ]
    scene = _scene(bodies)
    [pair] = mutual_contacts(scene)
    assert [(e.time.as_fraction(), e.before, e.at, e.after) for e in pair.events] == [
        (F(8, 5), SEPARATE, TOUCHING, OVERLAPPING),
        (F(12, 5), OVERLAPPING, TOUCHING, SEPARATE),
    ]
    for k in range(17):
        t = F(k, 4)
        assert _static(scene, "a", "b", t) == _code(pair.state_at(t))
    # a sphere passing a spheroid along the spheroid's axis, off the beat of the samples
    bodies[1] = {"name": "b", "a": F(1, 7), "b": F(1, 7), "c": F(1, 7), "x": 2, "y": 0, "z": 1,
                 "motion": _linear(F(-3, 2), 0)}  # fmt: skip
    scene = _scene(bodies)
    [pair] = mutual_contacts(scene)
    times = [e.time for e in pair.events]
    assert [e.time.as_fraction() for e in pair.events] == [
        F(4 - F(3, 10) - F(1, 7), F(5, 2)),
        F(4 + F(3, 10) + F(1, 7), F(5, 2)),
    ]
    assert len(times) == 2
    for k in range(33):
        t = F(k, 8)
        assert _static(scene, "a", "b", t) == _code(pair.state_at(t))


def test_a_spinning_sphere_and_a_passing_one():
    """Two spheres, one turning (its matrix a varying positive multiple of a sphere's): the
    quadratic parts are proportional with a ratio k(t) that is not constant, Δ4 ≡ 0; they
    touch when the centres are 1/5 + 3/10 apart, at t = 2 ± 1/2."""
    text = (
        HEAD.format(mutual="mutual = true")
        + """
[[ellipsoid]]
name = "spin"
standard = "sphere"
radius = 0.2
center = [0, 0, 1]
[ellipsoid.motion]
type = "keyframes"
keys = [
    { t = 0, at = [0, 0, 1], rotation = [1, 0, 0, 0] },
    { t = 4, at = [0, 0, 1], rotation = [1, 1, 0, 1] },
]

[[ellipsoid]]
name = "pass"
standard = "sphere"
radius = 0.3
center = [-2, 0, 1]
[ellipsoid.motion]
type = "linear"
velocity = [1, 0, 0]
"""
    )
    scene = parse_scene(text, "spin.toml")
    [pair] = mutual_contacts(scene)
    assert [(e.time.as_fraction(), e.before, e.at, e.after) for e in pair.events] == [
        (F(3, 2), SEPARATE, TOUCHING, OVERLAPPING),
        (F(5, 2), OVERLAPPING, TOUCHING, SEPARATE),
    ]
    for k in range(17):
        t = F(k, 4)
        assert _static(scene, "spin", "pass", t) == _code(pair.state_at(t))
