"""The complete decision for pairs of ellipsoids in one pass over the input.

The criterion kernel (:mod:`quadric_contact.modes.kernels.criterion`) and the signature kernel
(:mod:`quadric_contact.modes.kernels.signature`) each read every pair; a decision that ran them
one after the other, with the type of every ``Q`` found by a third pass, paid for three reads,
and for the arrays that carried the pairs from one to the next.  This kernel does it all in one
pass, block by block (:data:`NB` pairs, in the L1 cache):

1. a gather copies the block into column buffers and checks symmetry on the way;
2. a straight-line loop (vectorised by LLVM) computes for each pair the screen's reading of
   ``P(lambda) = det(lambda E + Q)`` -- the table index of the signs of ``Delta_2 .. Delta_4``
   and the signs of the coefficients, exactly as the criterion kernel computes them
   (:func:`~quadric_contact.modes.kernels.criterion.screen_pair`) -- and whether ``E`` and ``Q``
   are certainly ellipsoids (:func:`~quadric_contact.modes.kernels.support.certified_ellipsoid`,
   the short test of the types: for ``Q`` it reads ``det Q = c0`` with the screen's bound);
3. a scalar loop reads the criterion's region code (the rule of the region kernel, tabulated
   for the two rows of an ellipsoid by :func:`ellipsoid_regions`) and lists the pairs that it
   leaves: everything
   but non-real roots (a crossing, Remark 9) and, unless the caller needs more
   (``outside_too``), the two positive roots of two ellipsoids (Wang-Wang-Kim: ``E`` in the
   closed ``R+`` of ``Q``); with ``Delta_4 > 0`` certain the roots are simple, the positive
   ones distinct, and the ellipsoids strictly apart (Wang-Wang-Kim): the separation code is
   that side, without the signature;
4. where the block has listed pairs, they are copied side by side (in multiples of
   ``_LANES``, the doubles of a vector), a second straight-line loop computes the first stage
   of the pencil's signature over them (the sample points and the member at the first one to
   try, :func:`~quadric_contact.modes.kernels.signature.signature_first`, the signature kernel's
   code, called rather than inlined), and for each a witness at that member gives its code; the
   others go on through the rest of the signature
   (:func:`~quadric_contact.modes.kernels.signature.signature_finish`, a called function: the
   decision table :data:`quadric_contact.theory.decision.REGION_OF`, the scalar certificate as
   a second reading).  A pair in five is listed: the stage over the whole block in place cost
   more than the copy;
5. a last loop reads the three codes of every pair through the caller's table
   (:func:`read_one`): the answer, and the pairs no step settles, while the block is in the
   cache.

Pairs whose ``E`` or ``Q`` is not certainly an ellipsoid, or that fail a guard (non-finite,
not symmetric, out of range), are marked :data:`OUT`: the general steps of
:mod:`quadric_contact.modes.decision.pipeline` decide them (and raise for invalid input).  Everything is
certified: a code here is the exact answer for the binary64 matrices.
"""

from __future__ import annotations

import threading
from typing import Any

import numpy as np

from quadric_contact._generated import blocks
from quadric_contact.model.classification import QuadricKind
from quadric_contact.modes.codes import UNCERTAIN, ContactCode, RegionCode
from quadric_contact.modes.decision.answers import ROWS, region_code_masked, row_of
from quadric_contact.modes.kernels import errorbounds as eb
from quadric_contact.modes.kernels._jit import HAVE_NUMBA, plain
from quadric_contact.modes.kernels._jit import njit as _njit
from quadric_contact.modes.kernels.criterion import (
    CONTACT_CODES,
    FALL_INDEX,
    FALLBACK,
    gather_block,
    read_pair,
    screen_pair,
)
from quadric_contact.modes.kernels.signature import (
    NB,
    WITNESS_FIRST,
    WITNESS_LAST,
    signature_finish_called,
    signature_first_called,
    witness,
)
from quadric_contact.modes.kernels.signs import plain_sign
from quadric_contact.modes.kernels.support import certified_ellipsoid
from quadric_contact.modes.kernels.threads import run_parallel
from quadric_contact.modes.stacks.pairs import Pairs

