"""The first-contact scale on stacks, in blocks: the certificate of
:mod:`quadric_contact.modes.distance.scale_kernel` laid out for the vector unit.

:mod:`quadric_contact.modes.distance.scale_kernel` states the certificate and the error bounds; this module
computes the same signs and the same enclosure for many pairs at once:

1. a gather copies a block of :data:`NB` pairs into column buffers (one row per upper entry; ``E``
   multiplied by ``-1`` when ``E[0, 0] < 0``, which is the scalar kernel's choice of sign: its
   ``A`` is certified positive definite for one sign at most, and only for the sign with
   ``E[0, 0] > 0``);
2. straight-line loops over the block, with no branch and no transcendental function (so that
   LLVM vectorises them):

   * the checks of the scalar kernel (finite entries; ``Q`` certainly nondegenerate, or a plane;
     ``A`` certainly positive definite; ``det E`` certainly negative; the sign of ``f(0)``
     certain);
   * :data:`NEWTON` steps of the search, each kept inside the bracket of the scalar kernel (in
     ``w = mu / (1 + |mu|)``; a step that leaves it bisects it, except a step shorter than
     ``10^-12 |mu|``, Newton's near the root, which is taken as it is).  Where ``Q`` is an ellipsoid
     and the root is at ``mu > 0`` the step is Newton's on
     ``phi(mu) = (f(mu) - f_inf)^(-1/2)`` rather than on ``f`` (``f_inf = Q(c_Q)``, the value of
     ``Q`` at its centre and the limit of ``f`` at ``+inf``): ``phi`` is affine in ``mu`` for two
     spheres, and the search ends in about five steps where Newton's method on ``f`` takes
     fifteen.  The search is floats only: nothing trusts it;
   * the offset ``rel`` of the two certificate points ``mu (1 -+ rel)`` from the error bound of
     ``Y^T Q Y`` at the root over its slope (four times the noise, within ``[1e-13, 1e-5]``);
   * the certificate at the two points, as the scalar kernel computes it: the leading minors of
     ``A + mu Q00`` and ``Y^T Q Y`` with their bounds ``gamma_D`` times the magnitude program,
     and the enclosure of ``s(mu)^2`` from ``Y^T E Y``, ``Y_4``, ``det A`` and ``det E``;
3. a scalar loop writes the enclosures and hands every pair not certified in the block (a check
   that failed, or signs not certain at the two points: mostly a search not finished in
   :data:`NEWTON` steps) to the scalar kernel, which answers it or leaves it to the exact path.

The blocks read the upper triangles of ``E`` and ``Q``: the inputs are symmetric (the public
functions check it).

Two things differ from the scalar kernel in how the numbers are computed, not in what is
certified.  The quadratic forms ``Y^T W Y`` are summed row by row (``sum_i y_i (sum_j W_ij
y_j)``, 15 roundings on the longest path instead of 25, within ``D = 32``; the magnitude program
is the same sum on absolute values).  The outward roundings use ``x -+ (2^-50 |x| + 10^-300)``
in place of ``nextafter`` (which does not vectorise): ``2^-50 |x| >= 4 ulp(x)``, so after the
rounding of the sum ``x`` has moved by at least two units in the last place, as two calls of
``nextafter`` move it, or farther (the enclosure only widens).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from quadric_contact._generated import blocks
from quadric_contact.modes.distance.scale_kernel import _GAMMA, _TINY, _U
from quadric_contact.modes.distance.scale_kernel import _kernel as _scalar
from quadric_contact.modes.kernels._jit import njit
from quadric_contact.modes.kernels.threads import kernel_stack, run_parallel

__all__ = ["NB", "NEWTON", "scale_blocks", "scale_stack"]

NB = 32
"""Pairs per block."""
NEWTON = 8
"""Steps of the search in the block; a pair not certified after them goes to the scalar kernel."""

_G = _GAMMA
_T = _TINY
_INF = math.inf
_W = 2.0**-50
_R40 = 1 + 2.0**-40
_load = njit(blocks.load_upper, inline=True)


@njit(inline=True)
def gather_signed(M: Any, k: int, b: Any, t: int, S: int, sign: float) -> None:  # pragma: no cover
    """Column ``t`` of the block buffer ``b``: the ten upper entries of ``sign * M[k]`` (``M``
    a stack ``(n, 4, 4)``)."""
    b[t] = sign * M[k, 0, 0]
    b[S + t] = sign * M[k, 0, 1]
    b[2 * S + t] = sign * M[k, 0, 2]
    b[3 * S + t] = sign * M[k, 0, 3]
    b[4 * S + t] = sign * M[k, 1, 1]
    b[5 * S + t] = sign * M[k, 1, 2]
    b[6 * S + t] = sign * M[k, 1, 3]
    b[7 * S + t] = sign * M[k, 2, 2]
    b[8 * S + t] = sign * M[k, 2, 3]
    b[9 * S + t] = sign * M[k, 3, 3]


@njit(inline=True)
def signed_upper(M: Any, k: int, sign: float) -> Any:  # pragma: no cover
    """The ten upper entries of ``sign * M[k]`` (``M`` a stack ``(n, 4, 4)``), as a tuple."""
    return (
        sign * M[k, 0, 0],
        sign * M[k, 0, 1],
        sign * M[k, 0, 2],
        sign * M[k, 0, 3],
        sign * M[k, 1, 1],
        sign * M[k, 1, 2],
        sign * M[k, 1, 3],
        sign * M[k, 2, 2],
        sign * M[k, 2, 3],
        sign * M[k, 3, 3],
    )


@njit(inline=True)
def _det3(
    a00: float, a01: float, a02: float, a10: float, a11: float, a12: float, a20: float, a21: float, a22: float
) -> float:
    """A 3x3 determinant by the first row (the expression of the scalar kernel's ``_det3``)."""
    return a00 * (a11 * a22 - a12 * a21) - a01 * (a10 * a22 - a12 * a20) + a02 * (a10 * a21 - a11 * a20)


@njit(inline=True)
def _mag3(
    a00: float, a01: float, a02: float, a10: float, a11: float, a12: float, a20: float, a21: float, a22: float
) -> float:
    """The magnitude program of :func:`_det3` (entries ``>= 0``, every sign made +)."""
    return a00 * (a11 * a22 + a12 * a21) + a01 * (a10 * a22 + a12 * a20) + a02 * (a10 * a21 + a11 * a20)


@njit(inline=True)
def _cofactors(p: Any) -> tuple[float, float, float, float]:
    """``Y = adj(P) e_4`` of a symmetric ``P`` (ten upper entries), as the scalar kernel."""
    p00, p01, p02, p03, p11, p12, p13, p22, p23, p33 = p
    y0 = -_det3(p01, p11, p12, p02, p12, p22, p03, p13, p23)
    y1 = _det3(p00, p01, p02, p02, p12, p22, p03, p13, p23)
    y2 = -_det3(p00, p01, p02, p01, p11, p12, p03, p13, p23)
    y3 = _det3(p00, p01, p02, p01, p11, p12, p02, p12, p22)
    return y0, y1, y2, y3


@njit(inline=True)
def _cofactors_mag(p: Any) -> tuple[float, float, float, float]:
    """The magnitude programs of :func:`_cofactors` (``p`` the absolute entries)."""
    p00, p01, p02, p03, p11, p12, p13, p22, p23, p33 = p
    a0 = _mag3(p01, p11, p12, p02, p12, p22, p03, p13, p23)
    a1 = _mag3(p00, p01, p02, p02, p12, p22, p03, p13, p23)
    a2 = _mag3(p00, p01, p02, p01, p11, p12, p03, p13, p23)
    a3 = _mag3(p00, p01, p02, p01, p11, p12, p02, p12, p22)
    return a0, a1, a2, a3


@njit(inline=True)
def _det4(p: Any) -> float:
    """``det P`` by the first row (the expression of the scalar kernel's ``_det4``)."""
    p00, p01, p02, p03, p11, p12, p13, p22, p23, p33 = p
    return (
        p00 * _det3(p11, p12, p13, p12, p22, p23, p13, p23, p33)
        - p01 * _det3(p01, p12, p13, p02, p22, p23, p03, p23, p33)
        + p02 * _det3(p01, p11, p13, p02, p12, p23, p03, p13, p33)
        - p03 * _det3(p01, p11, p12, p02, p12, p22, p03, p13, p23)
    )


@njit(inline=True)
def _mag4(p: Any) -> float:
    """The magnitude program of :func:`_det4`."""
    p00, p01, p02, p03, p11, p12, p13, p22, p23, p33 = p
    return (
        p00 * _mag3(p11, p12, p13, p12, p22, p23, p13, p23, p33)
        + p01 * _mag3(p01, p12, p13, p02, p22, p23, p03, p23, p33)
        + p02 * _mag3(p01, p11, p13, p02, p12, p23, p03, p13, p33)
        + p03 * _mag3(p01, p11, p12, p02, p12, p22, p03, p13, p23)
    )


@njit(inline=True)
def _form(y: Any, w: Any) -> float:
    """``Y^T W Y`` summed row by row (``W`` symmetric, ten upper entries)."""
    y0, y1, y2, y3 = y
    w00, w01, w02, w03, w11, w12, w13, w22, w23, w33 = w
    return (
        y0 * (w00 * y0 + w01 * y1 + w02 * y2 + w03 * y3)
        + y1 * (w01 * y0 + w11 * y1 + w12 * y2 + w13 * y3)
        + y2 * (w02 * y0 + w12 * y1 + w22 * y2 + w23 * y3)
        + y3 * (w03 * y0 + w13 * y1 + w23 * y2 + w33 * y3)
    )


@njit(inline=True)
def _abs10(a: Any) -> Any:
    return (
        abs(a[0]),
        abs(a[1]),
        abs(a[2]),
        abs(a[3]),
        abs(a[4]),
        abs(a[5]),
        abs(a[6]),
        abs(a[7]),
        abs(a[8]),
        abs(a[9]),
    )


@njit(inline=True)
def _pencil(e: Any, q: Any, mu: float) -> Any:
    """``E + mu Q`` (ten upper entries)."""
    return (
        e[0] + mu * q[0],
        e[1] + mu * q[1],
        e[2] + mu * q[2],
        e[3] + mu * q[3],
        e[4] + mu * q[4],
        e[5] + mu * q[5],
        e[6] + mu * q[6],
        e[7] + mu * q[7],
        e[8] + mu * q[8],
        e[9] + mu * q[9],
    )


@njit(inline=True)
def _times(x: float, ex: float, y: float, ey: float) -> tuple[float, float]:
    """The product of ``x +- ex`` and ``y +- ey``: a value and a bound (as the scalar kernel)."""
    p = x * y
    e = ((abs(x) + ex) * (abs(y) + ey) - abs(x) * abs(y) + abs(p) * 8 * _U) * _R40 + _T
    return p, e


@njit(inline=True)
def _down(x: float) -> float:
    """Below ``x`` by at least two units in the last place (``-inf`` stays; NaN stays NaN)."""
    return x - (abs(x) * _W + 1e-300)


@njit(inline=True)
def _up(x: float) -> float:
    """Above ``x`` by at least two units in the last place."""
    return x + (abs(x) * _W + 1e-300)


@njit(inline=True)
def _pencil_magnitude(ea: Any, qa: Any, mu: float) -> Any:
    """The magnitudes ``|E| + |mu| |Q|`` of the member's upper entries (``ea``, ``qa``: the
    absolute entries), the arguments of the magnitude programs."""
    am = abs(mu)
    return (
        ea[0] + am * qa[0],
        ea[1] + am * qa[1],
        ea[2] + am * qa[2],
        ea[3] + am * qa[3],
        ea[4] + am * qa[4],
        ea[5] + am * qa[5],
        ea[6] + am * qa[6],
        ea[7] + am * qa[7],
        ea[8] + am * qa[8],
        ea[9] + am * qa[9],
    )


@njit(inline=True)
def _point(
    e: Any, ea: Any, q: Any, qa: Any, mu: float, detA: float, eA: float, detE: float, eE: float
) -> tuple[bool, float, float, float, float]:
    """At ``mu``: is ``A + mu Q00`` certainly positive definite, ``Y^T Q Y`` and its bound, and an
    enclosure of ``s(mu)^2`` (``-inf, inf`` when the denominator's sign is not certain)."""
    p = _pencil(e, q, mu)
    pa = _pencil_magnitude(ea, qa, mu)
    y = _cofactors(p)
    ya = _cofactors_mag(pa)
    # the leading minors of A + mu Q00 (the third is Y_4)
    m1 = p[0]
    e1 = pa[0] * _G + _T
    m2 = p[0] * p[4] - p[1] * p[1]
    e2 = (pa[0] * pa[4] + pa[1] * pa[1]) * _G + _T
    e3 = ya[3] * _G + _T
    definite = (m1 > e1) & (m2 > e2) & (y[3] > e3)
    s = _form(y, q)
    es = _form(ya, qa) * _G + _T
    # s(mu)^2 = (Y_4^2 det E - (Y^T E Y) det A) / (Y_4^2 det E)
    T = _form(y, e)
    eT = _form(ya, ea) * _G + _T
    y33, e33 = _times(y[3], e3, y[3], e3)
    M, eM = _times(y33, e33, detE, eE)
    N, eN = _times(T, eT, detA, eA)
    num = M - N
    eNum = (eM + eN + abs(num) * 2 * _U) * _R40
    lo_n, hi_n = num - eNum, num + eNum
    lo_d, hi_d = M - eM, M + eM
    c0, c1, c2, c3 = lo_n / lo_d, lo_n / hi_d, hi_n / lo_d, hi_n / hi_d
    lo = _down(min(min(c0, c1), min(c2, c3)))
    hi = _up(max(max(c0, c1), max(c2, c3)))
    sure = abs(M) > eM
    return definite, s, es, lo if sure else -_INF, hi if sure else _INF


@njit(inline=True)
def _plain_slope(e: Any, q: Any, mu: float) -> tuple[float, float, bool]:
    """``f(mu)``, ``f'(mu) = -2 g^T (A + mu Q00)^-1 g`` (``g = Q00 x + b``) and "definite", in
    plain binary64 (the search), from the adjugate of ``A + mu Q00``."""
    p00, p01, p02, p03, p11, p12, p13, p22, p23, p33 = _pencil(e, q, mu)
    c00 = p11 * p22 - p12 * p12
    c01 = p02 * p12 - p01 * p22
    c02 = p01 * p12 - p02 * p11
    c11 = p00 * p22 - p02 * p02
    c12 = p02 * p01 - p00 * p12
    c22 = p00 * p11 - p01 * p01
    det = p00 * c00 + p01 * c01 + p02 * c02
    definite = (p00 > 0.0) & (c22 > 0.0) & (det > 0.0)
    inv = 1.0 / det
    x0 = -(c00 * p03 + c01 * p13 + c02 * p23) * inv
    x1 = -(c01 * p03 + c11 * p13 + c12 * p23) * inv
    x2 = -(c02 * p03 + c12 * p13 + c22 * p23) * inv
    q00, q01, q02, q03, q11, q12, q13, q22, q23, q33 = q
    g0 = q00 * x0 + q01 * x1 + q02 * x2 + q03
    g1 = q01 * x0 + q11 * x1 + q12 * x2 + q13
    g2 = q02 * x0 + q12 * x1 + q22 * x2 + q23
    f = x0 * (g0 + q03) + x1 * (g1 + q13) + x2 * (g2 + q23) + q33
    qq = c00 * g0 * g0 + c11 * g1 * g1 + c22 * g2 * g2 + 2.0 * (c01 * g0 * g1 + c02 * g0 * g2 + c12 * g1 * g2)
    return f, -2.0 * qq * inv, definite


@njit
def scale_blocks(Es: Any, Qs: Any, out: Any, flag: Any, start: int, stop: int) -> None:  # pragma: no cover
    """Pairs ``start .. stop`` of the stacks ``Es``, ``Qs`` (``(n, 4, 4)``): ``out[k]`` the
    enclosure of ``s*``, ``flag[k]`` 0 (certified in the block), 2 (certified by the scalar
    kernel) or 1 (left to the exact path, ``out[k] = [-inf, inf]``)."""
    S = NB
    eb = np.empty(10 * S)
    qb = np.empty(10 * S)
    # per pair: ok, side, phi_s (0: plain Newton), f_inf, det A, its bound, det E, its bound,
    # mu, lo, hi (the bracket in w), done (then: certified), f', enclosure lo, hi
    st = np.empty(15 * S)
    for blo in range(start, stop, S):
        m = min(S, stop - blo)
        for t in range(m):
            k = blo + t
            sg = -1.0 if Es[k, 0, 0] < 0.0 else 1.0
            gather_signed(Es, k, eb, t, S, sg)
            gather_signed(Qs, k, qb, t, S, 1.0)
        # the checks, the side of the root, f_inf
        for i in range(m):
            e = _load(eb, i, S)
            q = _load(qb, i, S)
            ea = _abs10(e)
            qa = _abs10(q)
            fin = (ea[0] < _INF) & (ea[1] < _INF) & (ea[2] < _INF) & (ea[3] < _INF) & (ea[4] < _INF)
            fin = fin & (ea[5] < _INF) & (ea[6] < _INF) & (ea[7] < _INF) & (ea[8] < _INF) & (ea[9] < _INF)
            fin = fin & (qa[0] < _INF) & (qa[1] < _INF) & (qa[2] < _INF) & (qa[3] < _INF) & (qa[4] < _INF)
            fin = fin & (qa[5] < _INF) & (qa[6] < _INF) & (qa[7] < _INF) & (qa[8] < _INF) & (qa[9] < _INF)
            plane = (q[0] == 0.0) & (q[1] == 0.0) & (q[2] == 0.0) & (q[4] == 0.0) & (q[5] == 0.0)
            plane = plane & (q[7] == 0.0) & ((q[3] != 0.0) | (q[6] != 0.0) | (q[8] != 0.0))
            qok = plane | (abs(_det4(q)) > _mag4(qa) * _G + _T)
            # A certainly positive definite (Sylvester), det E certainly negative
            m2 = e[0] * e[4] - e[1] * e[1]
            e2 = (ea[0] * ea[4] + ea[1] * ea[1]) * _G + _T
            detA = _det3(e[0], e[1], e[2], e[1], e[4], e[5], e[2], e[5], e[7])
            eA = _mag3(ea[0], ea[1], ea[2], ea[1], ea[4], ea[5], ea[2], ea[5], ea[7]) * _G + _T
            aok = (e[0] > ea[0] * _G + _T) & (m2 > e2) & (detA > eA)
            detE = _det4(e)
            eE = _mag4(ea) * _G + _T
            # f(0) det(A)^2 = Y^T Q Y at mu = 0
            y = _cofactors(e)
            ya = _cofactors_mag(ea)
            s0 = _form(y, q)
            e0 = _form(ya, qa) * _G + _T
            ok = fin & qok & aok & (detE < -eE) & (abs(s0) > e0)
            side = 1.0 if s0 > 0.0 else -1.0
            # f_inf = Q(c_Q) = q33 - b^T adj(Q00) b / det Q00, when Q00 is positive definite
            c00 = q[4] * q[7] - q[5] * q[5]
            c01 = q[2] * q[5] - q[1] * q[7]
            c02 = q[1] * q[5] - q[2] * q[4]
            c11 = q[0] * q[7] - q[2] * q[2]
            c12 = q[2] * q[1] - q[0] * q[5]
            c22 = q[0] * q[4] - q[1] * q[1]
            dq = q[0] * c00 + q[1] * c01 + q[2] * c02
            b0, b1, b2 = q[3], q[6], q[8]
            bb = (
                c00 * b0 * b0
                + c11 * b1 * b1
                + c22 * b2 * b2
                + 2.0 * (c01 * b0 * b1 + c02 * b0 * b2 + c12 * b1 * b2)
            )
            finf = q[9] - bb / dq
            use = (side > 0.0) & (q[0] > 0.0) & (c22 > 0.0) & (dq > 0.0) & (finf < 0.0)
            st[i] = 1.0 if ok else 0.0
            st[S + i] = side
            st[2 * S + i] = 1.0 / math.sqrt(-finf) if use else 0.0
            st[3 * S + i] = finf if use else 0.0
            st[4 * S + i] = detA
            st[5 * S + i] = eA
            st[6 * S + i] = detE
            st[7 * S + i] = eE
            st[8 * S + i] = 0.0  # mu
            st[9 * S + i] = 0.0  # lo (w)
            st[10 * S + i] = side  # hi (w)
            st[11 * S + i] = 0.0  # done
        # the search
        for _ in range(NEWTON):
            for i in range(m):
                e = _load(eb, i, S)
                q = _load(qb, i, S)
                side = st[S + i]
                phis = st[2 * S + i]
                finf = st[3 * S + i]
                mu = st[8 * S + i]
                lo = st[9 * S + i]
                hi = st[10 * S + i]
                done = st[11 * S + i] != 0.0
                f, df, definite = _plain_slope(e, q, mu)
                w = mu / (1.0 + abs(mu))
                good = definite & (abs(f) < _INF) & (side * f > 0.0)
                lo2 = w if good else lo
                hi2 = hi if (good | (w == 0.0)) else w
                narrow = abs(hi2 - lo2) <= 2e-16 * abs(hi2)
                # the step: Newton's on phi = (f - f_inf)^(-1/2) where f_inf is known, on f otherwise
                g = f - finf
                sq = math.sqrt(max(g, 0.0))
                tphi = mu + 2.0 * g * (1.0 - phis * sq) / df
                tf = mu - f / df
                nm = tphi if ((phis != 0.0) & (g > 0.0)) else tf
                valid = definite & (abs(f) < _INF) & (abs(df) < _INF) & (df != 0.0) & (abs(nm) < _INF)
                conv = valid & (abs(nm - mu) <= 4e-16 * abs(mu))
                nxt = nm / (1.0 + abs(nm)) if valid else 2.0
                inside = (min(lo2, hi2) < nxt) & (nxt < max(lo2, hi2))
                nxt = nxt if inside else 0.5 * (lo2 + hi2)
                stuck = (nxt == lo2) | (nxt == hi2)
                fin = done | narrow | conv | stuck
                # a step this short is Newton's near the root: taken as it is (in w it may
                # round onto the end of the bracket)
                near = valid & (abs(nm - mu) <= 1e-12 * abs(mu))
                fin = fin & (not near) | conv | done
                mu2 = nm if near else nxt / (1.0 - abs(nxt))
                st[8 * S + i] = mu if fin else mu2
                st[9 * S + i] = lo if done else lo2
                st[10 * S + i] = hi if done else hi2
                st[11 * S + i] = 1.0 if fin else 0.0
                st[12 * S + i] = df  # the slope of f at the last point
        # the offset of the certificate points, then the certificate
        for i in range(m):
            e = _load(eb, i, S)
            q = _load(qb, i, S)
            ea = _abs10(e)
            qa = _abs10(q)
            side = st[S + i]
            detA = st[4 * S + i]
            eA = st[5 * S + i]
            detE = st[6 * S + i]
            eE = st[7 * S + i]
            mu = st[8 * S + i]
            df = st[12 * S + i]
            p = _pencil(e, q, mu)
            am = abs(mu)
            pa = _pencil_magnitude(ea, qa, mu)
            y3 = _det3(p[0], p[1], p[2], p[1], p[4], p[5], p[2], p[5], p[7])
            ya = _cofactors_mag(pa)
            noise = _form(ya, qa) * _G + _T
            slope = abs(df) * y3 * y3 * am
            rel = max(1e-13, min(4.0 * noise / slope, 1e-5))
            rel = rel if (slope > 0.0) else 1e-5
            m1 = mu * (1.0 - rel)
            m2 = mu * (1.0 + rel)
            d1, s1, e1, l1, h1 = _point(e, ea, q, qa, m1, detA, eA, detE, eE)
            d2, s2, e2, l2, h2 = _point(e, ea, q, qa, m2, detA, eA, detE, eE)
            lo2 = max(min(l1, l2), 0.0)
            hi2 = max(h1, h2)
            fin = (abs(l1) < _INF) & (abs(l2) < _INF) & (abs(h1) < _INF) & (abs(h2) < _INF)
            cert = (st[i] != 0.0) & d1 & d2 & (side * s1 > e1) & (side * s2 < -e2)
            cert = cert & fin & (abs(mu) < _INF)
            r_lo = _down(math.sqrt(lo2))
            st[13 * S + i] = max(r_lo, 0.0) if lo2 > 0.0 else 0.0
            st[14 * S + i] = _up(math.sqrt(hi2))
            st[11 * S + i] = 1.0 if cert else 0.0
        for i in range(m):
            k = blo + i
            if st[11 * S + i] != 0.0:
                out[k, 0] = st[13 * S + i]
                out[k, 1] = st[14 * S + i]
                flag[k] = 0
            else:
                _scalar(Es, Qs, out, flag, k, k + 1)
                if flag[k] == 0:
                    flag[k] = 2


def scale_stack(
    Es: np.ndarray, Qs: np.ndarray, *, blocks: bool = True, threads: int | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """Enclosures ``(n, 2)`` of the one-sided first-contact scale of float64 stacks ``(n, 4, 4)``
    and a mask of the pairs left to the exact path (their rows ``[-inf, inf]``).

    ``blocks``: the block kernel of this module (the scalar kernel of
    :mod:`quadric_contact.modes.distance.scale_kernel`
    answering the pairs it does not certify), or the scalar kernel alone.  The matrices are
    symmetric (the block kernel reads their upper triangles; the public functions check it).

    Examples
    --------
    >>> E = np.diag([1.0, 1.0, 1.0, -1.0]); Q = np.zeros((4, 4)); Q[0, 3] = Q[3, 0] = 0.5; Q[3, 3] = -3.0
    >>> enc, rest = scale_stack(E[None], Q[None])   # the unit ball and the plane x = 3
    >>> bool(enc[0, 0] <= 3.0 <= enc[0, 1]), bool(rest[0]), float(enc[0, 1] - enc[0, 0]) < 1e-11
    (True, False, True)
    """
    out, flag = _scale_flags(Es, Qs, blocks=blocks, threads=threads)
    return out, flag == 1


def _scale_flags(
    Es: np.ndarray, Qs: np.ndarray, *, blocks: bool = True, threads: int | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """The enclosures and, for each pair, who answered it: 0 the block kernel, 2 the scalar
    kernel after the block kernel, 1 nobody (left to the exact path); the scalar kernel alone
    (``blocks=False``) gives 0 or 1."""
    return run_flags(scale_blocks if blocks else _scalar, Es, Qs, threads)


def run_flags(
    kernel: Any, Es: np.ndarray, Qs: np.ndarray, threads: int | None
) -> tuple[np.ndarray, np.ndarray]:
    """Run a scale kernel ``kernel(Es, Qs, out, flag, start, stop)`` over float64 stacks
    ``(n, 4, 4)`` on threads: the enclosures ``(n, 2)`` and the flag of each pair (0, 2:
    certified by the block or the scalar kernel, 1: left to the exact path).  Shared by the
    one-sided and the two-sided scale."""
    Es = kernel_stack(Es)
    Qs = kernel_stack(Qs)
    n = Es.shape[0]
    out = np.empty((n, 2))
    flag = np.empty(n, dtype=np.uint8)
    run_parallel(lambda a, b: kernel(Es, Qs, out, flag, a, b), n, threads)
    return out, flag
