"""The separation certificate: its lemmas, its float bounds, and its answers against
decisions that do not use it (the exact geometric decision)."""

from __future__ import annotations

import itertools
from fractions import Fraction as F

import numpy as np
import sympy as sp
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from quadric_contact import Quadric, characteristic_polynomial
from quadric_contact._generated import kernels
from quadric_contact.model.classification import inertia_from_minor_sums, principal_minor_sums_4
from quadric_contact.modes.decision.separation import (
    CROSSING,
    SEP_MINUS,
    SEP_PLUS,
    UNCERTAIN,
    decide_from_counts,
    positive_count,
    quartic_roots,
    separation_float,
)
from quadric_contact.modes.kernels import errorbounds as eb
from quadric_contact.modes.kernels.signature import (
    signature_float,
)
from quadric_contact.modes.stacks.batch import as_stack, make_pairs
from quadric_contact.testing.strategies import ellipsoids, quadrics, tangent_pairs
from quadric_contact.theory.certificate import separation_certificate
from quadric_contact.theory.geometric import decide_geometrically
from quadric_contact.theory.results import Region

CODES = {Region.R_MINUS: SEP_MINUS, Region.CONTACT: CROSSING, Region.R_PLUS: SEP_PLUS}


def test_the_step_lemma_exhaustively():
    """If n+ moves by exactly one between consecutive sample points (from 1 at -inf to 3 at
    +inf, four steps), each of the four intervals holds exactly one simple root: a root of
    multiplicity m changes n+ by at most m and by a number of m's parity, and the
    multiplicities add up to 4.  Every distribution of 4 (multiplicity-counted) roots over
    the four intervals, with every admissible change, is enumerated."""

    def changes(total: int) -> set[int]:
        # the change across an interval holding roots of total multiplicity `total`:
        # |change| <= total, change = total (mod 2)
        return {c for c in range(-total, total + 1) if (c - total) % 2 == 0}

    for dist in itertools.product(range(5), repeat=4):
        if sum(dist) != 4:
            continue
        for steps in itertools.product(*(changes(m) for m in dist)):
            if sum(steps) != 2:  # from n+ = 1 to n+ = 3
                continue
            if all(abs(s) == 1 for s in steps):
                assert dist == (1, 1, 1, 1)


def test_jacobi_and_the_rank_three_adjugate():
    """P'(l0) = tr(adj(l0 E + Q) E), and for a member of rank 3 with kernel vector X,
    adj = k X X^T: so P'(l0) = k X^T E X, zero when X lies on E (fact 3 of the module)."""
    lam = sp.Symbol("lambda")
    rng = np.random.default_rng(0)
    for _ in range(3):
        a = sp.Matrix(4, 4, lambda i, j: sp.Rational(int(rng.integers(-5, 6)), int(rng.integers(1, 4))))
        b = sp.Matrix(4, 4, lambda i, j: sp.Rational(int(rng.integers(-5, 6)), int(rng.integers(1, 4))))
        E, Q = a + a.T, b + b.T
        M = lam * E + Q
        assert sp.expand(sp.diff(M.det(), lam) - (M.adjugate() * E).trace()) == 0
    # rank 3: the unit sphere and the sphere of radius 2 about (3, 0, 0) touch at (1, 0, 0)
    E = sp.diag(1, 1, 1, -1)
    Q = sp.Matrix([[1, 0, 0, -3], [0, 1, 0, 0], [0, 0, 1, 0], [-3, 0, 0, 5]])
    M = 2 * E + Q  # lambda0 = 2: the member's singular point is the tangent point
    X = sp.Matrix([1, 0, 0, 1])
    assert M.rank() == 3 and sp.zeros(4, 1) == M * X
    adj = M.adjugate()
    k = adj[0, 0] / (X[0] * X[0])
    assert adj == k * X * X.T and (X.T * E * X)[0] == 0
    P = (sp.Symbol("l") * E + Q).det()
    assert sp.Poly(P, sp.Symbol("l")).eval(2) == 0 and sp.diff(P, sp.Symbol("l")).subs(sp.Symbol("l"), 2) == 0


def test_positive_count_needs_a_certain_nonzero_determinant():
    assert positive_count(1, 1, 1, 1) == 4
    assert positive_count(-1, 1, -1, 1) == 0
    assert positive_count(1, 1, 1, 0) == -1  # a singular member says nothing about its gap
    assert positive_count(1, 1, 1, UNCERTAIN) == -1
    assert positive_count(UNCERTAIN, 1, 1, 1) in (-1, 4)
    assert decide_from_counts(2, 1, 2, True) == CROSSING
    assert decide_from_counts(2, 3, 4, True) == SEP_PLUS
    assert decide_from_counts(0, 1, 2, True) == SEP_MINUS
    assert decide_from_counts(2, -1, 2, True) == UNCERTAIN
    assert decide_from_counts(2, -1, 2, False) == CROSSING


