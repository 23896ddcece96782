"""An exact geometric decision of how an ellipsoid meets a quadric.

This does not use the characteristic polynomial of the pencil.  It studies
``f(X) = X^T Q X`` on the *surface* of the ellipsoid ``E``:

* ``min f > 0``: the surface of ``E`` lies in ``R+ \\ Q`` (no contact);
  ``max f < 0``: in ``R- \\ Q``;
* ``min f = 0`` (or ``max f = 0``): ``E`` touches ``Q`` from ``R+`` (``R-``)
  without crossing it; the touching set is the set of minimisers: one
  point, two points, a circle (a curve of tangency) or all of ``E``
  (``Q`` is a multiple of ``E``);
* ``min f < 0 < max f``: the surfaces cross (transversal contact); the
  number of intersection curves follows from the critical points by Morse
  theory on the sphere.

Lagrange conditions
-------------------
With ``E: (x - x0)^T A_E (x - x0) = r`` and the exact ``LDL^T`` factorisation
``A_E = L D L^T``, the substitution ``x = x0 + L^-T y`` turns ``E`` into
``y^T D y = r`` (``D`` diagonal, positive) and ``f`` into
``y^T A' y + 2 b'^T y + c'``.  The critical points of ``f`` on ``E`` solve
``(A' - mu D) y = -b'``, ``y^T D y = r``.  With ``p3(mu) = det(A' - mu D)``
and ``w(mu) = adj(A' - mu D) b'``:

* *regular* critical points (``p3(mu) != 0``): ``y = -w/p3``, the roots of
  the degree-6 *secular polynomial* ``w^T D w - r p3^2`` that are not roots
  of ``p3``; the critical value is ``F(mu) = mu r + c' - b'^T w / p3``;
* *eigen* critical sets (``p3(lambda) = 0``, the system consistent): the
  points ``y_p + z`` with ``z`` in the kernel of ``A' - lambda D`` and
  ``(y_p + z)^T D (y_p + z) = r``: no point, one, two, a circle (double
  eigenvalue) or all of ``E`` (triple eigenvalue and ``b' = 0``).  These
  are the symmetric ("concentric", "coaxial") configurations.

Every multiplier is a real algebraic number (roots of polynomials over Q),
every critical value an exact :class:`~quadric_contact.exact.algebraic.RealAlgebraic`;
minimum and maximum are found by exact comparison, signs decided exactly.
The Morse index of a regular critical point is read from the bordered
Hessian, ``sign(n^T adj(A' - mu D) n)`` with ``n = D y`` (a polynomial in
``mu``), and the trace of the Hessian on the tangent plane.

Counting curves
---------------
For ``M = {f <= 0}`` and ``N = {f >= 0}`` on the sphere (0 a regular value):
``chi(M) = sum over critical sets below 0 of (-1)^index chi(set)``, each
component of ``M`` is a sphere with holes, so ``chi(M) = 2 c(M) - k`` with
``k`` the number of curves, and the components of ``M`` and ``N`` form a
tree whose edges are the curves: ``k = c(M) + c(N) - 1``.  ``c(M)`` lies
between ``#minima - #saddles`` and ``#minima`` below 0 (and likewise for
``N``); when these bounds leave two possibilities, the real intersection
of two quadrics has at most two components (Harnack's bound for a curve of
genus 1) and that decides (``harnack`` is then True in the result).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import flint

from quadric_contact.exact.algebraic import (
    RealAlgebraic,
    algebraic_value,
    real_roots,
    sign_at,
)
from quadric_contact.exact.errors import ExcludedQuadricError
from quadric_contact.exact.linalg import nullspace, solve
from quadric_contact.exact.rational import fmpq_of, fmpq_poly_of
from quadric_contact.exact.size import check_pair_size
from quadric_contact.model.classification import QuadricKind
from quadric_contact.model.quadric import Quadric
from quadric_contact.theory.pencil import as_quadric
from quadric_contact.theory.results import Region

__all__ = ["CriticalSet", "GeometricDecision", "decide_geometrically"]

Poly = Any  # flint.fmpq_poly


@dataclass(frozen=True)
class CriticalSet:
    """A connected family of critical points of ``X^T Q X`` on the surface of ``E``.

    Attributes
    ----------
    value : RealAlgebraic
        The critical value (exact).
    shape : str
        ``"point"`` (one point), ``"pair"`` (two points with the same
        multiplier), ``"circle"`` or ``"surface"`` (all of ``E``).
    index : int or None
        Morse index (0 minimum, 1 saddle, 2 maximum) for points; for a
        circle 0 (a circle of minima) or 2 (of maxima); None when the
        critical points are degenerate.
    multiplier : RealAlgebraic
        The Lagrange multiplier ``mu``.
    """

    value: RealAlgebraic
    shape: str
    index: int | None
    multiplier: RealAlgebraic

    @property
    def points(self) -> int | None:
        """Number of points, None for a circle or the whole surface."""
        return {"point": 1, "pair": 2}.get(self.shape)

    def describe(self) -> str:
        kind = {0: "minimum", 1: "saddle", 2: "maximum", None: "degenerate"}[self.index]
        what = {"point": "point", "pair": "two points", "circle": "circle", "surface": "whole surface"}[
            self.shape
        ]
        return f"{what} ({kind}) at value {self.value.approx(10)}"


@dataclass(frozen=True)
class GeometricDecision:
    """How the surface of ``E`` meets ``Q``, decided exactly without the pencil.

    Attributes
    ----------
    transversal : bool
        The surfaces cross (``min f < 0 < max f``).
    region : Region
        ``R-`` or ``R+`` (surface of ``E`` in that closed region, tangency
        allowed) or ``Region.CONTACT`` when transversal.  When ``Q`` is a
        multiple of ``E`` (``coincident``) the surface lies in both; ``R-``
        is reported.
    minimum, maximum : RealAlgebraic
        ``min`` and ``max`` of ``X^T Q X`` over the surface of ``E``
        (``E`` normalised to ``det E < 0``, ``Q`` exactly as given).
    minimizers, maximizers : str
        Structure of the extremal sets: ``"1 point"``, ``"2 points"``,
        ``"circle"``, ``"surface"``, or unions such as ``"1 point + circle"``.
    tangent_points : int
        Number of isolated points where the surfaces touch (critical points
        with value 0), whether or not they also cross elsewhere.
    tangent_curve : bool
        The surfaces touch along a circle (a critical circle with value 0).
    curves : int or None
        Number of intersection curves when the surfaces cross and 0 is not
        a critical value (None otherwise).
    harnack : bool
        ``curves`` needed Harnack's bound (at most two components).
    critical_sets : tuple of CriticalSet
    """

    transversal: bool
    region: Region
    minimum: RealAlgebraic
    maximum: RealAlgebraic
    minimizers: str
    maximizers: str
    tangent_points: int
    tangent_curve: bool
    curves: int | None
    harnack: bool
    coincident: bool
    critical_sets: tuple[CriticalSet, ...] = field(repr=False)

    @property
    def touching(self) -> bool:
        """The surfaces meet (crossing or tangent)."""
        return self.minimum.sign() <= 0 <= self.maximum.sign()

    def to_dict(self) -> dict[str, Any]:
        return {
            "transversal": self.transversal,
            "region": self.region.value,
            "min": self.minimum.approx(15),
            "max": self.maximum.approx(15),
            "minimizers": self.minimizers,
            "maximizers": self.maximizers,
            "tangent_points": self.tangent_points,
            "tangent_curve": self.tangent_curve,
            "curves": self.curves,
            "harnack": self.harnack,
            "coincident": self.coincident,
            "critical_sets": [c.describe() for c in self.critical_sets],
        }

    def __str__(self) -> str:
        lo, hi = self.minimum.approx(8), self.maximum.approx(8)
        if self.coincident:
            return "E and Q are the same surface (X^T Q X = 0 on all of E)"
        if self.transversal:
            n = f"{self.curves} curve{'s' if self.curves != 1 else ''}" if self.curves else "curves"
            extra = f", touching at {self.tangent_points} point(s)" if self.tangent_points else ""
            return f"transversal contact: min X^T Q X = {lo} < 0 < {hi} = max on E ({n}{extra})"
        side = "R+" if self.region is Region.R_PLUS else "R-"
        if self.tangent_curve:
            return f"E in {side}, tangent to Q along a circle (min {lo}, max {hi})"
        if self.tangent_points:
            return f"E in {side}, tangent to Q at {self.tangent_points} point(s) (min {lo}, max {hi})"
        return f"E in {side}, no contact (min X^T Q X = {lo}, max = {hi} on E)"


# -- exact linear algebra helpers --------------------------------------------------------------

Mat = list[list[Fraction]]


def _ldl(A: Mat) -> tuple[Mat, list[Fraction]]:
    """``A = L D L^T`` (L unit lower triangular) for a positive definite rational A."""
    n = len(A)
    L = [[Fraction(int(i == j)) for j in range(n)] for i in range(n)]
    D = [Fraction(0)] * n
    for j in range(n):
        D[j] = A[j][j] - sum((L[j][k] ** 2 * D[k] for k in range(j)), Fraction(0))
        assert D[j] > 0
        for i in range(j + 1, n):
            L[i][j] = (A[i][j] - sum((L[i][k] * L[j][k] * D[k] for k in range(j)), Fraction(0))) / D[j]
    return L, D


def _inv_lower_unit(L: Mat) -> Mat:
    n = len(L)
    X = [[Fraction(int(i == j)) for j in range(n)] for i in range(n)]
    for i in range(n):
        for j in range(i):
            X[i][j] = -sum((L[i][k] * X[k][j] for k in range(j, i)), Fraction(0))
    return X


def _mul(A: Mat, B: Mat) -> Mat:
    return [
        [sum((A[i][k] * B[k][j] for k in range(len(B))), Fraction(0)) for j in range(len(B[0]))]
        for i in range(len(A))
    ]


def _T(A: Mat) -> Mat:
    return [list(r) for r in zip(*A, strict=True)]


def _matvec(A: Mat, v: Sequence[Fraction]) -> list[Fraction]:
    return [sum((A[i][k] * v[k] for k in range(len(v))), Fraction(0)) for i in range(len(A))]


# -- polynomial helpers ---------------------------------------------------------------------


def _poly_fn(num: Poly, den: Poly | None = None) -> Callable[..., Any]:
    """A ``takes_const`` function ``mu -> num(mu)/den(mu)`` for :func:`algebraic_value`."""
    nc = [Fraction(int(c.p), int(c.q)) for c in num.coeffs()]
    dc = [Fraction(int(c.p), int(c.q)) for c in den.coeffs()] if den is not None else None

    def horner(coeffs: list[Fraction], x: Any, const: Callable[[Fraction], Any]) -> Any:
        acc = const(coeffs[-1]) if coeffs else const(Fraction(0))
        for c in reversed(coeffs[:-1]):
            acc = acc * x + const(c)
        return acc

    def run(x: Any, const: Callable[[Fraction], Any] = Fraction) -> Any:
        v = horner(nc, x, const)
        if dc is not None:
            v = v / horner(dc, x, const)
        return v

    run.takes_const = True  # type: ignore[attr-defined]
    return run


def _value(num: Poly, den: Poly | None, mu: RealAlgebraic) -> RealAlgebraic:
    if mu.is_rational:
        x = fmpq_of(mu.as_fraction())
        v = num(x) / (den(x) if den is not None else 1)
        return RealAlgebraic(Fraction(int(v.p), int(v.q)))
    if den is not None:
        # reduce modulo the minimal polynomial first (keeps the matrices small)
        m = mu.poly
        return algebraic_value(_poly_fn(num % m, den % m), [mu])
    return algebraic_value(_poly_fn(num % mu.poly), [mu])


# -- the decision ---------------------------------------------------------------------------


def _setup(E: Quadric, Q: Quadric) -> tuple[list[Fraction], Mat, list[Fraction], Fraction, Fraction]:
    """``(D, A', b', c', r)`` of the module docstring."""
    AE = [[E[i, j] for j in range(3)] for i in range(3)]
    bE = [E[i, 3] for i in range(3)]
    x0 = solve(AE, [-v for v in bE])
    assert x0 is not None
    r = -E.value_at(x0)
    assert r > 0
    L, D = _ldl(AE)
    Minv = _T(_inv_lower_unit(L))  # x = x0 + M y with M = L^-T
    A = [[Q[i, j] for j in range(3)] for i in range(3)]
    b = [Q[i, 3] for i in range(3)]
    Ap = _mul(_T(Minv), _mul(A, Minv))
    Ax0b = [u + v for u, v in zip(_matvec(A, x0), b, strict=True)]
    bp = _matvec(_T(Minv), Ax0b)
    cp = Q.value_at(x0)
    return D, Ap, bp, cp, r


def decide_geometrically(E: Any, Q: Any) -> GeometricDecision:
    """Decide exactly how the surface of the ellipsoid ``E`` meets the quadric ``Q``.

    Independent of the characteristic polynomial: the extremes of
    ``X^T Q X`` over the surface of ``E`` are found from the Lagrange
    conditions (see the module docstring), exactly.

    Parameters
    ----------
    E : Quadric, matrix-like or equation
        A real ellipsoid (normalised to ``det E < 0``).
    Q : Quadric, matrix-like or equation
        Any quadric (cones, planes and the other types the theory excludes
        are fine), taken exactly as given: its sign fixes ``R-`` and ``R+``.

    Returns
    -------
    GeometricDecision

    Raises
    ------
    NotAnEllipsoidError
        If ``E`` is not a real ellipsoid.
    ExcludedQuadricError
        If ``Q`` is the zero matrix.
    WorkLimitError
        If the pair is larger than :data:`~quadric_contact.exact.bounds.MAX_PAIR_BITS`
        (refused before the work).

    References
    ----------
    Remark 9 (why this is needed when ``E`` is not small), eq. (8).

    Examples
    --------
    The flat ellipsoid inside the throat of a one-sheet hyperboloid (the
    counterexample to Table 1): two intersection curves, four real roots.

    >>> g = decide_geometrically("100*(x - 17/20)**2 + y**2 + z**2 - 1", "x**2 + y**2 - z**2/100 - 1")
    >>> g.transversal, g.curves
    (True, 2)

    A unit sphere inside a circular cylinder of radius 1: a circle of tangency.

    >>> g = decide_geometrically("x**2 + y**2 + z**2 - 1", "x**2 + y**2 - 1")
    >>> g.region, g.tangent_curve, g.maximizers
    (<Region.R_MINUS: 'R-'>, True, 'circle')
    """
    e = as_quadric(E, "E").as_ellipsoid()
    q = as_quadric(Q, "Q")
    check_pair_size(e, q, "the exact geometric decision")
    if q.kind is QuadricKind.ZERO:
        raise ExcludedQuadricError("Q is the zero matrix: every point satisfies X^T Q X = 0", q, kind=q.kind)
    D, Ap, bp, cp, r = _setup(e, q)
    sets = _critical_sets(D, Ap, bp, cp, r)
    return _classify(sets)


def _critical_sets(
    D: list[Fraction], Ap: Mat, bp: list[Fraction], cp: Fraction, r: Fraction
) -> list[CriticalSet]:
    mu = flint.fmpq_poly([0, 1])
    H = [
        [fmpq_poly_of([Ap[i][j]]) - (mu * fmpq_of(D[i]) if i == j else 0) for j in range(3)] for i in range(3)
    ]

    def cof(i: int, j: int) -> Poly:
        rows = [k for k in range(3) if k != i]
        cols = [k for k in range(3) if k != j]
        m = H[rows[0]][cols[0]] * H[rows[1]][cols[1]] - H[rows[0]][cols[1]] * H[rows[1]][cols[0]]
        return m if (i + j) % 2 == 0 else -m

    adj = [[cof(j, i) for j in range(3)] for i in range(3)]  # adjugate = transpose of cofactors
    p3 = sum((H[0][j] * cof(0, j) for j in range(3)), fmpq_poly_of([0]))
    bq = [fmpq_of(v) for v in bp]
    w = [sum((adj[i][j] * bq[j] for j in range(3)), fmpq_poly_of([0])) for i in range(3)]
    Dq = [fmpq_of(d) for d in D]
    Dw = [Dq[i] * w[i] for i in range(3)]
    Pb = sum((bq[i] * w[i] for i in range(3)), fmpq_poly_of([0]))
    Npsi = sum((w[i] * Dw[i] for i in range(3)), fmpq_poly_of([0]))
    rq, cq = fmpq_of(r), fmpq_of(cp)
    S = Npsi - rq * p3 * p3
    NF = (mu * rq + cq) * p3 - Pb  # F = NF / p3
    # bordered Hessian and tangent trace, as polynomials in mu
    G = sum((Dw[i] * adj[i][j] * Dw[j] for i in range(3) for j in range(3)), fmpq_poly_of([0]))
    trH = H[0][0] + H[1][1] + H[2][2]
    Tr = trH * sum((Dw[i] * Dw[i] for i in range(3)), fmpq_poly_of([0])) - sum(
        (Dw[i] * H[i][j] * Dw[j] for i in range(3) for j in range(3)), fmpq_poly_of([0])
    )

    sets: list[CriticalSet] = []
    # regular critical points: roots of S that are not roots of p3
    Sreg = S
    while True:
        g = Sreg.gcd(p3)
        if g.degree() <= 0:
            break
        Sreg = Sreg / g
    if Sreg.degree() > 0:
        for root, mult in real_roots(Sreg, multiplicities=True):
            value = _value(NF, p3, root)
            idx: int | None
            sg = sign_at(G, root) if mult == 1 else 0
            if sg > 0:
                idx = 0 if sign_at(Tr, root) > 0 else 2
            elif sg < 0:
                idx = 1
            else:
                idx = None
            sets.append(CriticalSet(value, "point", idx, root))
    # eigen critical sets
    _, factors = p3.factor()
    eig_roots: list[tuple[RealAlgebraic, int]] = []
    for f, m in factors:
        for rt in real_roots(f):
            eig_roots.append((rt, m))
    for lam, m in eig_roots:
        below = sum(mm for other, mm in eig_roots if other < lam)
        if m == 1:
            sets.extend(_simple_eigen(lam, below, Pb, p3, w, Dq, rq, cq))
        else:
            lamq = lam.as_fraction()  # a multiple root of a cubic over Q is rational
            sets.extend(_multiple_eigen(lamq, m, below, eig_roots, D, Ap, bp, cp, r))
    return sets


def _simple_eigen(
    lam: RealAlgebraic, below: int, Pb: Poly, p3: Poly, w: list[Poly], Dq: list[Any], rq: Any, cq: Any
) -> list[CriticalSet]:
    """Critical points at a simple eigenvalue: y = y_p +- t v (consistent case)."""
    if sign_at(Pb, lam) != 0:
        return []  # b' has a component along the eigenvector: no critical point here
    mu = flint.fmpq_poly([0, 1])
    dp3 = p3.derivative()
    dw = [wi.derivative() for wi in w]
    # psi(lambda) = y_p^T D y_p with y_p = -w'(lambda)/p3'(lambda)
    R1 = rq * dp3 * dp3 - sum((dw[i] * Dq[i] * dw[i] for i in range(3)), fmpq_poly_of([0]))
    s = sign_at(R1, lam)
    if s < 0:
        return []
    value = _value((mu * rq + cq) * dp3 - Pb.derivative(), dp3, lam)
    if s == 0:
        return [CriticalSet(value, "point", None, lam)]
    index = {0: 0, 1: 1, 2: 2}[below]
    return [CriticalSet(value, "pair", index, lam)]


def _multiple_eigen(
    lam: Fraction,
    m: int,
    below: int,
    eig_roots: list[tuple[RealAlgebraic, int]],
    D: list[Fraction],
    Ap: Mat,
    bp: list[Fraction],
    cp: Fraction,
    r: Fraction,
) -> list[CriticalSet]:
    """Critical sets at a double or triple (rational) eigenvalue."""
    H = [[Ap[i][j] - (lam * D[i] if i == j else 0) for j in range(3)] for i in range(3)]
    kernel = nullspace(H, zero=Fraction(0), one=Fraction(1))
    if any(sum((k[i] * bp[i] for i in range(3)), Fraction(0)) != 0 for k in kernel):
        return []  # inconsistent
    lamA = RealAlgebraic(lam)
    if m == 3:
        return [CriticalSet(RealAlgebraic(lam * r + cp), "surface", None, lamA)]
    y = solve(H, [-v for v in bp])
    assert y is not None
    # make y_p D-orthogonal to the kernel (Gram matrix solve)
    G = [[sum((k1[i] * D[i] * k2[i] for i in range(3)), Fraction(0)) for k2 in kernel] for k1 in kernel]
    rhs = [sum((k[i] * D[i] * y[i] for i in range(3)), Fraction(0)) for k in kernel]
    coef = solve(G, rhs)
    assert coef is not None
    yp = [y[i] - sum((coef[j] * kernel[j][i] for j in range(len(kernel))), Fraction(0)) for i in range(3)]
    rho = r - sum((yp[i] * D[i] * yp[i] for i in range(3)), Fraction(0))
    if rho < 0:
        return []
    value = RealAlgebraic(lam * r + cp + sum((bp[i] * yp[i] for i in range(3)), Fraction(0)))
    if rho == 0:
        return [CriticalSet(value, "point", None, lamA)]
    other = next(o for o, mm in eig_roots if mm == 1)
    index = 0 if other > lamA else 2
    return [CriticalSet(value, "circle", index, lamA)]


def _shape_text(sets: list[CriticalSet]) -> str:
    pts = sum(c.points or 0 for c in sets)
    parts = []
    if pts:
        parts.append(f"{pts} point{'s' if pts > 1 else ''}")
    circles = sum(1 for c in sets if c.shape == "circle")
    if circles:
        parts.append("circle" if circles == 1 else f"{circles} circles")
    if any(c.shape == "surface" for c in sets):
        parts.append("surface")
    return " + ".join(parts)


def _classify(sets: list[CriticalSet]) -> GeometricDecision:
    values = [c.value for c in sets]
    lo = min(values)
    hi = max(values)
    minimizers = [c for c in sets if c.value == lo]
    maximizers = [c for c in sets if c.value == hi]
    slo, shi = lo.sign(), hi.sign()
    zero_sets = [c for c in sets if c.value.sign() == 0]
    tangent_points = sum(c.points or 0 for c in zero_sets)
    tangent_curve = any(c.shape == "circle" for c in zero_sets)
    coincident = any(c.shape == "surface" for c in zero_sets)
    transversal = slo < 0 < shi
    if transversal:
        region = Region.CONTACT
    elif slo >= 0 and not (shi == 0 and slo == 0):
        region = Region.R_PLUS
    else:
        region = Region.R_MINUS
    curves, harnack = (None, False)
    if transversal and not zero_sets:
        curves, harnack = _count_curves(sets)
    return GeometricDecision(
        transversal=transversal,
        region=region,
        minimum=lo,
        maximum=hi,
        minimizers=_shape_text(minimizers),
        maximizers=_shape_text(maximizers),
        tangent_points=tangent_points,
        tangent_curve=tangent_curve,
        curves=curves,
        harnack=harnack,
        coincident=coincident,
        critical_sets=tuple(sets),
    )


def _count_curves(sets: list[CriticalSet]) -> tuple[int | None, bool]:
    """Number of curves of ``{f = 0}`` (0 a regular value), by Morse-Bott counts."""
    if any(c.index is None for c in sets):
        return None, False
    chi_M = 0
    seeds_M = mergers_M = seeds_N = mergers_N = 0
    for c in sets:
        below = c.value.sign() < 0
        npts = c.points or 0  # circles contribute 0 to the Euler characteristic
        if below:
            chi_M += npts * (-1) ** (c.index or 0)
        is_min = c.index == 0
        is_max = c.index == 2
        is_sad = c.index == 1
        count = npts if c.shape != "circle" else 1
        if below:
            seeds_M += count if is_min else 0
            mergers_M += count if (is_sad or (is_max and c.shape == "circle")) else 0
        else:
            seeds_N += count if is_max else 0
            mergers_N += count if (is_sad or (is_min and c.shape == "circle")) else 0
    options = []
    for cM in range(max(1, seeds_M - mergers_M), seeds_M + 1):
        cN = cM - chi_M + 1
        if max(1, seeds_N - mergers_N) <= cN <= seeds_N:
            options.append(cM + cN - 1)
    options = sorted(set(options))
    if len(options) == 1:
        return options[0], False
    bounded = [k for k in options if k <= 2]
    if len(bounded) == 1:
        return bounded[0], True
    return None, False
