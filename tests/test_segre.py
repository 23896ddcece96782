"""The Segre characteristic of a pencil, on pencils whose Jordan structure is known."""

from __future__ import annotations

from collections import Counter
from fractions import Fraction as F

from hypothesis import given
from hypothesis import strategies as st

from quadric_contact import Quadric
from quadric_contact.testing.strategies import ellipsoids, quadrics, rigid_motions
from quadric_contact.theory.segre import segre_symbol

positive = st.integers(1, 4).map(F)
entries = st.integers(-3, 3).map(F)


@given(st.tuples(positive, positive, positive, positive), st.tuples(entries, entries, entries, entries))
def test_a_diagonal_pencil_has_one_block_per_entry(e, q):
    """``E = diag(e0, e1, e2, -e3)`` and ``Q = diag(q0..q3)``: ``det(lambda E + Q)`` has the
    roots ``-q_i / E_ii``, and the pencil is diagonal, so every Jordan block has size 1: the
    symbol groups the equal roots, ``(11)`` for a double one, and all roots are real."""
    E = Quadric.diagonal(e[0], e[1], e[2], -e[3])
    if not any(q):
        return
    Q = Quadric.diagonal(*q)
    diag_e = (e[0], e[1], e[2], -e[3])
    roots = Counter(-qi / ei for qi, ei in zip(q, diag_e, strict=True))
    s = segre_symbol(E, Q)
    expected = sorted("1" if k == 1 else "(" + "1" * k + ")" for k in roots.values())
    assert sorted(str(g) for g in s.groups) == expected
    assert s.real_roots == len(roots)
    assert {g.eigenvalue.as_fraction(): g.multiplicity for g in s.groups} == dict(roots)


@given(ellipsoids(bound=3), quadrics(bound=3), rigid_motions(bound=3))
def test_the_symbol_is_invariant_under_a_common_motion(E, Q, m):
    s = segre_symbol(E, Q)
    assert segre_symbol(E.moved(m), Q.moved(m)) == s
    assert sum(g.multiplicity for g in s.groups) == 4  # det(lambda E + Q) has degree 4 (det E != 0)


def test_a_jordan_block_of_size_two():
    """Example 11: a double root with a rank-2 member is ``(11)``; the sphere tangent to a
    plane from outside gives a root of multiplicity 2 with one block of size 2 ... the
    printed symbols of the paper's examples."""
    assert str(segre_symbol("2*x**2 + 2*y**2 + 3*z**2 - 1", "x**2 + y**2 + 8*z")) == "[(11)11]_1"
    # a unit sphere and the plane z = 1 that touches it: P = lambda^2 (...) with a non-diagonalisable root
    s = segre_symbol(Quadric.sphere(1), Quadric.plane((0, 0, 1), 1))
    assert sum(g.multiplicity for g in s.groups) == 4
    assert any(max(g.blocks) >= 2 for g in s.groups)  # tangency: a block of size at least 2
