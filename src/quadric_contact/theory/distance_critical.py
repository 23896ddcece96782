"""The signed distance of any ellipsoid from a curved quadric, certified: every critical point
of the contact system isolated by the Krawczyk operator, so the extremum is provably global.

The contact system
------------------
Write ``E`` as ``(x - c)^T A (x - c) = r`` and ``A = U^T D U`` (rational ``LDL^T``: ``U`` unit
upper triangular, ``D`` diagonal positive).  With ``P = U^-1 diag(sqrt(r / d_i))`` and
``N = U^T diag(sqrt(r d_i))`` the map ``v -> x = c + P v`` takes the unit sphere onto the surface
of ``E``, and ``N v`` is an outward normal of ``E`` at ``x`` (``(N v) . (P w) = r v . w``: the
vectors ``P w``, ``w`` orthogonal to ``v``, are the tangent vectors).  A *contact critical
point* is a unit ``v``, a signed length ``t`` and the points::

    x = c + P v,    nu = N v / |N v|,    y = x + t nu   on the surface of K,

where the surface of ``K`` is normal to ``nu`` at ``y`` with its outward normal ``-nu``::

    F1 = g . P w1 = 0,   F2 = g . P w2 = 0,   F3 = K(y) = 0,   g . nu < 0,

``g = K00 y + k`` (half the gradient of ``K``), ``w1, w2`` spanning the plane orthogonal to
``v``.  ``v`` runs over the six faces of the cube in gnomonic charts ``V = s e_i + a e_j + b
e_k``, ``a, b`` in ``[-1, 1]`` (``v = V / |V|``, ``w1 = e_j - a s e_i``, ``w2 = e_k - b s e_i``):
three equations in the three unknowns ``(a, b, t)``.

Which critical point
--------------------
* ``K`` convex (:data:`~quadric_contact.theory.distance.CONVEX_SOLIDS`): the signed distance is
  ``-min_u (h_E(u) + h_K(-u))`` over unit ``u`` (``h`` the support functions: the distance of
  the origin from the boundary of the Minkowski difference ``E - K``, outside or inside it), and
  the critical points of ``u -> h_E(u) + h_K(-u)`` are exactly the contact critical points with
  ``u = nu``, at the value ``-t``.  So the signed distance is the **largest** ``t``.
* ``K`` not convex, the solids apart (decided exactly, :func:`overlap_exact`): the nearest pair
  ``x, y`` of the two surfaces has ``y - x`` along the outward normal of ``E`` and ``x - y``
  along that of ``K`` (the open segment between them lies outside both solids), so it is a
  contact critical point with ``t >= 0``, and every such point has ``t = |y - x| >= `` the
  distance: the distance is the **least** ``t >= 0``.  A crossing pair is refused (the
  translation distance of a non-convex solid can be reached with two contacts at once, which is
  not a critical point of this system).

Certification
-------------
A float search seeds candidates; each is certified by the Krawczyk operator, which bounds the
range of ``t`` worth searching (a critical point is a pair of surface points: the distance is at
most its ``|t|``).  Then a branch and bound over ``faces x [t_lo, t_hi]`` in binary64 interval
arithmetic, rounded outwards (``nextafter`` after every operation), discards a box where some
``F_i`` or the orientation excludes a zero, or where the Krawczyk image misses the box, and
records a box where the Krawczyk image lies inside it (exactly one zero there).  A box that is
neither, below a width, means a degenerate critical point (a symmetric configuration: a circle
of nearest points): the pair is refused as undecided.  The recorded boxes are contracted by the
Krawczyk operator, in binary64 intervals and then in arb balls at the precision the digits ask.
The extremum of finitely many enclosed numbers is enclosed by the extrema of the ends, ties or
not.

References
----------
R. Krawczyk, Newton-Algorithmen zur Bestimmung von Nullstellen mit Fehlerschranken, Computing
4 (1969) 187-201.  R. E. Moore, A test for existence of solutions to nonlinear systems, SIAM J.
Numer. Anal. 14 (1977) 611-615.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import flint
import numpy as np

from quadric_contact.exact.errors import UndecidedError
from quadric_contact.exact.precision import working_precision
from quadric_contact.model.quadric import Quadric
from quadric_contact.theory.contact_scale import centred_form
from quadric_contact.theory.overlap import overlap_exact
from quadric_contact.theory.results import OverlapCode

__all__ = [
    "FACES",
    "CriticalDistance",
    "critical_boxes",
    "critical_distance",
    "critical_distance_binary64",
    "ldl_frame",
]

FACES: tuple[tuple[int, int, int, int], ...] = tuple(
    (i, (i + 1) % 3, (i + 2) % 3, s) for i in range(3) for s in (1, -1)
)
"""The six gnomonic charts ``(i, j, k, s)``: ``V = s e_i + a e_j + b e_k``."""

MAX_BOXES = 400_000
"""Boxes examined by the branch and bound before the pair is refused as undecided."""

MAX_BITS = 4096

# --------------------------------------------------------------------------------------------
# binary64 intervals, rounded outwards, over numpy arrays


def _dn(x: Any) -> Any:
    return np.nextafter(x, -np.inf)


def _up(x: Any) -> Any:
    return np.nextafter(x, np.inf)


class IV:
    """Intervals ``[lo, hi]`` over numpy arrays (elementwise), every operation rounded
    outwards.  A float operand is taken as the exact point it is."""

    __slots__ = ("hi", "lo")
    __array_ufunc__ = None

    def __init__(self, lo: Any, hi: Any = None) -> None:
        self.lo = np.asarray(lo, dtype=float)
        self.hi = self.lo if hi is None else np.asarray(hi, dtype=float)

    @staticmethod
    def of(x: Any) -> IV:
        return x if isinstance(x, IV) else IV(x)

    def __add__(self, o: Any) -> Any:
        if isinstance(o, Dual):
            return NotImplemented
        o = IV.of(o)
        return IV(_dn(self.lo + o.lo), _up(self.hi + o.hi))

    __radd__ = __add__

    def __neg__(self) -> IV:
        return IV(-self.hi, -self.lo)

    def __sub__(self, o: Any) -> Any:
        if isinstance(o, Dual):
            return NotImplemented
        o = IV.of(o)
        return IV(_dn(self.lo - o.hi), _up(self.hi - o.lo))

    def __rsub__(self, o: Any) -> IV:
        return IV.of(o) - self

    def __mul__(self, o: Any) -> Any:
        if isinstance(o, Dual):
            return NotImplemented
        o = IV.of(o)
        p = (self.lo * o.lo, self.lo * o.hi, self.hi * o.lo, self.hi * o.hi)
        lo = np.fmin(np.fmin(p[0], p[1]), np.fmin(p[2], p[3]))
        hi = np.fmax(np.fmax(p[0], p[1]), np.fmax(p[2], p[3]))
        return IV(_dn(lo), _up(hi))

    __rmul__ = __mul__

    def sq(self) -> IV:
        a, b = self.lo * self.lo, self.hi * self.hi
        hi = np.fmax(a, b)
        lo = np.where((self.lo <= 0) & (self.hi >= 0), 0.0, _dn(np.fmin(a, b)))
        return IV(lo, _up(hi))

    def __truediv__(self, o: Any) -> Any:
        if isinstance(o, Dual):
            return NotImplemented
        o = IV.of(o)
        zero = (o.lo <= 0) & (o.hi >= 0)
        with np.errstate(divide="ignore", invalid="ignore"):
            rec = IV(np.where(zero, -np.inf, _dn(1.0 / o.hi)), np.where(zero, np.inf, _up(1.0 / o.lo)))
        out = self * rec
        return IV(np.where(zero, -np.inf, out.lo), np.where(zero, np.inf, out.hi))

    def __rtruediv__(self, o: Any) -> IV:
        return IV.of(o) / self

    def sqrt(self) -> IV:
        with np.errstate(invalid="ignore"):
            return IV(_dn(np.sqrt(np.maximum(self.lo, 0.0))), _up(np.sqrt(self.hi)))

    @property
    def mid(self) -> Any:
        return 0.5 * self.lo + 0.5 * self.hi

    @property
    def width(self) -> Any:
        return self.hi - self.lo

    def take(self, idx: Any) -> IV:
        return IV(self.lo[idx], self.hi[idx])


_IV_RANGE = (Fraction(1, 2**1000), Fraction(2**1000))
"""The magnitudes a constant of the binary64 search may have: beyond them its intervals would
lose their relative precision (or the rounding loops below would walk ulp by ulp)."""


def _in_iv_range(q: Fraction) -> None:
    if q != 0 and not _IV_RANGE[0] <= abs(q) <= _IV_RANGE[1]:
        raise UndecidedError(
            "the pair's constants lie beyond the range of the binary64 search (magnitudes "
            "2^-1000 .. 2^1000): a matrix scaled far from 1, or an ellipsoid of extreme proportions"
        )


def _iv_of_fraction(q: Fraction) -> IV:
    _in_iv_range(q)
    f = float(q)
    lo = f if Fraction(f) <= q else float(_dn(f))
    hi = f if Fraction(f) >= q else float(_up(f))
    return IV(lo, hi)


def _iv_sqrt_fraction(q: Fraction) -> IV:
    _in_iv_range(q)
    f = math.sqrt(float(q))
    lo, hi = float(_dn(f)), float(_up(f))
    while Fraction(lo) ** 2 > q:
        lo = float(_dn(lo))
    while Fraction(hi) ** 2 < q:
        hi = float(_up(hi))
    return IV(lo, hi)


# --------------------------------------------------------------------------------------------
# forward derivatives in (a, b, t), over any number type


class Dual:
    """A value and its gradient in the three unknowns ``(a, b, t)``."""

    __slots__ = ("d", "v")
    __array_ufunc__ = None

    def __init__(self, v: Any, d: Sequence[Any] | None = None) -> None:
        self.v = v
        self.d = d  # None: a constant

    def _grad(self) -> Sequence[Any] | None:
        return self.d

    def __add__(self, o: Any) -> Dual:
        if isinstance(o, Dual):
            if self.d is None:
                return Dual(self.v + o.v, o.d)
            if o.d is None:
                return Dual(self.v + o.v, self.d)
            return Dual(self.v + o.v, [p + q for p, q in zip(self.d, o.d, strict=True)])
        return Dual(self.v + o, self.d)

    __radd__ = __add__

    def __neg__(self) -> Dual:
        return Dual(-self.v, None if self.d is None else [-p for p in self.d])

    def __sub__(self, o: Any) -> Dual:
        return self + (-o)

    def __rsub__(self, o: Any) -> Dual:
        return (-self) + o

    def __mul__(self, o: Any) -> Dual:
        if isinstance(o, Dual):
            if self.d is None:
                return Dual(self.v * o.v, None if o.d is None else [self.v * q for q in o.d])
            if o.d is None:
                return Dual(self.v * o.v, [p * o.v for p in self.d])
            return Dual(self.v * o.v, [p * o.v + self.v * q for p, q in zip(self.d, o.d, strict=True)])
        return Dual(self.v * o, None if self.d is None else [p * o for p in self.d])

    __rmul__ = __mul__

    def __rtruediv__(self, o: Any) -> Dual:
        return Dual(o, None) / self

    def __truediv__(self, o: Any) -> Dual:
        if isinstance(o, Dual):
            q = self.v / o.v
            if o.d is None:
                return Dual(q, None if self.d is None else [p / o.v for p in self.d])
            sd = self.d if self.d is not None else [0, 0, 0]
            return Dual(q, [(p - q * w) / o.v for p, w in zip(sd, o.d, strict=True)])
        return Dual(self.v / o, None if self.d is None else [p / o for p in self.d])


@dataclass
class _Ops:
    """The number type's square root and square."""

    sqrt: Callable[[Any], Any]
    sq: Callable[[Any], Any]


