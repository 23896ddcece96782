"""The criterion on binary64 stacks at the speed of memory: plain ``float`` and the
semi-static screen of the certified ``filter``.

Both read the input once, in blocks of :data:`NB` pairs small enough for the L1 cache:
a gather (``quadric_contact._generated.blocks``) copies each block into column
buffers, one row per upper entry (transposing the ``(n, 4, 4)`` or packed ``(n, 10)``
layout to structure-of-arrays) and checks symmetry on the way; a straight-line loop over
the block, which LLVM vectorises, computes everything; a short scalar loop writes the
codes.  When one matrix is fixed (one ``Q`` against a stack of ``E``, or one ``E``
against a stack of ``Q``), its products are computed once per call
(``pencil_q_part``, ``pencil_e_part``, its row maxima and guards) and only the stack is
read.

Each kernel answers the pairs it is sure of and marks the others :data:`FALLBACK`; the
drivers (:mod:`quadric_contact.modes.numbers.binary64`) send those to the general kernels of
:mod:`quadric_contact.modes.kernels.filter`, which decide them as before.  So the codes
are those of the general path, only faster:

* plain ``float``: the same generated programs in the same order (the same bits) and the
  same decisions; it falls back where the general kernel reads an exact fact (``det Q``
  not certainly non-zero, possibly proportional quadratic parts, an input outside the
  guard, a non-finite coefficient);
* the *screen* (certified): the bound of each coefficient from the row maxima of the two
  matrices (:data:`~quadric_contact.modes.kernels.errorbounds.SEMI_PENCIL`), one relative error per
  pair, and the compact Delta forms with their magnitude programs
  (:data:`~quadric_contact.modes.kernels.errorbounds.SEMI_DELTA`); a few flops more than plain
  float for nearly every pair.  It answers only where every sign it reads is certain.
"""

from __future__ import annotations

import threading
from typing import Any

import numpy as np

from quadric_contact._generated import blocks, formulas, kernels
from quadric_contact.modes.codes import INVALID, UNCERTAIN
from quadric_contact.modes.decision.answers import CONTACT_TABLE, ROWS, region_code_masked
from quadric_contact.modes.kernels import errorbounds as eb
from quadric_contact.modes.kernels._jit import njit
from quadric_contact.modes.kernels.signs import plain_sign, sign_index, sign_within
from quadric_contact.modes.kernels.support import certified_ellipsoid

__all__ = [
    "CONTACT_CODES",
    "FALLBACK",
    "FALL_INDEX",
    "NB",
    "fast_codes",
    "gather_block",
    "kernel",
    "read_pair",
    "region_out",
    "screen_pair",
]

NB = 32
"""Pairs per block: 10 rows of 32 doubles per matrix (2.5 KB), in L1 with everything else;
larger blocks evict each other's rows (measured: 64 pairs per block is a third slower)."""

FALLBACK = 6
"""Internal code of the fast kernels: the general kernels must decide this pair."""


# compile-time constants of the kernels
_SP0, _SP1, _SP2, _SP3, _SP4 = eb.SEMI_PENCIL
(_SR2, _SG2), (_SR3, _SG3), (_SR4, _SG4) = eb.SEMI_DELTA
_IN_MIN = eb.INPUT_MIN
_IN_MAX = eb.INPUT_MAX
_C_MIN = eb.COEFFICIENT_MIN
_C_MAX = eb.SEMI_COEFFICIENT_MAX
_RHO_MAX = eb.RHO_MAX
_TINY = 2.0**-1000

