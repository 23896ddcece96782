"""Random rational convex solids cut by planes, and an independent brute-force minimiser of
their distance from an ellipsoid, shared by the proof of the distance to cut pieces and its tests.

The brute force enumerates: no barrier, duality or support function is involved.
"""

from __future__ import annotations

import itertools
from fractions import Fraction as F
from typing import Any


def rotation(rng: Any) -> list[list[Any]]:
    """A rational rotation from an integer quaternion."""
    a, b, c, d = (int(v) for v in rng.integers(-4, 5, 4))
    if a == b == c == d == 0:
        a = 1
    n = a * a + b * b + c * c + d * d
    return [
        [F(a * a + b * b - c * c - d * d, n), F(2 * (b * c - a * d), n), F(2 * (b * d + a * c), n)],
        [F(2 * (b * c + a * d), n), F(a * a - b * b + c * c - d * d, n), F(2 * (c * d - a * b), n)],
        [F(2 * (b * d - a * c), n), F(2 * (c * d + a * b), n), F(a * a - b * b - c * c + d * d, n)],
    ]


def moved(S: Any, R: Any, t: Any) -> list[list[Any]]:
    """``S(R^T (y - t))`` as a 4x4 matrix of Fractions."""
    Tinv = [[R[j][i] for j in range(3)] + [-sum(R[j][i] * t[j] for j in range(3))] for i in range(3)]
    Tinv.append([F(0), F(0), F(0), F(1)])
    return [
        [sum(Tinv[k][i] * S[k][m] * Tinv[m][j] for k in range(4) for m in range(4)) for j in range(4)]
        for i in range(4)
    ]


def diag(a: Any, b: Any, c: Any, lin: Any = (0, 0, 0), const: Any = 0) -> list[list[Any]]:
    """The matrix of ``a x^2 + b y^2 + c z^2 + 2 lin . (x, y, z) + const``, in Fractions."""
    z = F(0)
    return [
        [F(a), z, z, F(lin[0])],
        [z, F(b), z, F(lin[1])],
        [z, z, F(c), F(lin[2])],
        [F(lin[0]), F(lin[1]), F(lin[2]), F(const)],
    ]


def standard(kind: str, rng: Any) -> tuple[list[list[Any]], tuple[int, int, int]]:
    """The standard solid of a convex kind (inside negative, curvatures 1/2 to 2) and a point
    inside it."""
    k = [F(int(v), 4) for v in rng.integers(2, 9, 3)]
    return {
        "ellipsoid": (diag(k[0], k[1], k[2], const=-2), (0, 0, 0)),
        "elliptic paraboloid": (diag(k[0], k[1], 0, lin=(0, 0, F(-1, 2))), (0, 0, 1)),
        "elliptic cylinder": (diag(k[0], k[1], 0, const=-2), (0, 0, 0)),
        "parabolic cylinder": (diag(k[0], 0, 0, lin=(0, 0, F(-1, 2))), (0, 0, 1)),
        "parallel planes": (diag(0, 0, k[2], const=-1), (0, 0, 0)),
        "plane": (diag(0, 0, 0, lin=(0, 0, F(1, 2))), (0, 0, -1)),
    }[kind]


KINDS = (
    "ellipsoid",
    "elliptic paraboloid",
    "elliptic cylinder",
    "parabolic cylinder",
    "parallel planes",
    "plane",
)


