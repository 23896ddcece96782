"""The decision table (quadric_contact.theory.decision): one table for the scalar path, every
number mode and the kernels, checked against the exact extremes of X^T Q X on E and against
the paper's criterion where E is small."""

from __future__ import annotations

from fractions import Fraction
from itertools import product

import numpy as np
import pytest

import quadric_contact as qc
from quadric_contact.modes import ContactCode, ContactKindCode, RegionCode
from quadric_contact.modes.decision import separation as sep
from quadric_contact.testing.hardcases import hard_cases
from quadric_contact.testing.samples import random_pairs
from quadric_contact.testing.symmetric import axis_family, stable
from quadric_contact.theory import decision as dec
from quadric_contact.theory.decision import Definite, Plane, Roots, Rule, Surface
from quadric_contact.theory.geometric import decide_geometrically
from quadric_contact.theory.pencil import characteristic_polynomial


def test_codes_are_the_array_codes():
    assert (dec.NO_CONTACT, dec.CONTACT, dec.UNCERTAIN) == (
        ContactCode.NO_CONTACT,
        ContactCode.CONTACT,
        ContactCode.UNCERTAIN,
    )
    assert (dec.R_MINUS, dec.R_CONTACT, dec.R_PLUS, dec.UNCERTAIN) == (
        RegionCode.R_MINUS,
        RegionCode.CONTACT,
        RegionCode.R_PLUS,
        RegionCode.UNCERTAIN,
    )
    assert (sep.SEP_MINUS, sep.CROSSING, sep.SEP_PLUS, sep.UNCERTAIN) == (-1, 0, 1, 2)


def test_known_facts_index_the_rule_they_name():
    """Every combination of known, consistent facts: the table holds decide_facts' answer."""
    for s, r, d, p in product(range(3), range(4), range(3), range(2)):
        if dec._consistent(s, r, d, p):
            k = dec.table_index(s, r, d, p)
            assert (dec.CONTACT_OF[k], dec.REGION_OF[k], dec.RULE_OF[k]) == dec.decide_facts(s, r, d, p)


def test_unknown_facts_answer_only_where_every_completion_agrees():
    unknown = dec.table_index(Surface.UNKNOWN, Roots.UNKNOWN, Definite.UNKNOWN, Plane.UNKNOWN)
    assert dec.CONTACT_OF[unknown] == dec.UNCERTAIN and dec.REGION_OF[unknown] == dec.UNCERTAIN
    # a definite member decides whatever else is unknown
    for definite, region in ((Definite.POSITIVE, dec.R_PLUS), (Definite.NEGATIVE, dec.R_MINUS)):
        k = dec.table_index(Surface.UNKNOWN, Roots.UNKNOWN, definite, Plane.UNKNOWN)
        assert (dec.CONTACT_OF[k], dec.REGION_OF[k]) == (dec.NO_CONTACT, region)
    # non-real roots exclude a definite member: a crossing though definiteness is unread
    k = dec.table_index(Surface.UNKNOWN, Roots.NONREAL, Definite.UNKNOWN, Plane.UNKNOWN)
    assert (dec.CONTACT_OF[k], dec.REGION_OF[k], dec.RULE_OF[k]) == (
        dec.CONTACT,
        dec.R_CONTACT,
        Rule.NONREAL_ROOTS,
    )
    # four simple roots and no member definite: a crossing, whatever the type of Q
    k = dec.table_index(Surface.UNKNOWN, Roots.SIMPLE, Definite.NONE, Plane.UNKNOWN)
    assert dec.CONTACT_OF[k] == dec.CONTACT
    # a multiple root without a definite member: only the exact analysis can tell
    k = dec.table_index(Surface.REAL, Roots.MULTIPLE, Definite.NONE, Plane.OTHER)
    assert dec.RULE_OF[k] == Rule.ESCALATE and dec.CONTACT_OF[k] == dec.UNCERTAIN


def test_the_separation_kernel_reads_the_table():
    """The kernels' counts-to-answer step is a lookup in the same table (plain Python run of
    the compiled function, so the test needs no compiler)."""
    assert sep._REGION_OF is dec.REGION_OF  # the kernels' constant is the table itself
    f = getattr(sep.decide_from_counts, "py_func", sep.decide_from_counts)
    assert f(2, 3, 4, True) == sep.SEP_PLUS and f(0, 1, 2, True) == sep.SEP_MINUS
    assert f(2, 1, 2, True) == sep.CROSSING  # 1, 2, 1, 2, 3: four simple roots
    assert f(2, 2, 2, True) == sep.UNCERTAIN and f(2, 2, 2, False) == sep.CROSSING
    assert f(-1, 3, 2, True) == sep.UNCERTAIN


