"""The complete decision for pairs of ellipsoids in one pass over the input.

The criterion kernel (:mod:`quadric_contact.modes.kernels_criterion`) and the signature kernel
(:mod:`quadric_contact.modes.kernels_signature`) each read every pair; a decision that ran them
one after the other, with the type of every ``Q`` found by a third pass, paid for three reads,
and for the arrays that carried the pairs from one to the next.  This kernel does it all in one
pass, block by block (:data:`NB` pairs, in the L1 cache):

1. a gather copies the block into column buffers and checks symmetry on the way;
2. a straight-line loop (vectorised by LLVM) computes for each pair the screen's reading of
   ``P(lambda) = det(lambda E + Q)`` -- the table index of the signs of ``Delta_2 .. Delta_4``
   and the signs of the coefficients, exactly as the criterion kernel computes them
   (:func:`~quadric_contact.modes.kernels_criterion.screen_pair`) -- and whether ``E`` and ``Q``
   are certainly ellipsoids (:func:`~quadric_contact.modes.kernels_support.certified_ellipsoid`,
   the short test of the types: for ``Q`` it reads ``det Q = c0`` with the screen's bound);
3. a scalar loop reads the criterion's region code (the rule of the region kernel, tabulated
   for the two rows of an ellipsoid by :func:`ellipsoid_regions`) and lists the pairs that it
   leaves: everything
   but non-real roots (a crossing, Remark 9) and, unless the caller needs more
   (``outside_too``), the two positive roots of two ellipsoids (Wang-Wang-Kim: ``E`` in the
   closed ``R+`` of ``Q``); with ``Delta_4 > 0`` certain the roots are simple, the positive
   ones distinct, and the ellipsoids strictly apart (Wang-Wang-Kim): the separation code is
   that side, without the signature;
4. for the listed pairs only, a second straight-line loop computes the pencil's signature at
   the sample points, and a scalar loop looks the facts up in
   :data:`quadric_contact.theory.decision.REGION_OF`, with the scalar certificate as a second
   reading (:func:`~quadric_contact.modes.kernels_signature.signature_rows`, the same code as
   the signature kernel).

Pairs whose ``E`` or ``Q`` is not certainly an ellipsoid, or that fail a guard (non-finite,
not symmetric, out of range), are marked :data:`OUT`: the general steps of
:mod:`quadric_contact.modes.pipeline` decide them (and raise for invalid input).  Everything is
certified: a code here is the exact answer for the binary64 matrices.
"""

from __future__ import annotations

import threading
from typing import Any

import numpy as np

from quadric_contact._generated import blocks
from quadric_contact.model.classification import QuadricKind
from quadric_contact.modes import errorbounds as eb
from quadric_contact.modes._jit import HAVE_NUMBA, python_twin
from quadric_contact.modes._jit import njit as _njit
from quadric_contact.modes.base import ContactCode, Pairs, RegionCode
from quadric_contact.modes.decisions import ROWS, UNCERTAIN, region_code_masked, row_of
from quadric_contact.modes.kernels_criterion import (
    CONTACT_CODES,
    FALL_INDEX,
    FALLBACK,
    gather_block,
    read_pair,
    screen_pair,
)
from quadric_contact.modes.kernels_signature import NB, signature_rows
from quadric_contact.modes.kernels_support import certified_ellipsoid

__all__ = ["NOT_RUN", "OUT", "decide_ellipsoids", "read_codes"]

OUT = 7
"""Code of a pair this kernel leaves to the general steps (``Q`` or ``E`` not certainly an
ellipsoid, or a guard failed)."""

NOT_RUN = 3
"""Separation code of a pair whose criterion reading settled it (the signature was not read)."""

_load = _njit(blocks.load_upper, inline=True)
_pencil = _njit(blocks.pencil, inline=True)
_q_part = _njit(blocks.pencil_q_part, inline=True)
_with_q = _njit(blocks.pencil_with_q_part, inline=True)
_upper_full = _njit(blocks.upper_full, inline=True)
_gather_full = _njit(blocks.gather_full, inline=True)
_abs10 = _njit(blocks.abs_upper, inline=True)
_row_maxima = _njit(blocks.row_maxima, inline=True)
_row_bound = _njit(blocks.row_bound, inline=True)
_SP0 = eb.SEMI_PENCIL[0]
_ROW_PLUS = row_of(QuadricKind.ELLIPSOID, 1)
_ROW_MINUS = row_of(QuadricKind.ELLIPSOID, -1)
_CONTACT = int(RegionCode.CONTACT)
_CROSSING = int(ContactCode.CONTACT)
_TABLE = CONTACT_CODES
_FALL_INDEX = FALL_INDEX
_NO_CONTACT = int(ContactCode.NO_CONTACT)


