"""Exact tools shared by the proofs: the real intersection of two symmetric quadrics,
their tangent points, the contact type, and the Segre characteristic of the pencil.

Symmetric pairs.  The constructions of the proofs place both quadrics
symmetrically with respect to the planes ``y = 0`` and ``z = 0``: each is
``f(x) + p y^2 + q z^2 = 0`` with ``f`` of degree <= 2 (the matrix has no
``xy, xz, yz, y, z`` entries).  Writing ``Y = y^2 >= 0``, ``Z = z^2 >= 0``,
the two equations are linear in ``(Y, Z)``:

* if the 2x2 system is regular, ``Y = Y(x)`` and ``Z = Z(x)`` are
  polynomials of degree <= 2 and the real intersection is
  ``{(x, +-sqrt Y(x), +-sqrt Z(x)) : Y(x) >= 0, Z(x) >= 0}``.  The set of such
  ``x`` is a finite union of closed intervals and points, found exactly from
  the real roots of ``Y`` and ``Z``.  Over an interval ``[l, r]`` the preimage
  is ``2^k`` closed curves, ``k`` the number of ``Y, Z`` that stay positive
  on all of ``[l, r]`` (a coordinate that vanishes somewhere lets the curve
  pass from one sign to the other); over an isolated ``x`` it is ``2^k``
  points;
* if it is singular (the ``(y^2, z^2)`` parts are proportional), a
  combination of the equations involves ``x`` only: each real root ``x_k``
  gives the ellipse ``p y^2 + q z^2 = -f(x_k)`` of the ellipsoid (a curve, a
  point or nothing).

Tangent points.  ``E`` and ``Q`` are tangent at ``X`` (homogeneous) iff
``(l E + Q) X = 0`` for some ``l``, necessarily a multiple root of ``P`` (a
root of ``gcd(P, P')``, rational or quadratic).  The real points of ``E`` in
the kernel of ``l E + Q`` are found exactly: a point, a pair of points on a
line, or a plane section (a curve of tangency).

Segre characteristic.  For each root ``l`` of ``P`` the sizes of the Jordan
blocks of ``-E^-1 Q`` at ``l`` (from the ranks of its powers); blocks of one
eigenvalue are grouped in parentheses, and the subscript is the number of
distinct real roots, as in Tu et al. (2009) and the paper.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import sympy as sp

from quadric_contact import Quadric, characteristic_polynomial
from quadric_contact.paper.proving import ensure

X_, LAM = sp.Symbol("x"), sp.Symbol("lambda")


def _group_order(g: tuple[int, ...]) -> tuple[int, int, tuple[int, ...]]:
    """Largest block first, then larger multiplicity, as the paper writes [2(11)], [(21)1], [(11)11]."""
    return (-max(g), -sum(g), g)


def _rat(v: Any) -> sp.Rational:
    return sp.Rational(v.numerator, v.denominator)


@dataclass(frozen=True)
class SymmetricForm:
    """``fxx x^2 + 2 fx x + f0 + p y^2 + q z^2`` of a quadric symmetric in ``y`` and ``z``."""

    fxx: sp.Rational
    fx: sp.Rational
    f0: sp.Rational
    p: sp.Rational
    q: sp.Rational

    @classmethod
    def of(cls, Q: Quadric) -> SymmetricForm:
        M = Q.matrix
        for i, j in ((0, 1), (0, 2), (1, 2), (1, 3), (2, 3)):
            ensure(M[i][j] == 0, f"{Q.equation()} is not symmetric in y and z (entry {i},{j})")
        return cls(_rat(M[0][0]), _rat(M[0][3]), _rat(M[3][3]), _rat(M[1][1]), _rat(M[2][2]))

    def f(self, x: Any) -> Any:
        return self.fxx * x**2 + 2 * self.fx * x + self.f0


@dataclass
class Component:
    """A connected component of the real intersection (up to the symmetries ``y -> -y``, ``z -> -z``,
    ``copies`` of them)."""

    kind: str  # "curve" or "point"
    copies: int
    lo: sp.Expr
    hi: sp.Expr
    sample: tuple[sp.Expr, sp.Expr, sp.Expr] | None = None


def _sign_at(poly: sp.Poly, r: sp.Expr) -> int:
    if poly.is_zero:
        return 0
    value = poly.eval(r) if not poly.is_ground else poly.LC()
    value = sp.nsimplify(value) if not value.is_Rational else value
    if value == 0 or sp.simplify(value) == 0:
        return 0
    return 1 if value > 0 else -1


def _real_roots(poly: sp.Poly) -> list[sp.Expr]:
    if poly.is_zero or poly.degree() <= 0:
        return []
    return sorted(set(sp.real_roots(poly)), key=lambda r: sp.N(r, 30))


def _between(a: sp.Expr, b: sp.Expr) -> sp.Rational:
    """A rational strictly between the real algebraic numbers a < b."""
    lo, hi = sp.N(a, 40), sp.N(b, 40)
    candidate = sp.nsimplify((lo + hi) / 2, rational=True, tolerance=(hi - lo) / 8)
    ensure(a < candidate < b, "a rational between two roots")
    return candidate


def intersection(E: Quadric, Q: Quadric) -> list[Component]:
    """The connected components of the real intersection of two symmetric quadrics (``E`` an ellipsoid)."""
    e, q = SymmetricForm.of(E), SymmetricForm.of(Q)
    ensure(e.p > 0 and e.q > 0 and e.fxx > 0, "E is an ellipsoid with the paper's sign")
    det = e.p * q.q - e.q * q.p
    components: list[Component] = []
    if det == 0:
        k = q.p / e.p
        ensure(q.q == k * e.q, "proportional (y^2, z^2) parts")
        g = sp.Poly(sp.expand(q.f(X_) - k * e.f(X_)), X_)
        ensure(not g.is_zero, "the quadrics share a whole surface")
        for r in _real_roots(g):
            rhs = -e.f(r)  # p y^2 + q z^2 = rhs
            s = sp.sign(sp.nsimplify(rhs)) if rhs.is_Rational else (1 if rhs > 0 else (-1 if rhs < 0 else 0))
            if s > 0:
                components.append(Component("curve", 1, r, r, (r, sp.sqrt(rhs / e.p), sp.Integer(0))))
            elif s == 0:
                components.append(Component("point", 1, r, r, (r, sp.Integer(0), sp.Integer(0))))
        return components
    # Y(x), Z(x) from  p1 Y + q1 Z = -f1(x),  p2 Y + q2 Z = -f2(x).
    fe, fq = -e.f(X_), -q.f(X_)
    Y = sp.Poly(sp.expand((fe * q.q - e.q * fq) / det), X_)
    Z = sp.Poly(sp.expand((e.p * fq - q.p * fe) / det), X_)
    ensure(not (Y.is_zero and Z.is_zero), "Y and Z do not both vanish identically")
    roots = sorted(set(_real_roots(Y)) | set(_real_roots(Z)), key=lambda r: sp.N(r, 30))

    def ok_at(r: sp.Expr) -> bool:
        return _sign_at(Y, r) >= 0 and _sign_at(Z, r) >= 0

    def ok_between(a: sp.Expr | None, b: sp.Expr | None) -> bool:
        if a is None or b is None:  # unbounded side: impossible for an ellipsoid unless empty
            probe = (b - 1) if a is None and b is not None else (a + 1 if a is not None else sp.Integer(0))
            probe = sp.floor(sp.N(probe)) if a is None else sp.ceiling(sp.N(probe))
        else:
            probe = _between(a, b)
        return ok_at(sp.Rational(probe))

    # Walk the real line: pieces where Y >= 0 and Z >= 0.
    pieces: list[tuple[sp.Expr, sp.Expr]] = []
    start: sp.Expr | None = None
    if not roots:
        ensure(not ok_at(sp.Integer(0)), "an ellipsoid is bounded")
        return []
    ensure(not ok_between(None, roots[0]) and not ok_between(roots[-1], None), "bounded intersection")
    for i, r in enumerate(roots):
        left_ok = ok_between(roots[i - 1], r) if i > 0 else False
        right_ok = ok_between(r, roots[i + 1]) if i + 1 < len(roots) else False
        here = ok_at(r)
        if not here:
            ensure(not left_ok and not right_ok, "feasible set is closed")
            continue
        if not left_ok:
            start = r
        if not right_ok:
            assert start is not None
            pieces.append((start, r))
            start = None
    for lo, hi in pieces:
        if lo == hi:
            k = (_sign_at(Y, lo) > 0) + (_sign_at(Z, lo) > 0)
            point = (
                lo,
                sp.sqrt(Y.eval(lo)) if not Y.is_zero else 0,
                sp.sqrt(Z.eval(lo)) if not Z.is_zero else 0,
            )
            components.append(Component("point", 2**k, lo, hi, point))
        else:

            def positive_on(poly: sp.Poly, lo: sp.Expr = lo, hi: sp.Expr = hi) -> bool:
                if poly.is_zero:
                    return False
                return all(not (lo <= r <= hi) for r in _real_roots(poly)) and _sign_at(poly, lo) > 0

            k = positive_on(Y) + positive_on(Z)
            xs = _between(lo, hi)
            point = (
                xs,
                sp.sqrt(Y.eval(xs)) if not Y.is_zero else 0,
                sp.sqrt(Z.eval(xs)) if not Z.is_zero else 0,
            )
            components.append(Component("curve", 2**k, lo, hi, point))
    return components


# -- tangency ----------------------------------------------------------------------------------


def multiple_roots(E: Quadric, Q: Quadric) -> list[sp.Expr]:
    """The real multiple roots of ``P`` (exact: roots of ``gcd(P, P')``)."""
    P = sp.Poly(characteristic_polynomial(E, Q, normalize=False).as_sympy(), LAM)
    g = sp.gcd(P, P.diff(LAM))
    if g.degree() <= 0:
        return []
    return [r for r in sp.roots(g, LAM) if r.is_real]


def tangent_points(E: Quadric, Q: Quadric) -> tuple[list[tuple[sp.Expr, ...]], list[sp.Expr]]:
    """Real points where ``E`` and ``Q`` are tangent (from kernels of dimension 1 and 2), and the
    roots whose member has rank <= 1 (a double plane: possible curves of tangency)."""
    Em, Qm = E.to_sympy(), Q.to_sympy()
    points: list[tuple[sp.Expr, ...]] = []
    planes: list[sp.Expr] = []
    for lam in multiple_roots(E, Q):
        kernel = (lam * Em + Qm).nullspace(simplify=True)
        if len(kernel) == 1:
            v = kernel[0]
            candidates = [v]
        elif len(kernel) == 2:
            u, v = kernel
            s = sp.Symbol("s")
            quad = sp.expand(((u + s * v).T * Em * (u + s * v))[0, 0])
            candidates = [u + r * v for r in sp.solve(quad, s) if r.is_real]
            if sp.simplify((v.T * Em * v)[0, 0]) == 0:
                candidates.append(v)
        else:
            planes.append(lam)  # a member of rank <= 1: a double plane, tangent along its section of E
            continue
        for v in candidates:
            if sp.simplify(v[3]) == 0:
                continue
            pt = tuple(sp.simplify(v[i] / v[3]) for i in range(3))
            X = sp.Matrix([*pt, 1])
            if sp.simplify((X.T * Em * X)[0, 0]) == 0 and all(t.is_real for t in pt) and pt not in points:
                points.append(pt)
    return points, planes


CONTACT_TYPES = (
    "no contact",
    "1 isolated tangent point",
    "2 isolated tangent points",
    "curve with no tangent points",
    "curve of tangency",
)


def is_tangent_at(E: Quadric, Q: Quadric, point: Sequence[sp.Expr]) -> bool:
    """The gradients of ``E`` and ``Q`` are parallel at ``point`` (exact)."""
    X = sp.Matrix([*point, 1])
    gE = (E.to_sympy() * X)[:3, 0]
    gQ = (Q.to_sympy() * X)[:3, 0]
    return all(sp.simplify(t) == 0 for t in gE.cross(gQ))


def contact_type(E: Quadric, Q: Quadric) -> str:
    """The type of contact of Table 3, or a description of a configuration excluded by smallness."""
    comps = intersection(E, Q)
    points, rank_one = tangent_points(E, Q)
    curves = [c for c in comps if c.kind == "curve"]
    isolated = [c for c in comps if c.kind == "point"]
    n_points = sum(c.copies for c in isolated)
    n_curves = sum(c.copies for c in curves)
    for c in isolated:
        assert c.sample is not None
        ensure(is_tangent_at(E, Q, c.sample), "an isolated point of the intersection is a tangent point")
    if n_curves == 0:
        if n_points == 0:
            return "no contact"
        return f"{n_points} isolated tangent point" + ("s" if n_points > 1 else "")
    if n_curves == 1 and n_points == 0:
        c = curves[0]
        assert c.sample is not None
        if is_tangent_at(E, Q, c.sample):
            ensure(bool(rank_one), "a curve of tangency comes with a double plane in the pencil")
            return "curve of tangency"
        on_curve = [p for p in points if c.lo <= p[0] <= c.hi]
        return "curve with no tangent points" if not on_curve else "curve with a tangent point"
    if n_points == 0:
        return "two curves" if n_curves == 2 else f"{n_curves} curves"
    return "curve and isolated tangent point" if n_curves == 1 else f"{n_curves} curves and {n_points} points"


# -- Segre characteristic ---------------------------------------------------------------------


def segre(E: Quadric, Q: Quadric) -> tuple[tuple[tuple[int, ...], ...], int]:
    """``(groups, real)``: the Jordan block sizes of each eigenvalue (sorted) and the number of
    distinct real eigenvalues of the pencil ``l E + Q``."""
    P = sp.Poly(characteristic_polynomial(E, Q, normalize=False).as_sympy(), LAM)
    A = -E.to_sympy().inv() * Q.to_sympy()
    groups: list[tuple[int, ...]] = []
    real = 0
    factors = sp.factor_list(P)[1]
    for factor, multiplicity in factors:
        poly = sp.Poly(factor, LAM)
        ensure(
            multiplicity == 1 or poly.degree() <= 2, "a multiple root of a quartic is rational or quadratic"
        )
        for r in sp.roots(poly, LAM) if poly.degree() <= 2 else poly.all_roots():
            real += 1 if r.is_real else 0
            if multiplicity == 1:
                groups.append((1,))
                continue
            N = A - r * sp.eye(4)
            ranks = [4]
            power = sp.eye(4)
            while len(ranks) <= multiplicity:
                power = (power * N).applyfunc(sp.simplify)
                ranks.append(power.rank(simplify=True))
            at_least = [ranks[k - 1] - ranks[k] for k in range(1, len(ranks))]
            sizes = []
            for k in range(len(at_least), 0, -1):
                exactly = at_least[k - 1] - (at_least[k] if k < len(at_least) else 0)
                sizes += [k] * exactly
            ensure(sum(sizes) == multiplicity, f"blocks {sizes} of multiplicity {multiplicity}")
            groups.append(tuple(sorted(sizes, reverse=True)))
    return tuple(sorted(groups, key=_group_order)), real


def parse_segre(text: str) -> tuple[tuple[tuple[int, ...], ...], int]:
    """``"[(11)11]_3"`` -> ``(((1, 1), (1,), (1,)), 3)`` (groups sorted like :func:`segre`)."""
    body, _, sub = text.partition("_")
    inner = body.strip()[1:-1]
    groups: list[tuple[int, ...]] = []
    i = 0
    while i < len(inner):
        if inner[i] == "(":
            j = inner.index(")", i)
            groups.append(tuple(sorted((int(ch) for ch in inner[i + 1 : j]), reverse=True)))
            i = j + 1
        else:
            groups.append((int(inner[i]),))
            i += 1
    return tuple(sorted(groups, key=_group_order)), int(sub)


def show_segre(value: tuple[Sequence[Sequence[int]], int]) -> str:
    groups, real = value
    parts = ["".join(map(str, g)) if len(g) == 1 else "(" + "".join(map(str, g)) + ")" for g in groups]
    return "[" + "".join(parts) + f"]_{real}"
