"""The general binary64 kernels: the dynamic filter and plain float with exact facts.

They decide what the fast kernels of :mod:`quadric_contact.modes.kernels.criterion` leave
(:data:`~quadric_contact.modes.kernels.criterion.FALLBACK`), and everything for exact input
rounded to binary64, whose bounds need the constants for rounded inputs:

* the *dynamic filter* (the filter proper): the magnitude companion of every value (so an
  exact zero has an exact zero bound: structural zeros such as ``c0 = c1 = 0`` for a plane are
  recognised, never left to rounding), an exact power-of-two rescaling of the roots and
  coefficients, the relative and then the absolute form of the Delta bounds, equal quadratic
  parts (``Delta_4 = 0``) compared exactly, and the exact facts about the quadrics when the
  caller passes them (``det Q = 0``, ``rank Q <= 2``); the bounds are derived in
  :mod:`quadric_contact.modes.kernels.errorbounds`;
* *plain float* with the exact structural zeros: ``c0 = 0`` (``det Q = 0``) and ``c1 = 0``
  (``rank Q <= 2``) from per-quadric flags, ``Delta_4 = 0`` for proportional quadratic parts.

Layout: blocks of :data:`NB` pairs gathered into column buffers by the generated gathers
(``quadric_contact._generated.blocks``), straight-line loops that vectorise (each reads
buffers it does not write), then the decisions in a scalar loop.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from quadric_contact._generated import blocks, formulas, kernels
from quadric_contact.modes.codes import INVALID, UNCERTAIN
from quadric_contact.modes.decision.answers import (
    CONTACT_TABLE,
    ELLIPSOID_NOT,
    ELLIPSOID_UNCERTAIN,
    ELLIPSOID_YES,
    ROWS,
    ellipsoid_status,
    region_code_masked,
)
from quadric_contact.modes.kernels import errorbounds as eb
from quadric_contact.modes.kernels._jit import njit as _njit
from quadric_contact.modes.kernels.signs import plain_sign, sign_index, sign_within

__all__ = ["NB", "filter_kernel", "float_kernel"]

NB = 32
"""Pairs per block; the block buffers are 1-D, row ``k`` at ``k * NB`` (constant offsets from one
base pointer: the compiled loops then need no run-time overlap checks and vectorise)."""
_NB = NB

# The generated functions, compiled as they are (one source for numpy and numba).
_pencil = _njit(formulas.pencil_coefficients, inline=True)
_pencil_mag = _njit(kernels.pencil_coefficients_magnitude, inline=True)
_deltas = _njit(formulas.paper_deltas, inline=True)
_deltas_mag = _njit(kernels.paper_deltas_magnitude, inline=True)
_minors = _njit(kernels.leading_minors_3, inline=True)
_minors_mag = _njit(kernels.leading_minors_3_magnitude, inline=True)
_gather_full = _njit(blocks.gather_full, inline=True)
_load = _njit(blocks.load_upper, inline=True)
_abs10 = _njit(blocks.abs_upper, inline=True)
_nonfinite = _njit(blocks.nonfinite, inline=True)
_outside = _njit(blocks.outside_count, inline=True)
_ellipsoid_status = _njit(ellipsoid_status, inline=True)
_region_code_masked = region_code_masked

_INPUT_MIN = eb.INPUT_MIN
_INPUT_MAX = eb.INPUT_MAX
_COEF_MIN = eb.COEFFICIENT_MIN
_RHO_MAX = eb.RHO_MAX
_ROUND_UP = eb.ROUND_UP


@_njit(inline=True)
def _split(a: float) -> tuple[float, float]:
    """Veltkamp's splitting: ``a = hi + lo`` with halves of 26 bits (no overflow below 2^996)."""
    c = 134217729.0 * a
    hi = c - (c - a)
    return hi, a - hi


@_njit(inline=True)
def _same_product(a: float, b: float, c: float, d: float) -> bool:
    """``a b == c d`` exactly (Dekker's TwoProduct: ``a b = p + e`` with both floats), for
    factors that are zero or in ``[2^-400, 2^400]`` (then no error term underflows)."""
    p = a * b
    q = c * d
    if p != q:
        return False
    ah, al = _split(a)
    bh, bl = _split(b)
    ch, cl = _split(c)
    dh, dl = _split(d)
    e1 = ((ah * bh - p) + ah * bl + al * bh) + al * bl
    e2 = ((ch * dh - q) + ch * dl + cl * dh) + cl * dl
    return e1 == e2