_gather_full = njit(blocks.gather_full, inline=True)
_gather_packed = njit(blocks.gather_packed, inline=True)
_load = njit(blocks.load_upper, inline=True)
_upper_full = njit(blocks.upper_full, inline=True)
_upper_packed = njit(blocks.upper_packed, inline=True)
_row_maxima = njit(blocks.row_maxima, inline=True)
_abs10 = njit(blocks.abs_upper, inline=True)
_smallest = njit(blocks.smallest_nonzero, inline=True)
_plane = njit(blocks.quadratic_part_zero, inline=True)
_row_bound = njit(blocks.row_bound, inline=True)
_pencil = njit(blocks.pencil, inline=True)
_q_part = njit(blocks.pencil_q_part, inline=True)
_with_q = njit(blocks.pencil_with_q_part, inline=True)
_e_part = njit(blocks.pencil_e_part, inline=True)
_with_e = njit(blocks.pencil_with_e_part, inline=True)
_deltas = njit(formulas.paper_deltas, inline=True)
_compact_both = njit(blocks.paper_deltas_compact_and_magnitude, inline=True)
_minors = njit(kernels.leading_minors_3, inline=True)


# -- pieces of the straight-line loops --------------------------------------------------------


@njit(inline=True)
def _guard_ok(a: Any, R: Any) -> bool:
    """The input guard of one matrix (``a``: absolute upper entries, ``R``: row maxima): every
    entry at most INPUT_MAX, every non-zero one at least INPUT_MIN (a NaN fails)."""
    top = max(max(R[0], R[1]), max(R[2], R[3]))
    return (top <= _IN_MAX) & (_smallest(a, _IN_MAX) >= _IN_MIN)


@njit(inline=True)
def _nz1(a: float) -> float:
    return a if a != 0.0 else 1.0


@njit(inline=True)
def _smallest5(a0: float, a1: float, a2: float, a3: float, a4: float) -> float:
    """The smallest non-zero value (1 if all are zero)."""
    return min(min(min(_nz1(a0), _nz1(a1)), min(_nz1(a2), _nz1(a3))), _nz1(a4))


@njit(inline=True)
def _screen_core(e: Any, R: Any, c: Any, W: Any, plane: bool, guard: bool) -> Any:
    """The screen on one pair: ``(ok, table index, signs of c0 .. c4, E certainly an ellipsoid
    and the guard holds)`` (floats but the flags).  ``e``,
    ``R``: the upper entries of ``E`` and its row maxima; ``c``: the coefficients;
    ``W``: the row bound; ``plane``: ``Q`` has a zero quadratic part; ``guard``: both inputs
    pass the input guard."""
    c0, c1, c2, c3, c4 = c
    r0 = 0.0 if plane else _SP0 * W[0]
    r1 = 0.0 if plane else _SP1 * W[1]
    r2 = _SP2 * W[2]
    r3 = _SP3 * W[3]
    r4 = _SP4 * W[4]
    # E is certainly an ellipsoid (Sylvester; det E = c4 < 0)
    ell, o = certified_ellipsoid(e, R, c4, r4)
    # o c1, o c3 for o = +-1, as a choice rather than a product (the multipliers are the busy units)
    x1 = -c1 if o < 0.0 else c1
    x3 = -c3 if o < 0.0 else c3
    a0, a1, a2, a3, a4 = abs(c0), abs(c1), abs(c2), abs(c3), abs(c4)
    # Every coefficient in range (a NaN or an infinity fails the sum); rho the largest r_k / |c_k|:
    # |c_k| + 2^-1000 is |c_k| itself when it is at least COEFFICIENT_MIN, and a zero coefficient
    # with a non-zero bound (r_k >= 2^-800) gets a quotient far above RHO_MAX.
    rng = (a0 + a1 + a2 + a3 + a4 <= _C_MAX) & (_smallest5(a0, a1, a2, a3, a4) >= _C_MIN)
    rho = max(
        max(max(r0 / (a0 + _TINY), r1 / (a1 + _TINY)), max(r2 / (a2 + _TINY), r3 / (a3 + _TINY))),
        r4 / (a4 + _TINY),
    )
    ok = guard & ell & rng & (rho <= _RHO_MAX)
    # the Delta forms and their magnitude programs at |c| (sharing the products: the same bits)
    d2, d3, d4, A2, A3, A4 = _compact_both(c0, x1, c2, x3, c4)
    d4 = 0.0 if plane else d4
    A4 = 0.0 if plane else A4
    idx = (
        1.0 * sign_index(sign_within(d2, (_SR2 * rho + _SG2) * A2))
        + 4.0 * sign_index(sign_within(d3, (_SR3 * rho + _SG3) * A3))
        + 16.0 * sign_index(sign_within(d4, (_SR4 * rho + _SG4) * A4))
    )
    s0, s1, s2, s3, s4 = plain_sign(c0), plain_sign(x1), plain_sign(c2), plain_sign(x3), plain_sign(c4)
    return ok, idx, 1.0 * s0, 1.0 * s1, 1.0 * s2, 1.0 * s3, 1.0 * s4, ell & guard


