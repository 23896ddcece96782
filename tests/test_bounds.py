"""Every accepted input is answered within a documented bound, or refused up front.

One test (or a few) per way of making the package hang, exhaust memory, abort,
crash while printing, or load code from a planted file, with inputs that the
parser accepts.  None of them measures time: where the defect was slowness the
test observes the work done (calls, terms, sizes) or that the refusal came
before the work.  The subprocess fuzzer is in ``tests/test_hostile_fuzz.py``.
"""

from __future__ import annotations

import re
from fractions import Fraction
from typing import Any

import pytest

from quadric_contact.exact import reading
from quadric_contact.exact.errors import EquationError, NotANumberError
from quadric_contact.exact.reading import MAX_LENGTH, parse_number, parse_polynomial


def _env_with_src() -> dict[str, str]:
    """The environment of a child interpreter that imports this checkout's package."""
    import os
    from pathlib import Path

    env = dict(os.environ)
    env["PYTHONPATH"] = str(Path(__file__).resolve().parents[1] / "src")
    return env


# -- the tokenizer: one anchored match per token ------------------------------------------


class _CountingPattern:
    """Stands in for the token pattern: records where every match starts and
    refuses the scanning methods (a search retries at every later position)."""

    def __init__(self, pattern: re.Pattern[str]) -> None:
        self.pattern = pattern
        self.starts: list[int] = []

    def match(self, text: str, pos: int = 0) -> re.Match[str] | None:
        self.starts.append(pos)
        return self.pattern.match(text, pos)

    def __getattr__(self, name: str) -> Any:
        raise AssertionError(f"the tokenizer called {name}: it scans, so a failure retries at every position")


