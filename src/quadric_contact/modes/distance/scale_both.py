"""The first-contact scale of two ellipsoids scaled together (``scale="both"``, the
Perram-Wertheim contact function) on stacks: a compiled kernel that encloses ``s*`` in binary64
with a certificate, for the pairs it can certify; the others go to the exact scalar path.

The certificate
---------------
Write ``E = [[A, a], [a^T, e]]`` and ``Q = [[B, b], [b^T, q]]`` (``A``, ``B`` positive definite,
``det E < 0``, ``det Q < 0``: real ellipsoids, inside negative), ``E(x) = X^T E X`` with
``X = (x, 1)``, and ``r_E = -det E / det A``, ``r_Q = -det Q / det B`` (``E(x) = (x - c_E)^T A
(x - c_E) - r_E``).  Scaled about their centres by ``s`` the solids are ``f(x) <= s^2`` and
``g(x) <= s^2`` with ``f = 1 + E(x) / r_E``, ``g = 1 + Q(x) / r_Q`` (convex), so::

    s*^2 = min_x max(f(x), g(x)).

*Upper bound.*  Any point ``x`` lies in both solids scaled by ``sqrt(max(f(x), g(x)))``, so
``s*^2 <= max(f(x), g(x))``.  The point taken is ``x(mu) = Y[:3] / Y_4`` with
``Y = adj(E + mu Q) e_4`` (``Y_4 = det(A + mu B)``), where::

    f(x(mu)) = 1 - (Y^T E Y) det A / (Y_4^2 det E),   g(x(mu)) = 1 - (Y^T Q Y) det B / (Y_4^2 det Q).

*Lower bound.*  For ``mu >= 0`` and every ``x``, ``max(f, g) >= (r_E f + mu r_Q g) / (r_E + mu r_Q)``
(a weighted mean), and the right side is ``1 + (E(x) + mu Q(x)) / (r_E + mu r_Q)``, whose least
value over ``x`` is a Schur complement (``A + mu B`` is positive definite):
``min_x X^T M X = det M / det M_00`` for ``M = E + mu Q``.  Hence, for every ``mu >= 0``::

    s*^2 >= L(mu) = 1 - det(E + mu Q) det A det B / (Y_4 (det E det B + mu det Q det A)).

At the optimum ``mu*`` (``f(x(mu*)) = g(x(mu*))``, the minimax theorem for the convex ``f``,
``g``) the two bounds meet; at a ``mu`` within a few units in the last place of it they are
apart by about ``|f - g|`` at ``x(mu)``, which the search drives to rounding level.  No bound
assumes anything of ``mu`` but ``mu >= 0``: the search is floats only and nothing trusts it
(``proofs/first_contact_scale.py`` proves the identities and states the argument).

Every quantity of the two bounds is computed in binary64 with a static error bound, as in
:mod:`quadric_contact.modes.distance.scale_kernel`: a straight-line program of ``+ - *`` whose every path
has at most ``D`` roundings errs by at most ``gamma_D = D u / (1 - D u)`` times the same program
run on absolute values (``u = 2^-53``).  The longest paths here are ``det(E + mu Q)`` (the
pencil's entries 2, a 3x3 minor 5, a product and a sum of four 4: 11) and ``Y^T W Y`` (the
cofactors 7, the row sums 4, the product and the sum of four 4: 15, summed row by row as in
:mod:`quadric_contact.modes.distance.scale_blocks`); ``D = 32`` is used for all of them.  Products,
sums and quotients of bounded quantities carry their bounds forward (:func:`_times`, the
corners of an interval quotient), and the ends are rounded outwards.

A pair is certified when its enclosure of ``s*`` is at most :data:`WIDTH` relative wide.  The
others (an ``E`` or ``Q`` not certainly a real ellipsoid, a centre on or very near the other's
centre, an overflow, a search not finished) are flagged, and the caller answers them with the
exact path.

The search
----------
``rho(mu) = sqrt(f(x(mu)) / g(x(mu)))`` increases from ``0`` (``mu = 0``) to ``inf``; the root
of ``rho = 1`` is ``mu*``.  For two spheres ``rho`` is linear in ``mu``, so Newton's method on
``rho - 1`` (``rho' = rho sigma (mu / (r_E f) + 1 / (r_Q g))``, ``sigma = u^T (A + mu B)^-1 u``,
``u = B x + b``) ends in one step there and in a few elsewhere.  The steps are kept inside a
bracket in ``w = mu / (1 + mu)`` (``(0, 1)``): a step that leaves it bisects it.

Layout: a gather copies a block of :data:`NB` pairs into column buffers (one row per upper
entry; ``E`` and ``Q`` multiplied by ``-1`` when their first entry is negative), then
straight-line loops over the block run the checks, :data:`NEWTON` steps of the search and the
certificate (no branch, so that LLVM vectorises them); a pair not certified in the block goes
to the scalar kernel (:func:`_scalar`: up to :data:`STEPS` steps, the same certificate), which
answers it or leaves it to the exact path.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from quadric_contact._generated import blocks
from quadric_contact.modes.distance.scale_blocks import (
    _G,
    _R40,
    _T,
    _abs10,
    _cofactors,
    _cofactors_mag,
    _det3,
    _det4,
    _down,
    _form,
    _mag3,
    _mag4,
    _pencil,
    _pencil_magnitude,
    _times,
    _up,
    gather_signed,
    run_flags,
    signed_upper,
)
from quadric_contact.modes.distance.scale_kernel import _U
from quadric_contact.modes.kernels._jit import njit

__all__ = ["NB", "NEWTON", "STEPS", "WIDTH", "scale_both_stack"]

NB = 32
"""Pairs per block."""
NEWTON = 6
"""Steps of the search in the block; a pair not certified after them goes to the scalar kernel."""
STEPS = 60
"""Steps of the search in the scalar kernel."""
WIDTH = 1e-7
"""The widest enclosure of ``s*`` certified, relative to its upper end; a wider one is left to
the exact path.  The enclosures are as wide as the pair's conditioning in binary64 makes them:
the corner entries of ellipsoids far from the origin cancel (``r_E`` is the difference of
``e`` and ``a^T A^-1 a``, both about ``|c_E|^2 / axis^2`` times it), and the bounds grow with
that ratio (on random pairs: a median of about ``10^-11``, ``10^-9`` at the 99th percentile).
A pair wider than this is better answered exactly."""

_INF = math.inf
_load = njit(blocks.load_upper, inline=True)


@njit(inline=True)
def _setup(e: Any, q: Any) -> tuple[bool, float, float, float, float, float, float, float, float, float]:
    """The checks of a pair (``E``, ``Q`` with positive first entries) and its constants:
    ``(ok, det A, bound, det B, bound, det E, bound, det Q, bound, mu0)``; ``ok`` when every
    entry is finite, ``A`` and ``B`` are certainly positive definite (Sylvester) and ``det E``,
    ``det Q`` certainly negative.  ``mu0 = tr A / tr B`` starts the search."""
    ea = _abs10(e)
    qa = _abs10(q)
    fin = True
    for j in range(10):
        fin = fin & (ea[j] < _INF) & (qa[j] < _INF)
    detA = _det3(e[0], e[1], e[2], e[1], e[4], e[5], e[2], e[5], e[7])
    eA = _mag3(ea[0], ea[1], ea[2], ea[1], ea[4], ea[5], ea[2], ea[5], ea[7]) * _G + _T
    m2 = e[0] * e[4] - e[1] * e[1]
    e2 = (ea[0] * ea[4] + ea[1] * ea[1]) * _G + _T
    aok = (e[0] > ea[0] * _G + _T) & (m2 > e2) & (detA > eA)
    detB = _det3(q[0], q[1], q[2], q[1], q[4], q[5], q[2], q[5], q[7])
    eB = _mag3(qa[0], qa[1], qa[2], qa[1], qa[4], qa[5], qa[2], qa[5], qa[7]) * _G + _T
    n2 = q[0] * q[4] - q[1] * q[1]
    f2 = (qa[0] * qa[4] + qa[1] * qa[1]) * _G + _T
    bok = (q[0] > qa[0] * _G + _T) & (n2 > f2) & (detB > eB)
    detE = _det4(e)
    eE = _mag4(ea) * _G + _T
    detQ = _det4(q)
    eQ = _mag4(qa) * _G + _T
    ok = fin & aok & bok & (detE < -eE) & (detQ < -eQ)
    mu0 = (e[0] + e[4] + e[7]) / (q[0] + q[4] + q[7])
    return ok, detA, eA, detB, eB, detE, eE, detQ, eQ, mu0


@njit(inline=True)
def _plain(e: Any, q: Any, mu: float, rE: float, rQ: float) -> tuple[float, float, bool]:
    """``rho(mu)``, ``rho'(mu)`` and "usable" in plain binary64 (the search)."""
    p00, p01, p02, p03, p11, p12, p13, p22, p23, p33 = _pencil(e, q, mu)
    c00 = p11 * p22 - p12 * p12
    c01 = p02 * p12 - p01 * p22
    c02 = p01 * p12 - p02 * p11
    c11 = p00 * p22 - p02 * p02
    c12 = p02 * p01 - p00 * p12
    c22 = p00 * p11 - p01 * p01
    det = p00 * c00 + p01 * c01 + p02 * c02
    inv = 1.0 / det
    x0 = -(c00 * p03 + c01 * p13 + c02 * p23) * inv
    x1 = -(c01 * p03 + c11 * p13 + c12 * p23) * inv
    x2 = -(c02 * p03 + c12 * p13 + c22 * p23) * inv
    e00, e01, e02, e03, e11, e12, e13, e22, e23, e33 = e
    q00, q01, q02, q03, q11, q12, q13, q22, q23, q33 = q
    h0 = e00 * x0 + e01 * x1 + e02 * x2 + e03
    h1 = e01 * x0 + e11 * x1 + e12 * x2 + e13
    h2 = e02 * x0 + e12 * x1 + e22 * x2 + e23
    u0 = q00 * x0 + q01 * x1 + q02 * x2 + q03
    u1 = q01 * x0 + q11 * x1 + q12 * x2 + q13
    u2 = q02 * x0 + q12 * x1 + q22 * x2 + q23
    f = 1.0 + (x0 * (h0 + e03) + x1 * (h1 + e13) + x2 * (h2 + e23) + e33) / rE
    g = 1.0 + (x0 * (u0 + q03) + x1 * (u1 + q13) + x2 * (u2 + q23) + q33) / rQ
    sig = (
        c00 * u0 * u0 + c11 * u1 * u1 + c22 * u2 * u2 + 2.0 * (c01 * u0 * u1 + c02 * u0 * u2 + c12 * u1 * u2)
    ) * inv
    rho = math.sqrt(max(f, 0.0) / g)
    drho = rho * sig * (mu / (rE * f) + 1.0 / (rQ * g))
    usable = (det > 0.0) & (f > 0.0) & (g > 0.0) & (abs(rho) < _INF) & (drho > 0.0) & (drho < _INF)
    return rho, drho, usable


