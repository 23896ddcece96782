"""Number modes: one question, many number types.

A number mode chooses the arithmetic of every stage of the decision
(:mod:`~quadric_contact.modes.decision.pipeline`), never the question:

* ``certified``: ``filter``, then ``ball``, then ``exact``, and the exact scalar
  predicates for what the stages leave; always answers, never wrong;
* ``filter``: binary64 with a rigorous error bound; answers where sure, else UNCERTAIN;
* ``float``: plain binary64 (with the exact structural zeros); always answers, may be wrong;
* ``ball``: python-flint ``arb`` balls at ``prec`` bits; answers where sure, else UNCERTAIN;
* ``mpmath``: mpmath ``mpf`` at ``dps`` digits (with the exact structural zeros); always
  answers, may be wrong;
* ``exact``: integers and exact rationals; always answers, never wrong.

A mode is an object; pass a name or an instance (to set options or to read
its :attr:`~NumberMode.counts` afterwards)::

    >>> import numpy as np
    >>> from quadric_contact import transversal_contact
    >>> from quadric_contact.modes import CertifiedMode
    >>> mode = CertifiedMode()
    >>> E = np.diag([2.0, 2.0, 3.0, -1.0])                          # Example 11
    >>> Q = np.array([[1.0, 0, 0, 0], [0, 1, 0, 0], [0, 0, 0, 4], [0, 0, 4, 0]])
    >>> transversal_contact(np.stack([E, E]), Q, mode=mode)
    array([1, 1], dtype=int8)
    >>> mode.last.decided["criterion (filter)"]
    2
"""

from __future__ import annotations

from quadric_contact.modes.codes import (
    ContactCode,
    ContactKindCode,
    CriterionCode,
    OverlapCode,
    Provenance,
    RegionCode,
    Sign,
    SmallnessCode,
    StageCounts,
    Step,
)
from quadric_contact.modes.numbers.binary64 import FilterMode, FloatMode
from quadric_contact.modes.numbers.certified import CertifiedMode
from quadric_contact.modes.numbers.number_mode import NumberMode
from quadric_contact.modes.numbers.objects import BallMode, ExactMode, MpmathMode
from quadric_contact.modes.numbers.registry import MODES, get_mode
from quadric_contact.modes.stacks.pairs import MatrixStack, Pairs

__all__ = [
    "MODES",
    "BallMode",
    "CertifiedMode",
    "ContactCode",
    "ContactKindCode",
    "CriterionCode",
    "ExactMode",
    "FilterMode",
    "FloatMode",
    "MatrixStack",
    "MpmathMode",
    "NumberMode",
    "OverlapCode",
    "Pairs",
    "Provenance",
    "RegionCode",
    "Sign",
    "SmallnessCode",
    "StageCounts",
    "Step",
    "get_mode",
]