@settings(max_examples=60, deadline=None)
@given(
    st.lists(st.fractions(-50, 50, max_denominator=20), min_size=4, max_size=4), st.fractions(F(1, 10), 10)
)
def test_quartic_roots_of_real_rooted_quartics(roots, lead):
    x = sp.Symbol("x")
    p = sp.Poly(
        sp.Rational(lead.numerator, lead.denominator)
        * sp.prod(x - sp.Rational(r.numerator, r.denominator) for r in roots),
        x,
    )
    c = [float(v) for v in reversed(p.all_coeffs())]
    got = quartic_roots(*c)
    assert got[4]
    want = sorted(float(r) for r in roots)
    scale = max(1.0, max(abs(v) for v in want))
    gaps = [b - a for a, b in itertools.pairwise(want)]
    if min(gaps) >= 1e-2 * scale:
        # distinct roots: the approximations are close enough to place a sample point in each gap
        for g, w in zip(got[:4], want, strict=True):
            assert abs(g - w) <= 1e-6 * scale
    else:
        # multiple roots: approximations only need to be numbers (the certificate then abstains)
        assert all(np.isfinite(got[:4]))


@settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(st.floats(-4, 4), min_size=20, max_size=20), st.floats(-3, 3))
def test_member_error_bounds_hold(entries, s):
    """|E_k^ - E_k(s E + Q)| <= K_k M_k for the float member (MEMBER_ERRBOUND), against exact."""
    e = [float(v) for v in entries[:10]]
    q = [float(v) for v in entries[10:]]
    m = [s * a + b for a, b in zip(e, q, strict=True)]
    w = [abs(s) * abs(a) + abs(b) for a, b in zip(e, q, strict=True)]
    got = kernels.quadric_invariants(*m)
    mag = kernels.quadric_invariants_magnitude(*w)
    exact = kernels.quadric_invariants(*(F(s) * F(a) + F(b) for a, b in zip(e, q, strict=True)))
    for k in range(4):
        bound = eb.MEMBER_ERRBOUND[False][k] * mag[3 + k]
        assert abs(F(got[3 + k]) - exact[3 + k]) <= F(bound)


# the geometric decision takes up to seconds a pair: a few examples by default, many in the slow
# profile (HYPOTHESIS_PROFILE=slow)
_GEOMETRIC_EXAMPLES = 300 if settings.default.max_examples > 100 else 15


@settings(max_examples=_GEOMETRIC_EXAMPLES, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.tuples(ellipsoids(), quadrics()) | tangent_pairs())
def test_certificates_agree_with_the_geometric_decision(pair):
    """The exact certificate (when it decides) and the certified float one (when it decides)
    agree with the exact extremes of X^T Q X on E, which do not use the pencil's roots."""
    E, Q = pair
    cert = separation_certificate(characteristic_polynomial(E, Q))
    geo = decide_geometrically(E, Q)
    if cert.decided:
        assert cert.region == geo.region, (E, Q)
        # a definite member means strictly apart: the geometric minimum (maximum) is not 0
        if cert.region is Region.R_PLUS:
            assert geo.minimum.sign() > 0
        if cert.region is Region.R_MINUS:
            assert geo.maximum.sign() < 0
    pairs, _ = make_pairs(as_stack([E], "E"), as_stack([Q], "Q"))
    # the scalar certificate, and the block kernel the cascade runs
    for code in (
        int(separation_float(pairs, certified=True)[0]),
        int(signature_float(pairs, certified=True)[0]),
    ):
        if code != UNCERTAIN:
            assert code == CODES[geo.region], (E, Q)


def test_the_exact_certificate_on_a_tangent_pair_says_nothing():
    E, Q = Quadric.sphere(1), Quadric.sphere(1, (2, 0, 0))  # touching from outside
    assert not separation_certificate(characteristic_polynomial(E, Q)).decided
    pairs, _ = make_pairs(as_stack([E], "E"), as_stack([Q], "Q"))
    assert int(separation_float(pairs, certified=True)[0]) == UNCERTAIN
    assert int(signature_float(pairs, certified=True)[0]) == UNCERTAIN


def test_the_block_kernel_agrees_with_the_scalar_certificate():
    """The block kernel (fast reading, the scalar certificate where it is not sure) and the
    scalar certificate pair by pair: both certified, so never two different certain answers,
    and every certain answer is the exact certificate's."""
    from quadric_contact.testing.samples import random_ellipsoids

    rng = np.random.default_rng(3)
    E, _ = random_ellipsoids(300, rng, axes=(0.5, 2.0), box=2.0)
    Q, _ = random_ellipsoids(300, rng, axes=(0.5, 2.0), box=2.0)
    pairs, _ = make_pairs(as_stack(E, "E"), as_stack(Q, "Q"))
    a = signature_float(pairs, certified=True)
    b = separation_float(pairs, certified=True)
    both = (a != UNCERTAIN) & (b != UNCERTAIN)
    assert both.sum() > 200 and (a[both] == b[both]).all()
    assert (a[b != UNCERTAIN] != UNCERTAIN).all()  # the kernel falls back to the certificate
    # and every certain answer is right
    for k in np.flatnonzero(a != UNCERTAIN)[:40]:
        e, q = Quadric.from_matrix(E[k]), Quadric.from_matrix(Q[k])
        i = [inertia_from_minor_sums(principal_minor_sums_4(e.upper))]  # E is an ellipsoid: (3, 1) or (1, 3)
        assert {i[0].positive, i[0].negative} == {1, 3}
        assert CODES[separation_certificate(characteristic_polynomial(e, q)).region] == a[k]
