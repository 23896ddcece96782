"""The ``distance`` effect of scenes: read from TOML, checked against closed forms derived here,
honest where it has no answer, refused with the field named on bad options, and carried by the
text report, ``--json`` and the result objects."""

from __future__ import annotations

import json
import math
from fractions import Fraction as F

import pytest

from quadric_contact.exact.bounds import MAX_DISTANCE_EVALUATIONS, MIN_DISTANCE_TOLERANCE
from quadric_contact.exact.errors import SceneError
from quadric_contact.interfaces.cli import main
from quadric_contact.model.quadric import Quadric
from quadric_contact.scenes.path_distance import path_distance
from quadric_contact.scenes.scene_model import DISTANCE_EVALUATIONS, DISTANCE_TOLERANCE, Scene
from quadric_contact.scenes.scene_toml import builtin_scene, parse_scene
from quadric_contact.scenes.simulate import simulate
from quadric_contact.scenes.trajectory import PolynomialMotion

# Ball a (radius 1/4) flies straight past the globe (the unit sphere at the origin):
#   p(t) = (-4 + 2 t, 3/2, 1 + t/2),  |p|^2 = 17/4 t^2 - 15 t + 77/4,
# least at t* = 15 / (2 * 17/4) = 30/17, where |p|^2 = 77/4 - 15^2 / 17 = 409/68; so
#   min d = sqrt(409/68) - 1 - 1/4.
# Against the floor (the solid z <= -3) its distance 1 + t/2 + 3 - 1/4 grows: least at t = 0.
# Ball b (radius 1/2) dips over the floor: centre height -1 - 2 t + t^2/2, so
#   d(t) = (-1 - 2 t + t^2/2) + 3 - 1/2 = (t - 2)^2 / 2 - 1/2: least -1/2 (a penetration) at t = 2.
A_RADIUS, B_RADIUS = F(1, 4), F(1, 2)
A_START, A_VELOCITY = (F(-4), F(3, 2), F(1)), (F(2), F(0), F(1, 2))
SPAN = (F(0), F(4))
TOLERANCE = F(1, 2000)

SCENE = """
[scene]
name = "balls past a globe and over a floor"
time = [0, 4]
effects = ["zone", "distance"]
distance_tolerance = "1/2000"
distance_evaluations = 300

[[object]]
name = "globe"
[[object.piece]]
name = "globe"
standard = "sphere"
radius = 1

[[object]]
name = "floor"
[[object.piece]]
name = "floor"
equation = "z = -3"

[[object]]
name = "post"
[[object.piece]]
name = "post"
standard = "sphere"
radius = 1
center = [40, 40, 0]

[[ellipsoid]]
name = "a"
standard = "sphere"
radius = "1/4"
center = [-4, 1.5, 1]
motion = { type = "linear", velocity = [2, 0, 0.5] }

[[ellipsoid]]
name = "b"
standard = "sphere"
radius = 0.5
center = [0, 6, -1]
motion = { type = "polynomial", translation = [[0], [0], "-2*t + t^2/2"] }

[[ellipsoid]]
name = "c"
standard = "sphere"
radius = 0.5
center = [0, -6, 0]

[effects]
ellipsoids = { b = ["distance"], c = ["zone"] }
pieces = { "post/post" = ["zone"] }
"""


def read(text: str = SCENE) -> Scene:
    return parse_scene(text, "distance.toml", check_smallness=False)


@pytest.fixture(scope="module")
def result():
    return simulate(read())


def a_distance(t: F) -> float:
    """The closed form of ball a against the globe (floats: for the localisation check)."""
    p = [s + v * t for s, v in zip(A_START, A_VELOCITY, strict=True)]
    return math.sqrt(sum(float(c) ** 2 for c in p)) - 1 - float(A_RADIUS)


