"""The first-contact scale on stacks: a compiled kernel that encloses ``s*`` in binary64 with a
certificate, for the pairs it can certify; the others go to the exact scalar path.

The certificate
---------------
Write ``E = [[A, a], [a^T, e]]`` (``A`` positive definite, ``det E < 0``: a real ellipsoid,
inside negative) and ``Q = [[Q00, b], [b^T, q]]``.  ``s*^2 = min (x - c)^T A (x - c) / r`` over
the surface of ``Q`` (``c`` the centre of ``E``, ``r = -det E / det A``).  For a multiplier
``mu`` with ``A + mu Q00`` positive definite, ``x(mu) = -(A + mu Q00)^-1 (a + mu b)`` is the
stationary point of ``h(x) = E(x) + mu Q(x)``, a convex function; so if ``Q(x(mu*)) = 0`` then
``E(x) >= E(x(mu*))`` on the whole surface of ``Q`` (``h`` is least at ``x(mu*)`` and equals
``E`` there): ``x(mu*)`` is the nearest point, globally.  Along the positive definite interval
(which holds ``mu = 0`` and is convex, so two definite ends make the segment between them
definite) ``f(mu) = Q(x(mu))`` decreases (``f' = -2 g^T (A + mu Q00)^-1 g``), so a sign change
of ``f`` between two definite ends ``mu1 < mu2`` holds exactly one root, which is ``mu*``.  With
``Y(mu) = adj(E + mu Q) e_4 = det(A + mu Q00) (x(mu), 1)``::

    f(mu) det(A + mu Q00)^2 = Y^T Q Y,
    s(mu)^2 = 1 - det(E + mu Q) det A / (det(A + mu Q00) det E)   (at mu*: s*^2),

and ``s(mu)^2`` is monotone in ``|mu|`` on the definite interval (it is ``|p(mu)|^2`` in the
coordinates where ``E`` is the unit ball, ``p_i = mu b_i / (1 + mu m_i)`` on the eigenbasis), so
``s*^2`` lies between its values at ``mu1`` and ``mu2`` (``tests/test_contact_scale_kernel.py``
checks the identities in exact arithmetic).

Every sign and every bound is computed in binary64 with a static error bound: a straight-line
program of ``+ - *`` whose every path has at most ``D`` roundings errs by at most
``gamma_D = D u / (1 - D u)`` times the same program run on absolute values (``u = 2^-53``);
the longest path here, ``Y^T W Y`` (the pencil's entries 2, a 3x3 minor 5, two products and a
sum of 16 terms), has 25, and ``D = 32`` is used for all of them.
A pair whose signs cannot be certified (a touch at ``mu = 0``, a singular ``Q``, a root too
close to the end of the definite interval, an ``E`` that is not certainly an ellipsoid) is
flagged, and the caller answers it with the exact path.

:func:`scale_stack` runs the same certificate in blocks laid out for the vector unit
(:mod:`quadric_contact.modes.distance.scale_blocks`), with this kernel for the pairs the blocks do not
certify.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from quadric_contact.modes.kernels._jit import njit

__all__: list[str] = []  # the driver is quadric_contact.modes.distance.scale_blocks.scale_stack

_U = 2.0**-53
_D = 32
_GAMMA = (_D * _U / (1 - _D * _U)) * (1 + 2.0**-40)
_TINY = 1e-290


@njit(inline=True)
def _det3(
    m00: float, m01: float, m02: float, m11: float, m12: float, m22: float, m10: float, m20: float, m21: float
) -> float:
    return m00 * (m11 * m22 - m12 * m21) - m01 * (m10 * m22 - m12 * m20) + m02 * (m10 * m21 - m11 * m20)


@njit(inline=True)
def _minor(P: Any, r0: int, r1: int, r2: int, c0: int, c1: int, c2: int) -> float:
    return _det3(
        P[r0, c0], P[r0, c1], P[r0, c2], P[r1, c1], P[r1, c2], P[r2, c2], P[r1, c0], P[r2, c0], P[r2, c1]
    )


@njit(inline=True)
def _det4(P: Any) -> float:
    return (
        P[0, 0] * _minor(P, 1, 2, 3, 1, 2, 3)
        - P[0, 1] * _minor(P, 1, 2, 3, 0, 2, 3)
        + P[0, 2] * _minor(P, 1, 2, 3, 0, 1, 3)
        - P[0, 3] * _minor(P, 1, 2, 3, 0, 1, 2)
    )


@njit(inline=True)
def _pencil(E: Any, Q: Any, mu: float, P: Any, Pa: Any) -> None:
    """``P = E + mu Q`` and ``Pa = |E| + |mu| |Q|`` (the magnitudes)."""
    am = abs(mu)
    for i in range(4):
        for j in range(4):
            P[i, j] = E[i, j] + mu * Q[i, j]
            Pa[i, j] = abs(E[i, j]) + am * abs(Q[i, j])


@njit(inline=True)
def _form(P: Any, Pa: Any, W: Any, Wa: Any) -> tuple[float, float, float, float]:
    """``(Y^T W Y, bound, Y_4, bound)`` with ``Y = adj(P) e_4`` (the cofactors of the last row
    of the symmetric ``P``; ``Y_4 = det`` of its leading 3x3 block)."""
    y0 = -_minor(P, 1, 2, 3, 0, 1, 2)
    y1 = _minor(P, 0, 2, 3, 0, 1, 2)
    y2 = -_minor(P, 0, 1, 3, 0, 1, 2)
    y3 = _minor(P, 0, 1, 2, 0, 1, 2)
    a0 = _mag3(Pa, 1, 2, 3)
    a1 = _mag3(Pa, 0, 2, 3)
    a2 = _mag3(Pa, 0, 1, 3)
    a3 = _mag3(Pa, 0, 1, 2)
    y = (y0, y1, y2, y3)
    ya = (a0, a1, a2, a3)
    s = 0.0
    sa = 0.0
    for i in range(4):
        for j in range(4):
            s += y[i] * W[i, j] * y[j]
            sa += ya[i] * Wa[i, j] * ya[j]
    return s, sa * _GAMMA + _TINY, y3, a3 * _GAMMA + _TINY


@njit(inline=True)
def _secular(P: Any, Pa: Any, Q: Any, Qa: Any) -> tuple[float, float]:
    """``(Y^T Q Y, bound)``: ``f(mu) det(A + mu Q00)^2``."""
    s, e, _, _ = _form(P, Pa, Q, Qa)
    return s, e


@njit(inline=True)
def _times(x: float, ex: float, y: float, ey: float) -> tuple[float, float]:
    """The product of ``x +- ex`` and ``y +- ey``: a value and a bound."""
    p = x * y
    e = ((abs(x) + ex) * (abs(y) + ey) - abs(x) * abs(y) + abs(p) * 8 * _U) * (1 + 2.0**-40) + _TINY
    return p, e


@njit(inline=True)
def _mag3(Pa: Any, r0: int, r1: int, r2: int) -> float:
    """The 3x3 minor of rows ``r0, r1, r2`` and columns 0, 1, 2 of ``|P|``, signs made +."""
    return (
        Pa[r0, 0] * (Pa[r1, 1] * Pa[r2, 2] + Pa[r1, 2] * Pa[r2, 1])
        + Pa[r0, 1] * (Pa[r1, 0] * Pa[r2, 2] + Pa[r1, 2] * Pa[r2, 0])
        + Pa[r0, 2] * (Pa[r1, 0] * Pa[r2, 1] + Pa[r1, 1] * Pa[r2, 0])
    )


@njit(inline=True)
def _mag4(Pa: Any) -> float:
    """``det`` of ``|P|`` by the first row with every sign made +."""
    return (
        Pa[0, 0] * _mag3c(Pa, 1, 2, 3)
        + Pa[0, 1] * _mag3c(Pa, 0, 2, 3)
        + Pa[0, 2] * _mag3c(Pa, 0, 1, 3)
        + Pa[0, 3] * _mag3c(Pa, 0, 1, 2)
    )


@njit(inline=True)
def _mag3c(Pa: Any, c0: int, c1: int, c2: int) -> float:
    """The minor of rows 1, 2, 3 and columns ``c0, c1, c2`` of ``|P|``, signs made +."""
    return (
        Pa[1, c0] * (Pa[2, c1] * Pa[3, c2] + Pa[2, c2] * Pa[3, c1])
        + Pa[1, c1] * (Pa[2, c0] * Pa[3, c2] + Pa[2, c2] * Pa[3, c0])
        + Pa[1, c2] * (Pa[2, c0] * Pa[3, c1] + Pa[2, c1] * Pa[3, c0])
    )


@njit(inline=True)
def _definite(P: Any, Pa: Any) -> int:
    """``1`` when the leading 3x3 block of ``P`` is certainly positive definite, ``-1`` when it
    is certainly not (a leading minor certainly negative), ``0`` undecided."""
    m1 = P[0, 0]
    e1 = Pa[0, 0] * _GAMMA + _TINY
    m2 = P[0, 0] * P[1, 1] - P[0, 1] * P[1, 0]
    e2 = (Pa[0, 0] * Pa[1, 1] + Pa[0, 1] * Pa[1, 0]) * _GAMMA + _TINY
    m3 = _minor(P, 0, 1, 2, 0, 1, 2)
    e3 = _mag3(Pa, 0, 1, 2) * _GAMMA + _TINY
    if m1 > e1 and m2 > e2 and m3 > e3:
        return 1
    if m1 < -e1 or m2 < -e2 or m3 < -e3:
        return -1
    # a nonpositive leading minor with the earlier ones positive: not definite
    if m1 > e1 and m2 < -e2:
        return -1
    return 0


@njit(inline=True)
def _positive_before(E: Any, Q: Any, Qa: Any, mu: float, P: Any, Pa: Any, side: float) -> int:
    """Is ``mu`` before the root: ``1`` (definite and ``side * f > 0``), ``-1`` (not definite or
    ``side * f < 0``), ``0`` undecided.  Floats only (the search; certificates are separate)."""
    _pencil(E, Q, mu, P, Pa)
    d = _definite(P, Pa)
    if d < 0:
        return -1
    s, e = _secular(P, Pa, Q, Qa)
    if d == 0:
        return 0
    if side * s > e:
        return 1
    if side * s < -e:
        return -1
    return 0


@njit(inline=True)
def _s2_bounds(
    E: Any, Ea: Any, Q: Any, mu: float, P: Any, Pa: Any, detA: float, eA: float, detE: float, eE: float
) -> tuple[float, float]:
    """An enclosure of ``s(mu)^2 = (x(mu) - c)^T A (x(mu) - c) / r
    = (Y_4^2 det E - (Y^T E Y) det A) / (Y_4^2 det E)``."""
    _pencil(E, Q, mu, P, Pa)
    T, eT, y3, e3 = _form(P, Pa, E, Ea)
    y33, e33 = _times(y3, e3, y3, e3)
    M, eM = _times(y33, e33, detE, eE)
    N, eN = _times(T, eT, detA, eA)
    num = M - N
    eNum = (eM + eN + abs(num) * 2 * _U) * (1 + 2.0**-40)
    if not (abs(M) > eM):
        return -np.inf, np.inf
    lo_n, hi_n = num - eNum, num + eNum
    lo_d, hi_d = M - eM, M + eM
    c0, c1, c2, c3 = lo_n / lo_d, lo_n / hi_d, hi_n / lo_d, hi_n / hi_d
    lo = min(min(c0, c1), min(c2, c3))
    hi = max(max(c0, c1), max(c2, c3))
    return np.nextafter(np.nextafter(lo, -np.inf), -np.inf), np.nextafter(np.nextafter(hi, np.inf), np.inf)


@njit(inline=True)
def _plain(E: Any, Q: Any, mu: float, P: Any) -> tuple[float, bool]:
    """``f(mu)`` and "definite" in plain binary64 (the search; the certificate is apart)."""
    for i in range(4):
        for j in range(4):
            P[i, j] = E[i, j] + mu * Q[i, j]
    y0 = -_minor(P, 1, 2, 3, 0, 1, 2)
    y1 = _minor(P, 0, 2, 3, 0, 1, 2)
    y2 = -_minor(P, 0, 1, 3, 0, 1, 2)
    y3 = _minor(P, 0, 1, 2, 0, 1, 2)
    definite = P[0, 0] > 0 and P[0, 0] * P[1, 1] - P[0, 1] * P[1, 0] > 0 and y3 > 0
    y = (y0, y1, y2, y3)
    s = 0.0
    for i in range(4):
        for j in range(4):
            s += y[i] * Q[i, j] * y[j]
    return s / (y3 * y3), definite


@njit(inline=True)
def _plain_slope(E: Any, Q: Any, mu: float, P: Any) -> tuple[float, float, bool]:
    """``f(mu)``, ``f'(mu) = -2 g^T (A + mu Q00)^-1 g`` (``g = Q00 x + b``) and "definite", in
    plain binary64 (the search)."""
    for i in range(4):
        for j in range(4):
            P[i, j] = E[i, j] + mu * Q[i, j]
    y0 = -_minor(P, 1, 2, 3, 0, 1, 2)
    y1 = _minor(P, 0, 2, 3, 0, 1, 2)
    y2 = -_minor(P, 0, 1, 3, 0, 1, 2)
    y3 = _minor(P, 0, 1, 2, 0, 1, 2)
    definite = P[0, 0] > 0 and P[0, 0] * P[1, 1] - P[0, 1] * P[1, 0] > 0 and y3 > 0
    x0, x1, x2 = y0 / y3, y1 / y3, y2 / y3
    f = 0.0
    X = (x0, x1, x2, 1.0)
    for i in range(4):
        for j in range(4):
            f += X[i] * Q[i, j] * X[j]
    g0 = Q[0, 0] * x0 + Q[0, 1] * x1 + Q[0, 2] * x2 + Q[0, 3]
    g1 = Q[1, 0] * x0 + Q[1, 1] * x1 + Q[1, 2] * x2 + Q[1, 3]
    g2 = Q[2, 0] * x0 + Q[2, 1] * x1 + Q[2, 2] * x2 + Q[2, 3]
    a00 = P[1, 1] * P[2, 2] - P[1, 2] * P[2, 1]
    a01 = P[0, 2] * P[2, 1] - P[0, 1] * P[2, 2]
    a02 = P[0, 1] * P[1, 2] - P[0, 2] * P[1, 1]
    a11 = P[0, 0] * P[2, 2] - P[0, 2] * P[2, 0]
    a12 = P[0, 2] * P[1, 0] - P[0, 0] * P[1, 2]
    a22 = P[0, 0] * P[1, 1] - P[0, 1] * P[1, 0]
    q = a00 * g0 * g0 + a11 * g1 * g1 + a22 * g2 * g2 + 2.0 * (a01 * g0 * g1 + a02 * g0 * g2 + a12 * g1 * g2)
    return f, -2.0 * q / y3, definite


@njit
def _kernel(Es: Any, Qs: Any, out: Any, flag: Any, start: int, stop: int) -> None:  # pragma: no cover
    P = np.empty((4, 4))
    Pa = np.empty((4, 4))
    E = np.empty((4, 4))
    Ea = np.empty((4, 4))
    Qa = np.empty((4, 4))
    for k in range(start, stop):
        out[k, 0] = -np.inf
        out[k, 1] = np.inf
        flag[k] = 1
        Q = Qs[k]
        ok = True
        for i in range(4):
            for j in range(4):
                E[i, j] = Es[k, i, j]
                Ea[i, j] = abs(E[i, j])
                Qa[i, j] = abs(Q[i, j])
                if not (math.isfinite(E[i, j]) and math.isfinite(Q[i, j])):
                    ok = False
        if not ok:
            continue
        # Q nondegenerate (certainly), or a plane: the types of Table 1 with a real surface but
        # the imaginary ellipsoid (which has no root: flagged below); the others (cylinders,
        # parallel planes, and the excluded types) go to the exact path
        plane = True
        for i in range(3):
            for j in range(3):
                if Q[i, j] != 0.0:
                    plane = False
        if plane:
            plane = Q[0, 3] != 0.0 or Q[1, 3] != 0.0 or Q[2, 3] != 0.0
        if not plane and not (abs(_det4(Q)) > _mag4(Qa) * _GAMMA + _TINY):
            continue
        # the sign of E: A positive definite
        if _definite(E, Ea) != 1:
            for i in range(4):
                for j in range(4):
                    E[i, j] = -E[i, j]
            if _definite(E, Ea) != 1:
                continue
        detA = _minor(E, 0, 1, 2, 0, 1, 2)
        eA = _mag3(Ea, 0, 1, 2) * _GAMMA + _TINY
        detE = _det4(E)
        eE = _mag4(Ea) * _GAMMA + _TINY
        if not (detE < -eE):
            continue  # not certainly a real ellipsoid
        # the side of the root: the sign of f(0), Q at the centre of E
        _pencil(E, Q, 0.0, P, Pa)
        s0, e0 = _secular(P, Pa, Q, Qa)
        if abs(s0) <= e0:
            continue  # the centre is on (or too near) the surface: the exact path
        side = 1.0 if s0 > 0 else -1.0
        # the search: Newton's method on f in mu, kept inside a bracket in w = mu / (1 + |mu|)
        # ((-1, 1)): lo before the root (definite, side f > 0), hi after it; a step that
        # leaves the bracket bisects it in w
        lo = 0.0
        hi = side
        mu = 0.0
        for _ in range(200):
            f, df, definite = _plain_slope(E, Q, mu, P)
            w = mu / (1.0 + abs(mu))
            if definite and math.isfinite(f) and side * f > 0:
                lo = w
            elif w != 0.0:
                hi = w
            if abs(hi - lo) <= 2e-16 * abs(hi):
                break
            nxt = 2.0  # outside: bisect
            if definite and math.isfinite(f) and math.isfinite(df) and df != 0.0:
                m2 = mu - f / df
                if abs(m2 - mu) <= 4e-16 * abs(mu):
                    break  # converged (mu evaluated, at the root to rounding)
                nxt = m2 / (1.0 + abs(m2))
            if not (min(lo, hi) < nxt < max(lo, hi)):
                nxt = 0.5 * (lo + hi)
            if nxt == lo or nxt == hi:  # noqa: SIM109 (compiled: two float comparisons)
                break
            mu = nxt / (1.0 - abs(nxt))
        # the certificate: mu1 before the root, mu2 after it, both definite, widened until the
        # signs are certified
        if not math.isfinite(mu):
            continue
        rel = 1e-13  # typical: the signs are certified from 1e-13 to 1e-12
        for _ in range(11):
            m1 = mu * (1.0 - rel)
            m2 = mu * (1.0 + rel)
            _pencil(E, Q, m1, P, Pa)
            ok1 = _definite(P, Pa) == 1
            s1, e1 = _secular(P, Pa, Q, Qa)
            _pencil(E, Q, m2, P, Pa)
            ok2 = _definite(P, Pa) == 1
            s2, e2 = _secular(P, Pa, Q, Qa)
            if ok1 and ok2 and side * s1 > e1 and side * s2 < -e2:
                l1, h1 = _s2_bounds(E, Ea, Q, m1, P, Pa, detA, eA, detE, eE)
                l2, h2 = _s2_bounds(E, Ea, Q, m2, P, Pa, detA, eA, detE, eE)
                lo2 = max(min(l1, l2), 0.0)
                hi2 = max(h1, h2)
                if math.isfinite(lo2) and math.isfinite(hi2):
                    out[k, 0] = np.nextafter(math.sqrt(lo2), -np.inf) if lo2 > 0 else 0.0
                    out[k, 1] = np.nextafter(math.sqrt(hi2), np.inf)
                    flag[k] = 0
                break
            if not (ok1 and ok2) and rel > 1e-9:
                break
            # the next offset from the slope of Y^T Q Y between the two points and the larger
            # error bound (then by factors, should the slope mislead)
            nxt = rel * 10.0 if rel < 1e-9 else rel * 4.0
            if abs(s2 - s1) > 8.0 * max(e1, e2):  # a slope above the noise
                slope = abs(s2 - s1) / abs(m2 - m1)
                nxt = max(rel * 1.5, min(nxt, 3.0 * max(e1, e2) / slope / abs(mu)))
            rel = nxt