@njit(inline=True)
def _quotient(n: float, en: float, d: float, ed: float) -> tuple[float, float]:
    """An enclosure of ``1 - n / d = (d - n) / d`` from ``n +- en``, ``d +- ed``
    (``-inf, inf`` when the sign of ``d`` is not certain)."""
    diff = d - n
    ediff = (ed + en + abs(diff) * 2 * _U) * _R40
    lo_n, hi_n = diff - ediff, diff + ediff
    lo_d, hi_d = d - ed, d + ed
    c0, c1, c2, c3 = lo_n / lo_d, lo_n / hi_d, hi_n / lo_d, hi_n / hi_d
    lo = _down(min(min(c0, c1), min(c2, c3)))
    hi = _up(max(max(c0, c1), max(c2, c3)))
    sure = abs(d) > ed
    return (lo if sure else -_INF), (hi if sure else _INF)


@njit(inline=True)
def _bounds(
    e: Any,
    q: Any,
    mu: float,
    detA: float,
    eA: float,
    detB: float,
    eB: float,
    detE: float,
    eE: float,
    detQ: float,
    eQ: float,
) -> tuple[float, float]:
    """``lo <= s*^2 <= hi`` from the multiplier ``mu >= 0``: ``L(mu)`` and
    ``max(f, g)`` at ``x(mu)``, each computed with its error bound and rounded outwards."""
    ea = _abs10(e)
    qa = _abs10(q)
    p = _pencil(e, q, mu)
    pa = _pencil_magnitude(ea, qa, mu)
    y = _cofactors(p)
    ya = _cofactors_mag(pa)
    y3 = y[3]
    e3 = ya[3] * _G + _T
    # the lower bound L(mu) = 1 - det M det A det B / (Y_4 (det E det B + mu det Q det A))
    dM = _det4(p)
    eM = _mag4(pa) * _G + _T
    n1, en1 = _times(dM, eM, detA, eA)
    num, enum = _times(n1, en1, detB, eB)
    t1, et1 = _times(detE, eE, detB, eB)
    t2, et2 = _times(detQ, eQ, detA, eA)
    t3, et3 = _times(mu, 0.0, t2, et2)
    s = t1 + t3
    es = (et1 + et3 + abs(s) * 2 * _U) * _R40
    den, eden = _times(y3, e3, s, es)
    lo, _ = _quotient(num, enum, den, eden)
    # the upper bound: f and g at x(mu) = Y[:3] / Y_4
    y33, e33 = _times(y3, e3, y3, e3)
    TE = _form(y, e)
    eTE = _form(ya, ea) * _G + _T
    dE, edE = _times(y33, e33, detE, eE)
    nE, enE = _times(TE, eTE, detA, eA)
    _, hf = _quotient(nE, enE, dE, edE)
    TQ = _form(y, q)
    eTQ = _form(ya, qa) * _G + _T
    dQ, edQ = _times(y33, e33, detQ, eQ)
    nQ, enQ = _times(TQ, eTQ, detB, eB)
    _, hg = _quotient(nQ, enQ, dQ, edQ)
    ok = (mu >= 0.0) & (mu < _INF)
    return (max(lo, 0.0) if ok else -_INF), (max(hf, hg) if ok else _INF)


