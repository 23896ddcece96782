"""The base class of the number modes: the questions, answered by one pipeline.

:class:`NumberMode` declares the stages a mode implements with its numbers and
answers the public questions (:meth:`~NumberMode.decide`, by the question's name: the contact,
the region, the kind of contact, the overlap, by handing itself to
:mod:`quadric_contact.modes.decision.pipeline`; the raw criterion and smallness, by its own
stages), returning the codes with the counts of the stages that settled them.  It is apart from
:mod:`quadric_contact.modes.codes` (the codes and inputs every mode shares, which the
pipeline itself imports), so the pipeline is imported here at module level without
a cycle.
"""

from __future__ import annotations

import threading
from abc import ABC, abstractmethod
from collections.abc import Callable
from typing import Any, NamedTuple

import numpy as np

from quadric_contact.exact.errors import ChoiceError
from quadric_contact.modes.codes import Provenance, StageCounts, StageMethod, Step
from quadric_contact.modes.decision.pipeline import decide, decide_overlap
from quadric_contact.modes.stacks.pairs import MatrixStack, Pairs

__all__ = ["QUESTIONS", "Decided", "NumberMode"]


class Decided(NamedTuple):
    """What one call of :meth:`NumberMode.decide` settled: the codes (int8, one per pair) and
    the counts of the stages that settled them, this call's alone."""

    codes: np.ndarray
    counts: StageCounts


class NumberMode(ABC):
    """A way of evaluating the closed forms (one formula, many number types).

    The public predicates ask a mode a question by its name, :meth:`decide` (``"contact"``,
    ``"region"``, ``"kind"``, ``"overlap"``, and ``"criterion"``, ``"smallness"``; the
    shorthands :meth:`contact`, :meth:`region`, :meth:`kind`, :meth:`overlap` give the codes
    alone), and always mean the geometry (do the surfaces cross, where is ``E``, how do they
    touch, do the solids overlap), for every pair.  They are answered by one pipeline
    (:mod:`quadric_contact.modes.decision.pipeline`) from the *stages* a mode
    implements with its numbers:

    * :meth:`criterion_contact`, :meth:`criterion_region`: the paper's criterion (the
      nature of the roots of ``P``, Corollary 10 / Remark 9, and the Table 4 reading
      of their signs; Theorem 14 for planes), with no smallness test;
    * :meth:`classify`: the type of each quadric;
    * :meth:`smallness`: Definition 1 through Tables 1-2 (corrected), a public report, not
      a step of the decision;
    * :meth:`separation`: the pencil's signature sequence, looked up in the decision table
      (:mod:`quadric_contact.modes.decision.separation`, :mod:`quadric_contact.theory.decision`).

    Every call of :meth:`decide` returns which stage settled how many entries with the codes
    (:class:`Decided`), and, for a caller who holds the instance, records them in :attr:`last`
    and adds them to :attr:`counts` (under a lock).  :attr:`last` is a convenience of a
    caller's own instance: when one instance serves several threads it is whichever call
    finished last; the counts of a call come with the call.

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
        #: What every call so far settled, stage by stage (added up under a lock).
        self.counts = StageCounts()
        #: What the last call to finish settled, stage by stage (a convenience of a caller's own
        #: instance; :meth:`decide` returns each call's counts with its codes).
        self.last = StageCounts()
        self._lock = threading.Lock()

    def _record(self, counts: StageCounts) -> None:
        """Make ``counts`` the :attr:`last` call's and add them to :attr:`counts`."""
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

    def decide(self, question: str, pairs: Pairs) -> Decided:
        """The codes answering ``question`` for every pair, with the counts of the stages that
        settled them (this call's: nothing else reads them), also recorded in :attr:`last` and
        :attr:`counts`.

        ``question`` is a key of :data:`QUESTIONS`: ``"contact"`` (:class:`ContactCode`),
        ``"region"`` (:class:`RegionCode`), ``"kind"`` (:class:`ContactKindCode`),
        ``"overlap"`` (:class:`OverlapCode`), ``"criterion"`` (:class:`CriterionCode`, the raw
        criterion) or ``"smallness"`` (:class:`SmallnessCode`).

        Raises
        ------
        ChoiceError
            For another question.
        """
        answer = QUESTIONS.get(question)
        if answer is None:
            raise ChoiceError(
                f"question must be one of {', '.join(QUESTIONS)}, got {question!r}",
                question,
                choices=tuple(QUESTIONS),
            )
        codes, counts = answer(self, pairs)
        self._record(counts)
        return Decided(codes, counts)

    def contact(self, pairs: Pairs) -> np.ndarray:
        """:class:`ContactCode` of every pair: do the surfaces cross (int8, ``(pairs.n,)``)."""
        return self.decide("contact", pairs).codes

    def region(self, pairs: Pairs) -> np.ndarray:
        """:class:`RegionCode` of every pair: the side of ``Q`` the surface of ``E`` is on."""
        return self.decide("region", pairs).codes

    def kind(self, pairs: Pairs) -> np.ndarray:
        """:class:`ContactKindCode` of every pair (Table 3)."""
        return self.decide("kind", pairs).codes

    def overlap(self, pairs: Pairs) -> np.ndarray:
        """:class:`OverlapCode` of every pair: do the solids of ``E`` and ``Q`` overlap?"""
        return self.decide("overlap", pairs).codes

    def criterion(self, pairs: Pairs) -> np.ndarray:
        """:class:`CriterionCode` of every pair (the raw criterion)."""
        return self.decide("criterion", pairs).codes

    def public_smallness(self, pairs: Pairs) -> np.ndarray:
        """:class:`SmallnessCode` of every pair (the smallness question)."""
        return self.decide("smallness", pairs).codes

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

    def with_candidates(self, method: StageMethod, pairs: Pairs) -> tuple[np.ndarray, np.ndarray | None]:
        """``method.run(self, pairs)`` and the entries that may be ``UNCERTAIN``
        (increasing, a superset), or None when any may be: where a cascade looks for the
        entries of its next stage without searching the whole batch."""
        return method.run(self, pairs), None

    def staged(self, method: StageMethod, pairs: Pairs) -> tuple[np.ndarray, list[str], np.ndarray]:
        """Run the stage ``method``: ``(codes, stage names, index of the stage that decided
        each entry or -1)``.  A cascade (the certified mode) reports each of its stages."""
        codes = method.run(self, pairs)
        which = np.negative((codes == 2).view(np.int8))  # 0 decided, -1 not
        return codes, [self.stage], which

    def staged_rows(
        self, method: StageMethod, pairs: Pairs
    ) -> tuple[np.ndarray, list[str], np.ndarray, np.ndarray | None]:
        """:meth:`staged` and the entries not decided by the first stage (a superset, or None
        when not known), so that the counts need not search the batch."""
        return (*self.staged(method, pairs), None)

    def __repr__(self) -> str:
        return f"{type(self).__name__}()"