LONG_RUNS = [
    " " * (MAX_LENGTH - 1) + "!",
    "\t" * (MAX_LENGTH - 1) + "!",
    "\u00a0" * (MAX_LENGTH - 1),
    "1" * (MAX_LENGTH - 1) + "e",
    "1_" * (MAX_LENGTH // 2 - 1) + "e",
    "1" * (MAX_LENGTH - 2) + "..",
    "." + "1" * (MAX_LENGTH - 2) + "e",
    "1" * 999 + "." + "1" * (MAX_LENGTH - 1001) + "e",
    "x + " * (MAX_LENGTH // 4 - 1) + "1!",
]


@pytest.mark.parametrize("text", LONG_RUNS, ids=lambda s: f"{s[:3]!r}x{len(s)}")
def test_the_tokenizer_matches_once_per_token_never_scans(text, monkeypatch):
    counting = _CountingPattern(reading._TOKEN)
    monkeypatch.setattr(reading, "_TOKEN", counting)
    with pytest.raises(EquationError):
        parse_polynomial(text, ("x",), max_degree=1)
    # every match starts where the previous token ended: strictly increasing, and at most
    # one try per token (each token is at least one character long)
    assert counting.starts == sorted(set(counting.starts))
    assert len(counting.starts) <= len(text) // 2 + 2


def test_the_tokenizer_still_reads_what_it_read():
    assert parse_number(" \t1_000.5e-1 \n") == parse_number("100.05")
    assert parse_polynomial("  x**2 +\t3*x\r\n", ("x",)) == {(2,): 1, (1,): 3}
    with pytest.raises(NotANumberError, match="malformed number '1111111111e'"):
        parse_number("1" * 10 + "e")


# -- output: every accepted number prints and serialises -----------------------------------


def _big_pair(digits: int, seed: int = 2) -> tuple[Any, Any]:
    """An ellipsoid and a hyperboloid whose entries are fractions of ``digits``-digit
    integers (accepted: within MAX_DIGITS), so that P's coefficients exceed
    Python's 4300-digit limit on int -> str."""
    import random
    from fractions import Fraction

    from quadric_contact import Quadric

    rng = random.Random(seed)

    def entry() -> Fraction:
        return Fraction(
            rng.randrange(10 ** (digits - 1), 10**digits), rng.randrange(10 ** (digits - 1), 10**digits)
        )

    def matrix(diagonal: tuple[int, ...]) -> list[list[Fraction]]:
        M = [[entry() / 1000 for _ in range(4)] for _ in range(4)]
        for i in range(4):
            for j in range(i):
                M[i][j] = M[j][i]
            M[i][i] += diagonal[i]
        return M

    return Quadric(matrix((1, 1, 1, -1))), Quadric(matrix((1, 1, -1, -1)))


def _read_back(text: Any) -> Fraction:
    """A JSON exact value read back without Python's int <- str limit."""
    import flint

    p, _, q = str(text).partition("/")
    return Fraction(int(flint.fmpz(p)), int(flint.fmpz(q or "1")))


def test_a_polynomial_and_a_region_of_huge_numbers_print_and_serialise():
    import json
    import sys

    from quadric_contact.exact.printing import fraction_text
    from quadric_contact.theory.pencil import characteristic_polynomial
    from quadric_contact.theory.regions import decide_region

    E, Q = _big_pair(490)
    P = characteristic_polynomial(E, Q)
    limit = sys.get_int_max_str_digits()
    assert limit and max(c.denominator.bit_length() for c in P.coefficients) > 3.33 * limit  # beyond it
    text = str(P)
    assert repr(P) == f"CharacteristicPolynomial({text})"
    assert fraction_text(P.coefficients[0]).split("/")[-1] in text
    region = decide_region(P, method="theory")
    assert "CharacteristicPolynomial(" in repr(region)
    data = json.loads(json.dumps(region.to_dict()))
    assert [_read_back(c) for c in data["coefficients"]] == list(P.coefficients)
    assert _read_back(data["delta4"]) == P.deltas()[2]


def test_the_polynomial_prints_text_that_reads_back_to_it():
    import random

    from quadric_contact.exact.reading import parse_univariate
    from quadric_contact.theory.pencil import CharacteristicPolynomial

    rng = random.Random(5)
    cases = [[Fraction(rng.randint(-3, 3), rng.choice([1, 1, 2, 3])) for _ in range(5)] for _ in range(200)]
    cases.append([Fraction(-(10**5000), 3), Fraction(1, 10**4400), Fraction(0), Fraction(0), Fraction(1)])
    for coefficients in cases:
        P = object.__new__(CharacteristicPolynomial)
        object.__setattr__(P, "coefficients", tuple(coefficients))
        text = str(P)
        if max(abs(c.numerator) for c in coefficients) < 10**100:
            back = parse_univariate(text, "lambda", max_degree=4)
            assert list(back) + [Fraction(0)] * (5 - len(back)) == coefficients, text
        else:
            assert text == "lambda**4 + lambda/1" + "0" * 4400 + " - 1" + "0" * 5000 + "/3", text[:40]


def test_check_prints_huge_numbers_plain_and_json(capsys):
    import json

    from quadric_contact.interfaces.cli import main

    E, Q = _big_pair(100, seed=3)
    e, q = E.equation(), Q.equation()
    assert len(e) < MAX_LENGTH and len(q) < MAX_LENGTH
    assert main(["check", e, q]) in (0, 3)
    assert "Delta4 = " in capsys.readouterr().out
    assert main(["check", "--json", e, q]) in (0, 3)
    data = json.loads(capsys.readouterr().out)
    assert len(data["contact"]["delta4"]) > 4300


# -- families: bounds estimated before building, names that cannot collide ----------------

EIGHT_FACTORS = "*".join(f"({p}+{k})" for p, k in zip("abcdefgh", range(2, 10), strict=True))
FOUR_PARAMETER_HEAVY = (
    "x^2+y^2+z^2-1",
    "(a+2)*(b+3)*(c+4)*(d+5)*x^2 + (a+3)*(b+4)*(c+5)*(d+6)*y^2 - (a+4)*(b+5)*(c+6)*(d+7)*z^2"
    " - (a+5)*(b+6)*(c+7)*(d+8)",
    "a b c d",
)


def test_too_many_parameters_are_refused_before_anything_is_read():
    from quadric_contact.exact.bounds import MAX_PARAMETERS
    from quadric_contact.families.family import family

    with pytest.raises(EquationError, match="MAX_PARAMETERS"):
        family("x^2+y^2+z^2-1", f"{EIGHT_FACTORS}*x^2 + y^2 - z^2 - 1", "a b c d e f g h")
    assert MAX_PARAMETERS < 8


def test_the_eight_factor_family_no_longer_aborts_the_interpreter():
    import subprocess
    import sys

    code = (
        "from quadric_contact.families.family import family\n"
        "from quadric_contact.exact.errors import QuadricContactError\n"
        "try:\n"
        f"    fam = family('x^2+y^2+z^2-1', '{EIGHT_FACTORS}*x^2 + y^2 - z^2 - 1', 'a b c d e f g h')\n"
        "    fam.coefficients, fam.deltas\n"
        "except QuadricContactError as exc:\n"
        "    print('refused:', type(exc).__name__)\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=300, env=_env_with_src()
    )
    assert done.returncode == 0, done.stderr[-2000:]
    assert "refused: EquationError" in done.stdout


def test_a_family_whose_discriminant_is_too_large_is_refused_before_it_is_built(monkeypatch):
    import flint

    from quadric_contact.exact.bounds import MAX_FAMILY_WORK_PRODUCTS
    from quadric_contact.exact.errors import WorkLimitError
    from quadric_contact.families import family_budget
    from quadric_contact.families.family import family

    fam = family(*FOUR_PARAMETER_HEAVY)
    built: list[int] = []
    real = family_budget.CountedPolynomial.__mul__

    def watch(self: Any, other: Any) -> Any:
        out = real(self, other)
        built.append(len(out.p) if isinstance(out.p, flint.fmpq_mpoly) else 1)
        return out

    monkeypatch.setattr(family_budget.CountedPolynomial, "__mul__", watch)
    with pytest.raises(WorkLimitError, match="MAX_FAMILY") as info:
        _ = fam.deltas
    assert info.value.details["needed"] > info.value.details["limit"]
    assert "a, b, c, d" in str(info.value)  # names the family
    # nothing was built beyond what the budget allows, charged before each product
    assert built and max(built) <= MAX_FAMILY_WORK_PRODUCTS


def test_a_moderate_family_is_answered_and_its_discriminant_is_exact():
    import sympy

    from quadric_contact.families.family import family

    fam = family("(x - u)^2 + v*(y - w)^2 + 3*(z - s)^2 - 1", "x**2 + y**2 - u*(z-3)**2 - v", "u v w s")
    point = {"u": Fraction(1, 2), "v": Fraction(2), "w": Fraction(1, 3), "s": Fraction(-1)}
    d4 = fam.deltas[2].subs(
        {sympy.Symbol(k): sympy.Rational(v.numerator, v.denominator) for k, v in point.items()}
    )
    from quadric_contact.exact.discriminants import paper_deltas
    from quadric_contact.theory.pencil import characteristic_polynomial

    E, Q = fam.at(**point)
    P = characteristic_polynomial(E, Q)
    assert sympy.Rational(d4) == sympy.Rational(*paper_deltas(P.coefficients)[2].as_integer_ratio())


def test_the_reference_point_search_is_bounded(monkeypatch):
    from quadric_contact.exact.bounds import MAX_REFERENCE_POINTS
    from quadric_contact.exact.errors import NotAnEllipsoidError
    from quadric_contact.families.family import Family, family

    tried = []
    real = Family._not_an_ellipsoid

    def count(self: Any, point: Any) -> str:
        tried.append(point)
        return real(self, point)

    monkeypatch.setattr(Family, "_not_an_ellipsoid", count)
    with pytest.raises(NotAnEllipsoidError, match="MAX_REFERENCE_POINTS"):
        family("x^2 + y^2 + z^2 + 1 + (u*v*w*s)^2", "z", "u v w s")  # never real
    assert len(tried) == MAX_REFERENCE_POINTS


@pytest.mark.parametrize(
    ("name", "why"),
    [
        ("lambda", "characteristic polynomial"),
        ("t", "smallness"),
        ("class", "keyword"),
        ("match", "keyword"),
        ("at", "attribute"),
        ("E", "attribute"),
        ("reference", "attribute"),
        ("name", "keyword argument"),
        ("refine", "keyword argument"),
        ("resolution", "keyword argument"),
    ],
)
def test_parameter_names_that_would_collide_are_refused(name, why):
    from quadric_contact.families.family import family

    with pytest.raises(EquationError, match=why):
        family(f"(x - {name})^2 + y^2 + z^2 - 1", "z", name)


def test_every_public_attribute_of_a_family_is_a_refused_name():
    from quadric_contact.families.family import _reserved_names, family

    fam = family("(x - u)^2 + y^2 + z^2 - 1", "z", "u")
    public = {n for n in (*vars(fam), *dir(fam)) if not n.startswith("_")}
    assert public <= set(_reserved_names())


def test_the_pencil_symbol_cannot_be_a_parameter():
    import sympy

    from quadric_contact.families.family import family

    fam = family("(x - u)^2 + y^2 + z^2 - 1", "x^2 + y^2 - z^2 - 1", "u")
    lam = sympy.Symbol("mu")
    assert sympy.Poly(fam.characteristic_polynomial("mu"), lam).degree() == 4
    for bad in ("u", "x", "1u", "a b"):
        with pytest.raises(EquationError, match="symbol"):
            fam.characteristic_polynomial(bad)


def test_an_unknown_quantity_or_backend_lists_the_valid_ones():
    from quadric_contact.exact.errors import ChoiceError
    from quadric_contact.families.family import family

    fam = family("(x - u)^2 + y^2 + z^2 - 1", "x^2 + y^2 - z^2 - 1", "u")
    with pytest.raises(ChoiceError, match="Delta4") as info:
        fam.quantity("Delta5")
    assert "Delta4" in info.value.details["choices"]
    with pytest.raises(ChoiceError, match="numpy"):
        fam.lambdify("Delta4", backend="fortran")


# -- motions: the degree bound holds for coefficient lists too -----------------------------


def _drone_scene(translation: str, quaternion: str) -> str:
    from pathlib import Path

    import quadric_contact.scenes as scenes

    text = (Path(scenes.__file__).parent / "drone_cooling_tower.toml").read_text()
    text = re.sub(r"(?m)^translation = .*$", f"translation = {translation}", text)
    return re.sub(r"(?m)^quaternion = .*$", f"quaternion = {quaternion}", text)


@pytest.mark.parametrize(
    ("translation", "quaternion"),
    [
        ("[[" + "0, " * 200 + "1], [0], [0]]", "[[4], [0], [0], [0, 1]]"),
        ("[[0, 8], [0], [0, 30, -2.5]]", "[[4], [0], [0], [" + "0, " * 100 + "1]]"),
        ('["t**9", "0", "0"]', "[[4], [0], [0], [0, 1]]"),
    ],
    ids=["translation of degree 200", "quaternion of degree 100", "text of degree 9"],
)
def test_a_motion_above_the_degree_bound_is_refused_before_it_is_read(translation, quaternion, monkeypatch):
    from quadric_contact.exact import rational
    from quadric_contact.exact.errors import SceneError
    from quadric_contact.scenes.scene_toml import parse_scene

    calls = []
    real = rational.to_fraction
    monkeypatch.setattr(rational, "to_fraction", lambda v: calls.append(v) or real(v))
    with pytest.raises(SceneError, match="MAX_MOTION_DEGREE"):
        parse_scene(_drone_scene(translation, quaternion))
    assert len(calls) < 50  # the long list was never read entry by entry


def test_a_motion_at_the_degree_bound_is_read():
    from quadric_contact.exact.bounds import MAX_MOTION_DEGREE
    from quadric_contact.scenes.trajectory import PolynomialMotion

    top = [0] * MAX_MOTION_DEGREE + [Fraction(1, 10**9)]
    m = PolynomialMotion((top, [0], "t**8"), quaternion=([4], [0], [0], top))
    assert len(m.translation[0]) == len(m.quaternion[3]) == MAX_MOTION_DEGREE + 1
    with pytest.raises(Exception, match="MAX_MOTION_DEGREE"):
        PolynomialMotion(([0] * (MAX_MOTION_DEGREE + 1) + [1], [0], [0]))
    with pytest.raises(Exception, match="MAX_MOTION_DEGREE"):
        PolynomialMotion(((0 for _ in iter(int, 1)), [0], [0]))  # an endless generator: cut, not read


# -- scene files: regular files of bounded size, bounded nesting -----------------------------


@pytest.mark.parametrize("special", ["/dev/zero", "fifo", "directory"])
def test_a_scene_path_that_is_not_a_regular_file_is_refused_unread(special, tmp_path):
    import os

    from quadric_contact.exact.errors import SceneError
    from quadric_contact.scenes.scene_toml import load_scene

    if special == "fifo":
        path = tmp_path / "scene.toml"
        os.mkfifo(path)  # no writer: opening it for reading would block
    elif special == "directory":
        path = tmp_path
    else:
        path = special
    with pytest.raises(SceneError, match="not a regular file"):
        load_scene(path)


def test_a_scene_file_beyond_the_size_bound_is_refused(tmp_path):
    from quadric_contact.exact.bounds import MAX_SCENE_BYTES
    from quadric_contact.exact.errors import SceneError
    from quadric_contact.scenes.scene_toml import load_scene, parse_scene

    path = tmp_path / "big.toml"
    path.write_text("# " + "x" * MAX_SCENE_BYTES + "\n")
    with pytest.raises(SceneError, match="MAX_SCENE_BYTES"):
        load_scene(path)
    with pytest.raises(SceneError, match="MAX_SCENE_BYTES"):
        parse_scene(path.read_text())


@pytest.mark.parametrize("opening", ["[", "{a = ", "[\n"])
def test_deep_nesting_in_a_scene_is_a_scene_error(opening):
    from quadric_contact.exact.errors import SceneError
    from quadric_contact.scenes.scene_toml import parse_scene

    closing = {"[": "]", "{a = ": "}", "[\n": "]\n"}[opening]
    text = "[scene]\nname = 'deep'\ntime = [0, 1]\nx = " + opening * 600 + "1" + closing * 600 + "\n"
    with pytest.raises(SceneError, match="MAX_SCENE_DEPTH"):
        parse_scene(text)


def test_strings_and_comments_do_not_count_as_nesting():
    from quadric_contact.scenes.scene_toml import _nesting_depth

    assert (
        _nesting_depth("a = '[[[['\nb = \"\\\"[[[\"\nc = '''\n[[[\n'''\n# [[[[[[\n[[d]]\ne = [[1], [2]]\n")
        == 2
    )


def test_places_are_bounded_in_scenes():
    from quadric_contact.exact.bounds import MAX_PLACES
    from quadric_contact.exact.errors import SceneError
    from quadric_contact.scenes.scene_toml import parse_scene

    text = _drone_scene("[[0, 8], [0], [0, 30, -2.5]]", "[[4], [0], [0], [0, 1]]")
    parse_scene(re.sub(r"(?m)^places = .*$", f"places = {MAX_PLACES}", text), check_smallness=False)
    with pytest.raises(SceneError, match="MAX_PLACES"):
        parse_scene(re.sub(r"(?m)^places = .*$", f"places = {MAX_PLACES + 1}", text), check_smallness=False)


# -- the command line: numbers through the reader, paths and addresses checked first -------


def _cli(args: list[str], capsys: Any) -> tuple[int, str, str]:
    from quadric_contact.interfaces.cli import main

    try:
        status = main(args)
    except SystemExit as exc:  # argparse refuses an option
        status = int(exc.code or 0)
    out = capsys.readouterr()
    return status, out.out, out.err


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["sweep", "--serial", "-n", "1", "--amplitude", "1e100000"], "MAX_DIGITS"),
        (["sweep", "--serial", "-n", "1", "--amplitude", "1e-10000000"], "MAX_DIGITS"),
        (["sweep", "--serial", "-n", "1", "--amplitude", "\uff11/20"], "ASCII digits"),
        (["sweep", "--serial", "-n", "1", "--amplitude", "10**100"], "[0, 1000]"),
        (["sweep", "--serial", "-n", "1", "--places", "1000"], "[0, 100]"),
        (["sweep", "--serial", "-n", "\uff11"], "ASCII digits"),
        (["sweep", "--serial", "-n", "1e30"], "[1, 10000000]"),
        (["simulate", "--places", "101", "bee_and_tree"], "[0, 100]"),
        (["simulate", "--frames", "10**9", "bee_and_tree"], "[2, 1000]"),
        (["simulate", "--bodies", "1/2", "many_bodies"], "integer"),
    ],
)
def test_command_line_numbers_are_read_by_the_package_and_bounded(args, message, capsys):
    status, _, err = _cli(args, capsys)
    assert status == 2 and message in err, err


