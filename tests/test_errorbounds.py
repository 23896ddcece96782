"""Every bound of the float filter holds, checked against exact rational arithmetic.

The filter's quantities come from ``float64.filter_quantities`` (the numpy variant,
which the compiled kernels match code for code: see test_modes.py); the exact
values from Fractions of the very same binary64 inputs.
"""

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from quadric_contact._generated import formulas, kernels
from quadric_contact.exact.entries import ENTRY_INDICES
from quadric_contact.modes.kernels import errorbounds as eb
from quadric_contact.modes.kernels.numpy_backend import filter_quantities
from quadric_contact.testing.hardcases import hard_cases
from quadric_contact.testing.samples import random_pairs
from quadric_contact.testing.strategies import ellipsoids, quadrics

U = eb.UNIT_ROUNDOFF


def _upper_exact(M):
    return [Fraction(M[i][j]) for i, j in ENTRY_INDICES]


def _exact_coefficients(E, Q):
    """c0..c4 for the paper's sign of E (odd ones negated when e00 < 0), exactly."""
    e, q = _upper_exact(E), _upper_exact(Q)
    c = list(formulas.pencil_coefficients(*e, *q))
    if e[0] < 0:
        c[1], c[3] = -c[1], -c[3]
    return c


def _check_pairs(E, Q, *, rounded_from=None):
    """Assert every bound of filter_quantities for the pairs (E[k], Q[k]).

    ``rounded_from``: the exact rational matrices that E, Q are the roundings of."""
    fq = filter_quantities(E, Q, rounded=rounded_from is not None, same_ok=rounded_from is None)
    checked = 0
    for k in range(E.shape[0]):
        exact_src = (E[k], Q[k]) if rounded_from is None else rounded_from[k]
        c = _exact_coefficients(*exact_src)
        for t in range(5):
            assert abs(Fraction(fq["c"][t][k]) - c[t]) <= Fraction(fq["r"][t][k]), (k, t)
        if fq["outside"][k]:
            continue
        cs = [v * Fraction(fq["s"][t][k]) for t, v in enumerate(c)]
        for t in range(5):
            assert abs(Fraction(fq["x"][t][k]) - cs[t]) <= Fraction(fq["y"][t][k])
        exact_d = formulas.paper_deltas(*cs)
        for j in range(3):
            err = abs(Fraction(fq["d"][j][k]) - exact_d[j])
            if fq["same"][k] and j == 2:
                assert exact_d[2] == 0  # Delta_4 identically zero for equal quadratic parts
                continue
            assert err <= Fraction(fq["bound_absolute"][j][k]), (k, j)
            if fq["rho"][k] <= eb.RHO_MAX:
                assert err <= Fraction(fq["bound_relative"][j][k]), (k, j)
        checked += 1
    return checked


def test_constants_are_derived_and_rounded_up():
    assert eb.gamma(3) == 3 * U / (1 - 3 * U)
    for n in (1, 10, 22):
        k = eb.program_errbound(n, n, 4)
        assert Fraction(k) >= eb.gamma(n) / (1 - U) ** (n + 1)
    assert Fraction(eb.round_up(Fraction(1, 3))) >= Fraction(1, 3)
    # the rounded-input constants are larger
    assert all(a < b for a, b in zip(eb.PENCIL_ERRBOUND[False], eb.PENCIL_ERRBOUND[True], strict=True))


def test_round_up_factor_covers_one_rounding_of_a_sum():
    rng = np.random.default_rng(0)
    a, e = rng.random(10000), rng.random(10000) * 1e-12
    b = (a + e) * eb.ROUND_UP
    assert all(Fraction(bv) >= Fraction(av) + Fraction(ev) for av, ev, bv in zip(a, e, b, strict=True))


def test_bounds_hold_on_every_binary64_hard_case():
    cases = [c for c in hard_cases() if not c.exact_input]
    E = np.stack([c.matrices()[0] for c in cases])
    Q = np.stack([c.matrices()[1] for c in cases])
    assert _check_pairs(E, Q) > 0.8 * len(cases)


def test_bounds_hold_on_random_pairs_of_every_type():
    E, Q, _ = random_pairs(400, np.random.default_rng(7))
    assert _check_pairs(E, Q) >= 390  # rounded parallel planes may fail the coefficient guard


@pytest.mark.parametrize(
    "scale_e, scale_q", [(2.0**150, 2.0**150), (2.0**-150, 2.0**-150), (2.0**20, 2.0**-20)]
)
def test_bounds_hold_with_huge_and_tiny_scales(scale_e, scale_q):
    E, Q, _ = random_pairs(100, np.random.default_rng(8))
    assert _check_pairs(E * scale_e, Q * scale_q) >= 95


