"""The signature kernel (quadric_contact.modes.kernels.signature): its sample points, its
semi-static bounds against exact rational arithmetic, its reading of the facts against the
decision table's rule, and its answers against the exact decision."""

from __future__ import annotations

import math
from fractions import Fraction
from itertools import product

import numpy as np
import pytest
from numpy.polynomial import polynomial as npoly

from quadric_contact._generated import formulas, kernels
from quadric_contact.exact.entries import ENTRY_INDICES
from quadric_contact.modes.decision import separation as sep
from quadric_contact.modes.kernels import errorbounds as eb
from quadric_contact.modes.kernels import signature as ks
from quadric_contact.modes.stacks.batch import as_stack, make_pairs
from quadric_contact.testing.hardcases import hard_cases
from quadric_contact.testing.samples import random_ellipsoids, random_pairs
from quadric_contact.theory import decision as dec


def test_critical_polynomial_is_the_fit_it_says():
    """Re-derive the least-squares fit and check its accuracy on a dense grid."""
    t = 0.5 + 0.5 * np.cos(np.linspace(0.0, np.pi, 513))
    fit = npoly.polyfit(t, np.cos(2.0 * np.arccos(t) / 3.0), 8)
    assert np.allclose(fit, ks.CRITICAL_POLYNOMIAL, rtol=0, atol=1e-12)
    grid = np.linspace(0.0, 1.0, 200_001)
    err = np.abs(npoly.polyval(grid, np.array(ks.CRITICAL_POLYNOMIAL)) - np.cos(2.0 * np.arccos(grid) / 3.0))
    assert err.max() < 4e-9


def test_fast_critical_points_are_the_trigonometric_ones():
    rng = np.random.default_rng(5)
    worst = 0.0
    for _ in range(3000):
        r = np.sort(rng.normal(size=4) * 10.0 ** rng.uniform(-3, 3))
        c = npoly.polyfromroots(r) * rng.choice([-1.0, 1.0]) * 10.0 ** rng.uniform(-5, 5)
        a = dec.critical_points(c[1], c[2], c[3], c[4])
        b = ks.critical_points_fast(c[1], c[2], c[3], c[4])
        if not a[3]:
            continue
        # both lie strictly between consecutive roots where the roots are well apart
        gaps = np.diff(r)
        if gaps.min() > 1e-6 * np.abs(r).max():
            assert b[3]
            assert r[0] < b[0] < r[1] < b[1] < r[2] < b[2] < r[3]
        if b[3]:
            scale = max(abs(a[0]), abs(a[2]), gaps.min())
            worst = max(worst, max(abs(a[k] - b[k]) for k in range(3)) / scale)
    assert worst < 1e-9


def test_fast_critical_points_flag_a_cubic_without_three_real_roots():
    # P' = 4x^3 + 4x: one real root
    assert not ks.critical_points_fast(4.0, 0.0, 0.0, 1.0)[3]
    assert not ks.critical_points_fast(1.0, 1.0, 1.0, 0.0)[3]  # c4 = 0
    assert not ks.critical_points_fast(math.nan, 1.0, 1.0, 1.0)[3]


def _exact_minors(s, e, q):
    m = [Fraction(s) * a + b for a, b in zip(e, q, strict=True)]
    return kernels.leading_minors_4(*m)


@pytest.mark.parametrize("rounded", [False, True])
def test_semi_static_member_bounds_hold(rounded):
    """|d_k^ - d_k(s E + Q)| <= the kernel's bound, exactly, at the sample points the kernel
    uses and at points near the roots (where the minors are small)."""
    rng = np.random.default_rng(23 if rounded else 29)
    E, Q, _ = random_pairs(120, rng)
    SK = tuple(eb.MEMBER_MINORS_SEMI[rounded])
    checked = 0
    for k in range(E.shape[0]):
        if rounded:
            # rationals with denominators 3 and 7, and their roundings
            ex = [Fraction(round(E[k][i, j] * 1e6), 3_000_000) for i, j in ENTRY_INDICES]
            qx = [Fraction(round(Q[k][i, j] * 1e6), 7_000_000) for i, j in ENTRY_INDICES]
            e = tuple(float(v) for v in ex)
            q = tuple(float(v) for v in qx)
        else:
            e = tuple(float(E[k][i, j]) for i, j in ENTRY_INDICES)
            q = tuple(float(Q[k][i, j]) for i, j in ENTRY_INDICES)
            ex = [Fraction(v) for v in e]
            qx = [Fraction(v) for v in q]
        if e[0] < 0:
            e = tuple(-v for v in e)
            ex = [-v for v in ex]
        c = formulas.pencil_coefficients(*e, *q)
        s1, s2, s3, _ = ks.critical_points_fast(c[1], c[2], c[3], c[4])
        roots = [r.real for r in np.roots(list(reversed(c))) if abs(r.imag) < 1e-9]
        for s in [s1, s2, s3, *roots, *(np.nextafter(r, np.inf) for r in roots)]:
            if not math.isfinite(s):
                continue
            got = ks.member_minors_bounded(float(s), e, q, SK, True)
            if not got[8]:
                continue
            exact = _exact_minors(float(s), ex, qx)
            for t in range(4):
                assert abs(Fraction(got[t]) - exact[t]) <= Fraction(got[4 + t]), (k, s, t)
            checked += 1
    assert checked > 300