@njit(inline=True)
def read_pair(eb_: Any, qb_: Any, i: int, S: int) -> Any:
    """Pair ``i`` of the block buffers: ``(e, q, |e|, row maxima of |e|, |q|, row maxima of
    |q|)``, what every kernel reads of a pair before its screen (the criterion kernel's
    distinct pairs, the decision kernel's)."""
    e = _load(eb_, i, S)
    q = _load(qb_, i, S)
    ae = _abs10(e)
    aq = _abs10(q)
    return e, q, ae, _row_maxima(ae), aq, _row_maxima(aq)


@njit(inline=True)
def screen_pair(e: Any, q: Any, c: Any, R: Any, T: Any, W: Any, ae: Any, aq: Any, sym: bool) -> Any:
    """The screen's reading of one pair as the criterion kernels take it (the guards of both
    matrices, ``Q``'s zero quadratic part read from ``aq``): ``(ok, table index, signs of
    c0 .. c4, E certainly an ellipsoid and every guard holds)``.  ``c``: the coefficients;
    ``R``, ``T``: the row maxima of ``ae = |E|`` and ``aq = |Q|``; ``W``: the row bound;
    ``sym``: both matrices are symmetric.  For the decision kernel
    (:mod:`quadric_contact.modes.kernels.decision`)."""
    guard = _guard_ok(ae, R) & _guard_ok(aq, T) & sym
    return _screen_core(e, R, c, W, _plane(aq), guard)


@njit(inline=True)
def _float_core(e: Any, q: Any, c: Any, r0: float, plane: bool, guard: bool) -> Any:
    """Plain binary64 on one pair, as the general float kernel computes it: ``(fallback,
    valid, table index, signs of c0 .. c4)``.  ``r0``: a bound of the error of ``c0 = det Q``
    (valid under ``guard``, the input guard of ``Q``); the pair falls back when ``det Q`` is
    not certainly non-zero (the general kernel reads the exact fact), when the quadratic parts
    may be proportional (it compares them exactly) or a coefficient is not finite.  A plane
    (``Q`` with a zero quadratic part) is decided here: ``c0 = c1 = 0`` come out as exact zeros
    and ``Delta_4`` vanishes identically there (``codegen.verify_plane_zeros``), which is what the
    general kernel reads from the exact facts and the proportional (zero) quadratic part."""
    c0, c1, c2, c3, c4 = c
    m2, m3 = _minors(e[0], e[1], e[2], e[4], e[5], e[7])
    e00 = e[0]
    sa = plain_sign(e00)
    valid = (sa != 0) & (m2 > 0.0) & (plain_sign(m3) == sa) & (c4 < 0.0)
    facts = (abs(c0) <= r0) & (not plane)
    prop = (
        (q[1] * e00 == q[0] * e[1]) & (q[2] * e00 == q[0] * e[2]) & (q[4] * e00 == q[0] * e[4])
        & (q[5] * e00 == q[0] * e[5]) & (q[7] * e00 == q[0] * e[7])
    )  # fmt: skip
    fin = (
        (abs(c0) <= 1.7976931348623157e308) & (abs(c1) <= 1.7976931348623157e308)
        & (abs(c2) <= 1.7976931348623157e308) & (abs(c3) <= 1.7976931348623157e308)
        & (abs(c4) <= 1.7976931348623157e308)
    )  # fmt: skip
    fallback = facts | (prop & (not plane)) | (not fin) | (not guard)
    x1 = -c1 if e00 < 0.0 else c1
    x3 = -c3 if e00 < 0.0 else c3
    d2, d3, d4 = _deltas(c0, x1, c2, x3, c4)
    d4 = 0.0 if plane else d4
    idx = (
        1.0 * sign_index(plain_sign(d2))
        + 4.0 * sign_index(plain_sign(d3))
        + 16.0 * sign_index(plain_sign(d4))
    )
    s0, s1, s2, s3, s4 = plain_sign(c0), plain_sign(x1), plain_sign(c2), plain_sign(x3), plain_sign(c4)
    return fallback, valid, idx, 1.0 * s0, 1.0 * s1, 1.0 * s2, 1.0 * s3, 1.0 * s4


