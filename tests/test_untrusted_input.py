"""Untrusted text never runs: the hostile corpus through every entry point that takes
text, with the audit hook of ``tests/untrusted.py`` armed (it blocks and records any
program run, any ``eval``/``exec``/``compile`` of text, any file written).

Every string of the corpus must be refused with the package's own error (exit
status 2 for the command line), and no file named ``PWNED`` may appear."""

from __future__ import annotations

import contextlib
import io
import os
import sys
from collections.abc import Callable
from fractions import Fraction
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from tests.bee_and_tree import CROWN
from tests.untrusted import HOSTILE, PAYLOAD, untrusted

import quadric_contact as qc
from quadric_contact import Quadric
from quadric_contact.exact.algebraic import compile_expression
from quadric_contact.exact.errors import QuadricContactError, SceneError
from quadric_contact.exact.rational import to_fraction
from quadric_contact.interfaces.cli import main
from quadric_contact.model.motions import rotation_from_quaternion
from quadric_contact.scenes.scene_toml import load_scene, parse_scene
from quadric_contact.scenes.trajectory import Keyframes, PolynomialMotion
from quadric_contact.theory.pencil import as_quadric

BEE = "(x - 3)^2 + (y - 3)^2 + 3*(z - 5.5)^2 - 0.1"
TRUNK = "x^2 + y^2 - 0.25*(z - 3)^2 - 1"


def _cli(*args: str) -> int:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(["check", "--", *args])
    if code != 0:
        assert "error" in err.getvalue(), err.getvalue()
    return code


def _object_matrix(entry: Any) -> np.ndarray:
    m = np.array([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, Fraction(-1, 10)]], dtype=object)
    m[3, 3] = entry
    return m


ENTRY_POINTS: dict[str, Callable[[str], Any]] = {
    "Quadric.from_equation": Quadric.from_equation,
    "Quadric(text) via as_quadric": as_quadric,
    "characteristic_polynomial": lambda s: qc.characteristic_polynomial(BEE, s),
    "transversal_contact(E text)": lambda s: qc.transversal_contact(s, TRUNK),
    "relative_position(Q text)": lambda s: qc.relative_position(BEE, s),
    "plane_side(plane text)": lambda s: qc.plane_side(BEE, s),
    "smallness(Q text)": lambda s: qc.smallness(BEE, s),
    "to_fraction": to_fraction,
    "Quadric.from_matrix (string entry)": lambda s: Quadric.from_matrix(
        [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, s]]
    ),
    "Quadric.from_coefficients": lambda s: Quadric.from_coefficients(np.eye(3), [0, 0, 0], s),
    "Quadric.diagonal": lambda s: Quadric.diagonal(1, 1, 1, s),
    "Quadric.ellipsoid (semi-axis)": lambda s: Quadric.ellipsoid(s, 1, 1),
    "Quadric.sphere (radius)": lambda s: Quadric.sphere(s),
    "Quadric.sphere (centre)": lambda s: Quadric.sphere(1, center=(0, s, 0)),
    "Quadric.translated": lambda s: Quadric.sphere(1).translated((s, 0, 0)),
    "Quadric.plane (offset)": lambda s: Quadric.plane((0, 0, 1), s),
    "Quadric.scaled": lambda s: Quadric.sphere(1).scaled(s),
    "Quadric.standard (kind)": lambda s: Quadric.standard(s, a=1),
    "Quadric.standard (parameter)": lambda s: Quadric.standard("ellipsoid", a=s, b=1, c=1),
    "rotation_from_quaternion": lambda s: rotation_from_quaternion(1, s, 0, 0),
    "transversal_contact(object array)": lambda s: qc.transversal_contact(_object_matrix(s), TRUNK),
    "transversal_contact(string array)": lambda s: qc.transversal_contact(
        np.array(_object_matrix(s).astype(str)), Quadric.from_equation(TRUNK).to_numpy()
    ),
    "PolynomialMotion (text in t)": lambda s: PolynomialMotion((s, "0", "0")),
    "PolynomialMotion.linear": lambda s: PolynomialMotion.linear((s, 0, 0)),
    "Keyframes (time)": lambda s: Keyframes([(0, (0, 0, 0)), (s, (1, 0, 0))]),
    "compile_expression": lambda s: compile_expression(s, []),
}