def test_the_effect_and_its_options_are_read_from_toml():
    scene = read()
    assert "distance" in scene.effects
    assert scene.distance_tolerance == TOLERANCE and scene.distance_evaluations == 300
    assert scene.ellipsoid_effects == {"b": ("distance",), "c": ("zone",)}
    assert scene.piece_effects == {("post", "post"): ("zone",)}
    plain = read(SCENE.replace('distance_tolerance = "1/2000"\ndistance_evaluations = 300\n', ""))
    assert (plain.distance_tolerance, plain.distance_evaluations) == (
        DISTANCE_TOLERANCE,
        DISTANCE_EVALUATIONS,
    )
    assert read(SCENE.replace('"1/2000"', "0.002")).distance_tolerance == F(1, 500)  # read exactly


def test_only_the_pairs_that_ask_get_a_distance(result):
    asked = {(d.ellipsoid, d.object, d.piece) for p in result.pairs for d in p.distances}
    # c asks for zones only, the post only for zones; a and b ask (a through the scene's effects)
    assert asked == {
        ("a", "globe", "globe"),
        ("a", "floor", "floor"),
        ("b", "globe", "globe"),
        ("b", "floor", "floor"),
    }
    assert result.ledger.by_target["globe/globe"]["distance_evaluations"] > 0
    assert "post/post" not in result.ledger.by_target


def test_ball_passing_a_sphere_against_the_closed_form(result):
    d = result.distance("a", "globe", "globe")
    lo, hi = d.minimum
    # min d = sqrt(409/68) - 5/4: compare squares exactly, lo + 5/4 > 0 here
    assert (lo + F(5, 4)) ** 2 <= F(409, 68) <= (hi + F(5, 4)) ** 2
    assert hi - lo <= TOLERANCE and d.tolerance_reached
    t_star = F(30, 17)
    assert any(a <= t_star <= b for a, b in d.times)
    # every reported interval is one the Lipschitz bound could not discard: at its ends
    # d <= min d + 2 tol + V (b - a), with V = |velocity| (floats, with a margin)
    speed = math.sqrt(sum(float(v) ** 2 for v in A_VELOCITY))
    least = a_distance(t_star)
    for a, b in d.times:
        for t in (a, b):
            assert a_distance(t) - least <= 2 * float(TOLERANCE) + speed * float(b - a) + 1e-9
    assert 2 <= d.evaluations <= 300


def test_minimum_at_the_start_of_the_span(result):
    d = result.distance("a", "floor", "floor")
    lo, hi = d.minimum
    least = A_START[2] + 3 - A_RADIUS  # 1 + t/2 + 3 - 1/4 at t = 0
    assert lo <= least <= hi and hi - lo <= TOLERANCE
    assert d.times[0][0] == SPAN[0] and all(b < 1 for _, b in d.times)


def test_a_penetration_against_the_closed_form(result):
    d = result.distance("b", "floor", "floor")
    lo, hi = d.minimum
    assert lo <= F(-1, 2) <= hi < 0 and hi - lo <= TOLERANCE
    assert any(a <= 2 <= b for a, b in d.times)
    # d(t) - min d = (t - 2)^2 / 2 <= 2 tol + V (b - a) at the ends of a live interval, with
    # V = max |z'| = max |t - 2| <= 2 on [0, 4]
    for a, b in d.times:
        for t in (a, b):
            assert (t - 2) ** 2 / 2 <= 2 * TOLERANCE + 2 * (b - a)