def _exact_pairs(seed: int, n: int) -> list[tuple[np.ndarray, np.ndarray]]:
    E, Q, _ = random_pairs(n, np.random.default_rng(seed))
    return [(E[i], Q[i]) for i in range(n)]


@pytest.mark.parametrize("seed", [0, 1])
def test_the_decision_equals_the_exact_extremes(seed):
    """Against the exact extremes of X^T Q X on E (theory.geometric), which decide without the
    pencil's signatures: random pairs of every type."""
    for E, Q in _exact_pairs(seed, 12):
        P = characteristic_polynomial(E, Q)
        d = dec.decide_pencil(P)
        geo = decide_geometrically(P.E, P.Q)
        if d.transversal is not None:
            assert d.transversal == geo.transversal, (E, Q, d, geo)
        if d.region_value is not None:
            assert d.region_value == geo.region, (E, Q, d, geo)


def test_symmetric_placements_decided_without_escalating_where_kernels_lie_at_infinity():
    """A sphere on the axis of a cylinder: the double root of the symmetry has its member's
    kernel at infinity, so the table decides a crossing without the geometric analysis; inside,
    a definite member.  The exact extremes agree."""
    Q = qc.Quadric.from_equation("x**2 + y**2 - 1")
    inside = dec.decide_exact(qc.Quadric.sphere(Fraction(1, 2), (0, 0, 1)), Q)
    assert inside.rule is Rule.NEGATIVE_MEMBER and inside.transversal is False
    E = qc.Quadric.sphere(Fraction(3, 2), (0, 0, 1))
    crossing = dec.decide_exact(E, Q)
    assert crossing.rule is Rule.HARMLESS_ROOTS and 2 in crossing.facts.multiplicities
    assert crossing.transversal is decide_geometrically(E, Q).transversal is True


def test_the_paper_route_agrees_where_e_is_small():
    """Corollary 10 (the paper's route, with the exact smallness of Tables 1-2) and the table
    give the same answer wherever the paper's route decides."""
    seen = 0
    for E, Q in _exact_pairs(7, 40):
        try:
            paper = qc.transversal_contact(E, Q, method="theory")
        except qc.ExcludedQuadricError:
            continue
        if not paper.decided:
            continue
        seen += 1
        assert paper.transversal == qc.transversal_contact(E, Q).transversal
    assert seen >= 10


def test_float_mode_is_right_on_symmetric_placements():
    """The float mode reads the same table in binary64 (and the mpmath mode in its digits);
    symmetric placements (multiple roots that rounding turns non-real) are answered as the
    exact decision answers them wherever that answer is stable under a small perturbation, for
    every question (contact, region, kind), scalar and stack alike."""
    family = axis_family()

    def exact_contact(E, Q):
        return qc.transversal_contact(E, Q, mode="exact")

    keep = stable(family, exact_contact)
    assert keep.sum() >= 0.9 * len(family)
    family = [p for p, k in zip(family, keep, strict=True) if k]
    E = np.stack([p.E for p in family])
    Q = np.stack([p.Q for p in family])
    exact = exact_contact(E, Q)
    region = qc.relative_position(E, Q, mode="exact")
    assert set(exact.tolist()) == {0, 1}  # both answers occur
    kind = qc.contact_kind(E, Q, mode="exact")
    for mode in ("float", "mpmath"):
        assert (qc.transversal_contact(E, Q, mode=mode) == exact).all(), mode
        assert (qc.relative_position(E, Q, mode=mode) == region).all(), mode
        assert (qc.contact_kind(E, Q, mode=mode) == kind).all(), mode
        for k in range(0, len(family), 7):
            one = qc.transversal_contact(family[k].E, family[k].Q, mode=mode)
            assert one.transversal == bool(exact[k]), (mode, family[k].name)
            one_kind = qc.contact_kind(family[k].E, family[k].Q, mode=mode)
            assert ContactKindCode.from_kind(one_kind) == kind[k], family[k].name


def test_the_symmetric_family_is_hard_for_the_raw_criterion():
    """The raw float criterion (non-real roots read from rounded discriminants) calls some of
    these placements crossings although they are apart: the family exercises the fault."""
    family = axis_family()
    E = np.stack([p.E for p in family])
    Q = np.stack([p.Q for p in family])
    exact = qc.transversal_contact(E, Q, mode="exact")
    raw = qc.corollary_10(E, Q, mode="float")
    assert np.count_nonzero((raw == 1) & (exact == 0)) > 0


def test_float_mode_is_right_on_the_ladders_down_to_1e_12():
    """The hard-case ladders (binary64 rounding of exact placements at distances 1e-2 .. 1e-16
    from tangency): down to 1e-12 the float mode gives the exact answer for the rounded input."""
    cases = [
        c
        for c in hard_cases(("ladder",))
        if c.direction != "tangent" and c.distance is not None and float(c.distance) >= 1e-12
    ]
    assert len(cases) > 50
    pairs = [c.matrices() for c in cases]
    E = np.stack([e for e, _ in pairs])
    Q = np.stack([q for _, q in pairs])
    exact = qc.transversal_contact(E, Q, mode="exact")
    got = qc.transversal_contact(E, Q, mode="float")
    wrong = [c.id for c, a, b in zip(cases, got, exact, strict=True) if a != b]
    assert wrong == []