def _toml(s: str) -> str:
    """``s`` as a TOML basic string (every control character escaped)."""
    out = []
    for c in s:
        if c in '"\\':
            out.append("\\" + c)
        elif ord(c) < 0x20 or ord(c) == 0x7F:
            out.append(f"\\u{ord(c):04X}")
        else:
            out.append(c)
    return '"' + "".join(out) + '"'


SCENE = """
[scene]
name = "s"
time = [0, {time}]
effects = ["zone", "contact"]

[[object]]
name = "tree"
tree = {{ plane = {plane}, plus = "crown", minus = "trunk" }}

[[object.piece]]
name = "crown"
equation = {crown}

[[object.piece]]
name = "trunk"
matrix = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, -0.25, 0.75], [0, 0, 0.75, {entry}]]

[[ellipsoid]]
name = "bee"
equation = {bee}
motion = {{ type = "keyframes", keys = [
    {{ t = 0, at = [3, 3, 5.5] }}, {{ t = {t}, at = [1.5, {at}, 6.5] }}] }}

[[ellipsoid]]
name = "ball"
standard = "sphere"
radius = {radius}
center = [{center}, 0, 20]
motion = {{ type = "polynomial", translation = [{path}, [0], [{velocity}]] }}
"""

SCENE_FIELDS = {
    "scene.time[1]": "time",
    "object[0].tree.plane": "plane",
    "object[0].piece[0].equation": "crown",
    "object[0].piece[1].matrix[3][3]": "entry",
    "ellipsoid[0].equation": "bee",
    "ellipsoid[0].motion.keys[1].t": "t",
    "ellipsoid[0].motion.keys[1].at[1]": "at",
    "ellipsoid[1].radius": "radius",
    "ellipsoid[1].center[0]": "center",
    "ellipsoid[1].motion.translation[0]": "path",
    "ellipsoid[1].motion.translation[2][0]": "velocity",
}
GOOD_FIELDS = {
    "time": "2",
    "plane": _toml("z = 6"),
    "crown": _toml(CROWN),
    "entry": "-3.25",
    "bee": _toml(BEE),
    "t": "2",
    "at": "0.5",
    "radius": _toml("1/4"),
    "center": "10",
    "path": _toml("t/2"),
    "velocity": "0",
}


def scene_text(**fields: str) -> str:
    return SCENE.format(**{**GOOD_FIELDS, **fields})


@pytest.fixture(scope="module", autouse=True)
def warm_up(tmp_path_factory):
    """Run every entry point once, unarmed, on good and on bad text, so that lazy
    imports and first-call set-up (numba, dataclasses) happen before the hook is armed."""
    good = {
        "to_fraction": "1/3",
        "Quadric.from_matrix (string entry)": "-1",
        "Quadric.from_coefficients": "-1",
        "Quadric.diagonal": "-1",
        "Quadric.ellipsoid (semi-axis)": "2",
        "Quadric.sphere (radius)": "2",
        "Quadric.sphere (centre)": "1",
        "Quadric.translated": "1",
        "Quadric.plane (offset)": "1",
        "Quadric.scaled": "2",
        "Quadric.standard (kind)": "parallel planes",
        "Quadric.standard (parameter)": "2",
        "rotation_from_quaternion": "1",
        "transversal_contact(object array)": "-1/10",
        "transversal_contact(string array)": "-0.1",
        "PolynomialMotion (text in t)": "t",
        "PolynomialMotion.linear": "1",
        "Keyframes (time)": "1",
        "plane_side(plane text)": "z - 6",
    }
    for name, fn in ENTRY_POINTS.items():
        for text in (good.get(name, BEE if "E text" in name else TRUNK), "x2 + 1", "1e99999999"):
            with contextlib.suppress(QuadricContactError):
                fn(text)
    _cli(BEE, TRUNK)
    _cli("x2", TRUNK)
    parse_scene(scene_text(), "good.toml", check_smallness=True)
    path = tmp_path_factory.mktemp("warm") / "good.toml"
    path.write_text(scene_text())
    load_scene(path, check_smallness=False)
    for key, field in SCENE_FIELDS.items():
        with contextlib.suppress(SceneError):
            parse_scene(scene_text(**{field: _toml("x2")}), "bad.toml", check_smallness=False)
        assert key


