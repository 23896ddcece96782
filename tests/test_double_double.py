"""The double-double reading of the invariants of a quadric: its primitives are exact where they
claim to be and within the published bounds elsewhere, its values lie within its bounds of the
exact values (Fractions of the very same binary64 entries), every sign it certifies is the
exact sign, compiled and numpy agree bit for bit, and on quadrics of every type it leaves
nothing to integer arithmetic but exact zeros."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

from quadric_contact import codegen
from quadric_contact._generated import dd_programs, kernels
from quadric_contact.exact.entries import ENTRY_INDICES
from quadric_contact.modes.facts import exact_facts, float_invariant_signs
from quadric_contact.modes.kernels import double_double as dd
from quadric_contact.modes.kernels import errorbounds as eb
from quadric_contact.modes.kernels._jit import HAVE_NUMBA, njit
from quadric_contact.modes.kernels.numpy_backend import dd_invariant_quantities
from quadric_contact.modes.numbers.objects import ExactMode
from quadric_contact.modes.stacks.batch import as_stack
from quadric_contact.testing.hardcases import hard_cases
from quadric_contact.testing.samples import random_pairs, random_rotations

U = eb.UNIT_ROUNDOFF
UNC = 2


def _word(hi, lo):
    return Fraction(hi) + Fraction(lo)


def _exact_invariants(M):
    """The seven invariants of the binary64 matrix ``M``, in Fractions."""
    return kernels.quadric_invariants(*(Fraction(M[i, j]) for i, j in ENTRY_INDICES))


def _sign(x):
    return (x > 0) - (x < 0)


def _symmetric(M):
    return (M + np.swapaxes(M, -1, -2)) / 2


# -- populations ------------------------------------------------------------------------------


def _every_type(n, seed):
    E, Q, _ = random_pairs(n, np.random.default_rng(seed))
    return np.concatenate([Q, -Q, E])


def _integer_structural_zeros(n, seed):
    """Integer matrices ``P^T D P`` (``P`` unimodular-ish integer, ``D`` diagonal with zeros):
    exact structural zeros (``det Q = 0`` of rank 3 and 2, rank-1 quadratic parts) whose
    products do not vanish, so no magnitude is zero."""
    rng = np.random.default_rng(seed)
    out = []
    diagonals = ([1, 2, 0, -1], [3, 0, 0, -1], [1, -2, 0, 0], [2, 0, 0, 5], [0, 0, 1, -4], [1, 1, 1, 0])
    for k in range(n):
        P = np.eye(4) + np.triu(rng.integers(-3, 4, size=(4, 4)), 1)
        P = P[rng.permutation(4)]
        D = np.diag(np.array(diagonals[k % len(diagonals)], dtype=float))
        out.append(P.T @ D @ P)
    return np.array(out)


def _rank_one_quadratic_parts(n, seed):
    """``A = s v v^T`` exactly (small integer ``v``), with an arbitrary last row: cofactors
    exactly zero, so ``JA = detA = 0`` and, when ``b`` is in the span, ``det Q`` too."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        v = rng.integers(-5, 6, size=3).astype(float)
        v[rng.integers(0, 3)] = rng.integers(1, 6)
        M = np.zeros((4, 4))
        M[:3, :3] = np.outer(v, v) * rng.choice([-1.0, 1.0, 2.0])
        M[:3, 3] = M[3, :3] = rng.integers(-4, 5, size=3) if rng.random() < 0.5 else v * rng.integers(-3, 4)
        M[3, 3] = rng.integers(-4, 5)
        out.append(M)
    return np.array(out)


def _wild_scales(n, seed):
    """Quadrics of every type scaled by ``D S D`` with ``D`` diagonal powers of two spread over
    ``2^-40 .. 2^40`` (entries of wildly different sizes, inside the guard), and by a common
    ``2^+-150``."""
    rng = np.random.default_rng(seed)
    Q = _every_type(n, seed)[:n]
    D = 2.0 ** rng.integers(-40, 41, size=(n, 4))
    scaled = Q * D[:, :, None] * D[:, None, :]
    common = Q * (2.0 ** rng.choice([-150, 150], size=n))[:, None, None]
    return np.concatenate([scaled, common])