def test_scalar_and_stack_read_the_same_facts_through_the_same_table():
    """The kernels' Sylvester test and the scalar path's read the same generated program; on
    the same pairs, a definite member found by the certified kernel is the one the exact facts
    report (same sign), and a crossing it certifies is a crossing of the exact decision."""
    from quadric_contact.modes.stacks.batch import as_stack, make_pairs

    E, Q, _ = random_pairs(60, np.random.default_rng(11))
    pairs, _ = make_pairs(as_stack(E, "E"), as_stack(Q, "Q"))
    codes = sep.separation_float(pairs, certified=True)
    for i in range(60):
        exact = dec.decide_exact(E[i], Q[i])
        if codes[i] != sep.UNCERTAIN:
            assert codes[i] == exact.region, (i, codes[i], exact)
        if exact.rule in (Rule.POSITIVE_MEMBER, Rule.NEGATIVE_MEMBER):
            assert codes[i] in (exact.region, sep.UNCERTAIN)


def test_definiteness_is_sylvester_on_the_generated_program():
    from quadric_contact._generated.kernels import leading_minors_4

    rng = np.random.default_rng(5)
    for _ in range(200):
        a = rng.integers(-5, 6, size=(4, 4))
        m = a @ a.T * rng.choice([-1, 1]) + rng.integers(-3, 4) * np.eye(4, dtype=int)
        upper = tuple(int(m[i, j]) for i in range(4) for j in range(i, 4))
        eig = np.linalg.eigvalsh(m.astype(float))
        got = dec.definiteness(upper)
        if eig.min() > 1e-9:
            assert got is Definite.POSITIVE
        elif eig.max() < -1e-9:
            assert got is Definite.NEGATIVE
        elif eig.min() < -1e-9 and eig.max() > 1e-9:
            assert got is Definite.NONE
        d = leading_minors_4(*upper)
        assert d[3] == round(np.linalg.det(m.astype(float)))


def test_where_p_is_positive_three_minors_decide_definiteness_as_four_do():
    """The short reading of the common pairs: a member where ``P > 0`` has a positive
    determinant, so Sylvester's minors of orders 1-3 decide what all four decide."""
    rng = np.random.default_rng(11)
    E, Q, _ = random_pairs(150, rng)
    seen = {Definite.POSITIVE: 0, Definite.NEGATIVE: 0, Definite.NONE: 0}
    for i in range(len(E)):
        try:
            pencil = dec.Pencil(characteristic_polynomial(E[i], Q[i]))
        except qc.ExcludedQuadricError:
            continue
        for mu in (Fraction(k, 4) for k in range(-40, 41, 3)):
            n, d = mu.numerator, mu.denominator
            if pencil.sign_at(n, d) > 0:
                got = pencil.definite_where_p_positive(n, d)
                assert got is dec.definiteness(pencil.member(n, d)), (i, mu)
                seen[got] += 1
            else:
                assert dec.definiteness(pencil.member(n, d)) is Definite.NONE, (i, mu)
    assert min(seen.values()) > 20, seen  # every answer was met


def test_float_mode_reads_rounded_cylinders_by_the_members_not_by_rounded_root_signs():
    """Rotated parabolic cylinders rounded to binary64 are ellipsoids with two nearly zero
    eigenvalues; binary64's signs of P's coefficients then read two positive roots (E outside)
    where E lies well inside.  The float mode keeps that reading only where its certified guard
    reads the same, and answers the region of every such pair as the exact decision does."""
    from quadric_contact.modes.predicates import relative_position
    from quadric_contact.testing.samples import complete_populations

    E, Q, _ = complete_populations(300_000, np.random.default_rng(0))["every type"]
    # the pairs of that population (seed 0) where binary64's root signs misread the side
    rows = [13407, 33143, 67233, 69693, 72721, 100277, 121319, 126889]
    Es, Qs = E[rows], Q[rows]
    want = relative_position(Es, Qs, mode="exact")
    assert (relative_position(Es, Qs, mode="float") == want).all()
    for k in range(len(rows)):
        q = qc.Quadric.from_matrix(Qs[k])
        assert q.kind.value == "ellipsoid" and abs(np.linalg.det(Qs[k][:3, :3])) < 1e-12
        # the answer is not delicate: the centre of E is far from the surface
        e = qc.Quadric.from_matrix(Es[k])
        assert abs(float(q.value_at(e.center()))) > 0.1
