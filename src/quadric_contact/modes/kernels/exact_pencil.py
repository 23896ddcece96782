"""The pencil coefficients ``c0, ..., c4`` of ``det(lambda E + Q)`` exactly, in compiled code,
for integer matrices (the exact mode's binary64 input once scaled to integers).

The exact mode scales each binary64 matrix to integers
(:func:`~quadric_contact.modes.stacks.integers.integer_rows`);
for ordinary input they are below ``2^63`` and the coefficients below ``2^256``.  Python
integers spend most of their time on interpreter overhead at these sizes (about 40 ns an
operation, some 260 operations a pair), so this module computes the same expansion as
:func:`quadric_contact._generated.formulas.pencil_coefficients` (Laplace along rows 0, 1 with
every 2x2 minor split into its ``E``, mixed and ``Q`` parts) in fixed-size multi-digit
integer arithmetic that numba compiles.

Representation and bounds (why no ``int64`` overflows)
------------------------------------------------------
A number is a vector of signed ``int64`` digits in base ``2^26``; after normalisation
(floor division by ``2^26``, so the value is kept exactly) every digit but the top one
lies in ``[0, 2^26)`` and the top one carries the sign.  A batch is run with ``D``
digits an entry, ``D`` the smallest with every entry below ``2^(26 D - 1)`` in magnitude
(``D = 3`` for entries below ``2^77``, the common case), ``D <= MAX_DIGITS``.

* An entry has ``D`` digits, the top one in ``[-2^25, 2^25)``: every digit product is at
  most ``2^52`` in magnitude.
* A 2x2 minor (``E``, ``Q`` or mixed part) is a convolution of entry digits: an output
  digit sums at most ``D`` digit products for each of at most four products of entries,
  below ``4 D 2^52 < 2^63``.  Its value is below ``4 * 2^(52 D - 2) = 2^(52 D)``, so
  normalised into ``2 D`` digits its top digit is at most ``2^26`` in magnitude.
* A coefficient sums at most 18 products of two minors (``c2``); an output digit of one
  product sums at most ``2 D`` digit products (each at most ``2^52``), so the accumulators
  stay below ``36 D 2^52 < 2^63`` for ``D <= MAX_DIGITS = 48``.  Its value is below
  ``4! * 6 * 2^(4 (26 D - 1)) < 2^(104 D + 4)``: ``4 D + 1`` digits hold it normalised,
  and ``104 D + 5`` bits in two's complement.

The coefficients leave as little-endian 32-bit words in two's complement, which
:func:`pencil_coefficients_int` reads with ``int.from_bytes``.
"""

from __future__ import annotations

import numpy as np

from quadric_contact._generated.formulas import pencil_coefficients
from quadric_contact.exact.errors import ShapeError
from quadric_contact.modes.kernels._jit import HAVE_NUMBA, njit

__all__ = [
    "HAVE_KERNEL",
    "MAX_DIGITS",
    "dyadic_digits",
    "entry_digits",
    "pencil_coefficients_dyadic",
    "pencil_coefficients_int",
    "pencil_words",
]

MAX_DIGITS = 48
"""The most base-``2^26`` digits an entry may have (entries below ``2^1247``; the bounds above)."""

HAVE_KERNEL = HAVE_NUMBA
"""Compiled: without numba the exact mode keeps to Python integers."""

_BITS = 26
_MASK = (1 << _BITS) - 1