@_njit(inline=True)
def _tame(x: float) -> bool:
    a = abs(x)
    return a == 0.0 or (2.0**-400 <= a <= 2.0**400)


@_njit(inline=True)
def _proportional(
    e00: float,
    e01: float,
    e02: float,
    e11: float,
    e12: float,
    e22: float,
    q00: float,
    q01: float,
    q02: float,
    q11: float,
    q12: float,
    q22: float,
) -> bool:
    """The quadratic part of ``Q`` is ``k`` times that of ``E`` (``e00 != 0``), decided
    exactly: then ``lambda = -k`` is a double root of ``P`` and ``Delta_4 = 0``
    identically (equal quadratic parts, as for the bee and the crown of Example 17, are
    ``k = 1``)."""
    if (
        not (
            _tame(e00)
            and _tame(e01)
            and _tame(e02)
            and _tame(e11)
            and _tame(e12)
            and _tame(e22)
            and _tame(q00)
            and _tame(q01)
            and _tame(q02)
            and _tame(q11)
            and _tame(q12)
            and _tame(q22)
        )
        or e00 == 0.0
    ):
        return False
    return (
        _same_product(q01, e00, q00, e01)
        and _same_product(q02, e00, q00, e02)
        and _same_product(q11, e00, q00, e11)
        and _same_product(q12, e00, q00, e12)
        and _same_product(q22, e00, q00, e22)
    )  # fmt: skip


_NO_EXPONENT = -100000


@_njit(inline=True)
def _gather(
    E: Any, Q: Any, eidx: Any, qidx: Any, es: int, qs: int, blo: int, m: int, eb_: Any, qb_: Any, qi: Any,
    asym: Any,
) -> None:  # fmt: skip
    """Copy a block of pairs into column buffers (the ten upper entries of each matrix, from
    ``(m, 16)`` flat arrays) and flag the asymmetric pairs in ``asym``."""
    for t in range(m):
        p = blo + t
        ie = eidx[p] if eidx.shape[0] > 0 else p * es
        iq = qidx[p] if qidx.shape[0] > 0 else p * qs
        qi[t] = iq
        bad = _gather_full(E, ie, eb_, t, _NB)
        bad = _gather_full(Q, iq, qb_, t, _NB) | bad
        asym[t] = 1.0 if bad else 0.0


@_njit(inline=True)
def _bad(e: Any, q: Any, asym: float) -> float:
    """Non-zero if an entry is not finite or a matrix is not symmetric.  Branch-free."""
    z = _nonfinite(e) + _nonfinite(q) + asym
    return 0.0 if z == 0.0 else 1.0


@_njit(inline=True)
def _scaled_guard(c: float, r: float, a: float, y: float) -> float:
    """Non-zero unless the scaled coefficient ``a = |c s|`` and bound ``y = r s`` are safe for
    the Delta stage: a non-zero ``c`` must stay at least COEFFICIENT_MIN (so an underflow to
    zero cannot pose as a structural zero), so must ``a + y`` when ``r != 0``, and a non-zero
    bound must stay normal (then the scaling was exact)."""
    g = ((c != 0.0) & (a < _COEF_MIN)) | ((r != 0.0) & (a + y < _COEF_MIN)) | ((r != 0.0) & (y < 2.0**-1022))
    return 1.0 if g else 0.0


@_njit(inline=True)
def _denominator(a: float, y: float) -> float:
    return a if a != 0.0 else (1e300 if y == 0.0 else _COEF_MIN)


# Rows of the filter's block buffers.  Every compiled loop reads buffers it does not
# write (so that the run-time overlap checks of the vectoriser pass): ``ra`` is written
# by the pencil loop, ``sb`` by the scale loop, ``rc`` by the Delta loop.
_C, _R, _T = 0, 5, 10  # 5 rows each in ra
_M2, _M2E, _M3, _M3E, _E00, _BAD, _OUT, _SAME = 15, 16, 17, 18, 19, 20, 21, 22
_ROWS_A = 23
_X, _Y, _D, _DE, _OUT2 = 0, 5, 10, 13, 16  # in rc (_DE: the magnitudes of Delta)
_ROWS_C = 17


