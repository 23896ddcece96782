"""The base class of the number modes: the four questions, answered by one pipeline.

:class:`NumberMode` declares the stages a mode implements with its numbers and
answers the public questions (:meth:`~NumberMode.contact`, :meth:`~NumberMode.region`,
:meth:`~NumberMode.kind`, :meth:`~NumberMode.overlap`) by handing itself to
:mod:`quadric_contact.modes.decision.pipeline`.  It is apart from
:mod:`quadric_contact.modes.codes` (the codes and inputs every mode shares, which the
pipeline itself imports), so the pipeline is imported here at module level without
a cycle.
"""

from __future__ import annotations

import threading
from abc import ABC, abstractmethod
from typing import Any

import numpy as np

from quadric_contact.modes.codes import StageCounts
from quadric_contact.modes.decision.pipeline import decide, decide_overlap
from quadric_contact.modes.stacks.pairs import MatrixStack, Pairs

__all__ = ["NumberMode"]


class NumberMode(ABC):
    """A way of evaluating the closed forms (one formula, many number types).

    The public array predicates ask a mode four questions, :meth:`contact`,
    :meth:`region`, :meth:`kind` and :meth:`overlap`, and always mean the geometry (do the
    surfaces cross, where is ``E``, how do they touch, do the solids overlap), for every
    pair.  They are answered by one pipeline (:mod:`quadric_contact.modes.decision.pipeline`)
    from the *stages* a mode
    implements with its numbers:

    * :meth:`criterion_contact`, :meth:`criterion_region`: the paper's criterion (the
      nature of the roots of ``P``, Corollary 10 / Remark 9, and the Table 4 reading
      of their signs; Theorem 14 for planes), with no smallness test;
    * :meth:`classify`: the type of each quadric;
    * :meth:`smallness`: Definition 1 through Tables 1-2 (corrected), a public report, not
      a step of the decision;
    * :meth:`separation`: the pencil's signature sequence, looked up in the decision table
      (:mod:`quadric_contact.modes.decision.separation`, :mod:`quadric_contact.theory.decision`).

    Every public call records which stage settled how many entries in :attr:`last`
    and adds it to :attr:`counts` (thread-safe).

    Attributes
    ----------
    name : str
    certified : bool
        True if every answer other than ``UNCERTAIN`` is guaranteed right (for the
        matrices as given).
    complete : bool
        True if the mode ends with the exact scalar predicates for what its stages leave
        (``certified``, ``exact``): it never answers ``UNCERTAIN``.
    guard : NumberMode or None
        A plain mode's certified reading of the criterion: the pipeline confirms with it the
        crossings the plain mode reads from non-real roots (None: not needed).
    """

    name: str = "mode"
    stage: str = "mode"
    certified: bool = False
    complete: bool = False
    guard: NumberMode | None = None

    def __init__(self) -> None:
        #: What every call so far settled, stage by stage (added up; thread-safe).
        self.counts = StageCounts()
        #: What the last call settled, stage by stage.
        self.last = StageCounts()
        self._lock = threading.Lock()

    def _record(self, counts: StageCounts) -> None:
        with self._lock:
            self.last = counts
            self.counts.merge(counts)

    def __getstate__(self) -> dict[str, Any]:
        state = dict(self.__dict__)
        del state["_lock"]
        return state

    def __setstate__(self, state: dict[str, Any]) -> None:
        self.__dict__.update(state)
        self._lock = threading.Lock()

    def reset_counts(self) -> None:
        with self._lock:
            self.counts = StageCounts()
            self.last = StageCounts()

    # -- the questions (one pipeline for every mode) -------------------------------------

    def contact(self, pairs: Pairs) -> np.ndarray:
        """:class:`ContactCode` of every pair: do the surfaces cross (int8, ``(pairs.n,)``)."""
        return decide(self, pairs, "contact")

    def region(self, pairs: Pairs) -> np.ndarray:
        """:class:`RegionCode` of every pair: the side of ``Q`` the surface of ``E`` is on."""
        return decide(self, pairs, "region")

    def kind(self, pairs: Pairs) -> np.ndarray:
        """:class:`ContactKindCode` of every pair (Table 3)."""
        return decide(self, pairs, "kind")

    def overlap(self, pairs: Pairs) -> np.ndarray:
        """:class:`OverlapCode` of every pair: do the solids of ``E`` and ``Q`` overlap?"""
        return decide_overlap(self, pairs)

    def criterion(self, pairs: Pairs) -> np.ndarray:
        """:class:`CriterionCode` of every pair (the raw criterion), recording its counts."""
        codes, names, which, later = self.staged_rows("criterion_contact", pairs)
        self._record(_stage_counts("criterion", names, which, later))
        return codes

    def public_smallness(self, pairs: Pairs) -> np.ndarray:
        """:class:`SmallnessCode` of every pair, recording its counts."""
        codes, names, which, later = self.staged_rows("smallness", pairs)
        self._record(_stage_counts("smallness", names, which, later))
        return codes

    # -- the stages -------------------------------------------------------------------------

    @abstractmethod
    def criterion_contact(self, pairs: Pairs) -> np.ndarray:
        """The criterion: ``1`` non-real roots, ``0`` all roots real (``ContactCode`` values;
        ``UNCERTAIN`` where the mode cannot tell).  Validates the input."""

    @abstractmethod
    def criterion_region(self, pairs: Pairs) -> np.ndarray:
        """The criterion and Table 4's reading of the root signs (``RegionCode`` values)."""

    @abstractmethod
    def classify(self, Q: MatrixStack, rows: np.ndarray | None = None) -> np.ndarray:
        """Candidate Table 4 rows (int64 bit masks, see :mod:`~quadric_contact.modes.decision.answers`)
        of the quadrics ``rows`` (all by default): one bit where the type is certain."""

    @abstractmethod
    def separation(self, pairs: Pairs) -> np.ndarray:
        """Separation certificate codes (``RegionCode`` values -1, 0, 1 or ``UNCERTAIN``)."""

    def smallness(self, pairs: Pairs) -> np.ndarray:
        """:class:`SmallnessCode` of every pair (Tables 1-2, corrected)."""
        raise NotImplementedError(f"{type(self).__name__} does not decide smallness on arrays")

    def with_candidates(self, method: str, pairs: Pairs) -> tuple[np.ndarray, np.ndarray | None]:
        """``getattr(self, method)(pairs)`` and the entries that may be ``UNCERTAIN``
        (increasing, a superset), or None when any may be: where a cascade looks for the
        entries of its next stage without searching the whole batch."""
        return getattr(self, method)(pairs), None

    def staged(self, method: str, pairs: Pairs) -> tuple[np.ndarray, list[str], np.ndarray]:
        """Run the stage ``method``: ``(codes, stage names, index of the stage that decided
        each entry or -1)``.  A cascade (the certified mode) reports each of its stages."""
        codes = getattr(self, method)(pairs)
        which = np.negative((codes == 2).view(np.int8))  # 0 decided, -1 not
        return codes, [self.stage], which

    def staged_rows(
        self, method: str, pairs: Pairs
    ) -> tuple[np.ndarray, list[str], np.ndarray, np.ndarray | None]:
        """:meth:`staged` and the entries not decided by the first stage (a superset, or None
        when not known), so that the counts need not search the batch."""
        return (*self.staged(method, pairs), None)

    def __repr__(self) -> str:
        return f"{type(self).__name__}()"


def _stage_counts(
    step: str, names: list[str], which: np.ndarray, rows: np.ndarray | None = None
) -> StageCounts:
    """The counts of ``step`` from the deciding stage of every entry (``which``: stage index, or
    -1 undecided): nearly every entry is the first stage's (0).  ``rows``: a superset of the
    entries that are not (then the batch is not searched)."""
    if rows is not None:
        later = which[rows]
        later = later[later != 0]
    else:
        # one pass over the batch (nonzero on a bool array: on int8 it is ten times slower)
        later = which[np.flatnonzero(which != 0)] if np.count_nonzero(which) else which[:0]
    counts = StageCounts()
    for k, name in enumerate(names):
        k_count = which.size - later.size if k == 0 else np.count_nonzero(later == k)
        counts.add(f"{step} ({name})", int(k_count))
    counts.undecided = int(np.count_nonzero(later < 0))
    return counts