def _near_singular(n, seed):
    """Huge cancellation: ``R^T diag(a, b, c, d) R`` with a rotation ``R`` in 4-space made of two
    3D rotations and eigenvalues spread over 2^0 .. 2^-60, so that the invariants are tiny
    against their magnitudes."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        R = np.eye(4)
        R[:3, :3] = random_rotations(1, rng)[0]
        R2 = np.eye(4)
        R2[1:, 1:] = random_rotations(1, rng)[0]
        R = R @ R2
        lam = rng.choice([-1.0, 1.0], size=4) * 2.0 ** (-rng.integers(0, 61, size=4))
        out.append(_symmetric(R.T @ np.diag(lam) @ R))
    return np.array(out)


def _hard_case_matrices():
    return np.array([m for h in hard_cases() if not h.exact_input for m in h.matrices()], dtype=float)


# -- the primitives ---------------------------------------------------------------------------


def _random_doubles(rng, n, spread=60):
    return rng.normal(size=n) * 2.0 ** rng.integers(-spread, spread, size=n)


def test_error_free_transformations_are_exact():
    rng = np.random.default_rng(1)
    a, b = _random_doubles(rng, 3000), _random_doubles(rng, 3000)
    b[:500] = -a[:500] * (1 + 2.0**-50)  # cancellation
    s, e = dd.two_sum(a, b)
    p, f = dd.two_prod(a, b)
    h, low = dd.split(a)
    for k in range(a.size):
        assert _word(s[k], e[k]) == Fraction(a[k]) + Fraction(b[k])
        assert _word(p[k], f[k]) == Fraction(a[k]) * Fraction(b[k])
        assert Fraction(h[k]) + Fraction(low[k]) == Fraction(a[k])
        assert s[k] == a[k] + b[k] and p[k] == a[k] * b[k]  # the high word is the rounded result
    big, small = np.abs(a) + 1.0, a * 2.0**-70
    s, e = dd.fast_two_sum(big, small)
    assert all(_word(s[k], e[k]) == Fraction(big[k]) + Fraction(small[k]) for k in range(a.size))


def test_double_double_operations_stay_within_the_published_bounds():
    """AccurateDWPlusDW within ``3u^2 + 13u^3`` and DWTimesFP1 within ``3/2 u^2 + 4u^3`` of the
    exact result, cancellation included; every result is a double-word (``hi = RN(hi + lo)``)."""
    rng = np.random.default_rng(2)
    n = 3000
    x = dd.two_prod(_random_doubles(rng, n, 20), _random_doubles(rng, n, 20))
    y = dd.two_prod(_random_doubles(rng, n, 20), _random_doubles(rng, n, 20))
    near = dd.two_prod(-x[0], 1.0 + 2.0**-45)  # cancellation: x + near = xl - xh 2^-45
    first = np.arange(n) < 1000
    y = (np.where(first, near[0], y[0]), np.where(first, near[1], y[1]))
    c = _random_doubles(rng, n, 20)
    worst_add = worst_mul = Fraction(0)
    for op, ref, bound in (
        (dd.dd_add, lambda a, b: a + b, eb.DD_ADD_ERROR),
        (dd.dd_sub, lambda a, b: a - b, eb.DD_ADD_ERROR),
    ):
        z = op(x, y)
        for k in range(n):
            exact = ref(_word(x[0][k], x[1][k]), _word(y[0][k], y[1][k]))
            assert abs(_word(z[0][k], z[1][k]) - exact) <= bound * abs(exact)
            assert z[0][k] + z[1][k] == z[0][k]
            if exact:
                worst_add = max(worst_add, abs(_word(z[0][k], z[1][k]) - exact) / abs(exact))
    z = dd.dd_mul_d(x, c)
    for k in range(n):
        exact = _word(x[0][k], x[1][k]) * Fraction(c[k])
        assert abs(_word(z[0][k], z[1][k]) - exact) <= eb.DD_MUL_ERROR * abs(exact)
        assert z[0][k] + z[1][k] == z[0][k]
        if exact:
            worst_mul = max(worst_mul, abs(_word(z[0][k], z[1][k]) - exact) / abs(exact))
    assert 0 < worst_add < eb.DD_ADD_ERROR and 0 < worst_mul < eb.DD_MUL_ERROR  # not vacuous
    assert dd.dd_scale((3.0, 2.0**-60), -2.0) == (-6.0, -(2.0**-59))


def test_the_primitives_run_on_floats_and_on_arrays_alike():
    rng = np.random.default_rng(3)
    a, b, c = (_random_doubles(rng, 50, 10) for _ in range(3))
    arrays = dd.dd_mul_d(dd.dd_sub(dd.two_prod(a, b), dd.two_sum(b, c)), c)
    for k in range(50):
        one = dd.dd_mul_d(dd.dd_sub(dd.two_prod(a[k], b[k]), dd.two_sum(b[k], c[k])), c[k])
        assert one == (arrays[0][k], arrays[1][k])


# -- the bounds -------------------------------------------------------------------------------


def _growth(n_add, n_mul):
    return (1 + eb.DD_ADD_ERROR) ** n_add * (1 + eb.DD_MUL_ERROR) ** n_mul - 1


def test_constants_follow_from_the_counts_and_the_published_bounds():
    counts = dd_programs.DD_COUNTS["quadric_invariants_dd"]
    mag = kernels.ROUNDING_COUNTS["quadric_invariants"]["magnitude"]
    for k, K in enumerate(eb.INVARIANTS_DD_ERRBOUND):
        growth = (1 + eb.DD_ADD_ERROR) ** counts["dd_add"][k] * (1 + eb.DD_MUL_ERROR) ** counts["dd_mul_d"][
            k
        ] - 1
        assert Fraction(K) >= growth / (1 - U) ** (mag[k] + 1)
        assert K < 32 * 2.0**-106  # about 106 bits: the point of the exercise
    cof = dd_programs.DD_COUNTS["quadric_invariants_cofactor_magnitude"]
    for j, name in enumerate(eb.COFACTOR_OUTPUTS):
        k = counts["outputs"].index(name)
        assert eb.COFACTOR_AT[j] == k
        growth = (1 + eb.DD_ADD_ERROR) ** counts["dd_add"][k] * (1 + eb.DD_MUL_ERROR) ** counts["dd_mul_d"][
            k
        ] - 1
        need = growth * (1 + U) / (1 - eb.DD_ADD_ERROR) / (1 - U) ** (cof["magnitude"][j] + 1)
        assert Fraction(eb.INVARIANTS_DD_COFACTOR_ERRBOUND[j]) >= need
    # a cofactor is one rounded difference of two exact products
    assert set(dd_programs.DD_COUNTS["adjugate_3_dd"]["dd_add"]) == {1}


def _check_values_within_bounds(M):
    """Every double-double value within its bound of the exact invariant (inside the guard);
    returns how many values were checked and how many of those had a tiny exact value
    (below ``1e-20`` of the static magnitude: where binary64 is blind)."""
    got = dd_invariant_quantities(M)
    mags = kernels.quadric_invariants_magnitude(*(np.abs(M[:, i, j]) for i, j in ENTRY_INDICES))
    checked = tiny = 0
    for k in range(M.shape[0]):
        if got["outside"][k]:
            continue
        exact = _exact_invariants(M[k])
        for t in range(7):
            value = _word(got["hi"][t][k], got["lo"][t][k])
            assert abs(value - exact[t]) <= Fraction(got["bound"][t][k]), (k, t)
            assert got["hi"][t][k] + got["lo"][t][k] == got["hi"][t][k]
            checked += 1
            tiny += abs(exact[t]) < Fraction(1e-20) * Fraction(mags[t][k])
    return checked, tiny


@pytest.mark.parametrize(
    "make",
    [
        lambda: _every_type(700, 21),
        lambda: _near_singular(400, 22),
        lambda: _wild_scales(300, 23),
        lambda: _integer_structural_zeros(120, 24),
        lambda: _rank_one_quadratic_parts(120, 25),
        _hard_case_matrices,
    ],
    ids=["every-type", "near-singular", "wild-scales", "integer-zeros", "rank-one-A", "hard-cases"],
)
def test_double_double_values_are_within_their_bounds_of_the_exact_values(make):
    M = make()
    checked, _ = _check_values_within_bounds(M)
    assert checked >= 7 * 0.9 * M.shape[0]


def test_the_bounds_are_tested_where_binary64_is_blind():
    """The populations above put values far below binary64's reach: the check is not vacuous."""
    _, tiny = _check_values_within_bounds(np.concatenate([_every_type(300, 26), _near_singular(200, 27)]))
    assert tiny > 200