@pytest.mark.parametrize(
    "address", ["file:///etc/passwd", "__import__('os').system('x')", "tcp://h:99999", "h"]
)
def test_a_malformed_scheduler_address_is_refused_before_anything(address, capsys, monkeypatch):
    import quadric_contact.interfaces.cli.sweep as sweep_command

    monkeypatch.setattr(sweep_command, "read_scene_file", lambda *a: pytest.fail("the scene was read"))
    status, _, err = _cli(["sweep", "--scheduler", address, "-n", "1"], capsys)
    assert status == 2 and "is not a scheduler address" in err, err


def test_an_unreachable_scheduler_is_a_clear_error_after_the_timeout(monkeypatch):
    pytest.importorskip("dask.distributed")
    from quadric_contact.exact.errors import SchedulerError
    from quadric_contact.scenes import sweep

    monkeypatch.setattr(sweep, "SCHEDULER_TIMEOUT", 0.5)
    with pytest.raises(SchedulerError, match="cannot connect") as info:
        sweep.run_sweep(
            sweep.parse_scene.__globals__["builtin_scene"]
            .__globals__["resources"]
            .files("quadric_contact")
            .joinpath("scenes", "bee_and_tree.toml")
            .read_text(),
            "bee",
            1,
            scheduler="tcp://127.0.0.1:1",
        )
    assert isinstance(info.value, ConnectionError)


