"""Tables 1-2 (corrected) as data: every smallness condition as a comparison of two monomials.

The exact scalar decision (:func:`quadric_contact.theory.smallness.smallness`) compares the
*squares* of the two positive sides of every inequality of the corrected Table 1
row of ``Q`` (and, for two ellipsoids, of the enclosing alternative).  Each square
is a product of integer powers of a few positive *primitives* of one matrix (of the matrix
with its canonical sign, all absolute values):

* ``P``: ``|det M|`` (``E4`` of the invariants);
* ``A3``: ``|det M00|`` (``detA``);
* ``J2``: ``|J|``, the sum of the principal 2x2 minors of M00 (``JA``);
* ``K3``: ``|E3|`` = ``|K|`` when ``det M00 = 0`` (``E3``);
* ``J1``: ``|E2|`` = ``|J'|`` when M00 has rank 1 (``E2``);
* ``T``: ``|tr M00|`` (``trA``);
* ``L1..L3``: ``|lambda_i|``, the eigenvalues of M00 in increasing order.

With ``d^2 = -det Q / det Q00`` and so on (:func:`quadric_contact.theory.smallness.table_2_parameters`),
for instance the curvature side of an ellipsoid ``Q`` is
``a^2/c^4 = mu_3^2 / (mu_1 d^2) = L3^2 A3 / (L1 P)``.  The semi-axes of ``E`` are
``alpha^2 = P/(A3 L1)`` and ``gamma^2 = P/(A3 L3)``, so Lemma 3's curvature
``(gamma/alpha^2)^2 = L1^2 A3/(L3 P)``.

A condition is ``(q_slot, e_slot, relation)``: the ``q_slot``-th monomial of ``Q`` is
``>=`` (:data:`GE`) or ``<=`` (:data:`LE`) the ``e_slot``-th monomial of ``E``.  All the
conditions of a kind must hold (a maximum of two curvatures, as for the one-sheet
hyperboloid or the hyperbolic paraboloid's ``max|mu|``, is two conditions).  For an
ellipsoid ``Q`` the enclosing alternative (``Q`` small with respect to ``E``,
Definition 1 being symmetric) is a second conjunction.

The monomials are checked against the scalar decision on random rational pairs
of every kind (``tests/test_smallness_arrays.py``); the signs the invariants of
each kind must have (so that the absolute values are the right ones) are read
off the standard forms of Table 1 (:func:`kind_signs`).
"""

from __future__ import annotations

from functools import cache
from typing import Any

import numpy as np

from quadric_contact.model.classification import (
    TABLE_1_KINDS,
    QuadricKind,
    principal_minor_sums_3,
    principal_minor_sums_4,
)
from quadric_contact.model.quadric import Quadric
from quadric_contact.modes.codes import SmallnessCode

__all__ = [
    "E_SIDES",
    "GE",
    "LE",
    "MAX_DEGREE",
    "NPRIM",
    "PRIMITIVES",
    "Q_SIDES",
    "TABLE_CONDITIONS",
    "SmallnessCode",
    "kind_arrays",
    "kind_signs",
    "monomial",
]

K = QuadricKind

PRIMITIVES = ("P", "A3", "J2", "K3", "J1", "T", "L1", "L2", "L3")
NPRIM = len(PRIMITIVES)
P, A3, J2, K3, J1, T, L1, L2, L3 = range(NPRIM)

INVARIANT_OF_PRIMITIVE = (6, 2, 1, 5, 4, 0)
"""For the primitives ``P .. T``: the output of
:func:`quadric_contact._generated.kernels.quadric_invariants` it is the absolute value of
(``(trA, JA, detA, E1, E2, E3, E4)``)."""

GE, LE = 0, 1


def monomial(**powers: int) -> tuple[int, ...]:
    """Exponent vector over :data:`PRIMITIVES` (``monomial(P=1, A3=-1, L3=-1)``)."""
    out = [0] * NPRIM
    for name, e in powers.items():
        out[PRIMITIVES.index(name)] = e
    return tuple(out)


# The squared sides of E (an ellipsoid with det E < 0 and E00 positive definite).
E_SIDES = (
    monomial(P=1, A3=-1, L1=-1),  # 0: alpha^2
    monomial(A3=1, L1=2, P=-1, L3=-1),  # 1: (gamma/alpha^2)^2, Lemma 3
    monomial(P=1, A3=-1, L3=-1),  # 2: gamma^2 (enclosing alternative)
    monomial(A3=1, L3=2, P=-1, L1=-1),  # 3: (alpha/gamma^2)^2 (enclosing alternative)
)
ALPHA2, CURV2, GAMMA2, ALPHA_CURV2 = range(4)