_TABLE = np.concatenate(
    [np.where(CONTACT_TABLE == UNCERTAIN, FALLBACK, CONTACT_TABLE), [FALLBACK, INVALID]]
).astype(np.int8)
"""The contact code of a table index (0 .. 63), with :data:`FALLBACK` where the signs leave it
uncertain, and two more entries: 64 fall back, 65 invalid."""
_FALL_INDEX = 64.0
_INVALID_INDEX = 65.0
CONTACT_CODES = _TABLE
FALL_INDEX = _FALL_INDEX


@njit(inline=True)
def region_out(idx: float, sb: Any, i: int, S: int, row: int, mask: int) -> int:
    """The region code of the pair in column ``i``."""
    code = _TABLE[int(idx)]
    if code in (FALLBACK, INVALID):
        return int(code)
    region = region_code_masked(
        code, int(sb[i]), int(sb[S + i]), int(sb[2 * S + i]), int(sb[3 * S + i]), int(sb[4 * S + i]),
        row, mask, ROWS,
    )  # fmt: skip
    return FALLBACK if region == UNCERTAIN else int(region)


@njit(inline=True)
def gather_block(
    M: Any, idx: Any, stride: int, packed: bool, blo: int, m: int, b: Any, asym: Any, first: bool, S: int
) -> None:  # fmt: skip
    """Gather the block ``blo .. blo + m`` of one side into ``b`` (rows ``idx[p]``, or ``p * stride``
    when ``idx`` is empty); ``asym[t]`` becomes (``first``) or accumulates 1 where a matrix is not
    symmetric.  The branches are taken once per block, outside the loops over its pairs."""
    if idx.shape[0] > 0:
        if packed:
            for t in range(m):
                _gather_packed(M, idx[blo + t], b, t, S)
        else:
            for t in range(m):
                bad = _gather_full(M, idx[blo + t], b, t, S)
                asym[t] = (1.0 if bad else 0.0) + (0.0 if first else asym[t])
    else:
        if packed:
            for t in range(m):
                _gather_packed(M, (blo + t) * stride, b, t, S)
        else:
            for t in range(m):
                bad = _gather_full(M, (blo + t) * stride, b, t, S)
                asym[t] = (1.0 if bad else 0.0) + (0.0 if first else asym[t])
    if packed and first:
        for t in range(m):
            asym[t] = 0.0


@njit(inline=True)
def _rows_of_block(idx: Any, stride: int, blo: int, m: int, rows: Any) -> None:
    if idx.shape[0] > 0:
        for t in range(m):
            rows[t] = idx[blo + t]
    else:
        for t in range(m):
            rows[t] = (blo + t) * stride


# -- the kernels: one per (pairs / fixed Q / fixed E, float / screen, contact / region) ---------
#
# Made by the factories below with the two flags as constants of the closure (numba caches each
# on disk), so that the straight-line loops carry no test of them.  The three layouts share the
# body of one pair (:func:`_one_pair`) and the writing of a block (:func:`_write_block`); they
# differ only in what they read per pair and what they compute once.