@pytest.mark.parametrize("command", ["simulate", "sweep"])
def test_an_output_path_that_is_a_directory_is_refused_before_the_run(command, tmp_path, capsys, monkeypatch):
    import quadric_contact.interfaces.cli.simulate as simulate_command
    import quadric_contact.interfaces.cli.sweep as sweep_command

    monkeypatch.setattr(simulate_command, "simulate", lambda *a, **k: pytest.fail("the run started"))
    monkeypatch.setattr(sweep_command, "run_sweep", lambda *a, **k: pytest.fail("the run started"))
    extra = ["--serial", "-n", "1"] if command == "sweep" else []
    status, _, err = _cli([command, *extra, "-o", str(tmp_path), "bee_and_tree"], capsys)
    assert status == 2 and "is a directory" in err, err


def test_a_broken_pipe_exits_quietly():
    import subprocess
    import sys

    code = (
        "import sys\n"
        "from quadric_contact.interfaces.cli import main\n"
        "sys.stdout.close = lambda: None\n"
        "import os; r, w = os.pipe(); os.close(r); os.dup2(w, 1)\n"
        "sys.exit(main(['simulate', '--list']))\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=300, env=_env_with_src()
    )
    assert "Traceback" not in done.stderr and "BrokenPipeError" not in done.stderr, done.stderr
    assert done.returncode == 1


