"""The exact mode's Delta signs: binary64 with a rigorous bound first, the integers where that
cannot tell.  Never a wrong sign: checked against the exact integer Deltas."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from quadric_contact._generated import kernels
from quadric_contact.modes.numbers.objects import ExactMode, filtered_delta_signs

_UNC = 2


def _exact(c: list[int]) -> list[int]:
    return [(v > 0) - (v < 0) for v in kernels.paper_deltas_compact(*c)]


def _cols(rows: list[list[int]]) -> list[np.ndarray]:
    arr = np.empty((len(rows), 5), dtype=object)
    for i, r in enumerate(rows):
        arr[i] = r
    return [arr[:, k] for k in range(5)]


def _poly(roots: list[int], scale: int) -> list[int]:
    """Coefficients c0 .. c4 (constant first) of scale * prod (x - r)."""
    c = [scale]
    for r in roots:
        c = [0, *c]
        for k in range(len(c) - 1):
            c[k] -= r * c[k + 1]
    return c


coefficient = st.one_of(st.just(0), st.integers(-(2**400), 2**400), st.integers(-(2**60), 2**60))


@settings(max_examples=300, deadline=None)
@given(st.lists(st.lists(coefficient, min_size=5, max_size=5), min_size=1, max_size=20))
def test_filtered_signs_are_never_wrong(rows):
    got = filtered_delta_signs(_cols(rows))
    for r, row in zip(got, rows, strict=True):
        for g, want in zip(r, _exact(row), strict=True):
            assert g in (want, _UNC)


@settings(max_examples=200, deadline=None)
@given(
    st.lists(st.integers(-50, 50), min_size=3, max_size=3),
    st.integers(1, 2**200),
    st.integers(-(2**30), 2**30),
)
def test_double_roots_are_never_read_as_simple(roots, scale, nudge):
    """Delta_4 = 0 exactly at a double root: the bound must not give it a sign; nudged by a
    tiny amount it has one, which the filter gives right or leaves to the integers."""
    c = _poly([roots[0], roots[0], roots[1], roots[2]], scale)
    got = filtered_delta_signs(_cols([c]))[0]
    assert _exact(c)[2] == 0 and got[2] in (0, _UNC)
    c2 = [c[0] + nudge, *c[1:]]
    got2 = filtered_delta_signs(_cols([c2]))[0]
    for g, want in zip(got2, _exact(c2), strict=True):
        assert g in (want, _UNC)


def test_out_of_range_coefficients_go_to_the_integers():
    huge = [2**1100 + 1, -(2**1099), 3 * 2**1098, 2**1100, 7]
    tiny = [2**200, 1, 0, 0, 1]  # 1 is 2^-200 of the largest: below COEFFICIENT_MIN once scaled
    got = filtered_delta_signs(_cols([huge, tiny]))
    assert (got == _UNC).all()
    mode = ExactMode()
    assert (mode.delta_signs(_cols([huge, tiny])) == np.array([_exact(huge), _exact(tiny)])).all()


def test_the_exact_mode_reads_every_sign_right():
    rng = np.random.default_rng(5)
    rows = [[int(v) for v in rng.integers(-(2**62), 2**62, size=5)] for _ in range(200)]
    rows += [_poly([1, 1, 2, 3], 5), _poly([-2, -2, -2, 7], 2**90), [0, 0, 0, 0, 0], [0, 0, 1, 0, 1]]
    got = ExactMode().delta_signs(_cols(rows))
    assert [list(r) for r in got] == [_exact(r) for r in rows]
    assert (filtered_delta_signs(_cols(rows[:200])) != _UNC).mean() > 0.9  # the filter does settle
