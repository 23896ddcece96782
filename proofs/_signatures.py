"""The signature decision, written out plainly in exact arithmetic, and the truth it is compared with.

An implementation of the decision proved in :mod:`.twmw_2009_signature_decision`, kept
independent of the package's decision code: only the package's exact number types
(``Fraction``, python-flint) and sympy are used.

* :func:`signature_decision`: the exact characteristic polynomial ``P(l) = det(l E + Q)``
  (``E`` normalised to ``n_+(E) = 3``), its real roots isolated exactly with their
  multiplicities (sympy's square-free decomposition and interval isolation over QQ), one
  rational point in every gap between consecutive real roots and on both unbounded ends,
  the exact inertia of the member there (Descartes' rule on its characteristic polynomial,
  exact because a symmetric matrix has real eigenvalues), then the exact inertia of the
  member at each real multiple root (rational or quadratic, exact in ``Q(sqrt D)``);
* :func:`geometric_truth`: the same questions answered from the exact extremes of
  ``X^T Q X`` on the surface of ``E`` (:func:`~quadric_contact.theory.geometric.decide_geometrically`,
  Lagrange conditions, no pencil, no signatures);
* :func:`overlap_from`: whether the solids overlap, read from a decision (step (h)).
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import flint
import sympy as sp

from quadric_contact.model.classification import QuadricKind
from quadric_contact.model.quadric import Quadric
from quadric_contact.paper.proving import ensure
from quadric_contact.theory.results import OverlapCode, Region

LAM = sp.Symbol("lambda")

Mat = list[list[Fraction]]

NONE, TOUCHING, TRANSVERSAL, COINCIDENT = "no contact", "touching", "transversal", "coincident"

ROWS = (
    "a definite member in a gap",
    "a semidefinite member at a multiple root",
    "four simple real roots, no definite member",
    "non-real roots",
    "multiple roots without a real singular point, no definite member",
    "a real singular point, no semidefinite member",
    "Q a multiple of E",
)
"""The rows of the decision, in the order they are tried."""


def _variations(signs: Sequence[int]) -> int:
    nz = [s for s in signs if s]
    return sum(1 for u, v in itertools.pairwise(nz) if u != v)


def _descartes(signs_low_to_high: Sequence[int], n: int) -> tuple[int, int, int]:
    """``(n_+, n_-, n_0)`` of an ``n x n`` symmetric matrix from the signs of its characteristic
    polynomial's coefficients (constant term first): all its roots are real, so Descartes'
    rule counts the positive and the negative ones exactly."""
    signs = list(signs_low_to_high)
    zeros = 0
    while signs and signs[0] == 0:
        signs.pop(0)
        zeros += 1
    high_first = signs[::-1]
    degree = len(high_first) - 1
    positive = _variations(high_first)
    negative = _variations([s * (-1) ** (degree - k) for k, s in enumerate(high_first)])
    ensure(positive + negative + zeros == n, "a symmetric matrix has real eigenvalues only")
    return positive, negative, zeros


def _fmpq(v: Any) -> Any:
    v = Fraction(v)
    return flint.fmpq(v.numerator, v.denominator)


def _flint(M: Sequence[Sequence[Any]]) -> Any:
    n = len(M)
    return flint.fmpq_mat(n, n, [_fmpq(v) for row in M for v in row])


def _sign(v: Any) -> int:
    return 1 if v > 0 else (-1 if v < 0 else 0)


def inertia(M: Sequence[Sequence[Any]]) -> tuple[int, int, int]:
    """Exact inertia ``(n_+, n_-, n_0)`` of a rational symmetric matrix."""
    coeffs = _flint(M).charpoly().coeffs()  # constant term first
    return _descartes([_sign(c) for c in coeffs], len(M))


def _exact_sign(value: sp.Expr) -> int:
    """Sign of an element ``a + b sqrt(D)`` of a quadratic field, exactly: expanded, it is 0 only
    as the literal 0; otherwise ``a`` and ``b sqrt(D)`` are compared by their squares."""
    value = sp.expand(value)
    if value == 0:
        return 0
    if value.is_Rational:
        return 1 if value > 0 else -1
    surds = [t for t in value.atoms(sp.Pow) if t.exp == sp.Rational(1, 2)]
    ensure(len(surds) == 1, f"an element of one quadratic field: {value}")
    r = surds[0]
    poly = sp.Poly(value, r)
    ensure(poly.degree() <= 1, f"linear in the surd: {value}")
    coeffs = poly.all_coeffs()
    b, a = coeffs if len(coeffs) == 2 else (0, coeffs[0])
    a, b, d = sp.Rational(a), sp.Rational(b), sp.Rational(r.base)
    sa, sb = _sign(a), _sign(b)
    if sa == 0 or sb == 0 or sa == sb:
        return sa or sb
    # opposite signs: compare a^2 with b^2 d
    return sa if a * a > b * b * d else -sa


def inertia_algebraic(M: sp.Matrix) -> tuple[int, int, int]:
    """Exact inertia of a symmetric matrix over ``Q(sqrt D)``."""
    x = sp.Symbol("x")
    coeffs = sp.Poly(M.charpoly(x).as_expr(), x).all_coeffs()[::-1]
    return _descartes([_exact_sign(c) for c in coeffs], M.shape[0])


def normalised_ellipsoid(E: Quadric) -> Mat:
    """The matrix of ``E`` with ``n_+ = 3`` (negative inside), after checking it is a real ellipsoid:
    signature (3, 1) and a positive definite quadratic part."""
    M = [[Fraction(v) for v in row] for row in E.matrix]
    pos, neg, zero = inertia(M)
    ensure(zero == 0 and {pos, neg} == {1, 3}, f"E has signature (3, 1): {E}")
    if pos == 1:
        M = [[-v for v in row] for row in M]
    ensure(inertia([row[:3] for row in M[:3]]) == (3, 0, 0), f"E is a real ellipsoid: {E}")
    return M


def pencil_polynomial(E: Mat, Q: Mat) -> sp.Poly:
    """``det(l E + Q) = det E * det(l I + E^-1 Q)``, exactly, as a sympy polynomial over QQ."""
    Ef, Qf = _flint(E), _flint(Q)
    char = (-(Ef.inv() * Qf)).charpoly()  # det(l I + E^-1 Q)
    det = Ef.det()
    coeffs = [sp.Rational(int(c.p), int(c.q)) * sp.Rational(int(det.p), int(det.q)) for c in char.coeffs()]
    return sp.Poly(coeffs[::-1], LAM, domain=sp.QQ)


@dataclass(frozen=True)
class RealRoot:
    """A real root of ``P``: an isolating interval ``[lo, hi]`` (a point for a rational root), its
    multiplicity, and its exact value for a multiple root (rational or quadratic)."""

    lo: sp.Rational
    hi: sp.Rational
    multiplicity: int
    value: sp.Expr | None


def real_roots(P: sp.Poly) -> tuple[list[RealRoot], int]:
    """The real roots of ``P`` in increasing order, with pairwise disjoint isolating intervals, and
    the number of non-real roots (with multiplicity)."""
    _, parts = P.sqf_list()
    eps: sp.Rational | None = None
    while True:
        roots: list[RealRoot] = []
        nonreal = 0
        for f, m in parts:
            found = f.intervals(eps=eps) if eps is not None else f.intervals()
            nonreal += m * (f.degree() - len(found))
            for (lo, hi), _ in found:
                value = None
                if m > 1:
                    ensure(f.degree() <= 2, "a multiple root of a quartic is rational or quadratic")
                    value = next(r for r in sp.roots(f, LAM) if r.is_real and lo <= r <= hi)
                roots.append(RealRoot(sp.Rational(lo), sp.Rational(hi), m, value))
        roots.sort(key=lambda r: (r.lo, r.hi))
        if all(a.hi < b.lo for a, b in itertools.pairwise(roots)):
            return roots, nonreal
        eps = sp.Rational(1, 2**10) if eps is None else eps / 2**10


def gap_points(roots: Sequence[RealRoot]) -> list[sp.Rational]:
    """One rational point in each gap: left of the first root, between consecutive roots, right of
    the last (a single point, 0, when there is no real root)."""
    if not roots:
        return [sp.Integer(0)]
    return [
        roots[0].lo - 1,
        *((a.hi + b.lo) / 2 for a, b in itertools.pairwise(roots)),
        roots[-1].hi + 1,
    ]


def _member(E: Mat, Q: Mat, lam: Any) -> Any:
    if isinstance(lam, sp.Rational | sp.Integer) or (isinstance(lam, sp.Expr) and lam.is_Rational):
        t = Fraction(int(lam.p), int(lam.q))
        return [[t * e + q for e, q in zip(re, rq, strict=True)] for re, rq in zip(E, Q, strict=True)]
    return sp.Matrix(4, 4, lambda i, j: sp.expand(lam * sp.Rational(E[i][j]) + sp.Rational(Q[i][j])))


def _inertia_of(M: Any) -> tuple[int, int, int]:
    return inertia_algebraic(M) if isinstance(M, sp.Matrix) else inertia(M)


def _isotropic_in_kernel(E: Mat, M: Any) -> bool:
    """The kernel of the member ``M`` holds a real non-zero vector ``X`` with ``X^T E X = 0`` (a real
    singular point of the intersection): ``E`` restricted to the kernel is not definite."""
    S = M if isinstance(M, sp.Matrix) else sp.Matrix(4, 4, lambda i, j: sp.Rational(M[i][j]))
    K = sp.Matrix.hstack(*S.nullspace(simplify=True))
    restricted = (K.T * sp.Matrix(4, 4, lambda i, j: sp.Rational(E[i][j])) * K).applyfunc(sp.expand)
    pos, neg, _ = inertia_algebraic(restricted)
    return not (pos == restricted.shape[0] or neg == restricted.shape[0])


@dataclass(frozen=True)
class SignatureDecision:
    """What the signatures of the pencil decide.

    ``contact``: ``"no contact"``, ``"touching"`` (the surfaces meet, ``X^T Q X`` keeps one sign on
    ``E``), ``"transversal"`` or ``"coincident"``; ``region``: where the surface of ``E`` lies (``R+``,
    ``R-``, ``contact`` when transversal); ``witness``: the ``l`` of the definite (no contact) or
    semidefinite (touching) member; ``pattern``: the multiplicities of the real roots in increasing
    order, then ``+ 2k`` for ``2k`` non-real roots; ``signatures``: ``n_+`` of the member in each gap,
    left to right; ``singular``: a real multiple root whose member's kernel holds a real point of
    ``E`` (the intersection has a real singular point); ``row``: the row of :data:`ROWS` that decided.
    """

    contact: str
    region: Region
    witness: Any
    pattern: str
    signatures: tuple[int, ...]
    singular: bool
    row: str


def signature_decision(E: Quadric, Q: Quadric) -> SignatureDecision:
    """Decide contact and region of the ellipsoid ``E`` and the quadric ``Q`` from the signatures of
    the pencil (steps (b)-(g) of :mod:`.twmw_2009_signature_decision`), exactly."""
    Em = normalised_ellipsoid(E)
    Qm = [[Fraction(v) for v in row] for row in Q.matrix]
    P = pencil_polynomial(Em, Qm)
    ensure(P.degree() == 4, "P has degree 4 (det E != 0)")
    roots, nonreal = real_roots(P)
    pattern = ",".join(str(r.multiplicity) for r in roots) + (f"+{nonreal}" if nonreal else "")
    points = gap_points(roots)
    signatures = tuple(inertia(_member(Em, Qm, t))[0] for t in points)
    if roots:
        ensure(signatures[0] == 1 and signatures[-1] == 3, f"n_+ = 1 at -inf and 3 at +inf: {signatures}")
    # A multiple root's member: coincident, semidefinite, with a real singular point.
    singular = False
    semidefinite: tuple[Region, Any] | None = None
    for r in roots:
        if r.multiplicity == 1:
            continue
        M = _member(Em, Qm, r.value)
        if (isinstance(M, sp.Matrix) and M.is_zero_matrix) or (
            not isinstance(M, sp.Matrix) and all(v == 0 for row in M for v in row)
        ):
            return SignatureDecision(COINCIDENT, Region.R_MINUS, r.value, pattern, signatures, True, ROWS[6])
        singular = singular or _isotropic_in_kernel(Em, M)
        pos, neg, _ = _inertia_of(M)
        if semidefinite is None and (neg == 0 or pos == 0):
            semidefinite = (Region.R_PLUS if neg == 0 else Region.R_MINUS, r.value)
    for t, n_plus in zip(points, signatures, strict=True):
        if n_plus in (0, 4):
            region = Region.R_PLUS if n_plus == 4 else Region.R_MINUS
            return SignatureDecision(NONE, region, t, pattern, signatures, singular, ROWS[0])
    if nonreal:
        ensure(semidefinite is None, "non-real roots: no semidefinite member")
    if semidefinite is not None:
        ensure(singular, "a semidefinite member without a definite one has a real singular point")
        region, lam = semidefinite
        return SignatureDecision(TOUCHING, region, lam, pattern, signatures, singular, ROWS[1])
    if nonreal:
        row = ROWS[3]
    elif all(r.multiplicity == 1 for r in roots):
        row = ROWS[2]
    else:
        row = ROWS[5] if singular else ROWS[4]
    return SignatureDecision(TRANSVERSAL, Region.CONTACT, None, pattern, signatures, singular, row)


@dataclass(frozen=True)
class Truth:
    """Contact and region from the exact extremes of ``X^T Q X`` on the surface of ``E``."""

    contact: str
    region: Region
    minimum: Any
    maximum: Any


def geometric_truth(E: Quadric, Q: Quadric) -> Truth:
    """``min < 0 < max``: transversal; ``min > 0`` (``max < 0``): no contact, ``R+`` (``R-``);
    ``min = 0`` (``max = 0``) otherwise: touching from ``R+`` (``R-``); ``Q`` a multiple of ``E``:
    coincident.  Decided by :func:`~quadric_contact.theory.geometric.decide_geometrically`, which
    does not use the pencil."""
    from quadric_contact.theory.geometric import decide_geometrically

    g = decide_geometrically(E, Q)
    lo, hi = g.minimum.sign(), g.maximum.sign()
    if g.coincident:
        return Truth(COINCIDENT, Region.R_MINUS, g.minimum, g.maximum)
    if lo < 0 < hi:
        return Truth(TRANSVERSAL, Region.CONTACT, g.minimum, g.maximum)
    if lo > 0 or hi < 0:
        return Truth(NONE, Region.R_PLUS if lo > 0 else Region.R_MINUS, g.minimum, g.maximum)
    return Truth(TOUCHING, Region.R_PLUS if lo == 0 else Region.R_MINUS, g.minimum, g.maximum)


def agree(E: Quadric, Q: Quadric) -> tuple[SignatureDecision, Truth]:
    """The signature decision and the geometric truth, required equal."""
    d, t = signature_decision(E, Q), geometric_truth(E, Q)
    ensure(
        (d.contact, d.region) == (t.contact, t.region),
        f"E = {E.equation()}, Q = {Q.equation()}: signatures say {d.contact} {d.region} ({d.row}, "
        f"pattern {d.pattern}, n_+ {d.signatures}); the extremes of X^T Q X on E say {t.contact} {t.region} "
        f"(min {t.minimum.approx(12)}, max {t.maximum.approx(12)})",
    )
    return d, t


def overlap_from(d: SignatureDecision, E: Quadric, Q: Quadric) -> OverlapCode:
    """Whether the solid of ``E`` (its inside) and the solid of ``Q`` (``R-`` of ``Q`` with the sign
    of its solid, :func:`~quadric_contact.theory.overlap.solid_of`) overlap, from the decision for
    that sign of ``Q`` (step (h)): crossing, or the surface of ``E`` in the solid of ``Q``: they
    overlap; the surface of ``E`` outside (``R+``): they overlap iff ``Q`` is an ellipsoid whose centre
    is inside ``E``, else they are apart (no contact) or touch (touching)."""
    if d.contact == TRANSVERSAL or d.region is Region.R_MINUS:
        return OverlapCode.OVERLAPPING
    if Q.kind is QuadricKind.ELLIPSOID:
        centre = Q.center()
        ensure(centre is not None, "an ellipsoid has a centre")
        Em = normalised_ellipsoid(E)
        X = [*centre, Fraction(1)]
        if sum(X[i] * Em[i][j] * X[j] for i in range(4) for j in range(4)) < 0:
            return OverlapCode.OVERLAPPING
    return OverlapCode.TOUCHING if d.contact == TOUCHING else OverlapCode.SEPARATE
