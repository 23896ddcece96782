"""Properties on random rational pairs (hypothesis, exact constructions):

* certified == exact, for exact rational input and for its binary64 rounding;
* plain float == exact wherever the filter's error bounds (alone) are conclusive;
* the discriminant criterion == numeric root finding (numpy eigenvalues, mpmath
  polyroots at 50 digits) away from tangency.
"""

import numpy as np
from hypothesis import assume, given
from hypothesis import strategies as st
from tests.oracles import criterion_contact as transversal_contact_batch
from tests.oracles import criterion_region as relative_position_batch
from tests.oracles import mpmath_nonreal, numpy_nonreal, scalar_codes

from quadric_contact import Quadric, characteristic_polynomial
from quadric_contact.modes import ContactCode
from quadric_contact.modes.decision.answers import CONTACT_TABLE, sign_index
from quadric_contact.modes.kernels.numpy_backend import filter_quantities
from quadric_contact.testing.strategies import ellipsoids, quadrics, tangent_pairs

pairs = st.one_of(
    st.tuples(ellipsoids(), quadrics()),
    st.tuples(ellipsoids(min_axis=0.05, max_axis=0.5), quadrics(kind="plane")),
    tangent_pairs(),
)
batches = st.lists(pairs, min_size=1, max_size=6)


def _stacks(batch, exact):
    dtype = object if exact else float
    E = np.array(
        [[[v if exact else float(v) for v in row] for row in e.matrix] for e, _ in batch], dtype=dtype
    )
    Q = np.array(
        [[[v if exact else float(v) for v in row] for row in q.matrix] for _, q in batch], dtype=dtype
    )
    return E, Q


@given(batches)
def test_certified_equals_exact_on_rational_pairs(batch):
    want = [scalar_codes(e, q) for e, q in batch]
    E, Q = _stacks(batch, exact=True)
    assert list(transversal_contact_batch(E, Q)) == [c for c, _ in want]
    assert list(relative_position_batch(E, Q)) == [r for _, r in want]


@given(batches)
def test_certified_equals_exact_on_their_binary64_roundings(batch):
    E, Q = _stacks(batch, exact=False)
    from quadric_contact import Quadric

    want = [scalar_codes(Quadric.from_matrix(e), Quadric.from_matrix(q)) for e, q in zip(E, Q, strict=True)]
    assert list(transversal_contact_batch(E, Q)) == [c for c, _ in want]
    assert list(relative_position_batch(E, Q)) == [r for _, r in want]


@given(batches)
def test_float_equals_exact_wherever_its_error_bound_is_conclusive(batch):
    E, Q = _stacks(batch, exact=False)
    from quadric_contact import Quadric

    # The bounds alone: no structural knowledge (equal quadratic parts, exact rank of Q).
    fq = filter_quantities(E, Q, same_ok=False)
    deltas = fq["signs"][5:]
    floats = transversal_contact_batch(E, Q, mode="float")
    for k in range(len(batch)):
        if fq["outside"][k]:
            continue
        code = CONTACT_TABLE[sum(m * sign_index(int(s[k])) for m, s in zip((1, 4, 16), deltas, strict=True))]
        if code == 2:
            continue
        exact, _ = scalar_codes(Quadric.from_matrix(E[k]), Quadric.from_matrix(Q[k]))
        assert code == exact == floats[k]


@given(st.lists(st.tuples(ellipsoids(), quadrics()), min_size=1, max_size=6))
def test_discriminant_criterion_agrees_with_numeric_root_finding(batch):
    E, Q = _stacks(batch, exact=True)
    codes = transversal_contact_batch(E, Q)
    checked = 0
    for (e, q), code in zip(batch, codes, strict=True):
        P = characteristic_polynomial(e, q)
        numeric = mpmath_nonreal(P)
        if numeric is None:
            continue
        assert (code == ContactCode.CONTACT) == numeric
        eig = numpy_nonreal(P.E.to_numpy(), q.to_numpy())
        if eig is not None:
            assert (code == ContactCode.CONTACT) == eig
        checked += 1
    assume(checked > 0)


def test_the_root_finding_oracle_abstains_where_it_does_not_converge():
    """Two coaxial spheroids: the pencil has a triple root, where mpmath's iteration can stall;
    the oracle then abstains (None) rather than fail the property test above."""
    e = Quadric.from_equation("x**2/9 + y**2 + z**2 - 1")
    q = Quadric.from_equation("16*x**2/225 + y**2 + z**2 - 1")
    P = characteristic_polynomial(e, q)
    assert mpmath_nonreal(P) in (None, False)  # never True: the roots are real
    (code,) = transversal_contact_batch(*_stacks([(e, q)], exact=True))
    assert code == ContactCode.NO_CONTACT  # nested spheroids: no crossing