@njit(inline=True)
def _enclose(lo2: float, hi2: float) -> tuple[float, float, bool]:
    """``[sqrt(lo2), sqrt(hi2)]`` rounded outwards, and whether it is certified (finite,
    ``lo2 > 0``, at most :data:`WIDTH` relative wide)."""
    lo = max(_down(math.sqrt(max(lo2, 0.0))), 0.0)
    hi = _up(math.sqrt(max(hi2, 0.0)))
    good = (lo2 > 0.0) & (hi2 < _INF) & (hi - lo <= WIDTH * hi)
    return lo, hi, good


@njit(inline=True)
def _step(
    mu: float, lo: float, hi: float, rho: float, drho: float, usable: bool
) -> tuple[float, float, float]:
    """One step of the search from ``mu`` with bracket ``(lo, hi)`` in ``w``: the next ``mu``
    and the bracket."""
    w = mu / (1.0 + mu)
    below = usable & (rho < 1.0)
    above = usable & (rho > 1.0)
    lo2 = w if below else lo
    hi2 = w if above else hi
    nm = mu - (rho - 1.0) / drho
    nxt = nm / (1.0 + nm) if (usable & (nm > 0.0) & (nm < _INF)) else 2.0
    inside = (lo2 < nxt) & (nxt < hi2)
    nxt = nxt if inside else 0.5 * (lo2 + hi2)
    # a step this short is Newton's near the root: taken as it is
    near = usable & (abs(nm - mu) <= 1e-12 * mu) & (nm > 0.0)
    mu2 = nm if near else nxt / (1.0 - nxt)
    return mu2, lo2, hi2