def _iv_ops() -> _Ops:
    return _Ops(lambda x: x.sqrt(), lambda x: x.sq())


def _float_ops() -> _Ops:
    return _Ops(np.sqrt, lambda x: x * x)


def _arb_ops() -> _Ops:
    return _Ops(lambda x: x.sqrt(), lambda x: x * x)


def _dual_ops(base: _Ops) -> _Ops:
    def sqrt(x: Any) -> Any:
        if not isinstance(x, Dual):
            return base.sqrt(x)
        s = base.sqrt(x.v)
        return Dual(s, None if x.d is None else [p / (2 * s) for p in x.d])

    def sq(x: Any) -> Any:
        if not isinstance(x, Dual):
            return base.sq(x)
        return Dual(base.sq(x.v), None if x.d is None else [2 * x.v * p for p in x.d])

    return _Ops(sqrt, sq)


# --------------------------------------------------------------------------------------------
# the pair's constants


def ldl_frame(
    E: Quadric,
) -> tuple[list[Fraction], Fraction, list[list[Fraction]], list[Fraction], list[list[Fraction]]]:
    """``(c, r, Uinv, d, U)``: ``E: (x - c)^T A (x - c) = r``, ``A = U^T diag(d) U``.

    Examples
    --------
    >>> c, r, Uinv, d, U = ldl_frame(Quadric.ellipsoid(2, 1, 1))
    >>> r, d
    (Fraction(1, 1), [Fraction(1, 4), Fraction(1, 1), Fraction(1, 1)])
    """
    A, c, r = centred_form(E)
    n = 3
    U = [[Fraction(int(i == j)) for j in range(n)] for i in range(n)]
    d = [Fraction(0)] * n
    # A = U^T D U with U unit upper triangular: row by row
    for i in range(n):
        d[i] = A[i][i] - sum((U[k][i] ** 2 * d[k] for k in range(i)), Fraction(0))
        for j in range(i + 1, n):
            U[i][j] = (A[i][j] - sum((U[k][i] * U[k][j] * d[k] for k in range(i)), Fraction(0))) / d[i]
    Uinv = [[Fraction(int(i == j)) for j in range(n)] for i in range(n)]
    for j in range(n):  # back substitution, column by column
        for i in range(j - 1, -1, -1):
            Uinv[i][j] = -sum((U[i][k] * Uinv[k][j] for k in range(i + 1, j + 1)), Fraction(0))
    return c, r, Uinv, d, U


