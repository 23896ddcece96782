from fractions import Fraction

import flint
from hypothesis import given
from hypothesis import strategies as st

from quadric_contact.exact.descartes import root_signs, sign_variations
from quadric_contact.exact.discriminants import root_structure
from quadric_contact.exact.precision import working_precision


def test_sign_variations_ignore_zeros():
    assert sign_variations([1, 0, -1, 0, 0, 2]) == 2
    assert sign_variations([0, 0]) == 0


def _isolated(coeffs):
    f = flint.fmpq_poly([flint.fmpq(c.numerator, c.denominator) for c in coeffs])
    with working_precision(200):
        neg = zero = pos = 0
        for r, m in f.complex_roots():
            if r.imag.is_exact() and r.imag == 0:
                if r.real.is_exact() and r.real == 0:
                    zero += m
                elif r.real > 0:
                    pos += m
                else:
                    assert r.real < 0
                    neg += m
        return neg, zero, pos


@given(st.lists(st.fractions(-5, 5, max_denominator=4), min_size=5, max_size=5).filter(lambda c: c[-1] != 0))
def test_root_signs_equal_certified_isolation(coeffs):
    rs = root_signs(coeffs)
    assert (rs.negative, rs.zero, rs.positive) == _isolated(coeffs)
    assert rs.nonreal == 4 - rs.negative - rs.zero - rs.positive
    assert rs.method == ("descartes" if root_structure(coeffs).all_real else "isolation")


@given(st.lists(st.fractions(-3, 3, max_denominator=3), min_size=4, max_size=4))
def test_real_rooted_products_use_descartes_exactly(roots):
    poly = [Fraction(1)]
    for r in roots:
        poly = [
            (poly[i - 1] if i else 0) - r * (poly[i] if i < len(poly) else 0) for i in range(len(poly) + 1)
        ]
    rs = root_signs(poly)
    assert rs.method == "descartes"
    assert (rs.negative, rs.zero, rs.positive) == (
        sum(r < 0 for r in roots),
        sum(r == 0 for r in roots),
        sum(r > 0 for r in roots),
    )
