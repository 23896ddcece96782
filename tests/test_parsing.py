"""The package's parser (``quadric_contact.exact.reading``, and the reader of a quadric's
equation, ``quadric_contact.model.parsing``): exact values, refusals that
name the offending text and its position, every documented bound at its edge, an
algebra of sympy objects for parametric families, and hypothesis properties
(random well-formed expressions against an independent polynomial arithmetic,
printed quadrics read back, fuzzing)."""

from __future__ import annotations

import contextlib
import sys
from collections.abc import Callable
from decimal import Decimal
from fractions import Fraction
from typing import Any

import pytest
import sympy
from hypothesis import given, settings
from hypothesis import strategies as st
from tests.untrusted import untrusted

from quadric_contact import Quadric
from quadric_contact.exact.errors import EquationError, NonFiniteError, NotANumberError, QuadricContactError
from quadric_contact.exact.rational import to_fraction
from quadric_contact.exact.reading import (
    MAX_DEGREE,
    MAX_DEPTH,
    MAX_DIGITS,
    MAX_EXPONENT,
    MAX_LENGTH,
    MAX_WORK,
    Equation,
    Name,
    PolynomialAlgebra,
    Refusal,
    evaluate,
    parse_expression,
    parse_number,
    parse_polynomial,
    parse_univariate,
)
from quadric_contact.model.parsing import parse_quadric_equation
from quadric_contact.testing.strategies import quadrics, rationals

XYZ = ("x", "y", "z")

# -- an independent polynomial arithmetic, the oracle ---------------------------------------

Poly = dict[tuple[int, int, int], Fraction]


def p_const(c: Fraction) -> Poly:
    return {(0, 0, 0): Fraction(c)} if c else {}


def p_var(i: int) -> Poly:
    e = [0, 0, 0]
    e[i] = 1
    return {(e[0], e[1], e[2]): Fraction(1)}


def p_add(a: Poly, b: Poly, sign: int = 1) -> Poly:
    out = dict(a)
    for k, v in b.items():
        out[k] = out.get(k, Fraction(0)) + sign * v
    return {k: v for k, v in out.items() if v}


def p_mul(a: Poly, b: Poly) -> Poly:
    out: Poly = {}
    for ka, va in a.items():
        for kb, vb in b.items():
            k = (ka[0] + kb[0], ka[1] + kb[1], ka[2] + kb[2])
            out[k] = out.get(k, Fraction(0)) + va * vb
    return {k: v for k, v in out.items() if v}


def p_pow(a: Poly, n: int) -> Poly:
    out = p_const(Fraction(1))
    for _ in range(n):
        out = p_mul(out, a)
    return out


def p_degree(a: Poly) -> int:
    return max((sum(k) for k in a), default=0)


def matrix_of(p: Poly) -> tuple[Fraction, ...]:
    """The ten upper entries of the quadric of ``p`` (eq. (6)), built from the monomials."""

    def c(*e: int) -> Fraction:
        return p.get((e[0], e[1], e[2]), Fraction(0))

    half = Fraction(1, 2)
    return (
        c(2, 0, 0),
        c(1, 1, 0) * half,
        c(1, 0, 1) * half,
        c(1, 0, 0) * half,
        c(0, 2, 0),
        c(0, 1, 1) * half,
        c(0, 1, 0) * half,
        c(0, 0, 2),
        c(0, 0, 1) * half,
        c(0, 0, 0),
    )


# -- random well-formed expressions, printed with Python's precedence ------------------------

ATOM, POWER, UNARY, PRODUCT, SUM = 4, 3, 2, 1, 0  # precedence levels of the printed text


@st.composite
def numbers(draw: Any) -> tuple[str, Fraction]:
    """A non-negative literal in one of the accepted spellings, with its exact value."""
    form = draw(st.sampled_from(["int", "decimal", "sci", "frac", "underscore"]))
    m = draw(st.integers(0, 10**6))
    if form == "int":
        return str(m), Fraction(m)
    if form == "decimal":
        k = draw(st.integers(1, 6))
        return format(Decimal(m).scaleb(-k), "f"), Fraction(m, 10**k)
    if form == "sci":
        e = draw(st.integers(-8, 8))
        mark = draw(st.sampled_from(["e", "E", "e+"])) if e >= 0 else draw(st.sampled_from(["e", "E"]))
        return f"{m}{mark}{e}", Fraction(m) * Fraction(10) ** e
    if form == "underscore":
        return f"{m:_}", Fraction(m)
    q = draw(st.integers(1, 10**4))
    return f"({m}/{q})", Fraction(m, q)