@njit(inline=True)
def _certify_at(
    e: Any, q: Any, mu: float, detA: float, eA: float, detB: float, eB: float, detE: float, eE: float,
    detQ: float, eQ: float, out: Any, k: int,
) -> bool:  # fmt: skip  # pragma: no cover
    """The certificate at ``mu`` (:func:`_bounds`, :func:`_enclose`): where it holds, the
    enclosure of pair ``k`` goes to ``out[k]`` and the result is True."""
    l2, h2 = _bounds(e, q, mu, detA, eA, detB, eB, detE, eE, detQ, eQ)
    a, b, good = _enclose(l2, h2)
    if good:
        out[k, 0] = a
        out[k, 1] = b
    return good


@njit
def _scalar(Es: Any, Qs: Any, out: Any, flag: Any, start: int, stop: int) -> None:  # pragma: no cover
    """Pairs ``start .. stop``, one at a time: up to :data:`STEPS` steps of the search, the
    certificate after each step once the step is short; ``flag[k]`` 0 (certified) or 1."""
    for k in range(start, stop):
        out[k, 0] = -_INF
        out[k, 1] = _INF
        flag[k] = 1
        sg = -1.0 if Es[k, 0, 0] < 0.0 else 1.0
        sq = -1.0 if Qs[k, 0, 0] < 0.0 else 1.0
        e = signed_upper(Es, k, sg)
        q = signed_upper(Qs, k, sq)
        ok, detA, eA, detB, eB, detE, eE, detQ, eQ, mu = _setup(e, q)
        if not ok:
            continue
        rE = -detE / detA
        rQ = -detQ / detB
        lo = 0.0
        hi = 1.0
        if not (mu > 0.0 and mu < _INF):
            mu = 1.0
        for _ in range(STEPS):
            rho, drho, usable = _plain(e, q, mu, rE, rQ)
            mu2, lo, hi = _step(mu, lo, hi, rho, drho, usable)
            settled = usable and abs(mu2 - mu) <= 1e-9 * mu
            if settled and _certify_at(e, q, mu, detA, eA, detB, eB, detE, eE, detQ, eQ, out, k):
                flag[k] = 0
                break
            if not (hi - lo > 1e-17) or mu2 == mu:
                break
            mu = mu2
        # the search stopped: the certificate where it stopped
        if flag[k] == 1 and _certify_at(e, q, mu, detA, eA, detB, eB, detE, eE, detQ, eQ, out, k):
            flag[k] = 0