@njit(inline=True)
def _one_pair(
    filtered: bool, e: Any, q: Any, c: Any, R: Any, T: Any, eguard: bool, qguard: bool, plane: bool
) -> Any:  # fmt: skip
    """One pair: ``(table index or FALLBACK/INVALID index, signs of c0 .. c4)``.  ``R``, ``T``:
    the row maxima of ``|E|`` and ``|Q|``; ``eguard``: ``E`` passes the input guard (read by the
    screen only: plain float's bounds concern ``det Q`` alone); ``qguard``: ``Q`` passes it and
    both matrices are symmetric.  With ``filtered`` a compile-time constant, LLVM drops what the
    other branch needs (``E``'s row maxima and guard for plain float)."""
    if filtered:
        W = _row_bound(R[0], R[1], R[2], R[3], T[0], T[1], T[2], T[3])
        ok, idx, s0, s1, s2, s3, s4, _ = _screen_core(e, R, c, W, plane, eguard & qguard)
        x = idx if ok else _FALL_INDEX
    else:
        r0 = _SP0 * ((T[0] * T[1]) * (T[2] * T[3]))
        fb, valid, idx, s0, s1, s2, s3, s4 = _float_core(e, q, c, r0, plane, qguard)
        x = _FALL_INDEX if fb else (idx if valid else _INVALID_INDEX)
    return x, s0, s1, s2, s3, s4


@njit(inline=True)
def _keep_signs(
    region: bool, sb: Any, i: int, S: int, s0: float, s1: float, s2: float, s3: float, s4: float
) -> None:  # fmt: skip
    """Keep the signs of pair ``i`` for the region question."""
    if region:
        sb[i] = s0
        sb[S + i] = s1
        sb[2 * S + i] = s2
        sb[3 * S + i] = s3
        sb[4 * S + i] = s4


@njit(inline=True)
def _write_block(
    region: bool, blo: int, m: int, xb: Any, sb: Any, S: int, qi: Any, qrows: Any, qmasks: Any, out: Any,
    fb: Any, lo: int, nfb: int,
) -> int:  # fmt: skip
    """The codes of the block ``blo .. blo + m``: contact codes, or region codes from the signs
    and the Table 4 row and candidate mask of each pair's quadric (``qi``: its index in
    ``qrows``/``qmasks``).  The pairs left to the general kernels (:data:`FALLBACK`) are listed
    in ``fb[lo:]`` as they are written (``nfb`` so far; returned updated), so that the caller
    need not search the batch for them."""
    for i in range(m):
        code = region_out(xb[i], sb, i, S, qrows[qi[i]], qmasks[qi[i]]) if region else int(_TABLE[int(xb[i])])
        out[blo + i] = code
        if code == FALLBACK:
            fb[lo + nfb] = blo + i
            nfb += 1
    return nfb


def _make_pairs(filtered: bool, region: bool) -> Any:
    def kernel(
        E: Any, Q: Any, eidx: Any, qidx: Any, es: int, qs: int, epacked: bool, qpacked: bool, lo: int,
        hi: int, qrows: Any, qmasks: Any, out: Any, fb: Any,
    ) -> int:  # fmt: skip
        """Pairs ``lo .. hi``: ``E[eidx[p]]`` (or ``E[p * es]`` when ``eidx`` is empty) against
        ``Q[...]`` likewise; ``E``, ``Q`` flat ``(m, 16)`` matrices or packed ``(m, 10)``."""
        S = NB
        eb_ = np.empty(10 * S)
        qb_ = np.empty(10 * S)
        asym = np.empty(S)
        qi = np.empty(S, np.intp)
        xb = np.empty(S)
        sb = np.empty(5 * S)
        nfb = 0
        for blo in range(lo, hi, S):
            m = min(S, hi - blo)
            if eidx.shape[0] == 0 and qidx.shape[0] == 0 and not epacked and not qpacked:
                # the common case (two full stacks, rows p * stride): both sides in one loop
                for t in range(m):
                    bad_e = _gather_full(E, (blo + t) * es, eb_, t, S)
                    bad_q = _gather_full(Q, (blo + t) * qs, qb_, t, S)
                    asym[t] = 1.0 if (bad_e | bad_q) else 0.0
            else:
                gather_block(E, eidx, es, epacked, blo, m, eb_, asym, True, S)
                gather_block(Q, qidx, qs, qpacked, blo, m, qb_, asym, False, S)
            for i in range(m):
                e, q, ae, R, aq, T = read_pair(eb_, qb_, i, S)
                qguard = _guard_ok(aq, T) & (asym[i] == 0.0)
                x, s0, s1, s2, s3, s4 = _one_pair(
                    filtered, e, q, _pencil(e, q), R, T, _guard_ok(ae, R), qguard, _plane(aq)
                )
                xb[i] = x
                _keep_signs(region, sb, i, S, s0, s1, s2, s3, s4)
            if region:
                _rows_of_block(qidx, qs, blo, m, qi)
            nfb = _write_block(region, blo, m, xb, sb, S, qi, qrows, qmasks, out, fb, lo, nfb)
        return nfb

    return kernel


