"""The distance of two separated ellipsoids on stacks: a compiled kernel with a duality
certificate; the pairs it cannot certify go to the scalar certified path.

The certificate
---------------
For convex solids ``E`` and ``K`` apart, ``dist(E, K) = max over u != 0 of
-(h_E(u) + h_K(-u)) / |u|`` (``h`` the support functions: a plane of normal ``u`` between them),
and ``dist(E, K) <= |x - y|`` for any ``x`` in ``E`` and ``y`` in ``K``.  At the optimum the
two bounds meet.  The kernel finds ``u`` by Newton's method on ``grad phi(u) + lambda u = 0``,
``|u| = 1`` (``phi(u) = h_E(u) + h_K(-u)``, convex), then

* ``L``: a certified lower bound of ``-phi(u) / |u|``, with ``h`` read off the matrix
  ``[[A, a], [a^T, e]]`` itself around a float point ``c`` near the centre:
  ``h(v) = v . c - v^T adj(A) g / det A + sqrt(r v^T adj(A) v / det A)`` with ``g = A c + a``
  and ``r = -X_c^T E X_c + g^T adj(A) g / det A`` (exact identities), ``g`` and ``X_c^T E X_c``
  in twice the working precision (error-free transformations, Ogita, Rump and Oishi's Dot2),
  the other polynomials in binary64 with a static error bound (at most ``D`` roundings on
  every path: error ``<= gamma_D`` times the program on absolute values), the divisions and
  the root in interval arithmetic rounded outwards;
* ``U``: points ``x``, ``y`` near the support points, pulled towards the centres by a relative
  ``delta`` until ``X^T E X < 0`` and ``Y^T K Y < 0`` are certified (the points lie in the
  solids; the forms are evaluated in twice the working precision by error-free
  transformations, Ogita, Rump and Oishi's Dot2, so that ``delta`` can be ``1e-15``), and
  ``|x - y|`` rounded up.

``L <= dist <= U``; a pair is accepted when ``L > 0`` and ``U - L <= tol L``.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from quadric_contact.modes.kernels._jit import njit
from quadric_contact.modes.kernels.threads import kernel_stack, run_parallel

__all__ = ["dot2_bilinear", "separated_ellipsoids"]

_U = 2.0**-53
_GAMMA = (32 * _U / (1 - 32 * _U)) * (1 + 2.0**-40)
_TINY = 1e-290


@njit(inline=True)
def _dn(x: float) -> float:
    return np.nextafter(x, -np.inf)


@njit(inline=True)
def _up(x: float) -> float:
    return np.nextafter(x, np.inf)


@njit(inline=True)
def _adj3(M: Any, out: Any) -> None:
    """The adjugate of the leading 3x3 block of ``M`` (symmetric)."""
    out[0, 0] = M[1, 1] * M[2, 2] - M[1, 2] * M[2, 1]
    out[0, 1] = M[0, 2] * M[2, 1] - M[0, 1] * M[2, 2]
    out[0, 2] = M[0, 1] * M[1, 2] - M[0, 2] * M[1, 1]
    out[1, 1] = M[0, 0] * M[2, 2] - M[0, 2] * M[2, 0]
    out[1, 2] = M[0, 2] * M[1, 0] - M[0, 0] * M[1, 2]
    out[2, 2] = M[0, 0] * M[1, 1] - M[0, 1] * M[1, 0]
    out[1, 0] = out[0, 1]
    out[2, 0] = out[0, 2]
    out[2, 1] = out[1, 2]


@njit(inline=True)
def _adj3_abs(M: Any, out: Any) -> None:
    """The adjugate's magnitudes (every sign +) of the leading block of ``|M|``."""
    out[0, 0] = M[1, 1] * M[2, 2] + M[1, 2] * M[2, 1]
    out[0, 1] = M[0, 2] * M[2, 1] + M[0, 1] * M[2, 2]
    out[0, 2] = M[0, 1] * M[1, 2] + M[0, 2] * M[1, 1]
    out[1, 1] = M[0, 0] * M[2, 2] + M[0, 2] * M[2, 0]
    out[1, 2] = M[0, 2] * M[1, 0] + M[0, 0] * M[1, 2]
    out[2, 2] = M[0, 0] * M[1, 1] + M[0, 1] * M[1, 0]
    out[1, 0] = out[0, 1]
    out[2, 0] = out[0, 2]
    out[2, 1] = out[1, 2]