@njit
def _blocks(Es: Any, Qs: Any, out: Any, flag: Any, start: int, stop: int) -> None:  # pragma: no cover
    """Pairs ``start .. stop`` in blocks: ``flag[k]`` 0 (certified in the block), 2 (certified
    by the scalar kernel) or 1 (left to the exact path, ``out[k] = [-inf, inf]``)."""
    S = NB
    eb = np.empty(10 * S)
    qb = np.empty(10 * S)
    # per pair: ok, det A, its bound, det B, its bound, det E, its bound, det Q, its bound,
    # r_E, r_Q, mu, lo, hi (the bracket in w), certified, enclosure lo, hi
    st = np.empty(17 * S)
    for blo in range(start, stop, S):
        m = min(S, stop - blo)
        for t in range(m):
            k = blo + t
            sg = -1.0 if Es[k, 0, 0] < 0.0 else 1.0
            sq = -1.0 if Qs[k, 0, 0] < 0.0 else 1.0
            gather_signed(Es, k, eb, t, S, sg)
            gather_signed(Qs, k, qb, t, S, sq)
        for i in range(m):
            e = _load(eb, i, S)
            q = _load(qb, i, S)
            ok, detA, eA, detB, eB, detE, eE, detQ, eQ, mu0 = _setup(e, q)
            st[i] = 1.0 if ok else 0.0
            st[S + i] = detA
            st[2 * S + i] = eA
            st[3 * S + i] = detB
            st[4 * S + i] = eB
            st[5 * S + i] = detE
            st[6 * S + i] = eE
            st[7 * S + i] = detQ
            st[8 * S + i] = eQ
            st[9 * S + i] = -detE / detA
            st[10 * S + i] = -detQ / detB
            st[11 * S + i] = mu0 if ((mu0 > 0.0) & (mu0 < _INF)) else 1.0
            st[12 * S + i] = 0.0
            st[13 * S + i] = 1.0
        for _ in range(NEWTON):
            for i in range(m):
                e = _load(eb, i, S)
                q = _load(qb, i, S)
                mu = st[11 * S + i]
                rho, drho, usable = _plain(e, q, mu, st[9 * S + i], st[10 * S + i])
                mu2, lo, hi = _step(mu, st[12 * S + i], st[13 * S + i], rho, drho, usable)
                st[11 * S + i] = mu2
                st[12 * S + i] = lo
                st[13 * S + i] = hi
        for i in range(m):
            e = _load(eb, i, S)
            q = _load(qb, i, S)
            l2, h2 = _bounds(
                e,
                q,
                st[11 * S + i],
                st[S + i],
                st[2 * S + i],
                st[3 * S + i],
                st[4 * S + i],
                st[5 * S + i],
                st[6 * S + i],
                st[7 * S + i],
                st[8 * S + i],
            )
            a, b, good = _enclose(l2, h2)
            st[14 * S + i] = 1.0 if (good & (st[i] != 0.0)) else 0.0
            st[15 * S + i] = a
            st[16 * S + i] = b
        for i in range(m):
            k = blo + i
            if st[14 * S + i] != 0.0:
                out[k, 0] = st[15 * S + i]
                out[k, 1] = st[16 * S + i]
                flag[k] = 0
            else:
                _scalar(Es, Qs, out, flag, k, k + 1)
                if flag[k] == 0:
                    flag[k] = 2