def _make_fixed_q(filtered: bool, region: bool) -> Any:
    def kernel(
        E: Any, eidx: Any, es: int, epacked: bool, Qm: Any, qpacked: bool, lo: int, hi: int, qrows: Any,
        qmasks: Any, out: Any, fb: Any,
    ) -> int:  # fmt: skip
        """Pairs ``lo .. hi`` of a stack of ``E`` against the one quadric ``Qm[0]``: its products,
        row maxima and guard are computed once, only ``E`` is read."""
        S = NB
        q = _upper_packed(Qm, 0) if qpacked else _upper_full(Qm, 0)
        qbad = False if qpacked else _gather_full(Qm, 0, np.empty(10), 0, 1)
        aq = _abs10(q)
        T = _row_maxima(aq)
        qguard = _guard_ok(aq, T) & (not qbad)
        plane = _plane(aq)
        qp = _q_part(q)
        eb_ = np.empty(10 * S)
        asym = np.empty(S)
        qi = np.zeros(S, np.intp)  # every pair's quadric is qrows[0]
        xb = np.empty(S)
        sb = np.empty(5 * S)
        nfb = 0
        for blo in range(lo, hi, S):
            m = min(S, hi - blo)
            gather_block(E, eidx, es, epacked, blo, m, eb_, asym, True, S)
            for i in range(m):
                e = _load(eb_, i, S)
                ae = _abs10(e)
                R = _row_maxima(ae)
                sym = asym[i] == 0.0
                x, s0, s1, s2, s3, s4 = _one_pair(
                    filtered, e, q, _with_q(e, q, qp), R, T, _guard_ok(ae, R), qguard & sym, plane
                )
                xb[i] = x
                _keep_signs(region, sb, i, S, s0, s1, s2, s3, s4)
            nfb = _write_block(region, blo, m, xb, sb, S, qi, qrows, qmasks, out, fb, lo, nfb)
        return nfb

    return kernel


def _make_fixed_e(filtered: bool, region: bool) -> Any:
    def kernel(
        Em: Any, epacked: bool, Q: Any, qidx: Any, qs: int, qpacked: bool, lo: int, hi: int, qrows: Any,
        qmasks: Any, out: Any, fb: Any,
    ) -> int:  # fmt: skip
        """Pairs ``lo .. hi`` of the one ellipsoid ``Em[0]`` against a stack of ``Q``: its
        products, row maxima and guard are computed once, only ``Q`` is read."""
        S = NB
        e = _upper_packed(Em, 0) if epacked else _upper_full(Em, 0)
        ebad = False if epacked else _gather_full(Em, 0, np.empty(10), 0, 1)
        ae = _abs10(e)
        R = _row_maxima(ae)
        eguard = _guard_ok(ae, R)
        ep = _e_part(e)
        qb_ = np.empty(10 * S)
        asym = np.empty(S)
        qi = np.empty(S, np.intp)
        xb = np.empty(S)
        sb = np.empty(5 * S)
        nfb = 0
        for blo in range(lo, hi, S):
            m = min(S, hi - blo)
            gather_block(Q, qidx, qs, qpacked, blo, m, qb_, asym, True, S)
            for i in range(m):
                q = _load(qb_, i, S)
                aq = _abs10(q)
                T = _row_maxima(aq)
                qguard = _guard_ok(aq, T) & (asym[i] == 0.0) & (not ebad)
                x, s0, s1, s2, s3, s4 = _one_pair(
                    filtered, e, q, _with_e(e, q, ep), R, T, eguard, qguard, _plane(aq)
                )
                xb[i] = x
                _keep_signs(region, sb, i, S, s0, s1, s2, s3, s4)
            if region:
                _rows_of_block(qidx, qs, blo, m, qi)
            nfb = _write_block(region, blo, m, xb, sb, S, qi, qrows, qmasks, out, fb, lo, nfb)
        return nfb

    return kernel