def _filter_kernel_impl(
    E: Any,
    Q: Any,
    eidx: Any,
    qidx: Any,
    es: int,
    qs: int,
    lo: int,
    hi: int,
    KP: Any,
    KL: Any,
    DR: Any,
    DA: Any,
    qflags: Any,
    same_ok: bool,
    qrows: Any,
    qmasks: Any,
    want_region: bool,
    out: Any,
) -> None:
    """The filter on the pairs ``lo .. hi``.  Per block: gather (scalar), the pencil with its
    bounds (straight-line, vectorised), the scales (scalar bit work), the Delta stage
    (straight-line, vectorised), and the decisions (scalar)."""
    B = _NB
    eb_ = np.empty(10 * _NB)
    qb_ = np.empty(10 * _NB)
    asym = np.empty(_NB)
    qi = np.empty(B, np.intp)
    zb = np.empty(2 * _NB)
    ra = np.empty(_ROWS_A * _NB)
    sb = np.empty(5 * _NB)
    rc = np.empty(_ROWS_C * _NB)
    rai = ra.view(np.int64)
    sbi = sb.view(np.int64)
    K0, K1, K2, K3, K4 = KP[0], KP[1], KP[2], KP[3], KP[4]
    L2, L3 = KL[0], KL[1]
    same_flag = 1.0 if same_ok else 0.0
    for blo in range(lo, hi, B):
        m = min(B, hi - blo)
        _gather(E, Q, eidx, qidx, es, qs, blo, m, eb_, qb_, qi, asym)
        for t in range(m):
            z = qflags[qi[t]]
            zb[0 * _NB + t] = 1.0 if z & 1 else 0.0
            zb[1 * _NB + t] = 1.0 if z & 2 else 0.0
        for i in range(m):
            e00 = eb_[0 * _NB + i]
            e01 = eb_[1 * _NB + i]
            e02 = eb_[2 * _NB + i]
            e03 = eb_[3 * _NB + i]
            e11 = eb_[4 * _NB + i]
            e12 = eb_[5 * _NB + i]
            e13 = eb_[6 * _NB + i]
            e22 = eb_[7 * _NB + i]
            e23 = eb_[8 * _NB + i]
            e33 = eb_[9 * _NB + i]
            q00 = qb_[0 * _NB + i]
            q01 = qb_[1 * _NB + i]
            q02 = qb_[2 * _NB + i]
            q03 = qb_[3 * _NB + i]
            q11 = qb_[4 * _NB + i]
            q12 = qb_[5 * _NB + i]
            q13 = qb_[6 * _NB + i]
            q22 = qb_[7 * _NB + i]
            q23 = qb_[8 * _NB + i]
            q33 = qb_[9 * _NB + i]
            ev = _load(eb_, i, _NB)
            qv = _load(qb_, i, _NB)
            ra[_BAD * _NB + i] = _bad(ev, qv, asym[i])
            ra[_OUT * _NB + i] = _outside(_abs10(ev), _INPUT_MIN, _INPUT_MAX) + _outside(
                _abs10(qv), _INPUT_MIN, _INPUT_MAX
            )
            c0, c1, c2, c3, c4 = _pencil(
                e00, e01, e02, e03, e11, e12, e13, e22, e23, e33,
                q00, q01, q02, q03, q11, q12, q13, q22, q23, q33,
            )  # fmt: skip
            m0, m1, m2, m3, m4 = _pencil_mag(
                abs(e00), abs(e01), abs(e02), abs(e03), abs(e11), abs(e12), abs(e13), abs(e22), abs(e23),
                abs(e33), abs(q00), abs(q01), abs(q02), abs(q03), abs(q11), abs(q12), abs(q13), abs(q22),
                abs(q23), abs(q33),
            )  # fmt: skip
            r0 = K0 * m0
            r1 = K1 * m1
            r2 = K2 * m2
            r3 = K3 * m3
            r4 = K4 * m4
            # Structural zeros known exactly (rank of Q): det Q = 0 gives c0 = 0, rank <= 2 c1 = 0.
            c0 = 0.0 if zb[0 * _NB + i] != 0.0 else c0
            r0 = 0.0 if zb[0 * _NB + i] != 0.0 else r0
            c1 = 0.0 if zb[1 * _NB + i] != 0.0 else c1
            r1 = 0.0 if zb[1 * _NB + i] != 0.0 else r1
            # Proportional quadratic parts (compared exactly): lambda = -k is a double root,
            # so Delta_4 = 0 identically.
            prop = _proportional(e00, e01, e02, e11, e12, e22, q00, q01, q02, q11, q12, q22)
            ra[_SAME * _NB + i] = same_flag if prop else 0.0
            s2, s3 = _minors(e00, e01, e02, e11, e12, e22)
            t2, t3 = _minors_mag(abs(e00), abs(e01), abs(e02), abs(e11), abs(e12), abs(e22))
            ra[_M2 * _NB + i] = s2
            ra[_M2E * _NB + i] = L2 * t2
            ra[_M3 * _NB + i] = s3
            ra[_M3E * _NB + i] = L3 * t3
            ra[_E00 * _NB + i] = e00
            # The paper's sign of E: for -E the odd coefficients change sign (exact).
            o = -1.0 if e00 < 0.0 else 1.0
            c1 = o * c1
            c3 = o * c3
            ra[_C * _NB + i] = c0
            ra[(_C + 1) * _NB + i] = c1
            ra[(_C + 2) * _NB + i] = c2
            ra[(_C + 3) * _NB + i] = c3
            ra[(_C + 4) * _NB + i] = c4
            ra[_R * _NB + i] = r0
            ra[(_R + 1) * _NB + i] = r1
            ra[(_R + 2) * _NB + i] = r2
            ra[(_R + 3) * _NB + i] = r3
            ra[(_R + 4) * _NB + i] = r4
            ra[_T * _NB + i] = abs(c0) + r0
            ra[(_T + 1) * _NB + i] = abs(c1) + r1
            ra[(_T + 2) * _NB + i] = abs(c2) + r2
            ra[(_T + 3) * _NB + i] = abs(c3) + r3
            ra[(_T + 4) * _NB + i] = abs(c4) + r4
        for i in range(m):
            _scales(ra, rai, sbi, i)
        for i in range(m):
            c0 = ra[_C * _NB + i]
            c1 = ra[(_C + 1) * _NB + i]
            c2 = ra[(_C + 2) * _NB + i]
            c3 = ra[(_C + 3) * _NB + i]
            c4 = ra[(_C + 4) * _NB + i]
            r0 = ra[_R * _NB + i]
            r1 = ra[(_R + 1) * _NB + i]
            r2 = ra[(_R + 2) * _NB + i]
            r3 = ra[(_R + 3) * _NB + i]
            r4 = ra[(_R + 4) * _NB + i]
            x0 = c0 * sb[0 * _NB + i]
            x1 = c1 * sb[1 * _NB + i]
            x2 = c2 * sb[2 * _NB + i]
            x3 = c3 * sb[3 * _NB + i]
            x4 = c4 * sb[4 * _NB + i]
            y0 = r0 * sb[0 * _NB + i]
            y1 = r1 * sb[1 * _NB + i]
            y2 = r2 * sb[2 * _NB + i]
            y3 = r3 * sb[3 * _NB + i]
            y4 = r4 * sb[4 * _NB + i]
            a0 = abs(x0)
            a1 = abs(x1)
            a2 = abs(x2)
            a3 = abs(x3)
            a4 = abs(x4)
            rc[_OUT2 * _NB + i] = (
                _scaled_guard(c0, r0, a0, y0)
                + _scaled_guard(c1, r1, a1, y1)
                + _scaled_guard(c2, r2, a2, y2)
                + _scaled_guard(c3, r3, a3, y3)
                + _scaled_guard(c4, r4, a4, y4)
            )
            d2, d3, d4 = _deltas(x0, x1, x2, x3, x4)
            A2, A3, A4 = _deltas_mag(a0, a1, a2, a3, a4)
            d4 = 0.0 if ra[_SAME * _NB + i] != 0.0 else d4
            A4 = 0.0 if ra[_SAME * _NB + i] != 0.0 else A4
            rc[_D * _NB + i] = d2
            rc[(_D + 1) * _NB + i] = d3
            rc[(_D + 2) * _NB + i] = d4
            rc[_DE * _NB + i] = A2
            rc[(_DE + 1) * _NB + i] = A3
            rc[(_DE + 2) * _NB + i] = A4
            rc[_X * _NB + i] = x0
            rc[(_X + 1) * _NB + i] = x1
            rc[(_X + 2) * _NB + i] = x2
            rc[(_X + 3) * _NB + i] = x3
            rc[(_X + 4) * _NB + i] = x4
            rc[_Y * _NB + i] = y0
            rc[(_Y + 1) * _NB + i] = y1
            rc[(_Y + 2) * _NB + i] = y2
            rc[(_Y + 3) * _NB + i] = y3
            rc[(_Y + 4) * _NB + i] = y4
        for i in range(m):
            iq = qi[i] if want_region else 0
            out[blo + i] = _filter_decide(ra, rc, i, DR, DA, want_region, qrows[iq], qmasks[iq])