def scale_both_stack(
    Es: np.ndarray, Qs: np.ndarray, *, blocks: bool = True, threads: int | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """Enclosures ``(n, 2)`` of the first-contact scale of two ellipsoids scaled together
    (``scale="both"``) on float64 stacks ``(n, 4, 4)``, and a mask of the pairs left to the exact
    path (their rows ``[-inf, inf]``).

    ``blocks``: the block kernel (the scalar kernel answering the pairs it does not certify), or
    the scalar kernel alone.  The matrices are symmetric (the kernels read their upper
    triangles; the public functions check it).

    Examples
    --------
    >>> E = np.diag([1.0, 1.0, 1.0, -1.0]); Q = np.diag([1.0, 1.0, 1.0, 0.0])
    >>> Q[0, 3] = Q[3, 0] = -3.0; Q[3, 3] = 8.0   # unit spheres 3 apart: s* = 3/2
    >>> enc, rest = scale_both_stack(E[None], Q[None])
    >>> bool(enc[0, 0] <= 1.5 <= enc[0, 1]), bool(rest[0]), float(enc[0, 1] - enc[0, 0]) < 1e-11
    (True, False, True)
    """
    out, flag = _flags(Es, Qs, blocks=blocks, threads=threads)
    return out, flag == 1


def _flags(
    Es: np.ndarray, Qs: np.ndarray, *, blocks: bool = True, threads: int | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """The enclosures and, for each pair, who answered it: 0 the block kernel (or the scalar
    kernel alone, ``blocks=False``), 2 the scalar kernel after the block kernel, 1 nobody."""
    return run_flags(_blocks if blocks else _scalar, Es, Qs, threads)