def test_unknown_mode_and_backend_are_the_package_s_errors_listing_the_choices():
    import quadric_contact as qc
    from quadric_contact.exact.errors import ChoiceError
    from quadric_contact.modes import get_mode

    with pytest.raises(ChoiceError, match="certified") as info:
        qc.transversal_contact("x^2+y^2+z^2-1", "z", mode="nope")
    assert "exact" in info.value.details["choices"]
    with pytest.raises(ChoiceError):
        get_mode(["unhashable"])  # type: ignore[arg-type]
    with pytest.raises(ChoiceError, match="numba"):
        get_mode("float", backend="fortran")


# -- boundary objects become plain exact values, under the same bounds -----------------------


class _LyingStr(str):
    def __len__(self) -> int:
        return 1


class _AlwaysLess(Fraction):
    def __lt__(self, other: Any) -> bool:
        return True

    def __gt__(self, other: Any) -> bool:
        return True


class _LyingFloat(float):
    def as_integer_ratio(self) -> tuple[int, int]:
        return (1, 3)


class _LyingInt(int):
    def __int__(self) -> int:
        return 7

    @property
    def numerator(self) -> int:  # type: ignore[override]
        return 7


def test_subclasses_of_builtin_numbers_become_plain_values():
    from quadric_contact.exact.rational import to_fraction

    for value, expected in [
        (_AlwaysLess(1, 2), Fraction(1, 2)),
        (_LyingFloat(0.5), Fraction(1, 2)),
        (_LyingInt(5), Fraction(5)),
        (_LyingStr("1/3"), Fraction(1, 3)),
    ]:
        got = to_fraction(value)
        assert type(got) is Fraction and got == expected
        assert type(got.numerator) is int and type(got.denominator) is int


