"""The package's own reader of numbers and polynomial expressions: user text is data, never code.

Equations (``"x^2 + y^2 - 0.25*(z - 3)^2 = 1"``), numbers (``"8.36291"``,
``"1/3 + 2/7"``, ``"1e-5"``) and polynomial paths in time (``"3 - 2*t^2"``)
reach the package from users, courses and other programs: in
:meth:`~quadric_contact.Quadric.from_equation`, in every number a constructor
takes (:func:`~quadric_contact.exact.rational.to_fraction`), on the command line and
in scene files.  They are read here by a tokenizer and a recursive-descent
parser into a small syntax tree, which :func:`evaluate` folds over an
:class:`Algebra`: exact sparse polynomials over Q (:class:`PolynomialAlgebra`)
for quadrics, numbers and trajectories, or any other algebra with the same
eight operations (for instance sympy objects built programmatically, for
families of quadrics whose coefficients contain parameters declared with
``parse_expression(..., parameters=("u", "w"))``).  Nothing here calls
``eval``, ``exec``, ``compile``, ``sympify``, ``parse_expr`` or ``S()``.

The readers: :func:`parse_polynomial` (exponent tuple to
:class:`~fractions.Fraction`), :func:`parse_univariate` (coefficients of a
polynomial in ``t``), :func:`parse_number` (a :class:`~fractions.Fraction`)
and :func:`parse_expression` (the syntax tree, for other algebras).  The
reader of a quadric's equation (its ten matrix entries) is
:func:`quadric_contact.model.parsing.parse_quadric_equation`, built on these.

This module sits with the exact arithmetic (it imports only
:mod:`~quadric_contact.exact.errors`): :func:`~quadric_contact.exact.rational.to_fraction`
reads every number given as text with :func:`parse_number`.

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

Refused, with an :class:`~quadric_contact.exact.errors.EquationError` (or, for a
number, :class:`~quadric_contact.exact.errors.NotANumberError`) whose message names
the offending text and its position (1-based; ``details["offset"]`` is the
0-based index) and shows it under a caret: unknown
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
:data:`MAX_DEPTH` (nesting of parentheses and signs),
:data:`MAX_DEGREE` (degree of every intermediate polynomial) and
:data:`MAX_WORK` (arithmetic steps, weighted by the size of the numbers).
Numbers and lengths are checked before anything is computed with them, the
degree of a product before it is formed.  The slowest inputs the bounds
admit are read or refused in well under 100 ms
(``benchmarks/bench_parsing.py`` measures them).
"""

from __future__ import annotations

import dataclasses
import re
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any, Protocol, TypeVar

import flint

from quadric_contact.exact.bounds import (
    MAX_DEGREE,
    MAX_DEPTH,
    MAX_DIGITS,
    MAX_EXPONENT,
    MAX_LENGTH,
    MAX_WORK,
    WORK_BITS,
)
from quadric_contact.exact.errors import EquationError, NotANumberError

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
    "parse_univariate",
]

# The bounds live with the package's other bounds (exact/bounds.py); they are
# re-exported here, where the reader's documentation names them.
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
    :class:`~quadric_contact.exact.errors.EquationError` that says where: a
    ``{where}`` in the message becomes "at position N" (else it is appended)."""


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
    [ \t\r\n]*                                  # blanks before the token
    (?:
      ((?:{_DIGITS}(?:\.(?:{_DIGITS})?)?|\.{_DIGITS})(?:[eE][+-]?{_DIGITS})?)(?![._eE0-9])  # 1: number
    | ([A-Za-z_][A-Za-z0-9_]*)                                                    # 2: name
    | (\*\*|==|//|[-+*/^()=])                                                     # 3: operator
    | (\Z)                                                                        # 4: the end
    )
    """,
    re.VERBOSE,
)
_NUMBER = re.compile(rf"(?P<int>{_DIGITS})?(?:\.(?P<frac>{_DIGITS})?)?(?:[eE](?P<exp>[+-]?{_DIGITS}))?")
_INTEGER = re.compile(_DIGITS)

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

_CONSTANT_NAMES = frozenset({"pi", "e", "E", "I", "oo", "inf", "infinity", "nan", "tau"})

# A token is a tuple (kind, text, start, end, value): kind is one of these,
# value the exact Fraction of a number (None otherwise).
_NUM, _NAME, _OP, _END = "number", "name", "op", "end"
_Token = tuple[str, str, int, int, Fraction | None]


