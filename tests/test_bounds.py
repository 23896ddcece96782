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