@njit(inline=True)
def _minor3(P: Any, c0: int, c1: int, c2: int) -> tuple[float, float]:
    """The minor of rows 1, 2, 3 and columns ``c0, c1, c2``, and its magnitude."""
    v = (
        P[1, c0] * (P[2, c1] * P[3, c2] - P[2, c2] * P[3, c1])
        - P[1, c1] * (P[2, c0] * P[3, c2] - P[2, c2] * P[3, c0])
        + P[1, c2] * (P[2, c0] * P[3, c1] - P[2, c1] * P[3, c0])
    )
    m = (
        abs(P[1, c0]) * (abs(P[2, c1] * P[3, c2]) + abs(P[2, c2] * P[3, c1]))
        + abs(P[1, c1]) * (abs(P[2, c0] * P[3, c2]) + abs(P[2, c2] * P[3, c0]))
        + abs(P[1, c2]) * (abs(P[2, c0] * P[3, c1]) + abs(P[2, c1] * P[3, c0]))
    )
    return v, m


@njit(inline=True)
def _det4(P: Any) -> tuple[float, float]:
    """``det P`` and its error bound (cofactors along the first row)."""
    v0, m0 = _minor3(P, 1, 2, 3)
    v1, m1 = _minor3(P, 0, 2, 3)
    v2, m2 = _minor3(P, 0, 1, 3)
    v3, m3 = _minor3(P, 0, 1, 2)
    v = P[0, 0] * v0 - P[0, 1] * v1 + P[0, 2] * v2 - P[0, 3] * v3
    m = abs(P[0, 0]) * m0 + abs(P[0, 1]) * m1 + abs(P[0, 2]) * m2 + abs(P[0, 3]) * m3
    return v, m * _GAMMA + _TINY


@njit(inline=True)
def _inside_negative(M: Any) -> bool:
    """Make ``A`` of ``M`` positive (negating ``M`` if needed); is its 2x2 leading minor
    certainly positive (with ``det A > 0`` and ``det M < 0`` checked later: an ellipsoid)?"""
    if M[0, 0] < 0:
        for i in range(4):
            for j in range(4):
                M[i, j] = -M[i, j]
    d2 = M[0, 0] * M[1, 1] - M[0, 1] * M[1, 0]
    e2 = (abs(M[0, 0] * M[1, 1]) + abs(M[0, 1] * M[1, 0])) * _GAMMA + _TINY
    return M[0, 0] > 0 and d2 > e2


@njit(inline=True)
def _solve4(J: Any, F: Any, x: Any) -> bool:
    """``J x = F`` by Gaussian elimination with partial pivoting (``J``, ``F`` overwritten)."""
    for c in range(4):
        p = c
        for r in range(c + 1, 4):
            if abs(J[r, c]) > abs(J[p, c]):
                p = r
        if J[p, c] == 0.0:
            return False
        if p != c:
            for j in range(4):
                J[c, j], J[p, j] = J[p, j], J[c, j]
            F[c], F[p] = F[p], F[c]
        for r in range(c + 1, 4):
            f = J[r, c] / J[c, c]
            for j in range(c, 4):
                J[r, j] -= f * J[c, j]
            F[r] -= f * F[c]
    for c in range(3, -1, -1):
        acc = F[c]
        for j in range(c + 1, 4):
            acc -= J[c, j] * x[j]
        x[c] = acc / J[c, c]
    return True


@njit(inline=True)
def _mv(M: Any, u: Any, out: Any) -> float:
    """``out = M u``; returns ``u . M u``."""
    s = 0.0
    for i in range(3):
        out[i] = M[i, 0] * u[0] + M[i, 1] * u[1] + M[i, 2] * u[2]
        s += u[i] * out[i]
    return s


@njit(inline=True)
def _split(a: float) -> tuple[float, float]:
    c = 134217729.0 * a  # 2^27 + 1 (Dekker)
    h = c - (c - a)
    return h, a - h


@njit(inline=True)
def _two_product(a: float, b: float) -> tuple[float, float]:
    """``a b = p + e`` exactly (Dekker; no overflow or underflow assumed: checked by the
    caller's finiteness of the result)."""
    p = a * b
    ah, al = _split(a)
    bh, bl = _split(b)
    e = al * bl - (((p - ah * bh) - al * bh) - ah * bl)
    return p, e


@njit(inline=True)
def _two_sum(a: float, b: float) -> tuple[float, float]:
    s = a + b
    z = s - a
    return s, (a - (s - z)) + (b - z)


