"""The three-valued sign (:mod:`quadric_contact.modes.kernels.signs`): what it certifies is the
exact sign (Fractions of the same binary64 numbers), it is the if-chain of its definition on
every special value (zeros of both signs, subnormals, infinities, NaN, negative bounds), and its
three forms agree: compiled into a kernel, its Python function on scalars, and on numpy
columns (one source, two backends: each primitive is the plain side of a pair)."""

from __future__ import annotations

import itertools
import math
from fractions import Fraction

import numpy as np
import pytest

from quadric_contact.modes.codes import UNCERTAIN
from quadric_contact.modes.decision import answers
from quadric_contact.modes.kernels._jit import HAVE_NUMBA, compiled, numba, plain
from quadric_contact.modes.kernels.signs import (
    columns,
    dd_sign_within,
    plain_sign,
    sign_index,
    sign_within,
)

PRIMITIVES = (sign_within, plain_sign, dd_sign_within, sign_index)

TINY = 5e-324
SPECIAL = (
    -math.inf, -1e308, -1.0, -0.5, -TINY, -0.0, 0.0, TINY, 0.5, 1.0, 1e308, math.inf, math.nan,
    1.0 + 2**-52, 1.0 - 2**-53, -(1.0 + 2**-52),
)  # fmt: skip
"""Values and bounds: each bound is also met as a value, so ``v = +-err`` is among the pairs."""


def _definition(v: float, err: float) -> int:
    """The definition, as the kernels wrote it before it had one home."""
    if v > err:
        return 1
    if v < -err:
        return -1
    if err == 0.0:
        return 0
    return UNCERTAIN


def _dd_definition(hi: float, lo: float, err: float) -> int:
    if (hi > err) or (hi == err and lo > 0.0):
        return 1
    if (hi < -err) or (hi == -err and lo < 0.0):
        return -1
    if err == 0.0:
        return 0
    return UNCERTAIN


PAIRS = list(itertools.product(SPECIAL, SPECIAL))


def test_the_primitives_are_plain_functions_with_a_compiled_side():
    """The names are the Python functions (nothing to unwrap for numpy or Python callers);
    compiled code gets their ``forceinline`` compiled side."""
    for p in PRIMITIVES:
        assert type(p).__name__ == "function", p
        if HAVE_NUMBA:
            side = compiled(p)
            assert side.py_func is p
            assert side.targetoptions.get("forceinline"), p
        else:
            assert compiled(p) is p


def test_sign_within_is_its_definition_on_every_special_value():
    f = sign_within
    for v, err in PAIRS:
        assert f(v, err) == _definition(v, err), (v, err)
        assert plain(sign_within)(v, err) == f(v, err)


def test_the_cases_of_the_definition():
    f = sign_within
    assert f(0.5, 1.0) == UNCERTAIN  # within the bound: either sign
    assert f(-1.0, 1.0) == UNCERTAIN  # on the bound: the exact value may be zero
    assert f(1.0 + 2**-52, 1.0) == 1  # the next binary64 number above the bound
    assert f(-(1.0 + 2**-52), 1.0) == -1
    assert f(0.0, 0.0) == 0  # an exact zero
    assert f(-0.0, 0.0) == 0
    assert f(TINY, 0.0) == 1  # exact: the smallest positive number is positive
    assert f(math.nan, 1.0) == UNCERTAIN
    assert f(1.0, math.nan) == UNCERTAIN
    assert f(math.inf, 1e308) == 1


def test_plain_sign_is_sign_within_a_zero_bound():
    f, g = plain_sign, sign_within
    for v in SPECIAL:
        assert f(v) == g(v, 0.0) == _definition(v, 0.0), v
    assert f(math.nan) == 0


def test_a_certified_sign_is_the_exact_sign():
    """Wherever the sign is certain, every exact value within the bound has it."""
    rng = np.random.default_rng(7)
    f = sign_within
    seen = set()
    for _ in range(2000):
        v = float(rng.normal()) * 2.0 ** int(rng.integers(-30, 30)) if rng.random() > 0.05 else 0.0
        err = abs(v) * float(rng.choice([0.5, 1.0, 2.0, 0.0]))
        s = f(v, err)
        seen.add(s)
        if s != UNCERTAIN:
            for x in (Fraction(v) - Fraction(err), Fraction(v) + Fraction(err)):
                assert (x > 0) - (x < 0) == s, (v, err)
    assert seen == {-1, 0, 1, UNCERTAIN}


