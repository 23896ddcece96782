"""The binary64 stages: plain ``float`` and the certified ``filter``.

Both evaluate the generated closed forms (:mod:`quadric_contact._generated`):
numba compiles the very functions of ``formulas.py`` and ``kernels.py`` into
loop kernels (``backend="numba"``), and numpy evaluates the same functions on
whole columns (``backend="numpy"``, the lambdify-style variant, also the
fallback when numba is missing).  The two give identical codes (tested).

The filter works in two stages, each reporting a sign only when it is certain
(the bounds are derived in :mod:`quadric_contact.modes.errorbounds`):

* the *screen* (Shewchuk's stage A): the pencil with static bounds (path counts
  times powers of the largest entries), the roots balanced and the coefficients
  normalised, the Deltas with their magnitude programs; it settles nearly every
  generic pair for little more than the price of plain float;
* the *filter proper*, for what the screen leaves: the magnitude companion of every
  value (so an exact zero gives an exact zero bound: structural zeros such as
  ``c0 = c1 = 0`` for a plane are recognised, never left to rounding), an exact
  power-of-two rescaling of the roots and coefficients, the relative and then the
  absolute form of the Delta bounds, equal quadratic parts (``Delta_4 = 0``) compared
  exactly, and a second pass with exact facts about the quadrics involved.

Anything still uncertain is ``UNCERTAIN`` and goes to the next stage of the mode.

Kernel layout: pairs are processed in blocks of :data:`_NB`; a block is gathered
from the ``(n, 4, 4)`` stacks into 1-D column buffers, computed in straight-line
loops that vectorise (each reads buffers it does not write; division is IEEE, see
:mod:`._jit`), then decided in a scalar loop.  Threads split the pair range
(:func:`run_parallel`); the kernels release the GIL.
"""

from __future__ import annotations

import contextlib
import os
import threading
from collections.abc import Callable, Iterator
from concurrent.futures import ThreadPoolExecutor
from typing import Any

import numpy as np

from .._generated import formulas, kernels
from . import errorbounds as eb
from ._jit import HAVE_NUMBA, numba
from ._jit import njit as _njit
from .base import INVALID, MatrixStack, NumberMode, Pairs
from .decisions import (
    CONTACT_TABLE,
    ELLIPSOID_NOT,
    ELLIPSOID_UNCERTAIN,
    ELLIPSOID_YES,
    ROWS,
    UNCERTAIN_ROW,
    ellipsoid_from_signs,
    ellipsoid_status,
    masks_from_invariant_signs,
    region_code_masked,
    rows_from_masks,
)
from .validation import exact_matrix, raise_not_ellipsoid, validate_rows

__all__ = [
    "BACKENDS",
    "BLOCK",
    "HAVE_NUMBA",
    "FilterMode",
    "FloatMode",
    "check_stack",
    "filter_quantities",
    "float_invariant_signs",
    "float_pairs",
    "region_codes_from_signs",
    "run_parallel",
]

BACKENDS = ("numba", "numpy") if HAVE_NUMBA else ("numpy",)
BLOCK = 256
"""Pairs per block of the numba kernels."""

_UNC = 2


# The generated functions, compiled as they are (one source for numpy and numba).
_pencil = _njit(formulas.pencil_coefficients, inline=True)
_pencil_mag = _njit(kernels.pencil_coefficients_magnitude, inline=True)
_deltas = _njit(formulas.paper_deltas, inline=True)
_deltas_mag = _njit(kernels.paper_deltas_magnitude, inline=True)
_minors = _njit(kernels.leading_minors_3, inline=True)
_minors_mag = _njit(kernels.leading_minors_3_magnitude, inline=True)
_invariants = _njit(kernels.quadric_invariants, inline=True)
_invariants_mag = _njit(kernels.quadric_invariants_magnitude, inline=True)
_ellipsoid_status = _njit(ellipsoid_status, inline=True)
_region_code_masked = region_code_masked

_INPUT_MIN = eb.INPUT_MIN
_INPUT_MAX = eb.INPUT_MAX
_COEF_MIN = eb.COEFFICIENT_MIN
_RHO_MAX = eb.RHO_MAX
_SCREEN_EPS = eb.SCREEN_EPS
_ROUND_UP = eb.ROUND_UP
_FLOAT_MAX = float(np.finfo(np.float64).max)


@_njit(inline=True)
def _sgn(v: float, err: float) -> int:
    """Three-valued sign of a value known to within ``err``."""
    if v > err:
        return 1
    if v < -err:
        return -1
    if err == 0.0:
        return 0
    return _UNC


@_njit(inline=True)
def _psgn(v: float) -> int:
    """Plain sign of a float."""
    if v > 0.0:
        return 1
    if v < 0.0:
        return -1
    return 0


@_njit(inline=True)
def _sidx(s: int) -> int:
    return 3 if s == _UNC else s + 1


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
    e00: float, e01: float, e02: float, e11: float, e12: float, e22: float,
    q00: float, q01: float, q02: float, q11: float, q12: float, q22: float,
) -> bool:
    """The quadratic part of ``Q`` is ``k`` times that of ``E`` (``e00 != 0``), decided
    exactly: then ``lambda = -k`` is a double root of ``P`` and ``Delta_4 = 0``
    identically (equal quadratic parts, as for the bee and the crown of Example 17, are
    ``k = 1``)."""
    if not (
        _tame(e00) and _tame(e01) and _tame(e02) and _tame(e11) and _tame(e12) and _tame(e22)
        and _tame(q00) and _tame(q01) and _tame(q02) and _tame(q11) and _tame(q12) and _tame(q22)
    ) or e00 == 0.0:
        return False
    return (
        _same_product(q01, e00, q00, e01)
        and _same_product(q02, e00, q00, e02)
        and _same_product(q11, e00, q00, e11)
        and _same_product(q12, e00, q00, e12)
        and _same_product(q22, e00, q00, e22)
    )  # fmt: skip


_NO_EXPONENT = -100000
_NB = 256
"""Pairs per block; the block buffers are 1-D, row ``k`` at ``k * _NB`` (constant offsets from
one base pointer: the compiled loops then need no run-time overlap checks and vectorise)."""


@_njit(inline=True)
def _gather(
    E: Any, Q: Any, eidx: Any, qidx: Any, es: int, qs: int, blo: int, m: int, eb_: Any, qb_: Any, qi: Any
) -> None:
    """Copy a block of pairs into column buffers: rows 0-9 the upper entries (codegen
    order), rows 10-15 the strictly lower ones (for the symmetry check)."""
    for t in range(m):
        p = blo + t
        ie = eidx[p] if eidx.shape[0] > 0 else p * es
        iq = qidx[p] if qidx.shape[0] > 0 else p * qs
        qi[t] = iq
        eb_[0 * _NB + t] = E[ie, 0, 0]
        eb_[1 * _NB + t] = E[ie, 0, 1]
        eb_[2 * _NB + t] = E[ie, 0, 2]
        eb_[3 * _NB + t] = E[ie, 0, 3]
        eb_[4 * _NB + t] = E[ie, 1, 1]
        eb_[5 * _NB + t] = E[ie, 1, 2]
        eb_[6 * _NB + t] = E[ie, 1, 3]
        eb_[7 * _NB + t] = E[ie, 2, 2]
        eb_[8 * _NB + t] = E[ie, 2, 3]
        eb_[9 * _NB + t] = E[ie, 3, 3]
        eb_[10 * _NB + t] = E[ie, 1, 0]
        eb_[11 * _NB + t] = E[ie, 2, 0]
        eb_[12 * _NB + t] = E[ie, 3, 0]
        eb_[13 * _NB + t] = E[ie, 2, 1]
        eb_[14 * _NB + t] = E[ie, 3, 1]
        eb_[15 * _NB + t] = E[ie, 3, 2]
        qb_[0 * _NB + t] = Q[iq, 0, 0]
        qb_[1 * _NB + t] = Q[iq, 0, 1]
        qb_[2 * _NB + t] = Q[iq, 0, 2]
        qb_[3 * _NB + t] = Q[iq, 0, 3]
        qb_[4 * _NB + t] = Q[iq, 1, 1]
        qb_[5 * _NB + t] = Q[iq, 1, 2]
        qb_[6 * _NB + t] = Q[iq, 1, 3]
        qb_[7 * _NB + t] = Q[iq, 2, 2]
        qb_[8 * _NB + t] = Q[iq, 2, 3]
        qb_[9 * _NB + t] = Q[iq, 3, 3]
        qb_[10 * _NB + t] = Q[iq, 1, 0]
        qb_[11 * _NB + t] = Q[iq, 2, 0]
        qb_[12 * _NB + t] = Q[iq, 3, 0]
        qb_[13 * _NB + t] = Q[iq, 2, 1]
        qb_[14 * _NB + t] = Q[iq, 3, 1]
        qb_[15 * _NB + t] = Q[iq, 3, 2]