def _stage_counts(
    step: Step, names: list[str], which: np.ndarray, rows: np.ndarray | None = None
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
        counts.add(Provenance(step, name), int(k_count))
    counts.undecided = int(np.count_nonzero(later < 0))
    return counts


def _by_stages(
    step: Step, method: StageMethod
) -> Callable[[NumberMode, Pairs], tuple[np.ndarray, StageCounts]]:
    """A question a mode answers by its stage ``method`` alone (down its cascade), counted as
    ``step``."""

    def answer(mode: NumberMode, pairs: Pairs) -> tuple[np.ndarray, StageCounts]:
        codes, names, which, later = mode.staged_rows(method, pairs)
        return codes, _stage_counts(step, names, which, later)

    return answer


QUESTIONS: dict[str, Callable[[NumberMode, Pairs], tuple[np.ndarray, StageCounts]]] = {
    "contact": lambda mode, pairs: decide(mode, pairs, "contact"),
    "region": lambda mode, pairs: decide(mode, pairs, "region"),
    "kind": lambda mode, pairs: decide(mode, pairs, "kind"),
    "overlap": decide_overlap,
    "criterion": _by_stages(Step.CRITERION, StageMethod.CRITERION_CONTACT),
    "smallness": _by_stages(Step.SMALLNESS, StageMethod.SMALLNESS),
}
"""The questions of :meth:`NumberMode.decide`: how each is answered (the codes and their counts)."""
