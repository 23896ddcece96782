"""A brute force for the penetration depth into any solid, convex or not, for the proof of the
depth into non-convex solids and its tests.

``depth = min { |v| : E + v and K have disjoint interiors }``.  ``E + v`` is free of ``K =
{Q <= 0}`` exactly when ``g(v) = min over p in E of Q(p + v) >= 0``: a quadratic over an
ellipsoid, the trust-region subproblem, solved here through the eigenvalues of the quadratic form
in the ellipsoid's unit-ball coordinates and a bisection of its secular equation.  Along a ray
``t w``, the first ``t`` with ``g(t w) >= 0`` is found by a scan and a bisection, and the depth is
the least such ``t`` over directions: a grid of directions, then a local search from the best.
Binary64 throughout, about ``1e-9`` relative: independent of the certificates it checks (no
inscribed ellipsoid, no support function, no exact predicate).
"""

from __future__ import annotations

import numpy as np


def _form(M):
    M = np.asarray(M, dtype=float)
    return M[:3, :3], M[:3, 3], M[3, 3]


def least_on_ellipsoid(E, Q, v):
    """``min over p in E of Q(p + v)`` (``E``, ``Q`` float ``4 x 4`` matrices, ``E`` inside negative)."""
    A, a, e = _form(E)
    c = -np.linalg.solve(A, a)
    r = c @ A @ c - e
    w, U = np.linalg.eigh(A)
    L = U / np.sqrt(w / r)  # p = c + L s, |s| <= 1 is E
    B, b, q = _form(Q)
    x0 = c + v
    H = L.T @ B @ L
    g = L.T @ (B @ x0 + b)
    k = x0 @ B @ x0 + 2 * b @ x0 + q
    h, V = np.linalg.eigh(H)
    gp = V.T @ g
    best = np.inf
    if h[0] > 0:
        s = -gp / h
        if s @ s <= 1:
            best = k + gp @ s  # the interior minimum: k - g^T H^-1 g
    # the boundary: s = -(H + mu)^-1 g with |s| = 1, mu >= -h_min: the largest real root of
    # prod (h_i + mu)^2 - sum g_i^2 prod_(j != i) (h_j + mu)^2, then one Newton step
    sq = [np.polymul([1.0, x], [1.0, x]) for x in h]
    poly = np.polymul(np.polymul(sq[0], sq[1]), sq[2])
    for i in range(3):
        term = np.polymul(sq[(i + 1) % 3], sq[(i + 2) % 3]) * gp[i] ** 2
        poly = np.polysub(poly, term)
    roots = np.roots(poly)
    real = roots[np.abs(roots.imag) <= 1e-9 * (1 + np.abs(roots.real))].real
    real = real[real >= -h[0] - 1e-12 * (1 + abs(h[0]))]
    hi = float(np.max(real)) if real.size else max(0.0, -h[0])
    for _ in range(3):
        f = np.sum((gp / (h + hi)) ** 2) - 1
        df = -2 * np.sum(gp**2 / (h + hi) ** 3)
        if df != 0 and np.isfinite(f / df) and hi - f / df > -h[0]:
            hi -= f / df
    s = -gp / (h + hi)
    s = s / max(1.0, np.linalg.norm(s))
    on_sphere = k + 2 * gp @ s + s @ (h * s)
    return min(best, on_sphere)


def first_free(E, Q, w, t_max):
    """The least ``t`` in ``[0, t_max]`` with ``E + t w`` free of ``K`` (``inf`` if none)."""
    ts = np.linspace(0, t_max, 40)
    vals = [least_on_ellipsoid(E, Q, t * w) for t in ts]
    for i in range(1, len(ts)):
        if vals[i] >= 0:
            a, b = ts[i - 1], ts[i]
            for _ in range(45):
                m = 0.5 * (a + b)
                if least_on_ellipsoid(E, Q, m * w) >= 0:
                    b = m
                else:
                    a = m
            return b
    return np.inf


def depth(E, Q, t_max, grid=6):
    """The penetration depth of ``E`` into ``K = {Q <= 0}`` (both float matrices), about 9 digits."""
    th = np.linspace(0, np.pi, grid + 1)[1:-1]
    ph = np.linspace(0, 2 * np.pi, 2 * grid, endpoint=False)
    dirs = [np.array([np.sin(a) * np.cos(b), np.sin(a) * np.sin(b), np.cos(a)]) for a in th for b in ph]
    dirs += [np.array([0.0, 0, 1]), np.array([0.0, 0, -1])]
    coarse = [(first_free(E, Q, d, t_max), d) for d in dirs]
    coarse.sort(key=lambda x: x[0])
    best = np.inf
    for t0, d0 in coarse[:2]:
        d, t, step = d0, t0, 0.05
        e1 = np.cross(d, [1.0, 0, 0] if abs(d[0]) < 0.9 else [0, 1.0, 0])
        e1 /= np.linalg.norm(e1)
        e2 = np.cross(d, e1)
        while step > 1e-8:
            moved = False
            for a, b in ((1, 0), (-1, 0), (0, 1), (0, -1), (1, 1), (-1, -1), (1, -1), (-1, 1)):
                n = d + step * (a * e1 + b * e2)
                n /= np.linalg.norm(n)
                tn = first_free(E, Q, n, min(t_max, 1.5 * t))
                if tn < t:
                    d, t, moved = n, tn, True
                    e1 = np.cross(d, [1.0, 0, 0] if abs(d[0]) < 0.9 else [0, 1.0, 0])
                    e1 /= np.linalg.norm(e1)
                    e2 = np.cross(d, e1)
                    break
            if not moved:
                step /= 2
        best = min(best, t)
    return best