# -- the signs --------------------------------------------------------------------------------


def _adversarial():
    E, Q, _ = random_pairs(60, np.random.default_rng(31))
    outside = np.concatenate([Q[:20] * 2.0**200, Q[20:40] * 2.0**-200])
    tiny_entry = Q[40:50].copy()
    tiny_entry[:, 0, 1] = tiny_entry[:, 1, 0] = 2.0**-190
    nan = Q[50:55].copy()
    nan[:, 2, 2] = np.nan
    inf = Q[55:60].copy()
    inf[:, 0, 3] = inf[:, 3, 0] = np.inf
    return np.concatenate([outside, tiny_entry, nan, inf]), np.concatenate([E[:5], Q[:5]])


def _assert_certified_signs_are_exact(M, signs):
    decided = 0
    for k in range(M.shape[0]):
        exact = _exact_invariants(M[k])
        for t in range(7):
            if signs[k, t] != UNC:
                assert signs[k, t] == _sign(exact[t]), (k, t, M[k])
                decided += 1
    return decided


POPULATIONS = {
    "every-type": lambda: _every_type(1200, 41),
    "near-singular": lambda: _near_singular(300, 42),
    "wild-scales": lambda: _wild_scales(300, 43),
    "integer-zeros": lambda: _integer_structural_zeros(120, 44),
    "rank-one-A": lambda: _rank_one_quadratic_parts(120, 45),
    "hard-cases": _hard_case_matrices,
}


