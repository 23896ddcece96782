"""The kind of contact (Table 3), from the singular members of the pencil.

If ``E`` and ``Q`` are tangent at ``X`` (both contain ``X`` and their
gradients are parallel), then ``(lambda0*E + Q) X = 0`` for some real
``lambda0``: ``X`` is a singular point of a member of the pencil, and
``lambda0`` is a *multiple* root of ``P`` (``P'(lambda0)`` is proportional
to ``X^T E X = 0`` at a simple root).  Conversely a real singular point of
``lambda0*E + Q`` lying on ``E`` lies on ``Q`` with parallel normals.  So
the tangency set is read off the kernels of the members at the multiple
roots, which are rational or quadratic irrationals (``gcd(P, P')`` has
degree at most 2): exact arithmetic in ``Q(sqrt d)``
(:class:`~quadric_contact.exact.algebraic.QuadraticNumber`).

* rank 3 (a point): a tangent point if the point is on ``E``;
* rank 2 (a line of singular points): the line meets ``E`` in 0, 1 or 2
  real points, each a tangent point;
* rank 1 (a double plane): the plane meets ``E`` in a conic (a curve of
  tangency), a point, or nothing;
* rank 0: ``Q`` is a multiple of ``E`` (the same surface).

The Segre symbol alone does not decide the kind (Table 3 lists
``[(11)11]_3`` under three kinds): the kernels do.  Transversal contact is
decided by Remark 9 (non-real roots), by Theorem 2 when ``E`` is small, and
otherwise by the exact geometric decision.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import StrEnum
from itertools import pairwise
from typing import Any

import flint

from quadric_contact.exact.algebraic import QuadraticNumber
from quadric_contact.exact.linalg import nullspace
from quadric_contact.exact.rational import fmpq_poly_of, fraction_of, monic
from quadric_contact.model.classification import NO_REAL_POINTS, QuadricKind
from quadric_contact.theory.contact import decide_transversal, refuse
from quadric_contact.theory.pencil import CharacteristicPolynomial, characteristic_polynomial
from quadric_contact.theory.segre import SegreSymbol, segre_symbol

__all__ = ["ContactAnalysis", "ContactKind", "SingularMember", "analyze_contact", "contact_kind_exact"]


class ContactKind(StrEnum):
    """How the surfaces of ``E`` and ``Q`` meet (the rows of Table 3), and ``UNCERTAIN``."""

    NONE = "none"
    TANGENT_POINT = "tangent_point"
    TWO_TANGENT_POINTS = "two_tangent_points"
    TRANSVERSAL = "transversal"
    TANGENT_CURVE = "tangent_curve"
    UNCERTAIN = "uncertain"
    """Only from the number modes that abstain (``filter``, ``ball``): they cannot tell."""

    def __str__(self) -> str:
        return self.value


@dataclass(frozen=True)
class SingularMember:
    """A singular member ``lambda0*E + Q`` at a multiple root of ``P``.

    Attributes
    ----------
    root : QuadraticNumber
        ``lambda0`` (rational or ``a + b sqrt(d)``).
    rank : int
    tangent_points : int
        Real points of its singular set that lie on ``E``.
    points : tuple
        Their coordinates when they are in ``Q(sqrt d)`` (rank 3, and rank 2
        when the line meets ``E`` in rational points of that field); the
        count is always given.
    curve : bool
        Rank 1 and its plane meets ``E`` in a curve (a conic of tangency).
    """

    root: QuadraticNumber
    rank: int
    tangent_points: int
    points: tuple[tuple[QuadraticNumber, QuadraticNumber, QuadraticNumber], ...]
    curve: bool


@dataclass(frozen=True)
class ContactAnalysis:
    """Everything :func:`analyze_contact` found.

    Attributes
    ----------
    kind : ContactKind
    segre : SegreSymbol
    members : tuple of SingularMember
        The singular members at the multiple real roots of ``P``.
    tangent_points : int
        Number of isolated points of tangency.
    tangent_curve : bool
    transversal : bool
    transversal_by : str
        ``"Remark 9"`` (non-real roots), ``"Theorem 2"`` (all real, ``E``
        small) or ``"geometric decision"``.
    coincident : bool
        ``Q`` is a multiple of ``E`` (reported as ``TANGENT_CURVE``: every
        point is a point of tangency).
    """

    kind: ContactKind
    segre: SegreSymbol
    members: tuple[SingularMember, ...]
    tangent_points: int
    tangent_curve: bool
    transversal: bool
    transversal_by: str
    coincident: bool = False
    polynomial: CharacteristicPolynomial | None = field(default=None, repr=False, compare=False)

    def __str__(self) -> str:
        extra = ""
        if self.transversal and (self.tangent_points or self.tangent_curve):
            extra = f", also tangent at {self.tangent_points} point(s)"
        return f"{self.kind.value} (Segre {self.segre}; transversality by {self.transversal_by}{extra})"

    def to_dict(self) -> dict[str, Any]:
        return {
            "kind": self.kind.value,
            "segre": str(self.segre),
            "tangent_points": self.tangent_points,
            "tangent_curve": self.tangent_curve,
            "transversal": self.transversal,
            "transversal_by": self.transversal_by,
            "coincident": self.coincident,
            "members": [
                {
                    "lambda": str(m.root.to_sympy()),
                    "rank": m.rank,
                    "tangent_points": m.tangent_points,
                    "points": [[str(c.to_sympy()) for c in p] for p in m.points],
                    "curve": m.curve,
                }
                for m in self.members
            ],
        }


# -- linear algebra over Q(sqrt d) ------------------------------------------------------------

QMat = list[list[QuadraticNumber]]


def _form(M: QMat, u: list[QuadraticNumber], v: list[QuadraticNumber]) -> QuadraticNumber:
    acc = QuadraticNumber(0)
    for i in range(4):
        for j in range(4):
            if not M[i][j].is_zero():
                acc = acc + u[i] * M[i][j] * v[j]
    return acc


def _inertia_3(G: list[list[QuadraticNumber]]) -> tuple[int, int, int]:
    """(positive, negative, zero) of a symmetric 3x3 matrix over a real quadratic field."""
    # Characteristic polynomial t^3 - e1 t^2 + e2 t - e3 is real-rooted: Descartes is exact.
    e1 = G[0][0] + G[1][1] + G[2][2]
    e2 = (
        G[0][0] * G[1][1]
        - G[0][1] * G[1][0]
        + G[0][0] * G[2][2]
        - G[0][2] * G[2][0]
        + G[1][1] * G[2][2]
        - G[1][2] * G[2][1]
    )
    e3 = (
        G[0][0] * (G[1][1] * G[2][2] - G[1][2] * G[2][1])
        - G[0][1] * (G[1][0] * G[2][2] - G[1][2] * G[2][0])
        + G[0][2] * (G[1][0] * G[2][1] - G[1][1] * G[2][0])
    )
    coeffs = [QuadraticNumber(1), -e1, e2, -e3]
    signs = [c.sign() for c in coeffs]
    rank = 3 if signs[3] else 2 if signs[2] else 1 if signs[1] else 0
    nz = [s for s in signs[: rank + 1] if s]
    pos = sum(1 for a, b in pairwise(nz) if a != b)
    return pos, rank - pos, 3 - rank


def _sqrt_in_field(x: QuadraticNumber, d: int) -> QuadraticNumber | None:
    """``sqrt(x)`` if it lies in ``Q(sqrt d)`` (``x >= 0``), else None."""
    if x.d == 1:
        r = QuadraticNumber.sqrt(x.a)
        return r if (r.d == 1 or r.d == d or d == 1) else None
    # sqrt(a + b sqrt d) = u + v sqrt d: u^2 + d v^2 = a, 2 u v = b
    norm = x.norm()
    if norm < 0:
        return None
    n = QuadraticNumber.sqrt(norm)
    if n.d != 1:
        return None
    for u2 in ((x.a + n.a) / 2, (x.a - n.a) / 2):
        u = QuadraticNumber.sqrt(u2) if u2 > 0 else None
        if u is not None and u.d == 1:
            cand = QuadraticNumber(u.a, x.b / (2 * u.a), x.d)
            if cand * cand == x:
                return cand if cand.sign() >= 0 else -cand
    return None


def _line_solutions(
    a: QuadraticNumber, b: QuadraticNumber, c: QuadraticNumber, disc: QuadraticNumber, d: int
) -> list[tuple[QuadraticNumber, QuadraticNumber]]:
    """Projective solutions ``(s, t)`` of ``a s^2 + 2 b s t + c t^2 = 0`` in ``Q(sqrt d)``
    (empty when they need another square root)."""
    one, zero = QuadraticNumber(1), QuadraticNumber(0)
    if a.is_zero():
        return [(one, zero), (-c, 2 * b)] if not b.is_zero() else [(one, zero)]
    if disc.is_zero():
        return [(-b, a)]
    root = _sqrt_in_field(disc, d)
    if root is None:
        return []
    try:
        return [(-b + root, a), (-b - root, a)]
    except ValueError:
        return []


def _member(lam: QuadraticNumber, E: Any, Q: Any) -> tuple[SingularMember, bool]:
    Em = [[QuadraticNumber(E[i, j]) for j in range(4)] for i in range(4)]
    S = [[lam * Em[i][j] + QuadraticNumber(Q[i, j]) for j in range(4)] for i in range(4)]
    K = nullspace(
        S,
        zero=QuadraticNumber(0),
        one=QuadraticNumber(1),
        is_zero=QuadraticNumber.is_zero,
        inverse=QuadraticNumber.inverse,
    )
    rank = 4 - len(K)
    points: list[tuple[QuadraticNumber, QuadraticNumber, QuadraticNumber]] = []
    count = 0
    curve = False
    if rank == 3:
        (X,) = K
        if not X[3].is_zero() and _form(Em, X, X).is_zero():
            w = X[3].inverse()
            points.append((X[0] * w, X[1] * w, X[2] * w))
            count = 1
    elif rank == 2:
        X1, X2 = K
        a, b, c = _form(Em, X1, X1), _form(Em, X1, X2), _form(Em, X2, X2)
        disc = b * b - a * c
        count = {1: 2, 0: 1, -1: 0}[disc.sign()]
        for st in _line_solutions(a, b, c, disc, lam.d) if count else []:
            Xp = [st[0] * X1[i] + st[1] * X2[i] for i in range(4)]
            w = Xp[3].inverse()  # E has no real points at infinity
            points.append((Xp[0] * w, Xp[1] * w, Xp[2] * w))
    elif rank == 1:
        G = [[_form(Em, u, v) for v in K] for u in K]
        p, n, z = _inertia_3(G)
        if p and n:
            curve = True
        elif z == 1:
            count = 1
    coincident = rank == 0
    return SingularMember(lam, rank, count, tuple(points), curve), coincident


def _multiple_roots(P: CharacteristicPolynomial) -> list[QuadraticNumber]:
    """The distinct real multiple roots of P, as elements of Q or Q(sqrt d)."""
    p = fmpq_poly_of(P.coefficients)
    g = p.gcd(p.derivative())
    if g.degree() <= 0:
        return []
    out: list[QuadraticNumber] = []
    _, factors = g.factor()
    for f, _m in factors:
        f = monic(flint.fmpq_poly(f))
        c = [fraction_of(x) for x in f.coeffs()]
        if f.degree() == 1:
            out.append(QuadraticNumber(-c[0]))
        elif f.degree() == 2:
            disc = c[1] * c[1] - 4 * c[0]
            if disc > 0:
                r = QuadraticNumber.sqrt(disc)
                for sgn in (1, -1):
                    out.append((QuadraticNumber(-c[1]) + sgn * r) / 2)
        else:  # pragma: no cover - a quartic has at most two distinct multiple roots
            raise AssertionError("gcd(P, P') of degree > 2")
    return out


def analyze_contact(E: Any, Q: Any, *, small: bool | None = None) -> ContactAnalysis:
    """The kind of contact between the ellipsoid ``E`` and the quadric ``Q``, with the evidence.

    Parameters
    ----------
    E : Quadric, matrix-like or equation
        A real ellipsoid.
    Q : Quadric, matrix-like or equation
        Any quadric.
    small : bool, optional
        Assert smallness; by default it is decided exactly where ``Q`` is a
        type of Table 1, and the geometric decision is used otherwise.

    Returns
    -------
    ContactAnalysis

    References
    ----------
    Proof of Theorem 2, Lemma 8, Table 3, Remark 9.

    Examples
    --------
    A sphere between two parallel planes touching both (Segre ``[(11)(11)]_2``):

    >>> a = analyze_contact("x**2 + y**2 + z**2 - 1", "x**2 - 1")
    >>> a.kind, str(a.segre)
    (<ContactKind.TWO_TANGENT_POINTS: 'two_tangent_points'>, '[(11)(11)]_2')
    >>> [[str(c.to_sympy()) for c in p] for m in a.members for p in m.points]
    [['1', '0', '0'], ['-1', '0', '0']]
    """
    P = characteristic_polynomial(E, Q)
    e, q = P.E, P.Q
    refuse(q)
    if q.kind in NO_REAL_POINTS:
        # No real surface to touch or cross (X^T Q X keeps one sign on all of space).
        seg = segre_symbol(e, q)
        return ContactAnalysis(ContactKind.NONE, seg, (), 0, False, False, "no real points", False, P)
    members: list[SingularMember] = []
    coincident = False
    for lam in _multiple_roots(P):
        m, co = _member(lam, e, q)
        members.append(m)
        coincident = coincident or co
    seg = segre_symbol(e, q)
    tangent_points = sum(m.tangent_points for m in members)
    tangent_curve = any(m.curve for m in members) or coincident
    if not P.structure.all_real:
        transversal, by = True, "Remark 9"
    else:
        if q.kind in (QuadricKind.PLANE,):
            transversal, by = False, "Theorem 14"
        else:
            res = decide_transversal(P, small=small, method="auto")
            transversal = bool(res.transversal)
            by = "Theorem 2" if res.decided_by == "Corollary 10" else str(res.decided_by)
    if coincident:
        kind = ContactKind.TANGENT_CURVE
    elif transversal:
        kind = ContactKind.TRANSVERSAL
    elif tangent_curve:
        kind = ContactKind.TANGENT_CURVE
    elif tangent_points >= 2:
        kind = ContactKind.TWO_TANGENT_POINTS
    elif tangent_points == 1:
        kind = ContactKind.TANGENT_POINT
    else:
        kind = ContactKind.NONE
    return ContactAnalysis(
        kind, seg, tuple(members), tangent_points, tangent_curve, transversal, by, coincident, P
    )


def contact_kind_exact(E: Any, Q: Any, *, small: bool | None = None) -> ContactKind:
    """The kind of contact (a row of Table 3) between ``E`` and ``Q``, decided exactly for
    one pair (the scalar path of :func:`quadric_contact.contact_kind` in the ``certified``
    and ``exact`` modes).

    See :func:`analyze_contact` for the evidence behind the answer.

    Parameters
    ----------
    E, Q, small
        As for :func:`analyze_contact`.

    Returns
    -------
    ContactKind

    References
    ----------
    Table 3, proof of Theorem 2.

    Examples
    --------
    A unit sphere inside a circular one-sheet hyperboloid, touching its throat:

    >>> contact_kind_exact("x**2 + y**2 + z**2 - 1", "x**2 + y**2 - z**2/4 - 1")
    <ContactKind.TANGENT_CURVE: 'tangent_curve'>
    >>> contact_kind_exact("2*x**2 + 2*y**2 + 3*z**2 - 1", "x**2 + y**2 + 8*z")   # Example 11
    <ContactKind.TRANSVERSAL: 'transversal'>
    """
    return analyze_contact(E, Q, small=small).kind
