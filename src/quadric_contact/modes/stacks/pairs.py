"""The inputs of the number modes: validated stacks of matrices and the pairs they form.

The array predicates hand a mode a :class:`Pairs` (two :class:`MatrixStack` and how their rows
pair up) and read back codes (:mod:`quadric_contact.modes.codes`).
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import numpy as np

from quadric_contact.exact.entries import ENTRY_INDICES
from quadric_contact.modes.stacks.packing import unpack

__all__ = ["MatrixStack", "Pairs", "as_fraction_array"]


class MatrixStack:
    """Validated symmetric matrices, ``n`` of them.

    Attributes
    ----------
    floats : ndarray, shape (n, 4, 4), float64
        The matrices in binary64 (C-contiguous).  When ``exact`` is None they
        *are* the input (a float is an exact dyadic rational); otherwise they are
        the correctly rounded values of ``exact``.  For packed input they are made
        from ``packed`` on first use (the fast kernels read ``packed`` itself).
    exact : ndarray of Fraction, shape (n, 10), or None
        The upper entries exactly, when the input was not binary64.
    checked : bool
        Symmetry and finiteness were verified on conversion (exact or packed input);
        float input is verified by the kernels that read it.
    name : str
        ``"E"`` or ``"Q"``, for messages.
    shape : tuple of int
        The caller's batch shape (``()`` for a single matrix), for messages.
    packed : ndarray, shape (n, 10), float64, or None
        The ten upper entries of each matrix (:func:`quadric_contact.pack`), when the
        input came packed.
    """

    __slots__ = ("_exact_signs", "_floats", "checked", "exact", "name", "packed", "shape")

    def __init__(
        self,
        floats: np.ndarray | None,
        exact: np.ndarray | None = None,
        checked: bool = False,
        name: str = "M",
        shape: tuple[int, ...] = (),
        packed: np.ndarray | None = None,
    ) -> None:
        if floats is None and packed is None:
            raise ValueError("a MatrixStack needs floats or packed entries")
        self._floats = floats
        self.exact = exact
        self.checked = checked
        self.name = name
        self.shape = shape
        self.packed = packed
        self._exact_signs: tuple[np.ndarray, np.ndarray] | None = None

    def exact_signs_memo(self) -> tuple[np.ndarray, np.ndarray]:
        """``(known, signs)``: per matrix, whether its exact invariant signs (``(8,)`` int8, as
        :meth:`quadric_contact.modes.numbers.objects.ObjectMode.invariant_signs` gives them) have been
        computed, and those signs; filled by the exact mode, once per matrix and stack."""
        if self._exact_signs is None:
            n = len(self)
            self._exact_signs = (np.zeros(n, dtype=bool), np.zeros((n, 8), dtype=np.int8))
        return self._exact_signs

    @property
    def floats(self) -> np.ndarray:
        if self._floats is None:
            assert self.packed is not None
            self._floats = np.ascontiguousarray(unpack(self.packed))
        return self._floats

    @property
    def packed_only(self) -> bool:
        """Whether the stack holds packed entries that have not been unpacked (reading
        :attr:`floats` would unpack all of them)."""
        return self._floats is None

    def rows_floats(self, rows: np.ndarray) -> np.ndarray:
        """``floats[rows]`` (a new ``(k, 4, 4)`` array), without unpacking the rest of a packed stack."""
        if self._floats is None:
            assert self.packed is not None
            return np.ascontiguousarray(unpack(self.packed[rows]))
        return np.ascontiguousarray(self._floats[rows])

    def kernel_array(self) -> tuple[np.ndarray, bool]:
        """The array the fast kernels read and whether it is packed: ``(n, 10)`` packed
        entries, or the ``(n, 16)`` flat view of ``floats``."""
        if self.packed is not None:
            return self.packed, True
        return self.floats.reshape(-1, 16), False

    def where(self, row: int) -> str:
        """``E[2, 1]``-style position of a matrix in the caller's array."""
        if not self.shape:
            return self.name
        idx = np.unravel_index(int(row), self.shape)
        return f"{self.name}[{', '.join(str(int(i)) for i in idx)}]"

    def __len__(self) -> int:
        return int((self.packed if self._floats is None else self._floats).shape[0])  # type: ignore[union-attr]

    def __repr__(self) -> str:
        layout = "packed" if self.packed is not None else "float64"
        return (
            f"MatrixStack({self.name}, {len(self)} matrices, {layout}{', rounded' if self.rounded else ''})"
        )

    @property
    def rounded(self) -> bool:
        return self.exact is not None

    def upper_exact(self, rows: np.ndarray) -> list[np.ndarray]:
        """The ten upper-entry columns of ``rows`` as object arrays of exact rationals
        (Fractions, or Python floats standing for their exact dyadic values)."""
        if self.exact is not None:
            sub = self.exact[rows]
            return [sub[:, k] for k in range(10)]
        if self._floats is None:
            assert self.packed is not None
            psub = self.packed[rows]
            return [psub[:, k].astype(object) for k in range(10)]
        sub = self.floats[rows]
        return [sub[:, i, j].astype(object) for i, j in ENTRY_INDICES]