@dataclass
class _Pair:
    """The constants of a pair in one number type: ``c, P, N, K00, k, k33``."""

    c: list[Any]
    P: list[list[Any]]
    N: list[list[Any]]
    K00: list[list[Any]]
    k: list[Any]
    k33: Any


def _constants(E: Quadric, K: Quadric, kind: str) -> _Pair:
    c, r, Uinv, d, U = ldl_frame(E)
    if kind == "iv":
        num: Callable[[Fraction], Any] = _iv_of_fraction
        root: Callable[[Fraction], Any] = _iv_sqrt_fraction
    elif kind == "float":

        def num(q: Fraction) -> Any:
            return float(q)

        def root(q: Fraction) -> Any:
            return math.sqrt(float(q))

    else:

        def num(q: Fraction) -> Any:
            return flint.arb(flint.fmpq(q.numerator, q.denominator))

        def root(q: Fraction) -> Any:
            return num(q).sqrt()

    sr = [root(r / d[i]) for i in range(3)]
    sn = [root(r * d[i]) for i in range(3)]

    def prod(q: Fraction, s: Any) -> Any:
        if q == 0:
            return num(Fraction(0))
        if q == 1:
            return s
        return num(q) * s

    P = [[prod(Uinv[i][j], sr[j]) for j in range(3)] for i in range(3)]
    N = [[prod(U[j][i], sn[j]) for j in range(3)] for i in range(3)]
    K00 = [[num(K[i, j]) for j in range(3)] for i in range(3)]
    return _Pair([num(x) for x in c], P, N, K00, [num(K[i, 3]) for i in range(3)], num(K[3, 3]))


_FI = np.array([f[0] for f in FACES])
_FJ = np.array([f[1] for f in FACES])
_FK = np.array([f[2] for f in FACES])
_FS = np.array([float(f[3]) for f in FACES])