def wrap(item: tuple[str, Poly, int, int], level: int, spaces: str) -> str:
    text, _, prec, _ = item
    return text if prec >= level else f"({spaces}{text}{spaces})"


@st.composite
def expressions(draw: Any, depth: int = 3, max_degree: int = 4) -> tuple[str, Poly, int, int]:
    """``(text, value, precedence, degree bound)``; every intermediate degree stays
    <= ``max_degree`` (the parser's own bound is larger)."""
    sp = draw(st.sampled_from(["", " ", "  "]))
    power = draw(st.sampled_from(["**", "^"]))
    kind = draw(st.sampled_from(["num", "var"] + (["add", "mul", "div", "neg", "pow"] * 2 if depth else [])))
    if kind == "num":
        text, value = draw(numbers())
        return text, p_const(value), ATOM, 0
    if kind == "var":
        i = draw(st.integers(0, 2))
        return XYZ[i], p_var(i), ATOM, 1
    a = draw(expressions(depth - 1, max_degree))
    if kind == "neg":
        return f"-{sp}{wrap(a, UNARY, sp)}", p_mul(p_const(Fraction(-1)), a[1]), UNARY, a[3]
    if kind == "pow":
        n = draw(st.integers(0, max(0, max_degree // max(a[3], 1))))
        return f"{wrap(a, ATOM, sp)}{sp}{power}{sp}{n}", p_pow(a[1], n), POWER, a[3] * n
    if kind == "div":
        text, value = draw(numbers().filter(lambda t: t[1] != 0))
        return f"{wrap(a, PRODUCT, sp)}{sp}/{sp}{text}", p_mul(a[1], p_const(1 / value)), PRODUCT, a[3]
    b = draw(expressions(depth - 1, max_degree))
    if kind == "mul":
        if a[3] + b[3] > max_degree:
            return a
        return f"{wrap(a, PRODUCT, sp)}{sp}*{sp}{wrap(b, UNARY, sp)}", p_mul(a[1], b[1]), PRODUCT, a[3] + b[3]
    op = draw(st.sampled_from(["+", "-"]))
    value = p_add(a[1], b[1], 1 if op == "+" else -1)
    return f"{a[0]}{sp}{op}{sp}{wrap(b, PRODUCT, sp)}", value, SUM, max(a[3], b[3])


@given(expressions())
def test_random_expressions_read_exactly(item):
    text, value, _, _ = item
    assert parse_polynomial(text, XYZ, max_degree=4) == value
    if p_degree(value) <= 2:
        assert Quadric.from_equation(text).upper == matrix_of(value)
    else:
        with pytest.raises(EquationError, match="after expansion"):
            Quadric.from_equation(text)


@given(expressions(depth=2, max_degree=2), expressions(depth=2, max_degree=2))
def test_random_equations_are_lhs_minus_rhs(lhs, rhs):
    value = p_add(lhs[1], rhs[1], -1)
    assert parse_quadric_equation(f"{lhs[0]} = {rhs[0]}") == matrix_of(value)


# -- printed quadrics read back ------------------------------------------------------------


@given(quadrics())
def test_printed_quadrics_read_back(q):
    assert Quadric.from_equation(q.equation()) == q
    assert Quadric.from_equation(q.equation().replace("**", "^")) == q


MONOMIALS = [
    (2, 0, 0),
    (1, 1, 0),
    (1, 0, 1),
    (1, 0, 0),
    (0, 2, 0),
    (0, 1, 1),
    (0, 1, 0),
    (0, 0, 2),
    (0, 0, 1),
]
MONOMIALS.append((0, 0, 0))


@st.composite
def printed_polynomials(draw: Any) -> tuple[str, Poly]:
    """A random quadratic written term by term, in random order and spelling."""
    coefficient = rationals(min_value=-(10**6), max_value=10**6, max_denominator=10**6)
    terms = []
    value: Poly = {}
    for e in MONOMIALS:
        c = draw(coefficient)
        if c == 0:
            continue
        value[e] = c
        factors = [str(abs(c.numerator))] if abs(c) != 1 or e == (0, 0, 0) else []
        for v, k in zip(XYZ, e, strict=True):
            if k:
                factors.append(v if k == 1 else f"{v}{draw(st.sampled_from(['**', '^']))}{k}")
        body = "*".join(factors)
        if c.denominator != 1:
            body += f"/{c.denominator}"
        terms.append(("-" if c < 0 else "+", body))
    if not terms:
        return "0", {}
    order = draw(st.permutations(terms))
    text = " ".join(f"{s} {b}" for s, b in order)
    return text.removeprefix("+ "), value


@given(printed_polynomials())
def test_random_quadratics_printed_and_read_give_the_same_matrix(item):
    text, value = item
    assert parse_quadric_equation(text) == matrix_of(value)
    q = Quadric.from_equation(text)
    assert Quadric.from_equation(q.equation()) == q


# -- numbers --------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "text",
    ["0", "007", "8.36291", "-8.36291", "+.5", "5.", "1e-5", "1E5", "2.5e+3", "1_000.5", " -1/3 ", "12e0"],
)
def test_number_literals_are_the_decimals_they_spell(text):
    assert parse_number(text) == Fraction(text.strip()) == to_fraction(text)


@pytest.mark.parametrize(
    "text, expected",
    [
        ("1/3 + 2/7", Fraction(1, 3) + Fraction(2, 7)),
        ("(2/3)**3", Fraction(2, 3) ** 3),
        ("1/2**3", 1 / Fraction(2) ** 3),
        ("-2^2", -(Fraction(2) ** 2)),
        ("2*-3", Fraction(-6)),
        ("1/2/4", Fraction(1, 2) / 4),
        ("0**0", Fraction(1)),
        ("3 - 2 - 1", Fraction(0)),
    ],
)
def test_small_exact_number_expressions(text, expected):
    assert parse_number(text) == expected


@pytest.mark.parametrize("text", ["nan", "-inf", "Infinity", " +inf "])
def test_non_finite_words_are_non_finite(text):
    with pytest.raises(NonFiniteError):
        to_fraction(text)


@pytest.mark.parametrize("text", ["x", "2**-3", "sqrt(2)", "1/0", "1 = 1", "", "0x10", "1e", "--"])
def test_bad_numbers_raise_not_a_number(text):
    with pytest.raises(NotANumberError) as info:
        to_fraction(text)
    assert info.value.value is text


# -- refusals name the text and the position --------------------------------------------------

# (text, a fragment of the message, the offending substring, last occurrence?)
REFUSALS = [
    ("x2+y2+z2-1", "unknown name 'x2' at position 1 (did you mean 2*x or x**2?)", "x2", False),
    ("sin(x)", "function call sin(...)", "sin", False),
    ("x^2 + 3(z - 1)", "implicit multiplication", "(", True),
    ("x^2 + 3(z - 1)", "write 3*(z - 1)", "(", True),
    ("2x", "write 2*x", "x", False),
    ("(x)(y)", "write (x)*(y)", "(", True),
    ("x y", "write x*y", "y", False),
    ("x^2 y", "write x^2*y", "y", False),
    ("x**2 + 9**9**9", "a power of a power", "**", True),
    ("x**2 - 10**10**10", "a power of a power", "**", True),
    ("x**-1", "negative exponent", "-", False),
    ("x**y", "non-negative integer literal", "y", False),
    ("x**0.5", "non-negative integer literal", "0.5", False),
    ("1/x + y", "division by an expression in x, y, z", "x", False),
    ("x/(y - y)", "division by zero", "(y - y)", False),
    ("x**3 + y", "degree 3 after expansion", "x**3", False),
    ("x = y = z", "a second '='", "=", True),
    ("x == 1", "a single '='", "==", False),
    ("x**2 +", "expected a number, a name or '(' after '+'", "", False),
    ("x + (y", "never closed", "(", False),
    ("x + y)", "unmatched ')'", ")", False),
    ("x\x00 + 1", "control character U+0000", "\x00", False),
    ("x.real", "'.'", ".", False),
    ("().__class__", "'.'", ".", False),
    ("__import__('os')", "quotes", "'", False),
    ("1,5*x", "comma", ",", False),
    ("xy + 1", "did you mean x*y?", "xy", False),
    ("pi*x**2", "only rational numbers", "pi", False),
    ("x\u00b2", "write squares as **2", "\u00b2", False),
    ("x \u2212 y", "write the minus sign as '-'", "\u2212", False),
    ("x // 2", "'//'", "//", False),
    ("1.2.3*x", "malformed number '1.2.3'", "1.2.3", False),
    ("t**2", "unknown name 't'", "t", False),
    ("lambda: x", "the character ':'", ":", False),
    ("lambda + x", "unknown name 'lambda'", "lambda", False),
    ("[x for x in y]", "brackets", "[", False),
]


@pytest.mark.parametrize("text, fragment, offending, last", REFUSALS)
def test_refusals_name_the_text_and_its_position(text, fragment, offending, last):
    with pytest.raises(EquationError) as info:
        Quadric.from_equation(text)
    err = info.value
    message = str(err)
    assert fragment in message, message
    offset = (text.rindex(offending) if last else text.index(offending)) if offending else len(text)
    assert err.details["offset"] == offset, message
    assert err.details["position"] == offset + 1
    assert err.value is text
    if offending:
        # the snippet under the first line: the text, then a caret under the offending part
        shown, carets = message.splitlines()[1:3]
        column = carets.index("^")
        escaped = "".join(
            c if " " <= c <= "~" or c.isprintable() else f"\\u{ord(c):04x}" for c in text[:offset]
        )
        assert column == 4 + len(escaped), message
        assert shown[4:].startswith(escaped)


def test_power_accepts_caret_and_stars():
    assert parse_quadric_equation("x^2 + y^2 - z^2 = 1") == parse_quadric_equation("x**2 + y**2 - z**2 = 1")
    assert parse_quadric_equation("x^(2)") == parse_quadric_equation("x**+2")


def test_cancellation_beyond_degree_2_is_expanded_first():
    # the old reader's behaviour, kept: the degree is that of the expanded polynomial
    assert parse_quadric_equation("(x^2 + 1)^2 - x^4") == parse_quadric_equation("2*x^2 + 1")
    assert parse_quadric_equation("x**3 + y - x**3") == parse_quadric_equation("y")


# -- the bounds, each at its edge -----------------------------------------------------------


def refused(fn: Callable[[], Any], constant: str) -> str:
    with pytest.raises(QuadricContactError) as info:
        fn()
    assert constant in str(info.value), str(info.value)
    return str(info.value)


def test_bound_on_length():
    text = "x" + " " * (MAX_LENGTH - 1)
    assert parse_quadric_equation(text) == parse_quadric_equation("x")
    refused(lambda: parse_quadric_equation(text + " "), "MAX_LENGTH")
    refused(lambda: to_fraction("1" + " " * MAX_LENGTH), "MAX_LENGTH")


def test_bound_on_digits():
    nines = "9" * MAX_DIGITS
    assert parse_number(nines) == 10**MAX_DIGITS - 1
    assert parse_number("0" * 100 + nines) == 10**MAX_DIGITS - 1  # leading zeros are not digits
    refused(lambda: parse_number("9" + nines), "MAX_DIGITS")
    assert parse_number(f"1e-{MAX_DIGITS - 1}") == Fraction(1, 10 ** (MAX_DIGITS - 1))
    refused(lambda: parse_number(f"1e-{MAX_DIGITS}"), "MAX_DIGITS")
    refused(lambda: parse_number("1e99999999999999999999"), "MAX_DIGITS")
    # intermediate rationals too: a product, a power
    refused(lambda: parse_number(f"{nines} * {nines}"), "MAX_DIGITS")
    assert parse_number(f"10**{MAX_DIGITS - 1}") == 10 ** (MAX_DIGITS - 1)
    refused(lambda: parse_number(f"10**{MAX_DIGITS}"), "MAX_DIGITS")


def test_bound_on_exponent():
    assert parse_number(f"1**{MAX_EXPONENT}") == 1
    refused(lambda: parse_number(f"1**{MAX_EXPONENT + 1}"), "MAX_EXPONENT")
    refused(lambda: parse_number("1**" + "9" * 5000), "MAX_")


def test_bound_on_nesting():
    assert parse_number("(" * MAX_DEPTH + "1" + ")" * MAX_DEPTH) == 1
    refused(lambda: parse_number("(" * (MAX_DEPTH + 1) + "1" + ")" * (MAX_DEPTH + 1)), "MAX_DEPTH")
    assert parse_number("-" * MAX_DEPTH + "1") == (-1) ** MAX_DEPTH
    refused(lambda: parse_number("-" * (MAX_DEPTH + 1) + "1"), "MAX_DEPTH")
    refused(lambda: parse_number("(" * 100_000), "MAX_LENGTH")


def test_bound_on_intermediate_degree():
    top = f"(x^{MAX_DEGREE // 2})^2"
    assert parse_quadric_equation(f"{top} - x^{MAX_DEGREE} + y") == parse_quadric_equation("y")
    refused(lambda: parse_quadric_equation(f"x*{top}"), "MAX_DEGREE")
    refused(lambda: parse_quadric_equation(f"x^{MAX_DEGREE + 1}"), "MAX_DEGREE")


def test_bound_on_work():
    term = "(x + y + z + 1)^2*(x - y + z - 1)^2"
    # one term is cheap; enough of them exceed the budget, whatever the length allows
    alg = PolynomialAlgebra(XYZ)
    evaluate(parse_expression(term), alg)
    n = MAX_WORK // alg.work + 1
    assert len(" - ".join([term] * n)) < MAX_LENGTH
    refused(lambda: parse_quadric_equation(" - ".join([term] * n)), "MAX_WORK")


def test_polynomials_in_time():
    assert parse_univariate("3 - 2*t^2 + t/2") == (3, Fraction(1, 2), -2)
    assert parse_univariate("0") == (0,)
    assert parse_univariate(f"t^{MAX_DEGREE}")[-1] == 1
    refused(lambda: parse_univariate(f"t^{MAX_DEGREE + 1}"), "MAX_DEGREE")
    with pytest.raises(EquationError, match="unknown name 'x'"):
        parse_univariate("x + t")


# -- another algebra: sympy objects for families of quadrics -----------------------------------


class SympyAlgebra:
    """The same trees evaluated to sympy objects, built programmatically (no text
    is given to sympy): coefficients may contain parameters, and division is
    allowed by expressions in the parameters only."""

    def __init__(self, variables: tuple[str, ...], parameters: tuple[str, ...]) -> None:
        self.symbols = {n: sympy.Symbol(n) for n in (*variables, *parameters)}
        self.variables = {self.symbols[v] for v in variables}

    def constant(self, value: Fraction) -> Any:
        return sympy.Rational(value.numerator, value.denominator)

    def variable(self, name: str) -> Any:
        return self.symbols[name]

    def add(self, a: Any, b: Any) -> Any:
        return a + b

    def sub(self, a: Any, b: Any) -> Any:
        return a - b

    def neg(self, a: Any) -> Any:
        return -a

    def mul(self, a: Any, b: Any) -> Any:
        return a * b

    def div(self, a: Any, b: Any) -> Any:
        if b.free_symbols & self.variables:
            raise Refusal("division by an expression in the variables {where}")
        if sympy.expand(b) == 0:
            raise Refusal("division by zero {where}")
        return a / b

    def pow(self, a: Any, n: int) -> Any:
        return a**n


def test_the_same_tree_evaluates_to_a_parametric_family():
    text = "u*x^2 + y^2/(w + 1) - z/w = 1"
    tree = parse_expression(text, XYZ, parameters=("u", "w"), equation=True)
    assert isinstance(tree, Equation)
    names = {n.name: n.kind for n in _walk(tree) if isinstance(n, Name)}
    assert names == {"u": "parameter", "x": "variable", "y": "variable", "w": "parameter", "z": "variable"}
    got = evaluate(tree, SympyAlgebra(XYZ, ("u", "w")), text=text)
    x, y, z, u, w = sympy.symbols("x y z u w")
    assert sympy.simplify(got - (u * x**2 + y**2 / (w + 1) - z / w - 1)) == 0
    with pytest.raises(EquationError) as info:
        bad = "x/(u - x)"
        evaluate(parse_expression(bad, XYZ, parameters=("u",)), SympyAlgebra(XYZ, ("u",)), text=bad)
    assert info.value.details["offset"] == bad.index("(") and "in the variables" in str(info.value)
    with pytest.raises(EquationError, match="unknown name 'v'"):
        parse_expression("v*x", XYZ, parameters=("u",))


def _walk(node: Any):
    yield node
    for attr in ("operand", "base", "lhs", "rhs"):
        if hasattr(node, attr):
            yield from _walk(getattr(node, attr))
    for attr in ("terms", "factors"):
        for _, child in getattr(node, attr, ()):
            yield from _walk(child)


# -- fuzzing: always a quadric or the package's error -----------------------------------------

ALPHABET = "xyzt0123456789.eE_+-*/^()= \t\n,'\"[]{}:;!@#$%&|~`<>?\\\x00\x1b\u2212\u00b2\u00d7ｘ𝑥٣"
TOKENS = [
    "x", "y", "z", "t", "x2", "sin", "__import__", "lambda", "0", "1", "2", "10", "0.5", "1e3", "1e-3",
    "9999999999", "+", "-", "*", "/", "**", "^", "(", ")", "=", "==", "//", ".", ",", " ", "'", "[", "]",
]  # fmt: skip


def _read(text: str) -> None:
    """A quadric or the package's error, never anything else, with the audit hook
    armed (``tests/untrusted.py``: no program run, no code compiled, no file written)."""
    with untrusted():
        try:
            q = Quadric.from_equation(text)
        except EquationError:
            return
    assert isinstance(q, Quadric)


@settings(max_examples=300)
@given(st.text(alphabet=ALPHABET, max_size=120))
def test_fuzz_characters(text):
    _read(text)
    with untrusted(), contextlib.suppress(NotANumberError, NonFiniteError):
        assert isinstance(to_fraction(text), Fraction)


@settings(max_examples=300)
@given(st.lists(st.sampled_from(TOKENS), max_size=60))
def test_fuzz_tokens(tokens):
    _read("".join(tokens))
    _read(" ".join(tokens))


@given(st.text(max_size=200))
def test_fuzz_any_unicode(text):
    _read(text)


def test_work_stays_bounded_on_the_slowest_inputs():
    """A deterministic stand-in for the time bound: the Python calls made while
    reading the costliest inputs the bounds admit (``benchmarks/bench_parsing.py``
    times them)."""

    def fill(unit: str, tail: str) -> str:
        return unit * ((MAX_LENGTH - len(tail)) // len(unit)) + tail

    worst = [
        "(" * MAX_DEPTH + "x" + ")" * MAX_DEPTH,
        fill("1+", "1"),
        fill("x^2 + ", "1"),
        fill("(x + y + z + 1)^4*(x - y + z - 1)^4 - ", "1"),
        fill("3**600/7**400 + ", "1"),
        fill("7/", "7"),
        fill("-" * (MAX_DEPTH - 1) + "x*", "1"),
    ]
    calls = 0

    def count(frame: Any, event: str, arg: Any) -> None:
        nonlocal calls
        if event in ("call", "c_call"):
            calls += 1

    for text in worst:
        calls = 0
        sys.setprofile(count)
        try:
            parse_quadric_equation(text)
        except EquationError:
            pass
        finally:
            sys.setprofile(None)
        assert calls < 60 * MAX_LENGTH, (text[:40], calls)