@njit(inline=True)
def dot2_bilinear(M: Any, P: Any, Q: Any) -> tuple[float, float]:
    """``P^T M Q`` over the leading ``n x n`` block of ``M`` (``P``, ``Q`` tuples of ``n`` floats)
    as a dot product of length ``2 n^2`` with exact terms: ``P_i Q_j`` split exactly into
    ``h + l``, then Ogita-Rump-Oishi's Dot2, whose result errs by at most
    ``u |exact| + gamma_(2 n^2)^2 |M| . |P Q^T|`` (a twice-working-precision accuracy); an
    infinite bound where anything overflowed."""
    n = len(P)
    p = 0.0
    s = 0.0
    mag = 0.0
    for i in range(n):
        for j in range(n):
            hi_, lo_ = _two_product(P[i], Q[j])
            for f in (hi_, lo_):
                t, r = _two_product(M[i, j], f)
                p, q = _two_sum(p, t)
                s = s + (q + r)
                mag += abs(M[i, j] * f)
    res = p + s
    m = 2 * n * n
    g = m * _U / (1 - m * _U)
    err = (2 * _U * abs(res) + 2 * g * g * mag) * (1 + 2.0**-40) + _TINY
    if not math.isfinite(res) or not math.isfinite(mag) or mag > 1e290:
        return res, np.inf
    return res, err


@njit(inline=True)
def _form_accurate(M: Any, x0: float, x1: float, x2: float) -> tuple[float, float]:
    """``X^T M X`` (``X = (x, 1)``) in twice the working precision (:func:`dot2_bilinear`)."""
    X = (x0, x1, x2, 1.0)
    return dot2_bilinear(M, X, X)


@njit(inline=True)
def _dot_accurate(M: Any, i: int, c0: float, c1: float, c2: float) -> tuple[float, float]:
    """``g_i = M[i, :3] . c + M[i, 3]`` in twice the working precision (Dot2) and its bound."""
    X = (c0, c1, c2, 1.0)
    p = 0.0
    s = 0.0
    mag = 0.0
    for j in range(4):
        t, r = _two_product(M[i, j], X[j])
        p, q = _two_sum(p, t)
        s = s + (q + r)
        mag += abs(M[i, j] * X[j])
    res = p + s
    g4 = 4 * _U / (1 - 4 * _U)
    return res, (2 * _U * abs(res) + 2 * g4 * g4 * mag) * (1 + 2.0**-40) + _TINY


@njit(inline=True)
def _support(
    M: Any, adj: Any, adja: Any, detA: float, eA: float, c: Any, u: Any, sgn: float
) -> tuple[float, float]:
    """An enclosure of ``h(v)``, ``v = sgn u``, the support function of ``X^T M X <= 0``, read
    off the matrix around a float point ``c`` (near the centre): with ``g = A c + a`` and
    ``k = X_c^T M X_c``, ``h(v) = v . c - v^T adj(A) g / det A + sqrt(r v^T adj(A) v / det A)``,
    ``r = -k + g^T adj(A) g / det A`` (exact identities: the centre is ``c - A^-1 g``)."""
    g0, e0 = _dot_accurate(M, 0, c[0], c[1], c[2])
    g1, e1 = _dot_accurate(M, 1, c[0], c[1], c[2])
    g2, e2 = _dot_accurate(M, 2, c[0], c[1], c[2])
    g = (g0, g1, g2)
    eg = (e0, e1, e2)
    k, ek = _form_accurate(M, c[0], c[1], c[2])
    # w = v^T adj g, q = g^T adj g, p2 = u^T adj u: values and error bounds
    w = 0.0
    wm = 0.0
    wd = 0.0
    q = 0.0
    qm = 0.0
    qd = 0.0
    p2 = 0.0
    m2 = 0.0
    for i in range(3):
        for j in range(3):
            aij = abs(adj[i, j]) + adja[i, j] * _GAMMA
            w += sgn * u[i] * adj[i, j] * g[j]
            wm += abs(u[i]) * adja[i, j] * abs(g[j])
            wd += abs(u[i]) * aij * eg[j]
            q += g[i] * adj[i, j] * g[j]
            qm += abs(g[i]) * adja[i, j] * abs(g[j])
            qd += aij * (eg[i] * (abs(g[j]) + eg[j]) + abs(g[i]) * eg[j])
            p2 += u[i] * adj[i, j] * u[j]
            m2 += abs(u[i]) * adja[i, j] * abs(u[j])
    ew = (wm * _GAMMA + wd) * (1 + 2.0**-40) + _TINY
    eq = (qm * _GAMMA + qd) * (1 + 2.0**-40) + _TINY
    ep2 = m2 * _GAMMA + _TINY
    dl, dh = detA - eA, detA + eA
    # r = -k + q / det A, an enclosure (q >= 0 up to its error)
    ql, qh = q - eq, q + eq
    rl = _dn(-(k + ek) + (_dn(ql / dh) if ql >= 0 else _dn(ql / dl)))
    rh = _up(-(k - ek) + (_up(qh / dl) if qh >= 0 else _up(qh / dh)))
    # the root term sqrt(r p2 / det A)
    pl, ph = max(p2 - ep2, 0.0), p2 + ep2
    tl = _dn(_dn(max(rl, 0.0) * pl) / dh)
    th = _up(_up(rh * ph) / dl)
    sl = _dn(math.sqrt(max(tl, 0.0)))
    sh = _up(math.sqrt(th))
    # the linear terms: v . c and -w / det A
    vc = sgn * (u[0] * c[0] + u[1] * c[1] + u[2] * c[2])
    evc = (abs(u[0] * c[0]) + abs(u[1] * c[1]) + abs(u[2] * c[2])) * 3 * _U * (1 + 2.0**-40) + _TINY
    wl, wh = -(w + ew), -(w - ew)
    tl2 = _dn(wl / dh) if wl >= 0 else _dn(wl / dl)
    th2 = _up(wh / dl) if wh >= 0 else _up(wh / dh)
    lo = _dn(_dn(_dn(vc - evc) + tl2) + sl)
    hi = _up(_up(_up(vc + evc) + th2) + sh)
    return lo, hi