class _Faces:
    """The charts of a stack of boxes (face numbers ``0..5`` into :data:`FACES`): the columns
    ``i, j, k`` of ``P`` and ``N`` gathered per box, for binary64 intervals or floats."""

    def __init__(self, idx: np.ndarray) -> None:
        self.idx = idx
        self._cache: dict[int, tuple[Any, ...]] = {}

    def take(self, keep: np.ndarray) -> _Faces:
        return _Faces(self.idx[keep])

    def columns(self, C: _Pair) -> tuple[Any, ...]:
        key = id(C)
        if key not in self._cache:
            iv = isinstance(C.P[0][0], IV)

            def gather(M: list[list[Any]], cols: np.ndarray) -> list[Any]:
                if iv:
                    lo = np.array([[float(M[r][c].lo) for c in range(3)] for r in range(3)])
                    hi = np.array([[float(M[r][c].hi) for c in range(3)] for r in range(3)])
                    return [IV(lo[r, cols], hi[r, cols]) for r in range(3)]
                v = np.array([[float(M[r][c]) for c in range(3)] for r in range(3)])
                return [v[r, cols] for r in range(3)]

            fi, fj, fk = _FI[self.idx], _FJ[self.idx], _FK[self.idx]
            self._cache[key] = (
                gather(C.P, fi),
                gather(C.P, fj),
                gather(C.P, fk),
                gather(C.N, fi),
                gather(C.N, fj),
                gather(C.N, fk),
                _FS[self.idx],
            )
        return self._cache[key]


def _columns(C: _Pair, face: Any) -> tuple[Any, ...]:
    if isinstance(face, _Faces):
        return face.columns(C)
    i, j, k, s = face
    return (
        [C.P[r][i] for r in range(3)],
        [C.P[r][j] for r in range(3)],
        [C.P[r][k] for r in range(3)],
        [C.N[r][i] for r in range(3)],
        [C.N[r][j] for r in range(3)],
        [C.N[r][k] for r in range(3)],
        s,
    )


def _system(a: Any, b: Any, t: Any, C: _Pair, face: Any, ops: _Ops) -> tuple[Any, ...]:
    """``(F1, F2, F3, orient, x, y, nu)`` at ``(a, b, t)`` in the chart ``face`` (a tuple of
    :data:`FACES`, or :class:`_Faces` for a stack of boxes in several charts)."""
    Pi, Pj, Pk, Ni, Nj, Nk, s = _columns(C, face)
    rho = ops.sqrt(ops.sq(a) + ops.sq(b) + 1)
    x = [C.c[r] + (Pi[r] * s + Pj[r] * a + Pk[r] * b) / rho for r in range(3)]
    m = [Ni[r] * s + Nj[r] * a + Nk[r] * b for r in range(3)]
    mn = ops.sqrt(ops.sq(m[0]) + ops.sq(m[1]) + ops.sq(m[2]))
    nu = [m[r] / mn for r in range(3)]
    y = [x[r] + t * nu[r] for r in range(3)]
    g = [C.K00[r][0] * y[0] + C.K00[r][1] * y[1] + C.K00[r][2] * y[2] + C.k[r] for r in range(3)]
    pw1 = [Pj[r] - a * (Pi[r] * s) for r in range(3)]
    pw2 = [Pk[r] - b * (Pi[r] * s) for r in range(3)]
    F1 = g[0] * pw1[0] + g[1] * pw1[1] + g[2] * pw1[2]
    F2 = g[0] * pw2[0] + g[1] * pw2[1] + g[2] * pw2[2]
    F3 = y[0] * (g[0] + C.k[0]) + y[1] * (g[1] + C.k[1]) + y[2] * (g[2] + C.k[2]) + C.k33
    orient = g[0] * m[0] + g[1] * m[1] + g[2] * m[2]
    return F1, F2, F3, orient, x, y, nu


def _jacobian(a: Any, b: Any, t: Any, C: _Pair, face: Any, base: _Ops, zero: Any) -> list[list[Any]]:
    """The Jacobian of ``(F1, F2, F3)`` over ``(a, b, t)`` (forward derivatives)."""
    one = zero + 1
    da = Dual(a, [one, zero, zero])
    db = Dual(b, [zero, one, zero])
    dt = Dual(t, [zero, zero, one])
    F = _system(da, db, dt, C, face, _dual_ops(base))[:3]
    out = []
    for f in F:
        out.append(list(f.d) if isinstance(f, Dual) and f.d is not None else [zero, zero, zero])
    return out


# --------------------------------------------------------------------------------------------
# Krawczyk in binary64 intervals, vectorised over boxes


