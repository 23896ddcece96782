"""The penetration depth of an ellipsoid into a solid that is not convex, bracketed between an
inscribed ellipsoid and an exactly checked free translation.

For the solid ``K = {X^T Q X <= 0}`` of a hyperboloid, a hyperbolic paraboloid or cylinder, and
an ellipsoid ``E`` whose interior meets it, the depth is
``depth = min { |v| : E + v and K have disjoint interiors }`` (:mod:`quadric_contact.theory.distance`).
It is not the value of one critical point (``proofs/depth_into_non_convex_solids.py``), and it
is enclosed by two certificates:

* lower bound: for linear forms ``l_i`` and ``s_i >= 0``, ``C = {X^T Q X + sum s_i (l_i . X)^2
  <= 0}`` lies in ``K`` (the added terms are never negative), so every translation that frees
  ``E`` from ``K`` frees it from ``C``: ``depth(E, C) <= depth(E, K)``.  The ``l_i`` vanish at a
  point ``y`` of the surface near the contact, along the eigenvectors of ``Q``'s quadratic part
  whose eigenvalues are not positive, and the ``s_i`` make ``C`` an ellipsoid tangent to ``K``
  at ``y``; its depth is certified by the routes of two crossing ellipsoids, which the caller
  hands in (:mod:`quadric_contact.modes.distance.certified`);
* upper bound: ``C``'s nearest free translation ``v``, lengthened by ``10^-(digits + 1)`` and
  made rational, is checked free of ``K`` exactly
  (:func:`~quadric_contact.theory.overlap.overlap_exact` on ``E + v``: apart or touching), so
  ``depth(E, K) <= |v|``.

Where ``E``'s nearest free position touches ``K`` at one point where ``C`` touches it too, the two
bounds meet; the point ``y`` is moved to ``C``'s contact point and ``C`` rebuilt a few times, with
a few widths of ``C``, until they do.  Where they do not meet to the digits asked (a nearest free
position touching ``K`` at two points, as a ball in the waist of a hyperboloid, or ``C`` too
narrow for every width tried), the pair is left undecided, never given a wider answer.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import flint
import numpy as np

from quadric_contact.exact.errors import QuadricContactError, UndecidedError
from quadric_contact.exact.precision import working_precision
from quadric_contact.exact.rational import fraction_of
from quadric_contact.model.classification import QuadricKind
from quadric_contact.model.quadric import Quadric
from quadric_contact.modes.distance.depth_kernel import depth_and_minimiser
from quadric_contact.theory.overlap import overlap_exact
from quadric_contact.theory.results import OverlapCode

__all__ = ["InscribedDepth", "inscribed_ellipsoid", "nonconvex_depth"]

WIDTHS = (Fraction(1, 8), Fraction(1), Fraction(1, 64))
"""The widths ``kappa`` of the inscribed ellipsoids tried: ``s_i = |lambda_i| + kappa lambda_max``
(``lambda`` the eigenvalues of ``Q``'s quadratic part), a smaller ``kappa`` a longer ``C``."""
MOVES = 60
"""At most how many times the point of tangency moves to the inscribed ellipsoid's contact point
(binary64, a depth kernel call each: about 30 microseconds)."""


def inscribed_ellipsoid(K: Quadric, y: Any, width: Fraction) -> Quadric | None:
    """``C = {X^T Q X + sum s_i (l_i . (x - y))^2 <= 0}``, inside the solid of ``K`` (inside
    negative) for any ``y``; ``l_i`` the (float, made rational) unit eigenvectors of the quadratic
    part ``A`` of ``K`` with eigenvalues ``lambda_i <= 0``, ``s_i = |lambda_i| + width lambda_max``.
    None where ``C`` is no real ellipsoid.

    Examples
    --------
    The tube ``x^2 + y^2 - z^2 <= 1`` (inside a hyperboloid of one sheet), tangent at ``(1, 0, 0)``:

    >>> C = inscribed_ellipsoid(Quadric.from_equation("x^2 + y^2 - z^2 - 1"), (1, 0, 0), Fraction(1))
    >>> C.kind.value, C.equation()
    ('ellipsoid', 'x**2 + y**2 + z**2 - 1')
    """
    try:
        A = np.array([[float(K[i, j]) for j in range(3)] for i in range(3)])
        yq = [Fraction(v) if isinstance(v, (int, Fraction)) else Fraction(float(v)) for v in y]
    except (OverflowError, ValueError):
        return None  # beyond binary64 (the eigenvectors are binary64), or not finite
    if not np.all(np.isfinite(A)):
        return None
    vals, vecs = np.linalg.eigh(A)
    top = float(np.max(np.abs(vals)))
    if not top > 0:
        return None
    M = [[K[i, j] for j in range(4)] for i in range(4)]
    added = False
    for lam, vec in zip(vals, vecs.T, strict=True):
        if lam > 1e-12 * top:
            continue
        l3 = [Fraction(float(v)) for v in vec]
        ell = [*l3, -sum(l3[i] * yq[i] for i in range(3))]  # l . X, zero at y
        s = Fraction(abs(float(lam))) + width * Fraction(top)
        for i in range(4):
            for j in range(4):
                M[i][j] += s * ell[i] * ell[j]
        added = True
    if not added:
        return None
    try:
        C = Quadric.from_matrix(M)
    except QuadricContactError:
        return None
    if C.kind is not QuadricKind.ELLIPSOID:
        return None
    centre = C.center()
    if centre is None or not C.value_at(centre) < 0:
        return None
    return C


def _nearest_surface_point(Kf: np.ndarray, c: np.ndarray) -> np.ndarray | None:
    """A float point of the surface of ``K`` nearest ``c`` (the least of the critical points of
    ``|p - c|^2`` on it that a scan of the multiplier finds; ``Kf`` its binary64 matrix): the seed
    of the point of tangency."""
    A, b, q = Kf[:3, :3], Kf[:3, 3], float(Kf[3, 3])
    vals, V = np.linalg.eigh(A)
    cc, bb = V.T @ c, V.T @ b

    def point(mu: float) -> np.ndarray:
        # the stationary point of |p - c|^2 + mu Q(p): (I + mu A) p = c - mu b
        return (cc - mu * bb) / (1 + mu * vals)

    def f(mu: float) -> float:
        p = point(mu)
        return float(p @ (vals * p) + 2 * bb @ p + q)

    poles = sorted({-1 / v for v in vals if abs(v) > 1e-300})
    grid = np.concatenate([-np.logspace(6, -8, 400), [0.0], np.logspace(-8, 6, 400)])
    best, best_d = None, math.inf
    prev: tuple[float, float] | None = None  # the last multiplier scanned and f there
    for mu in grid:
        if any(abs(mu - p) < 1e-9 * (1 + abs(p)) for p in poles):
            prev = None
            continue
        fm = f(mu)
        if prev is not None and fm * prev[1] < 0 and not any(prev[0] < p < mu for p in poles):
            a, z = prev[0], float(mu)
            for _ in range(100):
                m = 0.5 * (a + z)
                if (f(m) < 0) == (f(a) < 0):
                    a = m
                else:
                    z = m
            p = V @ point(0.5 * (a + z))
            d = float(np.linalg.norm(p - c))
            if d < best_d:
                best, best_d = p, d
        prev = (float(mu), fm)
    return best


@dataclass(frozen=True)
class InscribedDepth:
    """The enclosure of ``-depth`` (an arb ball), the inscribed ellipsoid's own answer (its
    witnesses), the ellipsoid, and the free translation checked exactly."""

    distance: Any
    inner: Any
    inscribed: Quadric
    free: tuple[Fraction, Fraction, Fraction]
    bits: int


def nonconvex_depth(
    E: Quadric, K: Quadric, digits: int, ellipsoids: Callable[[Quadric, Quadric, int], Any]
) -> InscribedDepth | None:
    """The signed distance ``-depth`` of the ellipsoid ``E`` crossing the solid of ``K``, which
    is not convex (both inside negative), enclosed to ``digits`` digits between an inscribed
    ellipsoid's depth and an exactly checked free translation (module docstring); None where
    the two bounds do not meet.  ``ellipsoids(E, C, digits)`` is the certified signed distance
    of two ellipsoids (an object with arb ``distance``, ``normal``, ``point_Q``; raising
    :class:`~quadric_contact.exact.errors.UndecidedError` where it does not decide)."""
    centre = E.center()
    if centre is None:
        return None
    try:
        Ef, Kf = E.to_numpy(), K.to_numpy()
        cf = np.array([float(x) for x in centre])
    except OverflowError:
        return None  # entries beyond binary64: no search in binary64
    if not (np.all(np.isfinite(Ef)) and np.all(np.isfinite(Kf)) and np.all(np.isfinite(cf))):
        return None
    start = _nearest_surface_point(Kf, cf)
    if start is None:
        return None
    tol = Fraction(1, 10 ** (digits + 1))
    for width in WIDTHS:
        y = _tangency(Ef, Kf, start, width)
        if y is None:
            continue
        C = inscribed_ellipsoid(K, y, width)
        if C is None:
            continue
        try:
            inner = ellipsoids(E, C, digits + 2)
        except UndecidedError:
            continue
        if not inner.distance < 0 or inner.normal is None or inner.point_Q is None:
            continue
        depth_c = -fraction_of(inner.distance.mid())
        lower = -depth_c + fraction_of(inner.distance.rad())  # -depth(E, C) <= this
        v = [depth_c * (1 + tol) * fraction_of(x.mid()) for x in inner.normal]
        if overlap_exact(E.translated(v), K).code is OverlapCode.OVERLAPPING:
            continue
        norm2 = sum((x * x for x in v), Fraction(0))
        bits = max(64, int(digits * 3.33) + 40)
        with working_precision(bits):
            root = flint.arb(flint.fmpq(norm2.numerator, norm2.denominator)).sqrt()
            lo = -(fraction_of(root.mid()) + fraction_of(root.rad()))  # -depth(E, K) >= -|v|
            if lower - lo > abs(lo) * Fraction(1, 10**digits):
                continue
            ball = flint.arb(flint.fmpq(lo.numerator, lo.denominator)).union(
                flint.arb(flint.fmpq(lower.numerator, lower.denominator))
            )
        return InscribedDepth(ball, inner, C, (v[0], v[1], v[2]), bits)
    return None


def _tangency(Ef: np.ndarray, Kf: np.ndarray, y: np.ndarray, width: Fraction) -> np.ndarray | None:
    """The point of tangency in binary64: with ``C`` inscribed at ``y``, the depth kernel's
    minimiser ``u`` gives ``C``'s contact point (its support point in ``-u``), which ``C`` shares
    with ``K`` when it lies on their common conic; ``y`` moves there (projected onto ``K``'s
    surface by Newton steps along the gradient) until it stays, at most :data:`MOVES` times."""
    scale = 1.0 + float(np.max(np.abs(y)))
    for _ in range(MOVES):
        C = _inscribed_float(Kf, y, float(width))
        if C is None:
            return None
        found = depth_and_minimiser(Ef, C, 1e-6) or depth_and_minimiser(Ef, C, 1e-3)
        if found is None:
            return None
        u = found[2]
        A, b, q = C[:3, :3], C[:3, 3], C[3, 3]
        c = -np.linalg.solve(A, b)
        r = float(c @ A @ c - q)
        Bu = np.linalg.solve(A, -u)
        p = c + math.sqrt(r) * Bu / math.sqrt(float(-u @ Bu))
        for _ in range(8):  # onto K's surface
            g = 2 * (Kf[:3, :3] @ p + Kf[:3, 3])
            f = float(p @ Kf[:3, :3] @ p + 2 * Kf[:3, 3] @ p + Kf[3, 3])
            p = p - f * g / float(g @ g)
        if not np.all(np.isfinite(p)):
            return None
        moved = float(np.max(np.abs(p - y)))
        y = p
        if moved <= 1e-15 * scale:
            break
    return y


def _inscribed_float(Kf: np.ndarray, y: np.ndarray, width: float) -> np.ndarray | None:
    """:func:`inscribed_ellipsoid` in binary64 (the search's own; the certificate rebuilds it
    exactly)."""
    vals, vecs = np.linalg.eigh(Kf[:3, :3])
    top = float(np.max(np.abs(vals)))
    M = Kf.copy()
    for lam, vec in zip(vals, vecs.T, strict=True):
        if lam > 1e-12 * top:
            continue
        ell = np.array([*vec, -float(vec @ y)])
        M += (abs(float(lam)) + width * top) * np.outer(ell, ell)
    if not np.all(np.linalg.eigvalsh(M[:3, :3]) > 0):
        return None
    return M