@pytest.mark.parametrize("name", sorted(POPULATIONS))
def test_every_certified_sign_is_the_exact_sign(name):
    """The double-double reading alone, and the filtered invariant signs (binary64, then
    double-double) in both backends: a sign that is not UNCERTAIN is the sign of the exact
    invariant (Fractions), and the two backends agree sign for sign."""
    M = POPULATIONS[name]()
    alone = dd_invariant_quantities(M)["signs"]
    assert _assert_certified_signs_are_exact(M, alone) >= 0.9 * 7 * M.shape[0] * (name != "integer-zeros")
    filtered = float_invariant_signs(M, filtered=True)
    assert (filtered == float_invariant_signs(M, filtered=True, backend="numpy")).all()
    _assert_certified_signs_are_exact(M, filtered)
    assert (filtered[:, 7] == np.sign(M[:, 3, 3])).all()


def test_outside_the_guard_nothing_is_certified():
    bad, _ = _adversarial()
    for backend in ("numba", "numpy"):
        signs = float_invariant_signs(bad, filtered=True, backend=backend)
        assert (signs[:, :7] == UNC).all()
    assert dd_invariant_quantities(bad)["outside"].all()


def test_exact_zeros_are_certified_only_from_a_zero_magnitude():
    """A zero sign is certified only where a magnitude vanishes (then the value is exactly zero):
    every exact zero of the rank-one quadratic parts comes from zero cofactors and is certified;
    an exact zero whose products and cofactors do not vanish stays UNCERTAIN."""
    M = _rank_one_quadratic_parts(150, 51)
    signs = float_invariant_signs(M, filtered=True)
    for k in range(M.shape[0]):
        exact = _exact_invariants(M[k])
        assert exact[1] == exact[2] == exact[6] == 0  # JA, detA, det Q: adj(A) = 0
        assert signs[k, 1] == signs[k, 2] == signs[k, 6] == 0
    Z = _integer_structural_zeros(60, 52)
    signs = float_invariant_signs(Z, filtered=True)
    zero_det = np.array([_exact_invariants(m)[6] == 0 for m in Z])
    assert zero_det.all() and (signs[:, 6] == UNC).any()
    assert set(np.unique(signs[:, 6])) <= {0, UNC}


# -- what is left to the integers ----------------------------------------------------------------


def _left_to_integers(M):
    return np.flatnonzero((float_invariant_signs(M, filtered=True)[:, :7] == UNC).any(axis=1))


def _true_zeros(M):
    """The quadrics with an invariant that is exactly zero although its bound is not: no
    filter can certify those; only an integer (or exact) computation can."""
    got = dd_invariant_quantities(M)
    out = []
    for k in range(M.shape[0]):
        exact = _exact_invariants(M[k])
        if any(exact[t] == 0 and got["bound"][t][k] > 0 for t in range(7)):
            out.append(k)
    return np.array(out, dtype=np.intp)


def test_only_exact_zeros_are_left_to_the_integers():
    """On quadrics of every type (rotated parabolic cylinders and parallel planes included, whose
    detA and det Q are the square of the rounding), nothing is left to integer arithmetic;
    with integer structural zeros mixed in, exactly those are, and the integers' answer is
    needed only there (counted by spying on the exact invariants)."""
    M = _every_type(3000, 61)
    assert _left_to_integers(M).size == 0 == _true_zeros(M).size
    Z = np.concatenate([_every_type(500, 62), _integer_structural_zeros(90, 63)])
    left = _left_to_integers(Z)
    assert left.size > 0
    assert np.array_equal(left, _true_zeros(Z))


