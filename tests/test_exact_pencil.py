"""The exact mode's compiled pencil (quadric_contact.modes.kernels.exact_pencil): the same values of
c0 .. c4 (and so of the Deltas) as the generated expansion on Python integers, and the same
codes as the fmpz backend, on random float pairs, extreme digit ranges, the hard cases and
exact rational input."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

from quadric_contact._generated import formulas, kernels
from quadric_contact.modes import ExactMode
from quadric_contact.modes.kernels.exact_pencil import (
    MAX_DIGITS,
    pencil_coefficients_dyadic,
    pencil_coefficients_int,
)
from quadric_contact.modes.predicates import corollary_10
from quadric_contact.modes.stacks.batch import as_stack
from quadric_contact.modes.stacks.integers import dyadic_rows, integer_rows
from quadric_contact.modes.stacks.pairs import Pairs
from quadric_contact.testing.hardcases import hard_cases
from quadric_contact.testing.samples import random_pairs


def _generated(e_cols: list[np.ndarray], q_cols: list[np.ndarray]) -> list[np.ndarray]:
    return list(formulas.pencil_coefficients(*e_cols, *q_cols))


def _assert_same(got: list[np.ndarray], want: list[np.ndarray]) -> None:
    assert len(got) == len(want) == 5
    for k, (g, w) in enumerate(zip(got, want, strict=True)):
        assert g.shape == w.shape
        assert all(type(x) is int for x in g), k
        assert [int(x) for x in g] == [int(x) for x in w], f"c{k}"
    # The Deltas follow from the coefficients; check them as values too.
    for dg, dw in zip(kernels.paper_deltas_compact(*got), kernels.paper_deltas_compact(*want), strict=True):
        assert [int(x) for x in dg] == [int(x) for x in dw]


def _mode_pencil(E: object, Q: object) -> tuple[list[np.ndarray], list[np.ndarray], list[np.ndarray]]:
    """(int-backend coefficients, generated coefficients on integer_rows, E columns)."""
    se, sq = as_stack(E, "E"), as_stack(Q, "Q")
    n = len(se)
    pairs = Pairs(se, sq, n)
    rows = np.arange(n)
    e_cols, c = ExactMode("int").pencil(pairs, rows, rows, rows, rows)
    want_e = integer_rows(se, rows)
    want = _generated(want_e, integer_rows(sq, rows))
    for a, b in zip(e_cols, want_e, strict=True):
        assert [int(x) for x in a] == [int(x) for x in b]
    return c, want, e_cols


def test_random_float_pairs() -> None:
    E, Q, _ = random_pairs(600, np.random.default_rng(11))
    c, want, _ = _mode_pencil(E, Q)
    _assert_same(c, want)


@pytest.mark.parametrize("spread", [0, 11, 40, 300, 1300])
def test_extreme_dyadic_digits(spread: int) -> None:
    """Mantissas up to 2^53 - 1 in magnitude, zeros, and shifts up to ``spread`` bits (one
    to 51 digits an entry): every digit count, and the Python fallback beyond MAX_DIGITS."""
    rng = np.random.default_rng(spread)
    n = 60
    me = rng.integers(-(2**53) + 1, 2**53, (n, 10))
    mq = rng.integers(-(2**53) + 1, 2**53, (n, 10))
    me[:5] = 2**53 - 1
    mq[5:10] = -(2**53) + 1
    me[rng.random((n, 10)) < 0.2] = 0
    se = rng.integers(0, spread + 1, (n, 10))
    sq = rng.integers(0, spread + 1, (n, 10))
    se[:3] = spread
    got = pencil_coefficients_dyadic(me, se, mq, sq)
    e_cols = [me[:, k].astype(object) << se[:, k].astype(object) for k in range(10)]
    q_cols = [mq[:, k].astype(object) << sq[:, k].astype(object) for k in range(10)]
    _assert_same(got, _generated(e_cols, q_cols))


@pytest.mark.parametrize("bits", [1, 25, 26, 62, 77, 78, 200, 26 * MAX_DIGITS - 1, 26 * MAX_DIGITS + 5])
def test_integer_entries_at_digit_boundaries(bits: int) -> None:
    rng = np.random.default_rng(bits)
    n = 20
    top = 2**bits - 1
    e = np.array([[int(v) for v in row] for row in rng.integers(-(2**62), 2**62, (n, 10))], dtype=object)
    q = np.array([[int(v) for v in row] for row in rng.integers(-(2**62), 2**62, (n, 10))], dtype=object)
    e = e * top // 2**62
    q = q * top // 2**62
    e[0] = top
    q[1] = -top
    e[2] = 0
    got = pencil_coefficients_int(e, q)
    _assert_same(got, _generated([e[:, k] for k in range(10)], [q[:, k] for k in range(10)]))


def test_int64_input_and_empty() -> None:
    rng = np.random.default_rng(3)
    e = rng.integers(-(2**63) + 1, 2**63 - 1, (30, 10))
    q = rng.integers(-(2**63) + 1, 2**63 - 1, (30, 10))
    got = pencil_coefficients_int(e, q)
    _assert_same(
        got,
        _generated([e[:, k].astype(object) for k in range(10)], [q[:, k].astype(object) for k in range(10)]),
    )
    assert all(c.shape == (0,) for c in pencil_coefficients_int(e[:0], q[:0]))
    with pytest.raises(ValueError):
        pencil_coefficients_int(e[:, :9], q[:, :9])


def test_dyadic_rows_are_integer_rows() -> None:
    E, _, _ = random_pairs(200, np.random.default_rng(5))
    stack = as_stack(E, "E")
    rows = np.arange(len(stack))
    m, shift = dyadic_rows(stack, rows)
    built = [m[:, k].astype(object) << shift[:, k].astype(object) for k in range(10)]
    for a, b in zip(built, integer_rows(stack, rows), strict=True):
        assert [int(x) for x in a] == [int(x) for x in b]


def _hard_stacks(exact_input: bool) -> tuple[np.ndarray, np.ndarray]:
    cases = [h for h in hard_cases() if h.exact_input is exact_input]
    assert cases
    E = np.stack([h.matrices()[0] for h in cases])
    Q = np.stack([h.matrices()[1] for h in cases])
    return E, Q


@pytest.mark.parametrize("exact_input", [False, True])
def test_hard_cases_values_and_codes(exact_input: bool) -> None:
    E, Q = _hard_stacks(exact_input)
    c, want, _ = _mode_pencil(E, Q)
    _assert_same(c, want)
    assert (corollary_10(E, Q, mode=ExactMode("int")) == corollary_10(E, Q, mode=ExactMode("fmpz"))).all()


def test_fraction_input() -> None:
    """Exact rational input keeps to integer_rows (common denominators) and gives the
    generated values."""
    E, Q, _ = random_pairs(40, np.random.default_rng(8))
    rng = np.random.default_rng(9)
    Ef = E.astype(object)
    Qf = Q.astype(object)
    for M in (Ef, Qf):
        for p in range(len(M)):
            for i in range(4):
                for j in range(i, 4):
                    v = Fraction(float(M[p, i, j])) + Fraction(
                        int(rng.integers(1, 99)), int(rng.integers(1, 10**6))
                    )
                    M[p, i, j] = M[p, j, i] = v
    c, want, _ = _mode_pencil(Ef, Qf)
    _assert_same(c, want)
    assert (corollary_10(Ef, Qf, mode=ExactMode("int")) == corollary_10(Ef, Qf, mode=ExactMode("fmpz"))).all()


def test_codes_agree_with_fmpz_backend_on_random_pairs() -> None:
    E, Q, _ = random_pairs(400, np.random.default_rng(21))
    assert (corollary_10(E, Q, mode=ExactMode("int")) == corollary_10(E, Q, mode=ExactMode("fmpz"))).all()