def test_guard_turns_entries_outside_the_range_away():
    E, Q, _ = random_pairs(4, np.random.default_rng(9))
    Q[0] *= 2.0**200
    Q[1, 0, 1] = Q[1, 1, 0] = 2.0**-200
    fq = filter_quantities(E, Q)
    assert fq["outside"][0] and fq["outside"][1] and not fq["outside"][2:].any()


@given(st.lists(st.tuples(ellipsoids(), quadrics()), min_size=1, max_size=8))
def test_bounds_hold_for_rounded_rational_input(pairs):
    exact = [(e.matrix, q.matrix) for e, q in pairs]
    E = np.array([[[float(v) for v in row] for row in e] for e, _ in exact])
    Q = np.array([[[float(v) for v in row] for row in q] for _, q in exact])
    _check_pairs(E, Q, rounded_from=exact)


@pytest.mark.parametrize("rounded", [False, True])
def test_invariant_and_minor_bounds_hold(rounded):
    E, Q, _ = random_pairs(300, np.random.default_rng(11))
    for M in (E, Q):
        cols = [M[:, i, j] for i, j in ENTRY_INDICES]
        vals = kernels.quadric_invariants(*cols)
        mags = kernels.quadric_invariants_magnitude(*(np.abs(c) for c in cols))
        for k in range(M.shape[0]):
            exact = kernels.quadric_invariants(*(Fraction(c[k]) for c in cols))
            for t in range(7):
                bound = Fraction(eb.INVARIANTS_ERRBOUND[rounded][t] * mags[t][k])
                assert abs(Fraction(vals[t][k]) - exact[t]) <= bound
    a = [E[:, i, j] for i, j in ((0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2))]
    m = kernels.leading_minors_3(*a)
    mm = kernels.leading_minors_3_magnitude(*(np.abs(x) for x in a))
    for k in range(E.shape[0]):
        exact = kernels.leading_minors_3(*(Fraction(x[k]) for x in a))
        for t in range(2):
            assert abs(Fraction(m[t][k]) - exact[t]) <= Fraction(eb.MINORS_ERRBOUND[rounded][t] * mm[t][k])


def _screen_check(E, Q):
    """Every sign the screen reports as certain is the exact one."""
    from quadric_contact.modes.kernels.numpy_backend import screen_quantities

    sq = screen_quantities(E, Q)
    decided = 0
    for k in range(E.shape[0]):
        if not sq["ok"][k]:
            continue
        c = _exact_coefficients(E[k], Q[k])
        exact = [int(np.sign(v)) for v in c] + [int(np.sign(v)) for v in formulas.paper_deltas(*c)]
        for t, s in enumerate(sq["signs"]):
            if s[k] != 2:
                assert s[k] == exact[t], (k, t)
        decided += 1
    return decided


def test_screen_signs_are_exact_where_certain():
    cases = [c for c in hard_cases() if not c.exact_input]
    E = np.stack([c.matrices()[0] for c in cases])
    Q = np.stack([c.matrices()[1] for c in cases])
    assert _screen_check(E, Q) > 0.5 * len(cases)
    E, Q, _ = random_pairs(400, np.random.default_rng(17))
    assert _screen_check(E, Q) > 0.5 * 400  # rounded cylinders and parallel planes fail the screen
    assert _screen_check(E * 2.0**30, Q * 2.0**-20) > 0.5 * 400
    # coefficients beyond SEMI_COEFFICIENT_MAX: the screen steps aside (the dynamic filter rescales)
    assert _screen_check(E * 2.0**100, Q * 2.0**-60) == 0


def test_screen_constants_follow_from_the_rounding_counts():
    # the row bound: 24 W_k bounds the magnitude of c_k (24 permutations, one entry per row)
    from quadric_contact._generated.blocks import BLOCK_COUNTS

    value = eb._counts("pencil_coefficients")["value"]
    rows = BLOCK_COUNTS["row_bound"]["value"]
    for k in range(5):
        need = 24 * eb.gamma(value[k]) / (1 - Fraction(eb.UNIT_ROUNDOFF)) ** (rows[k] + 1)
        assert Fraction(eb.SEMI_PENCIL[k]) >= need
    for j, degree in enumerate((2, 4, 6)):
        rel, grow = eb.SEMI_DELTA[j]
        assert rel >= degree
        assert grow > 0
    assert eb.SEMI_MINORS[0] >= 2 * eb.gamma(eb._counts("leading_minors_3")["value"][0])
    assert eb.SEMI_MINORS[1] >= 6 * eb.gamma(eb._counts("leading_minors_3")["value"][1])


def test_row_bound_is_proved():
    from quadric_contact import codegen

    codegen.verify_row_bound()
    codegen.verify_minor_row_bounds()
    codegen.verify_plane_zeros()
