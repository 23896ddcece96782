"""Double-double arithmetic: the error-free transformations and the operations of the
double-double invariant program, as plain functions of binary64 numbers.

A double-double is a pair ``x = (xh, xl)`` of binary64 numbers standing for the real number
``xh + xl``, with ``xh = RN(xh + xl)`` (a *double-word number* in the sense of Joldes, Muller,
Popescu, "Tight and rigorous error bounds for basic building blocks of double-word
arithmetic", ACM TOMS 44(2), 2017, JMP 2017 below): about 106 bits.  The generated programs
of :mod:`!quadric_contact._generated.dd_programs` (the cofactors of a quadratic part, the
invariants of a quadric) are written with these operations, passed to them as arguments;
their error bounds are :data:`~quadric_contact.modes.kernels.errorbounds.INVARIANTS_DD_ERRBOUND` and
:data:`~quadric_contact.modes.kernels.errorbounds.INVARIANTS_DD_COFACTOR_ERRBOUND`.

Error-free transformations (exact in binary64 with rounding to nearest, when no operation
overflows and no result is subnormal; the callers' input guard makes sure of both):

* :func:`two_sum` -- Knuth's and Moller's 2Sum: ``s + e = a + b``;
* :func:`fast_two_sum` -- Dekker's Fast2Sum: ``s + e = a + b`` when ``a = 0`` or the exponent
  of ``a`` is at least that of ``b`` (the operations below call it only so);
* :func:`split` -- Veltkamp's splitting with ``C = 2^27 + 1``: ``a = ah + al``, both halves
  of at most 26 significant bits, so that their products are exact;
* :func:`two_prod` -- Dekker's product (Dekker, "A floating-point technique for extending
  the available precision", Numer. Math. 18, 1971), without a fused multiply-add:
  ``p + e = a b``.

Operations, with the relative error bounds ``|z - x op y| <= eps |x op y|`` that JMP 2017
proves for them (``u = 2^-53``; their 2Prod may be any exact product, Dekker's here):

* :func:`dd_add`, :func:`dd_sub` -- AccurateDWPlusDW (JMP 2017, Algorithm 6):
  ``eps = 3u^2 + 13u^3``;
* :func:`dd_mul_d` -- DWTimesFP1 (JMP 2017, Algorithm 7), a double-double times a binary64
  number: ``eps = 3/2 u^2 + 4u^3``;
* :func:`dd_scale` -- times a power of two (or -1): exact.

Every function uses ``+ - *`` only, without a branch: the same text runs on Python floats,
element by element on numpy arrays (the ``numpy`` backend), and compiled by numba (the
functions are registered with :func:`!quadric_contact.modes.kernels._jit.jitable`).  None may be
evaluated with a fused multiply-add or reassociated: numba compiles without ``fastmath``, so
LLVM keeps every product and every sum rounded on its own, as Dekker's product needs
(tested: the compiled program gives the numpy values bit for bit).
"""

from __future__ import annotations

from typing import Any

from quadric_contact.modes.kernels._jit import jitable

__all__ = [
    "OPERATIONS",
    "SPLITTER",
    "dd_add",
    "dd_mul_d",
    "dd_scale",
    "dd_sub",
    "fast_two_sum",
    "split",
    "two_prod",
    "two_sum",
]

SPLITTER = 134217729.0
"""Veltkamp's constant ``2^27 + 1`` for binary64 (53 bits: two halves of 26 bits and a sign)."""


@jitable
def two_sum(a: Any, b: Any) -> Any:
    """``(s, e)`` with ``s = RN(a + b)`` and ``s + e = a + b`` exactly (2Sum, six operations)."""
    s = a + b
    bb = s - a
    return s, (a - (s - bb)) + (b - bb)


@jitable
def fast_two_sum(a: Any, b: Any) -> Any:
    """``(s, e)`` with ``s = RN(a + b)`` and ``s + e = a + b`` exactly, when ``a = 0`` or the
    exponent of ``a`` is at least that of ``b`` (Fast2Sum, three operations)."""
    s = a + b
    return s, b - (s - a)


@jitable
def split(a: Any) -> Any:
    """``(ah, al)`` with ``a = ah + al`` exactly, each of at most 26 significant bits
    (Veltkamp; ``SPLITTER * a`` must not overflow)."""
    t = SPLITTER * a
    ah = t - (t - a)
    return ah, a - ah


@jitable
def two_prod(a: Any, b: Any) -> Any:
    """``(p, e)`` with ``p = RN(a b)`` and ``p + e = a b`` exactly (Dekker's product, without a
    fused multiply-add: the four partial products of the halves are exact, and so is every
    sum that gathers them)."""
    p = a * b
    ah, al = split(a)
    bh, bl = split(b)
    return p, ((ah * bh - p) + ah * bl + al * bh) + al * bl


@jitable
def dd_add(x: Any, y: Any) -> Any:
    """``x + y`` for double-doubles ``x``, ``y``: AccurateDWPlusDW (JMP 2017, Algorithm 6),
    relative error at most ``3u^2 + 13u^3``."""
    sh, sl = two_sum(x[0], y[0])
    th, tl = two_sum(x[1], y[1])
    c = sl + th
    vh, vl = fast_two_sum(sh, c)
    w = tl + vl
    return fast_two_sum(vh, w)


@jitable
def dd_sub(x: Any, y: Any) -> Any:
    """``x - y``: :func:`dd_add` of ``x`` and ``-y`` (negation is exact), the same bound."""
    return dd_add(x, (-y[0], -y[1]))


@jitable
def dd_mul_d(x: Any, y: Any) -> Any:
    """The double-double ``x`` times the binary64 number ``y``: DWTimesFP1 (JMP 2017,
    Algorithm 7), relative error at most ``3/2 u^2 + 4u^3``."""
    ch, cl1 = two_prod(x[0], y)
    cl2 = x[1] * y
    th, tl1 = fast_two_sum(ch, cl2)
    tl2 = tl1 + cl1
    return fast_two_sum(th, tl2)


@jitable
def dd_scale(x: Any, s: Any) -> Any:
    """``x`` times ``s``, a power of two or ``-1``: exact (both words scale; the result is again
    a double-word number)."""
    return x[0] * s, x[1] * s


OPERATIONS = (two_sum, two_prod, dd_add, dd_sub, dd_mul_d, dd_scale)
"""The operations the generated double-double programs take as their first arguments, in order."""
