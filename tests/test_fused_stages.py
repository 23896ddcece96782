"""The faster paths of the complete decision give the answers of the slower ones.

* Two ellipsoids whose characteristic polynomial has two positive roots are settled at the
  criterion (Wang-Wang-Kim: ``E`` outside ``Q`` or touching it from outside), for every pair,
  small or not: the certified answer equals the exact scalar one.
* Smallness of a sub-batch of distinct ellipsoids (taken in order) runs the fused loop, and
  the criterion of a sub-batch against one quadric the fixed-quadric kernel: the compiled
  codes equal the numpy fallback's.
"""

from __future__ import annotations

from fractions import Fraction as F

import numpy as np
import pytest

from quadric_contact import Quadric, relative_position, transversal_contact
from quadric_contact.modes import CertifiedMode, FilterMode, RegionCode
from quadric_contact.modes.kernels._jit import HAVE_NUMBA
from quadric_contact.modes.stacks.batch import as_stack, make_pairs
from quadric_contact.modes.stacks.pairs import Pairs
from quadric_contact.testing.samples import random_ellipsoids
from quadric_contact.theory.contact import transversal_contact_exact
from quadric_contact.theory.regions import relative_position_exact

numba_only = pytest.mark.skipif(not HAVE_NUMBA, reason="the compiled kernels need numba")

# name: (E, Q); exact constructions, both ellipsoids
PAIRS = {
    "apart": (Quadric.sphere(1), Quadric.ellipsoid(1, 2, 3, center=(5, 0, 0))),
    "apart, Q negated": (Quadric.sphere(1), -Quadric.ellipsoid(1, 2, 3, center=(5, 0, 0))),
    "touching from outside": (Quadric.sphere(1), Quadric.sphere(1, (2, 0, 0))),
    "touching, Q negated": (Quadric.sphere(1), -Quadric.sphere(1, (2, 0, 0))),
    "apart, E large": (Quadric.ellipsoid(5, 4, 3), Quadric.sphere(F(1, 10), (7, 0, 0))),
    "apart, rotated": (
        Quadric.ellipsoid(3, F(1, 5), F(1, 4), center=(F(1, 10), F(1, 7), F(1, 9)), rotation=(1, 2, 3, 4)),
        Quadric.ellipsoid(2, 1, F(1, 2), center=(4, 3, 0), rotation=(2, 1, 0, 1)),
    ),
    "E inside Q": (Quadric.sphere(F(1, 2)), Quadric.ellipsoid(3, 4, 5)),
    "Q inside E": (Quadric.ellipsoid(3, 4, 5), Quadric.sphere(F(1, 2))),
    "crossing": (Quadric.sphere(1), Quadric.sphere(1, (1, 0, 0))),
    "touching from inside": (Quadric.sphere(1), Quadric.sphere(2, (1, 0, 0))),
}


@pytest.mark.parametrize("name", list(PAIRS))
def test_two_ellipsoids_certified_equals_exact(name):
    E, Q = PAIRS[name]
    mode = CertifiedMode()
    got = int(transversal_contact([E], [Q], mode=mode)[0])
    assert got == int(transversal_contact_exact(E, Q).transversal)
    got = int(relative_position([E], [Q], mode=CertifiedMode())[0])
    assert got == int(RegionCode.from_region(relative_position_exact(E, Q).region))


@pytest.mark.parametrize("name", ["apart", "apart, Q negated", "apart, E large", "apart, rotated"])
def test_two_positive_roots_are_settled_at_the_criterion(name):
    """Apart (not touching: the filter reads the root signs), whether small or not."""
    E, Q = PAIRS[name]
    for predicate in (transversal_contact, relative_position):
        mode = CertifiedMode()
        predicate([E], [Q], mode=mode)
        decided = {k: v for k, v in mode.last.decided.items() if v}
        assert all(k.startswith("criterion (") for k in decided), (predicate.__name__, decided)