_FACTORIES = {"pairs": _make_pairs, "fixed_q": _make_fixed_q, "fixed_e": _make_fixed_e}
_compiled: dict[tuple[str, bool, bool], Any] = {}
_compiled_lock = threading.Lock()


def kernel(kind: str, filtered: bool, region: bool) -> Any:
    """The compiled kernel ``kind`` (``"pairs"``, ``"fixed_q"``, ``"fixed_e"``) for plain float or
    the screen (``filtered``), the contact or the region question (made once, on first use)."""
    key = (kind, filtered, region)
    k = _compiled.get(key)
    if k is None:
        with _compiled_lock:
            k = _compiled.get(key)
            if k is None:
                k = _compiled[key] = njit(_FACTORIES[kind](filtered, region))
    return k


# -- the driver -------------------------------------------------------------------------------


def fast_codes(
    E: np.ndarray,
    Q: np.ndarray,
    epacked: bool,
    qpacked: bool,
    indices: tuple[np.ndarray, np.ndarray, int, int],
    n: int,
    *,
    filtered: bool,
    qrows: np.ndarray | None,
    qmasks: np.ndarray | None,
    run: Any,
) -> tuple[np.ndarray, np.ndarray]:
    """Codes of ``n`` pairs (or :data:`FALLBACK`) from the fast kernels, and the pairs marked
    :data:`FALLBACK` (increasing), listed by the kernels as they write them.

    ``E``, ``Q``: flat ``(m, 16)`` or packed ``(m, 10)`` binary64 arrays (C-contiguous);
    ``indices``: ``(e_index, q_index, e_stride, q_stride)`` as the kernels read them (an empty
    index array means ``row = p * stride``); ``qrows``, ``qmasks``: the Table 4 row and
    candidate mask of every quadric for the region question (None: the contact question);
    ``run``: :func:`~quadric_contact.modes.kernels.threads.run_parallel` or a stand-in."""
    eidx, qidx, es, qs = indices
    out = np.empty(n, dtype=np.int8)
    if n == 0:
        return out, np.zeros(0, dtype=np.intp)
    fb = np.empty(n, dtype=np.intp)  # slice lo .. hi lists its fallbacks in fb[lo:]
    found: dict[int, int] = {}
    region = qrows is not None
    rows = np.zeros(1, dtype=np.int16) if qrows is None else np.ascontiguousarray(qrows, dtype=np.int16)
    masks = np.zeros(1, dtype=np.int64) if qmasks is None else np.ascontiguousarray(qmasks, dtype=np.int64)
    if qidx.shape[0] == 0 and qs == 0 and (es != 0 or eidx.shape[0] > 0):
        # one quadric against a stack of ellipsoids (all of them, or a sub-batch by index)
        k = kernel("fixed_q", filtered, region)

        def go(lo: int, hi: int) -> None:
            found[lo] = k(E, eidx, es, epacked, Q, qpacked, lo, hi, rows, masks, out, fb)

    elif eidx.shape[0] == 0 and qidx.shape[0] == 0 and es == 0 and qs != 0:
        k = kernel("fixed_e", filtered, region)

        def go(lo: int, hi: int) -> None:
            found[lo] = k(E, epacked, Q, qidx, qs, qpacked, lo, hi, rows, masks, out, fb)

    else:
        k = kernel("pairs", filtered, region)

        def go(lo: int, hi: int) -> None:
            found[lo] = k(E, Q, eidx, qidx, es, qs, epacked, qpacked, lo, hi, rows, masks, out, fb)

    run(go, n)
    parts = [fb[lo : lo + c] for lo, c in sorted(found.items()) if c]
    fall = np.concatenate(parts) if parts else np.zeros(0, dtype=np.intp)
    return out, fall