def test_a_fraction_subclass_does_not_drive_classification():
    from quadric_contact import Quadric

    M = [[_AlwaysLess(v) for v in row] for row in ([1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, -1])]
    q = Quadric(M)
    assert all(type(v) is Fraction for row in q.matrix for v in row)
    assert q.kind.value == Quadric.from_equation("x^2+y^2+z^2-1").kind.value


def test_a_lying_str_does_not_bypass_the_length_bound():
    from quadric_contact import Quadric

    with pytest.raises(EquationError, match="MAX_LENGTH"):
        Quadric.from_equation(_LyingStr("x^2 + " + "0*x + " * 1000 + "y^2 + z^2 - 1"))
    with pytest.raises(NotANumberError, match="MAX_LENGTH"):
        parse_number(_LyingStr("1" * (MAX_LENGTH + 1)))


@pytest.mark.parametrize(
    "value",
    [
        "Decimal('1e10000000')",
        "Decimal('1e-10000000')",
        "Decimal('1' * 1001)",
        "10**1000",
        "Fraction(1, 10**1000)",
    ],
)
def test_numbers_given_as_objects_respect_the_digit_bound(value):
    from decimal import Decimal

    from quadric_contact.exact.rational import to_fraction

    number = {
        "Decimal('1e10000000')": lambda: Decimal("1e10000000"),
        "Decimal('1e-10000000')": lambda: Decimal("1e-10000000"),
        "Decimal('1' * 1001)": lambda: Decimal("1" * 1001),
        "10**1000": lambda: 10**1000,
        "Fraction(1, 10**1000)": lambda: Fraction(1, 10**1000),
    }[value]()
    with pytest.raises(NotANumberError, match="MAX_DIGITS"):
        to_fraction(number)
    assert to_fraction(Decimal("1e999")) == 10**999