def test_exact_facts_ask_the_integers_only_about_exact_zeros(monkeypatch):
    from quadric_contact.modes import facts
    from quadric_contact.modes.decision.answers import masks_from_invariant_signs

    asked = []
    exact = facts.integer_invariant_signs

    def count(Q, rows):
        asked.append(len(rows))
        return exact(Q, rows)

    M = np.concatenate([_every_type(400, 71)[:800], _integer_structural_zeros(30, 72)])
    stack = as_stack(M, "Q")
    rows = np.arange(M.shape[0])
    reference = ExactMode().invariant_signs(as_stack(M, "Q"), rows)
    monkeypatch.setattr(facts, "integer_invariant_signs", count)
    flags, masks = exact_facts(stack, rows)
    assert sum(asked) == len(_true_zeros(M))
    det_zero = reference[:, 6] == 0
    assert (
        flags == (det_zero.astype(np.int8) | ((det_zero & (reference[:, 5] == 0)).astype(np.int8) << 1))
    ).all()
    assert (masks == masks_from_invariant_signs(reference)).all()


# -- compiled, uncompiled, generated ---------------------------------------------------------------


def _reader(adjugate, invariants):
    """A loop reading the double-double invariants of the flat ``(m, 16)`` matrices ``M`` into
    ``out`` (``(m, 14)``: the seven high words, then the seven low words) with the given programs
    and the operations, as the kernel does."""
    two_sum, two_prod, dd_add, dd_sub, dd_mul_d, dd_scale = dd.OPERATIONS

    def read_rows(M, out):
        for p in range(M.shape[0]):
            q00, q01, q02, q03, q11, q12, q13, q22, q23, q33 = (
                M[p, 0], M[p, 1], M[p, 2], M[p, 3], M[p, 5], M[p, 6], M[p, 7], M[p, 10], M[p, 11], M[p, 15]
            )  # fmt: skip
            C = adjugate(two_sum, two_prod, dd_add, dd_sub, dd_mul_d, dd_scale, q00, q01, q02, q11, q12, q22)
            w = invariants(
                two_sum, two_prod, dd_add, dd_sub, dd_mul_d, dd_scale,
                q00, q01, q02, q03, q11, q12, q13, q22, q23, q33, C[0], C[1], C[2], C[3], C[4], C[5],
            )  # fmt: skip
            for k in range(7):
                out[p, k] = w[k][0]
                out[p, 7 + k] = w[k][1]

    return read_rows


@pytest.mark.skipif(not HAVE_NUMBA, reason="numba not installed")
def test_compiled_programs_give_the_numpy_words_bit_for_bit():
    """numba compiles the programs without contracting a product and a sum into a fused
    multiply-add or reassociating (Dekker's product needs every product rounded on its own): the
    compiled words are the numpy ones, and the uncompiled Python ones, exactly."""
    M = np.concatenate([_every_type(300, 81), _near_singular(100, 82), _wild_scales(100, 83)])
    flat = np.ascontiguousarray(M).reshape(-1, 16)
    compiled = np.empty((M.shape[0], 14))
    programs = (dd_programs.adjugate_3_dd, dd_programs.quadric_invariants_dd)
    njit(cache=False)(_reader(*(njit(f, inline=True) for f in programs)))(flat, compiled)
    python = np.empty_like(compiled)
    _reader(dd_programs.adjugate_3_dd, dd_programs.quadric_invariants_dd)(flat[:40], python[:40])
    got = dd_invariant_quantities(M)
    columns = np.stack([*got["hi"], *got["lo"]], axis=1)
    assert np.array_equal(compiled, columns)
    assert np.array_equal(python[:40], columns[:40])


def test_the_programs_take_the_operations_of_the_module_in_order():
    assert tuple(f.__name__ for f in dd.OPERATIONS) == codegen.DD_OPERATIONS
    names = dd_programs.quadric_invariants_dd.__code__.co_varnames[: len(codegen.DD_OPERATIONS)]
    assert names == codegen.DD_OPERATIONS


def test_the_generated_programs_are_current_and_verified():
    assert codegen.DD_PATH.read_text() == codegen.emit_dd_programs()
    assert codegen.regenerate_dd(check=True)  # verifies the programs before comparing
    codegen.verify_cofactor_forms()


def test_the_verification_catches_a_wrong_program():
    text = codegen.emit_dd_programs()
    companion = kernels.quadric_invariants_magnitude
    for bad in (
        text.replace("E4 = dd_sub(E4_4, E4_7)", "E4 = dd_add(E4_4, E4_7)"),
        text.replace("C00 = dd_sub(p11_22, p12_12)", "C00 = dd_add(p11_22, p12_12)"),
        text.replace("JA = C00 + C11 + C22", "JA = C00 + C11"),
    ):
        assert bad != text
        with pytest.raises(AssertionError):
            codegen.verify_dd_programs(bad, companion)