def test_the_text_report_and_the_json_carry_the_enclosure(result, tmp_path, capsys):
    text = result.format_text()
    assert "least signed distance from globe: [" in text and "distance_evaluations" in text
    assert "(a penetration)" in text  # b against the floor
    path = tmp_path / "distance.toml"
    path.write_text(SCENE)
    assert main(["simulate", str(path), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    pair = next(p for p in data["pairs"] if (p["ellipsoid"], p["object"]) == ("a", "globe"))
    (entry,) = pair["distance"]
    lo, hi = F(entry["minimum"]["lo"]), F(entry["minimum"]["hi"])
    assert (lo + F(5, 4)) ** 2 <= F(409, 68) <= (hi + F(5, 4)) ** 2
    assert entry["available"] and entry["reason"] is None and entry["tolerance"] == "1/2000"
    assert (
        entry["tolerance_reached"] is True
        and entry["evaluations"] == result.distance("a", "globe", "globe").evaluations
    )
    assert any(F(a) <= F(30, 17) <= F(b) for a, b in entry["times"])
    low, high = (F(x) for x in entry["minimum"]["decimal"])
    assert low <= lo and hi <= high  # rounded outwards
    c_pair = next(p for p in data["pairs"] if p["ellipsoid"] == "c")
    assert c_pair["distance"] == []


def test_the_command_line_accepts_the_effect(tmp_path, capsys):
    path = tmp_path / "distance.toml"
    path.write_text(SCENE)
    assert main(["simulate", str(path), "--effects", "distance"]) == 0
    out = capsys.readouterr().out
    assert "least signed distance from floor" in out and "the least signed distance along the path" in out


# -- where the method has no answer, it says so --------------------------------------------

ONE = """
[scene]
name = "one"
time = [0, 2]
effects = ["distance"]
{scene_extra}
[[object]]
name = "o"
{tree}
[[object.piece]]
name = "p"
{piece}
[[ellipsoid]]
name = "e"
standard = "sphere"
radius = 0.5
center = [0, 0, 3]
motion = {motion}
"""


def one(
    piece: str = 'standard = "sphere"\nradius = 1',
    motion: str = '{ type = "linear", velocity = [1, 0, 0] }',
    tree: str = "",
    scene_extra: str = "",
):
    text = ONE.format(piece=piece, motion=motion, tree=tree, scene_extra=scene_extra)
    return simulate(read(text)).distance("e", "o", "p")


def test_a_turning_ellipsoid_is_answered():
    # a ball of radius 1/2 at height 3, turning about its centre, above the unit ball: 3/2 all along
    d = one(
        motion='{ type = "polynomial", translation = [[0], [0], [0]], quaternion = [[1], [0, 1], [0], [0]] }'
    )
    assert d.available and d.minimum[0] <= F(3, 2) <= d.minimum[1] and d.evaluations > 0


def test_a_fixed_orientation_is_a_translation():
    # a constant quaternion: the same rotated copy at every time; a sphere passing the unit
    # sphere at height 3: |p| = sqrt(t^2 + 9), least 3 - 3/2 at t = 0
    d = one(
        motion='{ type = "polynomial", translation = [[0, 1], [0], [0]], quaternion = [[2], [0], [0], [1]] }'
    )
    assert d.available and d.minimum[0] <= F(3, 2) <= d.minimum[1]


def _side_below(plane: str) -> str:
    """The region (``R-`` or ``R+`` of the plane as the scene reads it) holding the point
    ``(0, 0, -1)``: the sign of ``X^T P X`` there, computed from the plane's own matrix."""
    P = Quadric.from_equation(plane)
    X = (F(0), F(0), F(-1), F(1))
    value = sum(P[i, j] * X[i] * X[j] for i in range(4) for j in range(4))
    assert value != 0
    return "minus" if value < 0 else "plus"


@pytest.mark.parametrize("reading", ["", 'reading = "paper"'])
@pytest.mark.parametrize("side", ["minus", "plus"])
def test_a_cut_piece_keeps_the_side_of_its_tree(reading, side):
    # The ball of radius 2 at the origin cut by the plane z = 0; the still ball of radius 1/2
    # centred at (0, 0, 3).  Kept half below (z <= 0): the nearest point of the half ball to the
    # centre is the centre of its flat face (the centre projects onto the plane inside the
    # disc), so d = 3 - 1/2 = 5/2.  Kept half above: the nearest point is the top (0, 0, 2) of
    # the sphere, d = 3 - 2 - 1/2 = 1/2.  Which half a side keeps is read off the plane's matrix
    # (``_side_below``), so a flipped side gives the other value.
    d = one(
        piece='standard = "sphere"\nradius = 2',
        tree=f'tree = {{ plane = "z = 0", {side} = "p" }}',
        motion='{ type = "still" }',
        scene_extra=reading,
    )
    expected = F(5, 2) if side == _side_below("z = 0") else F(1, 2)
    lo, hi = d.minimum
    assert d.available and lo <= expected <= hi and hi - lo <= DISTANCE_TOLERANCE, d


def test_a_piece_in_two_leaves_is_the_union_of_its_parts():
    # The ball of radius 2 kept where x >= 1 and where x <= -1 (two leaves of one piece), the
    # still ball of radius 1/2 at (0, 0, 3): by symmetry both parts are as far; the nearest
    # point of the part x >= 1 to the centre c = (0, 0, 3) is on the rim (1, 0, sqrt 3) of its
    # flat face (the projection (1, 0, 3) of c on the plane is outside the disc y^2 + z^2 <= 3,
    # and c - (1, 0, sqrt 3) = (-1, 0, 3 - sqrt 3) is a + b combination of the sphere's normal
    # (1, 0, sqrt 3) and the face's (-1, 0, 0) with a = (3 - sqrt 3) / sqrt 3 > 0, b = a + 1 > 0),
    # so d = sqrt(1 + (3 - sqrt 3)^2) - 1/2.
    d = one(
        piece='standard = "sphere"\nradius = 2',
        tree='tree = { plane = "x = 1", plus = "p", minus = { plane = "x = -1", minus = "p" } }',
        motion='{ type = "still" }',
    )
    expected = math.sqrt(1 + (3 - math.sqrt(3)) ** 2) - 0.5
    lo, hi = d.minimum
    assert d.available and float(lo) <= expected + 1e-15 and expected - 1e-15 <= float(hi)
    assert hi - lo <= DISTANCE_TOLERANCE


def test_a_cut_piece_crossed_is_not_available():
    # the ball of radius 1/2 at height 3 moving down into the half ball z <= 0 of radius 2
    d = one(
        piece='standard = "sphere"\nradius = 2',
        tree='tree = { plane = "z = 0", minus = "p" }',
        motion='{ type = "linear", velocity = [0, 0, -2] }',
    )
    assert not d.available and d.reason.startswith("at t = ") and "cross or touch" in d.reason


def test_a_cut_piece_that_is_not_convex_is_not_available():
    # a hyperboloid of one sheet cut by a plane: its solid is not convex
    d = one(piece='equation = "x^2 + y^2 - z^2 = 1"', tree='tree = { plane = "z = 5", minus = "p" }')
    assert not d.available and "cut by the plane(s) z = 5" in d.reason and "not convex" in d.reason


def test_the_inside_of_a_piece_is_its_solid():
    # a ball whose inside is the outside of the sphere: the complement of a solid
    d = one(piece='standard = "sphere"\nradius = 1\ninside = "R+"')
    assert not d.available and "complement of its solid" in d.reason
    # a plane's other side is a half-space: z >= 0, with the still ball's centre at height 3
    # inside it, so d = -(3 + 1/2) (move it down by 7/2 to clear)
    d = one(piece='equation = "z = 0"\ninside = "R+"', motion='{ type = "still" }')
    lo, hi = d.minimum
    assert lo <= F(-7, 2) <= hi and hi - lo <= DISTANCE_TOLERANCE and d.times == ((F(0), F(2)),)
    d = one(piece='equation = "z = 0"', motion='{ type = "still" }')  # z <= 0: apart by 3 - 1/2
    lo, hi = d.minimum
    assert lo <= F(5, 2) <= hi and hi - lo <= DISTANCE_TOLERANCE


def test_an_undecided_distance_names_its_time():
    # the ball's centre enters the solid of a hyperboloid of one sheet (not convex), whose
    # penetration depth is not computed: x^2 + y^2 - z^2 <= 1 holds at (0, 0, 3)
    d = one(piece='equation = "x^2 + y^2 - z^2 = 1"')
    assert not d.available and d.reason.startswith("at t = ") and "not convex" in d.reason


def test_the_budget_is_a_bound():
    # a ball rolling on the floor touches it all the time: d = 0 everywhere, so no interval is
    # ever discarded and the budget runs out first; the enclosure still holds 0
    text = ONE.format(
        piece='equation = "z = 0"',
        motion='{ type = "linear", velocity = [1, 0, 0] }',
        tree="",
        scene_extra="distance_evaluations = 20",
    )
    d = simulate(read(text.replace("center = [0, 0, 3]", "center = [0, 0, 0.5]"))).distance("e", "o", "p")
    lo, hi = d.minimum
    assert lo <= 0 <= hi and d.evaluations == 20 and not d.tolerance_reached
    assert "the budget of 20 ran out" in d.describe()
    r = path_distance(Quadric.sphere(1), "z", PolynomialMotion([[0, 1], [0], [1]]), 0, 8, max_evaluations=7)
    assert len(r.samples) == 7


# -- bad options are refused, naming the field -----------------------------------------------


@pytest.mark.parametrize(
    ("line", "key"),
    [
        ('distance_tolerence = "1/100"', "scene.distance_tolerence"),  # an unknown key
        ('distance_tolerance = "tight"', "scene.distance_tolerance"),
        ('distance_tolerance = "-1/100"', "scene.distance_tolerance"),
        ("distance_tolerance = 0", "scene.distance_tolerance"),
        ("distance_tolerance = 1e-13", "scene.distance_tolerance"),
        ("distance_tolerance = [1]", "scene.distance_tolerance"),
        ("distance_evaluations = 1", "scene.distance_evaluations"),
        (f"distance_evaluations = {MAX_DISTANCE_EVALUATIONS + 1}", "scene.distance_evaluations"),
        ("distance_evaluations = 2.5", "scene.distance_evaluations"),
        ('distance_evaluations = "200"', "scene.distance_evaluations"),
    ],
)
def test_bad_options_name_the_field(line, key):
    text = SCENE.replace('distance_tolerance = "1/2000"\ndistance_evaluations = 300\n', line + "\n")
    with pytest.raises(SceneError) as info:
        read(text)
    assert str(info.value).startswith(f"distance.toml: {key}: expected"), str(info.value)


def test_a_tolerance_below_the_floor_says_why():
    small = MIN_DISTANCE_TOLERANCE / 10
    with pytest.raises(SceneError, match="MIN_DISTANCE_TOLERANCE") as info:
        read(SCENE.replace('"1/2000"', f'"{small}"'))
    assert info.value.details["key"] == "scene.distance_tolerance"
    assert (
        read(SCENE.replace('"1/2000"', f'"{MIN_DISTANCE_TOLERANCE}"')).distance_tolerance
        == MIN_DISTANCE_TOLERANCE
    )


def test_a_scene_built_directly_is_checked_too():
    scene = read()
    for field, value in (("distance_tolerance", F(-1)), ("distance_evaluations", 0)):
        with pytest.raises(SceneError, match=f"scene.{field}"):
            Scene(scene.name, scene.objects, scene.ellipsoids, scene.span, **{field: value})


# -- the built-in scene that asks for it -------------------------------------------------------


def test_ball_over_saddle_sinks_into_the_ground_by_the_closed_form_depth():
    """The ball (a sphere) follows a parabola, concave in time: its height above the ground
    is least at an end of the span, and its signed distance from the solid z <= 0 is that
    height minus its radius, both read from the scene."""
    scene = builtin_scene("ball_over_saddle")
    (ball,) = scene.ellipsoids
    assert "distance" in scene.effects
    (seg,) = ball.trajectory.segments(*scene.span, ball.center)
    q = ball.quadric
    centre = (*ball.center, F(1))
    # a sphere k |x - c|^2 - k r^2: its form at the centre is -k r^2
    at_centre = sum(q[i, j] * centre[i] * centre[j] for i in range(4) for j in range(4))
    radius_squared = -at_centre / q[0, 0]
    ends = [seg.center_at(t)[2] for t in scene.span]
    lowest = min(ends)
    t_low = scene.span[ends.index(lowest)]
    result = simulate(scene)
    d = result.distance("ball", "ground", "ground")
    lo, hi = d.minimum
    # min d = lowest - r, r = sqrt(radius_squared): lowest - hi <= r <= lowest - lo, squared
    assert lowest - hi >= 0 and (lowest - hi) ** 2 <= radius_squared <= (lowest - lo) ** 2
    assert hi - lo <= scene.distance_tolerance and any(a <= t_low <= b for a, b in d.times)
    roof = result.distance("ball", "roof", "saddle")
    assert not roof.available
    assert "R+ of its hyperbolic paraboloid, the complement of its solid" in roof.reason
    assert "least signed distance from saddle: not available" in result.format_text()
