"""The distance of an ellipsoid from a piece cut by planes, certified by weak duality.

A piece of an object's tree is the solid ``K`` of its quadric intersected with the half-spaces
``H_i = {y : n_i . y <= d_i}`` of the planes on its path (:mod:`quadric_contact.scenes.composite`):
``P = K ∩ H_1 ∩ ... ∩ H_m``.  Where ``K`` is convex (the types of
:data:`quadric_contact.theory.distance.CONVEX_SOLIDS`), ``P`` is convex and, for the ellipsoid
``E: (x - c)^T A (x - c) <= r`` apart from it, ``dist(E, P) = min |x - y|`` over ``x`` in ``E``,
``y`` in ``P`` is a convex program, enclosed here by two certificates evaluated exactly
(rationals) or in arb balls, never by trusting floats:

* upper bound: rational points ``x`` in ``E`` and ``y`` in ``P``, their membership checked
  exactly (``E(x) <= 0``, ``Q_K(y) <= 0``, ``n_i . y <= d_i``), give ``dist <= |x - y|``;
* lower bound: for ``mu_i >= 0`` and a vector ``w`` where the support function ``h_K`` is finite,
  put ``u = -w - sum mu_i n_i``.  For ``y`` in ``P``,
  ``u . y >= u . y + sum mu_i (n_i . y - d_i) = -w . y - sum mu_i d_i >= -h_K(w) - sum mu_i d_i``,
  and ``u . x <= h_E(u)`` for ``x`` in ``E``; so ``u . (y - x) >= L`` and, when ``u != 0``::

      dist(E, P) >= L / |u|,   L = -h_K(w) - sum mu_i d_i - h_E(u).

The support functions: ``h_E(u) = u . c + sqrt(r u^T A^-1 u)``.  For ``K = {y^T M y + 2 b . y + q
<= 0}`` with ``M`` positive semi-definite (its solid's sign), let ``P_N`` project onto the kernel
``N`` of ``M``, ``M^+ = (M + P_N)^-1 - P_N`` the pseudo-inverse and ``b_N = P_N b``:

* ``b_N = 0`` (ellipsoid, elliptic cylinder, slab): ``K = {(y - c_K)^T M (y - c_K) <= r_K}`` with
  ``c_K = -M^+ b``, ``r_K = b^T M^+ b - q``; ``h_K(w) = w . c_K + sqrt(r_K w^T M^+ w)`` for
  ``P_N w = 0``, ``+infinity`` otherwise;
* ``b_N != 0`` (elliptic paraboloid, parabolic cylinder, half-space): finite for ``w = 0``
  (``h_K = 0``) and for ``P_N w = 2 lambda b_N`` with ``lambda > 0``, where
  ``h_K(w) = w^T M^+ w / (4 lambda) - w^T M^+ b + lambda (b^T M^+ b - q)`` (the Lagrange
  multiplier of the one constraint; for a half-space ``2 b . y + q <= 0``, ``h_K(lambda 2 b) =
  -lambda q``).

``proofs/distance_to_cut_pieces.py`` re-derives both from the definition and checks the bound.
By Slater's condition (``P`` has an interior point, which is found and checked exactly) the two
bounds meet at the optimum: with the Karush-Kuhn-Tucker point ``x*, y*, beta, mu`` of the program,
``w = beta grad Q_K(y*)`` and ``u = y* - x*``.  That point is found in binary64 by a log-barrier
method, its active set then solved by Newton's method at ``digits + 20`` digits (mpmath); ``w`` is
projected exactly onto the cone where ``h_K`` is finite, and ``x*, y*`` are moved into the solids
until the exact checks pass.  A float search that goes wrong can only widen the enclosure, which
is then refused.

Limits, refused with :class:`~quadric_contact.exact.errors.UndecidedError` and the reason: ``E``
and ``P`` crossing or touching (the lower bound is not positive: the penetration depth into a cut
piece is not computed); a solid that is not convex; a cut piece with no interior point found
(empty, or flat); an enclosure that does not reach the digits asked.  The witnesses of
:class:`~quadric_contact.modes.distance.certified.DistanceEnclosure` are not enclosed (None); the
two exact points of the upper bound are given instead.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import flint
import mpmath
import numpy as np

from quadric_contact.exact.errors import (
    NotAPlaneError,
    QuadricContactError,
    UndecidedError,
    WorkLimitError,
)
from quadric_contact.exact.precision import working_precision
from quadric_contact.exact.rational import fraction_of
from quadric_contact.model.classification import QuadricKind
from quadric_contact.model.quadric import Quadric, as_quadric
from quadric_contact.modes.distance.certified import DistanceEnclosure
from quadric_contact.modes.distances import distance
from quadric_contact.theory.contact_scale import centred_form
from quadric_contact.theory.distance import CONVEX_SOLIDS
from quadric_contact.theory.overlap import solid_of
from quadric_contact.theory.results import Region

__all__ = [
    "MAX_DIGITS",
    "ConvexSolid",
    "CutPieceDistance",
    "HalfSpace",
    "cut_piece_distance",
    "half_space",
    "union_distance",
]

MAX_DIGITS = 300
"""The most significant digits :func:`cut_piece_distance` is asked for: Newton's method runs at
``digits + 20`` digits in mpmath, about a second a pair at this bound."""

Vec = tuple[Fraction, Fraction, Fraction]
Mat = tuple[Vec, Vec, Vec]


def _dot(a: Sequence[Any], b: Sequence[Any]) -> Any:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _mv(M: Sequence[Sequence[Any]], v: Sequence[Any]) -> list[Any]:
    return [_dot(M[i], v) for i in range(3)]


def _fmpq(x: Fraction) -> Any:
    return flint.fmpq(x.numerator, x.denominator)


def _arb(x: Fraction) -> Any:
    return flint.arb(_fmpq(x))


def _frac(x: Any) -> Fraction:
    """An mpmath number (or float) as the exact rational it is."""
    if isinstance(x, float):
        return Fraction(x)
    if not isinstance(x, mpmath.mpf):
        x = mpmath.mpf(x)  # (an mpf is read as it is: mpf(x) would round it to the context)
    sign, man, exp, _ = x._mpf_
    man, exp = (-1) ** sign * int(man), int(exp)
    return Fraction(man * 2**exp) if exp >= 0 else Fraction(man, 2**-exp)


@dataclass(frozen=True)
class HalfSpace:
    """``{y : n . y <= d}`` with rational data (``n != 0``)."""

    n: Vec
    d: Fraction
    name: str = ""

    def value(self, y: Sequence[Fraction]) -> Fraction:
        """``n . y - d`` (non-positive in the half-space)."""
        return Fraction(_dot(self.n, y)) - self.d


def half_space(plane: Any, side: Region | str, name: str = "") -> HalfSpace:
    """The half-space of a plane on one side, as the tree of an object gives it.

    ``R-`` is ``{X^T P X <= 0}`` and ``R+`` is ``{X^T P X >= 0}`` for the plane's matrix as given
    (:class:`~quadric_contact.theory.results.Region`), ``X = (y, 1)``; for a plane
    ``X^T P X = 2 b . y + q``.

    Raises
    ------
    NotAPlaneError
        ``plane`` is not a plane.
    QuadricContactError
        ``side`` is not ``R-`` or ``R+``.

    Examples
    --------
    >>> h = half_space("z - 5", "R-")          # z <= 5
    >>> h.n, h.d
    ((Fraction(0, 1), Fraction(0, 1), Fraction(1, 1)), Fraction(5, 1))
    >>> half_space("z - 5", "R+").n[2]         # z >= 5: -z <= -5
    Fraction(-1, 1)
    """
    p = as_quadric(plane, "plane")
    if p.kind is not QuadricKind.PLANE:
        raise NotAPlaneError(f"a cutting plane must be a plane, got {p.kind.value}", p, kind=p.kind)
    try:
        region = Region(side)
    except ValueError:
        raise QuadricContactError(
            f"the side of a cutting plane must be R- or R+, got {side!r}", side
        ) from None
    if region not in (Region.R_MINUS, Region.R_PLUS):
        raise QuadricContactError(f"the side of a cutting plane must be R- or R+, got {side!r}", side)
    b = [2 * p[i, 3] for i in range(3)]
    q = p[3, 3]
    if region is Region.R_MINUS:
        return HalfSpace((b[0], b[1], b[2]), -q, name or p.equation())
    return HalfSpace((-b[0], -b[1], -b[2]), q, name or p.equation())


def _nullspace(M: Sequence[Sequence[Fraction]]) -> list[list[Fraction]]:
    """A rational basis of the kernel of the symmetric ``M``."""
    den = math.lcm(*(x.denominator for row in M for x in row))
    Z = flint.fmpz_mat(3, 3, [int(x * den) for row in M for x in row])
    basis, nullity = Z.nullspace()
    return [[Fraction(int(basis[i, j])) for i in range(3)] for j in range(int(nullity))]


class ConvexSolid:
    """The convex solid ``{y^T M y + 2 b . y + q <= 0}`` of a quadric (``M`` positive semi-definite),
    with its support function and the exact projection onto the cone where it is finite.

    Examples
    --------
    The half-space ``z <= 1``: ``h(w)`` is finite only for ``w`` along ``+z``.

    >>> K = ConvexSolid(Quadric.from_equation("z - 1"))
    >>> K.project((Fraction(1), Fraction(0), Fraction(3)))
    (Fraction(0, 1), Fraction(0, 1), Fraction(3, 1))
    >>> K.support(K.project((Fraction(1), Fraction(0), Fraction(3))))
    Fraction(3, 1)
    """

    def __init__(self, Q: Quadric) -> None:
        K = solid_of(Q)
        self.quadric = K
        self.kind = K.kind
        if self.kind not in CONVEX_SOLIDS:
            raise UndecidedError(
                f"the solid of {self.kind.value} is not convex: the distance to it as cut by planes is "
                "not computed",
                K,
                kind=self.kind,
            )
        self.M = [[K[i, j] for j in range(3)] for i in range(3)]
        self.b = [K[i, 3] for i in range(3)]
        self.q = K[3, 3]
        basis = _nullspace(self.M)
        PN = [[Fraction(0)] * 3 for _ in range(3)]
        if basis:
            k = len(basis)
            G = flint.fmpq_mat(
                k, k, [_fmpq(Fraction(_dot(basis[i], basis[j]))) for i in range(k) for j in range(k)]
            )
            Gi = G.inv()
            for r in range(3):
                for s in range(3):
                    PN[r][s] = sum(
                        (
                            basis[i][r] * _frac_fmpq(Gi[i, j]) * basis[j][s]
                            for i in range(k)
                            for j in range(k)
                        ),
                        Fraction(0),
                    )
        self.PN = PN
        MP = flint.fmpq_mat(3, 3, [_fmpq(self.M[i][j] + PN[i][j]) for i in range(3) for j in range(3)]).inv()
        self.Mplus = [[_frac_fmpq(MP[i, j]) - PN[i][j] for j in range(3)] for i in range(3)]
        self.bN = _mv(PN, self.b)
        self.bN2 = Fraction(_dot(self.bN, self.bN))
        Mb = _mv(self.Mplus, self.b)
        self.bMb = Fraction(_dot(self.b, Mb))
        self.centre = [-x for x in Mb]  # the centre when bN = 0; a point of the axis otherwise
        self.r = self.bMb - self.q  # r_K when bN = 0

    def value(self, y: Sequence[Any]) -> Any:
        """``y^T M y + 2 b . y + q`` (non-positive in the solid)."""
        return _dot(y, _mv(self.M, y)) + 2 * _dot(self.b, y) + self.q

    def project(self, w: Sequence[Fraction]) -> Vec:
        """A vector where ``h`` is finite, near ``w``: ``w`` without its part in the kernel, plus
        (``b_N != 0``) its part along ``b_N`` when that is positive."""
        wN = _mv(self.PN, w)
        out = [Fraction(w[i]) - wN[i] for i in range(3)]
        if self.bN2:
            t = Fraction(_dot(w, self.bN)) / self.bN2
            out = [out[i] + t * self.bN[i] for i in range(3)] if t > 0 else [Fraction(0)] * 3
        return (out[0], out[1], out[2])

    def support(self, w: Sequence[Fraction]) -> Any:
        """``h_K(w)``: a Fraction (``b_N != 0`` or ``w = 0``) or an arb ball; ``w`` must be where
        ``h`` is finite (:meth:`project`)."""
        if not any(w):
            return Fraction(0)
        if _mv(self.PN, w) != [0, 0, 0] and not self.bN2:
            raise QuadricContactError("the support function is infinite in this direction", tuple(w))
        wMw = Fraction(_dot(w, _mv(self.Mplus, w)))
        if not self.bN2:
            return _arb(Fraction(_dot(w, self.centre))) + _arb(self.r * wMw).sqrt()
        t = Fraction(_dot(w, self.bN)) / self.bN2
        wN = _mv(self.PN, w)
        if t <= 0 or any(wN[i] != t * self.bN[i] for i in range(3)):
            raise QuadricContactError("the support function is infinite in this direction", tuple(w))
        lam = t / 2
        return wMw / (4 * lam) - Fraction(_dot(w, _mv(self.Mplus, self.b))) + lam * (self.bMb - self.q)

    def inner_point(self) -> list[Fraction]:
        """A point strictly inside the solid."""
        if not self.bN2:
            return list(self.centre)
        # along -b_N from the axis point: the form drops by 2 tau |b_N|^2
        g = self.value(self.centre)
        tau = (abs(g) + 1) / (2 * self.bN2)
        return [self.centre[i] - tau * self.bN[i] for i in range(3)]


def _frac_fmpq(x: Any) -> Fraction:
    return Fraction(int(x.p), int(x.q))


@dataclass(frozen=True)
class CutPieceDistance(DistanceEnclosure):
    """The certified distance of an ellipsoid from a cut piece (``method = "cut piece"``).

    Attributes
    ----------
    near_E, near_P : tuple of 3 Fraction, or None
        Exact points of ``E`` and of the cut piece at most the upper bound apart (not the
        nearest points; those are not enclosed, so ``point_E``, ``point_Q`` and ``normal`` are None).
    multipliers : tuple of Fraction
        The ``mu_i >= 0`` of the lower bound, one per half-space.
    """

    near_E: Vec | None = None
    near_P: Vec | None = None
    multipliers: tuple[Fraction, ...] = ()


# -- the numerical search ------------------------------------------------------------------


_COUPLING = np.block([[np.eye(3), -np.eye(3)], [-np.eye(3), np.eye(3)]])
"""The Hessian of ``|x - y|^2 / 2`` in ``(x, y)``."""


class _Program:
    """``min |x - y|^2 / 2`` over ``E x P`` in binary64 (a log-barrier method), normalised forms."""

    def __init__(self, A: Any, c: Any, r: Any, K: ConvexSolid, hs: Sequence[HalfSpace]) -> None:
        self.A = np.array([[float(v) for v in row] for row in A]) / float(r)
        self.c = np.array([float(v) for v in c])
        self.size2 = 1.0 / float(np.linalg.eigvalsh(self.A).min())  # the largest semi-axis, squared
        self.sK = max(1.0, max(abs(float(v)) for row in K.M for v in row), *(abs(float(v)) for v in K.b))
        self.M = np.array([[float(v) for v in row] for row in K.M]) / self.sK
        self.b = np.array([float(v) for v in K.b]) / self.sK
        self.q = float(K.q) / self.sK
        self.N = np.array([[float(v) for v in h.n] for h in hs]).reshape(-1, 3)
        norms = np.linalg.norm(self.N, axis=1) if len(hs) else np.zeros(0)
        self.norms = norms
        self.N = self.N / norms[:, None] if len(hs) else self.N
        self.d = np.array([float(h.d) for h in hs]) / norms if len(hs) else np.zeros(0)

    def cons_y(self, y: Any) -> tuple[Any, Any, list[Any]]:
        """Values, gradients, Hessians of the constraints on ``y`` (K, then the planes)."""
        vals = [y @ self.M @ y + 2 * self.b @ y + self.q]
        grads = [2 * (self.M @ y + self.b)]
        hess = [2 * self.M]
        for i in range(len(self.d)):
            vals.append(self.N[i] @ y - self.d[i])
            grads.append(self.N[i])
            hess.append(np.zeros((3, 3)))
        return np.array(vals), grads, hess

    def interior(self, y_start: Any) -> Any:
        """A point of ``P`` with every normalised constraint at most ``-s`` (``s`` as large as
        a few barrier steps make it), or None."""
        y = np.array(y_start, dtype=float)
        y_s = y.copy()
        vals, _, _ = self.cons_y(y)
        s = -float(vals.max()) - 1.0
        rho = 1e-2 / self.size2  # keeps the point near the start where P is unbounded
        z = np.append(y, s)
        for t in (1.0, 10.0, 100.0):
            for _ in range(60):
                y, s = z[:3], z[3]
                vals, grads, hess = self.cons_y(y)
                slack = -(vals + s)
                cap = 1.0 - s
                if slack.min() <= 0 or cap <= 0:
                    return None
                g = np.zeros(4)
                H = np.zeros((4, 4))
                g[3] = -t + 1.0 / cap
                H[3, 3] = 1.0 / cap**2
                g[:3] += 2 * rho * t * (y - y_s)
                H[:3, :3] += 2 * rho * t * np.eye(3)
                for v, gr, he in zip(slack, grads, hess, strict=True):
                    a = np.append(gr, 1.0)
                    g += a / v
                    H += np.outer(a, a) / v**2
                    H[:3, :3] += he / v
                H[:3, :3] += 1e-9 * np.eye(3)
                try:
                    step = -np.linalg.solve(H, g)
                except np.linalg.LinAlgError:
                    return None
                dec = float(-g @ step)

                def value(zz: Any, t: float = t) -> float | None:
                    vv, _, _ = self.cons_y(zz[:3])
                    sl = -(vv + zz[3])
                    if sl.min() <= 0 or zz[3] >= 1:
                        return None
                    reg = rho * t * float((zz[:3] - y_s) @ (zz[:3] - y_s))
                    return float(-t * zz[3] + reg - np.log(sl).sum() - np.log(1 - zz[3]))

                f0 = value(z)
                assert f0 is not None
                step_size = 1.0
                for _ in range(60):
                    zn = z + step_size * step
                    fn = value(zn)
                    if fn is not None and fn <= f0 - 0.25 * step_size * dec:
                        break
                    step_size /= 2
                else:
                    break
                z = zn
                if dec < 1e-10:
                    break
        return z[:3] if z[3] > 0 else None

    def solve(self, y0: Any) -> tuple[Any, Any, Any] | None:
        """``(x, y, lambda)`` near the optimum, with the barrier's multipliers of the
        normalised constraints (E, K, planes), or None."""
        x = self.c.copy()
        y = np.array(y0, dtype=float)
        scale = 1.0 + float(np.linalg.norm(x - y))
        t = 1.0 / scale**2
        ncons = 2 + len(self.d)
        lam = np.zeros(ncons)
        for _ in range(40):
            for _ in range(80):
                vals, grads, hess = self._all(x, y)
                if vals.max() >= 0:
                    return None
                g = t * np.concatenate([x - y, y - x])
                H = t * _COUPLING
                for v, gr, he in zip(vals, grads, hess, strict=True):
                    g += gr / -v
                    H += np.outer(gr, gr) / v**2 + he / -v
                H += 1e-14 * t * np.eye(6)
                try:
                    step = -np.linalg.solve(H, g)
                except np.linalg.LinAlgError:
                    return None
                dec = float(-g @ step)
                a = min(1.0, 0.95 * self._to_boundary(vals, grads, hess, step))
                f0 = self._barrier(x, y, t)
                if f0 is None:
                    return None
                for _ in range(60):
                    xn, yn = x + a * step[:3], y + a * step[3:]
                    fn = self._barrier(xn, yn, t)
                    if fn is not None and fn <= f0 - 0.25 * a * dec:
                        break
                    a /= 2
                else:
                    break
                x, y = xn, yn
                if dec < 1e-9:
                    break
            vals, _, _ = self._all(x, y)
            lam = 1.0 / (t * -vals)
            if ncons / t < 1e-11 * (self.size2 + float((x - y) @ (x - y))):
                break
            t *= 50.0
        return x, y, lam

    @staticmethod
    def _to_boundary(vals: Any, grads: list[Any], hess: list[Any], step: Any) -> float:
        """The largest ``a`` keeping every (quadratic) constraint negative along ``a step``: the
        least positive root of ``v + a g . s + a^2 s^T H s / 2``."""
        best = math.inf
        for v, gr, he in zip(vals, grads, hess, strict=True):
            slope, curve = float(gr @ step), float(step @ he @ step) / 2
            if curve > 0:
                root = (-slope + math.sqrt(slope * slope - 4 * curve * v)) / (2 * curve)
            elif slope > 0:
                root = -v / slope
            else:
                continue
            best = min(best, root)
        return best

    def _all(self, x: Any, y: Any) -> tuple[Any, list[Any], list[Any]]:
        d = x - self.c
        ve = d @ self.A @ d - 1.0
        ge = np.concatenate([2 * self.A @ d, np.zeros(3)])
        he = np.zeros((6, 6))
        he[:3, :3] = 2 * self.A
        vy, gy, hy = self.cons_y(y)
        grads = [ge]
        hess = [he]
        for gr, h in zip(gy, hy, strict=True):
            grads.append(np.concatenate([np.zeros(3), gr]))
            H6 = np.zeros((6, 6))
            H6[3:, 3:] = h
            hess.append(H6)
        return np.concatenate([[ve], vy]), grads, hess

    def _values(self, x: Any, y: Any) -> Any:
        """The constraint values only (E, K, the planes)."""
        d = x - self.c
        head = [d @ self.A @ d - 1.0, y @ self.M @ y + 2 * self.b @ y + self.q]
        return np.concatenate([head, self.N @ y - self.d]) if len(self.d) else np.array(head)

    def _barrier(self, x: Any, y: Any, t: float) -> float | None:
        vals = self._values(x, y)
        if vals.max() >= 0:
            return None
        return float(t * 0.5 * (x - y) @ (x - y) - np.log(-vals).sum())


def _kkt_newton(
    A: Any, c: Any, r: Any, K: ConvexSolid, hs: Sequence[HalfSpace], start: Any, active: list[int], dps: int
) -> tuple[Any, Any, Any, list[Any]] | None:
    """Newton's method at ``dps`` digits on the Karush-Kuhn-Tucker system of the active set
    (``-1`` for ``K``, ``i`` for the plane ``i``): ``x - y + alpha grad E(x) = 0``,
    ``y - x + beta grad Q_K(y) + sum mu_i n_i = 0``, ``E(x) = 0`` and the active constraints.
    Returns ``(x, y, beta, mu)`` (``mu`` for every plane, 0 off the active set) or None."""
    x0, y0, alpha0, beta0, mu0 = start
    planes = [i for i in active if i >= 0]
    k_on = -1 in active
    with mpmath.workdps(dps):

        def mp(v: Any) -> Any:
            return mpmath.mpf(v.numerator) / v.denominator if isinstance(v, Fraction) else mpmath.mpf(v)

        Am = [[mp(v) for v in row] for row in A]
        cm = [mp(v) for v in c]
        rm = mp(r)
        Mm = [[mp(v) for v in row] for row in K.M]
        bm = [mp(v) for v in K.b]
        qm = mp(K.q)
        ns = [[mp(v) for v in h.n] for h in hs]
        ds = [mp(h.d) for h in hs]
        z = [mp(v) for v in (*x0, *y0, alpha0)]
        if k_on:
            z.append(mp(beta0))
        z += [mp(mu0[i]) for i in planes]
        n_unk = len(z)
        tol = mpmath.mpf(10) ** (-dps + 8)
        for _ in range(100):
            x, y, alpha = z[0:3], z[3:6], z[6]
            beta = z[7] if k_on else mpmath.mpf(0)
            mus = z[(8 if k_on else 7) :]
            dx = [x[i] - cm[i] for i in range(3)]
            ge = [2 * _dot(Am[i], dx) for i in range(3)]
            gk = [2 * (_dot(Mm[i], y) + bm[i]) for i in range(3)]
            F = [x[i] - y[i] + alpha * ge[i] for i in range(3)]
            F += [
                y[i] - x[i] + beta * gk[i] + sum(m * ns[j][i] for m, j in zip(mus, planes, strict=True))
                for i in range(3)
            ]
            F.append(_dot(dx, [_dot(Am[i], dx) for i in range(3)]) - rm)
            if k_on:
                F.append(_dot(y, [_dot(Mm[i], y) for i in range(3)]) + 2 * _dot(bm, y) + qm)
            F += [_dot(ns[j], y) - ds[j] for j in planes]
            # the Jacobian in binary64 (a Newton step with it gains about 15 digits a step; the
            # residual F is evaluated at the full precision)
            J = np.zeros((n_unk, n_unk))
            af, bf = float(alpha), float(beta)
            for i in range(3):
                for j in range(3):
                    J[i, j] = (1 if i == j else 0) + 2 * af * float(Am[i][j])
                    J[i, 3 + j] = -1 if i == j else 0
                    J[3 + i, j] = -1 if i == j else 0
                    J[3 + i, 3 + j] = (1 if i == j else 0) + 2 * bf * float(Mm[i][j])
                J[i, 6] = J[6, i] = float(ge[i])
                col = 7
                if k_on:
                    J[3 + i, 7] = J[7, 3 + i] = float(gk[i])
                    col = 8
                for m, j in enumerate(planes):
                    J[3 + i, col + m] = J[col + m, 3 + i] = float(ns[j][i])
            try:
                with np.errstate(all="ignore"):
                    step_f = np.linalg.solve(J, -np.array([float(f) for f in F]))
            except np.linalg.LinAlgError:
                return None
            if not np.all(np.isfinite(step_f)) or np.linalg.cond(J) > 1e12:
                return None
            step = [mpmath.mpf(float(v)) for v in step_f]
            z = [z[i] + step[i] for i in range(n_unk)]
            size = max(abs(s) for s in step)
            if size <= tol * (1 + max(abs(v) for v in z)):
                break
        else:
            return None
        x, y, alpha = z[0:3], z[3:6], z[6]
        beta = z[7] if k_on else mpmath.mpf(0)
        mus = z[(8 if k_on else 7) :]
        mu_all = [mpmath.mpf(0)] * len(hs)
        for m, j in zip(mus, planes, strict=True):
            mu_all[j] = m
        if alpha <= 0:
            return None
        return x, y, beta, mu_all


# -- the certificate -----------------------------------------------------------------------


def _inside_E(A: Any, c: Any, r: Fraction, x: Sequence[Fraction]) -> bool:
    d = [x[i] - c[i] for i in range(3)]
    return bool(_dot(d, _mv(A, d)) <= r)


def _into(point: list[Fraction], target: list[Fraction], ok: Any, bits: int) -> list[Fraction] | None:
    """``point + eps (target - point)`` for the least ``eps = 2^-k`` (from ``2^-bits``) that ``ok``
    accepts, exactly; None if even ``target`` fails."""
    eps = Fraction(1, 2**bits)
    while True:
        p = [point[i] + eps * (target[i] - point[i]) for i in range(3)]
        if ok(p):
            return p
        if eps == 1:
            return None
        eps = min(eps * 4, Fraction(1))


def _bounds(
    A: Any,
    c: Any,
    r: Fraction,
    Ainv: Any,
    K: ConvexSolid,
    hs: Sequence[HalfSpace],
    y_in: list[Fraction],
    sol: tuple[Any, Any, Any, list[Any]],
    bits: int,
    dps: int,
) -> tuple[Any, Any, Vec, Vec, tuple[Fraction, ...]] | None:
    """``(lo, hi, x, y, mu)``: the two certified bounds (arb) from a near-optimal point."""
    xs, ys, beta, mus = sol
    xq = [_frac(v) for v in xs]
    yq = [_frac(v) for v in ys]

    def in_P(p: list[Fraction]) -> bool:
        return bool(K.value(p) <= 0 and all(h.value(p) <= 0 for h in hs))

    x = _into(xq, list(c), lambda p: _inside_E(A, c, r, p), bits)
    y = _into(yq, y_in, in_P, bits)
    if x is None or y is None:
        return None
    mu = [max(Fraction(0), _frac(m)) for m in mus]
    if beta > 0:
        with mpmath.workdps(dps):
            w_raw = [
                _frac(
                    beta
                    * 2
                    * (
                        _dot([mpmath.mpf(v.numerator) / v.denominator for v in K.M[i]], ys)
                        + mpmath.mpf(K.b[i].numerator) / K.b[i].denominator
                    )
                )
                for i in range(3)
            ]
        w = K.project(w_raw)
    else:
        w = (Fraction(0), Fraction(0), Fraction(0))
    u = [-w[i] - sum((mu[j] * hs[j].n[i] for j in range(len(hs))), Fraction(0)) for i in range(3)]
    u2 = Fraction(_dot(u, u))
    with working_precision(bits):
        diff2 = Fraction(sum(((x[i] - y[i]) ** 2 for i in range(3)), Fraction(0)))
        hi = _arb(diff2).sqrt()
        if u2 == 0:
            lo = flint.arb(0)
        else:
            hK = K.support(w)
            hK = _arb(hK) if isinstance(hK, Fraction) else hK
            hE = _arb(Fraction(_dot(u, c))) + _arb(r * Fraction(_dot(u, _mv(Ainv, u)))).sqrt()
            num = -hK - _arb(sum((mu[j] * hs[j].d for j in range(len(hs))), Fraction(0))) - hE
            lo = num / _arb(u2).sqrt()
    return lo, hi, (x[0], x[1], x[2]), (y[0], y[1], y[2]), tuple(mu)


def _inverse(A: Any) -> list[list[Fraction]]:
    Mi = flint.fmpq_mat(3, 3, [_fmpq(A[i][j]) for i in range(3) for j in range(3)]).inv()
    return [[_frac_fmpq(Mi[i, j]) for j in range(3)] for i in range(3)]


def cut_piece_distance(E: Any, Q: Any, halfspaces: Sequence[Any], *, digits: int = 15) -> DistanceEnclosure:
    """The certified distance of the ellipsoid ``E`` from the solid of ``Q`` cut by half-spaces.

    Parameters
    ----------
    E : Quadric, equation or matrix-like
        A real ellipsoid.
    Q : Quadric, equation or matrix-like
        A quadric whose solid (that of :func:`quadric_contact.distance`) is convex.
    halfspaces : sequence
        Each a :class:`HalfSpace` or a pair ``(plane, side)``, ``side`` one of ``"R-"``,
        ``"R+"`` (:func:`half_space`).  Empty: the whole solid, answered by
        :func:`quadric_contact.distance` (signed: a depth for a crossing pair).
    digits : int
        Significant digits of the enclosure, from 1 to :data:`MAX_DIGITS` (the search runs at
        ``digits + 20`` digits: the bound keeps a pair within seconds).

    Returns
    -------
    CutPieceDistance
        ``distance`` an arb ball holding ``dist(E, P) > 0``, ``method = "cut piece"``; or, with
        no half-space, the answer of :func:`quadric_contact.distance`.

    Raises
    ------
    UndecidedError
        ``E`` and the cut piece cross or touch (the penetration depth into a cut piece is not
        computed; ``.details`` holds the two bounds ``lower <= 0`` and ``upper``, and ``points``,
        exact points of ``E`` and of the piece ``upper`` apart at most), the solid is not convex,
        the cut piece has no interior point, or the enclosure does not reach the digits asked.
    NotAnEllipsoidError, NotAPlaneError, ExcludedQuadricError, QuadricContactError
        Bad input.
    WorkLimitError
        ``digits`` above :data:`MAX_DIGITS`, before any work.

    Examples
    --------
    The unit ball at height 4 above the ball of radius 2 at the origin cut to ``x >= 1``: the
    nearest point of the cut piece is on its rim ``(1, 0, sqrt 3)``, at ``sqrt(1 + (4 - sqrt 3)^2)``
    from the centre, so the distance is that less 1.

    >>> r = cut_piece_distance("x^2 + y^2 + (z - 4)^2 - 1", "x^2 + y^2 + z^2 - 4", [("x - 1", "R+")])
    >>> rim = (1 + (4 - flint.arb(3).sqrt()) ** 2).sqrt() - 1
    >>> r.distance.overlaps(rim), r.method
    (True, 'cut piece')
    >>> lo, hi = r.bounds
    >>> hi - lo <= Fraction(1, 10**14)
    True
    """
    if isinstance(digits, bool) or not isinstance(digits, int) or digits < 1:
        raise QuadricContactError(f"digits must be a positive integer, got {digits!r}", digits)
    if digits > MAX_DIGITS:
        raise WorkLimitError(
            f"the distance to a cut piece is computed to at most {MAX_DIGITS} digits (MAX_DIGITS), "
            f"{digits} were asked",
            digits,
            limit=MAX_DIGITS,
            needed=digits,
        )
    e = as_quadric(E, "E").as_ellipsoid()
    hs = [_as_half_space(h) for h in halfspaces]
    if not hs:
        whole: DistanceEnclosure = distance(e, Q, digits=digits)
        return whole
    K = ConvexSolid(as_quadric(Q, "Q"))
    A, c, r = centred_form(e)
    Ainv = _inverse(A)
    names = ", ".join(h.name or "a plane" for h in hs)
    prog = _Program(A, c, r, K, hs)
    y_start = K.inner_point()
    y_in_f = prog.interior([float(v) for v in y_start])
    y_in = None if y_in_f is None else [Fraction(float(v)) for v in y_in_f]
    if y_in is None or not (K.value(y_in) < 0 and all(h.value(y_in) < 0 for h in hs)):
        raise UndecidedError(
            f"the piece cut by {names} has no interior point found (empty, or flat): its distance is "
            "not computed",
            Q,
        )
    found = prog.solve(y_in_f)
    if found is None:
        raise UndecidedError("the search for the nearest points of the cut piece failed", Q)
    xf, yf, lam = found
    bits = max(64, int(digits * 3.33) + 40)
    dps = digits + 20
    sol = _polish(A, c, r, K, hs, prog, xf, yf, lam, dps)
    result = _bounds(A, c, r, Ainv, K, hs, y_in, sol, bits, dps)
    if result is None:
        raise UndecidedError("no exact points of the solids were found near the optimum", Q)
    lo, hi, x, y, mu = result
    lo_q = fraction_of(lo.mid()) - fraction_of(lo.rad())  # exactly (lower() rounds)
    hi_q = fraction_of(hi.mid()) + fraction_of(hi.rad())
    if lo_q <= 0:
        raise UndecidedError(
            f"E and the piece cut by {names} are not proven apart: they cross or touch, or are too close "
            f"to separate (the duality lower bound is {float(lo_q):.3g}, the upper bound "
            f"{float(hi_q):.3g}, the distance of two exact points of the solids); the penetration depth "
            "into a cut piece is not computed",
            Q,
            lower=lo_q,
            upper=hi_q,
            points=(x, y),
        )
    if hi_q - lo_q > lo_q * Fraction(1, 10**digits):
        raise UndecidedError(
            f"the distance to the piece cut by {names} was enclosed in "
            f"[{float(lo_q):.17g}, {float(hi_q):.17g}], "
            f"not to {digits} digits (a degenerate set of active constraints?)",
            Q,
            lower=lo_q,
            upper=hi_q,
        )
    with working_precision(bits):
        ball = lo.union(hi)  # holds both certified bounds, so the distance
    return CutPieceDistance(ball, None, None, None, bits, "cut piece", x, y, mu)


def _polish(
    A: Any,
    c: Any,
    r: Fraction,
    K: ConvexSolid,
    hs: Sequence[HalfSpace],
    prog: _Program,
    xf: Any,
    yf: Any,
    lam: Any,
    dps: int,
) -> tuple[Any, Any, Any, list[Any]]:
    """The KKT point at ``dps`` digits from the barrier's ``(x, y, lambda)``: the active set read
    off the multipliers, corrected while a multiplier comes out negative or an inactive
    constraint violated; the barrier's point itself when Newton's method fails."""
    # raw multipliers: normalised ones divided by the normalising factors
    beta0 = lam[1] / prog.sK
    mu0 = [lam[2 + i] / prog.norms[i] for i in range(len(hs))]
    vals, _, _ = prog._all(xf, yf)
    active = [j - 2 for j in range(1, len(vals)) if lam[j] > -vals[j]]
    alpha0 = lam[0] / float(r)
    start = (list(xf), list(yf), alpha0, beta0, mu0)
    for _ in range(2 * (len(hs) + 1)):
        sol = _kkt_newton(A, c, r, K, hs, start, active, dps)
        if sol is None:
            break
        xs, ys, beta, mus = sol
        yq = [_frac(v) for v in ys]
        neg = [j for j in active if (beta if j == -1 else mus[j]) < 0]
        scale = 1 + max(abs(float(v)) for v in (*yq, *K.b))
        viol = [
            j
            for j in range(-1, len(hs))
            if j not in active and (float(K.value(yq)) if j == -1 else float(hs[j].value(yq))) > 1e-9 * scale
        ]
        if not neg and not viol:
            return sol
        active = [j for j in active if j not in neg] + viol
    with mpmath.workdps(dps):
        return (
            [mpmath.mpf(v) for v in xf],
            [mpmath.mpf(v) for v in yf],
            mpmath.mpf(max(beta0, 0.0)),
            [mpmath.mpf(max(m, 0.0)) for m in mu0],
        )


def _as_half_space(h: Any) -> HalfSpace:
    if isinstance(h, HalfSpace):
        if not any(h.n):
            raise QuadricContactError("a half-space needs a normal n != 0", h)
        return h
    if not isinstance(h, (tuple, list)) or len(h) != 2:
        raise QuadricContactError(
            f"a cutting half-space is a HalfSpace or a pair (plane, side), got {h!r}", h
        )
    return half_space(h[0], h[1])


def union_distance(E: Any, Q: Any, parts: Sequence[Sequence[Any]], *, digits: int = 15) -> DistanceEnclosure:
    """The distance of ``E`` from a union of cut parts of one solid (a piece in several leaves of
    an object's tree): the least of the parts' distances, enclosed by the least ends.

    ``parts`` holds one sequence of half-spaces per part (as :func:`cut_piece_distance`).  A part
    with no half-space is the whole solid, which holds the others: its answer is the union's.
    Any part refused refuses the union.

    Examples
    --------
    The unit ball at height 4 above the ball of radius 2 cut into ``x <= -1`` and ``x >= 1``
    (mirror images, the same distance):

    >>> one = cut_piece_distance("x^2 + y^2 + (z - 4)^2 - 1", "x^2 + y^2 + z^2 - 4", [("x - 1", "R+")])
    >>> both = union_distance("x^2 + y^2 + (z - 4)^2 - 1", "x^2 + y^2 + z^2 - 4",
    ...                       [[("x + 1", "R-")], [("x - 1", "R+")]])
    >>> both.distance.overlaps(one.distance), both.method
    (True, 'cut piece')
    """
    parts = [list(p) for p in parts]
    if not parts:
        raise QuadricContactError("a union of cut parts needs at least one part", parts)
    if any(not p for p in parts):
        return cut_piece_distance(E, Q, [], digits=digits)
    answers = [cut_piece_distance(E, Q, p, digits=digits) for p in parts]
    if len(answers) == 1:
        return answers[0]
    ends = [a.bounds for a in answers]
    lo = min(b[0] for b in ends)
    hi = min(b[1] for b in ends)
    bits = max(a.bits for a in answers)
    with working_precision(bits):
        ball = _arb(lo).union(_arb(hi))
    best = [a for a, b in zip(answers, ends, strict=True) if b[0] <= hi]
    near = best[0] if len(best) == 1 and isinstance(best[0], CutPieceDistance) else None
    return CutPieceDistance(
        ball,
        None,
        None,
        None,
        bits,
        "cut piece",
        near.near_E if near else None,
        near.near_P if near else None,
        near.multipliers if near else (),
    )