def test_dd_sign_within_reads_the_double_double_exactly():
    """Signs of ``hi + lo`` (``hi = RN(hi + lo)``) against bounds at and next to ``|hi|``: the
    answer is 1 (-1) exactly when ``hi + lo > err`` (``< -err``) in rational arithmetic."""
    f = dd_sign_within
    rng = np.random.default_rng(11)
    seen = set()
    for _ in range(3000):
        hi = float(rng.normal())
        lo = float(rng.choice([-1.0, 0.0, 1.0])) * math.ulp(hi) * float(rng.choice([0.125, 0.25]))
        assert hi + lo == hi
        a = abs(hi)
        err = float(rng.choice([a, math.nextafter(a, 0.0), math.nextafter(a, math.inf), 0.0, a / 2]))
        s = f((hi, lo), err)
        seen.add(s)
        x = Fraction(hi) + Fraction(lo)
        assert s == _dd_definition(hi, lo, err)
        if err != 0.0:
            assert (s == 1) == (x > err) and (s == -1) == (x < -err), (hi, lo, err)
        else:
            assert s == (x > 0) - (x < 0)
    assert seen == {-1, 1, UNCERTAIN}  # hi is never zero here: the exact zero is below
    # the words exactly at the bound
    assert f((1.0, 2**-60), 1.0) == 1
    assert f((1.0, 0.0), 1.0) == UNCERTAIN
    assert f((1.0, -(2**-60)), 1.0) == UNCERTAIN
    assert f((-1.0, -(2**-60)), 1.0) == -1
    assert f((0.0, 0.0), 0.0) == 0


def test_sign_index_is_the_index_of_the_tables():
    f = sign_index
    assert [f(s) for s in (-1, 0, 1, UNCERTAIN)] == [0, 1, 2, 3]
    assert answers.sign_index is f
    assert sign_index(np.array([-1, 0, 1, UNCERTAIN], dtype=np.int8)).tolist() == [0, 1, 2, 3]
    signs = np.array(list(itertools.product((-1, 0, 1, UNCERTAIN), repeat=3)), dtype=np.int8)
    want = [answers.CONTACT_TABLE[f(a) + 4 * f(b) + 16 * f(c)] for a, b, c in signs.tolist()]
    assert answers.contact_from_signs(*signs.T).tolist() == want


def test_columns_agree_with_the_scalars():
    v = np.array([p[0] for p in PAIRS])
    err = np.array([p[1] for p in PAIRS])
    with np.errstate(invalid="ignore"):
        got = columns(sign_within)(v, err)
        plain_got = columns(plain_sign)(v)
    assert got.dtype == np.int8
    assert got.tolist() == [_definition(a, b) for a, b in PAIRS]
    assert plain_got.tolist() == [_definition(a, 0.0) for a in v.tolist()]
    lo = np.where(np.isfinite(v), v * 2.0**-60, 0.0)
    dd_got = columns(dd_sign_within)((v, lo), err)
    words = zip(v.tolist(), lo.tolist(), err.tolist(), strict=True)
    assert dd_got.tolist() == [_dd_definition(a, b, c) for a, b, c in words]


@pytest.mark.skipif(not HAVE_NUMBA, reason="numba is not installed")
def test_compiled_into_a_kernel_it_gives_the_same_signs():
    """Inlined into a compiled loop (as the kernels take it, from this module's globals), the
    primitives give what their Python functions give."""

    @numba.njit
    def kernel(v, err, lo, out):  # pragma: no cover - compiled
        for i in range(v.shape[0]):
            out[0, i] = sign_within(v[i], err[i])
            out[1, i] = plain_sign(v[i])
            out[2, i] = dd_sign_within((v[i], lo[i]), err[i])
            out[3, i] = sign_index(sign_within(v[i], err[i]))

    v = np.array([p[0] for p in PAIRS])
    err = np.array([p[1] for p in PAIRS])
    lo = np.where(np.isfinite(v), v * 2.0**-60, 0.0)
    out = np.empty((4, v.shape[0]), dtype=np.int64)
    kernel(v, err, lo, out)
    assert kernel.signatures  # compiled, not run by Python
    with np.errstate(invalid="ignore"):
        assert out[0].tolist() == columns(sign_within)(v, err).tolist()
        assert out[1].tolist() == columns(plain_sign)(v).tolist()
        assert out[2].tolist() == columns(dd_sign_within)((v, lo), err).tolist()
        assert out[3].tolist() == (columns(sign_within)(v, err) + 1).tolist()