@dataclass(frozen=True)
class Pairs:
    """The pairs ``(E[e_index[p]], Q[q_index[p]])`` for ``p`` in ``range(n)``.

    ``e_index`` is None when pair ``p`` uses ``E[p]`` (same length) or ``E[0]``
    (a single ellipsoid); likewise ``q_index``.
    """

    E: MatrixStack
    Q: MatrixStack
    n: int
    e_index: np.ndarray | None = None
    q_index: np.ndarray | None = None

    def e_rows(self) -> np.ndarray:
        return _rows(self.e_index, len(self.E), self.n)

    def q_rows(self) -> np.ndarray:
        return _rows(self.q_index, len(self.Q), self.n)

    def e_rows_at(self, which: np.ndarray) -> np.ndarray:
        """``e_rows()[which]``, without the rows of the whole batch."""
        return _rows_of(self.e_index, len(self.E), self.n, np.asarray(which, dtype=np.intp))

    def q_rows_at(self, which: np.ndarray) -> np.ndarray:
        """``q_rows()[which]``, without the rows of the whole batch."""
        return _rows_of(self.q_index, len(self.Q), self.n, np.asarray(which, dtype=np.intp))

    def take(self, which: np.ndarray) -> Pairs:
        """The sub-batch of the pairs ``which`` (indices into ``range(n)``).  A single matrix
        stays unindexed (no index of zeros to build and read back)."""
        which = np.asarray(which, dtype=np.intp)

        def index(own: np.ndarray | None, m: int) -> np.ndarray | None:
            if own is None and m == 1:
                return None  # the one matrix
            return _rows_of(own, m, self.n, which)

        return Pairs(self.E, self.Q, int(which.size), index(self.e_index, len(self.E)),
                     index(self.q_index, len(self.Q)))  # fmt: skip

    def kernel_indices(self) -> tuple[np.ndarray, np.ndarray, int, int]:
        """``(e_index, q_index, e_stride, q_stride)`` as the float kernels read them:
        an empty index array means ``row = p * stride``."""
        empty = np.zeros(0, dtype=np.intp)
        out: list[Any] = []
        for index in (self.e_index, self.q_index):
            out.append(empty if index is None else np.ascontiguousarray(index, dtype=np.intp))
        strides = [0 if (self.e_index is not None or len(self.E) == 1) else 1]
        strides.append(0 if (self.q_index is not None or len(self.Q) == 1) else 1)
        return out[0], out[1], strides[0], strides[1]


def _rows_of(index: np.ndarray | None, m: int, n: int, which: np.ndarray) -> np.ndarray:
    """``_rows(index, m, n)[which]`` without building the rows of the whole batch (the cascade
    takes a few pairs out of millions)."""
    if index is not None:
        return np.asarray(index, dtype=np.intp)[which]
    if m == n:
        return which.copy()
    return np.zeros(which.size, dtype=np.intp)


def _rows(index: np.ndarray | None, m: int, n: int) -> np.ndarray:
    if index is not None:
        return np.asarray(index, dtype=np.intp)
    if m == n:
        return np.arange(n, dtype=np.intp)
    return np.zeros(n, dtype=np.intp)


def as_fraction_array(values: Any) -> np.ndarray:
    """An object array of Fractions (helper for tests and fixtures)."""
    arr = np.asarray(values, dtype=object)
    return np.vectorize(Fraction, otypes=[object])(arr)