def brute(E: Any, K: Any, hs: Any, inner: Any, digits: int = 40) -> Any:
    """``min |x - y|`` by enumeration: sampled points give starts; from the best three, the
    Lagrange system of every set of active constraints (``E`` and at most three of ``K`` and the
    planes) is solved by Newton's method; the least distance among the feasible solutions.  None
    when the sampled solids come within ``0.05`` or too few samples fall in the piece."""
    import mpmath
    import numpy as np

    Ef = np.array([[float(E[i, j]) for j in range(4)] for i in range(4)])
    Kf = np.array([[float(K[i, j]) for j in range(4)] for i in range(4)])
    N = np.array([[float(v) for v in h.n] for h in hs])
    d = np.array([float(h.d) for h in hs])
    A = Ef[:3, :3]
    c = -np.linalg.solve(A, Ef[:3, 3])
    r = c @ A @ c - Ef[3, 3]
    vals, vecs = np.linalg.eigh(A / r)
    rng = np.random.default_rng(0)
    u = rng.normal(size=(600, 3))
    u /= np.linalg.norm(u, axis=1)[:, None]
    xs = c + (u / np.sqrt(vals)) @ vecs.T
    half = np.linalg.norm(c - np.array(inner)) / 2 + 3
    box = rng.uniform(-1, 1, (100000, 3)) * half + (c + np.array(inner)) / 2
    form = np.einsum("ni,ij,nj->n", box, Kf[:3, :3], box) + 2 * box @ Kf[:3, 3] + Kf[3, 3]
    ys = box[(form <= 0) & np.all(box @ N.T <= d, axis=1)][:4000]
    if len(ys) < 50:
        return None
    gaps = np.linalg.norm(xs[:, None, :] - ys[None, :, :], axis=2)
    if gaps.min() < 0.05:
        return None
    best = None
    with mpmath.workdps(digits + 10):

        def m(v: Any) -> Any:
            return mpmath.mpf(v.numerator) / v.denominator

        EA = [[m(E[i, j]) for j in range(4)] for i in range(4)]
        KA = [[m(K[i, j]) for j in range(4)] for i in range(4)]
        ns = [[m(v) for v in h.n] for h in hs]
        ds = [m(h.d) for h in hs]

        def form4(Q: Any, p: Any) -> Any:
            X = [*p, 1]
            return sum(Q[i][j] * X[i] * X[j] for i in range(4) for j in range(4))

        def grad(Q: Any, p: Any) -> Any:
            X = [*p, 1]
            return [2 * sum(Q[i][j] * X[j] for j in range(4)) for i in range(3)]

        subsets = [s for k in range(4) for s in itertools.combinations(["K", *range(len(hs))], k)]
        for flat in np.argsort(gaps, axis=None)[:300:100]:
            i, j = np.unravel_index(flat, gaps.shape)
            for s in subsets:

                def system(*z: Any, s: Any = s) -> list[Any]:
                    x, y, a, mult = z[0:3], z[3:6], z[6], z[7:]
                    gy = [mpmath.mpf(0)] * 3
                    eqs = []
                    for which, lam in zip(s, mult, strict=True):
                        g = grad(KA, y) if which == "K" else ns[which]
                        gy = [gy[k] + lam * g[k] for k in range(3)]
                        eqs.append(
                            form4(KA, y)
                            if which == "K"
                            else sum(ns[which][k] * y[k] for k in range(3)) - ds[which]
                        )
                    ge = grad(EA, x)
                    return [
                        *(x[k] - y[k] + a * ge[k] for k in range(3)),
                        *(y[k] - x[k] + gy[k] for k in range(3)),
                        form4(EA, x),
                        *eqs,
                    ]

                try:
                    z = mpmath.findroot(
                        system, [*xs[i], *ys[j], 0.3, *([0.3] * len(s))], tol=mpmath.mpf(10) ** (-2 * digits)
                    )
                except (ZeroDivisionError, ValueError, TypeError):  # (a singular system; NaN pivots)
                    continue
                x, y = z[0:3], z[3:6]
                tiny = mpmath.mpf(10) ** (-digits)
                if form4(EA, x) > tiny or form4(KA, y) > tiny:
                    continue
                if any(sum(ns[q][k] * y[k] for k in range(3)) - ds[q] > tiny for q in range(len(hs))):
                    continue
                dist = mpmath.sqrt(sum((x[k] - y[k]) ** 2 for k in range(3)))
                best = dist if best is None else min(best, dist)
    return best