@_njit(inline=True)
def _bad(b: Any, i: int) -> float:
    """Non-zero if an entry is not finite (``x * 0`` is NaN for inf and NaN) or the
    matrix is not symmetric (column ``i`` of a gathered buffer).  Branch-free."""
    z = (
        b[0 * _NB + i] * 0.0
        + b[1 * _NB + i] * 0.0
        + b[2 * _NB + i] * 0.0
        + b[3 * _NB + i] * 0.0
        + b[4 * _NB + i] * 0.0
        + b[5 * _NB + i] * 0.0
        + b[6 * _NB + i] * 0.0
        + b[7 * _NB + i] * 0.0
        + b[8 * _NB + i] * 0.0
        + b[9 * _NB + i] * 0.0
    )
    z += (
        abs(b[1 * _NB + i] - b[10 * _NB + i])
        + abs(b[2 * _NB + i] - b[11 * _NB + i])
        + abs(b[3 * _NB + i] - b[12 * _NB + i])
    )
    z += (
        abs(b[5 * _NB + i] - b[13 * _NB + i])
        + abs(b[6 * _NB + i] - b[14 * _NB + i])
        + abs(b[8 * _NB + i] - b[15 * _NB + i])
    )
    return 0.0 if z == 0.0 else 1.0


@_njit(inline=True)
def _out1(x: float) -> float:
    a = abs(x)
    return 1.0 if (a > _INPUT_MAX) | ((a < _INPUT_MIN) & (a != 0.0)) else 0.0


@_njit(inline=True)
def _outside(b: Any, i: int) -> float:
    """Non-zero if a non-zero entry is outside ``[INPUT_MIN, INPUT_MAX]``.  Branch-free."""
    return (
        _out1(b[0 * _NB + i])
        + _out1(b[1 * _NB + i])
        + _out1(b[2 * _NB + i])
        + _out1(b[3 * _NB + i])
        + _out1(b[4 * _NB + i])
        + _out1(b[5 * _NB + i])
        + _out1(b[6 * _NB + i])
        + _out1(b[7 * _NB + i])
        + _out1(b[8 * _NB + i])
        + _out1(b[9 * _NB + i])
    )


@_njit(inline=True)
def _nz(x: float) -> float:
    return abs(x) if x != 0.0 else _INPUT_MAX


@_njit(inline=True)
def _low(b: Any, i: int) -> float:
    """The smallest non-zero ``|entry|`` (``INPUT_MAX`` if all are zero).  Branch-free."""
    return min(
        _nz(b[0 * _NB + i]),
        _nz(b[1 * _NB + i]),
        _nz(b[2 * _NB + i]),
        _nz(b[3 * _NB + i]),
        _nz(b[4 * _NB + i]),
        _nz(b[5 * _NB + i]),
        _nz(b[6 * _NB + i]),
        _nz(b[7 * _NB + i]),
        _nz(b[8 * _NB + i]),
        _nz(b[9 * _NB + i]),
    )


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


