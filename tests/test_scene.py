"""Scene files: exact reading, the built-in scenes, and errors that name the file,
the key and what was expected."""

from __future__ import annotations

from fractions import Fraction as F

import pytest
from tests.bee_and_tree import bee_and_tree

from quadric_contact import Quadric
from quadric_contact.exact.errors import SceneError
from quadric_contact.model.classification import QuadricKind
from quadric_contact.scenes.scene_toml import builtin_scene, builtin_scene_names, load_scene, parse_scene
from quadric_contact.scenes.trajectory import Keyframes, PolynomialMotion, Stationary

GOOD = bee_and_tree(
    name="t",
    time="[0, 2]",
    effects='["zone", "contact"]',
    motion='{ type = "keyframes", keys = [{ t = 0, at = [3, 3, 5.5] }, { t = 2, at = [1.5, 0.5, 6.5] }] }',
)


def test_builtin_scenes_load_and_cover_several_quadric_types():
    names = builtin_scene_names()
    assert {
        "bee_and_tree",
        "drone_cooling_tower",
        "capsule_pipe",
        "ball_over_saddle",
        "swarm_around_tree",
    } <= set(names)
    kinds = set()
    for n in names:
        s = builtin_scene(n, check_smallness=False)
        assert s.objects and s.ellipsoids and s.span[0] < s.span[1]
        for o in s.objects:
            kinds |= {p.quadric.kind for p in o.pieces}
    assert {
        QuadricKind.ELLIPSOID,
        QuadricKind.HYPERBOLOID_ONE_SHEET,
        QuadricKind.ELLIPTIC_CYLINDER,
        QuadricKind.ELLIPTIC_PARABOLOID,
        QuadricKind.HYPERBOLIC_PARABOLOID,
        QuadricKind.PLANE,
    } <= kinds


def test_default_scene_is_example_17():
    s = builtin_scene()
    (tree,) = s.objects
    assert tree.pieces[0].quadric == Quadric.from_equation("x^2 + y^2 + 3*(z - 8.36291)^2 - 20")
    assert tree.pieces[1].quadric == Quadric.from_equation("x^2 + y^2 - 0.25*(z - 3)^2 - 1")
    assert tree.splits()[0].plane == Quadric.from_equation("z - 6")
    bee = s.ellipsoids[0]
    assert bee.quadric == Quadric.from_equation("(x-3)^2 + (y-3)^2 + 3*(z-5.5)^2 - 0.1")
    assert bee.center == (3, 3, F(11, 2))
    assert isinstance(bee.trajectory, Keyframes)


def test_numbers_are_read_exactly():
    text = GOOD.replace("at = [1.5, 0.5, 6.5]", 'at = [0.1, "1/3", 1e-1]')
    s = parse_scene(text, "x.toml", check_smallness=False)
    key = s.ellipsoids[0].trajectory.keys[1]
    assert key.position == (F(1, 10), F(1, 3), F(1, 10))


def test_other_quadric_and_motion_forms():
    text = """
[scene]
name = "forms"
time = ["0", "1/2"]
[[object]]
name = "o"
[[object.piece]]
name = "a"
standard = "hyperboloid of one sheet"
a = 2
b = 2
c = 3
rotation = [1, 1, 0, 0]
center = [0, 0, 1]
[[object.piece]]
name = "b"
matrix = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 0, 0], [0, 0, 0, -4]]
inside = "R-"
[[object.piece]]
name = "c"
standard = "plane"
normal = [0, 0, 1]
offset = -3
[[ellipsoid]]
name = "e1"
standard = "sphere"
radius = 0.5
[ellipsoid.motion]
type = "polynomial"
translation = [[0, 1], [0], [0, 0, -1]]
quaternion = [[1], [0, 1], [0], [0]]
[[ellipsoid]]
name = "e2"
standard = "ellipsoid"
semi_axes = [1, 0.5, 0.25]
motion = { type = "linear", velocity = [1, 0, 0] }
[[ellipsoid]]
name = "e3"
standard = "ellipsoid"
a = 1
b = 1
c = 1
"""
    s = parse_scene(text, "forms.toml", check_smallness=False)
    (o,) = s.objects
    assert o.root is None and [p.name for p in o.pieces] == ["a", "b", "c"]
    assert o.pieces[0].quadric == Quadric.hyperboloid_one_sheet(2, 2, 3).rotated((1, 1, 0, 0)).translated(
        (0, 0, 1)
    )
    assert o.pieces[1].quadric.kind is QuadricKind.ELLIPTIC_CYLINDER
    assert o.pieces[2].quadric.kind is QuadricKind.PLANE
    e1, e2, e3 = s.ellipsoids
    assert isinstance(e1.trajectory, PolynomialMotion) and e1.trajectory.quaternion is not None
    assert isinstance(e2.trajectory, PolynomialMotion) and isinstance(e3.trajectory, Stationary)
    assert s.span == (F(0), F(1, 2))