def test_semi_static_constants_follow_from_the_rounding_counts():
    from quadric_contact import codegen

    codegen.verify_member_minor_row_bounds()
    u = Fraction(eb.UNIT_ROUNDOFF)
    value = eb._counts("leading_minors_4")["value"]
    for rounded in (False, True):
        r = 1 if rounded else 0
        a = (1 + u) ** (2 + r) - 1
        for k in range(1, 5):
            need = ((1 + eb.gamma(value[k - 1])) * (1 + a) ** k - 1) * math.factorial(k)
            need /= (1 - u) ** ((2 + r) * k + k)
            assert Fraction(eb.MEMBER_MINORS_SEMI[rounded][k - 1]) >= need


_DEFS = [float(d) for d in dec.Definite]
_SIGNS = [-1.0, 0.0, 1.0, 2.0]


def test_the_kernels_reading_of_the_facts_follows_the_rule():
    """Every certified answer of decide_signature has its reason: a definite member at a sample
    point, or four simple roots (signs +, -, + of P at increasing points) with neither the
    first gap's nor the last gap's member definite.  The plain reading (certain signs only)
    answers everything."""
    for ok, d1, d2, d3, p1, p2, p3 in product((True, False), _DEFS, _DEFS, _DEFS, _SIGNS, _SIGNS, _SIGNS):
        code = ks.decide_signature(ok, d1, d2, d3, p1, p2, p3, True)
        defs = (d1, d2, d3)
        positive = float(dec.Definite.POSITIVE) in defs
        negative = float(dec.Definite.NEGATIVE) in defs
        simple = ok and (p1, p2, p3) == (1.0, -1.0, 1.0)
        none = float(dec.Definite.NONE)
        if code == sep.SEP_PLUS:
            assert positive
        elif code == sep.SEP_MINUS:
            assert negative
        elif code == sep.CROSSING:
            assert simple and d1 == none and d3 == none and not positive and not negative
        else:
            assert code == sep.UNCERTAIN
            assert not positive and not negative and not (simple and d1 == none and d3 == none)
        plain = ks.decide_signature(ok, d1, d2, d3, p1, p2, p3, False)
        if float(dec.Definite.UNKNOWN) not in defs and 2.0 not in (p1, p2, p3):  # a plain reading's facts
            assert plain != sep.UNCERTAIN
        if code != sep.UNCERTAIN and not (positive and negative):
            assert plain == code


def _pairs(E, Q):
    return make_pairs(as_stack(E, "E"), as_stack(Q, "Q"))[0]


def _populations():
    rng = np.random.default_rng(31)
    E1, Q1, _ = random_pairs(150, rng)
    E2, _ = random_ellipsoids(150, rng, axes=(0.5, 2.0), box=3.0)
    Q2, _ = random_ellipsoids(150, rng, axes=(2.0, 5.0), box=0.0)
    cases = [c for c in hard_cases() if not c.exact_input]
    E3 = np.stack([c.matrices()[0] for c in cases])
    Q3 = np.stack([c.matrices()[1] for c in cases])
    return [(E1, Q1), (E2, Q2), (E3, Q3)]


def test_certain_answers_are_the_exact_decision():
    decided = 0
    for E, Q in _populations():
        codes = ks.signature_float(_pairs(E, Q), certified=True)
        for i in range(E.shape[0]):
            if codes[i] == sep.UNCERTAIN:
                continue
            assert codes[i] == dec.decide_exact(E[i], Q[i]).region, (i, codes[i])
            decided += 1
    assert decided > 200


def test_plain_reading_agrees_where_the_certified_one_decides():
    for E, Q in _populations():
        pairs = _pairs(E, Q)
        cert = ks.signature_float(pairs, certified=True)
        plain = ks.signature_float(pairs, certified=False)
        assert (plain != sep.UNCERTAIN).all()
        sure = cert != sep.UNCERTAIN
        assert (plain[sure] == cert[sure]).all()


def test_the_tangent_pair_stays_uncertain():
    from quadric_contact import Quadric

    E, Q = Quadric.sphere(1), Quadric.sphere(1, (2, 0, 0))  # touching from outside
    pairs, _ = make_pairs(as_stack([E], "E"), as_stack([Q], "Q"))
    assert int(ks.signature_float(pairs, certified=True)[0]) == sep.UNCERTAIN


def test_the_compiled_kernel_is_the_python_one():
    rng = np.random.default_rng(37)
    E, Q, _ = random_pairs(64, rng)
    pairs = _pairs(E, Q)
    for certified in (True, False):
        a = ks.signature_float(pairs, certified=certified)
        b = ks.signature_float(pairs, certified=certified, backend="numpy")
        assert (a == b).all()


def test_one_quadric_against_a_stack_is_pair_by_pair():
    rng = np.random.default_rng(41)
    E, _ = random_ellipsoids(200, rng, axes=(0.05, 0.2), box=4.0)
    env, _ = random_ellipsoids(1, rng, axes=(3.0, 5.0), box=0.0)
    one = ks.signature_float(_pairs(E, env[0]), certified=True)
    each = ks.signature_float(_pairs(E, np.repeat(env, 200, axis=0)), certified=True)
    assert (one == each).all()