def _inv3(M: np.ndarray) -> np.ndarray:
    """Inverses of a stack of 3x3 float matrices by the adjugate (nan where singular)."""
    a = M
    cof = np.empty_like(a)
    for i in range(3):
        for j in range(3):
            r = [x for x in range(3) if x != i]
            s = [x for x in range(3) if x != j]
            cof[..., j, i] = (-1) ** (i + j) * (
                a[..., r[0], s[0]] * a[..., r[1], s[1]] - a[..., r[0], s[1]] * a[..., r[1], s[0]]
            )
    det = a[..., 0, 0] * cof[..., 0, 0] + a[..., 0, 1] * cof[..., 1, 0] + a[..., 0, 2] * cof[..., 2, 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        out = cof / det[..., None, None]
    return np.where(np.isfinite(out), out, np.nan)


def _krawczyk_iv(X: list[IV], m: list[Any], C: _Pair, Cf: _Pair, face: Any) -> list[IV]:
    """The Krawczyk image ``m - Y F(m) + (I - Y F'(X)) (X - m)`` of boxes ``X`` (a list of three
    IV), at the points ``m`` inside them, ``Y`` a float inverse of ``F'(m)``."""
    ivo = _iv_ops()
    zero = IV(np.zeros_like(X[0].lo))
    J = _jacobian(X[0], X[1], X[2], C, face, ivo, zero)
    mi = [IV(v) for v in m]
    Fm = _system(mi[0], mi[1], mi[2], C, face, ivo)[:3]
    Jf = _jacobian(m[0], m[1], m[2], Cf, face, _float_ops(), np.zeros_like(m[0]))
    Jm = np.stack(
        [np.stack([np.broadcast_to(Jf[p][q], m[0].shape) for q in range(3)], -1) for p in range(3)], -2
    )
    Y = _inv3(Jm)
    out = []
    for r in range(3):
        acc = IV(m[r])
        for q in range(3):
            acc = acc - Fm[q] * Y[..., r, q]
        for q in range(3):
            Mrq = IV(np.where(r == q, 1.0, 0.0) + np.zeros_like(m[0]))
            for p in range(3):
                Mrq = Mrq - J[p][q] * Y[..., r, p]
            acc = acc + Mrq * (X[q] - m[q])
        out.append(acc)
    return out


def _inside(Kx: list[IV], X: list[IV]) -> Any:
    ok = np.ones(X[0].lo.shape, dtype=bool)
    for r in range(3):
        ok &= (Kx[r].lo > X[r].lo) & (Kx[r].hi < X[r].hi)
    return ok


def _disjoint(Kx: list[IV], X: list[IV]) -> Any:
    out = np.zeros(X[0].lo.shape, dtype=bool)
    for r in range(3):
        out |= (Kx[r].lo > X[r].hi) | (Kx[r].hi < X[r].lo)
    return out


def _newton_float(m: list[Any], Cf: _Pair, face: Any, steps: int = 4) -> list[Any]:
    with np.errstate(all="ignore"):
        return _newton_steps(m, Cf, face, steps)


def _newton_steps(m: list[Any], Cf: _Pair, face: Any, steps: int) -> list[Any]:
    fo = _float_ops()
    m = [np.array(v, dtype=float) for v in m]
    for _ in range(steps):
        F = _system(m[0], m[1], m[2], Cf, face, fo)[:3]
        J = _jacobian(m[0], m[1], m[2], Cf, face, fo, np.zeros_like(m[0]))
        Jm = np.stack(
            [np.stack([np.broadcast_to(J[p][q], m[0].shape) for q in range(3)], -1) for p in range(3)], -2
        )
        Y = _inv3(Jm)
        step = [sum(Y[..., r, q] * F[q] for q in range(3)) for r in range(3)]
        m = [m[r] - step[r] for r in range(3)]
    return m


@dataclass
class _Found:
    """Certified boxes (each with exactly one zero) in one chart."""

    face: tuple[int, int, int, int]
    box: list[IV]


def _search(C: _Pair, Cf: _Pair, t_lo: float, t_hi: float, scale: float) -> list[_Found]:
    """Branch and bound over the six charts and ``t`` in ``[t_lo, t_hi]``: the certified boxes
    holding every zero with the right orientation."""
    ivo = _iv_ops()
    found: list[_Found] = []
    examined = 0
    tw = max(t_hi - t_lo, 1e-300)
    n0 = 4
    g = np.linspace(-1.0, 1.0, n0 + 1)
    A, B = np.meshgrid(g[:-1], g[:-1], indexing="ij")
    nf = len(FACES)
    idx = np.repeat(np.arange(nf), n0 * n0)
    lo = [np.tile(A.ravel(), nf), np.tile(B.ravel(), nf), np.full(nf * n0 * n0, t_lo)]
    hi = [lo[0] + 2.0 / n0, lo[1] + 2.0 / n0, np.full(nf * n0 * n0, t_hi)]
    while lo[0].size:
        examined += lo[0].size
        if examined > MAX_BOXES:
            raise UndecidedError(
                "the critical points of the contact system were not isolated within the box "
                f"budget ({MAX_BOXES}): a degenerate (symmetric) configuration"
            )
        faces = _Faces(idx)
        X = [IV(lo[r], hi[r]) for r in range(3)]
        F1, F2, F3, orient, *_ = _system(X[0], X[1], X[2], C, faces, ivo)
        keep = np.ones(lo[0].shape, dtype=bool)
        for f in (F1, F2, F3):
            keep &= ~((f.lo > 0) | (f.hi < 0))
        keep &= ~(orient.lo > 0)
        lo = [v[keep] for v in lo]
        hi = [v[keep] for v in hi]
        idx = idx[keep]
        if not lo[0].size:
            break
        faces = _Faces(idx)
        # Krawczyk on the box inflated by 10% about its centre (it then holds the box)
        ctr = [0.5 * (lo[r] + hi[r]) for r in range(3)]
        half = [0.55 * (hi[r] - lo[r]) for r in range(3)]
        Xi = [IV(_dn(ctr[r] - half[r]), _up(ctr[r] + half[r])) for r in range(3)]
        m = _newton_float(ctr, Cf, faces, steps=3)
        inbox = np.ones(lo[0].shape, dtype=bool)
        for r in range(3):
            inbox &= np.isfinite(m[r]) & (m[r] > Xi[r].lo) & (m[r] < Xi[r].hi)
        m = [np.where(inbox, m[r], ctr[r]) for r in range(3)]
        Kx = _krawczyk_iv(Xi, m, C, Cf, faces)
        ok = _inside(Kx, Xi)
        for n in np.flatnonzero(ok):
            found.append(_Found(FACES[int(idx[n])], [Xi[r].take(np.array([n])) for r in range(3)]))
        gone = ok | _disjoint(Kx, Xi)
        rest = ~gone
        lo = [v[rest] for v in lo]
        hi = [v[rest] for v in hi]
        idx = idx[rest]
        if not lo[0].size:
            break
        # narrow to the Krawczyk image (the zeros of the box lie in it), then bisect
        Kr = [Kx[r].take(rest) for r in range(3)]
        for r in range(3):
            nl = np.where(np.isfinite(Kr[r].lo), np.maximum(lo[r], Kr[r].lo), lo[r])
            nh = np.where(np.isfinite(Kr[r].hi), np.minimum(hi[r], Kr[r].hi), hi[r])
            lo[r], hi[r] = nl, nh
        w = np.stack([hi[0] - lo[0], hi[1] - lo[1], (hi[2] - lo[2]) / tw * 2.0])
        if np.any(w.max(axis=0) < 1e-11):
            raise UndecidedError(
                "a critical point of the contact system is not isolated (a degenerate, "
                "symmetric configuration)"
            )
        axis = np.argmax(w, axis=0)
        mid = [0.5 * (lo[r] + hi[r]) for r in range(3)]
        lo2 = [np.concatenate([lo[r], np.where(axis == r, mid[r], lo[r])]) for r in range(3)]
        hi2 = [np.concatenate([np.where(axis == r, mid[r], hi[r]), hi[r]]) for r in range(3)]
        lo, hi = lo2, hi2
        idx = np.concatenate([idx, idx])
    del scale
    return found


def _merge(found: list[_Found]) -> list[_Found]:
    """One entry per chart (the boxes of a chart stacked)."""
    out = []
    for face in FACES:
        mine = [f for f in found if f.face == face]
        if mine:
            out.append(
                _Found(
                    face,
                    [
                        IV(
                            np.concatenate([f.box[r].lo for f in mine]),
                            np.concatenate([f.box[r].hi for f in mine]),
                        )
                        for r in range(3)
                    ],
                )
            )
    return out


def _contract_iv(f: _Found, C: _Pair, Cf: _Pair, rounds: int = 6) -> _Found:
    X = f.box
    for _ in range(rounds):
        if float(np.max(X[2].width / (1 + np.abs(X[2].mid)))) < 1e-14:
            break
        m = [X[r].mid for r in range(3)]
        Kx = _krawczyk_iv(X, m, C, Cf, f.face)
        X = [
            IV(
                np.maximum(X[r].lo, np.where(np.isfinite(Kx[r].lo), Kx[r].lo, X[r].lo)),
                np.minimum(X[r].hi, np.where(np.isfinite(Kx[r].hi), Kx[r].hi, X[r].hi)),
            )
            for r in range(3)
        ]
    return _Found(f.face, X)


# --------------------------------------------------------------------------------------------
# arb refinement


def _arb_of(lo: float, hi: float) -> Any:
    return flint.arb(lo).union(flint.arb(hi))


def _krawczyk_arb(X: list[Any], C: _Pair, Cf: _Pair, face: tuple[int, int, int, int]) -> list[Any] | None:
    """One contraction ``K(X) ∩ X`` in arb of a box known to hold exactly one zero; None when
    the float Jacobian is singular."""
    ao = _arb_ops()
    m = [x.mid() for x in X]
    J = _jacobian(X[0], X[1], X[2], C, face, ao, flint.arb(0))
    Fm = _system(m[0], m[1], m[2], C, face, ao)[:3]
    mf = [np.array(float(v)) for v in m]
    Jf = _jacobian(mf[0], mf[1], mf[2], Cf, face, _float_ops(), np.zeros(()))
    Y = _inv3(np.array([[float(Jf[p][q]) for q in range(3)] for p in range(3)]))
    if not np.all(np.isfinite(Y)):
        return None
    out = []
    for r in range(3):
        acc = m[r]
        for q in range(3):
            acc = acc - Fm[q] * float(Y[r, q])
        for q in range(3):
            Mrq = flint.arb(int(r == q))
            for p in range(3):
                Mrq = Mrq - J[p][q] * float(Y[r, p])
            acc = acc + Mrq * (X[q] - m[q])
        out.append(acc)
    # every zero in X lies in K(X): the intersection keeps the box's one zero
    return [out[r].intersection(X[r]) for r in range(3)]


@dataclass(frozen=True)
class CriticalDistance:
    """The certified extremum: ``distance`` (arb) and the witnesses (tuples of arb, or None when
    the extremal critical point is not singled out), at ``bits``."""

    distance: Any
    point_E: tuple[Any, Any, Any] | None
    point_Q: tuple[Any, Any, Any] | None
    normal: tuple[Any, Any, Any] | None
    bits: int
    critical_points: int


def _seeds(Cf: _Pair, C: _Pair) -> list[_Found]:
    """Float candidates from a grid of directions, polished by Newton and certified."""
    with np.errstate(all="ignore"):
        return _seed_points(Cf, C)


def _seed_points(Cf: _Pair, C: _Pair) -> list[_Found]:
    out = []
    fo = _float_ops()
    g = np.linspace(-1, 1, 9)
    A, B = np.meshgrid(g, g, indexing="ij")
    a, b = A.ravel(), B.ravel()
    for face in FACES:
        # t from K(x + t nu) = 0 along each grid normal: both roots
        _, _, _, _, x, _, nu = _system(a, b, np.zeros_like(a), Cf, face, fo)
        K00, k, k33 = Cf.K00, Cf.k, Cf.k33
        Kx = [sum(K00[r][q] * x[q] for q in range(3)) + k[r] for r in range(3)]
        qa = sum(nu[r] * sum(K00[r][q] * nu[q] for q in range(3)) for r in range(3))
        qb = 2 * sum(nu[r] * Kx[r] for r in range(3))
        qc = sum(x[r] * (Kx[r] + k[r]) for r in range(3)) + k33
        with np.errstate(all="ignore"):
            disc = np.sqrt(np.maximum(qb * qb - 4 * qa * qc, 0.0))
            lin = np.abs(qa) < 1e-14 * (np.abs(qb) + 1e-300)
            t1 = np.where(lin, -qc / qb, (-qb - disc) / (2 * qa))
            t2 = np.where(lin, -qc / qb, (-qb + disc) / (2 * qa))
        for t in (t1, t2):
            ok = np.isfinite(t)
            if not ok.any():
                continue
            m = _newton_float([a[ok], b[ok], t[ok]], Cf, face, steps=8)
            F = _system(m[0], m[1], m[2], Cf, face, fo)
            good = np.isfinite(m[0]) & np.isfinite(m[1]) & np.isfinite(m[2])
            good &= (np.abs(m[0]) <= 1.5) & (np.abs(m[1]) <= 1.5)
            for f in F[:3]:
                good &= np.abs(f) < 1e-6 * (1 + np.abs(m[2]))
            if not good.any():
                continue
            pts = np.unique(np.round(np.stack([m[r][good] for r in range(3)], -1), 9), axis=0)
            mm = [pts[:, r] for r in range(3)]
            d = [np.maximum(1e-9 * (1 + np.abs(mm[r])), 1e-12) for r in range(3)]
            Xi = [IV(_dn(mm[r] - d[r]), _up(mm[r] + d[r])) for r in range(3)]
            Kx = _krawczyk_iv(Xi, mm, C, Cf, face)
            okk = _inside(Kx, Xi)
            if okk.any():
                out.append(_Found(face, [Xi[r].take(okk) for r in range(3)]))
    return out


def _size2(E: Quadric) -> Fraction:
    """The squared largest semi-axis of ``E``, within a factor 3 (``r / min d_i`` bounds it
    within the conditioning of ``U``; only a scale is needed)."""
    _, r, _, d, _ = ldl_frame(E)
    return r / min(d)


def _eval_iv(f: _Found, C: _Pair) -> tuple[Any, ...]:
    return _system(f.box[0], f.box[1], f.box[2], C, f.face, _iv_ops())


def critical_boxes(
    E: Quadric, K: Quadric, *, convex: bool
) -> list[tuple[tuple[int, int, int, int], list[tuple[float, float]]]]:
    """Every contact critical point that can be the extremum, each in a chart and a binary64
    box ``[(a_lo, a_hi), (b_lo, b_hi), (t_lo, t_hi)]`` holding it alone."""
    with np.errstate(all="ignore"):  # unbounded intervals are expected; every test handles them
        return _critical_boxes(E, K, convex)


def _critical_boxes(
    E: Quadric, K: Quadric, convex: bool
) -> list[tuple[tuple[int, int, int, int], list[tuple[float, float]]]]:
    C = _constants(E, K, "iv")
    Cf = _constants(E, K, "float")
    seeds = _seeds(Cf, C)
    if not seeds:
        raise UndecidedError("no critical point of the contact system was found to start from", E, other=K)
    seeds = [_contract_iv(s, C, Cf, rounds=3) for s in _merge(seeds)]
    t_abs_hi = np.inf
    t_best_lo = -np.inf
    for s in seeds:
        _, _, _, orient, _, _, _ = _eval_iv(s, C)
        t = s.box[2]
        t_abs_hi = min(t_abs_hi, float(np.max(np.maximum(np.abs(t.lo), np.abs(t.hi)))))
        oriented = orient.hi < 0
        if convex and oriented.any():
            t_best_lo = max(t_best_lo, float(np.max(t.lo[oriented])))
    if convex:
        if not np.isfinite(t_best_lo):
            raise UndecidedError("no oriented critical point was found to start from", E, other=K)
        lo_t, hi_t = t_best_lo, float(_up(t_abs_hi))
        # the exact overlap decision halves the range: crossing solids have every critical
        # t < 0 (the origin is inside the Minkowski difference), separated ones the largest > 0
        code = overlap_exact(E, K).code
        if code is OverlapCode.OVERLAPPING:
            hi_t = min(hi_t, 0.0)
        elif code is OverlapCode.SEPARATE:
            lo_t = max(lo_t, 0.0)
    else:
        lo_t, hi_t = -1e-9 * (1 + t_abs_hi), float(_up(t_abs_hi))
    # a margin: a zero on the edge of the searched slab could not be certified
    size = max(math.sqrt(float(x)) for x in (_size2(E),))
    margin = 0.02 * (abs(lo_t) + abs(hi_t) + size)
    lo_t = float(_dn(lo_t - margin))
    hi_t = float(_up(hi_t + margin))
    found = _search(C, Cf, lo_t, hi_t, 1.0)
    found = [_contract_iv(f, C, Cf) for f in _merge(found)]
    # one entry per certified box: (face, box), with its t interval
    boxes: list[tuple[tuple[int, int, int, int], list[tuple[float, float]]]] = []
    for f in found:
        for n in range(f.box[0].lo.size):
            boxes.append((f.face, [(float(f.box[r].lo[n]), float(f.box[r].hi[n])) for r in range(3)]))
    if not boxes:
        raise UndecidedError("no contact critical point in the searched range", E, other=K)
    return boxes


def critical_distance(E: Quadric, K: Quadric, *, convex: bool, digits: int = 15) -> CriticalDistance:
    """The signed distance of the ellipsoid ``E`` from the solid ``K`` as the extremal contact
    critical point: the largest ``t`` when ``K`` is convex, the least ``t >= 0`` when it is not
    (the caller has decided that the solids are apart), certified to ``digits`` digits.

    Examples
    --------
    >>> E = Quadric.ellipsoid(2, 1, 1, center=(6, 0, 0))
    >>> r = critical_distance(E, Quadric.ellipsoid(1, 2, 2), convex=True, digits=20)
    >>> r.distance.str(20, radius=False)
    '3.0000000000000000000'
    """
    return _extremum(critical_boxes(E, K, convex=convex), E, K, convex, digits)


def critical_distance_binary64(E: Quadric, K: Quadric, *, convex: bool) -> tuple[float, float]:
    """``(lo, hi)``: the same extremum enclosed in binary64 intervals rounded outwards (no arb
    stage): a rigorous enclosure, typically 1e-15 relative wide.

    Examples
    --------
    >>> E = Quadric.ellipsoid(2, 1, 1, center=(6, 0, 0))
    >>> lo, hi = critical_distance_binary64(E, Quadric.ellipsoid(1, 2, 2), convex=True)
    >>> lo <= 3 <= hi, hi - lo < 1e-13
    (True, True)
    """
    C = _constants(E, K, "iv")
    los, his = [], []
    for face, box in critical_boxes(E, K, convex=convex):
        X = [IV(lo, hi) for lo, hi in box]
        orient = _system(X[0], X[1], X[2], C, face, _iv_ops())[3]
        if float(orient.lo) > 0 or (not convex and box[2][1] < 0):
            continue
        los.append(box[2][0])
        his.append(box[2][1])
    if not los:
        raise UndecidedError("no contact critical point of the needed kind", E, other=K)
    if convex:
        return max(los), max(his)
    his_sure = [h for lo, h in zip(los, his, strict=True) if lo >= 0]
    return max(0.0, min(los)), min(his_sure) if his_sure else min(his)


def _extremum(
    boxes: list[tuple[tuple[int, int, int, int], list[tuple[float, float]]]],
    E: Quadric,
    K: Quadric,
    convex: bool,
    digits: int,
) -> CriticalDistance:
    Cf = _constants(E, K, "float")
    bits = 64
    while True:
        with working_precision(bits + 20):
            Ca = _constants(E, K, "arb")
            sols = []
            for face, box in boxes:
                X = [_arb_of(lo, hi) for lo, hi in box]
                for _ in range(4):
                    Y = _krawczyk_arb(X, Ca, Cf, face)
                    if Y is None:
                        break
                    X = Y
                    if X[2].rad() <= abs(X[2].mid()) * flint.arb(2) ** (-bits - 8) or X[2].rad() < flint.arb(
                        2
                    ) ** (-2 * bits):
                        break
                F1, F2, F3, orient, x, y, nu = _system(X[0], X[1], X[2], Ca, face, _arb_ops())
                if orient > 0:
                    continue  # the wrong orientation: not a contact critical point
                if not convex and X[2] < 0:
                    continue
                sols.append((X[2], x, y, nu))
            if not sols:
                raise UndecidedError("no contact critical point of the needed kind", E, other=K)
            if convex:
                lo = max((s[0].lower() for s in sols), key=lambda v: v)
                hi = max((s[0].upper() for s in sols), key=lambda v: v)
                best = max(sols, key=lambda s: s[0].mid())
            else:
                lo = min((s[0].lower() for s in sols), key=lambda v: v)
                lo = lo if lo > 0 else flint.arb(0)
                hi = min((s[0].upper() for s in sols if s[0] >= 0), default=None, key=lambda v: v)
                if hi is None:
                    hi = min((s[0].upper() for s in sols), key=lambda v: v)
                best = min(sols, key=lambda s: s[0].mid())
            dist = lo.union(hi)
            # the witnesses: the extremal point, with every other critical point whose t may tie
            ties = [s for s in sols if s[0].overlaps(dist)]
            witnesses: tuple[Any, Any, Any] = (None, None, None)
            if all(all(s[2][r].overlaps(best[2][r]) for r in range(3)) for s in ties):
                pe = tuple(best[1][r] for r in range(3))
                pq = tuple(best[2][r] for r in range(3))
                for s in ties:
                    pe = tuple(pe[r].union(s[1][r]) for r in range(3))
                    pq = tuple(pq[r].union(s[2][r]) for r in range(3))
                normal = tuple(-best[3][r] for r in range(3))
                for s in ties:
                    normal = tuple(normal[r].union(-s[3][r]) for r in range(3))
                witnesses = (pe, pq, normal)
        if _good(dist, digits) or bits >= MAX_BITS:
            return CriticalDistance(dist, *witnesses, bits, len(sols))
        bits *= 2


def _good(x: Any, digits: int) -> bool:
    if not x.is_finite():
        return False
    rad, scale = x.rad(), abs(x.mid())
    return bool(rad <= scale * flint.arb(10) ** (-digits) or scale + rad <= flint.arb(10) ** (-2 * digits))