@_njit(inline=True)
def _exponent_bits(t: float, bits: int) -> int:
    """Binary exponent of ``t >= 0`` from its bit pattern (a huge negative number for 0)."""
    return ((bits >> 52) & 2047) - 1023 if t != 0.0 else _NO_EXPONENT


@_njit(inline=True)
def _pow2_bits(e: int, t: float) -> int:
    """Bit pattern of ``2^e``, ``e`` clamped into the normal range (for ``t = 0`` the factor
    multiplies an exact zero; for ``e < -1022`` the product fails the guard anyway)."""
    return (max(1, min(2046, e + 1023)) << 52) if t != 0.0 else (1023 << 52)


@_njit(inline=True)
def _scales(ra: Any, rai: Any, sbi: Any, i: int) -> None:
    """``sb[(:) * _NB + i]`` (written through its int64 view ``sbi``): the powers of two
    ``2^(g + m k)`` that scale ``c_k``, exactly: ``P`` becomes ``2^g P(2^m lambda)`` and every
    sign read later is unchanged; ``m`` (any value is sound: the guards catch an underflow)
    roughly balances the lowest non-zero coefficient against ``c4``, ``g`` puts the largest
    in ``[1, 2)``.  Bit work only, branch-free, so that the loop vectorises."""
    t0 = ra[_T * _NB + i]
    t1 = ra[(_T + 1) * _NB + i]
    t2 = ra[(_T + 2) * _NB + i]
    t3 = ra[(_T + 3) * _NB + i]
    t4 = ra[(_T + 4) * _NB + i]
    f0 = _exponent_bits(t0, rai[_T * _NB + i])
    f1 = _exponent_bits(t1, rai[(_T + 1) * _NB + i])
    f2 = _exponent_bits(t2, rai[(_T + 2) * _NB + i])
    f3 = _exponent_bits(t3, rai[(_T + 3) * _NB + i])
    f4 = _exponent_bits(t4, rai[(_T + 4) * _NB + i])
    low = f0 if f0 != _NO_EXPONENT else (f1 if f1 != _NO_EXPONENT else f2)
    mm = max(-400, min(400, (low - f4) >> 2)) if low != _NO_EXPONENT else 0
    g = -max(f0, f1 + mm, f2 + 2 * mm, f3 + 3 * mm, f4 + 4 * mm)
    sbi[0 * _NB + i] = _pow2_bits(g, t0)
    sbi[1 * _NB + i] = _pow2_bits(g + mm, t1)
    sbi[2 * _NB + i] = _pow2_bits(g + 2 * mm, t2)
    sbi[3 * _NB + i] = _pow2_bits(g + 3 * mm, t3)
    sbi[4 * _NB + i] = _pow2_bits(g + 4 * mm, t4)