# The squared sides of Q, per kind, in the order of the conditions of Table 1 (corrected),
# as smallness.row_sides lists them.
Q_SIDES: dict[QuadricKind, tuple[tuple[int, ...], ...]] = {
    # d^2 = P/A3; a^2 = d^2/mu1, c^2 = d^2/mu3
    K.ELLIPSOID: (
        monomial(P=1, A3=-1, L3=-1),  # c^2
        monomial(A3=1, L3=2, P=-1, L1=-1),  # (a/c^2)^2
        monomial(P=1, A3=-1, L1=-1),  # a^2 (enclosing: gamma >= a)
        monomial(A3=1, L1=2, P=-1, L3=-1),  # (c/a^2)^2 (enclosing: alpha/gamma^2 <= c/a^2)
    ),
    # eigenvalues n < 0 < p1 <= p2: a^2 = d^2/p1, b^2 = d^2/p2, c^2 = d^2/|n|
    K.HYPERBOLOID_ONE_SHEET: (
        monomial(P=1, A3=-1, L3=-1),  # b^2
        monomial(A3=1, L1=2, P=-1, L2=-1),  # (a/c^2)^2
        monomial(A3=1, L3=2, P=-1, L2=-1),  # (a/b^2)^2 (corrected)
    ),
    K.HYPERBOLOID_TWO_SHEETS: (
        monomial(P=1, A3=-1, L1=-1),  # c^2
        monomial(A3=1, L3=2, P=-1, L1=-1),  # (c/b^2)^2
    ),
    # L^2 = 4 P/J2, b^2 = L/max|mu|: (2/b^2)^2 = max|mu|^2 J2/P
    K.ELLIPTIC_PARABOLOID: (monomial(J2=1, L3=2, P=-1),),
    K.HYPERBOLIC_PARABOLOID: (
        monomial(J2=1, L3=2, P=-1),  # mu = the positive eigenvalue
        monomial(J2=1, L1=2, P=-1),  # mu = the negative one
    ),
    # M^2 = K3/J2; eigenvalues 0 < m1 <= m2: a^2 = M^2/m1, b^2 = M^2/m2
    K.ELLIPTIC_CYLINDER: (
        monomial(K3=1, J2=-1, L3=-1),  # b^2
        monomial(J2=1, L3=2, K3=-1, L2=-1),  # (a/b^2)^2
    ),
    # eigenvalues n < 0 < p: a^2 = M^2/p (transverse), b^2 = M^2/|n|
    K.HYPERBOLIC_CYLINDER: (
        monomial(K3=1, J2=-1, L3=-1),  # a^2 (corrected)
        monomial(J2=1, L1=2, K3=-1, L3=-1),  # (a/b^2)^2
    ),
    # rank 1, mu = tr: (2/a^2)^2 = mu^3/|K| (corrected d'^2 = -4 K a'^2)
    K.PARABOLIC_CYLINDER: (monomial(T=3, K3=-1),),
    # a^2 = |J'|/mu^2
    K.PARALLEL_PLANES: (monomial(J1=1, T=-2),),
}

# (q_slot, e_slot, relation): the conditions of the corrected row; for the ellipsoid
# the enclosing alternative as a second tuple.
TABLE_CONDITIONS: dict[
    QuadricKind, tuple[tuple[tuple[int, int, int], ...], tuple[tuple[int, int, int], ...]]
] = {
    K.ELLIPSOID: (((0, ALPHA2, GE), (1, CURV2, LE)), ((2, GAMMA2, LE), (3, ALPHA_CURV2, GE))),
    K.HYPERBOLOID_ONE_SHEET: (((0, ALPHA2, GE), (1, CURV2, LE), (2, CURV2, LE)), ()),
    K.HYPERBOLOID_TWO_SHEETS: (((0, ALPHA2, GE), (1, CURV2, LE)), ()),
    K.ELLIPTIC_PARABOLOID: (((0, CURV2, LE),), ()),
    K.HYPERBOLIC_PARABOLOID: (((0, CURV2, LE), (1, CURV2, LE)), ()),
    K.ELLIPTIC_CYLINDER: (((0, ALPHA2, GE), (1, CURV2, LE)), ()),
    K.HYPERBOLIC_CYLINDER: (((0, ALPHA2, GE), (1, CURV2, LE)), ()),
    K.PARABOLIC_CYLINDER: (((0, CURV2, LE),), ()),
    K.PARALLEL_PLANES: (((0, ALPHA2, GE),), ()),
}