@njit
def _kernel(
    Es: Any, Ks: Any, tol: float, out: Any, flag: Any, start: int, stop: int
) -> None:  # pragma: no cover
    adj1 = np.empty((3, 3))
    adj2 = np.empty((3, 3))
    ad1 = np.empty((3, 3))
    ad2 = np.empty((3, 3))
    M1 = np.empty((3, 3))
    M2 = np.empty((3, 3))
    c1 = np.empty(3)
    c2 = np.empty(3)
    u = np.empty(3)
    J = np.empty((4, 4))
    F = np.empty(4)
    step = np.empty(4)
    m1 = np.empty(3)
    m2 = np.empty(3)
    for k in range(start, stop):
        out[k, 0] = -np.inf
        out[k, 1] = np.inf
        flag[k] = 1
        E = Es[k].copy()
        K = Ks[k].copy()
        ok = True
        for i in range(4):
            for j in range(4):
                if not (math.isfinite(E[i, j]) and math.isfinite(K[i, j])):
                    ok = False
        if not ok:
            continue
        # both ellipsoids with the inside negative: A positive definite, det < 0
        if not (_inside_negative(E) and _inside_negative(K)):
            continue
        _adj3(E, adj1)
        _adj3(K, adj2)
        Ea = np.abs(E)
        Ka = np.abs(K)
        _adj3_abs(Ea, ad1)
        _adj3_abs(Ka, ad2)
        detA1 = E[0, 0] * adj1[0, 0] + E[0, 1] * adj1[1, 0] + E[0, 2] * adj1[2, 0]
        eA1 = (Ea[0, 0] * ad1[0, 0] + Ea[0, 1] * ad1[1, 0] + Ea[0, 2] * ad1[2, 0]) * _GAMMA + _TINY
        detA2 = K[0, 0] * adj2[0, 0] + K[0, 1] * adj2[1, 0] + K[0, 2] * adj2[2, 0]
        eA2 = (Ka[0, 0] * ad2[0, 0] + Ka[0, 1] * ad2[1, 0] + Ka[0, 2] * ad2[2, 0]) * _GAMMA + _TINY
        detE, eE = _det4(E)
        detK, eK = _det4(K)
        if not (detA1 > eA1 and detA2 > eA2 and detE < -eE and detK < -eK):
            continue
        # float centres and the matrices M = r A^-1 of the support functions
        r1 = -detE / detA1
        r2 = -detK / detA2
        for i in range(3):
            c1[i] = -(adj1[i, 0] * E[0, 3] + adj1[i, 1] * E[1, 3] + adj1[i, 2] * E[2, 3]) / detA1
            c2[i] = -(adj2[i, 0] * K[0, 3] + adj2[i, 1] * K[1, 3] + adj2[i, 2] * K[2, 3]) / detA2
            for j in range(3):
                M1[i, j] = r1 * adj1[i, j] / detA1
                M2[i, j] = r2 * adj2[i, j] / detA2
        # Newton on grad phi(u) + lam u = 0, |u|^2 = 1; phi(u) = u.(c1 - c2) + |u|_M1 + |u|_M2
        nrm = 0.0
        for i in range(3):
            u[i] = c2[i] - c1[i]
            nrm += u[i] * u[i]
        nrm = math.sqrt(nrm)
        if nrm == 0.0:
            continue
        for i in range(3):
            u[i] /= nrm
        lam = nrm
        for _ in range(40):
            q1 = _mv(M1, u, m1)
            q2 = _mv(M2, u, m2)
            s1 = math.sqrt(max(q1, 1e-300))
            s2 = math.sqrt(max(q2, 1e-300))
            for i in range(3):
                F[i] = c1[i] - c2[i] + m1[i] / s1 + m2[i] / s2 + lam * u[i]
                for j in range(3):
                    J[i, j] = (
                        M1[i, j] / s1
                        - m1[i] * m1[j] / (s1 * s1 * s1)
                        + M2[i, j] / s2
                        - m2[i] * m2[j] / (s2 * s2 * s2)
                        + (lam if i == j else 0.0)
                    )
                J[i, 3] = u[i]
                J[3, i] = 2 * u[i]
            J[3, 3] = 0.0
            F[3] = u[0] * u[0] + u[1] * u[1] + u[2] * u[2] - 1.0
            if not _solve4(J, F, step):
                break
            for i in range(3):
                u[i] -= step[i]
            lam -= step[3]
            if abs(step[0]) + abs(step[1]) + abs(step[2]) < 1e-15:
                break
        if not (lam > 0):
            continue
        # L: a certified lower bound of -phi(u) / |u|
        h1l, h1h = _support(E, adj1, ad1, detA1, eA1, c1, u, 1.0)
        h2l, h2h = _support(K, adj2, ad2, detA2, eA2, c2, u, -1.0)
        phih = _up(h1h + h2h)
        if not (phih < 0):
            continue
        un2 = _up(_up(_up(u[0] * u[0]) + _up(u[1] * u[1])) + _up(u[2] * u[2]))
        L = _dn(-phih / _up(math.sqrt(un2)))
        # U: points of the solids near the support points, |x - y| rounded up
        s1 = math.sqrt(_mv(M1, u, m1))
        s2 = math.sqrt(_mv(M2, u, m2))
        delta = 1e-15
        Uok = False
        Ub = np.inf
        for _ in range(6):
            x0 = c1[0] + (1 - delta) * m1[0] / s1
            x1 = c1[1] + (1 - delta) * m1[1] / s1
            x2 = c1[2] + (1 - delta) * m1[2] / s1
            y0 = c2[0] - (1 - delta) * m2[0] / s2
            y1 = c2[1] - (1 - delta) * m2[1] / s2
            y2 = c2[2] - (1 - delta) * m2[2] / s2
            vE, eEx = _form_accurate(E, x0, x1, x2)
            vK, eKy = _form_accurate(K, y0, y1, y2)
            if vE < -eEx and vK < -eKy:
                d0 = max(abs(_up(x0 - y0)), abs(_dn(x0 - y0)))
                d1 = max(abs(_up(x1 - y1)), abs(_dn(x1 - y1)))
                d2 = max(abs(_up(x2 - y2)), abs(_dn(x2 - y2)))
                Ub = _up(math.sqrt(_up(_up(_up(d0 * d0) + _up(d1 * d1)) + _up(d2 * d2))))
                Uok = True
                break
            delta *= 10.0
        if Uok and L > 0 and Ub - L <= tol * L:
            out[k, 0] = L
            out[k, 1] = Ub
            flag[k] = 0


def separated_ellipsoids(Es: np.ndarray, Ks: np.ndarray, tol: float = 1e-12) -> tuple[np.ndarray, np.ndarray]:
    """Enclosures ``(n, 2)`` of the distance of separated ellipsoid pairs (float64 stacks
    ``(n, 4, 4)``) at most ``tol`` relative wide, and a mask of the pairs left to the scalar
    path (crossing, touching or too near, not both ellipsoids, or not certified).

    Examples
    --------
    >>> E = np.diag([1.0, 1.0, 1.0, -1.0]); K = E.copy(); K[0, 3] = K[3, 0] = -4.0; K[3, 3] = 15.0
    >>> enc, rest = separated_ellipsoids(E[None], K[None])   # unit balls at 0 and (4, 0, 0)
    >>> bool(enc[0, 0] <= 2.0 <= enc[0, 1]), bool(rest[0])
    (True, False)
    """
    Es = kernel_stack(Es)
    Ks = kernel_stack(Ks)
    n = Es.shape[0]
    out = np.empty((n, 2))
    flag = np.empty(n, dtype=np.uint8)
    run_parallel(lambda a, b: _kernel(Es, Ks, float(tol), out, flag, a, b), n)
    return out, flag.astype(bool)