@_njit(inline=True)
def _filter_decide(ra: Any, rc: Any, i: int, DR: Any, DA: Any, want_region: bool, row: int, mask: int) -> int:
    """The code of one pair from the filter's values and bounds."""
    if ra[_BAD * _NB + i] != 0.0:
        return INVALID
    e00 = ra[_E00 * _NB + i]
    sa = plain_sign(e00)
    ell = _ellipsoid_status(
        sa,
        sign_within(ra[_M2 * _NB + i], ra[_M2E * _NB + i]),
        sign_within(ra[_M3 * _NB + i], ra[_M3E * _NB + i]),
        sign_within(ra[(_C + 4) * _NB + i], ra[(_R + 4) * _NB + i]),
    )
    if ell == ELLIPSOID_NOT:
        return INVALID
    if ra[_OUT * _NB + i] + rc[_OUT2 * _NB + i] != 0.0 or ell == ELLIPSOID_UNCERTAIN:
        return UNCERTAIN
    contact = UNCERTAIN
    y0 = rc[_Y * _NB + i]
    y1 = rc[(_Y + 1) * _NB + i]
    y2 = rc[(_Y + 2) * _NB + i]
    y3 = rc[(_Y + 3) * _NB + i]
    y4 = rc[(_Y + 4) * _NB + i]
    # rho >= every y_k / a_k with one division: an exact zero (a = y = 0) drops out, a zero
    # with a non-zero bound makes rho huge (then the relative form does not apply).
    rho = max(y0, y1, y2, y3, y4) / min(
        _denominator(abs(rc[_X * _NB + i]), y0),
        _denominator(abs(rc[(_X + 1) * _NB + i]), y1),
        _denominator(abs(rc[(_X + 2) * _NB + i]), y2),
        _denominator(abs(rc[(_X + 3) * _NB + i]), y3),
        _denominator(abs(rc[(_X + 4) * _NB + i]), y4),
    )
    if rho <= _RHO_MAX:
        g2 = sign_within(rc[_D * _NB + i], (DR[0, 0] * rho + DR[0, 1]) * rc[_DE * _NB + i])
        g3 = sign_within(rc[(_D + 1) * _NB + i], (DR[1, 0] * rho + DR[1, 1]) * rc[(_DE + 1) * _NB + i])
        g4 = sign_within(rc[(_D + 2) * _NB + i], (DR[2, 0] * rho + DR[2, 1]) * rc[(_DE + 2) * _NB + i])
        contact = CONTACT_TABLE[sign_index(g2) + 4 * sign_index(g3) + 16 * sign_index(g4)]
    if contact == UNCERTAIN:
        # The absolute form: magnitudes at a and at b >= a + e (two programs).
        a0 = abs(rc[_X * _NB + i])
        a1 = abs(rc[(_X + 1) * _NB + i])
        a2 = abs(rc[(_X + 2) * _NB + i])
        a3 = abs(rc[(_X + 3) * _NB + i])
        a4 = abs(rc[(_X + 4) * _NB + i])
        b0 = (a0 + rc[_Y * _NB + i]) * _ROUND_UP
        b1 = (a1 + rc[(_Y + 1) * _NB + i]) * _ROUND_UP
        b2 = (a2 + rc[(_Y + 2) * _NB + i]) * _ROUND_UP
        b3 = (a3 + rc[(_Y + 3) * _NB + i]) * _ROUND_UP
        b4 = (a4 + rc[(_Y + 4) * _NB + i]) * _ROUND_UP
        A2, A3, A4 = _deltas_mag(a0, a1, a2, a3, a4)
        B2, B3, B4 = _deltas_mag(b0, b1, b2, b3, b4)
        g2 = sign_within(rc[_D * _NB + i], DA[0, 0] * (B2 - A2) + DA[0, 1] * A2)
        g3 = sign_within(rc[(_D + 1) * _NB + i], DA[1, 0] * (B3 - A3) + DA[1, 1] * A3)
        g4 = (
            0
            if ra[_SAME * _NB + i] != 0.0
            else sign_within(rc[(_D + 2) * _NB + i], DA[2, 0] * (B4 - A4) + DA[2, 1] * A4)
        )
        contact = CONTACT_TABLE[sign_index(g2) + 4 * sign_index(g3) + 16 * sign_index(g4)]
    if not want_region:
        return contact
    return _region_code_masked(
        contact,
        sign_within(rc[_X * _NB + i], rc[_Y * _NB + i]),
        sign_within(rc[(_X + 1) * _NB + i], rc[(_Y + 1) * _NB + i]),
        sign_within(rc[(_X + 2) * _NB + i], rc[(_Y + 2) * _NB + i]),
        sign_within(rc[(_X + 3) * _NB + i], rc[(_Y + 3) * _NB + i]),
        sign_within(rc[(_X + 4) * _NB + i], rc[(_Y + 4) * _NB + i]),
        row,
        mask,
        ROWS,
    )