# -- names in reports ------------------------------------------------------------------------


FORGED = ["bee\x1b[2J", "bee\r\n  first contact: t = 0", "bee\u202egnihton", "bee\u2066x\u2069", "bee\x00"]


@pytest.mark.parametrize("name", FORGED, ids=repr)
def test_a_scene_name_with_unsafe_characters_is_refused_when_read(name):
    import json

    from quadric_contact.exact.errors import SceneError
    from quadric_contact.scenes.scene_toml import parse_scene

    text = _drone_scene("[[0, 8], [0], [0, 30, -2.5]]", "[[4], [0], [0], [0, 1]]")
    text = text.replace('name = "drone"', f"name = {json.dumps(name)}")
    with pytest.raises(SceneError, match="control or format"):
        parse_scene(text, check_smallness=False)


def test_names_given_through_the_api_are_escaped_in_the_report():
    from dataclasses import replace

    from quadric_contact.exact.printing import unsafe_characters
    from quadric_contact.scenes.scene_toml import builtin_scene
    from quadric_contact.scenes.simulate import simulate

    scene = builtin_scene("bee_and_tree", check_smallness=False)
    forged = "bee\x1b[2J\r\n  first contact: t = 0\u202e"
    bee = replace(scene.ellipsoids[0], name=forged)
    scene = replace(scene, ellipsoids=(bee, *scene.ellipsoids[1:]))
    text = simulate(scene, effects=["first_contact"]).format_text()
    assert not [c for c in unsafe_characters(text) if c != "\n"]
    assert "\n  first contact: t = 0" not in text.replace("\\n  first contact: t = 0", "")


# -- the exact engine: a size bound before the work ------------------------------------------


def test_a_pair_beyond_the_size_bound_is_refused_before_the_geometric_work(monkeypatch):
    from quadric_contact.exact.bounds import MAX_PAIR_BITS
    from quadric_contact.exact.errors import WorkLimitError
    from quadric_contact.exact.size import pair_bits
    from quadric_contact.theory import geometric

    E, Q = _big_pair(490)
    assert pair_bits(E, Q) > MAX_PAIR_BITS
    monkeypatch.setattr(geometric, "_setup", lambda *a: pytest.fail("the work started"))
    with pytest.raises(WorkLimitError, match="MAX_PAIR_BITS") as info:
        geometric.decide_geometrically(E, Q)
    assert "E: " in str(info.value) and "Q: " in str(info.value)  # names the pair
    assert info.value.details["needed"] == pair_bits(E, Q)


def test_pair_bits_counts_a_common_denominator_and_the_largest_numerator():
    from quadric_contact import Quadric
    from quadric_contact.exact.size import matrix_bits, pair_bits

    assert matrix_bits([Fraction(1, 2), Fraction(3, 4), Fraction(-5)]) == 2 + (20).bit_length()
    E = Quadric.from_equation("x^2 + y^2 + z^2 - 1")
    assert pair_bits(E, E) == 2 * matrix_bits(E.upper)
    small = Quadric.from_equation("(x - 0.1)^2 + y^2/3 + 3*(z - 5.5)^2 - 0.1")
    from quadric_contact.exact.bounds import MAX_PAIR_BITS
    from quadric_contact.theory.geometric import decide_geometrically

    assert pair_bits(small, Quadric.from_equation("x^2 + y^2 - z^2/4 - 1")) < MAX_PAIR_BITS
    decide_geometrically(small, "x^2 + y^2 - z^2/4 - 1")  # answered
