"""The certified mode: a cascade of number modes, each answering only where it is sure.

Every stage of the decision pipeline (:mod:`quadric_contact.modes.decision.pipeline`: the
criterion, smallness, the separation certificate) runs down the cascade: ``filter``
(binary64 with a rigorous error bound) decides almost everything; what it leaves
``UNCERTAIN`` goes to ``ball`` (python-flint ``arb``), and what that leaves to
``exact`` (integers).  What the stages leave (tangencies, multiple roots) is decided
by the exact scalar predicates.  Every stage is certified, so the answer is the exact
answer for the matrices as given.  This is CGAL's filtered predicate
(``Filtered_predicate.h``), with the escalations counted so that the caller can read
who decided what: each call of :meth:`~NumberMode.decide` returns its counts with its codes,
and a caller's own instance keeps them in :attr:`CertifiedMode.last` and
:attr:`CertifiedMode.counts`.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from quadric_contact.modes.codes import UNCERTAIN, StageMethod
from quadric_contact.modes.decision.answers import UNCERTAIN_ROW
from quadric_contact.modes.numbers.binary64 import FilterMode
from quadric_contact.modes.numbers.number_mode import NumberMode
from quadric_contact.modes.numbers.objects import BallMode, ExactMode
from quadric_contact.modes.stacks.pairs import MatrixStack, Pairs
from quadric_contact.modes.stacks.rows import set_rows

__all__ = ["CertifiedMode"]

_UNCERTAIN_BIT = 1 << UNCERTAIN_ROW


class CertifiedMode(NumberMode):
    """Never wrong: ``filter``, then ``ball``, then ``exact`` (the default mode).

    Parameters
    ----------
    stages : sequence of NumberMode, optional
        The cascade; every stage must be certified and the last one must always
        decide (``ExactMode``).  Default ``(FilterMode(), BallMode(ball_prec), ExactMode())``.
    ball_prec : int
        Precision in bits of the ball stage (default 128).
    backend, threads
        Passed to the filter stage.

    Attributes
    ----------
    last, counts : StageCounts
        Entries decided by each stage in the last call to finish and in all calls so far (a
        convenience of a caller's own instance; each call's counts come with its codes, from
        :meth:`~NumberMode.decide`).
    """

    name = "certified"
    stage = "certified"
    certified = True
    complete = True

    def __init__(
        self,
        stages: Sequence[NumberMode] | None = None,
        *,
        ball_prec: int = 128,
        backend: str | None = None,
        threads: int | None = None,
    ) -> None:
        super().__init__()
        if stages is None:
            stages = (FilterMode(backend, threads), BallMode(ball_prec), ExactMode())
        stages = tuple(stages)
        if not stages or not all(s.certified for s in stages):
            raise ValueError("every stage of a certified cascade must be certified")
        self.stages = stages

    def staged(self, method: StageMethod, pairs: Pairs) -> tuple[np.ndarray, list[str], np.ndarray]:
        """Run ``method`` down the cascade: each stage gets what the previous ones left
        ``UNCERTAIN``."""
        return self.staged_rows(method, pairs)[:3]

    def staged_rows(
        self, method: StageMethod, pairs: Pairs
    ) -> tuple[np.ndarray, list[str], np.ndarray, np.ndarray | None]:
        stages = self.stages
        codes, maybe = stages[0].with_candidates(method, pairs)
        # the entries the first stage left: among ``maybe`` when it says where they can be
        todo = set_rows(codes == UNCERTAIN) if maybe is None else maybe[codes[maybe] == UNCERTAIN]
        later = todo
        which = np.zeros(pairs.n, dtype=np.int8)  # 0 decided by the first stage
        which[todo] = -1  # not yet
        skip = _skipped_on_binary64(stages, method, pairs)
        for k, stage in enumerate(stages[1:], start=1):
            if todo.size == 0:
                break
            if stage in skip:
                continue
            sub = method.run(stage, pairs.take(todo))
            codes[todo] = sub
            done = sub != UNCERTAIN
            which[todo[done]] = k
            todo = todo[~done]
        return codes, [_stage(s) for s in stages], which, later

    def _first_decisive(self, method: StageMethod, pairs: Pairs) -> np.ndarray:
        return self.staged(method, pairs)[0]

    def criterion_contact(self, pairs: Pairs) -> np.ndarray:
        return self._first_decisive(StageMethod.CRITERION_CONTACT, pairs)

    def criterion_region(self, pairs: Pairs) -> np.ndarray:
        # Each stage classifies the quadrics of the pairs it receives, with its own numbers.
        return self._first_decisive(StageMethod.CRITERION_REGION, pairs)

    def separation(self, pairs: Pairs) -> np.ndarray:
        return self._first_decisive(StageMethod.SEPARATION, pairs)

    def smallness(self, pairs: Pairs) -> np.ndarray:
        return self._first_decisive(StageMethod.SMALLNESS, pairs)

    def classify(self, Q: MatrixStack, rows: np.ndarray | None = None) -> np.ndarray:
        index = np.arange(len(Q)) if rows is None else np.asarray(rows)
        out = self.stages[0].classify(Q, index)
        skip = _skipped_classify_on_binary64(self.stages, Q)
        for stage in self.stages[1:]:
            if stage in skip:
                continue
            # rows_from_masks(out) == UNCERTAIN_ROW without finding the rows: not exactly one
            # candidate row (a single bit), or the uncertain row itself
            todo = np.flatnonzero((out == 0) | ((out & (out - 1)) != 0) | (out == _UNCERTAIN_BIT))
            if todo.size == 0:
                break
            out[todo] = stage.classify(Q, index[todo])
        return out

    def __repr__(self) -> str:
        return f"CertifiedMode(stages={self.stages!r})"


_CRITERION = frozenset({StageMethod.CRITERION_CONTACT, StageMethod.CRITERION_REGION})


def _skipped_on_binary64(
    stages: tuple[NumberMode, ...], method: StageMethod, pairs: Pairs
) -> tuple[NumberMode, ...]:
    """The middle stages that would only cost time on this batch: binary64 input, a criterion
    method, the last stage exact (it decides whatever they would have, for less: see
    :attr:`BallMode.before_exact_on_binary64`)."""
    if method not in _CRITERION or pairs.E.rounded or pairs.Q.rounded:
        return ()
    if not isinstance(stages[-1], ExactMode):
        return ()
    return tuple(
        s for s in stages[1:-1] if isinstance(s, BallMode) and method.value not in s.before_exact_on_binary64
    )


def _skipped_classify_on_binary64(stages: tuple[NumberMode, ...], Q: MatrixStack) -> tuple[NumberMode, ...]:
    """The middle stages of a type reading that would only cost time: binary64 input and an
    exact last stage, whose integer invariants (kept with the stack, so the structural facts of
    the criterion reuse them) cost less than 128-bit balls: on 5e4 quadrics of every type the
    ball stage took 0.58 s before the exact one, the exact one alone 0.19 s."""
    if Q.rounded or not isinstance(stages[-1], ExactMode):
        return ()
    return tuple(
        s for s in stages[1:-1] if isinstance(s, BallMode) and "classify" not in s.before_exact_on_binary64
    )


def _stage(mode: NumberMode) -> str:
    return str(getattr(mode, "stage", mode.name))
