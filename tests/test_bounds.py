"""Every accepted input is answered within a documented bound, or refused up front.

One test (or a few) per way of making the package hang, exhaust memory, abort,
crash while printing, or load code from a planted file, with inputs that the
parser accepts.  None of them measures time: where the defect was slowness the
test observes the work done (calls, terms, sizes) or that the refusal came
before the work.  The subprocess fuzzer is in ``tests/test_hostile_fuzz.py``.
"""

from __future__ import annotations

import re
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
