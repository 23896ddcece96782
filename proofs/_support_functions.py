"""Support functions of ellipsoids, shared by the proofs of the distance certificates.

``E`` given by a matrix ``M`` (a binary64 ``numpy`` array, read as exact rationals) is the solid
``(x - c)^T A (x - c) <= r``; its support function is ``h(u) = u . c + sqrt(r u^T A^-1 u)``,
and for a second ellipsoid ``K``, ``phi(u) = h_E(u) + h_K(-u)`` is the support function of the
Minkowski difference ``E + (-K)``.
"""

from __future__ import annotations

from fractions import Fraction as F
from typing import Any


def _dot(p: Any, q: Any) -> Any:
    return sum(a * b for a, b in zip(p, q, strict=True))


def centred_exact(M: Any) -> tuple[list[list[F]], list[F], F]:
    """``A``, ``c_true`` and ``r`` of the solid ``(x - c)^T A (x - c) <= r`` of ``M`` (its entries
    read as exact rationals)."""
    Q = [[F(float(M[i, j])) for j in range(4)] for i in range(4)]
    A = [row[:3] for row in Q[:3]]
    a = [Q[i][3] for i in range(3)]

    def cof(i: int, j: int) -> F:
        i1, i2, j1, j2 = (i + 1) % 3, (i + 2) % 3, (j + 1) % 3, (j + 2) % 3
        return A[i1][j1] * A[i2][j2] - A[i1][j2] * A[i2][j1]

    adj = [[cof(j, i) for j in range(3)] for i in range(3)]
    det = _dot(A[0], [adj[j][0] for j in range(3)])
    c = [-_dot(adj[i], a) / det for i in range(3)]
    r = _dot(c, [_dot(A[i], c) for i in range(3)]) - Q[3][3]
    return A, c, r


def least_support(E: Any, K: Any, digits: int = 40) -> Any:
    """``min phi`` over the unit sphere: the exact rational matrices, a grid of directions in
    binary64, then Newton's method on the sphere at ``digits`` digits from the best four."""
    import mpmath
    import numpy as np

    geo = []
    for M in (E, K):
        A, c, r = centred_exact(M)
        geo.append((A, c, r))
    with mpmath.workdps(digits + 20):

        def mat(rows: Any) -> Any:
            return mpmath.matrix([[mpmath.mpf(x.numerator) / x.denominator for x in row] for row in rows])

        Ms = [mat(A) ** -1 * (mpmath.mpf(r.numerator) / r.denominator) for A, _c, r in geo]
        cd = mat([[geo[0][1][i] - geo[1][1][i]] for i in range(3)])

        def parts(u: Any) -> Any:
            m = [M * u for M in Ms]
            n = [mpmath.sqrt((u.T * mi)[0]) for mi in m]
            return m, n, (u.T * cd)[0] + n[0] + n[1]

        Mf = [np.array(M.tolist(), dtype=float) for M in Ms]
        cf = np.array(cd.T.tolist()[0], dtype=float)
        k = np.arange(3000) + 0.5
        zz = 1 - 2 * k / 3000
        ss = np.sqrt(1 - zz * zz)
        V = np.stack([ss * np.cos(np.pi * (1 + 5**0.5) * k), ss * np.sin(np.pi * (1 + 5**0.5) * k), zz], -1)
        vals = V @ cf + sum(np.sqrt(np.einsum("ij,jk,ik->i", V, Mi, V)) for Mi in Mf)
        best = mpmath.inf
        for i in np.argsort(vals)[:4]:
            u = mpmath.matrix([float(x) for x in V[i]])
            for _ in range(60):
                m, n, f = parts(u)
                g = cd + m[0] / n[0] + m[1] / n[1]
                H = Ms[0] / n[0] - m[0] * m[0].T / n[0] ** 3 + Ms[1] / n[1] - m[1] * m[1].T / n[1] ** 3
                P = mpmath.eye(3) - u * u.T
                p = mpmath.lu_solve(P * H * P - (u.T * g)[0] * P + u * u.T, -(P * g))
                u = (u + p) / mpmath.norm(u + p)
                if mpmath.norm(p) < mpmath.mpf(10) ** (-digits):
                    break
            best = min(best, parts(u)[2])
        return best