MAX_DEGREE = max(sum(abs(e) for e in m) for m in (*E_SIDES, *(m for s in Q_SIDES.values() for m in s)))
"""The largest number of factors of a monomial (the float filter's range guard depends on it)."""

MAX_SLOTS = max(len(s) for s in Q_SIDES.values())
MAX_CONDITIONS = max(len(c[0]) for c in TABLE_CONDITIONS.values())
MAX_ALTERNATIVE = max(len(c[1]) for c in TABLE_CONDITIONS.values())


@cache
def kind_signs(kind: QuadricKind) -> tuple[int, ...]:
    """The signs the primitives of ``kind`` have before the absolute value: signs of
    ``(det, detA, JA, E3, E2, trA, lambda_1, lambda_2, lambda_3)`` of the matrix with the
    canonical sign, read off the standard form of Table 1 (they depend only on the type).
    For ``E`` use ``kind_signs(QuadricKind.ELLIPSOID)``."""

    params = dict(zip(Quadric.standard_parameters(kind), (3, 2, 1), strict=False))
    q = Quadric.standard(kind, **params)
    assert q.kind is kind and q.canonical_sign == 1
    u = q.upper
    tr, J, det00 = principal_minor_sums_3((u[0], u[1], u[2], u[4], u[5], u[7]))
    _, E2, E3, E4 = principal_minor_sums_4(u)
    # the standard forms have a diagonal quadratic part
    eig = sorted((u[0], u[4], u[7]))
    values = (E4, det00, J, E3, E2, tr, *eig)
    return tuple((v > 0) - (v < 0) for v in values)


@cache
def kind_arrays() -> dict[str, np.ndarray]:
    """The tables as arrays for the compiled kernels, indexed by the position of a kind in
    :data:`~quadric_contact.model.classification.TABLE_1_KINDS`:

    ``exponents`` (9, MAX_SLOTS, NPRIM) int64, ``nslots`` (9,), ``signs`` (9, NPRIM) (0 where the
    primitive is not used), ``cond`` (9, MAX_CONDITIONS, 3) and ``ncond`` (9,), ``alt``
    (9, MAX_ALTERNATIVE, 3) and ``nalt`` (9,), ``e_exponents`` (4, NPRIM), ``e_signs`` (NPRIM,).
    """
    n = len(TABLE_1_KINDS)
    exps = np.zeros((n, MAX_SLOTS, NPRIM), dtype=np.int64)
    nslots = np.zeros(n, dtype=np.int64)
    signs = np.zeros((n, NPRIM), dtype=np.int64)
    cond = np.zeros((n, MAX_CONDITIONS, 3), dtype=np.int64)
    ncond = np.zeros(n, dtype=np.int64)
    alt = np.zeros((n, max(MAX_ALTERNATIVE, 1), 3), dtype=np.int64)
    nalt = np.zeros(n, dtype=np.int64)
    for k, kind in enumerate(TABLE_1_KINDS):
        sides = Q_SIDES[kind]
        nslots[k] = len(sides)
        used = np.zeros(NPRIM, dtype=bool)
        for s, m in enumerate(sides):
            exps[k, s] = m
            used |= np.array(m) != 0
        signs[k] = np.where(used, kind_signs(kind), 0)
        assert (signs[k][used] != 0).all(), f"a primitive of {kind} is zero"
        inner, outer = TABLE_CONDITIONS[kind]
        ncond[k], nalt[k] = len(inner), len(outer)
        for c, row in enumerate(inner):
            cond[k, c] = row
        for c, row in enumerate(outer):
            alt[k, c] = row
    e_used = np.zeros(NPRIM, dtype=bool)
    for m in E_SIDES:
        e_used |= np.array(m) != 0
    e_signs = np.where(e_used, kind_signs(K.ELLIPSOID), 0)
    return {
        "exponents": exps,
        "nslots": nslots,
        "signs": signs,
        "cond": cond,
        "ncond": ncond,
        "alt": alt,
        "nalt": nalt,
        "e_exponents": np.array(E_SIDES, dtype=np.int64),
        "e_signs": e_signs.astype(np.int64),
    }


def kind_index(kind: QuadricKind) -> int:
    """Position of a Table 1 kind in :data:`~quadric_contact.model.classification.TABLE_1_KINDS`."""
    return TABLE_1_KINDS.index(kind)


def evaluate(values: Any, exponents: tuple[int, ...]) -> Any:
    """A monomial at primitive values of any number type (``values[j]`` for primitive ``j``)."""
    num: Any = 1
    den: Any = 1
    for j, e in enumerate(exponents):
        for _ in range(abs(e)):
            if e > 0:
                num = num * values[j]
            else:
                den = den * values[j]
    return num / den
