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


# -- the binary64 filter of the quartic's sign forms -----------------------------------------------


def test_filter_reads_the_generated_program_its_rounding_count_assumes():
    """The filter evaluates the generated forms in binary64; its bound counts the roundings of
    that program as written (left to right): pin the lines, and check the magnitude program is
    the same program on absolute values with every difference a sum."""
    import inspect

    from quadric_contact._generated import formulas
    from quadric_contact.exact.discriminants import magnitude_programs

    lines = [ln.strip() for ln in inspect.getsource(formulas.quartic_sign_forms).splitlines()]
    body = [ln for ln in lines if "=" in ln and not ln.startswith(('"', "def"))] + [lines[-1]]
    assert body == [
        "I = 12*c0*c4 - 3*c1*c3 + c2*c2",
        "J = 72*c0*c2*c4 - 27*c0*c3*c3 - 27*c1*c1*c4 + 9*c1*c2*c3 - 2*c2*c2*c2",
        "Delta2 = -8*c2*c4 + 3*c3*c3",
        "Delta3 = 16*c0*c2*c4*c4 - 6*c0*c3*c3*c4 - 18*c1*c1*c4*c4 + 14*c1*c2*c3*c4 - 3*c1*c3*c3*c3 "
        "- 4*c2*c2*c2*c4 + c2*c2*c3*c3",
        "return (Delta2, Delta3, 4*I*I*I - J*J)",
    ]
    # the magnitude program: each form's terms with their coefficients made positive
    a = sp.symbols("a0:5", positive=True)
    values = formulas.quartic_sign_forms(*a)
    i = 12 * a[0] * a[4] - 3 * a[1] * a[3] + a[2] * a[2]
    j = (
        72 * a[0] * a[2] * a[4]
        - 27 * a[0] * a[3] ** 2
        - 27 * a[1] ** 2 * a[4]
        + 9 * a[1] * a[2] * a[3]
        - 2 * a[2] ** 3
    )
    assert sp.expand(values[2] - (4 * i**3 - j**2)) == 0

    def positive(expr):
        return sum(
            abs(c) * m
            for m, c in zip(sp.Poly(expr, *a).monoms(), sp.Poly(expr, *a).coeffs(), strict=True)
            for m in [sp.Mul(*(x**k for x, k in zip(a, m, strict=True)))]
        )

    m2, m3, m4 = magnitude_programs(*a)
    assert sp.expand(m2 - positive(values[0])) == 0
    assert sp.expand(m3 - positive(values[1])) == 0
    assert sp.expand(m4 - (4 * positive(i) ** 3 + positive(j) ** 2)) == 0


def _quartics(seed, n):
    """Integer quartics of every size, and nearly degenerate ones: a double root, nearly."""
    import random

    rng = random.Random(seed)
    out = []
    for k in range(n):
        bits = rng.choice([1, 3, 8, 30, 60, 200, 600, 1000])
        if k % 3 == 0:
            a, b, c, d = (rng.randint(-50, 50) for _ in range(4))
            poly = flint.fmpz_poly([-a, 1]) ** 2 * flint.fmpz_poly([-b, 1]) * flint.fmpz_poly([-c, 1])
            cs = [int(x) * d for x in poly.coeffs()] + [0] * 5
            cs = cs[:5]
            cs[rng.randrange(5)] += rng.choice([-1, 0, 1])
            out.append(cs)
        else:
            out.append([rng.randint(-(2**bits), 2**bits) for _ in range(5)])
    return out


def test_filter_error_bounds_hold_exactly():
    """|computed - exact| <= bound for each form, the exact value of the scaled coefficients
    computed in rationals (form k is homogeneous of degree 2, 4, 6)."""
    from quadric_contact._generated import formulas
    from quadric_contact.exact.discriminants import binary64_forms

    checked = 0
    for cs in _quartics(11, 1500):
        forms = binary64_forms(cs)
        if forms is None:
            assert max(abs(x) for x in cs).bit_length() > 1000
            continue
        top = max(abs(x) for x in cs).bit_length()
        exact = formulas.quartic_sign_forms(*cs)
        for (value, bound), e, degree in zip(forms, exact, (2, 4, 6), strict=True):
            assert abs(Fraction(value) - Fraction(e, 2 ** (degree * top))) <= Fraction(bound)
            checked += 1
    assert checked > 3000


def test_filtered_signs_are_the_exact_signs():
    from quadric_contact._generated import formulas
    from quadric_contact.exact.discriminants import _binary64_form_signs, quartic_form_signs
    from quadric_contact.exact.rational import sign

    certified = 0
    cases = _quartics(12, 1500)
    for cs in cases:
        exact = tuple(sign(d) for d in formulas.quartic_sign_forms(*cs))
        assert quartic_form_signs(cs) == exact
        fast = _binary64_form_signs(cs)
        if fast is not None:
            assert fast == exact
            certified += 1
        if 0 in exact:
            assert fast is None  # an exact zero is never certified
    assert certified > len(cases) // 2
