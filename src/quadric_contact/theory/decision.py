"""The decision: how an ellipsoid sits against a quadric, read off the signatures of its pencil.

One table, written once, decides transversal contact and the region for every pair
``(E, Q)`` with ``E`` a real ellipsoid (the paper's sign, ``det E < 0``), small or not.
Its inputs are four facts about the pencil ``lambda E + Q`` and ``P(lambda) = det(lambda E + Q)``
that any number mode can read (exactly, with a certified error bound, or in plain binary64);
the exact scalar path, every number mode and the compiled kernels all look their answer up
here.  The argument is ``proofs/twmw_2009_signature_decision.py``; in short:

* ``E`` has no real point at infinity, so the surfaces share a real point iff the forms
  ``X^T E X`` and ``X^T Q X`` have a common non-trivial real zero;  by Finsler-Calabi (four
  variables) they have none iff some member ``lambda E + Q`` is definite (``E`` is indefinite,
  so the member is not ``E`` itself).  A *positive* definite member means ``X^T Q X > 0`` on
  ``E`` (strictly ``R+``), a *negative* one ``< 0`` (strictly ``R-``).
* The inertia of ``lambda E + Q`` is constant on each gap between consecutive real roots of
  ``P`` (one positive eigenvalue at ``-inf``, three at ``+inf``), so one point per gap tells
  whether a definite member exists: the pencil's *signature sequence* (Tu, Wang, Mourrain,
  Wang, CAGD 26 (2009) 317-335).
* A tangency needs a real multiple root (at a tangent point ``X``, ``(lambda0 E + Q) X = 0``
  and ``P'(lambda0) = 0``).  With four simple roots, or when ``E`` is definite on the kernel
  of the member at each multiple root (so no real point of ``E`` is in it: the structural
  double root ``0`` of a plane or of parallel planes, whose kernel lies at infinity, and the
  multiple roots of symmetric placements), every common point is a transversal crossing:
  contact iff no definite member.
* Non-real roots exclude a definite member (a definite pencil is simultaneously
  diagonalisable): transversal contact (Remark 9).
* A plane with all roots real and no definite member touches ``E`` (Theorem 14).  Any other
  multiple root without a definite member is a singular intersection: the table says
  :data:`Rule.ESCALATE`, and the exact analysis (:mod:`quadric_contact.theory.geometric`)
  decides.

The paper's route (Corollary 10 with the smallness of Tables 1-2, Theorem 13 with Table 4)
stays public under its own names (``method="theory"``, :func:`quadric_contact.corollary_10`,
:func:`quadric_contact.smallness`) and is checked against this table where ``E`` is small.

Facts a number mode cannot tell are ``UNKNOWN``: the table answers for them only where every
consistent completion gives the same answer (:func:`table_index`, :data:`CONTACT_OF`,
:data:`REGION_OF`, :data:`RULE_OF`), as CGAL's filtered predicates do.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import IntEnum
from fractions import Fraction
from itertools import pairwise, product
from typing import Any

import numpy as np

from quadric_contact._generated.kernels import leading_minors_3, leading_minors_4
from quadric_contact.exact.algebraic import rational_between, real_roots
from quadric_contact.exact.linalg import nullspace
from quadric_contact.model.classification import NO_REAL_POINTS, QuadricKind
from quadric_contact.theory.pencil import CharacteristicPolynomial, characteristic_polynomial
from quadric_contact.theory.results import Region

__all__ = [
    "CONTACT_OF",
    "REGION_OF",
    "RULE_OF",
    "Definite",
    "Pencil",
    "PencilDecision",
    "PencilFacts",
    "Plane",
    "Roots",
    "Rule",
    "Surface",
    "decide_exact",
    "decide_facts",
    "decide_pencil",
    "definiteness",
    "pencil_facts",
    "table_index",
]

# The codes of the array predicates (quadric_contact.modes.codes.ContactCode / RegionCode), which
# this layer may not import; a test checks they agree.
NO_CONTACT, CONTACT, UNCERTAIN = 0, 1, 2
R_MINUS, R_CONTACT, R_PLUS = -1, 0, 1


class Surface(IntEnum):
    """Has ``Q`` real points?  (A quadric without any keeps one sign on all of space.)"""

    REAL = 0
    NONE_PLUS = 1  # no real point, X^T Q X > 0 off its real locus: R+
    NONE_MINUS = 2
    UNKNOWN = 3


class Roots(IntEnum):
    """The root pattern of ``P``."""

    NONREAL = 0  # a pair of non-real roots
    SIMPLE = 1  # four simple real roots
    HARMLESS = 2  # all real; E is definite on the kernel of the member at each multiple root
    MULTIPLE = 3  # all real, another multiple root
    UNKNOWN = 4


class Definite(IntEnum):
    """Does a gap between consecutive real roots of ``P`` hold a definite member?"""

    POSITIVE = 0
    NEGATIVE = 1
    NONE = 2
    UNKNOWN = 3


class Plane(IntEnum):
    """Is ``Q`` a plane (Theorem 14)?"""

    PLANE = 0
    OTHER = 1
    UNKNOWN = 2


class Rule(IntEnum):
    """The row of the table that decided."""

    NO_REAL_POINTS = 0
    POSITIVE_MEMBER = 1
    NEGATIVE_MEMBER = 2
    NONREAL_ROOTS = 3
    SIMPLE_ROOTS = 4
    HARMLESS_ROOTS = 5
    PLANE_TOUCHING = 6
    ESCALATE = 7  # a singular intersection: the exact analysis decides
    UNCERTAIN = 8  # the facts given do not decide

    @property
    def decided_by(self) -> str:
        """The name a result gives for this row."""
        return _DECIDED_BY[self]


_DECIDED_BY = {
    Rule.NO_REAL_POINTS: "no real points",
    Rule.POSITIVE_MEMBER: "signature sequence",
    Rule.NEGATIVE_MEMBER: "signature sequence",
    Rule.NONREAL_ROOTS: "Remark 9",
    Rule.SIMPLE_ROOTS: "signature sequence",
    Rule.HARMLESS_ROOTS: "signature sequence",
    Rule.PLANE_TOUCHING: "Theorem 14",
    Rule.ESCALATE: "geometric decision",
    Rule.UNCERTAIN: "undecided",
}


def decide_facts(surface: int, roots: int, definite: int, plane: int) -> tuple[int, int, int]:
    """``(contact code, region code, rule)`` for *known* facts: the decision, written once.

    Contact codes are ``NO_CONTACT = 0, CONTACT = 1, UNCERTAIN = 2`` and region codes
    ``R_MINUS = -1, CONTACT = 0, R_PLUS = 1, UNCERTAIN = 2`` (those of
    :class:`~quadric_contact.modes.ContactCode` and :class:`~quadric_contact.modes.RegionCode`);
    ``UNCERTAIN`` here means "not from these facts": the region of a touching plane (Corollary 15
    gives it) and everything of a singular intersection (:data:`Rule.ESCALATE`).

    A definite member is read before the roots: it is a certificate of separation on its own,
    and a number mode that reads inconsistent facts (a definite member *and* non-real roots,
    impossible exactly) keeps the certificate.

    Examples
    --------
    >>> decide_facts(Surface.REAL, Roots.SIMPLE, Definite.POSITIVE, Plane.OTHER)
    (0, 1, <Rule.POSITIVE_MEMBER: 1>)
    >>> decide_facts(Surface.REAL, Roots.SIMPLE, Definite.NONE, Plane.OTHER)
    (1, 0, <Rule.SIMPLE_ROOTS: 4>)
    """
    if surface == Surface.NONE_PLUS:
        return NO_CONTACT, R_PLUS, Rule.NO_REAL_POINTS
    if surface == Surface.NONE_MINUS:
        return NO_CONTACT, R_MINUS, Rule.NO_REAL_POINTS
    if definite == Definite.POSITIVE:
        return NO_CONTACT, R_PLUS, Rule.POSITIVE_MEMBER
    if definite == Definite.NEGATIVE:
        return NO_CONTACT, R_MINUS, Rule.NEGATIVE_MEMBER
    if roots == Roots.NONREAL:
        return CONTACT, R_CONTACT, Rule.NONREAL_ROOTS
    if roots == Roots.SIMPLE:
        return CONTACT, R_CONTACT, Rule.SIMPLE_ROOTS
    if roots == Roots.HARMLESS:
        return CONTACT, R_CONTACT, Rule.HARMLESS_ROOTS
    if plane == Plane.PLANE:
        return NO_CONTACT, UNCERTAIN, Rule.PLANE_TOUCHING
    return UNCERTAIN, UNCERTAIN, Rule.ESCALATE


def _consistent(surface: int, roots: int, definite: int, plane: int) -> bool:
    """Facts that can hold together.  A definite member makes every root real (a definite
    pencil is simultaneously diagonalisable).  A plane's ``P`` has the double root 0, so never
    four simple roots.  A quadric without real points meets no ellipsoid, so some member is
    definite (Finsler-Calabi), of the sign ``X^T Q X`` keeps on all of space."""
    if definite in (Definite.POSITIVE, Definite.NEGATIVE) and roots == Roots.NONREAL:
        return False
    if plane == Plane.PLANE and roots == Roots.SIMPLE:
        return False
    if surface == Surface.NONE_PLUS:
        return definite == Definite.POSITIVE
    if surface == Surface.NONE_MINUS:
        return definite == Definite.NEGATIVE
    return True


_SIZES = (len(Surface), len(Roots), len(Definite), len(Plane))


def table_index(surface: Any, roots: Any, definite: Any, plane: Any) -> Any:
    """The flat index of the facts into :data:`CONTACT_OF`, :data:`REGION_OF` and
    :data:`RULE_OF` (scalars or integer arrays)."""
    return ((surface * _SIZES[1] + roots) * _SIZES[2] + definite) * _SIZES[3] + plane


def _build() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    n = _SIZES[0] * _SIZES[1] * _SIZES[2] * _SIZES[3]
    contact = np.empty(n, dtype=np.int8)
    region = np.empty(n, dtype=np.int8)
    rule = np.empty(n, dtype=np.int8)
    for s, r, d, p in product(*(range(k) for k in _SIZES)):
        options = [
            [v] if v != size - 1 else list(range(size - 1))
            for v, size in zip((s, r, d, p), _SIZES, strict=True)
        ]
        answers = {decide_facts(*c) for c in product(*options) if _consistent(*c)}
        contacts = {a[0] for a in answers}
        regions = {a[1] for a in answers}
        rules = {a[2] for a in answers}
        k = table_index(s, r, d, p)
        contact[k] = contacts.pop() if len(contacts) == 1 else UNCERTAIN
        region[k] = regions.pop() if len(regions) == 1 else UNCERTAIN
        rule[k] = rules.pop() if len(rules) == 1 else Rule.UNCERTAIN
    return contact, region, rule


CONTACT_OF, REGION_OF, RULE_OF = _build()
"""The decision as data: contact code, region code and :class:`Rule` for every combination of
facts, ``UNKNOWN`` ones included (indexed by :func:`table_index`)."""

_ROWS: tuple[tuple[int, int, Rule], ...] = tuple(
    (int(c), int(r), Rule(int(u))) for c, r, u in zip(CONTACT_OF, REGION_OF, RULE_OF, strict=True)
)
"""The same table, row by row, as Python objects: what the scalar path reads (a numpy scalar
read and an enum made per pair were a tenth of the common pair's decision)."""


# -- the facts, exactly ------------------------------------------------------------------------


def definiteness(m: tuple[int, ...]) -> Definite:
    """Is the symmetric matrix (upper entries ``m``, exact) positive or negative definite?
    Sylvester's criterion on its leading principal minors (the generated program the kernels
    run in binary64, :func:`~quadric_contact._generated.kernels.leading_minors_4`), exact both
    ways.

    >>> definiteness((2, 1, 0, 0, 2, 0, 0, 1, 0, 3)), definiteness((-1, 0, 0, 0, -1, 0, 0, -1, 0, 1))
    (<Definite.POSITIVE: 0>, <Definite.NONE: 2>)
    """
    d1, d2, d3, d4 = leading_minors_4(*m)
    return _sylvester(d1, d2, d3) if d4 > 0 else Definite.NONE


def _sylvester(d1: Any, d2: Any, d3: Any) -> Definite:
    """Sylvester's criterion on the leading principal minors of orders 1-3 of a symmetric 4x4
    matrix whose determinant is positive (a definite one's always is)."""
    if d2 > 0:
        if d1 > 0 and d3 > 0:
            return Definite.POSITIVE
        if d1 < 0 and d3 < 0:
            return Definite.NEGATIVE
    return Definite.NONE


class Pencil:
    """The pencil ``mu E_int + Q_int`` of the integer forms of ``E`` and ``Q``
    (:meth:`~quadric_contact.Quadric.integer_form`): positive multiples of ``E`` and ``Q``,
    so its members at ``mu`` are positive multiples of ``lambda E + Q`` at
    ``lambda = mu * root_scale``, with the same inertia."""

    def __init__(self, P: CharacteristicPolynomial) -> None:
        self.P = P
        self.e = P.E.integer_form()[0]
        self.q = P.Q.integer_form()[0]
        self.root_scale = P.root_scale

    @property
    def C(self) -> tuple[int, ...]:
        """The integer coefficients ``C_0 .. C_4`` of ``det(mu E_int + Q_int)``."""
        return self.P.integer_coefficients

    def member(self, n: int, d: int) -> tuple[int, ...]:
        """A positive multiple of the member at ``mu = n / d`` (``d > 0``), in integers."""
        return tuple(n * a + d * b for a, b in zip(self.e, self.q, strict=True))

    def definite_where_p_positive(self, n: int, d: int) -> Definite:
        """:func:`definiteness` of the member at ``mu = n / d`` (``d > 0``) where ``P(mu) > 0``
        (:meth:`sign_at`): its determinant is then positive, so Sylvester's criterion needs
        only the minors of orders 1 to 3, from the member's leading 3x3 block."""
        e, q = self.e, self.q
        a00, a01, a02 = n * e[0] + d * q[0], n * e[1] + d * q[1], n * e[2] + d * q[2]
        a11, a12, a22 = n * e[4] + d * q[4], n * e[5] + d * q[5], n * e[7] + d * q[7]
        d2, d3 = leading_minors_3(a00, a01, a02, a11, a12, a22)
        return _sylvester(a00, d2, d3)

    def sign_at(self, n: int, d: int) -> int:
        """The sign of ``P`` at ``lambda = mu * root_scale``, ``mu = n / d`` (``d > 0``): that of
        the integer ``sum C_k n^k d^(4-k)``."""
        total = 0
        nk, dk = 1, d**4
        for c in self.C:
            total += c * nk * dk
            nk *= n
            dk //= d
        return (total > 0) - (total < 0)


def critical_points(c1: float, c2: float, c3: float, c4: float) -> tuple[float, float, float, bool]:
    """Approximations of the three real roots of ``P' = 4 c4 x^3 + 3 c3 x^2 + 2 c2 x + c1``
    in increasing order (the flag is False when ``P'`` has one real root or the numbers are
    not finite).  Between two consecutive simple roots of ``P`` lies exactly one of them when
    ``P`` has four simple real roots (Rolle), which makes them the sample points of the gaps;
    nothing trusts them: the signs of ``P`` there are what certify.  Written over plain floats
    and ``math`` only, so that the compiled kernels run this same function.

    >>> [round(x, 9) for x in critical_points(-50.0, 35.0, -10.0, 1.0)[:3]]   # (x-1)(x-2)(x-3)(x-4)
    [1.381966011, 2.5, 3.618033989]
    """
    if c4 == 0.0:
        return 0.0, 0.0, 0.0, False
    a = 0.75 * c3 / c4
    b = 0.5 * c2 / c4
    c = 0.25 * c1 / c4
    a3 = a / 3.0
    p = b - a * a3
    q = a3 * (2.0 * a3 * a3 - b) + c
    if not (p < 0.0) or not math.isfinite(q):
        return 0.0, 0.0, 0.0, False
    m = 2.0 * math.sqrt(-p / 3.0)
    arg = 3.0 * q / (p * m)
    arg = min(1.0, max(-1.0, arg))
    th = math.acos(arg) / 3.0
    x0 = m * math.cos(th - 4.1887902047863905) - a3
    x1 = m * math.cos(th - 2.0943951023931957) - a3
    x2 = m * math.cos(th) - a3
    # the cosines are increasing in this order for th in [0, pi/3]
    ok = math.isfinite(x0) and math.isfinite(x1) and math.isfinite(x2) and x0 < x1 < x2
    return x0, x1, x2, ok


@dataclass(frozen=True)
class PencilFacts:
    """The facts of one pair, exactly, and how they were read.

    Attributes
    ----------
    surface, roots, definite, plane
        The inputs of the table.
    points : tuple of (Fraction, Definite)
        The points ``mu`` of the integer pencil (:class:`Pencil`) between consecutive real
        roots that were read, and what the member there is.
    scale : Fraction
        ``lambda = mu * scale``.
    multiplicities : tuple of int
        The multiplicities of the real roots, increasing (empty when not needed: four simple
        roots certified by the signs of ``P``, or non-real roots).
    """

    surface: Surface
    roots: Roots
    definite: Definite
    plane: Plane
    points: tuple[tuple[Fraction, Definite], ...] = ()
    scale: Fraction = Fraction(1)
    multiplicities: tuple[int, ...] = ()

    @property
    def samples(self) -> tuple[tuple[Fraction, Definite], ...]:
        """The points read, as ``lambda`` of ``lambda E + Q``, and what the member there is."""
        return tuple((mu * self.scale, d) for mu, d in self.points)

    @property
    def member(self) -> Fraction | None:
        """``lambda`` of a definite member, when one was found (the last point read)."""
        if self.points and self.points[-1][1] in (Definite.POSITIVE, Definite.NEGATIVE):
            return self.points[-1][0] * self.scale
        return None


def _surface(Q: Any) -> Surface:
    if Q.kind in NO_REAL_POINTS:
        return Surface.NONE_PLUS if Q.canonical_sign > 0 else Surface.NONE_MINUS
    return Surface.REAL


_SHORT_BITS = 10


def _dyadic(x: float, bits: int | None) -> tuple[int, int]:
    """``x`` rounded to ``bits`` significant bits (all of them for None), as ``(n, d)``."""
    if bits is None or x == 0.0:
        return x.as_integer_ratio()
    _, e = math.frexp(x)
    shift = bits - e
    if shift <= 0:
        return round(x / 2.0**-shift) << -shift, 1
    return round(x * 2.0**shift), 1 << shift


def pencil_facts(P: CharacteristicPolynomial) -> PencilFacts:
    """The facts of :func:`decide_facts` for the pair of ``P`` (``P.E`` with the paper's sign),
    exactly.

    The common pairs take the short way, in integers: the critical points of ``P`` in binary64
    (:func:`critical_points`) become exact dyadic rationals ``mu``; a definite member at one of
    them settles the pair whatever the roots; if ``P`` alternates in sign across them, the four
    roots are real and simple (each of the four intervals holds an odd number of roots) and,
    with no member definite there, none is anywhere.  What the short way cannot certify
    (non-real or multiple roots, sample points that miss a gap) is read from the exact root
    structure: Yang's discrimination sequence, exact isolation of the real roots with their
    multiplicities, a rational point in each gap.

    The type of ``Q`` is read only where the table needs it (no definite member and a multiple
    root): a definite member, non-real roots and four simple roots without a definite member
    each imply that ``Q`` has real points (a quadric without any meets no ``E``, so the pencil
    has a definite member by Finsler-Calabi), and none of them is a plane's (whose ``P`` has
    the double root 0 and, all roots real, a definite member or a touch: Theorem 14).
    """
    pencil = Pencil(P)
    C = pencil.C
    scale = pencil.root_scale
    real, other = Surface.REAL, Plane.OTHER
    try:
        # each coefficient rounded once, then divided (a sample point needs no more: the signs
        # of P certify); quotients of the integers where a coefficient is beyond binary64
        try:
            c4 = float(C[4])
            x0, x1, x2, ok = critical_points(float(C[1]) / c4, float(C[2]) / c4, float(C[3]) / c4, 1.0)
        except OverflowError:
            x0, x1, x2, ok = critical_points(C[1] / C[4], C[2] / C[4], C[3] / C[4], 1.0)
    except (OverflowError, ZeroDivisionError):
        ok = False
    points: list[tuple[Fraction, Definite]] = []
    if ok:
        top = (C[4] > 0) - (C[4] < 0)
        # Short dyadic sample points first (a readable witness, small integers); at full
        # precision again if they miss (a narrow gap).
        for bits in (_SHORT_BITS, None):
            if bits is None and not P.structure.all_real:
                # the short points missed because roots are non-real, which finer points cannot
                # change: the exact root structure (read next, and needed anyway) says so
                break
            points = []
            alternating = True
            # the likeliest definite members first: positive in the last gap (E outside Q),
            # negative in the first (E inside); the middle gap holds one only at a multiple root
            for k, x in ((2, x2), (0, x0), (1, x1)):
                n, d = _dyadic(x, bits)
                # a definite 4x4 matrix has a positive determinant, a positive multiple of
                # P(mu): where P is not positive the member is not definite, and where it is
                # the minors of orders 1 to 3 decide (a dozen products, where all four take
                # forty)
                s = pencil.sign_at(n, d)
                found_d = pencil.definite_where_p_positive(n, d) if s > 0 else Definite.NONE
                points.append((Fraction(n, d), found_d))
                if found_d is not Definite.NONE:
                    return PencilFacts(real, Roots.UNKNOWN, found_d, other, tuple(points), scale)
                alternating = alternating and s == (top if k == 1 else -top)
            if alternating:
                points.sort()
                return PencilFacts(real, Roots.SIMPLE, Definite.NONE, other, tuple(points), scale)
    if not P.structure.all_real:
        # a definite member would make every root real
        return PencilFacts(real, Roots.NONREAL, Definite.NONE, other, tuple(points), scale)
    found = real_roots(list(C), multiplicities=True)
    points = []
    for (a, _), (b, _) in pairwise(found):
        mu = rational_between(a, b)
        found_d = definiteness(pencil.member(mu.numerator, mu.denominator))
        points.append((mu, found_d))
        if found_d is not Definite.NONE:
            return PencilFacts(real, Roots.UNKNOWN, found_d, other, tuple(points), scale)
    mults = tuple(m for _, m in found)
    if all(m == 1 for m in mults):
        return PencilFacts(real, Roots.SIMPLE, Definite.NONE, other, tuple(points), scale, mults)
    Q = P.Q
    roots = Roots.HARMLESS if _harmless(pencil, found) else Roots.MULTIPLE
    plane = Plane.PLANE if Q.kind is QuadricKind.PLANE else Plane.OTHER
    return PencilFacts(_surface(Q), roots, Definite.NONE, plane, tuple(points), scale, mults)


def _harmless(pencil: Pencil, found: list[tuple[Any, int]]) -> bool:
    """Every multiple root ``lambda0`` is rational and ``E`` is definite on the kernel of
    ``lambda0 E + Q``: no real point of ``E`` lies in that kernel, so no real common point is a
    tangency (a tangent point ``X`` has ``(lambda0 E + Q) X = 0`` at a multiple root), and
    every real common point is a transversal crossing.  This is the structural double root 0
    of a plane or of parallel planes (kernel at infinity) and the multiple roots of symmetric
    placements (a sphere on the axis of a cylinder: the kernel at ``lambda0`` is the plane at
    infinity's directions across the axis).  An irrational multiple root is left to the exact
    analysis."""
    for r, m in found:
        if m == 1:
            continue
        if not r.is_rational:
            return False
        mu = r.as_fraction()
        member = pencil.member(mu.numerator, mu.denominator)
        full = _full(member)
        basis = nullspace([[Fraction(v) for v in row] for row in full], zero=Fraction(0), one=Fraction(1))
        e = _full(pencil.e)
        gram = [
            [sum(u[i] * e[i][j] * v[j] for i in range(4) for j in range(4)) for v in basis] for u in basis
        ]
        if not _definite_gram(gram):
            return False
    return True


def _full(m: tuple[int, ...]) -> list[list[int]]:
    a00, a01, a02, a03, a11, a12, a13, a22, a23, a33 = m
    return [[a00, a01, a02, a03], [a01, a11, a12, a13], [a02, a12, a22, a23], [a03, a13, a23, a33]]


def _definite_gram(g: list[list[Fraction]]) -> bool:
    """Is the small symmetric matrix ``g`` (exact) positive or negative definite (Sylvester)?"""
    k = len(g)
    minors = [_det([row[:j] for row in g[:j]]) for j in range(1, k + 1)]
    if all(d > 0 for d in minors):
        return True
    return all((d < 0) if j % 2 == 0 else (d > 0) for j, d in enumerate(minors))


def _det(a: list[list[Fraction]]) -> Fraction:
    if len(a) == 1:
        return Fraction(a[0][0])
    return sum(((-1) ** j) * a[0][j] * _det([row[:j] + row[j + 1 :] for row in a[1:]]) for j in range(len(a)))


@dataclass(frozen=True)
class PencilDecision:
    """The table's answer for one pair, with its witness.

    Attributes
    ----------
    contact : int
        ``NO_CONTACT`` (0), ``CONTACT`` (1), or ``UNCERTAIN`` (2): the exact analysis of a
        singular intersection decides (:attr:`rule` is :data:`Rule.ESCALATE`).
    region : int
        ``R_MINUS`` (-1), ``CONTACT`` (0), ``R_PLUS`` (1), or ``UNCERTAIN`` (2): not from the
        table (a touching plane, a singular intersection).
    rule : Rule
    facts : PencilFacts
    """

    contact: int
    region: int
    rule: Rule
    facts: PencilFacts

    @property
    def transversal(self) -> bool | None:
        return None if self.contact == UNCERTAIN else self.contact == CONTACT

    @property
    def region_value(self) -> Region | None:
        return {R_MINUS: Region.R_MINUS, R_CONTACT: Region.CONTACT, R_PLUS: Region.R_PLUS}.get(self.region)

    @property
    def decided_by(self) -> str:
        return self.rule.decided_by

    def __str__(self) -> str:
        f = self.facts
        if self.rule in (Rule.POSITIVE_MEMBER, Rule.NEGATIVE_MEMBER):
            positive = self.rule is Rule.POSITIVE_MEMBER
            return (
                f"the member {f.member} E + Q is {'positive' if positive else 'negative'} definite: "
                f"X^T Q X {'>' if positive else '<'} 0 on E ({'R+' if positive else 'R-'}, strictly)"
            )
        if self.rule is Rule.SIMPLE_ROOTS:
            at = ", ".join(str(s) for s, _ in f.samples)
            return (
                f"four simple real roots and no definite member (none at lambda = {at}, one point in "
                "each gap): the surfaces cross"
            )
        if self.rule is Rule.HARMLESS_ROOTS:
            return (
                f"all roots real (multiplicities {list(f.multiplicities)}), E definite on the kernel of "
                "the member at each multiple root (no real tangent point) and no definite member: "
                "the surfaces cross"
            )
        if self.rule is Rule.NONREAL_ROOTS:
            return "P has non-real roots, so no member is definite: transversal contact for any pair"
        if self.rule is Rule.NO_REAL_POINTS:
            return "Q has no real surface"
        if self.rule is Rule.PLANE_TOUCHING:
            return "a plane, all roots of P real and no definite member: the plane touches E"
        return "a multiple root and no definite member: a singular intersection"


def decide_pencil(P: CharacteristicPolynomial) -> PencilDecision:
    """The decision for the pair of ``P`` (exact facts, :func:`pencil_facts`, through the table).

    Examples
    --------
    Two unit spheres three apart: the member at the critical point of ``P`` between its two
    positive roots is positive definite.

    >>> from quadric_contact import Quadric, characteristic_polynomial
    >>> d = decide_pencil(characteristic_polynomial(Quadric.sphere(1), Quadric.sphere(1, (3, 0, 0))))
    >>> d.transversal, d.region_value, d.decided_by
    (False, <Region.R_PLUS: 'R+'>, 'signature sequence')
    >>> print(d)
    the member 5 E + Q is positive definite: X^T Q X > 0 on E (R+, strictly)
    """
    facts = pencil_facts(P)
    contact, region, rule = _ROWS[table_index(facts.surface, facts.roots, facts.definite, facts.plane)]
    return PencilDecision(contact, region, rule, facts)


def decide_exact(E: Any, Q: Any) -> PencilDecision:
    """:func:`decide_pencil` for ``E`` and ``Q`` as any input the package reads.

    A unit sphere on the axis of a cylinder of radius 1/2 crosses it; ``P`` has the double
    root -1 of the symmetry, whose member's kernel lies at infinity:

    >>> d = decide_exact("x**2 + y**2 + z**2 - 1", "x**2 + y**2 - 1/4")
    >>> d.transversal, d.decided_by, d.facts.multiplicities
    (True, 'signature sequence', (2, 1, 1))

    Of the same radius, it touches the cylinder along a circle: a singular intersection, which
    the exact analysis decides.

    >>> decide_exact("x**2 + y**2 + z**2 - 1", "x**2 + y**2 - 1").rule
    <Rule.ESCALATE: 7>
    """
    return decide_pencil(characteristic_polynomial(E, Q))
