"""The size of an exact pair, for the work bound of the exact engine.

The exact decisions (real algebraic numbers, discriminants, resultants) cost a
high power of the size of the entries; :func:`pair_bits` measures it before the
work and :func:`check_pair_size` refuses a pair beyond
:data:`~quadric_contact.exact.bounds.MAX_PAIR_BITS` with a
:class:`~quadric_contact.exact.errors.WorkLimitError` that names it.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from fractions import Fraction
from typing import Any

from quadric_contact.exact.bounds import MAX_PAIR_BITS
from quadric_contact.exact.errors import WorkLimitError

__all__ = ["check_pair_size", "matrix_bits", "pair_bits"]


def matrix_bits(entries: Iterable[Fraction]) -> int:
    """Bits of a matrix as integers over one denominator: the bit length of the
    common denominator plus that of the largest numerator over it.

    >>> matrix_bits([Fraction(1, 2), Fraction(3, 4), Fraction(0)])
    4
    """
    values = list(entries)
    d = math.lcm(*(v.denominator for v in values)) if values else 1
    top = max((abs(v.numerator * (d // v.denominator)).bit_length() for v in values), default=0)
    return d.bit_length() - 1 + top


def pair_bits(E: Any, Q: Any) -> int:
    """:func:`matrix_bits` of ``E`` plus that of ``Q`` (each a Quadric, or its entries)."""
    return sum(matrix_bits(getattr(M, "upper", M)) for M in (E, Q))


def check_pair_size(E: Any, Q: Any, what: str = "the exact decision") -> None:
    """Refuse a pair whose :func:`pair_bits` exceed :data:`MAX_PAIR_BITS`, before the work.

    Raises
    ------
    WorkLimitError
        Naming the pair (its equations, shortened) and the bound.
    """
    bits = pair_bits(E, Q)
    if bits > MAX_PAIR_BITS:
        names = []
        for label, M in (("E", E), ("Q", Q)):
            text = M.equation() if hasattr(M, "equation") else str(M)
            names.append(f"{label}: {text[:60]}{'...' if len(text) > 60 else ''}")
        raise WorkLimitError(
            f"{what}: the pair ({'; '.join(names)}) has {bits} bits of entries over common "
            f"denominators, more than {MAX_PAIR_BITS} (MAX_PAIR_BITS)",
            (E, Q),
            limit=MAX_PAIR_BITS,
            needed=bits,
        )