def mutate(old, new):
    assert old in GOOD, old
    return GOOD.replace(old, new)


MOTION = (
    'motion = { type = "keyframes", keys = [{ t = 0, at = [3, 3, 5.5] }, { t = 2, at = [1.5, 0.5, 6.5] }] }'
)

BAD = [
    # (text, key in the message, expectation in the message)
    ("this is = not toml [", "not valid TOML", "line"),
    (mutate('name = "t"\n', ""), "scene.name", "expected a string"),
    (mutate("time = [0, 2]", "time = [2, 0]"), "scene.time", "start < end"),
    (mutate("time = [0, 2]", "time = [0, inf]"), "scene.time[1]", "a finite number"),
    (mutate("time = [0, 2]", 'time = [0, "soon"]'), "scene.time[1]", "a finite number"),
    (
        mutate('effects = ["zone", "contact"]', 'effects = ["zone", "collisions"]'),
        "scene.effects[1]",
        "one of",
    ),
    (mutate("[scene]", "[scene]\nspeed = 3"), "scene.speed", "one of the keys"),
    (mutate('plus = "crown"', 'plus = "leaves"'), "object[0].tree.plus", "the name of a piece"),
    (mutate('plane = "z = 6"', 'plane = "z^2 = 6"'), "object[0].tree.plane", "the equation of a plane"),
    (
        mutate('equation = "x^2 + y^2 + 3*(z - 8.36291)^2 = 20"', 'equation = "x^3 = 1"'),
        "object[0].piece[0].equation",
        "a valid quadric",
    ),
    (
        mutate('equation = "x^2 + y^2 + 3*(z - 8.36291)^2 = 20"', 'equation = "x^2 + y^2 - z^2 = 0"'),
        "object[0].piece[0]",
        "a quadric of Table 1 or a plane",
    ),
    (mutate('name = "trunk"', 'name = "crown"'), "object[0].piece[1].name", "a name not used"),
    (
        mutate(
            'tree = { plane = "z = 6", plus = "crown", minus = "trunk" }',
            'tree = { plane = "z = 6", plus = "crown" }',
        ),
        "object[0].tree",
        "every piece placed in the tree",
    ),
    (
        mutate(
            'equation = "(x - 3)^2 + (y - 3)^2 + 3*(z - 5.5)^2 = 0.1"', 'equation = "x^2 + y^2 - z^2 = 1"'
        ),
        "ellipsoid[0]",
        "a real ellipsoid",
    ),
    (mutate("{ t = 2, at", "{ t = 0, at"), "ellipsoid[0].motion.keys[1].t", "a time after the previous key"),
    (
        mutate("at = [1.5, 0.5, 6.5]", "at = [1.5, 0.5]"),
        "ellipsoid[0].motion.keys[1].at",
        "a list of 3 numbers",
    ),
    (
        mutate("at = [1.5, 0.5, 6.5] }", "at = [1.5, 0.5, 6.5], rotation = [0, 0, 0, 0] }"),
        "ellipsoid[0].motion.keys[1].rotation",
        "a non-zero quaternion",
    ),
    (mutate('type = "keyframes"', 'type = "teleport"'), "ellipsoid[0].motion.type", "one of 'still'"),
    (
        mutate(
            MOTION,
            'motion = { type = "polynomial", translation = [[0], [0], [0]], '
            "quaternion = [[0, 1], [0], [0], [0]] }",
        ),
        "ellipsoid[0].motion",
        "defined on the whole time span",
    ),
    (
        mutate(
            MOTION,
            'motion = { type = "linear", velocity = [1, 0] }',
        ),
        "ellipsoid[0].motion.velocity",
        "a list of 3 numbers",
    ),
    (
        mutate('name = "bee"', 'name = "bee"\nsemi_axes = [1, 1, 1]'),
        "ellipsoid[0].semi_axes",
        "no parameters",
    ),
    (GOOD.split("[[ellipsoid]]")[0], "ellipsoid", "at least one [[ellipsoid]] table"),
]


@pytest.mark.parametrize(("text", "key", "expected"), BAD)
def test_bad_scene_files_name_file_key_and_expectation(text, key, expected):
    with pytest.raises(SceneError) as info:
        parse_scene(text, "scenes/broken.toml", check_smallness=False)
    msg = str(info.value)
    assert msg.startswith("scenes/broken.toml: "), msg
    assert key in msg and expected in msg, msg


