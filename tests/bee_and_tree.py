"""Example 17's bee and tree as scene text, written once for every test that reads it.

The tree is the plane ``z = 6`` with the crown above and the trunk below; the bee
is the small ellipsoid of Example 17.  Tests vary the scene's name, time span,
effects and the bee's motion (``tests/conftest.py`` offers the builder as the
``bee_and_tree`` fixture).
"""

from __future__ import annotations

CROWN = "x^2 + y^2 + 3*(z - 8.36291)^2 = 20"
TRUNK = "x^2 + y^2 - 0.25*(z - 3)^2 = 1"
BEE = "(x - 3)^2 + (y - 3)^2 + 3*(z - 5.5)^2 = 0.1"


def bee_and_tree(*, name: str, time: str, effects: str, motion: str) -> str:
    """The scene text (TOML) with the given ``[scene]`` values and the bee's ``motion`` table."""
    return f"""
[scene]
name = "{name}"
time = {time}
effects = {effects}

[[object]]
name = "tree"
tree = {{ plane = "z = 6", plus = "crown", minus = "trunk" }}

[[object.piece]]
name = "crown"
equation = "{CROWN}"

[[object.piece]]
name = "trunk"
equation = "{TRUNK}"

[[ellipsoid]]
name = "bee"
equation = "{BEE}"
motion = {motion}
"""