__all__ = ["CODE_RANGES", "NOT_RUN", "OUT", "decide_ellipsoids", "read_codes", "read_one"]

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


@_njit(inline=True)
def read_one(c: int, g: int, o: int, answers: Any, steps: Any) -> tuple[int, int]:
    """Read the codes ``c`` (criterion), ``g`` (separation), ``o`` (sign of ``Q``) of one pair
    through the table: ``(answers[key], steps[key])``, its answer and the step that gave it (0,
    1; 2: none), for ``key = ((c + 1) 5 + g + 1) 3 + o + 1``.  The codes are int8: read as
    ``int`` first, since the key exceeds 127 and numpy's int8 arithmetic (the Python twin's)
    wraps where numba's widens."""
    key = ((int(c) + 1) * 5 + int(g) + 1) * 3 + int(o) + 1
    return answers[key], steps[key]


def ellipsoid_regions() -> np.ndarray:
    """The region code the criterion reads for two ellipsoids whose roots are all real, by the
    canonical sign of ``Q`` (row 0: +1, row 1: -1) and the signs of ``c0, o c1, c2, o c3, c4``
    (``o`` the sign of ``E``'s quadratic part) as the key ``sum_j 3^j (s_j + 1)``:
    :func:`~quadric_contact.modes.decision.answers.region_code_masked`, the one rule, tabulated
    (``FALLBACK`` where it is uncertain, as the region kernel reads it), so that the kernel
    looks it up instead of branching through it for every pair."""
    f = plain(region_code_masked)  # at import: nothing is compiled
    table = np.empty((2, 243), dtype=np.int8)
    for k, row in enumerate((_ROW_PLUS, _ROW_MINUS)):
        for key in range(243):
            signs = [(key // 3**j) % 3 - 1 for j in range(5)]
            r = int(f(_NO_CONTACT, *signs, row, 1 << row, ROWS))
            table[k, key] = FALLBACK if r == UNCERTAIN else r
    return table


_REGIONS = ellipsoid_regions()
_R_PLUS = int(RegionCode.R_PLUS)
CODE_RANGES = (9, 5, 3)
"""How many values each of the three codes takes: ``crit`` in -1 .. 7 (:data:`OUT`), ``sep`` in
-1 .. 3 (:data:`NOT_RUN`), ``qsign`` in -1 .. 1; a reading table has their product of entries."""


# rows of the block buffer ``nb``: the first seven as the signature reads them
# (:func:`~quadric_contact.modes.kernels.signature.signature_first`), then what the code loop reads
_GUARD_ROW, _LAST_ROW, _SIGN_ROW, _INDEX_ROW, _Q_ROW, _KEY_ROW = 4, 5, 6, 7, 8, 9
_SIGNATURE_ROWS = 7
_LANES = 8
"""The listed pairs of a block go to the signature's stage in multiples of this many (copies of
the last fill the rest): its loop is vectorised, eight doubles a vector here, and leaves what
does not fill a vector to scalar code, seven times slower a pair."""


@_njit(inline=True)
def _note(
    i: int, S: int, ok: bool, idx: float, s0: float, s1: float, s2: float, s3: float, s4: float, ell: bool,
    o: float, e00: float, c: Any, nb: Any,
) -> None:  # fmt: skip
    """Keep what the screen read of pair ``i`` in the rows of ``nb``: the coefficients ``c1 ..
    c4`` for ``E`` in the paper's sign (``e00 > 0``: ``c_j (-1)^j`` where ``e00 < 0``) and that
    sign, for the signature; the table index (or the fallback's), the sign of ``Q`` where both
    are certainly ellipsoids (``ell``; else 0) and the key of the coefficients' signs, for the
    code loop."""
    f = -1.0 if e00 < 0.0 else 1.0
    nb[i] = f * c[1]
    nb[S + i] = c[2]
    nb[2 * S + i] = f * c[3]
    nb[3 * S + i] = c[4]
    nb[_SIGN_ROW * S + i] = f
    nb[_INDEX_ROW * S + i] = idx if ok else _FALL_INDEX
    nb[_Q_ROW * S + i] = o if ell else 0.0
    key = (s0 + 1.0) + 3.0 * (s1 + 1.0) + 9.0 * (s2 + 1.0) + 27.0 * (s3 + 1.0) + 81.0 * (s4 + 1.0)
    nb[_KEY_ROW * S + i] = key


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
    answers: Any,
    steps: Any,
    out: Any,
    left: Any,
    by_step: Any,
) -> int:
    """Pairs ``lo .. hi``: ``crit`` (the criterion's region code, or :data:`OUT`), ``sep`` (the
    separation code, or :data:`NOT_RUN`) and ``qsign`` (the canonical sign of ``Q``, an
    ellipsoid; 0 for the pairs left out), and these codes read through the table ``answers``,
    ``steps`` (:func:`read_one`): the answer into ``out``, the pairs no step settles into
    ``left[lo:]`` (their number is returned), the count of each step added to ``by_step``."""
    S = NB
    eb_ = np.empty(10 * S)
    qb_ = np.empty(10 * S)
    asym = np.empty(S)
    nb = np.empty(10 * S)  # what the screen read (_note)
    for i in range(S):
        nb[_GUARD_ROW * S + i] = 1.0  # the screen's guard held for the pairs the signature reads
    # the rows the code loop reads and writes, as arrays of their own: indexed by the loop's
    # counter, which cannot be negative, they need no test of a negative index (an index
    # ``row * S + i`` does, and those tests kept the loop from vectorising: 6 ns a pair more on
    # one thread)
    q_row = nb[_Q_ROW * S : (_Q_ROW + 1) * S]
    index_row = nb[_INDEX_ROW * S : (_INDEX_ROW + 1) * S]
    key_row = nb[_KEY_ROW * S : (_KEY_ROW + 1) * S]
    last_row = nb[_LAST_ROW * S : (_LAST_ROW + 1) * S]
    listed = np.empty(S, np.intp)
    li = np.empty(S, np.intp)
    step = np.empty(S, np.int8)
    # the listed pairs of a block, side by side for the signature (rows of S as in eb_, qb_, nb)
    el = np.empty(10 * S)
    ql = np.empty(10 * S)
    cl = np.empty(_SIGNATURE_ROWS * S)
    fb = np.empty(5 * S)
    # two-dimensional views for the copy: indexed by non-negative numbers (a row counter and an
    # unsigned column), no test of a negative index
    el2 = el.reshape(10, S)
    ql2 = ql.reshape(10, S)
    cl2 = cl.reshape(_SIGNATURE_ROWS, S)
    eb2 = eb_.reshape(10, S)
    qb2 = qb_.reshape(10, S)
    nb2 = nb.reshape(10, S)
    e1 = np.empty(10)
    q1 = np.empty(10)
    SKt = (SK[0], SK[1], SK[2], SK[3])
    nleft = n0 = n1 = 0
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
    if fixed_q:  # every column of the signature's buffer holds it
        for i in range(S):
            _gather_full(Q, 0, ql, i, S)
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
                _note(i, S, ok, idx, s0, s1, s2, s3, s4, eok & qell0, o0, e[0], c, nb)
        else:
            gather_block(Q, qidx, qs, False, blo, m, qb_, asym, False, S)
            for i in range(m):
                e, q, ae, R, aq, T = read_pair(eb_, qb_, i, S)
                c = _pencil(e, q)
                W = _row_bound(R[0], R[1], R[2], R[3], T[0], T[1], T[2], T[3])
                ok, idx, s0, s1, s2, s3, s4, eok = screen_pair(e, q, c, R, T, W, ae, aq, asym[i] == 0.0)
                qell, o = certified_ellipsoid(q, T, c[0], _SP0 * W[0])
                _note(i, S, ok, idx, s0, s1, s2, s3, s4, eok & qell, o, e[0], c, nb)
        # the codes, and which pairs the signature reads, without a branch on the data (the
        # outcomes are random: mispredicted branches cost more than the work)
        crit_b = crit[blo : blo + m]
        qsign_b = qsign[blo : blo + m]
        sep_b = sep[blo : blo + m]
        for i in range(m):
            o = q_row[i]
            x = int(index_row[i])
            code = _TABLE[x]
            crossing = code == _CROSSING
            r = _REGIONS[0 if o > 0.0 else 1, int(key_row[i])]
            r = _CONTACT if crossing else (r if code == _NO_CONTACT else FALLBACK)
            qs_ = plain_sign(o)
            outside = ((r == 1) | (r == -1)) & (r * qs_ == _R_PLUS)
            # Delta_4 certainly positive (its digit of the table index): with all roots real,
            # four simple roots, so the two positive ones are distinct and the ellipsoids are
            # strictly apart (Wang-Wang-Kim): a positive definite member exists, the separation
            # code is the side itself, no signature needed
            apart = outside & (((x >> 4) & 3) == 2)
            on = (qs_ != 0) & (not crossing) & ((outside_too & (not apart)) | (not outside))
            crit_b[i] = r if qs_ != 0 else OUT
            qsign_b[i] = qs_
            sep_b[i] = r if (apart & (qs_ != 0)) else NOT_RUN
            last_row[i] = 1.0 if outside else 0.0  # try the last critical point first
            listed[i] = 1 if on else 0
        k = 0
        for i in range(m):
            li[k] = i
            k += listed[i]
        if k:
            # the listed pairs side by side (a multiple of _LANES of them), the straight-line
            # stage over them, then pair by pair the witness (the predicate and the codes
            # signature_finish itself starts with) read here, the call only without one
            kp = (k + _LANES - 1) // _LANES * _LANES
            for j in range(kp):
                col = np.uintp(li[min(j, k - 1)])
                for t in range(10):
                    el2[t, j] = eb2[t, col]
                for t in range(_SIGNATURE_ROWS):
                    cl2[t, j] = nb2[t, col]
            if not fixed_q:
                for j in range(kp):
                    col = np.uintp(li[min(j, k - 1)])
                    for t in range(10):
                        ql2[t, j] = qb2[t, col]
            signature_first_called(el, ql, cl, kp, SKt, True, fb)
            for j in range(k):
                last = cl[_LAST_ROW * S + j] == 1.0
                if witness(last, fb[S + j]):
                    sep_b[li[j]] = WITNESS_LAST if last else WITNESS_FIRST
                else:
                    sep_b[li[j]] = signature_finish_called(el, ql, cl, fb, j, S, SKt, K, KD, True, e1, q1)
        # the codes read through the table, while they are in the cache (the counts in registers:
        # an increment in memory a pair waits for the one before); the pairs left are listed in
        # order only in a block that has some
        out_b = out[blo : blo + m]
        b0 = b1 = 0
        for i in range(m):
            a, s_ = read_one(crit_b[i], sep_b[i], qsign_b[i], answers, steps)
            out_b[i] = a
            step[i] = s_
            b0 += 1 if s_ == 0 else 0
            b1 += 1 if s_ == 1 else 0
        n0 += b0
        n1 += b1
        if b0 + b1 < m:
            for i in range(m):
                left[lo + nleft] = blo + i
                nleft += 1 if step[i] == 2 else 0
    by_step[0] += n0
    by_step[1] += n1
    by_step[2] += nleft
    return nleft


_KERNEL: dict[bool, Any] = {}
_LOCK = threading.Lock()


def _kernel(compiled: bool) -> Any:
    k = _KERNEL.get(compiled)
    if k is None:
        with _LOCK:
            k = _KERNEL.get(compiled)
            if k is None:
                k = _KERNEL[compiled] = (
                    _njit(_decide_block_kernel) if compiled else plain(_decide_block_kernel)
                )
    return k


_NO_TABLE = (np.zeros(int(np.prod(CODE_RANGES)), dtype=np.int8),) * 2


def decide_ellipsoids(
    pairs: Pairs,
    *,
    outside_too: bool,
    table: tuple[np.ndarray, np.ndarray] | None = None,
    backend: str = "numba",
    threads: int | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """``(crit, sep, qsign, out, left, by_step)`` for every pair of binary64 stacks (not rounded
    from exact input).

    ``crit``: the criterion's region code (:class:`~quadric_contact.modes.codes.RegionCode`,
    ``FALLBACK`` where the screen cannot read it, :data:`OUT` for a pair left to the general
    steps); ``sep``: the separation code (:data:`~quadric_contact.modes.decision.separation.SEP_MINUS`,
    ``CROSSING``, ``SEP_PLUS``, ``UNCERTAIN``, or :data:`NOT_RUN`); ``qsign``: the canonical
    sign of ``Q`` (0 where the pair is left out).  ``outside_too``: read the signature also
    where the criterion says ``E`` is in the closed ``R+`` of ``Q`` (the overlap question needs
    to tell a touch from a gap).

    ``table``: ``(answers, steps)``, indexed by the three codes as :func:`read_codes` reads
    them; the kernel reads every pair through it as it goes (a pass of its own over the codes
    cost a tenth of the decision): ``out`` the answers, ``left`` the pairs whose step is 2 (in
    order), ``by_step`` how many pairs each step took.  Without a table they read an all-zero
    one."""
    n = pairs.n
    crit = np.empty(n, dtype=np.int8)
    sep = np.empty(n, dtype=np.int8)
    qsign = np.empty(n, dtype=np.int8)
    out = np.empty(n, dtype=np.int8)
    left = np.empty(n, dtype=np.intp)
    by_step = np.zeros(3, dtype=np.int64)
    if n == 0:
        return crit, sep, qsign, out, left[:0].copy(), by_step
    answers, steps = _NO_TABLE if table is None else table
    SK = np.array(eb.MEMBER_MINORS_SEMI[False])
    K = np.array(eb.MEMBER_ERRBOUND[False])
    KD = np.array(eb.MEMBER_MINORS_ERRBOUND[False])
    eidx, qidx, es, qs = pairs.kernel_indices()
    E, Q = pairs.E.floats.reshape(-1, 16), pairs.Q.floats.reshape(-1, 16)
    parts: list[tuple[int, int, np.ndarray]] = []  # (lo, pairs left, counts) of every slice

    def go(lo: int, hi: int, kernel: Any) -> None:
        counts = np.zeros(3, dtype=np.int64)
        k = kernel(
            E, Q, eidx, qidx, es, qs, lo, hi, outside_too, SK, K, KD, crit, sep, qsign, answers, steps, out,
            left, counts,
        )  # fmt: skip
        parts.append((lo, int(k), counts))

    if backend == "numpy" or not HAVE_NUMBA:
        go(0, n, _kernel(False))
    else:
        k = _kernel(True)
        run_parallel(lambda lo, hi: go(lo, hi, k), n, threads)
    parts.sort(key=lambda part: part[0])
    rest = [left[lo : lo + k] for lo, k, _ in parts if k]
    for _, _, counts in parts:
        by_step += counts
    return crit, sep, qsign, out, (np.concatenate(rest) if rest else left[:0].copy()), by_step


@_njit
def _read_codes_impl(
    crit: Any, sep: Any, qsign: Any, answers: Any, steps: Any, out: Any, left: Any, by_step: Any
) -> int:
    k = n0 = n1 = 0
    for p in range(crit.shape[0]):
        a, s = read_one(crit[p], sep[p], qsign[p], answers, steps)
        out[p] = a
        n0 += 1 if s == 0 else 0
        n1 += 1 if s == 1 else 0
        left[k] = p
        k += 1 if s == 2 else 0
    by_step[0] += n0
    by_step[1] += n1
    by_step[2] += k
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
