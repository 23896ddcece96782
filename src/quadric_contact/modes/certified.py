"""The certified mode: a cascade of stages, each answering only where it is sure.

``filter`` (binary64 with a rigorous error bound) decides almost everything; what
it leaves ``UNCERTAIN`` goes to ``ball`` (python-flint ``arb``), and what that
leaves to ``exact`` (integers), which always decides.  Every stage is certified,
so the answer equals the exact evaluation of the same criterion on the same
matrices.  This is CGAL's filtered predicate (``Filtered_predicate.h``), with
the escalations counted so that the caller can read who decided what
(:attr:`CertifiedMode.last`, :attr:`CertifiedMode.counts`).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np

from .base import MatrixStack, NumberMode, Pairs, StageCounts
from .decisions import UNCERTAIN_ROW, rows_from_masks
from .float64 import FilterMode
from .objects import BallMode, ExactMode

__all__ = ["CertifiedMode"]

_UNC = 2


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
        Entries decided by each stage in the last call and in all calls so far.
    """

    name = "certified"
    certified = True

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

    def _cascade(self, pairs: Pairs, run: Callable[[NumberMode, Pairs], np.ndarray]) -> np.ndarray:
        counts = StageCounts()
        first = self.stages[0]
        codes = run(first, pairs)
        todo = np.flatnonzero(codes == _UNC)
        counts.add(_stage(first), pairs.n - todo.size)
        for stage in self.stages[1:]:
            if todo.size == 0:
                counts.add(_stage(stage), 0)
                continue
            sub = run(stage, pairs.take(todo))
            codes[todo] = sub
            done = sub != _UNC
            counts.add(_stage(stage), int(np.count_nonzero(done)))
            todo = todo[~done]
        counts.undecided = int(todo.size)
        self._record(counts)
        return codes

    def contact(self, pairs: Pairs) -> np.ndarray:
        return self._cascade(pairs, lambda stage, p: stage.contact(p))

    def region(self, pairs: Pairs) -> np.ndarray:
        # Each stage classifies the quadrics of the pairs it receives, with its own numbers.
        return self._cascade(pairs, lambda stage, p: stage.region(p))

    def smallness(self, pairs: Pairs) -> np.ndarray:
        return self._cascade(pairs, lambda stage, p: stage.smallness(p))

    def classify(self, Q: MatrixStack, rows: np.ndarray | None = None) -> np.ndarray:
        index = np.arange(len(Q)) if rows is None else np.asarray(rows)
        out = self.stages[0].classify(Q, index)
        for stage in self.stages[1:]:
            todo = np.flatnonzero(rows_from_masks(out) == UNCERTAIN_ROW)
            if todo.size == 0:
                break
            out[todo] = stage.classify(Q, index[todo])
        return out

    def __repr__(self) -> str:
        return f"CertifiedMode(stages={self.stages!r})"


def _stage(mode: NumberMode) -> str:
    return str(getattr(mode, "stage", mode.name))