def _filter_pairs_impl(
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
    eb_ = np.empty(16 * _NB)
    qb_ = np.empty(16 * _NB)
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
        _gather(E, Q, eidx, qidx, es, qs, blo, m, eb_, qb_, qi)
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
            ra[_BAD * _NB + i] = _bad(eb_, i) + _bad(qb_, i)
            ra[_OUT * _NB + i] = _outside(eb_, i) + _outside(qb_, i)
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
    sa = 1 if e00 > 0.0 else (-1 if e00 < 0.0 else 0)
    ell = _ellipsoid_status(
        sa,
        _sgn(ra[_M2 * _NB + i], ra[_M2E * _NB + i]),
        _sgn(ra[_M3 * _NB + i], ra[_M3E * _NB + i]),
        _sgn(ra[(_C + 4) * _NB + i], ra[(_R + 4) * _NB + i]),
    )
    if ell == ELLIPSOID_NOT:
        return INVALID
    if ra[_OUT * _NB + i] + rc[_OUT2 * _NB + i] != 0.0 or ell == ELLIPSOID_UNCERTAIN:
        return _UNC
    contact = _UNC
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
        g2 = _sgn(rc[_D * _NB + i], (DR[0, 0] * rho + DR[0, 1]) * rc[_DE * _NB + i])
        g3 = _sgn(rc[(_D + 1) * _NB + i], (DR[1, 0] * rho + DR[1, 1]) * rc[(_DE + 1) * _NB + i])
        g4 = _sgn(rc[(_D + 2) * _NB + i], (DR[2, 0] * rho + DR[2, 1]) * rc[(_DE + 2) * _NB + i])
        contact = CONTACT_TABLE[_sidx(g2) + 4 * _sidx(g3) + 16 * _sidx(g4)]
    if contact == _UNC:
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
        g2 = _sgn(rc[_D * _NB + i], DA[0, 0] * (B2 - A2) + DA[0, 1] * A2)
        g3 = _sgn(rc[(_D + 1) * _NB + i], DA[1, 0] * (B3 - A3) + DA[1, 1] * A3)
        g4 = (
            0
            if ra[_SAME * _NB + i] != 0.0
            else _sgn(rc[(_D + 2) * _NB + i], DA[2, 0] * (B4 - A4) + DA[2, 1] * A4)
        )
        contact = CONTACT_TABLE[_sidx(g2) + 4 * _sidx(g3) + 16 * _sidx(g4)]
    if not want_region:
        return contact
    return _region_code_masked(
        contact,
        _sgn(rc[_X * _NB + i], rc[_Y * _NB + i]),
        _sgn(rc[(_X + 1) * _NB + i], rc[(_Y + 1) * _NB + i]),
        _sgn(rc[(_X + 2) * _NB + i], rc[(_Y + 2) * _NB + i]),
        _sgn(rc[(_X + 3) * _NB + i], rc[(_Y + 3) * _NB + i]),
        _sgn(rc[(_X + 4) * _NB + i], rc[(_Y + 4) * _NB + i]),
        row,
        mask,
        ROWS,
    )


# Rows of the screen's block buffer.
_SC_X, _SC_D, _SC_DE = 0, 5, 8  # 5, 3, 3 rows
_SC_M2, _SC_M2E, _SC_M3, _SC_M3E, _SC_C4, _SC_R4, _SC_E00, _SC_BAD, _SC_FAIL = (
    11,
    12,
    13,
    14,
    15,
    16,
    17,
    18,
    19,
)
_SC_ROWS = 20


def _screen_pairs_impl(
    E: Any,
    Q: Any,
    eidx: Any,
    qidx: Any,
    es: int,
    qs: int,
    lo: int,
    hi: int,
    SP: Any,
    SM: Any,
    SD: Any,
    qrows: Any,
    qmasks: Any,
    want_region: bool,
    out: Any,
) -> None:
    """The screen (static bounds, see :mod:`~quadric_contact.modes.errorbounds`) on the pairs
    ``lo .. hi``: codes where it is sure, ``UNCERTAIN`` where the filter must look."""
    B = _NB
    eb_ = np.empty(16 * _NB)
    qb_ = np.empty(16 * _NB)
    qi = np.empty(B, np.intp)
    rb = np.empty(_SC_ROWS * _NB)
    S0, S1, S2, S3, S4 = SP[0], SP[1], SP[2], SP[3], SP[4]
    M2, M3 = SM[0], SM[1]
    D2, D3, D4 = SD[0], SD[1], SD[2]
    eps = _SCREEN_EPS
    for blo in range(lo, hi, B):
        m = min(B, hi - blo)
        _gather(E, Q, eidx, qidx, es, qs, blo, m, eb_, qb_, qi)
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
            rb[_SC_BAD * _NB + i] = _bad(eb_, i) + _bad(qb_, i)
            c0, c1, c2, c3, c4 = _pencil(
                e00, e01, e02, e03, e11, e12, e13, e22, e23, e33,
                q00, q01, q02, q03, q11, q12, q13, q22, q23, q33,
            )  # fmt: skip
            ma = max(abs(e00), abs(e01), abs(e02), abs(e11), abs(e12), abs(e22))
            me = max(ma, abs(e03), abs(e13), abs(e23), abs(e33))
            plane = max(abs(q00), abs(q01), abs(q02), abs(q11), abs(q12), abs(q22)) == 0.0
            mq = max(
                abs(q00),
                abs(q01),
                abs(q02),
                abs(q03),
                abs(q11),
                abs(q12),
                abs(q13),
                abs(q22),
                abs(q23),
                abs(q33),
            )
            # The input guard: every entry at most INPUT_MAX, every non-zero one at least
            # INPUT_MIN (NaN and infinities are caught as bad input first).
            low = min(_low(eb_, i), _low(qb_, i))
            fail = 1.0 if (me > _INPUT_MAX) | (mq > _INPUT_MAX) | (low < _INPUT_MIN) else 0.0
            me2 = me * me
            mq2 = mq * mq
            r0 = S0 * (mq2 * mq2)
            r1 = S1 * ((me * mq) * mq2)
            r2 = S2 * (me2 * mq2)
            r3 = S3 * ((me * mq) * me2)
            r4 = S4 * (me2 * me2)
            # A zero quadratic part of Q: c0 = c1 = 0 exactly (see errorbounds).
            r0 = 0.0 if plane else r0
            r1 = 0.0 if plane else r1
            # Every coefficient known to relative error eps (an exact zero needs a zero bound).
            fail += (
                (r0 > eps * abs(c0))
                + (r1 > eps * abs(c1))
                + (r2 > eps * abs(c2))
                + (r3 > eps * abs(c3))
                + (r4 > eps * abs(c4))
            )
            s2, s3 = _minors(e00, e01, e02, e11, e12, e22)
            rb[_SC_M2 * _NB + i] = s2
            rb[_SC_M2E * _NB + i] = M2 * (ma * ma)
            rb[_SC_M3 * _NB + i] = s3
            rb[_SC_M3E * _NB + i] = M3 * ((ma * ma) * ma)
            rb[_SC_C4 * _NB + i] = c4
            rb[_SC_R4 * _NB + i] = r4
            rb[_SC_E00 * _NB + i] = e00
            o = -1.0 if e00 < 0.0 else 1.0
            c1 = o * c1
            c3 = o * c3
            # Balance the roots and normalise, with two positive factors (see errorbounds).
            beta = np.sqrt(np.sqrt(abs(c0) / abs(c4)))
            beta = beta if (beta > 0.0) & (beta < _FLOAT_MAX) else 1.0
            b2 = beta * beta
            t0 = c0
            t1 = c1 * beta
            t2 = c2 * b2
            t3 = c3 * (b2 * beta)
            t4 = c4 * (b2 * b2)
            top = max(abs(t0), abs(t1), abs(t2), abs(t3), abs(t4))
            # the products above stayed normal (or are exact zeros)
            fail += (not (top <= _FLOAT_MAX)) + (top < 2.0**-1022)
            fail += (
                ((t0 != 0.0) & (abs(t0) < 2.0**-1022))
                + ((t1 != 0.0) & (abs(t1) < 2.0**-1022))
                + ((t2 != 0.0) & (abs(t2) < 2.0**-1022))
                + ((t3 != 0.0) & (abs(t3) < 2.0**-1022))
                + ((t4 != 0.0) & (abs(t4) < 2.0**-1022))
            )
            sc = 1.0 / top
            x0 = t0 * sc
            x1 = t1 * sc
            x2 = t2 * sc
            x3 = t3 * sc
            x4 = t4 * sc
            fail += (
                ((x0 != 0.0) & (abs(x0) < _COEF_MIN))
                + ((x1 != 0.0) & (abs(x1) < _COEF_MIN))
                + ((x2 != 0.0) & (abs(x2) < _COEF_MIN))
                + ((x3 != 0.0) & (abs(x3) < _COEF_MIN))
                + ((x4 != 0.0) & (abs(x4) < _COEF_MIN))
            )
            d2, d3, d4 = _deltas(x0, x1, x2, x3, x4)
            A2, A3, A4 = _deltas_mag(abs(x0), abs(x1), abs(x2), abs(x3), abs(x4))
            rb[_SC_DE * _NB + i] = D2 * A2
            rb[(_SC_DE + 1) * _NB + i] = D3 * A3
            rb[(_SC_DE + 2) * _NB + i] = D4 * A4
            rb[_SC_X * _NB + i] = x0
            rb[(_SC_X + 1) * _NB + i] = x1
            rb[(_SC_X + 2) * _NB + i] = x2
            rb[(_SC_X + 3) * _NB + i] = x3
            rb[(_SC_X + 4) * _NB + i] = x4
            rb[_SC_D * _NB + i] = d2
            rb[(_SC_D + 1) * _NB + i] = d3
            rb[(_SC_D + 2) * _NB + i] = d4
            rb[_SC_FAIL * _NB + i] = fail
        for i in range(m):
            iq = qi[i] if want_region else 0
            out[blo + i] = _screen_decide(rb, i, SD, want_region, qrows[iq], qmasks[iq])


@_njit(inline=True)
def _screen_decide(rb: Any, i: int, SD: Any, want_region: bool, row: int, mask: int) -> int:
    if rb[_SC_BAD * _NB + i] != 0.0:
        return INVALID
    e00 = rb[_SC_E00 * _NB + i]
    sa = 1 if e00 > 0.0 else (-1 if e00 < 0.0 else 0)
    ell = _ellipsoid_status(
        sa,
        _sgn(rb[_SC_M2 * _NB + i], rb[_SC_M2E * _NB + i]),
        _sgn(rb[_SC_M3 * _NB + i], rb[_SC_M3E * _NB + i]),
        _sgn(rb[_SC_C4 * _NB + i], rb[_SC_R4 * _NB + i]),
    )
    if ell == ELLIPSOID_NOT:
        return INVALID
    if rb[_SC_FAIL * _NB + i] != 0.0 or ell == ELLIPSOID_UNCERTAIN:
        return _UNC
    g2 = _sgn(rb[_SC_D * _NB + i], rb[_SC_DE * _NB + i])
    g3 = _sgn(rb[(_SC_D + 1) * _NB + i], rb[(_SC_DE + 1) * _NB + i])
    g4 = _sgn(rb[(_SC_D + 2) * _NB + i], rb[(_SC_DE + 2) * _NB + i])
    contact = CONTACT_TABLE[_sidx(g2) + 4 * _sidx(g3) + 16 * _sidx(g4)]
    if not want_region:
        return contact
    # Every coefficient passed r_k <= eps |c_k|: its sign is certain (exact zeros have r_k = 0).
    return _region_code_masked(
        contact,
        _psgn(rb[_SC_X * _NB + i]),
        _psgn(rb[(_SC_X + 1) * _NB + i]),
        _psgn(rb[(_SC_X + 2) * _NB + i]),
        _psgn(rb[(_SC_X + 3) * _NB + i]),
        _psgn(rb[(_SC_X + 4) * _NB + i]),
        row,
        mask,
        ROWS,
    )


def _float_pairs_impl(
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
    eb_ = np.empty(16 * _NB)
    qb_ = np.empty(16 * _NB)
    qi = np.empty(B, np.intp)
    cv = np.empty(5 * _NB)
    dv = np.empty(3 * _NB)
    mv = np.empty(2 * _NB)
    st = np.empty(2 * _NB)
    for blo in range(lo, hi, B):
        m = min(B, hi - blo)
        _gather(E, Q, eidx, qidx, es, qs, blo, m, eb_, qb_, qi)
        for i in range(m):
            e00 = eb_[0 * _NB + i]
            e01 = eb_[1 * _NB + i]
            e02 = eb_[2 * _NB + i]
            e11 = eb_[4 * _NB + i]
            e12 = eb_[5 * _NB + i]
            e22 = eb_[7 * _NB + i]
            st[0 * _NB + i] = _bad(eb_, i) + _bad(qb_, i)
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
            sa = 1 if e00 > 0.0 else (-1 if e00 < 0.0 else 0)
            ell = _ellipsoid_status(
                sa, _psgn(mv[0 * _NB + i]), _psgn(mv[1 * _NB + i]), _psgn(cv[4 * _NB + i])
            )
            if st[0 * _NB + i] != 0.0 or ell != ELLIPSOID_YES:
                out[p] = INVALID
                continue
            contact = CONTACT_TABLE[
                _sidx(_psgn(dv[0 * _NB + i]))
                + 4 * _sidx(_psgn(dv[1 * _NB + i]))
                + 16 * _sidx(_psgn(dv[2 * _NB + i]))
            ]
            if not want_region:
                out[p] = contact
                continue
            iq = qi[i]
            out[p] = _region_code_masked(
                contact,
                _psgn(cv[0 * _NB + i]),
                _psgn(cv[1 * _NB + i]),
                _psgn(cv[2 * _NB + i]),
                _psgn(cv[3 * _NB + i]),
                _psgn(cv[4 * _NB + i]),
                qrows[iq],
                qmasks[iq],
                ROWS,
            )


def _invariant_signs_impl(Q: Any, lo: int, hi: int, K: Any, filtered: bool, out: Any) -> None:
    """Signs of ``(trA, J, detA, E1, E2, E3, E4, q33)`` for ``Q[lo:hi]``; with
    ``filtered`` the bounded ones, and all ``UNCERTAIN`` outside the guard."""
    for p in range(lo, hi):
        q00 = Q[p, 0, 0]
        q01 = Q[p, 0, 1]
        q02 = Q[p, 0, 2]
        q03 = Q[p, 0, 3]
        q11 = Q[p, 1, 1]
        q12 = Q[p, 1, 2]
        q13 = Q[p, 1, 3]
        q22 = Q[p, 2, 2]
        q23 = Q[p, 2, 3]
        q33 = Q[p, 3, 3]
        v = _invariants(q00, q01, q02, q03, q11, q12, q13, q22, q23, q33)
        out[p, 7] = _psgn(q33)
        if not filtered:
            for k in range(7):
                out[p, k] = _psgn(v[k])
            continue
        g = 0.0
        for x in (q00, q01, q02, q03, q11, q12, q13, q22, q23, q33):
            a = abs(x)
            g += (not (a <= _INPUT_MAX)) + ((a < _INPUT_MIN) & (a != 0.0))
        mags = _invariants_mag(
            abs(q00), abs(q01), abs(q02), abs(q03), abs(q11), abs(q12), abs(q13), abs(q22), abs(q23), abs(q33)
        )
        for k in range(7):
            out[p, k] = _UNC if g != 0.0 else _sgn(v[k], K[k] * mags[k])


def _check_stack_impl(M: Any, lo: int, hi: int, out: Any) -> None:
    """1 where a matrix has a non-finite entry, 2 where it is not symmetric, else 0."""
    for p in range(lo, hi):
        flag = 0
        for i in range(4):
            for j in range(4):
                x = M[p, i, j]
                if not (abs(x) <= _FLOAT_MAX):
                    flag = 1
        if flag == 0:
            for i in range(4):
                for j in range(i + 1, 4):
                    if M[p, i, j] != M[p, j, i]:
                        flag = 2
        out[p] = flag


def _region_codes_impl(contact: Any, csigns: Any, rows: Any, masks: Any, out: Any) -> None:
    for p in range(contact.shape[0]):
        out[p] = _region_code_masked(
            contact[p],
            csigns[p, 0],
            csigns[p, 1],
            csigns[p, 2],
            csigns[p, 3],
            csigns[p, 4],
            rows[p],
            masks[p],
            ROWS,
        )


def _read_all_impl(E: Any, Q: Any, lo: int, hi: int) -> float:
    s = 0.0
    for p in range(lo, hi):
        for i in range(4):
            for j in range(4):
                s += E[p, i, j] + Q[p, i, j]
    return s


_filter_pairs = _njit(_filter_pairs_impl)
_screen_pairs = _njit(_screen_pairs_impl)
_float_pairs = _njit(_float_pairs_impl)
_invariant_signs = _njit(_invariant_signs_impl)
_check_stack = _njit(_check_stack_impl)
_region_codes = _njit(_region_codes_impl)


_read_all = (
    numba.njit(nogil=True, fastmath=True, cache=True)(_read_all_impl) if HAVE_NUMBA else _read_all_impl
)


def read_all(E: np.ndarray, Q: np.ndarray) -> float:
    """Read every entry of two ``(n, 4, 4)`` stacks once (compiled, threaded, reassociated
    sum): the memory-bandwidth floor of any kernel that reads them."""
    parts: list[float] = []
    run_parallel(lambda lo, hi: parts.append(_read_all(E, Q, lo, hi)), E.shape[0])
    return float(sum(parts))


# -- threads -----------------------------------------------------------------------------

_THREADS = max(1, min(os.cpu_count() or 1, int(os.environ.get("QUADRIC_CONTACT_THREADS", "0") or 0) or 64))
_MIN_PER_THREAD = 16384


_local = threading.local()


@contextlib.contextmanager
def single_threaded() -> Iterator[None]:
    """Run the kernels of this thread on this thread only (dask provides the parallelism)."""
    old = getattr(_local, "threads", None)
    _local.threads = 1
    try:
        yield
    finally:
        _local.threads = old


def run_parallel(kernel: Callable[..., None], n: int, threads: int | None = None) -> None:
    """Call ``kernel(lo, hi)`` on slices of ``range(n)``, on several threads when it pays
    (the numba kernels release the GIL).  One thread inside :func:`single_threaded`."""
    t = _THREADS if threads is None else max(1, threads)
    t = min(t, getattr(_local, "threads", None) or t)
    t = min(t, max(1, n // _MIN_PER_THREAD))
    if t <= 1 or not HAVE_NUMBA:
        kernel(0, n)
        return
    bounds = [n * k // t for k in range(t + 1)]
    with ThreadPoolExecutor(max_workers=t) as pool:
        list(pool.map(lambda k: kernel(bounds[k], bounds[k + 1]), range(t)))


# -- public entry points --------------------------------------------------------------------


def _constants(rounded: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    KP = np.array(eb.PENCIL_ERRBOUND[rounded])
    KL = np.array(eb.MINORS_ERRBOUND[rounded])
    DR = np.array(eb.DELTA_RELATIVE)
    DA = np.array(eb.DELTA_ABSOLUTE)
    return KP, KL, DR, DA


def float_pairs(
    E: np.ndarray,
    Q: np.ndarray,
    indices: tuple[np.ndarray, np.ndarray, int, int],
    n: int,
    *,
    filtered: bool,
    rounded: bool = False,
    qrows: np.ndarray | None = None,
    qmasks: np.ndarray | None = None,
    qflags: np.ndarray | None = None,
    same_ok: bool = False,
    prop: np.ndarray | None = None,
    backend: str = "numba",
    threads: int | None = None,
) -> np.ndarray:
    """Codes for ``n`` pairs of the float64 stacks ``E``, ``Q`` (``(m, 4, 4)``).

    ``prop`` (plain float only): per pair, whether the quadratic parts are proportional,
    decided exactly beforehand (for rounded exact input, whose floats cannot tell).

    Returns :class:`ContactCode` values (or :class:`RegionCode` values when
    ``qrows``, the row of every quadric, is given), ``UNCERTAIN`` where the
    filter cannot decide and :data:`~quadric_contact.modes.base.INVALID` where an
    input fails validation.
    """
    eidx, qidx, es, qs = indices
    want_region = qrows is not None
    flags = (
        np.zeros(Q.shape[0], dtype=np.int8) if qflags is None else np.ascontiguousarray(qflags, dtype=np.int8)
    )
    rows = np.zeros(1, dtype=np.int16) if qrows is None else np.ascontiguousarray(qrows, dtype=np.int16)
    masks = np.zeros(1, dtype=np.int64) if qmasks is None else np.ascontiguousarray(qmasks, dtype=np.int64)
    out = np.empty(n, dtype=np.int8)
    pp = np.zeros(0, dtype=np.int8) if prop is None else np.ascontiguousarray(prop, dtype=np.int8)
    if n == 0:
        return out
    if backend == "numpy" or not HAVE_NUMBA:
        return _numpy_pairs(
            E, Q, eidx, qidx, es, qs, n, filtered, rounded, rows, masks, want_region, flags, same_ok, pp
        )
    if backend != "numba":
        raise ValueError(f"backend must be one of {BACKENDS}, got {backend!r}")
    if filtered:
        KP, KL, DR, DA = _constants(rounded)
        SP = np.array(eb.SCREEN_PENCIL[rounded])
        SM = np.array(eb.SCREEN_MINORS[rounded])
        SD = np.array(eb.SCREEN_DELTA)
        run_parallel(
            lambda lo, hi: _screen_pairs(
                E, Q, eidx, qidx, es, qs, lo, hi, SP, SM, SD, rows, masks, want_region, out
            ),
            n,
            threads,
        )
        todo = np.flatnonzero(out == _UNC)
        if todo.size == 0:
            return out
        # What the screen leaves goes to the filter proper (same kernels, on the subset).
        sub_e = (eidx[todo] if eidx.shape[0] else todo * es).astype(np.intp)
        sub_q = (qidx[todo] if qidx.shape[0] else todo * qs).astype(np.intp)
        sub = np.empty(todo.size, dtype=np.int8)
        run_parallel(
            lambda lo, hi: _filter_pairs(
                E,
                Q,
                sub_e,
                sub_q,
                0,
                0,
                lo,
                hi,
                KP,
                KL,
                DR,
                DA,
                flags,
                same_ok,
                rows,
                masks,
                want_region,
                sub,
            ),
            todo.size,
            threads,
        )
        out[todo] = sub
        return out
    if filtered:
        run_parallel(
            lambda lo, hi: _filter_pairs(
                E,
                Q,
                eidx,
                qidx,
                es,
                qs,
                lo,
                hi,
                KP,
                KL,
                DR,
                DA,
                flags,
                same_ok,
                rows,
                masks,
                want_region,
                out,
            ),
            n,
            threads,
        )
    else:
        run_parallel(
            lambda lo, hi: _float_pairs(
                E, Q, eidx, qidx, es, qs, lo, hi, rows, masks, want_region, flags, same_ok, pp, out
            ),
            n,
            threads,
        )
    return out


def stage_codes(E: np.ndarray, Q: np.ndarray, stage: str, *, backend: str = "numba") -> np.ndarray:
    """Contact codes of one stage alone (``"screen"`` or ``"filter"``) for the pairs
    ``(E[k], Q[k])`` of two ``(n, 4, 4)`` binary64 stacks: for tests and measurements."""
    n = E.shape[0]
    out = np.empty(n, dtype=np.int8)
    e0 = np.zeros(0, dtype=np.intp)
    rows, masks = np.zeros(1, dtype=np.int16), np.zeros(1, dtype=np.int64)
    if backend == "numba" and HAVE_NUMBA:
        if stage == "screen":
            SP, SM, SD = (
                np.array(v) for v in (eb.SCREEN_PENCIL[False], eb.SCREEN_MINORS[False], eb.SCREEN_DELTA)
            )
            _screen_pairs(E, Q, e0, e0, 1, 1, 0, n, SP, SM, SD, rows, masks, False, out)
        else:
            KP, KL, DR, DA = _constants(False)
            flags = np.zeros(Q.shape[0], dtype=np.int8)
            _filter_pairs(E, Q, e0, e0, 1, 1, 0, n, KP, KL, DR, DA, flags, True, rows, masks, False, out)
        return out
    if stage == "screen":
        q = screen_quantities(E, Q)
        code = CONTACT_TABLE[_table_index(q["signs"][5:])]
        code = np.where(q["fail"] | (q["ell"] == ELLIPSOID_UNCERTAIN), _UNC, code)
    else:
        q = filter_quantities(E, Q)
        code = CONTACT_TABLE[_table_index(q["signs"][5:])]
        code = np.where(q["outside"] | (q["ell"] == ELLIPSOID_UNCERTAIN), _UNC, code)
    bad = ~(np.isfinite(E).all(axis=(1, 2)) & np.isfinite(Q).all(axis=(1, 2)))
    bad |= ~((np.swapaxes(E, 1, 2) == E).all(axis=(1, 2)) & (np.swapaxes(Q, 1, 2) == Q).all(axis=(1, 2)))
    return np.where(bad | (q["ell"] == ELLIPSOID_NOT), INVALID, code).astype(np.int8)


def float_invariant_signs(
    Q: np.ndarray, *, filtered: bool, rounded: bool = False, backend: str = "numba"
) -> np.ndarray:
    """``(m, 8)`` int8 signs of ``(trA, J, detA, E1, E2, E3, E4, q33)`` for every quadric."""
    out = np.empty((Q.shape[0], 8), dtype=np.int8)
    K = np.array(eb.INVARIANTS_ERRBOUND[rounded])
    if backend == "numpy" or not HAVE_NUMBA:
        return _numpy_invariant_signs(Q, filtered, K)
    _invariant_signs(Q, 0, Q.shape[0], K, filtered, out)
    return out


def check_stack(M: np.ndarray) -> np.ndarray:
    """Per matrix: 0 fine, 1 a non-finite entry, 2 not symmetric."""
    out = np.empty(M.shape[0], dtype=np.int8)
    if HAVE_NUMBA:
        run_parallel(lambda lo, hi: _check_stack(M, lo, hi, out), M.shape[0])
        return out
    finite = np.isfinite(M).all(axis=(1, 2))
    sym = (np.swapaxes(M, 1, 2) == M).all(axis=(1, 2))
    out[:] = np.where(~finite, 1, np.where(~sym, 2, 0))
    return out


def region_codes_from_signs(
    contact: np.ndarray, csigns: np.ndarray, rows: np.ndarray, masks: np.ndarray
) -> np.ndarray:
    """Region codes from contact codes, c-signs and the rows/masks of the quadrics (per pair)."""
    out = np.empty(contact.shape[0], dtype=np.int8)
    if HAVE_NUMBA:
        _region_codes(contact, csigns, rows.astype(np.int16), masks.astype(np.int64), out)
        return out
    for p in range(contact.shape[0]):
        out[p] = region_code_masked(
            int(contact[p]), *(int(v) for v in csigns[p]), int(rows[p]), int(masks[p]), ROWS
        )
    return out


# -- the numpy variant: the same generated functions on whole columns ------------------------

_NUMPY_CHUNK = 1 << 16


def _numpy_sign(v: np.ndarray, err: np.ndarray | None) -> np.ndarray:
    if err is None:
        return np.sign(v).astype(np.int8)
    s = np.where(v > err, 1, np.where(v < -err, -1, np.where(err == 0.0, 0, _UNC)))
    return s.astype(np.int8)


def _table_index(signs: list[np.ndarray]) -> np.ndarray:
    return sum(m * np.where(x == _UNC, 3, x + 1) for m, x in zip((1, 4, 16), signs, strict=True))  # type: ignore[return-value]


def _split_np(a: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    c = 134217729.0 * a
    hi = c - (c - a)
    return hi, a - hi


def proportional_quadratic_parts(A_e: np.ndarray, A_q: np.ndarray) -> np.ndarray:
    """numpy variant of the kernels' exact test that ``A_q = k A_e`` (``(6, k)`` arrays of the
    quadratic parts' upper entries ``00, 01, 02, 11, 12, 22``): ``q_ij e00 == q00 e_ij``
    exactly, by Dekker's TwoProduct, for entries that are zero or in ``[2^-400, 2^400]``."""
    with np.errstate(all="ignore"):
        absv = np.abs(np.concatenate([A_e, A_q]))
        tame = ((absv == 0) | ((absv >= 2.0**-400) & (absv <= 2.0**400))).all(axis=0) & (A_e[0] != 0)
        e00, q00 = A_e[0], A_q[0]
        ok = tame.copy()
        for t in range(1, 6):
            a, b, c, d = A_q[t], e00, q00, A_e[t]
            p, q = a * b, c * d
            ah, al = _split_np(a)
            bh, bl = _split_np(b)
            ch, cl = _split_np(c)
            dh, dl = _split_np(d)
            e1 = ((ah * bh - p) + ah * bl + al * bh) + al * bl
            e2 = ((ch * dh - q) + ch * dl + cl * dh) + cl * dl
            ok &= (p == q) & (e1 == e2)
    return ok


def filter_quantities(
    Em: np.ndarray,
    Qm: np.ndarray,
    *,
    rounded: bool = False,
    zflags: np.ndarray | None = None,
    same_ok: bool = True,
) -> dict[str, Any]:
    """Everything the filter computes for the pairs ``(Em[k], Qm[k])`` (numpy variant; the
    compiled kernels compute the same numbers in the same order).

    Keys: ``c``, ``r`` (coefficients for the paper's sign of E and their bounds),
    ``s`` (the power of two that scales each), ``x``, ``y`` (scaled), ``rho``, ``d`` (Delta_2..4 of
    ``x``), ``bound_relative``, ``bound_absolute`` (their two bounds), ``same``
    (equal quadratic parts), ``outside`` (a guard failed), ``ell`` (ellipsoid status),
    ``signs`` (the signs the filter reports for c0..c4 and Delta_2..4).
    """
    from ..codegen import ENTRY_INDICES

    KP, KL, DR, DA = _constants(rounded)
    k = Em.shape[0]
    z = np.zeros(k, dtype=np.int8) if zflags is None else zflags
    e = [Em[:, i, j] for i, j in ENTRY_INDICES]
    q = [Qm[:, i, j] for i, j in ENTRY_INDICES]
    with np.errstate(all="ignore"):
        c = list(formulas.pencil_coefficients(*e, *q))
        mi = kernels.leading_minors_3(e[0], e[1], e[2], e[4], e[5], e[7])
        c[0] = np.where(z & 1, 0.0, c[0])
        c[1] = np.where(z & 2, 0.0, c[1])
        A_e = np.stack([e[t] for t in (0, 1, 2, 4, 5, 7)])
        A_q = np.stack([q[t] for t in (0, 1, 2, 4, 5, 7)])
        same = same_ok & proportional_quadratic_parts(A_e, A_q)
        mc = kernels.pencil_coefficients_magnitude(*(np.abs(v) for v in e + q))
        mm = kernels.leading_minors_3_magnitude(*(np.abs(e[t]) for t in (0, 1, 2, 4, 5, 7)))
        r = [KP[t] * mc[t] for t in range(5)]
        r[0] = np.where(z & 1, 0.0, r[0])
        r[1] = np.where(z & 2, 0.0, r[1])
        sm = [_numpy_sign(mi[t], KL[t] * mm[t]) for t in range(2)]
        absx = np.abs(np.stack(e + q))
        outside = ((absx > eb.INPUT_MAX) | ~np.isfinite(absx) | ((absx < eb.INPUT_MIN) & (absx != 0))).any(
            axis=0
        )
        sa = np.sign(e[0]).astype(np.int8)
        ell = ellipsoid_from_signs(sa, sm[0], sm[1], _numpy_sign(c[4], r[4]))
        o = np.where(e[0] < 0, -1.0, 1.0)
        c[1] = o * c[1]
        c[3] = o * c[3]
        # c_k times 2^(g + m k), as the kernels scale (see there)
        tk = [np.abs(c[t]) + r[t] for t in range(5)]
        ek = [np.where(v == 0, _NO_EXPONENT, np.frexp(v)[1] - 1) for v in tk]
        low = np.where(ek[0] != _NO_EXPONENT, ek[0], np.where(ek[1] != _NO_EXPONENT, ek[1], ek[2]))
        m = np.where(low != _NO_EXPONENT, np.clip((low - ek[4]) >> 2, -400, 400), 0)
        g = -np.maximum.reduce([ek[t] + t * m for t in range(5)])
        s = [np.where(tk[t] == 0, 1.0, np.ldexp(1.0, np.clip(g + t * m, -1022, 1023))) for t in range(5)]
        x = [c[t] * s[t] for t in range(5)]
        y = [r[t] * s[t] for t in range(5)]
        a = [np.abs(v) for v in x]
        for t in range(5):
            outside |= ((c[t] != 0) & (a[t] < eb.COEFFICIENT_MIN)) | (
                (r[t] != 0) & (a[t] + y[t] < eb.COEFFICIENT_MIN)
            )
            outside |= (r[t] != 0) & (y[t] < 2.0**-1022)
        den = [np.where(a[t] != 0, a[t], np.where(y[t] == 0, 1e300, eb.COEFFICIENT_MIN)) for t in range(5)]
        rho = np.maximum.reduce(y) / np.minimum.reduce(den)
        d = list(formulas.paper_deltas(*x))
        A = list(kernels.paper_deltas_magnitude(*a))
        d[2] = np.where(same, 0.0, d[2])
        A[2] = np.where(same, 0.0, A[2])
        b = [(a[t] + y[t]) * eb.ROUND_UP for t in range(5)]
        Bm = kernels.paper_deltas_magnitude(*b)
        bound_rel = [(DR[j, 0] * rho + DR[j, 1]) * A[j] for j in range(3)]
        bound_abs = [DA[j, 0] * (Bm[j] - A[j]) + DA[j, 1] * A[j] for j in range(3)]
        bound_abs[2] = np.where(same, 0.0, bound_abs[2])
        rel = [_numpy_sign(d[j], bound_rel[j]) for j in range(3)]
        absolute = [_numpy_sign(d[j], bound_abs[j]) for j in range(3)]
        tier_a = CONTACT_TABLE[_table_index(rel)]
        use_b = (rho > eb.RHO_MAX) | (tier_a == _UNC)
        ds = [np.where(use_b, absolute[j], rel[j]).astype(np.int8) for j in range(3)]
        cs = [_numpy_sign(x[t], y[t]) for t in range(5)]
    return {
        "c": c,
        "r": r,
        "s": s,
        "x": x,
        "y": y,
        "rho": rho,
        "d": d,
        "bound_relative": bound_rel,
        "bound_absolute": bound_abs,
        "same": same,
        "outside": outside,
        "ell": ell,
        "signs": cs + ds,
    }


def screen_quantities(Em: np.ndarray, Qm: np.ndarray, *, rounded: bool = False) -> dict[str, Any]:
    """The screen's quantities for the pairs ``(Em[k], Qm[k])`` (numpy variant, the same
    operations in the same order as the compiled screen): ``x`` (balanced, normalised
    coefficients), ``d`` (their Deltas), ``fail``, ``ell`` and ``signs``."""
    from ..codegen import ENTRY_INDICES

    SP, SM, SD = eb.SCREEN_PENCIL[rounded], eb.SCREEN_MINORS[rounded], eb.SCREEN_DELTA
    e = [Em[:, i, j] for i, j in ENTRY_INDICES]
    q = [Qm[:, i, j] for i, j in ENTRY_INDICES]
    with np.errstate(all="ignore"):
        absx = np.abs(np.stack(e + q))
        fail = ((absx > eb.INPUT_MAX) | ~np.isfinite(absx) | ((absx < eb.INPUT_MIN) & (absx != 0))).any(
            axis=0
        )
        c = list(formulas.pencil_coefficients(*e, *q))
        ma = np.maximum.reduce([np.abs(e[t]) for t in (0, 1, 2, 4, 5, 7)])
        me = np.maximum.reduce([ma] + [np.abs(e[t]) for t in (3, 6, 8, 9)])
        mq = np.maximum.reduce([np.abs(v) for v in q])
        plane = np.maximum.reduce([np.abs(q[t]) for t in (0, 1, 2, 4, 5, 7)]) == 0
        me2, mq2 = me * me, mq * mq
        r = [
            SP[0] * (mq2 * mq2),
            SP[1] * ((me * mq) * mq2),
            SP[2] * (me2 * mq2),
            SP[3] * ((me * mq) * me2),
            SP[4] * (me2 * me2),
        ]
        # A zero quadratic part of Q: c0 = c1 = 0 exactly (see errorbounds).
        r[0] = np.where(plane, 0.0, r[0])
        r[1] = np.where(plane, 0.0, r[1])
        for t in range(5):
            fail |= r[t] > eb.SCREEN_EPS * np.abs(c[t])
        s2, s3 = kernels.leading_minors_3(e[0], e[1], e[2], e[4], e[5], e[7])
        ell = ellipsoid_from_signs(
            np.sign(e[0]).astype(np.int8),
            _numpy_sign(s2, SM[0] * (ma * ma)),
            _numpy_sign(s3, SM[1] * ((ma * ma) * ma)),
            _numpy_sign(c[4], r[4]),
        )
        o = np.where(e[0] < 0, -1.0, 1.0)
        c[1] = o * c[1]
        c[3] = o * c[3]
        beta = np.sqrt(np.sqrt(np.abs(c[0]) / np.abs(c[4])))
        beta = np.where((beta > 0) & (beta < _FLOAT_MAX), beta, 1.0)
        b2 = beta * beta
        tk = [c[0], c[1] * beta, c[2] * b2, c[3] * (b2 * beta), c[4] * (b2 * b2)]
        top = np.maximum.reduce([np.abs(v) for v in tk])
        fail |= ~(top <= _FLOAT_MAX) | (top < 2.0**-1022)
        for v in tk:
            fail |= (v != 0) & (np.abs(v) < 2.0**-1022)
        sc = 1.0 / top
        x = [v * sc for v in tk]
        for v in x:
            fail |= (v != 0) & (np.abs(v) < eb.COEFFICIENT_MIN)
        d = formulas.paper_deltas(*x)
        A = kernels.paper_deltas_magnitude(*(np.abs(v) for v in x))
    signs = [_numpy_sign(v, None) for v in x] + [_numpy_sign(d[j], SD[j] * A[j]) for j in range(3)]
    return {"x": x, "d": d, "fail": fail, "ell": ell, "signs": signs}


def _numpy_pairs(
    E: np.ndarray,
    Q: np.ndarray,
    eidx: np.ndarray,
    qidx: np.ndarray,
    es: int,
    qs: int,
    n: int,
    filtered: bool,
    rounded: bool,
    rows: np.ndarray,
    masks: np.ndarray,
    want_region: bool,
    qflags: np.ndarray,
    same_ok: bool,
    prop: np.ndarray,
) -> np.ndarray:
    from ..codegen import ENTRY_INDICES

    out = np.empty(n, dtype=np.int8)
    for lo in range(0, n, _NUMPY_CHUNK):
        hi = min(n, lo + _NUMPY_CHUNK)
        p = np.arange(lo, hi)
        ie = eidx[lo:hi] if eidx.shape[0] else p * es
        iq = qidx[lo:hi] if qidx.shape[0] else p * qs
        Em, Qm = E[ie], Q[iq]
        bad = ~(np.isfinite(Em).all(axis=(1, 2)) & np.isfinite(Qm).all(axis=(1, 2)))
        bad |= ~(
            (Em == np.swapaxes(Em, 1, 2)).all(axis=(1, 2)) & (Qm == np.swapaxes(Qm, 1, 2)).all(axis=(1, 2))
        )
        if filtered:
            fq = filter_quantities(Em, Qm, rounded=rounded, zflags=qflags[iq], same_ok=same_ok)
            signs, ell = fq["signs"], fq["ell"]
            sq = screen_quantities(Em, Qm, rounded=rounded)
        else:
            e = [Em[:, i, j] for i, j in ENTRY_INDICES]
            q = [Qm[:, i, j] for i, j in ENTRY_INDICES]
            with np.errstate(all="ignore"):
                c = list(formulas.pencil_coefficients(*e, *q))
                z = qflags[iq]
                c[0] = np.where(z & 1, 0.0, c[0])
                c[1] = np.where(z & 2, 0.0, c[1])
                mi = kernels.leading_minors_3(e[0], e[1], e[2], e[4], e[5], e[7])
                ell = ellipsoid_from_signs(
                    np.sign(e[0]).astype(np.int8),
                    _numpy_sign(mi[0], None),
                    _numpy_sign(mi[1], None),
                    _numpy_sign(c[4], None),
                )
                o = np.where(e[0] < 0, -1.0, 1.0)
                c[1] = o * c[1]
                c[3] = o * c[3]
                d = list(formulas.paper_deltas(*c))
                if prop.shape[0] > 0:
                    d[2] = np.where(prop[lo:hi] != 0, 0.0, d[2])
                elif same_ok:
                    A_e = np.stack([e[t] for t in (0, 1, 2, 4, 5, 7)])
                    A_q = np.stack([q[t] for t in (0, 1, 2, 4, 5, 7)])
                    d[2] = np.where(proportional_quadratic_parts(A_e, A_q), 0.0, d[2])
                signs = [_numpy_sign(v, None) for v in c] + [_numpy_sign(v, None) for v in d]
        contact = CONTACT_TABLE[_table_index(signs[5:])]
        if want_region:
            code = region_codes_from_signs(
                contact.astype(np.int8), np.stack(signs[:5], axis=1), rows[iq], masks[iq]
            )
        else:
            code = contact.astype(np.int8)
        if filtered:
            code = np.where(fq["outside"] | (ell == ELLIPSOID_UNCERTAIN), _UNC, code)
            invalid = bad | (ell == ELLIPSOID_NOT)
            # the screen first: where it is sure, its answer (the filter agrees where both are)
            s_contact = CONTACT_TABLE[_table_index(sq["signs"][5:])]
            if want_region:
                s_code = region_codes_from_signs(
                    s_contact.astype(np.int8), np.stack(sq["signs"][:5], axis=1), rows[iq], masks[iq]
                )
            else:
                s_code = s_contact.astype(np.int8)
            screened = ~sq["fail"] & (sq["ell"] != ELLIPSOID_UNCERTAIN) & (s_code != _UNC)
            code = np.where(screened, s_code, code)
        else:
            invalid = bad | (ell != ELLIPSOID_YES)
        out[lo:hi] = np.where(invalid, INVALID, code)
    return out


def _numpy_invariant_signs(Q: np.ndarray, filtered: bool, K: np.ndarray) -> np.ndarray:
    from ..codegen import ENTRY_INDICES

    q = [Q[:, i, j] for i, j in ENTRY_INDICES]
    out = np.empty((Q.shape[0], 8), dtype=np.int8)
    with np.errstate(all="ignore"):
        v = kernels.quadric_invariants(*q)
        if filtered:
            mags = kernels.quadric_invariants_magnitude(*(np.abs(x) for x in q))
            absx = np.abs(np.stack(q))
            outside = (
                (absx > eb.INPUT_MAX) | ~np.isfinite(absx) | ((absx < eb.INPUT_MIN) & (absx != 0))
            ).any(axis=0)
        for k in range(7):
            if filtered:
                out[:, k] = np.where(outside, _UNC, _numpy_sign(v[k], K[k] * mags[k]))
            else:
                out[:, k] = _numpy_sign(v[k], None)
    out[:, 7] = np.sign(q[9]).astype(np.int8)
    return out


# -- the modes -------------------------------------------------------------------------------


class FloatMode(NumberMode):
    """Plain binary64 (``mode="float"``): the fastest; it always answers and may be wrong
    near tangency, but not on structural zeros: it reads the exact facts the filter reads
    (``det Q = 0``, ``rank Q <= 2``, the type, computed exactly once per quadric where
    binary64 cannot tell) and recognises proportional quadratic parts exactly.

    Parameters
    ----------
    backend : {"numba", "numpy"}, optional
        Compiled kernels (default when numba is installed) or numpy on columns.
    threads : int, optional
        Threads for the compiled kernels (default: all cores; 1 under dask).
    """

    name = "float"
    stage = "float"
    certified = False
    filtered = False

    def __init__(self, backend: str | None = None, threads: int | None = None) -> None:
        super().__init__()
        self.backend = backend or BACKENDS[0]
        if self.backend not in BACKENDS:
            raise ValueError(f"backend must be one of {BACKENDS}, got {backend!r}")
        self.threads = threads

    def _kernel(self, pairs: Pairs, qtypes: Any, qflags: np.ndarray | None) -> np.ndarray:
        qrows, qmasks = qtypes if qtypes is not None else (None, None)
        rounded = pairs.E.rounded or pairs.Q.rounded
        prop = None
        if rounded and not self.filtered:
            from .objects import _proportional_exact

            prop = _proportional_exact(pairs, pairs.e_rows(), pairs.q_rows()).astype(np.int8)
        return float_pairs(
            pairs.E.floats,
            pairs.Q.floats,
            pairs.kernel_indices(),
            pairs.n,
            filtered=self.filtered,
            rounded=pairs.E.rounded or pairs.Q.rounded,
            qrows=qrows,
            qmasks=qmasks,
            qflags=qflags,
            same_ok=not rounded,
            prop=prop,
            backend=self.backend,
            threads=self.threads,
        )

    def _structural_flags(self, Q: MatrixStack, used: np.ndarray) -> np.ndarray:
        """Per quadric (length ``len(Q)``): the exact facts ``det Q = 0`` (bit 0) and
        ``rank Q <= 2`` (bit 1), computed exactly (:func:`exact_facts`) for the quadrics whose
        determinant binary64 cannot tell from zero, so that plain float reads the structural
        zeros of cylinders, planes and parallel planes as the filter does."""
        flags = np.zeros(len(Q), dtype=np.int8)
        if used.size == 0:
            return flags
        signs = float_invariant_signs(
            np.ascontiguousarray(Q.floats[used]), filtered=True, rounded=Q.rounded, backend=self.backend
        )
        maybe = used[(signs[:, 6] == 0) | (signs[:, 6] == _UNC)]
        if maybe.size:
            flags[maybe] = exact_facts(Q, maybe)[0]
        return flags

    def _codes(self, pairs: Pairs, qtypes: Any) -> np.ndarray:
        flags = None if self.filtered else self._structural_flags(pairs.Q, np.unique(pairs.q_rows()))
        codes = self._kernel(pairs, qtypes, flags)
        invalid = codes == INVALID
        if invalid.any():
            codes[invalid] = _diagnose(pairs, np.flatnonzero(invalid))
        if self.filtered:
            todo = np.flatnonzero(codes == _UNC)
            if todo.size:
                # Second pass with exact facts about the quadrics involved (once per quadric):
                # structural zeros of c0, c1 and, for regions, the exact type.
                used = np.unique(pairs.q_rows()[todo])
                facts, exact_masks = exact_facts(pairs.Q, used)
                flags = np.zeros(len(pairs.Q), dtype=np.int8)
                flags[used] = facts
                types = None
                if qtypes is not None:
                    masks = qtypes[1].copy()
                    masks[used] = exact_masks
                    types = (rows_from_masks(masks), masks)
                if flags.any() or types is not None:
                    again = self._kernel(pairs.take(todo), types, flags)
                    codes[todo] = np.where(again == INVALID, _UNC, again)
        return codes

    def criterion_contact(self, pairs: Pairs) -> np.ndarray:
        return self._codes(pairs, None)

    def criterion_region(self, pairs: Pairs) -> np.ndarray:
        used = np.unique(pairs.q_rows())
        masks = np.zeros(len(pairs.Q), dtype=np.int64)
        masks[used] = self.classify(pairs.Q, used)
        return self._codes(pairs, (rows_from_masks(masks), masks))

    def separation(self, pairs: Pairs) -> np.ndarray:
        from .separation import separation_float

        return separation_float(pairs, certified=self.filtered, backend=self.backend, threads=self.threads)

    def smallness(self, pairs: Pairs) -> np.ndarray:
        from . import smallness_float

        return smallness_float.run(self, pairs)

    def classify(self, Q: MatrixStack, rows: np.ndarray | None = None) -> np.ndarray:
        """The type of each quadric: binary64 with the filter's bounds; plain ``float`` takes
        the exact type where binary64 cannot tell (once per quadric), so that a structural
        zero (a cylinder's ``det Q = 0``) is never read from rounding noise."""
        index = np.arange(len(Q)) if rows is None else np.asarray(rows, dtype=np.intp)
        validate_rows(Q, index)
        sub = np.ascontiguousarray(Q.floats[index])
        signs = float_invariant_signs(sub, filtered=True, rounded=Q.rounded, backend=self.backend)
        masks = masks_from_invariant_signs(signs)
        if not self.filtered:
            unsure = np.flatnonzero(rows_from_masks(masks) == UNCERTAIN_ROW)
            if unsure.size:
                masks[unsure] = exact_facts(Q, index[unsure])[1]
        return masks

    def __repr__(self) -> str:
        return f"{type(self).__name__}(backend={self.backend!r})"


class FilterMode(FloatMode):
    """binary64 with a rigorous error bound (``mode="filter"``, the first stage of
    ``certified``): a sign only where it is certain, ``UNCERTAIN`` elsewhere.
    The bounds are derived in :mod:`quadric_contact.modes.errorbounds`.

    Structural zeros are recognised, not left to rounding: an exact zero entry gives
    an exact zero bound (a plane's ``c0 = c1 = 0``); equal quadratic parts (compared
    exactly) give ``Delta_4 = 0``; and the pairs still undecided after the first pass
    are run again with exact facts about their quadrics, computed once per quadric in
    integer arithmetic (:func:`exact_facts`: ``det Q = 0``, ``rank Q <= 2``, the type)."""

    name = "filter"
    stage = "filter"
    certified = True
    filtered = True


def exact_facts(Q: MatrixStack, rows: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Exact facts about the quadrics ``rows``, from their exact invariant signs (integer
    arithmetic, once per quadric): ``(flags, masks)`` with bit 0 of ``flags`` set when
    ``det Q = 0`` (then ``c0 = 0`` for every ``E``) and bit 1 when ``rank Q <= 2`` (then
    ``c1 = 0`` too; for a symmetric matrix the rank is 4 minus the number of trailing zeros
    of ``E1 .. E4``), and ``masks`` their Table 4 rows."""
    from .objects import ExactMode

    signs = ExactMode().invariant_signs(Q, np.asarray(rows, dtype=np.intp))
    det_zero = signs[:, 6] == 0
    flags = (det_zero.astype(np.int8) | ((det_zero & (signs[:, 5] == 0)).astype(np.int8) << 1)).astype(
        np.int8
    )
    return flags, masks_from_invariant_signs(signs)


def _diagnose(pairs: Pairs, which: np.ndarray) -> np.ndarray:
    """Raise for the first really invalid pair among ``which``; return ``UNCERTAIN`` for
    pairs flagged only because a plain float test could not see ``E`` as an ellipsoid."""
    e_rows, q_rows = pairs.e_rows()[which], pairs.q_rows()[which]
    validate_rows(pairs.E, np.unique(e_rows))
    validate_rows(pairs.Q, np.unique(q_rows))
    for row in np.unique(e_rows):
        if exact_matrix(pairs.E, int(row))._ellipsoid_sign() == 0:  # type: ignore[attr-defined]
            raise_not_ellipsoid(pairs.E, int(row))
    return np.full(which.size, _UNC, dtype=np.int8)