# Upper-entry index of (i, j) in the order of ENTRY_INDICES.
_UP = np.array([[0, 1, 2, 3], [1, 4, 5, 6], [2, 5, 7, 8], [3, 6, 8, 9]], dtype=np.int64)
# Column pairs of the 2x2 minors (rows 0, 1 on top, rows 2, 3 below).
_COLS = np.array([[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [2, 3]], dtype=np.int64)
# Laplace along rows 0, 1: the top minor on columns _COLS[k] times the bottom minor on
# the complementary columns _COLS[5 - k], with sign (-1)^(a + b + 1) (0-based columns).
_SIGN = np.array([1, -1, 1, 1, -1, 1], dtype=np.int64)


def entry_digits(bits: int) -> int:
    """The digits ``D`` an entry of ``bits`` bits (magnitude below ``2^bits``) needs."""
    return max(1, -(-(bits + 1) // _BITS))


def words(digits: int) -> int:
    """32-bit words of one coefficient for entries of ``digits`` digits."""
    return -(-(104 * digits + 5) // 32)


@njit
def _normalise(d: np.ndarray) -> None:  # pragma: no cover - compiled
    carry = np.int64(0)
    last = d.shape[0] - 1
    for i in range(last):
        v = d[i] + carry
        d[i] = v & _MASK
        carry = v >> _BITS
    d[last] += carry


def pencil_words(e: np.ndarray, q: np.ndarray, digits: int, nwords: int) -> np.ndarray:
    """``(n, 5, nwords)`` uint32: for pair ``p`` and coefficient ``k``, ``c_k`` in two's
    complement, least significant word first.

    ``e`` and ``q`` are ``(n, 10, digits)`` int64 base-``2^26`` digits of the upper entries,
    least significant first, normalised (the top digit signed, in ``[-2^25, 2^25)``)."""
    out = np.empty((e.shape[0], 5, nwords), dtype=np.uint32)
    _pencil_words_into(e, q, digits, nwords, out)
    return out


@njit
def _pencil_words_into(
    e: np.ndarray, q: np.ndarray, digits: int, nwords: int, out: np.ndarray
) -> None:  # pragma: no cover - compiled
    """:func:`pencil_words` into ``out`` (the caller's array: a kernel that takes arrays and
    returns none has a native version, :mod:`quadric_contact.modes.kernels.native`)."""
    n = e.shape[0]
    D = digits
    L = 2 * D  # digits of a minor
    C = 4 * D + 1  # digits of a coefficient
    ed = np.empty((4, 4, D), dtype=np.int64)
    qd = np.empty((4, 4, D), dtype=np.int64)
    mn = np.empty((2, 6, 3, L), dtype=np.int64)  # [top, bottom][column pair][E, mixed, Q][digit]
    acc = np.empty((5, C), dtype=np.int64)
    for p in range(n):
        for i in range(4):
            for j in range(4):
                u = _UP[i, j]
                for t in range(D):
                    ed[i, j, t] = e[p, u, t]
                    qd[i, j, t] = q[p, u, t]
        mn[:] = 0
        for h in range(2):
            r0 = 2 * h
            r1 = r0 + 1
            for k in range(6):
                a = _COLS[k, 0]
                b = _COLS[k, 1]
                for i in range(D):
                    ea0 = ed[r0, a, i]
                    eb0 = ed[r0, b, i]
                    qa0 = qd[r0, a, i]
                    qb0 = qd[r0, b, i]
                    for j in range(D):
                        ea1 = ed[r1, a, j]
                        eb1 = ed[r1, b, j]
                        qa1 = qd[r1, a, j]
                        qb1 = qd[r1, b, j]
                        mn[h, k, 0, i + j] += ea0 * eb1 - eb0 * ea1
                        mn[h, k, 1, i + j] += ea0 * qb1 + qa0 * eb1 - eb0 * qa1 - qb0 * ea1
                        mn[h, k, 2, i + j] += qa0 * qb1 - qb0 * qa1
                for t in range(3):
                    _normalise(mn[h, k, t])
        acc[:] = 0
        for k in range(6):
            s = _SIGN[k]
            kb = 5 - k
            for i in range(L):
                tE = s * mn[0, k, 0, i]
                tM = s * mn[0, k, 1, i]
                tQ = s * mn[0, k, 2, i]
                for j in range(L):
                    bE = mn[1, kb, 0, j]
                    bM = mn[1, kb, 1, j]
                    bQ = mn[1, kb, 2, j]
                    acc[0, i + j] += bQ * tQ
                    acc[1, i + j] += bM * tQ + tM * bQ
                    acc[2, i + j] += bE * tQ + tE * bQ + bM * tM
                    acc[3, i + j] += bE * tM + tE * bM
                    acc[4, i + j] += bE * tE
        for c in range(5):
            _normalise(acc[c])
            # Pack the digits into 32-bit words; the top digit is signed, and the words
            # after it repeat its sign (arithmetic shifts of the bit buffer).
            buf = np.int64(0)
            nb = 0
            w = 0
            for t in range(C):
                buf |= acc[c, t] << nb
                nb += _BITS
                while nb >= 32:
                    out[p, c, w] = np.uint32(buf & 0xFFFFFFFF)
                    buf >>= 32
                    nb -= 32
                    w += 1
            while w < nwords:
                out[p, c, w] = np.uint32(buf & 0xFFFFFFFF)
                buf >>= 32
                w += 1


def dyadic_digits(m: np.ndarray, shift: np.ndarray, digits: int) -> np.ndarray:
    """Base-``2^26`` digits of the integers ``m * 2^shift`` (``|m| < 2^62``, ``shift >= 0``),
    least significant first: ``(n, 10, digits)`` int64, each digit of the sign of its
    integer and below ``2^26`` in magnitude (not normalised; the bounds above hold)."""
    out = np.zeros((m.shape[0], 10, digits), dtype=np.int64)
    _dyadic_digits_into(m, shift, digits, out)
    return out


@njit
def _dyadic_digits_into(
    m: np.ndarray, shift: np.ndarray, digits: int, out: np.ndarray
) -> None:  # pragma: no cover - compiled
    """:func:`dyadic_digits` into ``out`` (zeros, the caller's)."""
    n = m.shape[0]
    for p in range(n):
        for u in range(10):
            v = m[p, u]
            neg = v < 0
            a = -v if neg else v
            s = shift[p, u]
            for t in range(digits):
                lo = _BITS * t - s  # bit of a at the bottom of digit t
                if lo >= 64:
                    break
                if lo >= 0:
                    d = (a >> lo) & _MASK
                elif lo > -_BITS:
                    k = -lo
                    d = (a & ((np.int64(1) << (_BITS - k)) - 1)) << k
                else:
                    d = np.int64(0)
                out[p, u, t] = -d if neg else d


def _digits(x: np.ndarray, digits: int) -> np.ndarray:
    """``(n, 10, digits)`` normalised base-``2^26`` digits of an object array of integers."""
    out = np.empty((*x.shape, digits), dtype=np.int64)
    v = x
    mask = _MASK
    for t in range(digits - 1):
        out[..., t] = (v & mask).astype(np.int64)
        v = v >> _BITS
    out[..., digits - 1] = v.astype(np.int64)
    return out


def pencil_coefficients_int(e: np.ndarray, q: np.ndarray, bits: np.ndarray | None = None) -> list[np.ndarray]:
    """``[c0, .., c4]`` of ``det(lambda E + Q)`` as object arrays of Python integers, exactly.

    Parameters
    ----------
    e, q : ndarray, shape (n, 10)
        The upper entries (order of :data:`~quadric_contact.exact.entries.ENTRY_INDICES`)
        of integer matrices ``E`` and ``Q``, as int64 or object arrays of Python integers.
    bits : ndarray, shape (n,), optional
        For each pair, a bound: every entry of both matrices is below ``2^bits`` in
        magnitude (computed when not given).  Pairs are run in groups of the same digit
        count; pairs whose entries exceed ``2^(26 MAX_DIGITS - 1)`` are evaluated on
        Python integers.

    Returns
    -------
    list of ndarray
        Five object arrays, equal to
        :func:`quadric_contact._generated.formulas.pencil_coefficients` on the same integers.

    Raises
    ------
    ShapeError
        ``e`` and ``q`` are not ``(n, 10)`` arrays of one shape.
    """
    if e.shape != q.shape or e.ndim != 2 or e.shape[1] != 10:
        raise ShapeError("e and q must be (n, 10) arrays of the same shape")
    eo, qo = e.astype(object), q.astype(object)
    if bits is None:
        length = np.frompyfunc(lambda v: int(v).bit_length(), 1, 1)
        both = np.concatenate([eo, qo], axis=1)
        bits = length(np.abs(both)).max(axis=1, initial=0).astype(np.int64)
    return _run(eo, qo, np.asarray(bits, dtype=np.int64), None)


def pencil_coefficients_dyadic(
    me: np.ndarray, se: np.ndarray, mq: np.ndarray, sq: np.ndarray
) -> list[np.ndarray]:
    """:func:`pencil_coefficients_int` for the integers ``E = me * 2^se``, ``Q = mq * 2^sq``
    (entrywise; ``(n, 10)`` int64 arrays, ``|m| < 2^53``, ``shift >= 0``), without building
    the integers: how the exact mode reads binary64 matrices."""
    bits = 53 + np.maximum(se.max(axis=1, initial=0), sq.max(axis=1, initial=0))
    return _run(None, None, bits, (me, se, mq, sq))


def _run(
    eo: np.ndarray | None,
    qo: np.ndarray | None,
    bits: np.ndarray,
    dyadic: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray] | None,
) -> list[np.ndarray]:
    n = bits.shape[0]
    need = -(-(bits + 1) // _BITS)
    need = np.maximum(need, 1)
    out = [np.empty(n, dtype=object) for _ in range(5)]
    slow = need > MAX_DIGITS
    if slow.any() or not HAVE_KERNEL:
        if eo is None or qo is None:
            assert dyadic is not None
            me, se, mq, sq = dyadic
            eo = me.astype(object) << se.astype(object)
            qo = mq.astype(object) << sq.astype(object)

        idx = np.flatnonzero(slow) if HAVE_KERNEL else np.arange(n)
        vals = pencil_coefficients(*(eo[idx, k] for k in range(10)), *(qo[idx, k] for k in range(10)))
        for k in range(5):
            out[k][idx] = vals[k]
        if not HAVE_KERNEL:
            return out
    frm = int.from_bytes
    for digits in np.unique(need[~slow]):
        d = int(digits)
        idx = np.flatnonzero(need == d)
        nw = words(d)
        if dyadic is not None:
            me, se, mq, sq = dyadic
            ed, qd = dyadic_digits(me[idx], se[idx], d), dyadic_digits(mq[idx], sq[idx], d)
        else:
            assert eo is not None and qo is not None
            ed, qd = _digits(eo[idx], d), _digits(qo[idx], d)
        raw = pencil_words(ed, qd, d, nw).tobytes()
        size = 4 * nw
        vals = np.empty(5 * idx.size, dtype=object)
        vals[:] = [frm(raw[i : i + size], "little", signed=True) for i in range(0, len(raw), size)]
        c = vals.reshape(idx.size, 5)
        for k in range(5):
            out[k][idx] = c[:, k]
    return out
