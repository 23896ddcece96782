"""The binary64 modes: plain ``float`` and the certified ``filter``, and their drivers.

Both evaluate the generated closed forms (:mod:`quadric_contact._generated`): numba compiles
the very functions of ``formulas.py``, ``kernels.py`` and ``blocks.py`` into loop kernels
(``backend="numba"``), and numpy evaluates the same functions on whole columns
(``backend="numpy"``, :mod:`~quadric_contact.modes.kernels.numpy_backend`, also the fallback when
numba is missing).  The two give identical codes (tested).

A stack of binary64 pairs goes first to the fast kernels
(:mod:`~quadric_contact.modes.kernels.criterion`: plain float, or the filter's semi-static
screen), which read the input once at the speed of memory and answer every pair they are
sure of; the few they leave go to the general kernels
(:mod:`~quadric_contact.modes.kernels.filter`: plain float with the exact facts about the
quadrics, or the dynamic filter), as does exact input rounded to binary64.  The filter then
runs the pairs still uncertain a second time with exact facts about their quadrics.  Anything
still uncertain is ``UNCERTAIN`` and goes to the next stage of the mode.

Threads split the pair range (:mod:`~quadric_contact.modes.kernels.threads`); the kernels release the
GIL.
"""

from __future__ import annotations

import functools
from typing import Any

import numpy as np

from quadric_contact.exact.errors import ChoiceError
from quadric_contact.modes.codes import INVALID, UNCERTAIN, StageMethod
from quadric_contact.modes.decision.answers import (
    CONTACT_TABLE,
    ELLIPSOID_NOT,
    ELLIPSOID_UNCERTAIN,
    UNCERTAIN_ROW,
    masks_from_invariant_signs,
    rows_from_masks,
)
from quadric_contact.modes.facts import (
    certified_ellipsoid_signs,
    ellipsoid_masks,
    exact_facts,
    float_invariant_signs,
    proportional_exact,
    used_rows,
)
from quadric_contact.modes.kernels import errorbounds as eb
from quadric_contact.modes.kernels._jit import HAVE_NUMBA
from quadric_contact.modes.kernels.criterion import FALLBACK, NB, fast_codes
from quadric_contact.modes.kernels.decision import decide_ellipsoids
from quadric_contact.modes.kernels.filter import filter_kernel, float_kernel
from quadric_contact.modes.kernels.numpy_backend import (
    filter_quantities,
    numpy_pairs,
    screen_quantities,
    table_index,
)
from quadric_contact.modes.kernels.signature import signature_float
from quadric_contact.modes.kernels.threads import run_parallel
from quadric_contact.modes.numbers.number_mode import NumberMode
from quadric_contact.modes.smallness import binary64 as smallness_float
from quadric_contact.modes.stacks.pairs import MatrixStack, Pairs
from quadric_contact.modes.stacks.rows import set_rows, unique_rows
from quadric_contact.modes.stacks.validation import (
    diagnose,
    rows_view,
    validate_rows,
)

__all__ = [
    "BACKENDS",
    "BLOCK",
    "HAVE_NUMBA",
    "FilterMode",
    "FloatMode",
    "float_pairs",
    "stage_codes",
]

BACKENDS = ("numba", "numpy") if HAVE_NUMBA else ("numpy",)
BLOCK = NB
"""Pairs per block of the numba kernels."""


