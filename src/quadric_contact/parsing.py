"""The package's own reader of equations and numbers: user text is data, never code.

Equations (``"x^2 + y^2 - 0.25*(z - 3)^2 = 1"``), numbers (``"8.36291"``,
``"1/3 + 2/7"``, ``"1e-5"``) and polynomial paths in time (``"3 - 2*t^2"``)
reach the package from users, courses and other programs: in
:meth:`~quadric_contact.Quadric.from_equation`, in every number a constructor
takes (:func:`~quadric_contact.rational.to_fraction`), on the command line and
in scene files.  They are read here by a tokenizer and a recursive-descent
parser into a small syntax tree, which :func:`evaluate` folds over an
:class:`Algebra`: exact sparse polynomials with :class:`fractions.Fraction`
coefficients (:class:`PolynomialAlgebra`) for quadrics, numbers and
trajectories, or any other algebra with the same eight operations (for
instance sympy objects built programmatically, for families of quadrics
whose coefficients contain declared parameters).  Nothing here calls
``eval``, ``exec``, ``compile``, ``sympify``, ``parse_expr`` or ``S()``.

Grammar
-------
Tokens may be separated by spaces, tabs and line breaks::

    input      = expression [ "=" expression ]     (one "=", where an equation is allowed)
    expression = term { ( "+" | "-" ) term }
    term       = factor { ( "*" | "/" ) factor }
    factor     = ( "+" | "-" ) factor | power
    power      = atom [ ( "**" | "^" ) exponent ]
    exponent   = [ "+" ] integer | "(" [ "+" ] integer ")"
    atom       = number | name | "(" expression ")"
    number     = digits [ "." [ digits ] ] [ scale ] | "." digits [ scale ]
    scale      = ( "e" | "E" ) [ "+" | "-" ] digits
    digits     = digit { [ "_" ] digit }                (ASCII digits)
    name       = a declared variable or parameter       (x, y, z; t in a path)

Precedence and associativity are Python's: ``-x**2`` is ``-(x**2)``,
``a/b*c`` is ``(a/b)*c``.  ``^`` is a power, as ``**`` (not Python's
exclusive or).  Numbers are exact: ``0.1`` is ``1/10``, ``1e-5`` is
``1/100000``, ``1/3`` is a third.

Refused, with an :class:`~quadric_contact.errors.EquationError` (or, for a
number, :class:`~quadric_contact.errors.NotANumberError`) whose message names
the offending text and its position and shows it under a caret: unknown
names (``x2``: "did you mean 2*x or x**2?"), function calls (``sin(x)``),
implicit multiplication (``3(z - 1)``, ``2x``, ``(x)(y)``, ``x y``: write
``*``), an exponent that is not a literal non-negative integer (``x**-1``,
``x**y``, ``x**0.5``), a power of a power without parentheses
(``9**9**9``), division by an expression in the variables, division by
zero, a degree above the one asked for after expansion, any character
outside the grammar (control characters, quotes, brackets, ``.`` after a
name, ``,``), and input beyond the bounds below.

Bounds
------
Every input is accepted or refused after a bounded amount of work; the
bounds are the module constants :data:`MAX_LENGTH` (characters),
:data:`MAX_DIGITS` (decimal digits of the numerator and of the denominator
of every literal and every intermediate rational), :data:`MAX_EXPONENT`,
:data:`MAX_DEPTH` (nesting of parentheses, signs and powers),
:data:`MAX_DEGREE` (degree of every intermediate polynomial) and
:data:`MAX_WORK` (arithmetic steps, weighted by the size of the numbers).
Measured on a laptop-class core, the slowest input that the bounds admit is
read or refused in a few tens of milliseconds
(``benchmarks/bench_parsing.py`` measures the hostile cases).
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any, Protocol, TypeVar

from .entries import ENTRY_INDICES
from .errors import EquationError, NotANumberError

__all__ = [
    "MAX_DEGREE",
    "MAX_DEPTH",
    "MAX_DIGITS",
    "MAX_EXPONENT",
    "MAX_LENGTH",
    "MAX_WORK",
    "Algebra",
    "Equation",
    "Expr",
    "Name",
    "Neg",
    "Number",
    "PolynomialAlgebra",
    "Power",
    "Product",
    "Refusal",
    "Sum",
    "evaluate",
    "parse_expression",
    "parse_number",
    "parse_polynomial",
    "parse_quadric_equation",
    "parse_univariate",
    "quadric_entries",
]

MAX_LENGTH = 10_000
"""Longest text read, in characters (a quadric's printed equation with
1000-digit coefficients fits)."""

MAX_DIGITS = 1_000
"""Most decimal digits in the numerator, and in the denominator, of a literal
(its significant digits) or of any rational that arises while evaluating.
It keeps each arithmetic step cheap, and below Python's limit of 4300 digits
for converting integers to and from text."""

MAX_EXPONENT = 1_000
"""Largest exponent of ``**`` / ``^`` (the result must also respect
:data:`MAX_DIGITS` and :data:`MAX_DEGREE`)."""

MAX_DEPTH = 64
"""Deepest nesting of parentheses, unary signs and powers."""

MAX_DEGREE = 8
"""Highest total degree of any polynomial that arises while evaluating (the
result may be required to have a lower one, 2 for a quadric); so
``(x**2 + 1)**2 - x**4`` is read as the quadric ``2*x**2 + 1``."""

MAX_WORK = 20_000
"""Most arithmetic steps spent on one input.  A step is one operation on two
coefficients, counted once more for every :data:`WORK_BITS` bits of the
operands; a product of polynomials with ``m`` and ``n`` terms costs ``m*n``
such steps, a sum ``m + n``."""

WORK_BITS = 512
"""Operand size (bits of numerators and denominators together) counted as one
more step; see :data:`MAX_WORK`."""

_LIMIT = 10**MAX_DIGITS  # a numerator or a denominator must stay below this
_LIMIT_BITS = _LIMIT.bit_length()


# -- the syntax tree ----------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class Number:
    """A literal, exactly (``0.1`` is ``Fraction(1, 10)``); ``start:end`` is its span."""

    value: Fraction
    start: int
    end: int


@dataclass(frozen=True, slots=True)
class Name:
    """A declared name; ``kind`` is ``"variable"`` or ``"parameter"``."""

    name: str
    kind: str
    start: int
    end: int


@dataclass(frozen=True, slots=True)
class Neg:
    """``-operand``."""

    operand: Expr
    start: int
    end: int


@dataclass(frozen=True, slots=True)
class Sum:
    """``terms[0][1] (op terms[k][1])...`` with each ``op`` ``"+"`` or ``"-"``
    (the first is always ``"+"``); n-ary, so long sums nest no deeper."""

    terms: tuple[tuple[str, Expr], ...]
    start: int
    end: int


@dataclass(frozen=True, slots=True)
class Product:
    """``factors[0][1] (op factors[k][1])...`` with ``op`` ``"*"`` or ``"/"``,
    left to right (the first is always ``"*"``)."""

    factors: tuple[tuple[str, Expr], ...]
    start: int
    end: int


@dataclass(frozen=True, slots=True)
class Power:
    """``base ** exponent`` with a literal exponent ``0 <= exponent <= MAX_EXPONENT``."""

    base: Expr
    exponent: int
    start: int
    end: int


@dataclass(frozen=True, slots=True)
class Equation:
    """``lhs = rhs``; it evaluates to ``lhs - rhs``."""

    lhs: Expr
    rhs: Expr
    start: int
    end: int


Expr = Number | Name | Neg | Sum | Product | Power | Equation
"""A node of the syntax tree."""


# -- errors -------------------------------------------------------------------------------


class Refusal(Exception):
    """Raised by an :class:`Algebra` to refuse an operation (division by zero,
    a degree or a number too large, ...); :func:`evaluate` turns it into an
    :class:`~quadric_contact.errors.EquationError` that says where."""


def _show_char(c: str) -> str:
    return c if " " <= c <= "~" or (c.isprintable() and not c.isspace()) else f"\\u{ord(c):04x}"


def _snippet(text: str, start: int, end: int, width: int = 30) -> str:
    """Two lines: the text around ``start:end`` (control characters escaped)
    and carets under ``start:end``."""
    end = max(min(end, start + 2 * width), start + 1)
    lo = max(0, start - width)
    hi = min(len(text), end + width)
    head = "..." if lo > 0 else ""
    tail = "..." if hi < len(text) else ""
    shown = [_show_char(c) for c in text[lo:hi]]
    before = len(head) + sum(len(s) for s in shown[: start - lo])
    marked = max(1, sum(len(s) for s in shown[start - lo : end - lo]))
    return f"    {head}{''.join(shown)}{tail}\n    {' ' * before}{'^' * marked}"


def _refuse(text: str, message: str, start: int, end: int | None = None, *, what: str = "") -> EquationError:
    end = start + 1 if end is None else end
    if "{where}" not in message:
        message += " ({where})"
    where = "at the end" if start >= len(text) else f"at position {start + 1}"
    message = message.replace("{where}", where)
    if what:
        message = f"{what}: {message}"
    if text:
        message += "\n" + _snippet(text, min(start, len(text)), min(end, len(text) + 1))
    return EquationError(message, text, offset=start, end=end, position=start + 1)


# -- the tokenizer ------------------------------------------------------------------------

_DIGITS = r"[0-9](?:_?[0-9])*"
_TOKEN = re.compile(
    rf"""
    (?P<ws>[ \t\r\n]+)
  | (?P<number>(?:{_DIGITS}(?:\.(?:{_DIGITS})?)?|\.{_DIGITS})(?:[eE][+-]?{_DIGITS})?)
  | (?P<name>[A-Za-z_][A-Za-z0-9_]*)
  | (?P<op>\*\*|==|//|[-+*/^()=])
    """,
    re.VERBOSE,
)
_NUMBER = re.compile(rf"(?P<int>{_DIGITS})?(?:\.(?P<frac>{_DIGITS})?)?(?:[eE](?P<exp>[+-]?{_DIGITS}))?")

_CHAR_HINTS = {
    ",": "a comma is not allowed (decimals are written with '.': 0.5)",
    "[": "brackets are not allowed: group with ( )",
    "]": "brackets are not allowed: group with ( )",
    "{": "braces are not allowed: group with ( )",
    "}": "braces are not allowed: group with ( )",
    ".": "'.' is only the decimal point of a number (no attribute access)",
    "'": "quotes are not allowed",
    '"': "quotes are not allowed",
    "\u2212": "write the minus sign as '-'",
    "\u00d7": "write products with '*'",
    "\u00b7": "write products with '*'",
    "\u22c5": "write products with '*'",
    "\u2219": "write products with '*'",
    "\u00f7": "write quotients with '/'",
    "\u00b2": "write squares as **2",
    "\u00b3": "write cubes as **3",
    "%": "'%' is not allowed (percentages: write /100)",
}

_CONSTANT_NAMES = {"pi", "e", "E", "I", "oo", "inf", "infinity", "nan", "tau"}


@dataclass(frozen=True, slots=True)
class _Token:
    kind: str  # "number", "name", "op", "end"
    text: str
    start: int
    end: int
    value: Fraction | None = None


def _number_value(text: str, literal: str, start: int, what: str) -> Fraction:
    m = _NUMBER.fullmatch(literal)
    assert m is not None, literal
    int_part = (m["int"] or "").replace("_", "")
    frac_part = (m["frac"] or "").replace("_", "").rstrip("0")
    exp_text = (m["exp"] or "0").replace("_", "")
    sign = -1 if exp_text.startswith("-") else 1
    exp_digits = exp_text.lstrip("+-").lstrip("0") or "0"
    mantissa = (int_part + frac_part).lstrip("0")
    end = start + len(literal)
    if len(mantissa) > MAX_DIGITS:
        raise _refuse(
            text,
            f"the number {{where}} has {len(mantissa)} significant digits, "
            f"more than {MAX_DIGITS} (MAX_DIGITS)",
            start,
            end,
            what=what,
        )
    if not mantissa:
        return Fraction(0)
    scale = len(exp_digits) <= 6 and sign * int(exp_digits) - len(frac_part)
    if scale is False or not -2 * MAX_DIGITS <= scale <= MAX_DIGITS:
        raise _refuse(
            text,
            f"the number {{where}} is too large or too small: more than {MAX_DIGITS} digits (MAX_DIGITS)",
            start,
            end,
            what=what,
        )
    value = Fraction(int(mantissa)) * Fraction(10) ** scale
    if abs(value.numerator) >= _LIMIT or value.denominator >= _LIMIT:
        raise _refuse(
            text,
            f"the number {{where}} has more than {MAX_DIGITS} digits (MAX_DIGITS)",
            start,
            end,
            what=what,
        )
    return value


def _tokenize(text: str, what: str) -> list[_Token]:
    tokens: list[_Token] = []
    pos, n = 0, len(text)
    match = _TOKEN.match
    while pos < n:
        m = match(text, pos)
        if m is None:
            c = text[pos]
            if c.isspace():
                desc = f"the space character U+{ord(c):04X} {{where}} is not allowed (use an ordinary space)"
            elif not c.isprintable():
                desc = f"the control character U+{ord(c):04X} {{where}} is not allowed"
            else:
                desc = f"the character {c!r} {{where}} is not allowed"
                hint = _CHAR_HINTS.get(c)
                if hint is None and c.isdigit():
                    hint = "only the ASCII digits 0-9 are allowed"
                if hint is None and c.isalpha():
                    hint = "names are ASCII: x, y, z"
                desc += f" ({hint})" if hint else " (only numbers, names, + - * / ** ^ ( ) and = are)"
            raise _refuse(text, desc, pos, what=what)
        kind = m.lastgroup
        assert kind is not None
        end = m.end()
        literal = m.group()
        if kind == "number":
            nxt = text[end : end + 1]
            if nxt in (".", "_") or nxt.isdigit() or nxt in ("e", "E"):
                bad_end = end
                while bad_end < n and (text[bad_end].isalnum() or text[bad_end] in "._"):
                    bad_end += 1
                raise _refuse(
                    text, f"malformed number {text[pos:bad_end]!r} {{where}}", pos, bad_end, what=what
                )
            tokens.append(_Token("number", literal, pos, end, _number_value(text, literal, pos, what)))
        elif kind == "op":
            if literal == "//":
                raise _refuse(
                    text, "'//' {where} is not allowed ('/' divides exactly)", pos, end, what=what
                )
            tokens.append(_Token("op", literal, pos, end))
        elif kind == "name":
            tokens.append(_Token("name", literal, pos, end))
        pos = end
    tokens.append(_Token("end", "", n, n))
    return tokens


# -- the parser ---------------------------------------------------------------------------


class _Parser:
    def __init__(self, text: str, names: dict[str, str], what: str) -> None:
        self.text = text
        self.names = names
        self.what = what
        self.tokens = _tokenize(text, what)
        self.i = 0

    # helpers
    def peek(self) -> _Token:
        return self.tokens[self.i]

    def advance(self) -> _Token:
        tok = self.tokens[self.i]
        self.i += 1
        return tok

    def refuse(self, message: str, start: int, end: int | None = None) -> EquationError:
        return _refuse(self.text, message, start, end, what=self.what)

    def allowed(self) -> str:
        return f"; allowed names: {', '.join(self.names)}" if self.names else ": a number contains no names"

    # grammar
    def parse(self, allow_equation: bool) -> Expr:
        if self.peek().kind == "end":
            raise EquationError(f"{self.what}: empty text" if self.what else "empty text", self.text)
        lhs = self.expression(0)
        tok = self.peek()
        if tok.text == "=":
            if not allow_equation:
                raise self.refuse("'=' {where} is not allowed here (not an equation)", tok.start, tok.end)
            self.advance()
            if self.peek().kind == "end":
                raise self.refuse("expected an expression after '=' {where}", tok.start, tok.end)
            rhs = self.expression(0)
            tok2 = self.peek()
            if tok2.text == "=":
                raise self.refuse("a second '=' {where}: an equation has one", tok2.start, tok2.end)
            lhs = Equation(lhs, rhs, lhs.start, rhs.end)
            tok = tok2
        if tok.text == "==":
            raise self.refuse("'==' {where}: an equation is written with a single '='", tok.start, tok.end)
        if tok.kind != "end":
            if tok.text == ")":
                raise self.refuse("unmatched ')' {where}", tok.start, tok.end)
            raise self.refuse(f"unexpected {tok.text!r} {{where}}", tok.start, tok.end)
        return lhs

    def expression(self, depth: int) -> Expr:
        first = self.term(depth)
        terms: list[tuple[str, Expr]] = [("+", first)]
        while self.peek().text in ("+", "-"):
            op = self.advance().text
            terms.append((op, self.term(depth)))
        if len(terms) == 1:
            return first
        return Sum(tuple(terms), first.start, terms[-1][1].end)

    def term(self, depth: int) -> Expr:
        first = self.factor(depth)
        factors: list[tuple[str, Expr]] = [("*", first)]
        while True:
            tok = self.peek()
            if tok.text in ("*", "/"):
                self.advance()
                factors.append((tok.text, self.factor(depth)))
            elif tok.kind in ("number", "name") or tok.text == "(":
                self.implicit(factors[-1][1], tok, depth)
            else:
                break
        if len(factors) == 1:
            return first
        return Product(tuple(factors), first.start, factors[-1][1].end)

    def implicit(self, left: Expr, tok: _Token, depth: int) -> None:
        """Two operands side by side: refuse, suggesting the explicit product."""
        if tok.kind == "name" and tok.text not in self.names:
            self.unknown_name(tok)
        save = self.i
        try:
            right_end = self.factor(depth).end
        except EquationError:
            right_end = tok.end
        self.i = save
        left_text = self.text[left.start : left.end]
        right_text = self.text[tok.start : right_end]
        raise self.refuse(
            f"implicit multiplication {{where}}: write {left_text}*{right_text}", tok.start, tok.end
        )

    def factor(self, depth: int) -> Expr:
        if depth > MAX_DEPTH:
            tok = self.peek()
            raise self.refuse(
                f"nesting deeper than {MAX_DEPTH} levels {{where}} (MAX_DEPTH)", tok.start, tok.end
            )
        tok = self.peek()
        if tok.text in ("+", "-"):
            self.advance()
            operand = self.factor(depth + 1)
            if tok.text == "+":
                return operand
            return Neg(operand, tok.start, operand.end)
        return self.power(depth)

    def power(self, depth: int) -> Expr:
        base = self.atom(depth)
        tok = self.peek()
        if tok.text not in ("**", "^"):
            return base
        self.advance()
        exponent, end = self.exponent(tok)
        nxt = self.peek()
        if nxt.text in ("**", "^"):
            raise self.refuse(
                "a power of a power {where}: write parentheses, (a**b)**c", nxt.start, nxt.end
            )
        return Power(base, exponent, base.start, end)

    def exponent(self, op: _Token) -> tuple[int, int]:
        tok = self.peek()
        paren = tok.text == "("
        if paren:
            self.advance()
            tok = self.peek()
        if tok.text == "+":
            self.advance()
            tok = self.peek()
        if tok.text == "-":
            raise self.refuse(
                "a negative exponent {where}: exponents are non-negative integers "
                "(write 1/x**2 for a number x)",
                tok.start,
                tok.end,
            )
        if tok.kind != "number":
            got = "the end" if tok.kind == "end" else repr(tok.text)
            raise self.refuse(
                f"the exponent after {op.text!r} {{where}} must be a non-negative integer literal, got {got}",
                tok.start,
                tok.end,
            )
        if not re.fullmatch(_DIGITS, tok.text):
            raise self.refuse(
                f"the exponent {tok.text} {{where}} must be a non-negative integer literal",
                tok.start,
                tok.end,
            )
        assert tok.value is not None and tok.value.denominator == 1
        n = int(tok.value)
        if n > MAX_EXPONENT:
            raise self.refuse(
                f"the exponent {tok.text} {{where}} is larger than {MAX_EXPONENT} (MAX_EXPONENT)",
                tok.start,
                tok.end,
            )
        self.advance()
        end = tok.end
        if paren:
            close = self.peek()
            if close.text != ")":
                raise self.refuse("expected ')' after the exponent {where}", close.start, close.end)
            self.advance()
            end = close.end
        return n, end

    def unknown_name(self, tok: _Token) -> None:
        name = tok.text
        nxt = self.tokens[self.i + 1]
        if nxt.text == "(":
            raise self.refuse(
                f"the function call {name}(...) {{where}} is not allowed: only + - * / ** and parentheses",
                tok.start,
                tok.end,
            )
        hint = ""
        variables = [v for v, k in self.names.items() if k == "variable"]
        m = re.fullmatch(r"([A-Za-z]+)([0-9]+)", name)
        if m and m[1] in self.names:
            v, d = m[1], m[2]
            hint = f" (did you mean {d}*{v} or {v}**{d}?)"
        elif name in _CONSTANT_NAMES:
            hint = " (only rational numbers are allowed)"
        elif variables and all(c in variables for c in name):
            hint = f" (did you mean {'*'.join(name)}?)"
        raise self.refuse(
            f"unknown name {name!r} {{where}}{hint}{self.allowed()}", tok.start, tok.end
        )

    def atom(self, depth: int) -> Expr:
        tok = self.peek()
        if tok.kind == "number":
            self.advance()
            assert tok.value is not None
            return Number(tok.value, tok.start, tok.end)
        if tok.kind == "name":
            kind = self.names.get(tok.text)
            if kind is None:
                self.unknown_name(tok)
            assert kind is not None
            self.advance()
            return Name(tok.text, kind, tok.start, tok.end)
        if tok.text == "(":
            self.advance()
            if depth + 1 > MAX_DEPTH:
                raise self.refuse(
                    f"nesting deeper than {MAX_DEPTH} levels {{where}} (MAX_DEPTH)", tok.start, tok.end
                )
            inner = self.expression(depth + 1)
            close = self.peek()
            if close.text != ")":
                if close.kind == "end":
                    raise self.refuse("the '(' {where} is never closed", tok.start, tok.end)
                raise self.refuse(f"expected ')' {{where}}, got {close.text!r}", close.start, close.end)
            self.advance()
            return _respan(inner, tok.start, close.end)
        if tok.kind == "end":
            prev = self.tokens[self.i - 1] if self.i else tok
            raise self.refuse(
                f"expected a number, a name or '(' after {prev.text!r} {{where}}", tok.start, tok.end
            )
        if tok.text == ")":
            raise self.refuse("unexpected ')' {where}: expected a number, a name or '('", tok.start, tok.end)
        raise self.refuse(
            f"unexpected {tok.text!r} {{where}}: expected a number, a name or '('", tok.start, tok.end
        )


def _respan(node: Expr, start: int, end: int) -> Expr:
    """The node with the span of its parentheses (for messages that quote it)."""
    fields = {f: getattr(node, f) for f in node.__dataclass_fields__}
    fields["start"], fields["end"] = start, end
    return type(node)(**fields)


# -- algebras ------------------------------------------------------------------------------

T = TypeVar("T")


class Algebra(Protocol[T]):
    """What :func:`evaluate` needs: the eight operations of the grammar.

    An algebra refuses an operation by raising :class:`Refusal`; evaluate
    adds where.  ``variable`` receives every declared name, variables and
    parameters alike (:attr:`Name.kind` tells them apart in the tree).
    """

    def constant(self, value: Fraction) -> T: ...

    def variable(self, name: str) -> T: ...

    def add(self, a: T, b: T) -> T: ...

    def sub(self, a: T, b: T) -> T: ...

    def neg(self, a: T) -> T: ...

    def mul(self, a: T, b: T) -> T: ...

    def div(self, a: T, b: T) -> T: ...

    def pow(self, a: T, n: int) -> T: ...


Polynomial = dict[tuple[int, ...], Fraction]
"""A sparse polynomial: exponent tuple (over the declared variables) -> non-zero coefficient."""


def _size(p: Polynomial) -> int:
    return max((c.numerator.bit_length() + c.denominator.bit_length() for c in p.values()), default=0)


def _degree(p: Polynomial) -> int:
    return max((sum(e) for e in p), default=0)


class PolynomialAlgebra:
    """Exact sparse polynomials over Q in the variables ``variables``.

    Every coefficient is checked against :data:`MAX_DIGITS`, every degree
    against ``max_degree`` (default :data:`MAX_DEGREE`), and the work against
    ``budget`` (default :data:`MAX_WORK`).  Division is by non-zero constants
    only.

    Examples
    --------
    >>> tree = parse_expression("(x - 1/2)^2", variables=("x",))
    >>> evaluate(tree, PolynomialAlgebra(("x",)))
    {(2,): Fraction(1, 1), (1,): Fraction(-1, 1), (0,): Fraction(1, 4)}
    """

    def __init__(
        self, variables: Sequence[str], *, max_degree: int = MAX_DEGREE, budget: int = MAX_WORK
    ) -> None:
        self.variables = tuple(variables)
        self.index = {v: i for i, v in enumerate(self.variables)}
        self.zero = (0,) * len(self.variables)
        self.max_degree = max_degree
        self.budget = budget
        self.work = 0

    def _charge(self, steps: int) -> None:
        self.work += steps
        if self.work > self.budget:
            raise Refusal(
                f"more than {self.budget} arithmetic steps (MAX_WORK) {{where}}: "
                "the input is too costly to expand"
            )

    def _checked(self, p: Polynomial) -> Polynomial:
        for c in p.values():
            if abs(c.numerator) >= _LIMIT or c.denominator >= _LIMIT:
                raise Refusal(f"a number with more than {MAX_DIGITS} digits (MAX_DIGITS) arises {{where}}")
        return p

    def _is_constant(self, p: Polynomial) -> bool:
        return not p or (len(p) == 1 and self.zero in p)

    def constant(self, value: Fraction) -> Polynomial:
        return {self.zero: Fraction(value)} if value else {}

    def variable(self, name: str) -> Polynomial:
        if name not in self.index:
            raise Refusal(f"{name!r} {{where}} is not a variable of this polynomial")
        e = [0] * len(self.variables)
        e[self.index[name]] = 1
        return {tuple(e): Fraction(1)}

    def add(self, a: Polynomial, b: Polynomial) -> Polynomial:
        self._charge(1 + len(b) * (1 + (_size(a) + _size(b)) // WORK_BITS))
        out = dict(a)
        for e, c in b.items():
            s = out.get(e, 0) + c
            if s:
                out[e] = s
            else:
                out.pop(e, None)
        return self._checked(out)

    def neg(self, a: Polynomial) -> Polynomial:
        self._charge(len(a))
        return {e: -c for e, c in a.items()}

    def sub(self, a: Polynomial, b: Polynomial) -> Polynomial:
        return self.add(a, self.neg(b))

    def mul(self, a: Polynomial, b: Polynomial) -> Polynomial:
        d = _degree(a) + _degree(b)
        if a and b and d > self.max_degree:
            raise Refusal(
                f"a product of degree {d} {{where}}: more than the {self.max_degree} allowed (MAX_DEGREE)"
            )
        self._charge(len(a) * len(b) * (1 + (_size(a) + _size(b)) // WORK_BITS))
        out: Polynomial = {}
        for ea, ca in a.items():
            for eb, cb in b.items():
                e = tuple(i + j for i, j in zip(ea, eb, strict=True))
                s = out.get(e, 0) + ca * cb
                if s:
                    out[e] = s
                else:
                    out.pop(e, None)
        return self._checked(out)

    def div(self, a: Polynomial, b: Polynomial) -> Polynomial:
        if not self._is_constant(b):
            names = ", ".join(self.variables)
            raise Refusal(f"division by an expression in {names} {{where}}: the result is not a polynomial")
        if not b:
            raise Refusal("division by zero {where}")
        return self.mul(a, {self.zero: 1 / b[self.zero]})

    def pow(self, a: Polynomial, n: int) -> Polynomial:
        if n == 0:
            return {self.zero: Fraction(1)}
        if not a:
            return {}
        if self._is_constant(a):
            c = a[self.zero]
            bits = max(abs(c.numerator).bit_length(), c.denominator.bit_length()) - 1
            if bits * n >= _LIMIT_BITS:
                raise Refusal(f"a power with more than {MAX_DIGITS} digits (MAX_DIGITS) {{where}}")
            self._charge(1 + n * (bits + 1) // WORK_BITS)
            return self._checked({self.zero: c**n})
        d = _degree(a) * n
        if d > self.max_degree:
            raise Refusal(
                f"a power of degree {d} {{where}}: more than the {self.max_degree} allowed (MAX_DEGREE)"
            )
        out = a
        for _ in range(n - 1):
            out = self.mul(out, a)
        return out


def evaluate(tree: Expr, algebra: Algebra[T], *, text: str | None = None, what: str = "") -> T:
    """Fold the syntax tree over ``algebra``.

    Parameters
    ----------
    tree : Expr
        From :func:`parse_expression`.
    algebra : Algebra
        The operations (:class:`PolynomialAlgebra`, or any other).
    text : str, optional
        The text the tree was read from, to quote in messages.
    what : str, optional
        What the text is (``"equation"``), to start messages with.

    Raises
    ------
    EquationError
        The algebra refused an operation; the message says where.
    """
    try:
        return _eval(tree, algebra)
    except _Located as exc:
        raise _refuse(text or "", exc.message, exc.start, exc.end, what=what) from None


class _Located(Exception):
    def __init__(self, message: str, start: int, end: int) -> None:
        super().__init__(message)
        self.message, self.start, self.end = message, start, end


def _eval(node: Expr, alg: Algebra[T]) -> T:
    try:
        if isinstance(node, Number):
            return alg.constant(node.value)
        if isinstance(node, Name):
            return alg.variable(node.name)
        if isinstance(node, Neg):
            return alg.neg(_eval(node.operand, alg))
        if isinstance(node, Sum):
            acc = _eval(node.terms[0][1], alg)
            for op, term in node.terms[1:]:
                value = _eval(term, alg)
                try:
                    acc = alg.add(acc, value) if op == "+" else alg.sub(acc, value)
                except Refusal as exc:
                    raise _Located(str(exc), node.start, term.end) from None
            return acc
        if isinstance(node, Product):
            acc = _eval(node.factors[0][1], alg)
            for op, factor in node.factors[1:]:
                value = _eval(factor, alg)
                try:
                    acc = alg.mul(acc, value) if op == "*" else alg.div(acc, value)
                except Refusal as exc:
                    start = factor.start if op == "/" else node.start
                    raise _Located(str(exc), start, factor.end) from None
            return acc
        if isinstance(node, Power):
            return alg.pow(_eval(node.base, alg), node.exponent)
        if isinstance(node, Equation):
            return alg.sub(_eval(node.lhs, alg), _eval(node.rhs, alg))
    except Refusal as exc:
        raise _Located(str(exc), node.start, node.end) from None
    raise TypeError(f"not a node of the syntax tree: {node!r}")


# -- the public readers ----------------------------------------------------------------------


def _check_text(text: Any, what: str) -> str:
    if not isinstance(text, str):
        raise EquationError(f"{what}: expected a string, got {type(text).__name__}", text)
    if len(text) > MAX_LENGTH:
        raise _refuse(
            text,
            f"the text has {len(text)} characters, more than {MAX_LENGTH} (MAX_LENGTH)",
            MAX_LENGTH,
            len(text),
            what=what,
        )
    return text


def _declare(variables: Sequence[str], parameters: Sequence[str]) -> dict[str, str]:
    names: dict[str, str] = {}
    for kind, group in (("variable", variables), ("parameter", parameters)):
        for v in group:
            if not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", v) or v in names:
                raise ValueError(f"bad or repeated name {v!r} among {tuple(variables) + tuple(parameters)}")
            names[v] = kind
    return names


def parse_expression(
    text: str,
    variables: Sequence[str] = ("x", "y", "z"),
    parameters: Sequence[str] = (),
    *,
    equation: bool = False,
    what: str = "",
) -> Expr:
    """Read ``text`` into a syntax tree (see the module's grammar).

    Parameters
    ----------
    text : str
        The user's text.
    variables, parameters : sequences of names
        The names the text may use.  Both are plain names to the parser;
        :class:`Name` nodes record which kind each is, so an algebra can, for
        instance, allow division by parameters only.
    equation : bool, default False
        Allow one ``=`` (the tree is then an :class:`Equation`).
    what : str, optional
        What the text is, to start messages with.

    Returns
    -------
    Expr

    Raises
    ------
    EquationError
        Anything outside the grammar or the bounds; the message names the
        offending text and its position (``details['offset']``, 0-based).

    Examples
    --------
    >>> tree = parse_expression("u*x^2 = 1", variables=("x",), parameters=("u",), equation=True)
    >>> tree.lhs.factors[1][1]
    Power(base=Name(name='x', kind='variable', start=2, end=3), exponent=2, start=2, end=5)
    >>> parse_expression("x2 + 1")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
        ...
    quadric_contact.errors.EquationError: unknown name 'x2' at position 1 (did you mean 2*x or x**2?); ...
        x2 + 1
        ^^
    """
    text = _check_text(text, what or "expression")
    return _Parser(text, _declare(variables, parameters), what).parse(equation)


def _locate_degree(tree: Expr, variables: Sequence[str], max_degree: int) -> tuple[int, int]:
    """The span of the first top-level term whose degree exceeds ``max_degree``."""
    sides = [tree.lhs, tree.rhs] if isinstance(tree, Equation) else [tree]
    for side in sides:
        terms = [t for _, t in side.terms] if isinstance(side, Sum) else [side]
        for t in terms:
            try:
                if _degree(_eval(t, PolynomialAlgebra(variables))) > max_degree:
                    return t.start, t.end
            except _Located:
                return t.start, t.end
    return tree.start, tree.end


def parse_polynomial(
    text: str,
    variables: Sequence[str] = ("x", "y", "z"),
    *,
    max_degree: int = 2,
    equation: bool = False,
    what: str = "",
) -> Polynomial:
    """Read ``text`` as an exact polynomial in ``variables`` of degree at most ``max_degree``.

    Returns
    -------
    dict
        Exponent tuple (over ``variables``) to non-zero :class:`~fractions.Fraction`;
        for an equation ``lhs = rhs``, the polynomial ``lhs - rhs``.

    Raises
    ------
    EquationError
        Anything :func:`parse_expression` refuses, division by an expression
        in the variables or by zero, a degree above ``max_degree`` after
        expansion, a bound exceeded.

    Examples
    --------
    >>> parse_polynomial("3 - 2*t^2 + t/2", ("t",), max_degree=4)
    {(0,): Fraction(3, 1), (2,): Fraction(-2, 1), (1,): Fraction(1, 2)}
    >>> parse_polynomial("x**2 - (x - 1)*(x + 1)", ("x",))
    {(0,): Fraction(1, 1)}
    """
    if max_degree > MAX_DEGREE:
        raise ValueError(f"max_degree {max_degree} exceeds MAX_DEGREE = {MAX_DEGREE}")
    what = what or ("equation" if equation else "polynomial")
    tree = parse_expression(text, variables, equation=equation, what=what)
    poly = evaluate(tree, PolynomialAlgebra(variables), text=text, what=what)
    degree = _degree(poly)
    if degree > max_degree:
        start, end = _locate_degree(tree, variables, max_degree)
        raise _refuse(
            text,
            f"degree {degree} after expansion {{where}}; at most {max_degree} is allowed here",
            start,
            end,
            what=what,
        )
    return poly


def parse_univariate(
    text: str, variable: str = "t", *, max_degree: int = MAX_DEGREE, what: str = ""
) -> tuple[Fraction, ...]:
    """Read ``text`` as a polynomial in one variable (a path in time ``t``):
    its coefficients in ascending powers (``(0,)`` for zero).

    Raises
    ------
    EquationError
        As :func:`parse_polynomial`.

    Examples
    --------
    >>> parse_univariate("2*t - 5*t^2")
    (Fraction(0, 1), Fraction(2, 1), Fraction(-5, 1))
    """
    what = what or f"polynomial in {variable}"
    poly = parse_polynomial(text, (variable,), max_degree=max_degree, what=what)
    degree = _degree(poly)
    return tuple(poly.get((k,), Fraction(0)) for k in range(degree + 1))


def parse_number(text: str) -> Fraction:
    """Read ``text`` as an exact rational number.

    Integers, decimals, scientific notation, fractions and small exact
    expressions (``"1/3 + 2/7"``, ``"2**-3"`` is refused: write ``1/2**3``).

    Raises
    ------
    NotANumberError
        Anything outside the grammar without names, division by zero, a bound
        exceeded; the message names the offending text and its position.

    Examples
    --------
    >>> parse_number("8.36291"), parse_number("-1/3 + 1e-2")
    (Fraction(836291, 100000), Fraction(-97, 300))
    """
    try:
        poly = parse_polynomial(text, (), max_degree=0, what="number")
    except EquationError as exc:
        raise NotANumberError(str(exc), text, **exc.details) from None
    return poly.get((), Fraction(0))


def _quadric_monomials() -> tuple[tuple[tuple[int, ...], Fraction], ...]:
    out = []
    for i, j in ENTRY_INDICES:
        e = [0, 0, 0]
        for k in (i, j):
            if k < 3:
                e[k] += 1
        out.append((tuple(e), Fraction(1) if i == j else Fraction(1, 2)))
    return tuple(out)


_QUADRIC_MONOMIALS = _quadric_monomials()
"""For each upper entry ``(i, j)`` of the matrix: the monomial whose coefficient
it takes, and the factor (``1/2`` off the diagonal: ``2 q_ij x_i x_j``)."""


def quadric_entries(poly: Polynomial) -> tuple[Fraction, ...]:
    """The ten upper entries (``ENTRY_INDICES`` order) of the symmetric matrix of a
    polynomial of degree at most 2 in ``x, y, z`` (eq. (6))."""
    return tuple(poly.get(mono, Fraction(0)) * f for mono, f in _QUADRIC_MONOMIALS)


def parse_quadric_equation(text: str) -> tuple[Fraction, ...]:
    """Read an equation (or an expression ``= 0``) of degree at most 2 in ``x, y, z``.

    Returns
    -------
    tuple of 10 Fractions
        The upper entries of the symmetric matrix, in the order of
        :data:`~quadric_contact.entries.ENTRY_INDICES`.

    Raises
    ------
    EquationError

    Examples
    --------
    >>> parse_quadric_equation("x^2 + y^2 - 0.25*(z - 3)^2 = 1")[7:]
    (Fraction(-1, 4), Fraction(3, 4), Fraction(-13, 4))
    >>> parse_quadric_equation("3(z - 1)^2")
    Traceback (most recent call last):
        ...
    quadric_contact.errors.EquationError: equation: implicit multiplication at position 2: write 3*(z - 1)^2
        3(z - 1)^2
         ^
    """
    return quadric_entries(parse_polynomial(text, ("x", "y", "z"), max_degree=2, equation=True))