@pytest.fixture(autouse=True)
def no_pwned(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    yield
    assert not (tmp_path / "PWNED").exists()
    assert not Path("PWNED").exists()


def test_the_hook_blocks_and_records(tmp_path):
    with pytest.raises(AssertionError, match="compile"), untrusted():
        eval("1 + 1")
    with pytest.raises(AssertionError, match=r"os\.system"), untrusted():
        os.system("touch PWNED")
    with pytest.raises(AssertionError, match="open"), untrusted():
        (tmp_path / "f.txt").write_text("x")
    with pytest.raises(AssertionError, match="compile"), untrusted():
        from sympy.parsing.sympy_parser import parse_expr

        with contextlib.suppress(PermissionError):  # recorded, even when swallowed
            parse_expr("x + 1")
    assert not (tmp_path / "PWNED").exists() and not (tmp_path / "f.txt").exists()
    assert eval("1 + 1") == 2  # disarmed again


def test_the_old_reader_would_have_run_the_payload():
    """The reader this package used before (``parse_expr`` with a whitelist of
    globals): the hook catches the issue's payload, and blocks it."""
    from sympy.parsing.sympy_parser import parse_expr, standard_transformations

    with (
        pytest.raises(AssertionError, match=r"compile|os\.system"),
        untrusted(),
        contextlib.suppress(Exception),
    ):
        parse_expr(PAYLOAD, global_dict={}, transformations=standard_transformations)


@pytest.mark.parametrize("entry", list(ENTRY_POINTS))
def test_hostile_corpus_through_the_api(entry):
    fn = ENTRY_POINTS[entry]
    unexpected = []
    with untrusted():
        for text in HOSTILE:
            try:
                fn(text)
            except QuadricContactError as exc:
                assert str(exc)
            else:
                unexpected.append(text)
    assert not unexpected, f"{entry} accepted {unexpected!r:.300}"


@pytest.mark.parametrize("position", ["E", "Q"])
def test_hostile_corpus_through_the_command_line(position):
    with untrusted():
        for text in HOSTILE:
            args = (text, TRUNK) if position == "E" else (BEE, text)
            assert _cli(*args) == 2, text[:60]


@pytest.mark.parametrize("key", list(SCENE_FIELDS))
def test_hostile_corpus_through_scene_files(key):
    field = SCENE_FIELDS[key]
    texts = [scene_text(**{field: _toml(text)}) for text in HOSTILE]
    with untrusted():
        for hostile, text in zip(HOSTILE, texts, strict=True):
            with pytest.raises(SceneError) as info:
                parse_scene(text, "hostile.toml")
            message = str(info.value)
            assert message.startswith("hostile.toml: "), message
            if "not valid TOML" not in message:
                assert info.value.details["key"].startswith(key), (hostile[:40], message)


def test_hostile_corpus_through_scene_files_on_disk(tmp_path):
    paths = []
    for i, text in enumerate(HOSTILE):
        p = tmp_path / f"hostile_{i}.toml"
        p.write_text(scene_text(crown=_toml(text)), encoding="utf-8")
        paths.append(p)
    with untrusted():
        for p in paths:
            with pytest.raises(SceneError) as info:
                load_scene(p)
            assert str(info.value).startswith(f"{p}: ")


@pytest.mark.parametrize(
    "raw, key",
    [
        ("time = [0, 1e99999999]", "scene.time[1]"),
        ("time = [0, 1e-99999999]", "scene.time[1]"),
        ("time = [0, " + "9" * 4000 + "]", "scene.time[1]"),
        ("time = [0, " + "9" * 5000 + "]", None),
        ("time = [0, inf]", "scene.time[1]"),
    ],
)
def test_raw_toml_numbers_are_bounded_too(raw, key):
    text = scene_text().replace("time = [0, 2]", raw)
    with untrusted(), pytest.raises(SceneError) as info:
        parse_scene(text, "raw.toml")
    if key is None:
        assert "not valid TOML" in str(info.value)
    else:
        assert info.value.details["key"] == key, str(info.value)
        assert "MAX_DIGITS" in str(info.value) or "inf" in raw


def test_text_is_still_read_where_it_is_valid():
    """The same entry points, armed, on good text: the parser itself trips nothing."""
    with untrusted():
        s = parse_scene(scene_text(), "good.toml", check_smallness=False)
        assert s.span == (0, 2)
        assert Quadric.from_equation(BEE)[3, 3] == Fraction(2173, 20)
        assert to_fraction("1/3 + 2/7") == Fraction(13, 21)
        assert _cli(BEE, TRUNK) == 0


def test_modules_imported_by_this_test_are_the_packages():
    assert sys.modules["quadric_contact"].__file__ == qc.__file__


def test_a_boolean_entry_is_refused_in_every_form():
    """``True`` is not a number in a single matrix, and not in a stack either (numpy would
    read it as 1 in a list of numbers)."""
    Q = [[True, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, -4]]
    E = "x**2 + y**2 + z**2 - 1"
    for form in (Q, [Q], (Q,)):
        with pytest.raises(qc.NotANumberError):
            qc.transversal_contact(E, form)


def test_root_counts_take_any_exact_number_and_refuse_the_rest():
    """numpy integers and binary64 values are the exact numbers they store; a NaN, a boolean or a
    complex number is refused with the package's errors."""
    import numpy as np

    want = qc.root_signs([1, 2, 3, 4, 5]).pattern
    assert qc.root_signs(np.array([1, 2, 3, 4, 5])).pattern == want
    assert qc.root_signs([np.int64(v) for v in (1, 2, 3, 4, 5)]).pattern == want
    assert (
        qc.root_structure(np.array([1.0, 2, 3, 4, 5])).describe()
        == qc.root_structure([1, 2, 3, 4, 5]).describe()
    )
    for bad, error in (
        ([1, 2, float("nan"), 4, 5], qc.NonFiniteError),
        ([True, 1, 1, 1, 1], qc.NotANumberError),
    ):
        with pytest.raises(error):
            qc.root_signs(bad)


def test_first_contact_scales_beyond_binary64_are_answered_or_refused_by_the_work_bound():
    """A root of the scale polynomial beyond binary64's range is bracketed in exact arithmetic:
    an answer, or the package's bound on the work, never an overflow."""
    r = qc.contact_scale("x**2 + y**2 + z**2 - 1", "x**2 + y**2 + z**2 - 1e320")
    assert r.scale == 10**160
    from quadric_contact.exact.errors import WorkLimitError

    with pytest.raises(WorkLimitError):
        qc.contact_scale("x**2 + y**2 + z**2 - 1", "x - 1e310")


def test_sympy_expressions_are_bounded_before_they_are_expanded():
    """A sympy expression with a huge power is refused before expansion (it would not finish);
    one whose numbers are too long to print is refused with a message that says so; powers that
    cancel still make a quadric."""
    import sympy as sp

    x, y, z = sp.symbols("x y z")
    with pytest.raises(qc.EquationError, match="degree <= 2"):
        qc.Quadric.from_equation(sp.Pow(x, 10**9, evaluate=False) + y**2)
    with pytest.raises(qc.EquationError, match="too long to print"):
        qc.transversal_contact(x**2 + y**2 + z**2 - sp.Integer(10) ** 5000, "x**2 + y**2 + z**2 - 4")
    assert qc.Quadric.from_equation((x + 1) ** 3 - x**3 + y**2 + z**2 - 5).kind is qc.QuadricKind.ELLIPSOID


def test_a_distance_beyond_the_binary64_search_is_refused_at_once():
    """A disc of thickness ``1e-200`` against a ball: the certified search runs in binary64
    intervals, which cannot hold its constants; it refuses the pair before searching (it used
    to walk a rounding loop ulp by ulp, without end)."""
    ball = np.diag([1.0, 1.0, 1.0, -4.0])
    with pytest.raises(qc.UndecidedError, match="beyond the range of the binary64 search"):
        qc.distance("1e400*x**2 + y**2 + z**2 - 1", ball)


def test_distance_options_are_checked_with_the_package_errors():
    """A mode the distance does not know is a ``ChoiceError`` naming the choices (as for the
    other predicates), and ``digits`` must be a positive integer."""
    from quadric_contact.exact.errors import ChoiceError

    E, Q = "x**2 + y**2 + z**2 - 1", "x - 3"
    with pytest.raises(ChoiceError, match="certified, exact, float"):
        qc.distance(E, Q, mode="fast")
    with pytest.raises(ChoiceError):
        qc.contact_scale(E, Q, mode="float")
    for digits in (-5, 0, None, 2.5, True):
        with pytest.raises(qc.NotANumberError, match="digits"):
            qc.distance(E, Q, digits=digits)