# -- the general path -----------------------------------------------------------------------


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
    screen: bool = False,
) -> np.ndarray:
    """Codes for ``n`` pairs of the float64 stacks ``E``, ``Q`` (``(m, 4, 4)``) by the general
    kernels (the dynamic filter, or plain float with the structural ``qflags``).

    ``prop`` (plain float only): per pair, whether the quadratic parts are proportional,
    decided exactly beforehand (for rounded exact input, whose floats cannot tell).
    ``screen``: the numpy variant lets the semi-static screen decide first, as the compiled
    path does (binary64 input, first pass of the filter).

    Returns :class:`ContactCode` values (or :class:`RegionCode` values when ``qrows``, the row
    of every quadric, is given), ``UNCERTAIN`` where the filter cannot decide and
    :data:`~quadric_contact.modes.codes.INVALID` where an input fails validation.
    """
    eidx, qidx, es, qs = indices
    want_region = qrows is not None
    flags = (
        np.zeros(Q.shape[0], dtype=np.int8) if qflags is None else np.ascontiguousarray(qflags, dtype=np.int8)
    )
    rows = np.zeros(1, dtype=np.int16) if qrows is None else np.ascontiguousarray(qrows, dtype=np.int16)
    masks = np.zeros(1, dtype=np.int64) if qmasks is None else np.ascontiguousarray(qmasks, dtype=np.int64)
    pp = np.zeros(0, dtype=np.int8) if prop is None else np.ascontiguousarray(prop, dtype=np.int8)
    out = np.empty(n, dtype=np.int8)
    if n == 0:
        return out
    if backend == "numpy" or not HAVE_NUMBA:
        return numpy_pairs(
            E,
            Q,
            eidx,
            qidx,
            es,
            qs,
            n,
            filtered,
            rounded,
            rows,
            masks,
            want_region,
            flags,
            same_ok,
            pp,
            screen,
        )
    if backend != "numba":
        raise ChoiceError(
            f"backend must be one of {', '.join(BACKENDS)}, got {backend!r}", backend, choices=tuple(BACKENDS)
        )

    E2 = np.ascontiguousarray(E).reshape(-1, 16)
    Q2 = np.ascontiguousarray(Q).reshape(-1, 16)
    if filtered:
        KP, KL, DR, DA = eb.filter_constants(rounded)
        run_parallel(
            lambda lo, hi: filter_kernel(
                E2,
                Q2,
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
            lambda lo, hi: float_kernel(
                E2, Q2, eidx, qidx, es, qs, lo, hi, rows, masks, want_region, flags, same_ok, pp, out
            ),
            n,
            threads,
        )
    return out


def _compact(stack: MatrixStack, rows: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(floats, used, index)``: the ``(k, 4, 4)`` matrices of the distinct ``rows``, the rows
    they are, and where each entry of ``rows`` finds its matrix among them."""
    used, index = unique_rows(rows, len(stack), return_inverse=True)
    return stack.rows_floats(used), used, index


def stage_codes(E: np.ndarray, Q: np.ndarray, stage: str, *, backend: str = "numba") -> np.ndarray:
    """Contact codes of one stage alone (``"screen"``, the semi-static screen, or ``"filter"``,
    the dynamic filter) for the pairs ``(E[k], Q[k])`` of two ``(n, 4, 4)`` binary64 stacks:
    ``UNCERTAIN`` where the stage is not sure (for the screen also where it would not look: an
    input outside its guards); for tests and measurements."""

    n = E.shape[0]
    e0 = np.zeros(0, dtype=np.intp)
    if stage == "screen":
        if backend == "numba" and HAVE_NUMBA:
            out, _ = fast_codes(
                E.reshape(-1, 16), Q.reshape(-1, 16), False, False, (e0, e0, 1, 1), n, filtered=True,
                qrows=None, qmasks=None, run=lambda k, m: k(0, m),
            )  # fmt: skip
            return np.where(out == FALLBACK, UNCERTAIN, out).astype(np.int8)
        sq = screen_quantities(E, Q)
        code = CONTACT_TABLE[table_index(sq["signs"][5:])]
        return np.where(sq["ok"], code, UNCERTAIN).astype(np.int8)
    if backend == "numba" and HAVE_NUMBA:
        out = np.empty(n, dtype=np.int8)
        rows, masks = np.zeros(1, dtype=np.int16), np.zeros(1, dtype=np.int64)
        KP, KL, DR, DA = eb.filter_constants(False)
        flags = np.zeros(Q.shape[0], dtype=np.int8)
        filter_kernel(
            E.reshape(-1, 16), Q.reshape(-1, 16), e0, e0, 1, 1, 0, n, KP, KL, DR, DA, flags, True, rows,
            masks, False, out,
        )  # fmt: skip
        return out
    q = filter_quantities(E, Q)
    code = CONTACT_TABLE[table_index(q["signs"][5:])]
    code = np.where(q["outside"] | (q["ell"] == ELLIPSOID_UNCERTAIN), UNCERTAIN, code)
    bad = ~(np.isfinite(E).all(axis=(1, 2)) & np.isfinite(Q).all(axis=(1, 2)))
    bad |= ~((np.swapaxes(E, 1, 2) == E).all(axis=(1, 2)) & (np.swapaxes(Q, 1, 2) == Q).all(axis=(1, 2)))
    return np.where(bad | (q["ell"] == ELLIPSOID_NOT), INVALID, code).astype(np.int8)


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
            choices = tuple(BACKENDS)
            message = f"backend must be one of {', '.join(choices)}, got {backend!r}"
            raise ChoiceError(message, backend, choices=choices)
        self.threads = threads
        if not self.filtered:
            # binary64's reading of non-real roots is confirmed by the filter's (see the pipeline)
            self.guard = FilterMode(self.backend, threads)
        # what classify remembers within one decision (None: nothing, not remembering)
        self._classified: tuple[MatrixStack, np.ndarray, np.ndarray] | tuple[()] | None = None

    def _fast(self, pairs: Pairs) -> bool:
        """The fast kernels apply: compiled, binary64 input (not rounded exact input)."""
        return self.backend == "numba" and HAVE_NUMBA and not (pairs.E.rounded or pairs.Q.rounded)

    def _kernel(
        self, pairs: Pairs, qtypes: Any, qflags: np.ndarray | None
    ) -> tuple[np.ndarray, np.ndarray | None]:
        """Codes of every pair: the fast kernels first when they apply (and no exact facts are
        given), the general ones for what they leave.  Also the pairs that may be ``INVALID``
        or ``UNCERTAIN`` (increasing; None: any of them): the screen answers only what it is
        sure of, so for the filter they are among those it left to the general kernels."""
        qrows, qmasks = qtypes if qtypes is not None else (None, None)
        if qflags is None and self._fast(pairs):
            E, epacked = pairs.E.kernel_array()
            Q, qpacked = pairs.Q.kernel_array()
            codes, fall = fast_codes(
                E, Q, epacked, qpacked, pairs.kernel_indices(), pairs.n, filtered=self.filtered, qrows=qrows,
                qmasks=qmasks, run=functools.partial(run_parallel, threads=self.threads),
            )  # fmt: skip
            if fall.size:
                codes[fall] = self._general(pairs.take(fall), qrows, qmasks, None, screen_done=True)
            return codes, (fall if self.filtered else None)
        return self._general(pairs, qrows, qmasks, qflags, screen_done=False), None

    def _general(
        self, pairs: Pairs, qrows: Any, qmasks: Any, qflags: np.ndarray | None, *, screen_done: bool
    ) -> np.ndarray:
        """The general kernels on ``pairs``; plain float computes the exact facts of the quadrics
        involved when they are not given.  The matrices of the pairs are gathered into compact
        stacks first when the pairs index them (a subset: nothing else is unpacked)."""
        rounded = pairs.E.rounded or pairs.Q.rounded
        if not self.filtered and qflags is None:
            qflags = self._structural_flags(pairs.Q, np.unique(pairs.q_rows()))
        prop = None
        if rounded and not self.filtered:
            prop = proportional_exact(pairs, pairs.e_rows(), pairs.q_rows()).astype(np.int8)
        if pairs.e_index is None and pairs.q_index is None:
            E, Q, indices = pairs.E.floats, pairs.Q.floats, pairs.kernel_indices()
            flags, rows, masks = qflags, qrows, qmasks
        else:
            E, _, eidx = _compact(pairs.E, pairs.e_rows())
            Q, used, qidx = _compact(pairs.Q, pairs.q_rows())
            indices = (eidx, qidx, 0, 0)
            flags = None if qflags is None else qflags[used]
            rows = None if qrows is None else np.asarray(qrows)[used]
            masks = None if qmasks is None else np.asarray(qmasks)[used]
        return float_pairs(
            E,
            Q,
            indices,
            pairs.n,
            filtered=self.filtered,
            rounded=rounded,
            qrows=rows,
            qmasks=masks,
            qflags=flags,
            same_ok=not rounded,
            prop=prop,
            backend=self.backend,
            threads=self.threads,
            screen=self.filtered and not rounded and qflags is None and not screen_done,
        )

    def _structural_flags(self, Q: MatrixStack, used: np.ndarray) -> np.ndarray:
        """Per quadric (length ``len(Q)``): the exact facts ``det Q = 0`` (bit 0) and
        ``rank Q <= 2`` (bit 1), computed exactly (:func:`~quadric_contact.modes.facts.exact_facts`)
        for the quadrics whose
        determinant binary64 cannot tell from zero, so that plain float reads the structural
        zeros of cylinders, planes and parallel planes as the filter does."""
        flags = np.zeros(len(Q), dtype=np.int8)
        if used.size == 0:
            return flags
        signs = float_invariant_signs(
            Q.rows_floats(used), filtered=True, rounded=Q.rounded, backend=self.backend
        )
        maybe = used[(signs[:, 6] == 0) | (signs[:, 6] == UNCERTAIN)]
        if maybe.size:
            flags[maybe] = exact_facts(Q, maybe)[0]
        return flags

    def _codes(self, pairs: Pairs, qtypes: Any) -> tuple[np.ndarray, np.ndarray | None]:
        """The criterion codes and the pairs that may be ``UNCERTAIN`` (see :meth:`_kernel`)."""
        codes, maybe = self._kernel(pairs, qtypes, None)

        def where(value: int) -> np.ndarray:
            return set_rows(codes == value) if maybe is None else maybe[codes[maybe] == value]

        invalid = where(INVALID)
        if invalid.size:
            codes[invalid] = diagnose(pairs, invalid)
        if self.filtered:
            todo = where(UNCERTAIN)
            if todo.size:
                # Second pass with exact facts about the quadrics involved (once per quadric):
                # structural zeros of c0, c1 and, for regions, the exact type.
                used = np.unique(pairs.q_rows_at(todo))
                facts, exact_masks = exact_facts(pairs.Q, used)
                flags = np.zeros(len(pairs.Q), dtype=np.int8)
                flags[used] = facts
                types = None
                if qtypes is not None:
                    masks = qtypes[1].copy()
                    masks[used] = exact_masks
                    types = (rows_from_masks(masks), masks)
                if flags.any() or types is not None:
                    again, _ = self._kernel(pairs.take(todo), types, flags)
                    codes[todo] = np.where(again == INVALID, UNCERTAIN, again)
        return codes, maybe

    def criterion_contact(self, pairs: Pairs) -> np.ndarray:
        return self._codes(pairs, None)[0]

    def criterion_region(self, pairs: Pairs) -> np.ndarray:
        return self._codes(pairs, self._region_types(pairs))[0]

    def _region_types(self, pairs: Pairs) -> tuple[np.ndarray, np.ndarray]:
        used = used_rows(pairs.q_index, len(pairs.Q), pairs.n)
        masks = np.zeros(len(pairs.Q), dtype=np.int64)
        masks[used] = self.classify(pairs.Q, used)
        if used.size == len(pairs.Q):
            return rows_from_masks(masks), masks
        # a few pairs of a large stack (those the decision kernel left): the rows of the
        # quadrics they use only (the others are never read; a zero mask is UNCERTAIN_ROW)
        rows = np.full(len(pairs.Q), UNCERTAIN_ROW, dtype=np.int16)
        rows[used] = rows_from_masks(masks[used])
        return rows, masks

    def with_candidates(self, method: StageMethod, pairs: Pairs) -> tuple[np.ndarray, np.ndarray | None]:
        if method is StageMethod.CRITERION_CONTACT:
            return self._codes(pairs, None)
        if method is StageMethod.CRITERION_REGION:
            return self._codes(pairs, self._region_types(pairs))
        return super().with_candidates(method, pairs)

    def decide_ellipsoids(
        self, pairs: Pairs, *, outside_too: bool, table: tuple[np.ndarray, np.ndarray] | None = None
    ) -> tuple[np.ndarray, ...] | None:
        """The decision kernel's reading of every pair, and its answers read through ``table``
        (:func:`~quadric_contact.modes.kernels.decision.decide_ellipsoids`: certified, in one pass),
        or None where it does not apply (input rounded from exact numbers, the numpy backend)."""
        if not self._fast(pairs):
            return None

        return decide_ellipsoids(pairs, outside_too=outside_too, table=table, threads=self.threads)

    def separation(self, pairs: Pairs) -> np.ndarray:
        return signature_float(pairs, certified=self.filtered, backend=self.backend, threads=self.threads)

    def smallness(self, pairs: Pairs) -> np.ndarray:
        return smallness_float.run(self, pairs)

    def classify(self, Q: MatrixStack, rows: np.ndarray | None = None) -> np.ndarray:
        """The type of each quadric: binary64 with the filter's bounds; plain ``float`` takes
        the exact type where binary64 cannot tell (once per quadric), so that a structural
        zero (a cylinder's ``det Q = 0``) is never read from rounding noise."""
        index = np.arange(len(Q)) if rows is None else np.asarray(rows, dtype=np.intp)
        seen = self._classified
        if seen and seen[0] is Q and bool(seen[1][index].all()):
            # the stages of one decision ask about the same quadrics (the pipeline's classes,
            # then smallness): once per quadric and call (see remember)
            return seen[2][index]
        validate_rows(Q, index)
        sub = Q.floats if rows is None else rows_view(Q, index)
        if Q.rounded:
            rest = None
            masks = masks_from_invariant_signs(
                float_invariant_signs(sub, filtered=True, rounded=True, backend=self.backend)
            )
        else:
            # Most quadrics of a stack of pairs are ellipsoids: a short certified test settles
            # them (a third of the invariants' work); the invariant signs decide the others.
            ell = certified_ellipsoid_signs(sub, backend=self.backend)
            masks = ellipsoid_masks(ell)
            rest = np.flatnonzero(ell == 0)
            if rest.size:
                masks[rest] = masks_from_invariant_signs(
                    float_invariant_signs(sub[rest], filtered=True, rounded=False, backend=self.backend)
                )
        if not self.filtered:
            unsure = np.flatnonzero(rows_from_masks(masks) == UNCERTAIN_ROW)
            if unsure.size:
                masks[unsure] = exact_facts(Q, index[unsure])[1]
        if seen is not None:
            if not seen or seen[0] is not Q:
                seen = (Q, np.zeros(len(Q), dtype=bool), np.zeros(len(Q), dtype=masks.dtype))
            seen[2][index] = masks
            seen[1][index] = True
            self._classified = seen
        return masks

    def remember(self) -> None:
        """From now on :meth:`classify` answers again from memory for the same stack (the
        pipeline calls this at the start of a decision and :meth:`forget` at its end)."""
        self._classified = ()

    def forget(self) -> None:
        """Drop what :meth:`classify` remembers, and stop remembering."""
        self._classified = None

    def __repr__(self) -> str:
        return f"{type(self).__name__}(backend={self.backend!r})"


class FilterMode(FloatMode):
    """binary64 with a rigorous error bound (``mode="filter"``, the first stage of
    ``certified``): a sign only where it is certain, ``UNCERTAIN`` elsewhere.
    The bounds are derived in :mod:`quadric_contact.modes.kernels.errorbounds`.

    Binary64 input goes first through the semi-static screen (one bound per coefficient from
    the row maxima of the two matrices; a few flops more than plain float), then, for what the
    screen leaves, the dynamic filter.  Structural zeros are recognised, not left to rounding:
    an exact zero entry gives an exact zero bound (a plane's ``c0 = c1 = 0``); equal quadratic
    parts (compared exactly) give ``Delta_4 = 0``; and the pairs still undecided after the first
    pass are run again with exact facts about their quadrics, computed once per quadric in
    integer arithmetic (:func:`~quadric_contact.modes.facts.exact_facts`: ``det Q = 0``,
    ``rank Q <= 2``, the type)."""

    name = "filter"
    stage = "filter"
    certified = True
    filtered = True
