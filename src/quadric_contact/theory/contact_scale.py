"""The first-contact scale: by what factor must ``E``, scaled about its centre, grow (or
shrink) to first touch ``Q``?  An exact real algebraic number read off the pencil.

The scaled ellipsoid
--------------------
Write the ellipsoid ``E`` (paper's sign, inside negative) as ``(x - c)^T A (x - c) = r``
with ``r > 0``.  Scaled about its centre by ``s > 0`` it is ``(x - c)^T A (x - c) = s^2 r``;
with ``t = s^2`` its matrix ``E_t`` differs from ``E`` in the corner entry only::

    E_t[3, 3] = c^T A c - t r.

Hence the pencil polynomial is *affine* in ``t``::

    P(l, t) = det(l E_t + Q) = P_0(l) + t B(l),   B(l) = -r l det(l A + Q_00),

(the cofactor of the corner entry), ``P_0 = det(l E_0 + Q)``.  With ``scale="both"`` (two
ellipsoids) ``Q`` is scaled about its own centre by the same factor, the corner of
``l E_t + Q_t`` is ``l (c^T A c - t r) + (c_Q^T A_Q c_Q - t r_Q)`` and
``B(l) = -(r l + r_Q) det(l A + A_Q)``: still affine in ``t``.

The contact scale
-----------------
``s* = inf {s > 0 : the closed solid of E_s meets the surface of Q}`` (one-sided), or
``inf {s > 0 : the solids of E_s and Q_s meet}`` (``scale="both"``: this is the square root of
the Perram-Wertheim contact function ``F(A, B)`` of two ellipsoids; Perram and Wertheim 1985).
Both predicates are monotone in ``s`` (the solids grow with ``s``).  ``s* = 0`` exactly when
the centre of ``E`` lies on the surface of ``Q`` (one-sided), or when the two ellipsoids share
their centre (``scale="both"``).

Which root
----------
At ``t* = s*^2`` the surfaces touch at a real point ``X = (p, 1)`` and ``X`` spans a kernel
vector of ``l0 E_t* + Q`` for a real ``l0``; with ``X^T E_t* X = 0``, Jacobi's formula makes
``l0`` a multiple root of ``P(., t*)`` (``proofs/first_contact_scale.py``).  Write
``P = G(l) P~(l, t)`` with ``G = gcd(P_0, B)`` the factor of ``P`` common to every ``t``.
Then ``t*`` is a root of

    ``R(t) = D(t) * Res_l(G*, P~)(t)``

where ``D`` is the discriminant (Yang's last ``D_n``, :mod:`quadric_contact.exact.discriminants`)
of ``P~`` in ``l`` and ``G*`` is ``G`` without its factor ``l`` (the structural root ``0``
of a singular ``Q``, whose kernel holds no finite point for the types accepted here).  The
roots of ``R`` are candidates; the answer is chosen and certified with the monotone predicate
itself, decided exactly at rational ``t`` by the package's exact decisions: with positive
candidates ``t_1 < t_2 < ...`` and rationals ``q_0 < t_1 < q_1 < t_2 < ...`` between them,
``t* = t_k`` for the first ``k`` with the predicate true at ``q_k``, and it is false at
``q_{k-1}`` (checked: an inconsistency raises, it never answers).

References
----------
J. W. Perram, M. S. Wertheim, Statistical mechanics of hard ellipsoids. I. Overlap algorithm
and the contact function, J. Comput. Phys. 58 (1985) 409-416.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import flint

from quadric_contact._generated import formulas
from quadric_contact.exact.algebraic import RealAlgebraic, algebraic_sqrt, rational_between, real_roots
from quadric_contact.exact.errors import ExcludedQuadricError, UndecidedError
from quadric_contact.model.classification import QuadricKind
from quadric_contact.model.quadric import Quadric, as_quadric
from quadric_contact.theory.geometric import decide_geometrically
from quadric_contact.theory.overlap import overlap_exact, solid_of

__all__ = [
    "SCALINGS",
    "ContactScaleResult",
    "centred_form",
    "contact_scale_exact",
    "reached_at",
    "scale_polynomial",
    "scaled",
]

SCALINGS = ("E", "both")
"""What is scaled: ``"E"`` alone (about its centre), or ``"both"`` ellipsoids about their
own centres (the Perram-Wertheim contact function)."""

_SEQUENCES: dict[int, Callable[..., Any]] = {
    2: formulas.discrimination_sequence_2,
    3: formulas.discrimination_sequence_3,
    4: formulas.discrimination_sequence_4,
}


def centred_form(E: Quadric) -> tuple[list[list[Fraction]], list[Fraction], Fraction]:
    """``(A, c, r)`` with ``E: (x - c)^T A (x - c) = r``, ``A`` positive definite, ``r > 0``.

    Parameters
    ----------
    E : Quadric
        A real ellipsoid with the paper's sign (inside negative).

    Examples
    --------
    >>> A, c, r = centred_form(Quadric.sphere(2, (1, 0, 0)))
    >>> A[0][0] * r   # the matrix is normalised: A = I/4, r = 1
    Fraction(1, 4)
    >>> c
    [Fraction(1, 1), Fraction(0, 1), Fraction(0, 1)]
    """
    centre = E.center()
    assert centre is not None, "an ellipsoid has a centre"
    A = [list(row) for row in E.quadratic_part]
    c = list(centre)
    cAc = sum(c[i] * A[i][j] * c[j] for i in range(3) for j in range(3))
    r = cAc - E.constant
    assert r > 0, "inside negative"
    return A, c, r


def scaled(E: Quadric, t: Fraction) -> Quadric:
    """The ellipsoid ``E`` scaled about its centre by ``sqrt(t)`` (``t > 0`` rational).

    Examples
    --------
    >>> scaled(Quadric.sphere(1, (3, 0, 0)), Fraction(4)).equation()
    'x**2 - 6*x + y**2 + z**2 + 5'
    """
    A, c, r = centred_form(E)
    cAc = sum(c[i] * A[i][j] * c[j] for i in range(3) for j in range(3))
    m = [list(row) for row in E.matrix]
    m[3][3] = cAc - t * r
    return Quadric(m)


def _det(m: list[list[Any]]) -> Any:
    """Determinant by cofactor expansion (entries in any commutative ring)."""
    n = len(m)
    if n == 1:
        return m[0][0]
    total = None
    for j in range(n):
        if m[0][j] == 0:
            continue
        minor = [row[:j] + row[j + 1 :] for row in m[1:]]
        term = m[0][j] * _det(minor) * (-1 if j % 2 else 1)
        total = term if total is None else total + term
    return total if total is not None else m[0][0] * 0


def _lin(a: Fraction, b: Fraction) -> Any:
    """The polynomial ``a + b l``."""
    return flint.fmpq_poly([flint.fmpq(a.numerator, a.denominator), flint.fmpq(b.numerator, b.denominator)])


def scale_polynomial(E: Quadric, Q: Quadric, scale: str = "E") -> tuple[Any, Any]:
    """``(P_0, B)`` with ``det(l E_t + Q_t) = P_0(l) + t B(l)`` (``fmpq_poly`` in ``l``).

    ``E_t`` is ``E`` scaled about its centre by ``sqrt(t)``; ``Q_t`` is ``Q`` (``scale="E"``)
    or ``Q`` scaled likewise about its centre (``scale="both"``, ``Q`` an ellipsoid).

    Examples
    --------
    Unit spheres centred 3 apart: at ``t = 4`` (``E`` grown to radius 2) they touch and a
    double root appears beside the structural one ``l = -1``:

    >>> P0, B = scale_polynomial(Quadric.sphere(1), Quadric.sphere(1, (3, 0, 0)))
    >>> P = P0 + 4 * B
    >>> P.gcd(P.derivative()).degree()
    2
    """
    A, c, r = centred_form(E)
    cAc = sum((c[i] * A[i][j] * c[j] for i in range(3) for j in range(3)), Fraction(0))
    q = [list(row) for row in Q.matrix]
    e0 = [list(row) for row in E.matrix]
    e0[3][3] = cAc
    rq = Fraction(0)
    if scale == "both":
        AQ, cq, rq = centred_form(Q)
        q[3][3] = sum((cq[i] * AQ[i][j] * cq[j] for i in range(3) for j in range(3)), Fraction(0))
    pencil = [[_lin(q[i][j], e0[i][j]) for j in range(4)] for i in range(4)]
    P0 = _det(pencil)
    top = _det([row[:3] for row in pencil[:3]])
    B = -_lin(rq, r) * top
    return P0, B


def _candidates(P0: Any, B: Any) -> Any:
    """``R(t) = D(t) Res_l(G*, P~)(t)`` as an ``fmpq_poly`` in ``t`` (see the module notes)."""
    G = P0.gcd(B)
    Pt, Bt = P0 / G, B / G  # exact division in Q[l]
    n = max(Pt.degree(), Bt.degree())
    coeffs = [
        flint.fmpq_poly(
            [Pt.coeffs()[k] if k <= Pt.degree() else 0, Bt.coeffs()[k] if k <= Bt.degree() else 0]
        )
        for k in range(n + 1)
    ]
    R = flint.fmpq_poly([1])
    if n >= 2:
        R = R * _SEQUENCES[n](*coeffs)[-1]
    g = G
    while g.degree() > 0 and g.coeffs()[0] == 0:
        g = g / flint.fmpq_poly([0, 1])
    if g.degree() > 0:
        # Res_l(g, Pt + t Bt) = lc(g)^n prod_{g(a) = 0} (Pt(a) + t Bt(a)): a polynomial of degree
        # <= deg g in t, interpolated exactly from deg g + 1 values.
        m = g.degree()
        xs = [flint.fmpq(k) for k in range(m + 1)]
        ys = [g.resultant(Pt + int(x) * Bt) for x in xs]
        R = R * _interpolate(xs, ys)
    return R


def _interpolate(xs: list[Any], ys: list[Any]) -> Any:
    """The polynomial of degree < len(xs) through the points (Lagrange, exact)."""
    out = flint.fmpq_poly([0])
    for i, (xi, yi) in enumerate(zip(xs, ys, strict=True)):
        term = flint.fmpq_poly([yi])
        for j, xj in enumerate(xs):
            if j != i:
                term = term * flint.fmpq_poly([-xj, 1]) / (xi - xj)
        out += term
    return out


def reached_at(E: Quadric, Q: Quadric, t: Fraction, scale: str = "E") -> bool:
    """The monotone predicate at a rational ``t > 0``: does the solid of ``E_t`` meet the
    surface of ``Q`` (``scale="E"``), or the solid of ``Q_t`` (``scale="both"``)?  Decided
    exactly (:func:`~quadric_contact.theory.geometric.decide_geometrically`,
    :func:`~quadric_contact.theory.overlap.overlap_exact`).

    Examples
    --------
    >>> e, q = Quadric.sphere(1), Quadric.plane((1, 0, 0), 3)
    >>> reached_at(e, q, Fraction(8)), reached_at(e, q, Fraction(9))
    (False, True)
    """
    Et = scaled(E, t)
    if scale == "both":
        return overlap_exact(Et, scaled(Q, t)).code.name != "SEPARATE"
    g = decide_geometrically(Et, Q)
    if g.minimum.sign() <= 0 <= g.maximum.sign():
        return True  # the surfaces meet
    if Q.kind is QuadricKind.ELLIPSOID:
        # surfaces apart: the surface of Q meets the solid of E_t iff it lies inside it
        return decide_geometrically(Q.as_ellipsoid(), Et).maximum.sign() < 0
    return False  # only an ellipsoid has a compact (closed) surface


@dataclass(frozen=True)
class ContactScaleResult:
    """The first-contact scale of a pair, exactly.

    Attributes
    ----------
    scale : RealAlgebraic
        ``s* >= 0``: ``E`` scaled about its centre by ``s*`` first touches ``Q``.
    squared : RealAlgebraic
        ``t* = s*^2``, a root of :attr:`polynomial`.
    polynomial : fmpq_poly
        ``R(t)``, whose roots hold every tangency of the scaled pencil.
    scaling : str
        ``"E"`` or ``"both"``.
    bracket : tuple of Fraction
        Rationals ``q_lo < t* < q_hi`` at which the monotone predicate was decided false and
        true (``(0, 0)`` when ``s* = 0``): ``t*`` is the only root of ``R`` between them.
    """

    scale: RealAlgebraic
    squared: RealAlgebraic
    polynomial: Any
    scaling: str
    bracket: tuple[Fraction, Fraction]

    def __float__(self) -> float:
        return float(self.scale)

    @property
    def touching(self) -> bool:
        """``s* = 1``: the pair touches as given."""
        return self.squared.compare(1) == 0

    @property
    def apart(self) -> bool:
        """``s* > 1``: ``E`` (``scale="E"``: its solid, from ``Q``'s surface) is clear of ``Q``."""
        return self.squared.compare(1) > 0


def _validate(E: Any, Q: Any, scale: str) -> tuple[Quadric, Quadric]:
    if scale not in SCALINGS:
        raise ValueError(f"scale must be one of {SCALINGS}, got {scale!r}")
    e = as_quadric(E, "E").as_ellipsoid()
    # with scale "E": the types with a solid (Table 1 and planes), the kinds the decisions know
    q = as_quadric(Q, "Q").as_ellipsoid() if scale == "both" else solid_of(Q)
    return e, q


def contact_scale_exact(E: Any, Q: Any, *, scale: str = "E") -> ContactScaleResult:
    """The factor ``s* >= 0`` by which ``E``, scaled about its centre, first touches ``Q``.

    Parameters
    ----------
    E : Quadric, equation or matrix-like
        A real ellipsoid.
    Q : Quadric, equation or matrix-like
        A quadric of Table 1 or a plane (``scale="E"``); an ellipsoid (``scale="both"``).
    scale : {"E", "both"}
        Scale ``E`` alone, or both ellipsoids about their own centres (then ``s*^2`` is the
        Perram-Wertheim contact function).

    Returns
    -------
    ContactScaleResult

    Raises
    ------
    NotAnEllipsoidError, ExcludedQuadricError
    UndecidedError
        If the candidates and the monotone predicate disagree (never observed; a guard).

    Examples
    --------
    A unit sphere 3 away from a unit sphere: ``E`` alone must grow to radius 2, both only
    to radius 3/2:

    >>> e, q = Quadric.sphere(1), Quadric.sphere(1, (3, 0, 0))
    >>> contact_scale_exact(e, q).scale, contact_scale_exact(e, q, scale="both").scale
    (RealAlgebraic(2), RealAlgebraic(3/2))
    >>> str(contact_scale_exact("x**2 + y**2 + z**2 - 1", "x**2 - y**2 - 1").scale)
    '1'
    >>> contact_scale_exact("2*x**2 + y**2 + z**2 - 1", "x - 2").scale.decimal(12)
    '2.828427124746'
    """
    e, q = _validate(E, Q, scale)
    _, c, _ = centred_form(e)
    if (scale == "E" and q.value_at(c) == 0) or (scale == "both" and q.center() == tuple(c)):
        # the centre of E on the surface of Q; or two ellipsoids with one centre, whose solids
        # share it at every scale
        zero = RealAlgebraic(0)
        return ContactScaleResult(zero, zero, flint.fmpq_poly([0, 1]), scale, (Fraction(0), Fraction(0)))
    P0, B = scale_polynomial(e, q, scale)
    R = _candidates(P0, B)
    if R.is_zero():
        raise UndecidedError(f"the scaled pencil of {e} and {q} is tangent for every scale", e, other=q)
    roots = real_roots(R, Fraction(0), _upper_bound(R))
    below = Fraction(0)
    for k, t in enumerate(roots):
        after = roots[k + 1] if k + 1 < len(roots) else None
        above = rational_between(t, after) if after is not None else _beyond(t)
        if reached_at(e, q, above, scale):
            lo = below if below > 0 else _below(t)
            if reached_at(e, q, lo, scale):
                raise UndecidedError(
                    f"the scale predicate holds below the candidate {t} for {e} and {q}", e, other=q
                )
            return ContactScaleResult(algebraic_sqrt(t), t, R, scale, (lo, above))
        below = above
    raise ExcludedQuadricError(f"{q} is never reached by {e} scaled about its centre", q)


def _upper_bound(R: Any) -> Fraction:
    """A rational above every root of ``R`` (Cauchy's bound)."""
    cs = [Fraction(int(a.p), int(a.q)) for a in R.coeffs()]
    while cs and cs[-1] == 0:
        cs.pop()
    return 2 + max((abs(x / cs[-1]) for x in cs[:-1]), default=Fraction(0))


def _beyond(t: RealAlgebraic) -> Fraction:
    """A rational beyond ``t`` (``2 (floor(hi) + 1) + 1``), in exact arithmetic: ``t`` may lie
    beyond binary64's range."""
    return Fraction(math.floor(Fraction(t.hi)) + 1) * 2 + 1


def _below(t: RealAlgebraic) -> Fraction:
    """A positive rational below ``t > 0`` (no root of ``R`` lies between: ``t`` is the first)."""
    return rational_between(RealAlgebraic(0), t)
