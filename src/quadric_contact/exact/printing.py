"""Text of exact numbers of any size, and of user-supplied names.

Python refuses to convert an integer of more than 4300 digits to text
(``sys.get_int_max_str_digits``), and its conversion is quadratic below that.
The package accepts numbers of up to :data:`~quadric_contact.exact.reading.MAX_DIGITS`
digits, and what it derives from them (a characteristic polynomial, a
discriminant) is larger still, so every exact number the package prints or
serialises goes through here: small integers as Python writes them, larger ones
through FLINT, which has no limit and is quasi-linear.  The interpreter's limit
is left as it is (it guards ``int(text)`` in the caller's own code).

Names that users give (scenes, ellipsoids, pieces) reach reports printed on a
terminal: :func:`safe_text` escapes the characters that would not print as
themselves.
"""

from __future__ import annotations

import unicodedata
from fractions import Fraction
from typing import Any

import flint

__all__ = [
    "JSON_INTEGER_BITS",
    "fraction_repr",
    "fraction_text",
    "int_text",
    "json_number",
    "safe_text",
    "unsafe_characters",
]

_SMALL_BITS = 4096
"""Integers below ``2**_SMALL_BITS`` (1233 digits) are written by Python itself."""

JSON_INTEGER_BITS = 53
"""An integer in :func:`json_number` stays a JSON number up to this many bits
(the integers every JSON reader holds exactly); a larger one is a string, as a
fraction is."""


def int_text(n: int) -> str:
    """``str(n)`` for an integer of any size.

    >>> len(int_text(10**5000))
    5001
    """
    n = int(n)
    if n.bit_length() < _SMALL_BITS:
        return str(n)
    return str(flint.fmpz(n).str())


def fraction_text(x: Any) -> str:
    """``str(x)`` of a :class:`~fractions.Fraction` (or an integer) of any size:
    ``"p/q"``, or ``"p"`` when the denominator is 1.

    >>> fraction_text(Fraction(-3, 4)), fraction_text(Fraction(10**4400)) == "1" + "0" * 4400
    ('-3/4', True)
    """
    x = Fraction(x)
    if x.denominator == 1:
        return int_text(x.numerator)
    return f"{int_text(x.numerator)}/{int_text(x.denominator)}"


def fraction_repr(x: Any) -> str:
    """``repr(x)`` of a :class:`~fractions.Fraction` of any size.

    >>> fraction_repr(Fraction(1, 3))
    'Fraction(1, 3)'
    """
    x = Fraction(x)
    return f"Fraction({int_text(x.numerator)}, {int_text(x.denominator)})"


def json_number(x: Any) -> Any:
    """A JSON-ready exact value: an integer of at most :data:`JSON_INTEGER_BITS`
    bits as itself, any other rational as its text (``"p/q"`` or the digits of a
    large integer); anything that is not a Fraction or an int is returned as is.

    >>> json_number(Fraction(6, 2)), json_number(Fraction(1, 3)), json_number(2**60)
    (3, '1/3', '1152921504606846976')
    """
    if isinstance(x, bool) or not isinstance(x, (int, Fraction)):
        return x
    x = Fraction(x)
    if x.denominator == 1 and x.numerator.bit_length() <= JSON_INTEGER_BITS:
        return int(x.numerator)
    return fraction_text(x)


def _escape_char(c: str) -> str:
    if c in "\n\r\t":
        return {"\n": "\\n", "\r": "\\r", "\t": "\\t"}[c]
    code = ord(c)
    return f"\\x{code:02x}" if code < 0x100 else f"\\u{code:04x}" if code < 0x10000 else f"\\U{code:08x}"


def unsafe_characters(text: str) -> list[str]:
    """The characters of ``text`` that a terminal or a reader would not show as
    themselves: control characters (``Cc``: ESC, CR, LF, ...) and format
    characters (``Cf``: the bidi overrides U+202A-U+202E and U+2066-U+2069,
    zero-width characters).

    >>> unsafe_characters("bee\\x1b[2J\\u202e")
    ['\\x1b', '\\u202e']
    """
    return [c for c in text if unicodedata.category(c) in ("Cc", "Cf")]


def safe_text(text: Any, *, keep_newlines: bool = False) -> str:
    """``text`` with every character of :func:`unsafe_characters` written as an
    escape (``\\x1b``, ``\\n``, ``\\u202e``), so that a user-supplied name cannot
    move the cursor, clear the screen, reverse the rest of a line or start a
    line of its own in a report.  ``keep_newlines`` keeps ``\\n`` (for text
    made of several lines whose names were escaped already).

    >>> safe_text("bee\\n  first contact: t = 0")
    'bee\\\\n  first contact: t = 0'
    """
    text = str(text)
    if not any(unicodedata.category(c) in ("Cc", "Cf") for c in text):
        return text
    return "".join(
        c if (keep_newlines and c == "\n") or unicodedata.category(c) not in ("Cc", "Cf") else _escape_char(c)
        for c in text
    )