def _number_value(text: str, literal: str, start: int, what: str) -> Fraction:
    end = start + len(literal)
    if literal.isdigit():  # the common case: a plain integer
        digits = literal.lstrip("0")
        if len(digits) <= MAX_DIGITS:
            return Fraction(int(digits or "0"))
        mantissa, frac_part, exp_digits, sign = digits, "", "0", 1
    else:
        m = _NUMBER.fullmatch(literal)
        assert m is not None, literal
        int_part = (m["int"] or "").replace("_", "")
        frac_part = (m["frac"] or "").replace("_", "").rstrip("0")
        exp_text = (m["exp"] or "0").replace("_", "")
        sign = -1 if exp_text.startswith("-") else 1
        exp_digits = exp_text.lstrip("+-").lstrip("0") or "0"
        mantissa = (int_part + frac_part).lstrip("0")
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
    scale = sign * int(exp_digits) - len(frac_part) if len(exp_digits) <= 6 else None
    if scale is None or not -2 * MAX_DIGITS <= scale <= MAX_DIGITS:
        raise _refuse(
            text,
            f"the number {{where}} is too large or too small: more than {MAX_DIGITS} digits (MAX_DIGITS)",
            start,
            end,
            what=what,
        )
    value = Fraction(int(mantissa) * 10**scale) if scale >= 0 else Fraction(int(mantissa), 10**-scale)
    if abs(value.numerator) >= _LIMIT or value.denominator >= _LIMIT:
        raise _refuse(
            text,
            f"the number {{where}} has more than {MAX_DIGITS} digits (MAX_DIGITS)",
            start,
            end,
            what=what,
        )
    return value


def _bad_character(text: str, pos: int, what: str) -> EquationError:
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
            hint = "names are ASCII letters, digits and _"
        desc += f" ({hint})" if hint else " (only numbers, names, + - * / ** ^ ( ) and = are)"
    return _refuse(text, desc, pos, what=what)


def _tokenize(text: str, what: str) -> list[_Token]:
    tokens: list[_Token] = []
    append = tokens.append
    pos = 0
    match = _TOKEN.match
    # One anchored match per token, never a search: a search would retry at
    # every later position after a failure, and each try rescans a run of
    # blanks or digits, which is quadratic in the length of the text.
    while (m := match(text, pos)) is not None:
        i = m.lastindex or 4
        start, end = m.span(i)
        literal = m.group(i)
        if i == 1:
            append((_NUM, literal, start, end, _number_value(text, literal, start, what)))
        elif i == 3:
            if literal == "//":
                raise _refuse(
                    text, "'//' {where} is not allowed ('/' divides exactly)", start, end, what=what
                )
            append((_OP, literal, start, end, None))
        elif i == 2:
            append((_NAME, literal, start, end, None))
        else:
            append((_END, "", end, end, None))
            return tokens
        pos = end
    pos = len(text) - len(text[pos:].lstrip(" \t\r\n"))
    c = text[pos]
    if "0" <= c <= "9" or (c == "." and "0" <= text[pos + 1 : pos + 2] <= "9"):
        # a number followed by what cannot follow one: "1.2.3", "2e", "1_"
        end = pos + 1
        while end < len(text) and ((text[end].isascii() and text[end].isalnum()) or text[end] in "._"):
            end += 1
        raise _refuse(text, f"malformed number {text[pos:end]!r} {{where}}", pos, end, what=what)
    raise _bad_character(text, pos, what)


# -- the parser ---------------------------------------------------------------------------