def ellipsoid_regions() -> np.ndarray:
    """The region code the criterion reads for two ellipsoids whose roots are all real, by the
    canonical sign of ``Q`` (row 0: +1, row 1: -1) and the signs of ``c0, o c1, c2, o c3, c4``
    (``o`` the sign of ``E``'s quadratic part) as the key ``sum_j 3^j (s_j + 1)``:
    :func:`~quadric_contact.modes.decisions.region_code_masked`, the one rule, tabulated
    (``FALLBACK`` where it is uncertain, as the region kernel reads it), so that the kernel
    looks it up instead of branching through it for every pair."""
    f = getattr(region_code_masked, "py_func", region_code_masked)
    table = np.empty((2, 243), dtype=np.int8)
    for k, row in enumerate((_ROW_PLUS, _ROW_MINUS)):
        for key in range(243):
            signs = [(key // 3**j) % 3 - 1 for j in range(5)]
            r = int(f(_NO_CONTACT, *signs, row, 1 << row, ROWS))
            table[k, key] = FALLBACK if r == UNCERTAIN else r
    return table


_REGIONS = ellipsoid_regions()
_R_PLUS = int(RegionCode.R_PLUS)


@_njit(inline=True)
def _note(
    i: int, S: int, ok: bool, idx: float, s0: float, s1: float, s2: float, s3: float, s4: float, ell: bool,
    o: float, e00: float, c: Any, xb: Any, ob: Any, kb: Any, pc: Any,
) -> None:  # fmt: skip
    """Keep what the screen read of pair ``i`` for the code loop: the table index (or the
    fallback's), the sign of ``Q`` where both are certainly ellipsoids (``ell``; else 0), the key
    of the coefficients' signs, and the coefficients for ``E`` in the paper's sign (``e00 > 0``):
    ``c_j (-1)^j`` where ``e00 < 0``."""
    xb[i] = idx if ok else _FALL_INDEX
    ob[i] = o if ell else 0.0
    kb[i] = (s0 + 1.0) + 3.0 * (s1 + 1.0) + 9.0 * (s2 + 1.0) + 27.0 * (s3 + 1.0) + 81.0 * (s4 + 1.0)
    f = -1.0 if e00 < 0.0 else 1.0
    pc[i] = f * c[1]
    pc[S + i] = c[2]
    pc[2 * S + i] = f * c[3]
    pc[3 * S + i] = c[4]


def _decide_block_kernel(
    E: Any,
    Q: Any,  # (n, 16): row-major 4x4 matrices
    eidx: Any,
    qidx: Any,
    es: int,
    qs: int,
    lo: int,
    hi: int,
    outside_too: bool,
    SK: Any,
    K: Any,
    KD: Any,
    crit: Any,
    sep: Any,
    qsign: Any,
) -> None:
    """Pairs ``lo .. hi``: ``crit`` (the criterion's region code, or :data:`OUT`), ``sep`` (the
    separation code, or :data:`NOT_RUN`) and ``qsign`` (the canonical sign of ``Q``, an
    ellipsoid; 0 for the pairs left out)."""
    S = NB
    eb_ = np.empty(10 * S)
    qb_ = np.empty(10 * S)
    asym = np.empty(S)
    xb = np.empty(S)
    kb = np.empty(S)
    ob = np.empty(S)
    pc = np.empty(4 * S)
    hb = np.empty(S)
    li = np.empty(S, np.intp)
    C = 2 * S  # the listed pairs, gathered over blocks until there are at least S of them
    ec = np.empty(10 * C)  # E in the paper's sign
    qc = np.empty(10 * C)
    cb = np.empty(6 * C)
    at = np.empty(C, np.intp)
    fb = np.empty(6 * C)
    e1 = np.empty(10)
    q1 = np.empty(10)
    nl = 0
    # one quadric against a stack of ellipsoids: what depends on it alone once (its products in
    # the pencil, its row maxima, whether it is certainly an ellipsoid: the same programs, the
    # same bits, as for a pair), and the stack of quadrics is not read
    fixed_q = qidx.shape[0] == 0 and qs == 0
    q0 = _upper_full(Q, 0 if fixed_q else (qidx[lo] if qidx.shape[0] > 0 else lo * qs))
    qp = _q_part(q0)
    aq0 = _abs10(q0)
    T0 = _row_maxima(aq0)
    qell0, o0 = certified_ellipsoid(q0, T0, qp[12], _SP0 * ((T0[0] * T0[1]) * (T0[2] * T0[3])))
    qbad = _gather_full(Q, 0, np.empty(10), 0, 1) if fixed_q else False  # its symmetry
    if fixed_q:  # every column of the block buffer holds it (the signature's pairs copy it)
        for i in range(S):
            _gather_full(Q, 0, qb_, i, S)
    for blo in range(lo, hi, S):
        m = min(S, hi - blo)
        gather_block(E, eidx, es, False, blo, m, eb_, asym, True, S)
        if fixed_q:
            for i in range(m):
                e = _load(eb_, i, S)
                ae = _abs10(e)
                R = _row_maxima(ae)
                c = _with_q(e, q0, qp)
                W = _row_bound(R[0], R[1], R[2], R[3], T0[0], T0[1], T0[2], T0[3])
                sym = (asym[i] == 0.0) & (not qbad)
                ok, idx, s0, s1, s2, s3, s4, eok = screen_pair(e, q0, c, R, T0, W, ae, aq0, sym)
                _note(i, S, ok, idx, s0, s1, s2, s3, s4, eok & qell0, o0, e[0], c, xb, ob, kb, pc)
        else:
            gather_block(Q, qidx, qs, False, blo, m, qb_, asym, False, S)
            for i in range(m):
                e, q, ae, R, aq, T = read_pair(eb_, qb_, i, S)
                c = _pencil(e, q)
                W = _row_bound(R[0], R[1], R[2], R[3], T[0], T[1], T[2], T[3])
                ok, idx, s0, s1, s2, s3, s4, eok = screen_pair(e, q, c, R, T, W, ae, aq, asym[i] == 0.0)
                qell, o = certified_ellipsoid(q, T, c[0], _SP0 * W[0])
                _note(i, S, ok, idx, s0, s1, s2, s3, s4, eok & qell, o, e[0], c, xb, ob, kb, pc)
        # the codes, and the list of pairs for the signature, without a branch on the data
        # (the outcomes are random: mispredicted branches cost more than the work)
        k = 0
        for i in range(m):
            p = blo + i
            o = ob[i]
            code = _TABLE[int(xb[i])]
            crossing = code == _CROSSING
            r = _REGIONS[0 if o > 0.0 else 1, int(kb[i])]
            r = _CONTACT if crossing else (r if code == _NO_CONTACT else FALLBACK)
            qs_ = (1 if o > 0.0 else 0) - (1 if o < 0.0 else 0)
            outside = ((r == 1) | (r == -1)) & (r * qs_ == _R_PLUS)
            # Delta_4 certainly positive (its digit of the table index): with all roots real,
            # four simple roots, so the two positive ones are distinct and the ellipsoids are
            # strictly apart (Wang-Wang-Kim): a positive definite member exists, the separation
            # code is the side itself, no signature needed
            apart = outside & (((int(xb[i]) >> 4) & 3) == 2)
            listed = (qs_ != 0) & (not crossing) & ((outside_too & (not apart)) | (not outside))
            crit[p] = r if qs_ != 0 else OUT
            qsign[p] = qs_
            sep[p] = r if (apart & (qs_ != 0)) else NOT_RUN
            hb[k] = 1.0 if outside else 0.0  # try the last critical point first
            li[k] = i
            k += 1 if listed else 0
        for j in range(k):
            # listed for the signature: E in the paper's sign (det E < 0, e00 > 0)
            i = li[j]
            u = nl + j
            f = -1.0 if eb_[i] < 0.0 else 1.0
            for t in range(10):
                ec[t * C + u] = f * eb_[t * S + i]
                qc[t * C + u] = qb_[t * S + i]
            for t in range(4):
                cb[t * C + u] = pc[t * S + i]
            cb[4 * C + u] = 1.0  # the screen's guard held for both matrices
            cb[5 * C + u] = hb[j]
            at[u] = blo + i
        nl += k
        if nl >= S or blo + S >= hi:
            # the signature's straight-line loop over at least a block of listed pairs (a few
            # pairs a block would run it in its scalar remainder, at the latency of its
            # divisions and square roots)
            if nl:
                signature_rows(ec, qc, cb, nl, C, SK, K, KD, 1.0, fb, e1, q1, at, sep)
            nl = 0


_KERNEL: dict[bool, Any] = {}
_LOCK = threading.Lock()


def _kernel(compiled: bool) -> Any:
    k = _KERNEL.get(compiled)
    if k is None:
        with _LOCK:
            k = _KERNEL.get(compiled)
            if k is None:
                k = _KERNEL[compiled] = (
                    _njit(_decide_block_kernel) if compiled else python_twin(_decide_block_kernel)
                )
    return k


def decide_ellipsoids(
    pairs: Pairs, *, outside_too: bool, backend: str = "numba", threads: int | None = None
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(crit, sep, qsign)`` for every pair of binary64 stacks (not rounded from exact input):
    the criterion's region code (:class:`~quadric_contact.modes.base.RegionCode`,
    ``FALLBACK`` where the screen cannot read it, :data:`OUT` for a pair left to the general
    steps), the separation code (:data:`~quadric_contact.modes.separation.SEP_MINUS`,
    ``CROSSING``, ``SEP_PLUS``, ``UNCERTAIN``, or :data:`NOT_RUN`) and the canonical sign of
    ``Q`` (0 where the pair is left out).  ``outside_too``: read the signature also where the
    criterion says ``E`` is in the closed ``R+`` of ``Q`` (the overlap question needs to tell a
    touch from a gap)."""
    from quadric_contact.modes.threads import run_parallel

    n = pairs.n
    crit = np.empty(n, dtype=np.int8)
    sep = np.empty(n, dtype=np.int8)
    qsign = np.empty(n, dtype=np.int8)
    if n == 0:
        return crit, sep, qsign
    SK = np.array(eb.MEMBER_MINORS_SEMI[False])
    K = np.array(eb.MEMBER_ERRBOUND[False])
    KD = np.array(eb.MEMBER_MINORS_ERRBOUND[False])
    eidx, qidx, es, qs = pairs.kernel_indices()
    E, Q = pairs.E.floats.reshape(-1, 16), pairs.Q.floats.reshape(-1, 16)
    if backend == "numpy" or not HAVE_NUMBA:
        _kernel(False)(E, Q, eidx, qidx, es, qs, 0, n, outside_too, SK, K, KD, crit, sep, qsign)
        return crit, sep, qsign
    k = _kernel(True)

    def go(lo: int, hi: int) -> None:
        k(E, Q, eidx, qidx, es, qs, lo, hi, outside_too, SK, K, KD, crit, sep, qsign)

    run_parallel(go, n, threads)
    return crit, sep, qsign


@_njit
def _read_codes_impl(
    crit: Any, sep: Any, qsign: Any, answers: Any, steps: Any, out: Any, left: Any, by_step: Any
) -> int:
    k = 0
    for p in range(crit.shape[0]):
        key = ((crit[p] + 1) * 5 + sep[p] + 1) * 3 + qsign[p] + 1
        out[p] = answers[key]
        s = steps[key]
        by_step[s] += 1
        left[k] = p
        k += 1 if s == 2 else 0
    return k


def read_codes(
    crit: np.ndarray, sep: np.ndarray, qsign: np.ndarray, answers: np.ndarray, steps: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Read the kernel's codes through a table: for every pair the entry
    ``((crit + 1) 5 + sep + 1) 3 + qsign + 1`` of ``answers`` (the answer) and of ``steps``
    (0, 1: the step that gave it; 2: none).  Returns the answers, the pairs whose step is 2 (in
    order) and how many pairs each step took; one pass (numpy's fancy indexing took 1.4 ms per
    300 000 pairs, several times this)."""
    n = crit.shape[0]
    out = np.empty(n, dtype=np.int8)
    left = np.empty(n, dtype=np.intp)
    by_step = np.zeros(3, dtype=np.int64)
    k = _read_codes_impl(crit, sep, qsign, answers, steps, out, left, by_step)
    return out, left[:k].copy(), by_step