def test_scene_error_carries_file_and_key():
    with pytest.raises(SceneError) as info:
        parse_scene(mutate("time = [0, 2]", "time = [0, nan]"), "f.toml")
    assert info.value.details["file"] == "f.toml" and info.value.details["key"] == "scene.time[1]"
    assert isinstance(info.value, ValueError)


def test_load_scene_from_file_and_by_name(tmp_path):
    p = tmp_path / "mine.toml"
    p.write_text(GOOD)
    s = load_scene(p, check_smallness=False)
    assert s.source == str(p) and s.name == "t"
    assert load_scene("capsule_pipe", check_smallness=False).name.startswith("Capsule")
    with pytest.raises(SceneError, match="no such file"):
        load_scene(tmp_path / "missing.toml")
    bad = tmp_path / "bin.toml"
    bad.write_bytes(b"\xff\xfe\x00")
    with pytest.raises(SceneError, match="cannot read"):
        load_scene(bad)


NOT_SMALL = """
[scene]
name = "flat ellipsoid in a throat"
time = [0, 1]
effects = ["contact", "relative_position"]
{policy}

[[object]]
name = "tower"

[[object.piece]]
name = "throat"
equation = "x^2 + y^2 - z^2/100 = 1"

[[ellipsoid]]
name = "disc"
standard = "ellipsoid"
semi_axes = [0.1, 1, 1]
center = [0.85, 0, 0]
"""


def test_smallness_is_checked_per_piece_at_load():
    """Example 17: the bee is small with respect to the crown and the trunk (Table 2)."""
    s = builtin_scene()
    checks = {k[2]: c for k, c in s.smallness.items()}
    assert set(checks) == {"crown", "trunk"}
    assert all(c.small and c.table_4_applies for c in checks.values())
    assert s.work.done["smallness_checks"] == 2
    # not needed by the effects: not checked
    zone_only = parse_scene(GOOD.replace('effects = ["zone", "contact"]', 'effects = ["zone"]'), "z.toml")
    assert zone_only.smallness == {} and zone_only.work.done["smallness_checks"] == 0


def test_not_small_is_refused_by_default():
    """The corrected hyperboloid row (erratum table-1-h1-curvature): a flat ellipsoid
    against the throat is not small, although the printed Table 1 says it is."""
    with pytest.raises(SceneError) as info:
        parse_scene(NOT_SMALL.format(policy=""), "throat.toml")
    msg = str(info.value)
    assert msg.startswith("throat.toml: ") and "'disc' is not small with respect to piece 'throat'" in msg
    assert "on_not_small" in msg and info.value.details["key"] == "scene.on_not_small"
    assert info.value.value.report.paper_small is True
    assert "a/b^2 <= gamma/alpha^2" in msg and "FAILS" in msg  # the failing condition is shown


def test_not_small_with_warn_keeps_the_scene_and_leaves_contact_undecided():
    from quadric_contact.scenes.simulate import simulate

    with pytest.warns(UserWarning, match="not small"):
        s = parse_scene(NOT_SMALL.format(policy='on_not_small = "warn"'), "throat.toml")
    (check,) = s.smallness.values()
    assert check.small is False and "NOT small" in str(check)
    r = simulate(s)
    state = dict(r.pairs[0].initial.pieces)["throat"]
    # four real roots (the two curves of Remark 9): Corollary 10 may not conclude
    assert state.contact is None and state.region is None
    assert "contact undecided, region undecided" in r.format_text()


def test_enclosing_pair_is_small_but_table_4_is_not_used():
    """A sphere of radius 2 around a sphere of radius 1 (erratum
    table-1-ellipsoid-enclosing): small, contact decided, region undecided."""
    from quadric_contact.scenes.simulate import simulate

    text = """
[scene]
name = "enclosing"
time = [0, 1]
effects = ["contact", "relative_position"]
[[object]]
name = "ball"
[[object.piece]]
name = "ball"
standard = "sphere"
radius = 1
[[ellipsoid]]
name = "shell"
standard = "sphere"
radius = 2
motion = { type = "linear", velocity = [0.5, 0, 0] }
"""
    s = parse_scene(text, "enc.toml")
    (check,) = s.smallness.values()
    assert check.small and not check.table_4_applies
    r = simulate(s)
    pair = r.pairs[0]
    assert r.pairs[0].events == []  # the shell (radius 2) moves by 1/2: it never reaches the ball
    value = dict(pair.initial.pieces)["ball"]
    assert value.contact is False and value.region is None
