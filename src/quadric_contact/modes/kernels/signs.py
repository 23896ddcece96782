"""The three-valued sign: the primitive every filtered predicate reads its numbers with.

A filtered value is a binary64 number ``v`` and a bound ``err`` of its error, ``|v - x| <= err``
for the exact value ``x``.  :func:`sign_within` says what that certifies of the sign of ``x``:

* ``1`` if ``v > err`` (then ``x >= v - err > 0``), ``-1`` if ``v < -err``;
* ``0`` if ``err == 0``: the value is exact and neither test held, so ``x = v = 0``;
* else :data:`~quadric_contact.modes.codes.UNCERTAIN`: ``x`` may have either sign, or be zero.

Both comparisons are exact: ``-err`` is a binary64 number (negation does not round), and a
comparison of two binary64 numbers does not round, so no error enters between the bound and the
answer.  The tests are made in this order (``1`` first: both can hold only for a negative
bound).  With a NaN value neither holds, and the answer is ``UNCERTAIN`` (``0`` if the bound is
zero); with a NaN bound it is ``UNCERTAIN``.  The plain sign is the same reading with the bound
zero (:func:`plain_sign`), and :func:`dd_sign_within` reads a double-double value the same way.
:func:`sign_index` turns a three-valued sign into its index in the decision tables.

One source, two backends
------------------------
Each primitive is a plain function registered as a pair
(``quadric_contact.modes.kernels._jit.jitable`` with ``inline``): the name is the Python
function, which runs on scalars (the kernels' Python twins) and element by element on numpy
columns (the numpy backend; :func:`columns` stores the signs as ``int8``), and compiled code
that calls it calls its ``forceinline`` compiled side.  So the bodies branch on nothing: each
test is a boolean, and the answer is made of them with ``*`` and ``-``, which numpy applies
element by element and numba compiles to a few integer operations (the straight-line loops that
inline them stay vectorised).  They give Python or numpy integers (``int64``); the numpy callers
store them as ``int8``, the loops that work in doubles multiply them by ``1.0``.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from quadric_contact.modes.codes import UNCERTAIN
from quadric_contact.modes.kernels._jit import jitable

__all__ = ["columns", "dd_sign_within", "plain_sign", "sign_index", "sign_within"]


@jitable(inline=True)
def sign_within(v: Any, err: Any) -> Any:
    """The sign of the value ``v`` known to within ``err``: ``1`` if ``v > err``, ``-1`` if
    ``v < -err``, ``0`` if ``err == 0`` (exact), else :data:`UNCERTAIN`."""
    p = 1 * (v > err)
    n = (1 - p) * (v < -err)
    return p - n + UNCERTAIN * (1 - p - n) * (err != 0.0)


@jitable(inline=True)
def plain_sign(v: Any) -> Any:
    """The sign of ``v`` read as exact: ``1``, ``-1`` or ``0`` (a NaN reads as ``0``);
    :func:`sign_within` with ``err = 0``."""
    return 1 * (v > 0.0) - 1 * (v < 0.0)


@jitable(inline=True)
def dd_sign_within(v: Any, err: Any) -> Any:
    """The sign of the double-double ``v = (hi, lo)`` (``hi = RN(hi + lo)``) known to within
    ``err``, as :func:`sign_within` reads a binary64 value, without adding the words.

    The sign where ``|hi + lo| > err``, read exactly: ``hi > err`` implies ``hi + lo > err``
    (rounding is monotonic and ``err`` is a binary64 number), and so does ``hi = err`` with
    ``lo > 0``; otherwise ``hi + lo <= err`` (``hi < err`` implies it the same way, and
    ``hi = err`` with ``lo <= 0`` at once).  The same for ``-err``, the signs exchanged."""
    hi, lo = v
    p = 1 * ((hi > err) | ((hi == err) & (lo > 0.0)))
    n = (1 - p) * ((hi < -err) | ((hi == -err) & (lo < 0.0)))
    return p - n + UNCERTAIN * (1 - p - n) * (err != 0.0)


@jitable(inline=True)
def sign_index(s: Any) -> Any:
    """The index of a three-valued sign in the decision tables: ``-1, 0, 1, UNCERTAIN`` ->
    ``0, 1, 2, 3`` (``UNCERTAIN = 2`` is the code that makes it ``s + 1`` for all four)."""
    return s + 1


def columns(primitive: Callable[..., Any]) -> Callable[..., np.ndarray]:
    """The primitive on numpy columns, the signs as ``int8`` (the arrays of the modes): the
    primitive itself, element by element."""

    def on_columns(*args: Any) -> np.ndarray:
        return np.asarray(primitive(*args)).astype(np.int8)

    return on_columns
