"""Scene files read through the package's parser: every number and equation,
unique names, and messages that name the file, the key and what was expected."""

from __future__ import annotations

from fractions import Fraction

import pytest

from quadric_contact.exact.errors import ChoiceError, SceneError
from quadric_contact.exact.reading import parse_univariate
from quadric_contact.scenes.scene_toml import load_scene, parse_scene

SCENE = """
[scene]
name = "two balls over a plane"
time = [0, 2]
effects = ["zone", "contact"]

[[object]]
name = "floor"
[[object.piece]]
name = "ground"
equation = "z = 0"

[[ellipsoid]]
name = "a"
standard = "sphere"
radius = "1/4"
center = [0, 0, "3/2"]
motion = { type = "polynomial", translation = ["t/2", [0], "-t^2/4"] }

[[ellipsoid]]
name = "b"
equation = "4*x^2 + 4*y^2 + 4*(z - 2)^2 = 1"
motion = { type = "linear", velocity = ["1e-1", 0, "-1/2"] }
"""


def read(text: str = SCENE) -> object:
    return parse_scene(text, "balls.toml", check_smallness=False)


def failure(text: str) -> SceneError:
    with pytest.raises(SceneError) as info:
        read(text)
    assert str(info.value).startswith("balls.toml: "), str(info.value)
    return info.value


def test_numbers_and_paths_in_t_are_read_exactly():
    s = read()
    a, b = s.ellipsoids
    assert a.center == (0, 0, Fraction(3, 2))
    assert a.trajectory.translation == (
        parse_univariate("t/2"),
        (Fraction(0),),
        (Fraction(0), Fraction(0), Fraction(-1, 4)),
    )
    assert b.trajectory.translation[0] == (Fraction(0), Fraction(1, 10))


@pytest.mark.parametrize(
    "old, new, key, expected, cause",
    [
        ('name = "b"', 'name = "a"', "ellipsoid[1].name", "a name not used by another", "ellipsoid[0].name"),
        ('name = "b"', 'name = "floor"', "ellipsoid[1].name", "a name not used by another", "object[0].name"),
        (
            "time = [0, 2]",
            "time = [2, 0]",
            "scene.time",
            "[start, end] with start < end",
            "reversed: the end 0 is not after",
        ),
        ("time = [0, 2]", "time = [2, 2]", "scene.time", "[start, end] with start < end", "empty"),
        ("time = [0, 2]", 'time = [0, "2x"]', "scene.time[1]", "a finite number", "unknown name 'x'"),
        ('radius = "1/4"', 'radius = "1/0"', "ellipsoid[0].radius", "a finite number", "division by zero"),
        ('"t/2"', '"sin(t)"', "ellipsoid[0].motion.translation[0]", "a polynomial in t", "function call"),
        ('"t/2"', '"t^9"', "ellipsoid[0].motion.translation[0]", "a polynomial in t", "MAX_DEGREE"),
        ('"t/2"', '"x/2"', "ellipsoid[0].motion.translation[0]", "a polynomial in t", "unknown name 'x'"),
        (
            '"4*x^2 + 4*y^2 + 4*(z - 2)^2 = 1"',
            '"4x^2 + 4y^2 + 4(z - 2)^2 = 1"',
            "ellipsoid[1].equation",
            "a valid quadric",
            "write 4*x",
        ),
        ('"z = 0"', '"z == 0"', "object[0].piece[0].equation", "a valid quadric", "a single '='"),
        ('"1e-1"', '"1e-99999"', "ellipsoid[1].motion.velocity[0]", "a finite number", "MAX_DIGITS"),
    ],
)
def test_errors_name_the_key_what_was_expected_and_why(old, new, key, expected, cause):
    assert old in SCENE
    err = failure(SCENE.replace(old, new, 1))
    message = str(err)
    assert err.details["key"] == key, message
    assert f"expected {expected}" in message and cause in message, message


def test_an_unknown_smallness_override_is_a_choice_error(tmp_path):
    path = tmp_path / "balls.toml"
    path.write_text(SCENE, encoding="utf-8")
    for call in (
        lambda: parse_scene(SCENE, "balls.toml", on_not_small="ignore"),
        lambda: parse_scene(SCENE, "balls.toml", check_smallness=False, on_not_small="ignore"),
        lambda: load_scene(path, on_not_small="ignore"),
        lambda: load_scene("bee_and_tree", on_not_small="ignore"),
    ):
        with pytest.raises(
            ChoiceError, match="on_not_small must be one of 'refuse', 'warn' or None, got 'ignore'"
        ):
            call()
    assert parse_scene(SCENE, "balls.toml", on_not_small="warn").on_not_small == "refuse"  # the file's own


def test_duplicate_object_names():
    twice = SCENE.replace('[[ellipsoid]]\nname = "a"', '[[object]]\nname = "floor"\n[[object.piece]]\n'
                          'name = "g"\nequation = "z = 1"\n\n[[ellipsoid]]\nname = "a"', 1)  # fmt: skip
    err = failure(twice)
    assert err.details["key"] == "object[1].name" and "object[0].name is also 'floor'" in str(err)