class _Parser:
    """Recursive descent over the token list, one method per rule of the grammar."""

    def __init__(self, text: str, names: dict[str, str], what: str) -> None:
        self.text = text
        self.names = names
        self.what = what
        self.tokens = _tokenize(text, what)
        self.i = 0

    def refuse(self, message: str, start: int, end: int | None = None) -> EquationError:
        return _refuse(self.text, message, start, end, what=self.what)

    def parse(self, allow_equation: bool) -> Expr:
        tokens = self.tokens
        if tokens[0][0] == _END:
            raise EquationError(f"{self.what}: empty text" if self.what else "empty text", self.text)
        lhs = self.expression(0)
        tok = tokens[self.i]
        if tok[1] == "=":
            if not allow_equation:
                raise self.refuse("'=' {where} is not allowed here (not an equation)", tok[2], tok[3])
            self.i += 1
            if tokens[self.i][0] == _END:
                raise self.refuse("expected an expression after '=' {where}", tok[2], tok[3])
            rhs = self.expression(0)
            tok2 = tokens[self.i]
            if tok2[1] == "=":
                raise self.refuse("a second '=' {where}: an equation has one", tok2[2], tok2[3])
            lhs = Equation(lhs, rhs, lhs.start, rhs.end)
            tok = tok2
        if tok[1] == "==":
            raise self.refuse("'==' {where}: an equation is written with a single '='", tok[2], tok[3])
        if tok[0] != _END:
            if tok[1] == ")":
                raise self.refuse("unmatched ')' {where}", tok[2], tok[3])
            raise self.refuse(f"unexpected {tok[1]!r} {{where}}", tok[2], tok[3])
        return lhs

    def expression(self, depth: int) -> Expr:
        """expression = term { ("+" | "-") term }"""
        first = self.term(depth)
        tokens = self.tokens
        op = tokens[self.i][1]
        if op != "+" and op != "-":
            return first
        terms: list[tuple[str, Expr]] = [("+", first)]
        while op == "+" or op == "-":
            self.i += 1
            terms.append((op, self.term(depth)))
            op = tokens[self.i][1]
        return Sum(tuple(terms), first.start, terms[-1][1].end)

    def term(self, depth: int) -> Expr:
        """term = factor { ("*" | "/") factor }; two factors side by side are refused."""
        first = self.factor(depth)
        tokens = self.tokens
        factors: list[tuple[str, Expr]] | None = None
        while True:
            tok = tokens[self.i]
            op = tok[1]
            if op == "*" or op == "/":
                self.i += 1
                if factors is None:
                    factors = [("*", first)]
                factors.append((op, self.factor(depth)))
            elif tok[0] == _NUM or tok[0] == _NAME or op == "(":
                self.implicit(factors[-1][1] if factors else first, tok, depth)
            else:
                break
        if factors is None:
            return first
        return Product(tuple(factors), first.start, factors[-1][1].end)

    def implicit(self, left: Expr, tok: _Token, depth: int) -> None:
        """Two operands side by side: refuse, suggesting the explicit product."""
        if tok[0] == _NAME and tok[1] not in self.names:
            self.unknown_name(tok)
        save = self.i
        try:
            right_end = self.factor(depth).end
        except EquationError:
            right_end = tok[3]
        self.i = save
        left_text = self.text[left.start : left.end]
        right_text = self.text[tok[2] : right_end]
        raise self.refuse(
            f"implicit multiplication {{where}}: write {left_text}*{right_text}", tok[2], tok[3]
        )

    def factor(self, depth: int) -> Expr:
        """factor = ("+" | "-") factor | power"""
        tok = self.tokens[self.i]
        sign = tok[1]
        if sign != "+" and sign != "-":
            return self.power(depth)
        if depth >= MAX_DEPTH:
            raise self.refuse(f"nesting deeper than {MAX_DEPTH} levels {{where}} (MAX_DEPTH)", tok[2], tok[3])
        self.i += 1
        operand = self.factor(depth + 1)
        return operand if sign == "+" else Neg(operand, tok[2], operand.end)

    def power(self, depth: int) -> Expr:
        """power = atom [ ("**" | "^") exponent ]"""
        base = self.atom(depth)
        tok = self.tokens[self.i]
        if tok[1] != "**" and tok[1] != "^":
            return base
        self.i += 1
        exponent, end = self.exponent(tok)
        nxt = self.tokens[self.i]
        if nxt[1] == "**" or nxt[1] == "^":
            raise self.refuse("a power of a power {where}: write parentheses, (a**b)**c", nxt[2], nxt[3])
        return Power(base, exponent, base.start, end)

    def exponent(self, op: _Token) -> tuple[int, int]:
        """exponent = [ "+" ] integer | "(" [ "+" ] integer ")" """
        tokens = self.tokens
        tok = tokens[self.i]
        paren = tok[1] == "("
        if paren:
            self.i += 1
            tok = tokens[self.i]
        if tok[1] == "+":
            self.i += 1
            tok = tokens[self.i]
        if tok[1] == "-":
            raise self.refuse(
                "a negative exponent {where}: exponents are non-negative integers "
                "(write 1/x**2 for a number x)",
                tok[2],
                tok[3],
            )
        if tok[0] != _NUM:
            got = "the end" if tok[0] == _END else repr(tok[1])
            raise self.refuse(
                f"the exponent after {op[1]!r} {{where}} must be a non-negative integer literal, got {got}",
                tok[2],
                tok[3],
            )
        if not _INTEGER.fullmatch(tok[1]):
            raise self.refuse(
                f"the exponent {tok[1]} {{where}} must be a non-negative integer literal", tok[2], tok[3]
            )
        value = tok[4]
        assert value is not None and value.denominator == 1
        if value > MAX_EXPONENT:
            raise self.refuse(
                f"the exponent {tok[1]} {{where}} is larger than {MAX_EXPONENT} (MAX_EXPONENT)",
                tok[2],
                tok[3],
            )
        self.i += 1
        end = tok[3]
        if paren:
            close = tokens[self.i]
            if close[1] != ")":
                raise self.refuse("expected ')' after the exponent {where}", close[2], close[3])
            self.i += 1
            end = close[3]
        return int(value), end

    def unknown_name(self, tok: _Token) -> None:
        name = tok[1]
        if self.tokens[self.i + 1][1] == "(":
            raise self.refuse(
                f"the function call {name}(...) {{where}} is not allowed: only + - * / ** and parentheses",
                tok[2],
                tok[3],
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
        allowed = ": a number contains no names"
        if self.names:
            allowed = f"; allowed names: {', '.join(self.names)}"
        raise self.refuse(f"unknown name {name!r} {{where}}{hint}{allowed}", tok[2], tok[3])

    def atom(self, depth: int) -> Expr:
        """atom = number | name | "(" expression ")" """
        tok = self.tokens[self.i]
        kind = tok[0]
        if kind == _NUM:
            self.i += 1
            assert tok[4] is not None
            return Number(tok[4], tok[2], tok[3])
        if kind == _NAME:
            name_kind = self.names.get(tok[1])
            if name_kind is None:
                self.unknown_name(tok)
            self.i += 1
            return Name(tok[1], name_kind or "", tok[2], tok[3])
        if tok[1] == "(":
            if depth >= MAX_DEPTH:
                raise self.refuse(
                    f"nesting deeper than {MAX_DEPTH} levels {{where}} (MAX_DEPTH)", tok[2], tok[3]
                )
            self.i += 1
            inner = self.expression(depth + 1)
            close = self.tokens[self.i]
            if close[1] != ")":
                if close[0] == _END:
                    raise self.refuse("the '(' {where} is never closed", tok[2], tok[3])
                raise self.refuse(f"expected ')' {{where}}, got {close[1]!r}", close[2], close[3])
            self.i += 1
            return _respan(inner, tok[2], close[3])
        if kind == _END:
            prev = self.tokens[self.i - 1] if self.i else tok
            raise self.refuse(f"expected a number, a name or '(' after {prev[1]!r} {{where}}", tok[2], tok[3])
        raise self.refuse(
            f"unexpected {tok[1]!r} {{where}}: expected a number, a name or '('", tok[2], tok[3]
        )


def _respan(node: Expr, start: int, end: int) -> Expr:
    """The node with the span of its parentheses (for messages that quote it)."""
    return dataclasses.replace(node, start=start, end=end)


# -- algebras ------------------------------------------------------------------------------

T = TypeVar("T")


class Algebra(Protocol[T]):
    """What :func:`evaluate` needs: the eight operations of the grammar.

    An algebra refuses an operation by raising :class:`Refusal`; evaluate
    adds where.  ``variable`` receives every declared name, variables and
    parameters alike (:attr:`Name.kind` tells them apart in the tree).
    :func:`evaluate` never uses a value twice, so an algebra may update its
    operands in place.
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

_Packed = dict[int, Any]  # packed monomial -> non-zero flint.fmpq

if hasattr(flint.fmpq, "height_bits"):

    def _height(c: Any) -> int:
        return int(c.height_bits())

else:  # pragma: no cover - older python-flint

    def _height(c: Any) -> int:
        return max(abs(int(c.p)).bit_length(), int(c.q).bit_length())


_FLINT_LIMIT = flint.fmpz(_LIMIT)
_ONE = flint.fmpq(1)


class PolynomialAlgebra:
    """Exact sparse polynomials over Q in ``variables``, with every bound checked.

    Internally a polynomial is a dict from a *packed* monomial (the exponent
    of variable ``i`` in bits ``8i..8i+7``, so multiplying monomials adds
    integers) to a non-zero ``flint.fmpq``; :meth:`to_dict` gives the public
    form, exponent tuple to :class:`~fractions.Fraction`.  Every coefficient
    is checked against :data:`MAX_DIGITS`, every degree against
    ``max_degree`` (default :data:`MAX_DEGREE`) and the work against
    ``budget`` (default :data:`MAX_WORK`).  Division is by non-zero
    constants only.

    Examples
    --------
    >>> alg = PolynomialAlgebra(("x",))
    >>> alg.to_dict(evaluate(parse_expression("(x - 1/2)^2", variables=("x",)), alg))
    {(2,): Fraction(1, 1), (1,): Fraction(-1, 1), (0,): Fraction(1, 4)}
    """

    def __init__(
        self, variables: Sequence[str], *, max_degree: int = MAX_DEGREE, budget: int = MAX_WORK
    ) -> None:
        if not 0 <= max_degree < 256:
            raise ValueError(f"max_degree must be in [0, 255], got {max_degree}")
        self.variables = tuple(variables)
        self.shift = {v: 8 * i for i, v in enumerate(self.variables)}
        self.max_degree = max_degree
        self.budget = budget
        self.work = 0
        self._degrees: dict[int, int] = {0: 0}

    # -- bookkeeping
    def _key_degree(self, key: int) -> int:
        d = self._degrees.get(key)
        if d is None:
            d, k = 0, key
            while k:
                d += k & 255
                k >>= 8
            self._degrees[key] = d
        return d

    def degree(self, p: _Packed) -> int:
        """Total degree (0 for the zero polynomial)."""
        return max(map(self._key_degree, p), default=0)

    def _charge(self, steps: int, coefficients: Iterable[Any], *, counted: bool = False) -> None:
        """Count ``steps`` operations, weighted by the size of the coefficients
        they produced (``counted``: their unweighted count was charged before),
        and check those coefficients against MAX_DIGITS."""
        bits = 0
        for c in coefficients:
            h = _height(c)
            if h >= _LIMIT_BITS - 1 and (c.q >= _FLINT_LIMIT or abs(c.p) >= _FLINT_LIMIT):
                raise Refusal(f"a number with more than {MAX_DIGITS} digits (MAX_DIGITS) arises {{where}}")
            if h > bits:
                bits = h
        self.work += steps * ((0 if counted else 1) + 2 * bits // WORK_BITS)
        if self.work > self.budget:
            raise Refusal(
                f"more than {self.budget} arithmetic steps (MAX_WORK) {{where}}: "
                "the input is too costly to expand"
            )

    def to_dict(self, p: _Packed) -> Polynomial:
        """The public form: exponent tuple (over ``variables``) -> Fraction."""
        out: Polynomial = {}
        for key, c in p.items():
            out[tuple((key >> self.shift[v]) & 255 for v in self.variables)] = Fraction(int(c.p), int(c.q))
        return out

    @staticmethod
    def _constant_of(p: _Packed) -> Any:
        """The value of a constant polynomial, or None if it is not constant."""
        if not p:
            return flint.fmpq(0)
        if len(p) == 1 and 0 in p:
            return p[0]
        return None

    # -- the operations
    def constant(self, value: Fraction) -> _Packed:
        return {0: flint.fmpq(value.numerator, value.denominator)} if value else {}

    def variable(self, name: str) -> _Packed:
        if name not in self.shift:
            raise Refusal(f"{name!r} {{where}} is not a variable of this polynomial")
        if self.max_degree < 1:
            raise Refusal(f"the variable {name!r} {{where}}: only a constant is allowed here")
        return {1 << self.shift[name]: _ONE}

    def add(self, a: _Packed, b: _Packed) -> _Packed:
        if len(b) > len(a):
            a, b = b, a
        for k, c in b.items():
            v = a.get(k)
            if v is None:
                a[k] = c
            else:
                s = v + c
                if s:
                    a[k] = s
                else:
                    del a[k]
        self._charge(max(1, len(b)), (a[k] for k in b if k in a))
        return a

    def neg(self, a: _Packed) -> _Packed:
        for k, c in a.items():
            a[k] = -c
        self._charge(1, ())
        return a

    def sub(self, a: _Packed, b: _Packed) -> _Packed:
        return self.add(a, self.neg(b))

    def mul(self, a: _Packed, b: _Packed) -> _Packed:
        if not a or not b:
            return {}
        if len(a) < len(b):
            a, b = b, a
        if len(b) == 1 and 0 in b:  # by a constant
            c = b[0]
            out = {k: v * c for k, v in a.items()}
            self._charge(len(a), out.values())
            return out
        d = self.degree(a) + self.degree(b)
        if d > self.max_degree:
            raise Refusal(
                f"a product of degree {d} {{where}}: more than the {self.max_degree} allowed (MAX_DEGREE)"
            )
        self._charge(len(a) * len(b), ())  # refuse before the work, not after
        out = {}
        get = out.get
        for kb, cb in b.items():
            for ka, ca in a.items():
                k = ka + kb
                v = get(k)
                out[k] = ca * cb if v is None else v + ca * cb
        out = {k: v for k, v in out.items() if v}
        self._charge(len(a) * len(b), out.values(), counted=True)
        return out

    def div(self, a: _Packed, b: _Packed) -> _Packed:
        c = self._constant_of(b)
        if c is None:
            names = ", ".join(self.variables)
            raise Refusal(f"division by an expression in {names} {{where}}: the result is not a polynomial")
        if not c:
            raise Refusal("division by zero {where}")
        return self.mul(a, {0: 1 / c})

    def pow(self, a: _Packed, n: int) -> _Packed:
        if n == 0:
            return {0: _ONE}
        if not a:
            return {}
        c = self._constant_of(a)
        if c is not None:
            if (_height(c) - 1) * n >= _LIMIT_BITS:
                raise Refusal(f"a power with more than {MAX_DIGITS} digits (MAX_DIGITS) {{where}}")
            out = {0: c**n}
            self._charge(1 + n.bit_length(), out.values())
            return out
        d = self.degree(a) * n
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
        if isinstance(node, Product):
            acc = _eval(node.factors[0][1], alg)
            for op, factor in node.factors[1:]:
                value = _eval(factor, alg)
                try:
                    acc = alg.mul(acc, value) if op == "*" else alg.div(acc, value)
                except Refusal as exc:
                    raise _Located(str(exc), factor.start if op == "/" else node.start, factor.end) from None
            return acc
        if isinstance(node, Sum):
            acc = _eval(node.terms[0][1], alg)
            for op, term in node.terms[1:]:
                value = _eval(term, alg)
                try:
                    acc = alg.add(acc, value) if op == "+" else alg.sub(acc, value)
                except Refusal as exc:
                    raise _Located(str(exc), node.start, term.end) from None
            return acc
        if isinstance(node, Power):
            return alg.pow(_eval(node.base, alg), node.exponent)
        if isinstance(node, Neg):
            return alg.neg(_eval(node.operand, alg))
        if isinstance(node, Equation):
            return alg.sub(_eval(node.lhs, alg), _eval(node.rhs, alg))
    except Refusal as exc:
        raise _Located(str(exc), node.start, node.end) from None
    raise TypeError(f"not a node of the syntax tree: {node!r}")


# -- the public readers ----------------------------------------------------------------------


def _check_text(text: Any, what: str) -> str:
    if not isinstance(text, str):
        raise EquationError(f"{what}: expected a string, got {type(text).__name__}", text)
    text = str.__str__(text)  # a plain copy of a subclass: its own __len__ or methods never run
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
    quadric_contact.exact.errors.EquationError: unknown name 'x2' at position 1 (did you mean ...
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
            alg = PolynomialAlgebra(variables)
            try:
                if alg.degree(_eval(t, alg)) > max_degree:
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
    if not 0 <= max_degree <= MAX_DEGREE:
        raise ValueError(f"max_degree must be in [0, MAX_DEGREE = {MAX_DEGREE}], got {max_degree}")
    what = what or ("equation" if equation else "polynomial")
    tree = parse_expression(text, variables, equation=equation, what=what)
    alg = PolynomialAlgebra(variables)
    packed = evaluate(tree, alg, text=text, what=what)
    degree = alg.degree(packed)
    if degree > max_degree:
        start, end = _locate_degree(tree, variables, max_degree)
        raise _refuse(
            text,
            f"degree {degree} after expansion {{where}}; at most {max_degree} is allowed here",
            start,
            end,
            what=what,
        )
    return alg.to_dict(packed)


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
    degree = max((e[0] for e in poly), default=0)
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