def _float_kernel_impl(
    E: Any,
    Q: Any,
    eidx: Any,
    qidx: Any,
    es: int,
    qs: int,
    lo: int,
    hi: int,
    qrows: Any,
    qmasks: Any,
    want_region: bool,
    qflags: Any,
    same_ok: bool,
    prop: Any,
    out: Any,
) -> None:
    """Plain binary64 on the pairs ``lo .. hi`` (gather, straight-line arithmetic, decisions),
    with the filter's exact structural zeros: ``c0 = 0`` (``det Q = 0``) and ``c1 = 0``
    (``rank Q <= 2``) from the per-quadric flags, ``Delta_4 = 0`` for proportional quadratic
    parts."""
    B = _NB
    eb_ = np.empty(10 * _NB)
    qb_ = np.empty(10 * _NB)
    asym = np.empty(_NB)
    qi = np.empty(B, np.intp)
    cv = np.empty(5 * _NB)
    dv = np.empty(3 * _NB)
    mv = np.empty(2 * _NB)
    st = np.empty(2 * _NB)
    for blo in range(lo, hi, B):
        m = min(B, hi - blo)
        _gather(E, Q, eidx, qidx, es, qs, blo, m, eb_, qb_, qi, asym)
        for i in range(m):
            e00 = eb_[0 * _NB + i]
            e01 = eb_[1 * _NB + i]
            e02 = eb_[2 * _NB + i]
            e11 = eb_[4 * _NB + i]
            e12 = eb_[5 * _NB + i]
            e22 = eb_[7 * _NB + i]
            st[0 * _NB + i] = _bad(_load(eb_, i, _NB), _load(qb_, i, _NB), asym[i])
            st[1 * _NB + i] = e00
            c0, c1, c2, c3, c4 = _pencil(
                e00, e01, e02, eb_[3 * _NB + i], e11, e12, eb_[6 * _NB + i], e22, eb_[8 * _NB + i],
                eb_[9 * _NB + i], qb_[0 * _NB + i], qb_[1 * _NB + i], qb_[2 * _NB + i], qb_[3 * _NB + i],
                qb_[4 * _NB + i], qb_[5 * _NB + i], qb_[6 * _NB + i], qb_[7 * _NB + i], qb_[8 * _NB + i],
                qb_[9 * _NB + i],
            )  # fmt: skip
            s2, s3 = _minors(e00, e01, e02, e11, e12, e22)
            mv[0 * _NB + i] = s2
            mv[1 * _NB + i] = s3
            z = qflags[qi[i]]
            c0 = 0.0 if z & 1 else c0
            c1 = 0.0 if z & 2 else c1
            o = -1.0 if e00 < 0.0 else 1.0
            c1 = o * c1
            c3 = o * c3
            cv[0 * _NB + i] = c0
            cv[1 * _NB + i] = c1
            cv[2 * _NB + i] = c2
            cv[3 * _NB + i] = c3
            cv[4 * _NB + i] = c4
            d2, d3, d4 = _deltas(c0, c1, c2, c3, c4)
            if prop.shape[0] > 0:
                if prop[blo + i] != 0:
                    d4 = 0.0
            elif same_ok and _proportional(
                e00, e01, e02, e11, e12, e22,
                qb_[0 * _NB + i], qb_[1 * _NB + i], qb_[2 * _NB + i], qb_[4 * _NB + i], qb_[5 * _NB + i],
                qb_[7 * _NB + i],
            ):  # fmt: skip
                d4 = 0.0
            dv[0 * _NB + i] = d2
            dv[1 * _NB + i] = d3
            dv[2 * _NB + i] = d4
        for i in range(m):
            p = blo + i
            e00 = st[1 * _NB + i]
            sa = plain_sign(e00)
            ell = _ellipsoid_status(
                sa, plain_sign(mv[0 * _NB + i]), plain_sign(mv[1 * _NB + i]), plain_sign(cv[4 * _NB + i])
            )
            if st[0 * _NB + i] != 0.0 or ell != ELLIPSOID_YES:
                out[p] = INVALID
                continue
            contact = CONTACT_TABLE[
                sign_index(plain_sign(dv[0 * _NB + i]))
                + 4 * sign_index(plain_sign(dv[1 * _NB + i]))
                + 16 * sign_index(plain_sign(dv[2 * _NB + i]))
            ]
            if not want_region:
                out[p] = contact
                continue
            iq = qi[i]
            out[p] = _region_code_masked(
                contact,
                plain_sign(cv[0 * _NB + i]),
                plain_sign(cv[1 * _NB + i]),
                plain_sign(cv[2 * _NB + i]),
                plain_sign(cv[3 * _NB + i]),
                plain_sign(cv[4 * _NB + i]),
                qrows[iq],
                qmasks[iq],
                ROWS,
            )


filter_kernel = _njit(_filter_kernel_impl)
"""The dynamic filter on pairs ``lo .. hi`` of flat ``(m, 16)`` stacks (see the module docstring)."""
float_kernel = _njit(_float_kernel_impl)
"""Plain binary64 with exact structural zeros on pairs ``lo .. hi`` of flat ``(m, 16)`` stacks."""
