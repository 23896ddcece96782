"""P(lambda) = det(lambda E + Q): exact, fast path equal to sympy, invariant under motions."""

from fractions import Fraction

import flint
import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from quadric_contact import NotAnEllipsoidError, Quadric, characteristic_polynomial
from quadric_contact.exact.precision import working_precision
from quadric_contact.testing.strategies import ellipsoids, quadrics, rigid_motions


def _sympy_charpoly(E, Q):
    lam = sp.Symbol("lambda")
    p = sp.Poly((lam * E.to_sympy() + Q.to_sympy()).det(), lam)
    return tuple(Fraction(int(c.p), int(c.q)) for c in (p.coeff_monomial(lam**k) for k in range(5)))


@settings(max_examples=25)  # a symbolic determinant per example
@given(e=ellipsoids(), q=quadrics())
def test_coefficients_equal_sympy_determinant(e, q):
    P = characteristic_polynomial(e, q, normalize=False)
    assert P.coefficients == _sympy_charpoly(e, q)


@given(e=ellipsoids(), q=quadrics(), m=rigid_motions())
def test_coefficients_unchanged_by_a_common_rigid_motion(e, q, m):
    assert (
        characteristic_polynomial(e.moved(m), q.moved(m)).coefficients
        == characteristic_polynomial(e, q).coefficients
    )


@given(e=ellipsoids(), q=quadrics())
def test_c4_is_det_e_and_c0_is_det_q(e, q):
    P = characteristic_polynomial(e, q)
    assert P[4] == Fraction(str(sp.Matrix(P.E.matrix).det())) < 0
    assert P[0] == Fraction(str(sp.Matrix(q.matrix).det()))


@settings(max_examples=25)
@given(
    st.lists(st.floats(-1e3, 1e3, allow_nan=False, allow_infinity=False), min_size=10, max_size=10),
    st.lists(st.floats(-1e3, 1e3, allow_nan=False, allow_infinity=False), min_size=10, max_size=10),
)
def test_float_input_is_exact_dyadic(eu, qu):
    # Arbitrary symmetric float matrices, normalize=False: the integer path must
    # agree with sympy on the exact dyadic rationals.
    def sym(u):
        m = np.zeros((4, 4))
        k = 0
        for i in range(4):
            for j in range(i, 4):
                m[i, j] = m[j, i] = u[k]
                k += 1
        return Quadric.from_matrix(m)

    E, Q = sym(eu), sym(qu)
    assert characteristic_polynomial(E, Q, normalize=False).coefficients == _sympy_charpoly(E, Q)


def test_normalisation_flips_e_and_roots():
    e = Quadric.ellipsoid(1, 2, 3, center=(1, 1, 1))
    q = Quadric.from_equation("x**2 - y - 1")
    P = characteristic_polynomial(-e, q)
    assert P.e_flipped and e == P.E
    assert characteristic_polynomial(e, q) == P
    raw = characteristic_polynomial(-e, q, normalize=False)
    assert raw.coefficients == tuple(c * (-1) ** k for k, c in enumerate(P.coefficients))


def test_root_scale_relates_integer_and_rational_polynomials():
    e = Quadric.from_equation("(x - 3)**2 + (y - 3)**2 + 3*(z - 5.5)**2 - 0.1")
    q = Quadric.from_equation("x**2 + y**2 + 3*(z - 8.36291)**2 - 20")
    P = characteristic_polynomial(e, q)
    s = P.root_scale
    dE, dQ = e.integer_form()[1], q.integer_form()[1]
    assert s == Fraction(dE, dQ)
    for k in range(5):
        assert P.coefficients[k] == Fraction(P.integer_coefficients[k], dE**k * dQ ** (4 - k))
    lam = Fraction(7, 3)
    integer_value = sum(C * (lam / s) ** k for k, C in enumerate(P.integer_coefficients))
    assert P(lam) == integer_value / dQ**4


def test_certified_roots_enclose_true_roots():
    P = characteristic_polynomial("2*x**2 + 2*y**2 + 3*z**2 - 1", "x**2 + y**2 + 8*z")
    roots = P.roots()
    real = [(r, m) for r, m in roots if r.imag == 0]
    assert len(real) == 1 and real[0][1] == 2 and real[0][0].real.contains(-0.5)


@given(e=ellipsoids(), q=quadrics())
def test_pencil_root_signs_equal_certified_isolation(e, q):
    P = characteristic_polynomial(e, q)
    f = flint.fmpq_poly([flint.fmpq(c.numerator, c.denominator) for c in P.coefficients])
    with working_precision(300):
        counts = {"-": 0, "0": 0, "+": 0}
        for r, m in f.complex_roots():
            if r.imag.is_exact() and r.imag == 0:
                key = "0" if (r.real.is_exact() and r.real == 0) else ("+" if r.real > 0 else "-")
                assert key == "0" or not r.real.contains(0)
                counts[key] += m
    s = P.signs
    assert (s.negative, s.zero, s.positive) == (counts["-"], counts["0"], counts["+"])


@settings(max_examples=25)  # a symbolic determinant per example
@given(e=ellipsoids(), q=quadrics(), negate=st.booleans())
def test_the_normalised_polynomial_is_sympys_of_the_ellipsoid_with_the_papers_sign(e, q, negate):
    """The ellipsoid test and ``P`` share ``det E`` (``P``'s leading coefficient); an ``E`` given
    with its inside positive gives ``P`` of ``-E``: the odd coefficients negated."""
    given_e = -e if negate else e
    P = characteristic_polynomial(given_e, q)
    assert e.as_ellipsoid() == P.E and P.e_flipped == (given_e != P.E)
    assert P.coefficients == _sympy_charpoly(P.E, q)


def test_a_quadric_that_is_not_an_ellipsoid_is_refused_by_name():
    for text, kind in (
        ("x**2 + y**2 - z**2 - 1", "hyperboloid of one sheet"),  # an indefinite quadratic part
        ("x**2 + 2*y**2 + 3*z**2 + 1", "imaginary ellipsoid"),  # definite, det > 0
        ("x**2 + y**2 + z**2", "imaginary cone"),  # definite, det = 0
    ):
        with pytest.raises(NotAnEllipsoidError, match=kind):
            characteristic_polynomial(text, "x - 1")
