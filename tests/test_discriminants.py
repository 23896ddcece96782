"""Discrimination system: derived Delta_3, Delta_4 against the printed ones,
and the exact root classification against an independent factorisation."""

from fractions import Fraction

import flint
import pytest
import sympy as sp
from hypothesis import given
from hypothesis import strategies as st

from quadric_contact import codegen, paper
from quadric_contact.exact.discriminants import revised_sign_list, root_structure
from quadric_contact.exact.errors import DegeneratePencilError

C = codegen.coefficient_symbols(4)
NAMES = {str(s): s for s in C}


def _terms(expr):
    return dict(sp.Poly(sp.sympify(expr, locals=NAMES), *C).terms())


def test_printed_delta3_equals_derived_term_by_term():
    derived = _terms(codegen.derive_paper_deltas()[1])
    assert _terms(paper.PRINTED["Delta3"]) == derived


def test_printed_delta4_term_by_term():
    derived = _terms(codegen.derive_paper_deltas()[2])
    printed = _terms(paper.PRINTED["Delta4"])
    only_printed = {m: c for m, c in printed.items() if derived.get(m) != c}
    only_derived = {m: c for m, c in derived.items() if printed.get(m) != c}
    # Exactly the recorded erratum: -27 c0^2 c4^4 printed where -27 c0^2 c3^4 is true.
    assert only_printed == {(2, 0, 0, 0, 4): -27}
    assert only_derived == {(2, 0, 0, 4, 0): -27}
    erratum = next(e for e in paper.ERRATA if e.key == "delta4-term")
    assert _terms(erratum.printed) == only_printed and _terms(erratum.corrected) == only_derived


def test_revised_sign_list():
    assert revised_sign_list([1, 0, 0, 1]) == [1, -1, -1, 1]
    assert revised_sign_list([1, -1, 0, 0]) == [1, -1, 0, 0]
    assert revised_sign_list([1, 0, -1, 0, 0, 0, 1]) == [1, -1, -1, 1, 1, -1, 1]


def _independent(coeffs):
    """(sorted real multiplicities, sorted non-real pair multiplicities) by flint factorisation."""
    f = flint.fmpq_poly([flint.fmpq(c.numerator, c.denominator) for c in coeffs])
    real, pairs = [], []
    _, factors = f.factor()
    for g, m in factors:
        roots = g.complex_roots()
        nr = sum(1 for r, _ in roots if r.imag.is_exact() and r.imag == 0)
        real += [m] * nr
        pairs += [m] * ((g.degree() - nr) // 2)
    return tuple(sorted(real, reverse=True)), tuple(sorted(pairs, reverse=True))


small_q = st.fractions(-4, 4, max_denominator=3)


@st.composite
def quartics_with_structure(draw):
    """Products of random linear and quadratic rational factors, with repeats."""
    poly = [Fraction(draw(st.integers(-3, 3).filter(bool)))]
    degree = 0
    while degree < 4:
        if degree <= 2 and draw(st.booleans()):
            b, c = draw(small_q), draw(small_q)
            factor = [c, b, Fraction(1)]
        else:
            factor = [draw(small_q), Fraction(1)]
        times = draw(st.integers(1, (4 - degree) // (len(factor) - 1)))
        for _ in range(times):
            out = [Fraction(0)] * (len(poly) + len(factor) - 1)
            for i, a in enumerate(poly):
                for j, b2 in enumerate(factor):
                    out[i + j] += a * b2
            poly = out
            degree += len(factor) - 1
    return poly


@given(quartics_with_structure())
def test_root_structure_matches_factorisation(coeffs):
    s = root_structure(coeffs)
    assert (s.real, s.nonreal) == _independent(coeffs)


@given(st.lists(st.fractions(-5, 5, max_denominator=4), min_size=2, max_size=5))
def test_root_structure_random_coefficients(coeffs):
    if not any(coeffs[1:]):
        return
    s = root_structure(coeffs)
    assert (s.real, s.nonreal) == _independent(coeffs[: max(i for i, c in enumerate(coeffs) if c) + 1])


@pytest.mark.parametrize(
    "coeffs, real, nonreal",
    [
        ([1, 0, 2, 0, 1], (), (2,)),  # (x^2+1)^2
        ([0, 0, 0, 0, 1], (4,), ()),  # x^4
        ([0, 0, -1, 0, 1], (2, 1, 1), ()),  # x^2 (x^2 - 1)
        ([0, 0, 1, 0, 1], (2,), (1,)),  # x^2 (x^2 + 1)
        ([5], (), ()),
        ([1, 1], (1,), ()),
    ],
)
def test_degenerate_cases(coeffs, real, nonreal):
    s = root_structure(coeffs)
    assert (s.real, s.nonreal) == (real, nonreal)


def test_zero_polynomial_is_a_degenerate_pencil():
    with pytest.raises(DegeneratePencilError):
        root_structure([0, 0, 0])