def _random_pairs(n: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    E, _ = random_ellipsoids(n, rng, axes=(0.5, 2.0), box=2.0)
    Q, _ = random_ellipsoids(n, rng, axes=(0.5, 2.0), box=2.0)
    return E, Q


def test_random_ellipsoid_pairs_equal_the_exact_answer():
    """Similar sizes (many pairs not small): the certified stack against the exact scalar path."""
    E, Q = _random_pairs(40, 3)
    contact = transversal_contact(E, Q, mode=CertifiedMode())
    region = relative_position(E, Q, mode=CertifiedMode())
    for k in range(E.shape[0]):
        e, q = Quadric.from_matrix(E[k]), Quadric.from_matrix(Q[k])
        assert int(contact[k]) == int(transversal_contact_exact(e, q).transversal)
        assert int(region[k]) == int(RegionCode.from_region(relative_position_exact(e, q).region))


@numba_only
@pytest.mark.parametrize("predicate", [transversal_contact, relative_position])
def test_compiled_and_numpy_backends_agree_on_the_complete_decision(predicate):
    E, Q = _random_pairs(3000, 4)
    small, _ = random_ellipsoids(3000, np.random.default_rng(5), axes=(0.1, 0.5), box=6.0)
    env = Quadric.ellipsoid(3, 4, 5).to_numpy()
    for e, q in ((E, Q), (small, env)):
        a = predicate(e, q, mode=CertifiedMode(backend="numba"))
        b = predicate(e, q, mode=CertifiedMode(backend="numpy"))
        np.testing.assert_array_equal(a, b)


def _sub_batches(n: int):
    rng = np.random.default_rng(6)
    increasing = np.flatnonzero(rng.random(n) < 0.7)
    return {"in order": increasing, "shuffled": rng.permutation(increasing), "repeated": np.sort(
        rng.integers(0, n, size=n // 2))}  # fmt: skip


@numba_only
@pytest.mark.parametrize("which", ["in order", "shuffled", "repeated"])
def test_smallness_of_a_sub_batch_compiled_equals_numpy(which):
    n = 2000
    small, _ = random_ellipsoids(n, np.random.default_rng(7), axes=(0.1, 2.0), box=6.0)
    for env in (Quadric.ellipsoid(3, 4, 5).to_numpy(), Quadric.hyperboloid_one_sheet(2, 3, 4).to_numpy()):
        pairs, _ = make_pairs(as_stack(small, "E"), as_stack(env, "Q"))
        rows = _sub_batches(n)[which]
        # the one quadric by an index of zeros (Pairs.take) and unindexed (the pipeline's)
        for sub in (pairs.take(rows), Pairs(pairs.E, pairs.Q, rows.size, rows, None)):
            a = FilterMode(backend="numba").smallness(sub)
            b = FilterMode(backend="numpy").smallness(sub)
            np.testing.assert_array_equal(a, b)
            assert (a != 2).mean() > 0.5  # the filter decides most of them


@numba_only
@pytest.mark.parametrize("which", ["in order", "shuffled", "repeated"])
def test_criterion_of_a_sub_batch_against_one_quadric_compiled_equals_numpy(which):
    n = 2000
    small, _ = random_ellipsoids(n, np.random.default_rng(8), axes=(0.1, 2.0), box=6.0)
    pairs, _ = make_pairs(as_stack(small, "E"), as_stack(Quadric.ellipsoid(3, 4, 5).to_numpy(), "Q"))
    rows = _sub_batches(n)[which]
    sub = Pairs(pairs.E, pairs.Q, rows.size, rows, None)
    for method in ("criterion_contact", "criterion_region"):
        a = getattr(FilterMode(backend="numba"), method)(sub)
        b = getattr(FilterMode(backend="numpy"), method)(sub)
        np.testing.assert_array_equal(a, b)


def test_packed_stacks_are_validated_without_unpacking_and_name_the_bad_row():
    """A packed stack is checked on its ten entries (symmetric by construction); a non-finite
    entry is still refused with the row that holds it, in every mode."""
    import quadric_contact as qc
    from quadric_contact.exact.errors import NonFiniteError

    E = np.tile(np.diag([1.0, 1.0, 1.0, -1.0]), (5, 1, 1))
    Q = np.tile(np.diag([1.0, 1.0, 1.0, -9.0]), (5, 1, 1))
    Q[:, :3, 3] = Q[:, 3, :3] = [5.0, 0.0, 0.0]
    PE, PQ = qc.pack(E), qc.pack(Q)
    for mode in ("certified", "filter", "float", "exact"):
        expect = qc.transversal_contact(E, Q, mode=mode)
        assert (qc.transversal_contact(qc.Packed(PE), qc.Packed(PQ), mode=mode) == expect).all()
    bad = PQ.copy()
    bad[3, 2] = np.nan
    with pytest.raises(NonFiniteError, match=r"\[3\]"):
        qc.transversal_contact(qc.Packed(PE), qc.Packed(bad), mode="certified")
