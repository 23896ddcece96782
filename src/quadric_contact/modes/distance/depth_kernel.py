"""The penetration depth of two crossing ellipsoids on stacks: a compiled kernel with a
certificate on both sides; the pairs it cannot certify go to the scalar certified path.

The depth
---------
For ellipsoids ``E`` and ``K`` (solids ``X^T M X <= 0``), ``D = E + (-K) = {x - y}`` is convex
with support function ``phi(u) = h_E(u) + h_K(-u)``.  The interiors meet exactly when ``0`` is
inside ``D``, and then the depth is the distance from ``0`` to the boundary of ``D``,
``depth = min over unit u of phi(u)``; the signed distance is ``-depth``.

Each ellipsoid is first bracketed between two ellipsoids with float data (below): a float
centre ``c``, a float upper-triangular ``L`` and radii ``sigma <= 1 <= tau`` (both within a few
units in the last place of 1 for a well-conditioned ellipsoid) with
``c + sigma L B`` inside the solid and the solid inside ``c + tau L B`` (``B`` the unit ball),
so ``h(u) <= c . u + tau |L^T u|``.

* Upper bound: ``depth <= phi(u) / |u|`` for every ``u != 0`` (``phi`` is homogeneous), at a
  float local minimiser ``u*``, with ``phi(u*)`` bounded above through the outer ellipsoids,
  every operation rounded upwards.  ``u*``: Newton's method on the sphere from the best two of
  27 directions (in the tangent plane; the Hessian shifted where it is not positive definite,
  with a step along a direction of negative curvature there, so that a saddle of a symmetric
  configuration is left).
* Lower bound ``r``: ``depth >= r`` as soon as ``phi(u) >= r`` for every unit ``u``.  Any
  point ``z`` of ``D`` gives ``phi(u) >= z . u``.  The sphere is covered by the six faces of
  the cube, each the square ``[-1, 1]^2`` of gnomonic coordinates ``(a, b)``,
  ``w = s e_i + a e_j + b e_k``, cut into a quadtree.  On a cell with corners ``w_1 .. w_4``,
  ``z . w >= r |w|`` at the corners implies it on the whole square (``w = sum l_i w_i``,
  ``l_i >= 0`` summing to 1: ``z . w = sum l_i z . w_i >= r sum l_i |w_i| >= r |w|`` by the
  triangle inequality, ``r >= 0``), so ``phi >= r`` on the cone of the cell.  The test is
  exact for the linear bound (the least ``z . u`` over the spherical cell, where positive, is
  at a corner): nothing is lost to a circumscribed cap.  The point of a cell is a point of
  ``D`` near its support point in the direction of the cell's centre; a cell whose corners
  fail with its parent's point and with its own is cut into four, and the pair is given up
  (left to the scalar path) after :data:`BUDGET` points or below cells of half-width
  ``2^-MAX_LEVEL``.  Where a failing cell's centre has ``z . u < r``, or where a failing cell
  more than 64 half-widths from ``u*`` (it may lie across the edge of a region below ``r``,
  whose cells would otherwise be cut down to the last level; looked at on every fourth level)
  has a corner at which ``phi`` in binary64 is below ``r``, a deeper local minimum is near:
  Newton's method restarts there (at most four times), and ``r`` only ever goes down, so every
  cell accepted stays accepted.  With ``r = depth_hi / (1 + 0.9 tol)`` an accepted pair's
  enclosure ``[-depth_hi, -r]`` of the signed distance is at most ``tol`` relative wide, and
  ``r > 0`` proves that the interiors meet.  Near ``u*`` the linear bound loses about
  ``R rho^2`` on a cell of half-width ``rho`` (``R`` a radius of curvature of the boundary of
  ``D``), so about 20 levels reach ``1e-12``; far from it, a few coarse cells do.

The ellipsoids between float data, once a pair
----------------------------------------------
For each ellipsoid: a float centre ``c`` (refined once by its residual), ``g = A c + a`` and
``k = X_c^T M X_c`` in twice the working precision (Dot2, as the support enclosure of
:mod:`quadric_contact.modes.distance.apart_kernel`), so that ``X^T M X = y^T A y + 2 g . y + k``
for ``x = c + y`` and the solid is ``||x - c_true||_A^2 <= r``, ``r = -k + g^T A^-1 g``
(enclosed in ``[r_lo, r_hi]``), with ``||c - c_true||_A = sqrt(g^T adj(A) g / det A) <= rho_g``.
``L``: ``sqrt(-k)`` times the inverse of the float Cholesky factor of ``A``; ``N = L^T A L``
entry by entry in twice the working precision (Dot2 of the 18 exact products), and Gershgorin
bounds ``mu <= lambda(N) <= nu`` rounded outwards, so that
``mu |s|^2 <= ||L s||_A^2 <= nu |s|^2``.

* Outer: ``||x - c||_A <= sqrt(r_hi) + rho_g`` on the solid, so ``x = c + L s`` has
  ``|s| <= tau = (sqrt(r_hi) + rho_g) / sqrt(mu)``.
* Inner, for the points actually computed: every point the kernel uses is
  ``x~_k = fl(c_k + fl(sum_j L_kj s_j))`` for a float ``s`` with ``|s| <= 1``.  It differs from
  ``c + L s`` by at most ``eps_k = u |c_k| + gamma_(m+1) |L_k|_2`` in coordinate ``k`` (``m``
  the terms of row ``k``: ``gamma_m sum_j |L_kj s_j| <= gamma_m |L_k|_2`` for the row, ``u``
  for the sum), so ``||x~ - c||_A <= |s| sqrt(nu) + eta`` with
  ``eta = max_k eps_k sqrt(sum |A_ij|)`` (``e^T A e <= |e|^T |A| |e|``).  Hence ``x~`` is in
  the solid whenever ``|s| <= sigma = (sqrt(r_lo) - rho_g - eta) / sqrt(nu)`` (the triangle
  inequality in the ``A`` norm; every step rounded down), checked for each point as
  ``fl(s . s) (1 + 8u) <= sigma^2`` rounded down (three squares summed err by ``gamma_3``).
  The point of a cell is ``s = sigma' (L^T v) / |L^T v|`` for the direction ``v`` (``-v``
  for ``K``; ``sigma' = sigma (1 - 16u)`` leaves room for the rounding of ``s``): the support
  point of ``c + sigma' L B``.

A cell thus costs two points and four corner tests in binary64 (about fifty nanoseconds), where
a point certified by its own Dot2 form would cost a few hundred.  The enclosure is at best
about ``(tau - sigma) R`` wide (``R = |L^T u*|``, a few units in the last place of the
ellipsoids' size): depths much below ``1e-2`` of the size, and ellipsoids much thinner than
``1e-2`` of their distance from the origin, are left to the scalar path at ``tol = 1e-12``.

The corner test, in binary64 with static bounds: ``d_k = fl(x~_k - y~_k)``,
``t = fl(d . w)``, ``m = fl(|d| . |w|)``; the exact ``T = (x~ - y~) . w`` has
``|t - T| <= gamma_4 / ((1 - u)(1 - gamma_3)) m <= 8u m``, so ``T >= t - e`` with
``e = fl(8u m + tiny)``; with ``t_l = fl(t - e) > 0`` and ``n2 = fl(fl(1 + a^2) + b^2)``
(``|w|^2`` within ``gamma_3``), a corner passes when ``fl(t_l^2) >= fl(fl(r^2_up n2) (1 + 16u))``:
``T^2 >= fl(t_l^2) / (1 + u)^3``, ``r^2 |w|^2 <= fl(r^2_up n2) / ((1 - u)(1 - gamma_3))`` and
``(1 + 16u)(1 - u)^2 (1 - gamma_3) >= (1 + u)^3``.

Scale.  The error bounds above hold without overflow and with underflow only where its
absolute error (at most ``2^-1074`` an operation) is covered: input entries are at most
``1e100``, the diagonal of ``A`` and of ``L`` at least ``1e-100``, entries of ``L`` and
centre coordinates at most ``1e50``, entries of ``L`` below ``1e-140`` and centre
coordinates below ``1e-100`` are set to zero (any float ``c`` and ``L`` will do), so that the
exact products of the Dot2 sums stay normal; ``r`` is at least ``1e-150``.  Other pairs are
left to the scalar path.

``proofs/depth_of_crossing_ellipsoids.py`` checks the corner lemma, the cap bound it improves
on, the bracketing of the ellipsoids and the kernel's enclosures against a brute-force
minimiser.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from quadric_contact.modes.distance.apart_kernel import (
    _GAMMA,
    _TINY,
    _U,
    _adj3,
    _adj3_abs,
    _det4,
    _dn,
    _dot_accurate,
    _form_accurate,
    _inside_negative,
    _up,
    dot2_bilinear,
)
from quadric_contact.modes.kernels._jit import njit
from quadric_contact.modes.kernels.threads import kernel_stack, run_parallel

__all__ = [
    "BUDGET",
    "MAX_LEVEL",
    "covered_outside_cap",
    "crossing_ellipsoids",
    "crossing_ellipsoids_cells",
    "depth_and_minimiser",
]

BUDGET = 4000
"""Cells (points of ``D``) a pair may use before it is left to the scalar path."""
MAX_LEVEL = 30
"""The deepest level of the quadtree: cells of half-width ``2^-30`` (about ``1e-9`` rad)."""
_CAP = 4 * MAX_LEVEL + 16
"""The stack of cells: depth first, it holds at most ``6 + 3 * MAX_LEVEL`` cells."""
_RESTARTS = 4
"""Newton restarts from cells whose centre (or, far from the minimiser, a corner) lies below the
target."""
_WEIGHT = 256
"""A pair here costs about as much as this many pairs of the decision kernels (for the split of
a stack between threads, :func:`quadric_contact.modes.kernels.threads.run_parallel`)."""
_TWIN_ELEMENTS = 36 * 250
"""The largest call the kernel's Python twin answers while the kernel is not compiled (a pair
is 36 array elements; the twin takes about 5 ms a pair, so about a second): a larger stack
compiles the kernel (about 15 s) or loads it (``quadric_contact.modes.kernels._jit.njit``)."""

_C_S = 1.0 + 8 * _U
_C_T = 1.0 + 16 * _U
_E8 = 8 * _U
_E6 = 6 * _U
_G2 = 2 * _U / (1 - 2 * _U) * (1 + 2.0**-40)
_G3 = 3 * _U / (1 - 3 * _U) * (1 + 2.0**-40)
_G4 = 4 * _U / (1 - 4 * _U) * (1 + 2.0**-40)
_BIG = 1e100  # the largest entry of an input matrix
_FAR = 1e50  # the largest centre coordinate and entry of L
_NEAR = 1e-100  # smaller centre coordinates are flushed to 0; the least diagonal of A and L
_FLUSH = 1e-140  # smaller entries of L are flushed to 0
_SMALL = 1e-150  # the least target r


@njit(inline=True)
def _bilinear(
    M: Any, p0: float, p1: float, p2: float, q0: float, q1: float, q2: float
) -> tuple[float, float]:
    """``p^T A q`` (``A`` the leading 3x3 block of ``M``) in twice the working precision, with
    its error bound (:func:`~quadric_contact.modes.distance.apart_kernel.dot2_bilinear`)."""
    return dot2_bilinear(M, (p0, p1, p2), (q0, q1, q2))


@njit(inline=True)
def _inner(M: Any, adj: Any, adja: Any, detA: float, eA: float, c: Any, L: Any) -> tuple[float, float]:
    """Refine the float centre ``c``, set ``L`` (upper triangular) and return ``(sigma, tau)``:
    every ``fl(c + fl(L s))`` with float ``|s| <= sigma`` lies in the solid of ``M``, and the
    solid lies in ``c + L B(tau)`` (``(0, 0)`` when not certified).  See the module's
    docstring."""
    for i in range(3):
        if not (abs(c[i]) <= _FAR):
            return 0.0, 0.0
        if abs(c[i]) < _NEAR:
            c[i] = 0.0
    g0, e0 = _dot_accurate(M, 0, c[0], c[1], c[2])
    g1, e1 = _dot_accurate(M, 1, c[0], c[1], c[2])
    g2, e2 = _dot_accurate(M, 2, c[0], c[1], c[2])
    d0 = (adj[0, 0] * g0 + adj[0, 1] * g1 + adj[0, 2] * g2) / detA
    d1 = (adj[1, 0] * g0 + adj[1, 1] * g1 + adj[1, 2] * g2) / detA
    d2 = (adj[2, 0] * g0 + adj[2, 1] * g1 + adj[2, 2] * g2) / detA
    if math.isfinite(d0) and math.isfinite(d1) and math.isfinite(d2):
        c[0] -= d0
        c[1] -= d1
        c[2] -= d2
    for i in range(3):
        if abs(c[i]) < _NEAR:
            c[i] = 0.0
        if not (abs(c[i]) <= _FAR):
            return 0.0, 0.0
    g0, e0 = _dot_accurate(M, 0, c[0], c[1], c[2])
    g1, e1 = _dot_accurate(M, 1, c[0], c[1], c[2])
    g2, e2 = _dot_accurate(M, 2, c[0], c[1], c[2])
    g = (g0, g1, g2)
    eg = (e0, e1, e2)
    k, ek = _form_accurate(M, c[0], c[1], c[2])
    # q = g^T adj g and its error bound (as in the support enclosure)
    q = 0.0
    qm = 0.0
    qd = 0.0
    for i in range(3):
        for j in range(3):
            aij = abs(adj[i, j]) + adja[i, j] * _GAMMA
            q += g[i] * adj[i, j] * g[j]
            qm += abs(g[i]) * adja[i, j] * abs(g[j])
            qd += aij * (eg[i] * (abs(g[j]) + eg[j]) + abs(g[i]) * eg[j])
    eq = (qm * _GAMMA + qd) * (1 + 2.0**-40) + _TINY
    dl, dh = detA - eA, detA + eA
    ql, qh = q - eq, q + eq
    rl = _dn(-(k + ek) + (_dn(ql / dh) if ql >= 0 else _dn(ql / dl)))
    rh = _up(-(k - ek) + (_up(qh / dl) if qh >= 0 else _up(qh / dh)))
    if not (rl > 0 and rh < np.inf and -k > 0 and dl > 0):
        return 0.0, 0.0
    rho_g = _up(math.sqrt(_up(max(qh, 0.0) / dl)))
    # the Cholesky factor R of A (R^T R = A) and L = sqrt(-k) R^-1
    if not (M[0, 0] > 0):
        return 0.0, 0.0
    R00 = math.sqrt(M[0, 0])
    R01 = M[0, 1] / R00
    R02 = M[0, 2] / R00
    t = M[1, 1] - R01 * R01
    if not (t > 0):
        return 0.0, 0.0
    R11 = math.sqrt(t)
    R12 = (M[1, 2] - R01 * R02) / R11
    t = M[2, 2] - R02 * R02 - R12 * R12
    if not (t > 0):
        return 0.0, 0.0
    R22 = math.sqrt(t)
    sr = math.sqrt(-k)
    L[0, 0] = sr / R00
    L[1, 1] = sr / R11
    L[2, 2] = sr / R22
    L[0, 1] = -R01 * L[1, 1] / R00
    L[1, 2] = -R12 * L[2, 2] / R11
    L[0, 2] = (R01 * R12 - R02 * R11) * L[2, 2] / (R00 * R11)
    L[1, 0] = 0.0
    L[2, 0] = 0.0
    L[2, 1] = 0.0
    # the scale: products of entries of L and of c neither overflow nor underflow
    for i in range(3):
        for j in range(3):
            if abs(L[i, j]) < _FLUSH:
                L[i, j] = 0.0
            if not (abs(L[i, j]) <= _FAR):
                return 0.0, 0.0
        if not (L[i, i] >= _NEAR):
            return 0.0, 0.0
    # nu >= lambda_max(L^T A L) and mu <= lambda_min(L^T A L): Gershgorin on the entries
    # enclosed in twice the working precision
    nu = 0.0
    mu = np.inf
    for i in range(3):
        hi = 0.0
        lo = 0.0
        for j in range(3):
            v, e = _bilinear(M, L[0, i], L[1, i], L[2, i], L[0, j], L[1, j], L[2, j])
            if i == j:
                hi = _up(hi + _up(v + e))
                lo = _dn(lo + _dn(v - e))
            else:
                off = _up(abs(v) + e)
                hi = _up(hi + off)
                lo = _dn(lo - off)
        nu = max(nu, hi)
        mu = min(mu, lo)
    if not (mu > 0 and nu < np.inf):
        return 0.0, 0.0
    # eta >= ||e||_A for the rounding error e of a point: |e_k| <= eps_k =
    # u |c_k| + gamma_(m_k + 1) |L_k|_2, m_k the terms of row k of L s; e^T A e <= max(eps)^2
    # times the sum of |A_ij|
    n0 = _up(math.sqrt(_up(_up(_up(L[0, 0] * L[0, 0]) + _up(L[0, 1] * L[0, 1])) + _up(L[0, 2] * L[0, 2]))))
    n1 = _up(math.sqrt(_up(_up(L[1, 1] * L[1, 1]) + _up(L[1, 2] * L[1, 2]))))
    e0 = _up(_up(_U * abs(c[0])) + _up(_G4 * n0))
    e1 = _up(_up(_U * abs(c[1])) + _up(_G3 * n1))
    e2 = _up(_up(_U * abs(c[2])) + _up(_G2 * abs(L[2, 2])))
    sa = 0.0
    for i in range(3):
        for j in range(3):
            sa = _up(sa + abs(M[i, j]))
    eta = _up(max(e0, max(e1, e2)) * _up(math.sqrt(sa)))
    sigma = _dn(_dn(_dn(_dn(math.sqrt(rl)) - rho_g) - eta) / _up(math.sqrt(nu)))
    tau = _up(_up(_up(math.sqrt(rh)) + rho_g) / _dn(math.sqrt(mu)))
    if not (sigma > 0.5 and math.isfinite(sigma) and tau < 2.0):
        return 0.0, 0.0
    return min(sigma, 1.0), tau


@njit(inline=True)
def _bracket(M: Any, adj: Any, adja: Any, c: Any, L: Any) -> tuple[float, float]:
    """For the matrix ``M`` (negated in place if needed, so that the inside is negative): the
    float centre ``c``, the float ``L`` and the radii ``(sigma, tau)`` of :func:`_inner`;
    ``(0, 0)`` when ``M`` is not certainly an ellipsoid of a workable scale."""
    # an ellipsoid with the inside negative: A positive definite, det < 0
    if not (_inside_negative(M) and M[0, 0] >= _NEAR and M[1, 1] >= _NEAR and M[2, 2] >= _NEAR):
        return 0.0, 0.0
    _adj3(M, adj)
    Ma = np.abs(M)
    _adj3_abs(Ma, adja)
    detA = M[0, 0] * adj[0, 0] + M[0, 1] * adj[1, 0] + M[0, 2] * adj[2, 0]
    eA = (Ma[0, 0] * adja[0, 0] + Ma[0, 1] * adja[1, 0] + Ma[0, 2] * adja[2, 0]) * _GAMMA + _TINY
    detM, eM = _det4(M)
    if not (detA > eA and detM < -eM):
        return 0.0, 0.0
    for i in range(3):
        c[i] = -(adj[i, 0] * M[0, 3] + adj[i, 1] * M[1, 3] + adj[i, 2] * M[2, 3]) / detA
    return _inner(M, adj, adja, detA, eA, c, L)


@njit(inline=True)
def _point(
    c: Any, L: Any, sig: float, sig2: float, sgn: float, w0: float, w1: float, w2: float
) -> tuple[float, float, float, bool]:
    """``fl(c + fl(L s))`` with ``s = sig (L^T v) / |L^T v|``, ``v = sgn w``: a point of the
    solid near its support point in the direction ``v`` (``ok``: ``|s|^2 <= sig2`` checked)."""
    q0 = sgn * (L[0, 0] * w0)
    q1 = sgn * (L[0, 1] * w0 + L[1, 1] * w1)
    q2 = sgn * (L[0, 2] * w0 + L[1, 2] * w1 + L[2, 2] * w2)
    nq = math.sqrt(q0 * q0 + q1 * q1 + q2 * q2)
    if not (nq > 0):
        return c[0], c[1], c[2], False
    f = sig / nq
    s0 = f * q0
    s1 = f * q1
    s2 = f * q2
    ok = (s0 * s0 + s1 * s1 + s2 * s2) * _C_S <= sig2
    x0 = c[0] + (L[0, 0] * s0 + L[0, 1] * s1 + L[0, 2] * s2)
    x1 = c[1] + (L[1, 1] * s1 + L[1, 2] * s2)
    x2 = c[2] + L[2, 2] * s2
    return x0, x1, x2, ok


@njit(inline=True)
def _corner(dn: float, da: float, db: float, a: float, b: float, R2: float) -> bool:
    """Is ``(x~ - y~) . w >= r |w|`` certain at the corner ``w = (sign, a, b)`` of a face (in
    the face's coordinates; ``dn`` carries the sign), with ``R2 >= r^2``?"""
    pa = da * a
    pb = db * b
    t = (dn + pa) + pb
    m = (abs(dn) + abs(pa)) + abs(pb)
    tl = t - (m * _E8 + _TINY)
    if not (tl > 0):
        return False
    n2 = (1.0 + a * a) + b * b
    return tl * tl >= (R2 * n2) * _C_T


@njit(inline=True)
def _on_face(ax: int, s: float, a: float, b: float) -> tuple[float, float, float]:
    """The direction of gnomonic coordinates ``(a, b)`` on the face ``s e_ax`` of the cube
    (the other two axes in cyclic order: ``e_(ax+1)`` takes ``a``, ``e_(ax+2)`` takes ``b``)."""
    if ax == 0:
        return s, a, b
    if ax == 1:
        return b, s, a
    return a, b, s


@njit(inline=True)
def _cell_ok(dn: float, da: float, db: float, a: float, b: float, h: float, R2: float) -> bool:
    return (
        _corner(dn, da, db, a - h, b - h, R2)
        and _corner(dn, da, db, a + h, b - h, R2)
        and _corner(dn, da, db, a - h, b + h, R2)
        and _corner(dn, da, db, a + h, b + h, R2)
    )


@njit(inline=True)
def _phi(cd: Any, L1: Any, L2: Any, u0: float, u1: float, u2: float) -> float:
    """``phi(u) = u . (c_E - c_K) + |L_E^T u| + |L_K^T u|`` in binary64 (the search's estimate)."""
    a0 = L1[0, 0] * u0
    a1 = L1[0, 1] * u0 + L1[1, 1] * u1
    a2 = L1[0, 2] * u0 + L1[1, 2] * u1 + L1[2, 2] * u2
    b0 = L2[0, 0] * u0
    b1 = L2[0, 1] * u0 + L2[1, 1] * u1
    b2 = L2[0, 2] * u0 + L2[1, 2] * u1 + L2[2, 2] * u2
    return (
        cd[0] * u0
        + cd[1] * u1
        + cd[2] * u2
        + math.sqrt(a0 * a0 + a1 * a1 + a2 * a2)
        + math.sqrt(b0 * b0 + b1 * b1 + b2 * b2)
    )


@njit(inline=True)
def _lt(L: Any, v0: float, v1: float, v2: float) -> tuple[float, float, float]:
    """``L^T v`` for the upper-triangular ``L``."""
    return L[0, 0] * v0, L[0, 1] * v0 + L[1, 1] * v1, L[0, 2] * v0 + L[1, 2] * v1 + L[2, 2] * v2


@njit(inline=True)
def _newton(cd: Any, L1: Any, L2: Any, u: Any) -> float:
    """A local minimiser of ``phi`` on the unit sphere from ``u`` (overwritten): Newton's
    method in the tangent plane, the Hessian shifted where it is not positive definite (and a
    step along a direction of negative curvature added, to leave saddles), steps at most 0.5
    long and halved until ``phi`` does not grow.  Returns ``phi(u)``."""
    f = _phi(cd, L1, L2, u[0], u[1], u[2])
    for _ in range(60):
        # the tangent basis e, t of u
        if abs(u[0]) <= abs(u[1]) and abs(u[0]) <= abs(u[2]):
            e0, e1, e2 = 0.0, u[2], -u[1]
        elif abs(u[1]) <= abs(u[2]):
            e0, e1, e2 = -u[2], 0.0, u[0]
        else:
            e0, e1, e2 = u[1], -u[0], 0.0
        ne = math.sqrt(e0 * e0 + e1 * e1 + e2 * e2)
        e0 /= ne
        e1 /= ne
        e2 /= ne
        t0 = u[1] * e2 - u[2] * e1
        t1 = u[2] * e0 - u[0] * e2
        t2 = u[0] * e1 - u[1] * e0
        # gradient z = cd + L1 s1 + L2 s2 and the tangent Hessian
        g_e = cd[0] * e0 + cd[1] * e1 + cd[2] * e2
        g_t = cd[0] * t0 + cd[1] * t1 + cd[2] * t2
        h_ee = 0.0
        h_et = 0.0
        h_tt = 0.0
        scale = abs(cd[0]) + abs(cd[1]) + abs(cd[2])
        for which in range(2):
            Lw = L1 if which == 0 else L2
            q0, q1, q2 = _lt(Lw, u[0], u[1], u[2])
            n = math.sqrt(q0 * q0 + q1 * q1 + q2 * q2)
            if not (n > 0):
                return np.inf
            s0, s1, s2 = q0 / n, q1 / n, q2 / n
            pe0, pe1, pe2 = _lt(Lw, e0, e1, e2)
            pt0, pt1, pt2 = _lt(Lw, t0, t1, t2)
            se = s0 * pe0 + s1 * pe1 + s2 * pe2
            st = s0 * pt0 + s1 * pt1 + s2 * pt2
            g_e += se
            g_t += st
            h_ee += (pe0 * pe0 + pe1 * pe1 + pe2 * pe2 - se * se) / n
            h_et += (pe0 * pt0 + pe1 * pt1 + pe2 * pt2 - se * st) / n
            h_tt += (pt0 * pt0 + pt1 * pt1 + pt2 * pt2 - st * st) / n
            scale += n
        h_ee -= f
        h_tt -= f
        # the least eigenvalue; shift when not safely positive
        tr = h_ee + h_tt
        disc = math.sqrt((h_ee - h_tt) * (h_ee - h_tt) + 4 * h_et * h_et)
        lmin = 0.5 * (tr - disc)
        floor = 1e-9 * scale
        # at a saddle (or a maximum) the gradient vanishes: step along the negative curvature
        ce = 0.0
        ct = 0.0
        if lmin < -floor:
            ae, at = h_et, lmin - h_ee
            be, bt = lmin - h_tt, h_et
            if ae * ae + at * at < be * be + bt * bt:
                ae, at = be, bt
            na = math.sqrt(ae * ae + at * at)
            if na > 0:
                ce = 0.25 * ae / na
                ct = 0.25 * at / na
                if ce * g_e + ct * g_t > 0:
                    ce = -ce
                    ct = -ct
        if lmin < floor:
            shift = floor - lmin + 1e-3 * (abs(h_ee) + abs(h_tt))
            h_ee += shift
            h_tt += shift
        det = h_ee * h_tt - h_et * h_et
        if not (det > 0):
            break
        pe = -(h_tt * g_e - h_et * g_t) / det + ce
        pt = -(h_ee * g_t - h_et * g_e) / det + ct
        plen = math.sqrt(pe * pe + pt * pt)
        if not math.isfinite(plen):
            break
        if plen > 0.5:
            pe *= 0.5 / plen
            pt *= 0.5 / plen
            plen = 0.5
        moved = False
        for _half in range(30):
            v0 = u[0] + pe * e0 + pt * t0
            v1 = u[1] + pe * e1 + pt * t1
            v2 = u[2] + pe * e2 + pt * t2
            nv = math.sqrt(v0 * v0 + v1 * v1 + v2 * v2)
            v0 /= nv
            v1 /= nv
            v2 /= nv
            fv = _phi(cd, L1, L2, v0, v1, v2)
            if fv <= f + 4e-16 * scale:
                u[0] = v0
                u[1] = v1
                u[2] = v2
                f = fv
                moved = True
                break
            pe *= 0.5
            pt *= 0.5
            plen *= 0.5
        if not moved or plen < 1e-15:
            break
    return f


@njit(inline=True)
def _starts(cd: Any, L1: Any, L2: Any, st: Any) -> None:
    """The best two, by ``phi``, of the 26 directions of the cube and the direction from
    ``c_E`` to ``c_K``, into the rows of ``st``."""
    best1 = np.inf
    best2 = np.inf
    nc = math.sqrt(cd[0] * cd[0] + cd[1] * cd[1] + cd[2] * cd[2])
    st[0, 0], st[0, 1], st[0, 2] = 0.0, 0.0, 1.0
    st[1, 0], st[1, 1], st[1, 2] = 0.0, 0.0, -1.0
    for idx in range(28):
        if idx < 27:
            i0 = idx % 3 - 1
            i1 = (idx // 3) % 3 - 1
            i2 = idx // 9 - 1
            if i0 == 0 and i1 == 0 and i2 == 0:
                continue
            nn = math.sqrt(float(i0 * i0 + i1 * i1 + i2 * i2))
            v0, v1, v2 = i0 / nn, i1 / nn, i2 / nn
        else:
            if not (nc > 0):
                continue
            v0, v1, v2 = -cd[0] / nc, -cd[1] / nc, -cd[2] / nc
        fv = _phi(cd, L1, L2, v0, v1, v2)
        if fv < best1:
            best2 = best1
            st[1, 0], st[1, 1], st[1, 2] = st[0, 0], st[0, 1], st[0, 2]
            best1 = fv
            st[0, 0], st[0, 1], st[0, 2] = v0, v1, v2
        elif fv < best2:
            best2 = fv
            st[1, 0], st[1, 1], st[1, 2] = v0, v1, v2


@njit(inline=True)
def _norm_up(L: Any, u: Any) -> float:
    """``|L^T u|`` rounded up (``L`` upper triangular)."""
    m = 0.0
    for j in range(3):
        lo = 0.0
        hi = 0.0
        for i in range(j + 1):
            lo = _dn(lo + _dn(L[i, j] * u[i]))
            hi = _up(hi + _up(L[i, j] * u[i]))
        a = max(abs(lo), abs(hi))
        m = _up(m + _up(a * a))
    return _up(math.sqrt(m))


@njit(inline=True)
def _depth_hi(c1: Any, L1: Any, t1: float, c2: Any, L2: Any, t2: float, u: Any) -> float:
    """``phi(u) / |u|`` rounded up, ``phi`` bounded by the outer ellipsoids:
    ``h_E(u) <= c_E . u + tau_E |L_E^T u|``, ``h_K(-u) <= -c_K . u + tau_K |L_K^T u|``;
    nan when not positive."""
    ph = 0.0
    for i in range(3):
        ph = _up(ph + _up(c1[i] * u[i]))
        ph = _up(ph + _up(-c2[i] * u[i]))
    ph = _up(ph + _up(t1 * _norm_up(L1, u)))
    ph = _up(ph + _up(t2 * _norm_up(L2, u)))
    un2 = _dn(_dn(_dn(u[0] * u[0]) + _dn(u[1] * u[1])) + _dn(u[2] * u[2]))
    if not (ph > 0 and un2 > 0 and math.isfinite(ph)):
        return np.nan
    return _up(ph / _dn(math.sqrt(un2)))


@njit(twin_elements=_TWIN_ELEMENTS)
def _kernel(
    Es: Any,
    Ks: Any,
    tol: float,
    cover: Any,
    out: Any,
    flag: Any,
    work: Any,
    best: Any,
    start: int,
    stop: int,
) -> None:  # pragma: no cover
    """The pairs ``start:stop`` of the stacks: ``out`` their enclosures, ``flag`` 1 where left to
    the scalar path, ``work`` the cells used, ``best`` the minimiser ``u*`` (a float unit vector;
    nan where the pair is not read).

    ``cover`` ``(n, 5)``: where ``cover[k, 0] > 0`` the pair is only covered, with the fixed
    target ``r = cover[k, 0]`` and without Newton's method: a cell is accepted by the corner test
    or when its four corners ``w`` have ``w . c >= cover[k, 4] |w|`` in binary64 (``c =
    cover[k, 1:4]``, the cap of the caller's isolating box); a cell whose centre lies below
    ``r`` fails the pair.  ``flag[k] = 0`` then means ``phi >= r`` on every direction the cap
    does not hold (``out[k] = (-r, -r)``)."""
    Ms = np.empty((2, 4, 4))  # E and K, the inside negative
    adj = np.empty((2, 3, 3))
    ad = np.empty((2, 3, 3))
    L = np.zeros((2, 3, 3))
    c = np.empty((2, 3))
    sig = np.empty(2)  # the inner radii (of the unit ball through L)
    sq = np.empty(2)  # sig^2 rounded down
    tau = np.empty(2)  # the outer radii
    pt = np.empty((2, 3))  # the two points of a cell
    cd = np.empty(3)
    u = np.empty(3)  # the best minimiser
    ub = np.empty(3)
    st = np.empty((2, 3))  # directions Newton's method starts from
    sf = np.empty(_CAP, dtype=np.int64)  # the stack of cells: face
    sl = np.empty(_CAP, dtype=np.int64)  # level
    sk = np.empty(_CAP, dtype=np.int64)  # its point: 0 none, 1 the parent's, 2 its own
    sa = np.empty(_CAP)  # centre, gnomonic coordinates
    sb = np.empty(_CAP)
    sh = np.empty(_CAP)  # half-width
    sd = np.empty((_CAP, 3))  # the point of D, in the face's coordinates
    shrink = 1.0 / (1.0 + 0.9 * tol)
    for k in range(start, stop):
        out[k, 0] = -np.inf
        out[k, 1] = np.inf
        flag[k] = 1
        work[k] = 0
        best[k, 0], best[k, 1], best[k, 2] = np.nan, np.nan, np.nan
        ok = True
        for i in range(4):
            for j in range(4):
                Ms[0, i, j] = Es[k, i, j]
                Ms[1, i, j] = Ks[k, i, j]
                if not (abs(Es[k, i, j]) <= _BIG and abs(Ks[k, i, j]) <= _BIG):
                    ok = False  # also not finite
        if not ok:
            continue
        for which in range(2):
            sig[which], tau[which] = _bracket(Ms[which], adj[which], ad[which], c[which], L[which])
            if not (sig[which] > 0):
                ok = False
                break
            sq[which] = _dn(sig[which] * sig[which])
            sig[which] *= 1.0 - 16 * _U  # the points' radius, leaving room for rounding
        if not ok:
            continue
        L1 = L[0]
        L2 = L[1]
        for i in range(3):
            cd[i] = c[0, i] - c[1, i]
        fixed = cover[k, 0] > 0  # cover only, with the caller's target and cap
        cap = cover[k, 4]
        _starts(cd, L1, L2, st)
        pending = 0 if fixed else 2
        f = np.inf  # phi at u, in binary64
        dhi = cover[k, 0] if fixed else np.inf  # the upper bound of the depth
        u[0], u[1], u[2] = cover[k, 1], cover[k, 2], cover[k, 3]
        rt = 0.0  # the target: the lower bound once every cell is accepted
        R2 = 0.0
        top = 0
        for face in range(6):
            sf[top] = face
            sl[top] = 0
            sk[top] = 0
            sa[top] = 0.0
            sb[top] = 0.0
            sh[top] = 1.0
            top += 1
        cells = 0
        restarts = 0
        good = True
        while True:
            # Newton's method from the pending starts: the upper bound, the target
            while pending > 0:
                pending -= 1
                ub[0], ub[1], ub[2] = st[pending, 0], st[pending, 1], st[pending, 2]
                fb = _newton(cd, L1, L2, ub)
                if not (fb > 0):
                    good = False  # apart, touching or no minimum: not for this kernel
                    break
                if fb < f:
                    dnew = _depth_hi(c[0], L1, tau[0], c[1], L2, tau[1], ub)
                    if dnew < dhi:
                        f = fb
                        dhi = dnew
                        u[0], u[1], u[2] = ub[0], ub[1], ub[2]
            if not (good and dhi < np.inf):
                good = False
                break
            rt = dhi if fixed else _dn(dhi * shrink)
            if not (rt > _SMALL):
                good = False
                break
            R2 = _up(rt * rt)
            # the cells, depth first
            restart = False
            while top > 0:
                top -= 1
                face = int(sf[top])
                lvl = int(sl[top])
                kind = int(sk[top])
                a = sa[top]
                b = sb[top]
                h = sh[top]
                dn, da, db = sd[top, 0], sd[top, 1], sd[top, 2]
                accepted = False
                usable = kind != 0
                w0, w1, w2 = 0.0, 0.0, 0.0
                ax = face // 2
                sgn = 1.0 if face % 2 == 0 else -1.0
                if fixed:
                    inside = True  # the cell's cone lies in the cap: its four corners do
                    for corner in range(4):
                        ca = a - h if corner % 2 == 0 else a + h
                        cb = b - h if corner < 2 else b + h
                        q0, q1, q2 = _on_face(ax, sgn, ca, cb)
                        nq = math.sqrt((1.0 + ca * ca) + cb * cb)
                        inside = inside and q0 * u[0] + q1 * u[1] + q2 * u[2] >= cap * nq
                    if inside:
                        continue
                for attempt in range(2):
                    if attempt == 1:
                        if kind == 2:
                            break  # its own point was tested before the restart
                        # its own point: the support points of E and K in the directions w, -w
                        w0, w1, w2 = _on_face(ax, sgn, a, b)
                        cells += 1
                        usable = True
                        for which in range(2):
                            x0, x1, x2, okp = _point(
                                c[which], L[which], sig[which], sq[which], 1.0 - 2.0 * which, w0, w1, w2
                            )
                            pt[which, 0] = x0
                            pt[which, 1] = x1
                            pt[which, 2] = x2
                            usable = usable and okp
                        if not usable:
                            break
                        d0 = pt[0, 0] - pt[1, 0]
                        d1 = pt[0, 1] - pt[1, 1]
                        d2 = pt[0, 2] - pt[1, 2]
                        if ax == 0:
                            dn, da, db = sgn * d0, d1, d2
                        elif ax == 1:
                            dn, da, db = sgn * d1, d2, d0
                        else:
                            dn, da, db = sgn * d2, d0, d1
                        kind = 2
                    elif kind == 0:
                        continue
                    if _cell_ok(dn, da, db, a, b, h, R2):
                        accepted = True
                        break
                if accepted:
                    continue
                if fixed and usable and kind == 2:
                    nw = math.sqrt((1.0 + a * a) + b * b)
                    outside = w0 * u[0] + w1 * u[1] + w2 * u[2] < cap * nw
                    if outside and dn + da * a + db * b < rt * nw:
                        good = False  # phi below the target outside the cap: not isolated
                        break
                elif usable and kind == 2 and int(sk[top]) != 2 and restarts < _RESTARTS:
                    # a deeper local minimum than u's: where the cell's centre is below the
                    # target, or where a cell far from u for its size (more than 64 half-widths,
                    # it may lie across the edge of a region below the target; looked at on every
                    # fourth level from the sixth) has a corner below it (phi in binary64):
                    # Newton's method from there, then this cell again
                    nw = math.sqrt((1.0 + a * a) + b * b)
                    v0, v1, v2 = w0 / nw, w1 / nw, w2 / nw
                    below = dn + da * a + db * b < rt * nw
                    far = v0 * u[0] + v1 * u[1] + v2 * u[2] < 1.0 - 2048.0 * h * h
                    if not below and lvl % 4 == 2 and lvl > 2 and far:
                        least = rt
                        for corner in range(4):
                            ca = a - h if corner % 2 == 0 else a + h
                            cb = b - h if corner < 2 else b + h
                            q0, q1, q2 = _on_face(ax, sgn, ca, cb)
                            nq = math.sqrt((1.0 + ca * ca) + cb * cb)
                            fq = _phi(cd, L1, L2, q0 / nq, q1 / nq, q2 / nq)
                            if fq < least:
                                least = fq
                                v0, v1, v2 = q0 / nq, q1 / nq, q2 / nq
                                below = True
                    if below:
                        restarts += 1
                        st[0, 0], st[0, 1], st[0, 2] = v0, v1, v2
                        pending = 1
                        sk[top] = 2
                        sd[top, 0] = dn
                        sd[top, 1] = da
                        sd[top, 2] = db
                        top += 1
                        restart = True
                        break
                if lvl >= MAX_LEVEL or cells >= BUDGET or top + 4 > _CAP:
                    good = False
                    break
                hh = 0.5 * h
                for child in range(4):
                    sf[top] = face
                    sl[top] = lvl + 1
                    sk[top] = 1 if usable else 0
                    sa[top] = a - hh if child % 2 == 0 else a + hh
                    sb[top] = b - hh if child < 2 else b + hh
                    sh[top] = hh
                    sd[top, 0] = dn
                    sd[top, 1] = da
                    sd[top, 2] = db
                    top += 1
            if not (good and restart):
                break
        work[k] = cells
        best[k, 0], best[k, 1], best[k, 2] = u[0], u[1], u[2]
        if not good:
            continue
        if fixed:
            out[k, 0] = -rt
            out[k, 1] = -rt
            flag[k] = 0
        elif _up(dhi - rt) <= _dn(tol * rt):
            out[k, 0] = -dhi
            out[k, 1] = -rt
            flag[k] = 0


def crossing_ellipsoids(Es: np.ndarray, Ks: np.ndarray, tol: float = 1e-12) -> tuple[np.ndarray, np.ndarray]:
    """Enclosures ``(n, 2)`` of the signed distance ``-depth`` of crossing ellipsoid pairs
    (float64 stacks ``(n, 4, 4)``) at most ``tol`` relative wide, and a mask of the pairs left
    to the scalar path (apart, touching or too shallow for ``tol``, not both ellipsoids, or
    not certified).

    Examples
    --------
    >>> E = np.diag([1.0, 1.0, 1.0, -1.0]); K = E.copy(); K[0, 3] = K[3, 0] = -1.0; K[3, 3] = 0.0
    >>> enc, rest = crossing_ellipsoids(E[None], K[None])   # unit balls at 0 and (1, 0, 0)
    >>> bool(enc[0, 0] <= -1.0 <= enc[0, 1]), bool(rest[0])
    (True, False)
    """
    out, rest, _ = crossing_ellipsoids_cells(Es, Ks, tol)
    return out, rest


def crossing_ellipsoids_cells(
    Es: np.ndarray, Ks: np.ndarray, tol: float = 1e-12
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`crossing_ellipsoids`, and the number of cells (points of ``D``) each pair used."""
    Es = kernel_stack(Es)
    Ks = kernel_stack(Ks)
    out, rest, work, _ = _run(Es, Ks, tol, np.zeros((Es.shape[0], 5)))
    return out, rest, work


def depth_and_minimiser(
    E: np.ndarray, K: np.ndarray, tol: float = 1e-12
) -> tuple[float, float, np.ndarray] | None:
    """One pair of crossing ellipsoids (binary64 ``4 x 4`` matrices): ``(lo, hi, u)`` with
    ``lo <= depth <= hi`` (``phi >= lo`` on the whole sphere) and the float unit minimiser ``u``
    whose ``phi(u) / |u|`` is at most ``hi``; None where the kernel leaves the pair.

    Examples
    --------
    >>> E = np.diag([1.0, 1.0, 1.0, -1.0]); K = E.copy(); K[0, 3] = K[3, 0] = -1.0; K[3, 3] = 0.0
    >>> lo, hi, u = depth_and_minimiser(E, K)   # unit balls at 0 and (1, 0, 0): depth 1
    >>> bool(lo <= 1.0 <= hi), [round(abs(float(x)), 9) for x in u]
    (True, [1.0, 0.0, 0.0])
    """
    out, rest, _, best = _run(kernel_stack(E), kernel_stack(K), tol, np.zeros((1, 5)))
    if rest[0]:
        return None
    return float(-out[0, 1]), float(-out[0, 0]), best[0].copy()


def covered_outside_cap(E: np.ndarray, K: np.ndarray, r: float, centre: np.ndarray, cos_cap: float) -> bool:
    """``phi(u) >= r`` proven for every unit ``u`` of one pair (binary64 ``4 x 4`` matrices)
    with ``u . centre < cos_cap`` in binary64 (a cell is excused when its four corners ``w`` have
    ``w . centre >= cos_cap |w|``, which puts its cone in the cap of the directions within
    ``arccos(cos_cap)`` of ``centre``, up to the rounding of that test: the caller's margin).
    False where a cell's centre outside the cap has a point of ``D`` below ``r`` (another
    minimum), or the budget runs out.

    Examples
    --------
    >>> E = np.diag([1.0, 1.0, 1.0, -1.0]); K = E.copy(); K[0, 3] = K[3, 0] = -1.0; K[3, 3] = 0.0
    >>> x = np.array([1.0, 0.0, 0.0])           # the depth 1 is reached at u = x only
    >>> covered_outside_cap(E, K, 1.0, x, math.cos(1e-3)), covered_outside_cap(E, K, 1.001, x, math.cos(1e-3))
    (True, False)
    """
    cover = np.array([[r, *centre, cos_cap]], dtype=np.float64)
    if not (r > 0 and np.all(np.isfinite(cover))):
        raise ValueError("the target must be positive and the cap finite")
    _, rest, _, _ = _run(kernel_stack(E), kernel_stack(K), 1e-12, cover)
    return not bool(rest[0])


def _run(
    Es: np.ndarray, Ks: np.ndarray, tol: float, cover: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The kernel over read-only stacks: enclosures, the mask left, cells, minimisers."""
    cover = np.ascontiguousarray(cover, dtype=np.float64).view()
    cover.flags.writeable = False
    n = Es.shape[0]
    out = np.empty((n, 2))
    flag = np.empty(n, dtype=np.uint8)
    work = np.empty(n, dtype=np.int64)
    best = np.empty((n, 3))
    if n:
        # a pair costs about what _WEIGHT pairs of the decision kernels cost: the stack is split
        # for the threads as if it had _WEIGHT times as many pairs (slice [a, b) of the weighted
        # range is the pairs [ceil(a / W), ceil(b / W)), so the slices still cover each pair once)
        W = _WEIGHT

        def run(a: int, b: int) -> None:
            _kernel(Es, Ks, float(tol), cover, out, flag, work, best, (a + W - 1) // W, (b + W - 1) // W)

        run_parallel(run, n * W)
    return out, flag.astype(bool), work, best
