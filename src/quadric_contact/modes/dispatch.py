"""One dispatch for every public predicate: a stack or a single pair, a complete mode or another.

A public predicate (:mod:`quadric_contact.modes.predicates`) is a :class:`Question`, the pieces
that differ from one question to the next, and a call of :func:`ask`, which does the rest the
same way for all of them:

* a stack (:func:`~quadric_contact.modes.stacks.batch.is_stack`, decided by the type of the
  input) goes to :func:`~quadric_contact.modes.stacks.batch.run_stack`: an int8 array of codes;
* a single pair in a complete mode (``certified``, ``exact``) is decided by the question's
  exact scalar function, and counted as one ``"exact pair"`` in the caller's mode instance;
* a single pair in any other mode (and the raw criterion, in every mode) is a stack of one: the
  mode answers it with the counts of the stages that settled it
  (:meth:`~quadric_contact.modes.NumberMode.decide`), and the question builds its result from
  the code and the :class:`~quadric_contact.modes.codes.Provenance` of the deciding stage
  (:class:`Single`).  Nothing is read back from the mode instance, which other threads may be
  using at the same time.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from quadric_contact.modes.codes import Provenance, StageCounts, Step
from quadric_contact.modes.numbers.number_mode import NumberMode
from quadric_contact.modes.numbers.registry import get_mode
from quadric_contact.modes.stacks.batch import MODE_QUESTIONS, as_stack, is_stack, make_pairs, run_stack

__all__ = ["Question", "Single", "ask", "replace"]


@dataclass(frozen=True)
class Single:
    """One pair decided by a mode's stages (a stack of one): what a :class:`Question` builds its
    result from.

    Attributes
    ----------
    code : int
        The code of the pair (the question's code type).
    provenance : Provenance or None
        The stage that decided it (None: none did, the code is ``UNCERTAIN``).
    mode : str
        The mode's name.
    E, Q
        The pair the stages were asked about (as :attr:`Question.prepare` gave it).
    held
        What :attr:`Question.prepare` kept for the result (None if nothing).
    options : dict
        The predicate's keyword options.
    """

    code: int
    provenance: Provenance | None
    mode: str
    E: Any
    Q: Any
    held: Any = None
    options: dict[str, Any] = field(default_factory=dict)

    @property
    def stage(self) -> str:
        """The name of the deciding stage (``"criterion (filter)"``, ...), or ``"undecided"``."""
        return "undecided" if self.provenance is None else str(self.provenance)

    @property
    def cannot_tell(self) -> str:
        """The reason of an ``UNCERTAIN`` answer."""
        return f"{self.mode} mode cannot tell ({self.stage})"

    @property
    def decided_in(self) -> str:
        """How a decided answer was decided, for its reason."""
        return f"decided in {self.mode} mode by {self.stage}"


def _as_given(E: Any, Q: Any) -> tuple[Any, Any, Any]:
    return E, Q, None


def _codes(codes: Any, **options: Any) -> Any:
    return codes


def _valid(**options: Any) -> None:
    return None


@dataclass(frozen=True)
class Question:
    """The pieces of one public predicate that differ from the others' (data for :func:`ask`).

    Attributes
    ----------
    name : str
        The question of :func:`~quadric_contact.modes.stacks.batch.run_stack` (and, through
        :data:`~quadric_contact.modes.stacks.batch.MODE_QUESTIONS`, of the mode for a single
        pair).
    build : callable
        ``build(single)``: the result object of a single pair decided by a mode's stages
        (:class:`Single`).
    exact : callable or None
        ``exact(E, Q, **options)``: the exact scalar path, which decides a single pair in the
        complete modes; None: the mode's stages decide a single pair in every mode.
    exact_only : tuple of str
        The options only the exact scalar path takes (refused, when given, for stacks and in
        the other modes).
    prepare : callable
        ``prepare(E, Q)``, before the stages see a single pair: the pair they are asked about
        and what the result needs besides (checks that raise go here).
    relabel : bool
        The exact path's result records the name of the mode (``result.mode``).
    validate : callable
        ``validate(**options)``, first of all, on every path.
    stack : callable
        ``stack(codes, **options)``: a stack's answer from its codes.
    """

    name: str
    build: Callable[[Single], Any]
    exact: Callable[..., Any] | None = None
    exact_only: tuple[str, ...] = ()
    prepare: Callable[[Any, Any], tuple[Any, Any, Any]] = _as_given
    relabel: bool = True
    validate: Callable[..., Any] = _valid
    stack: Callable[..., Any] = _codes


_COMPLETE: dict[str, NumberMode] = {}


def _mode(mode: str | NumberMode) -> NumberMode:
    """The mode of a call.  A complete mode named by a string (``certified``, ``exact``) decides
    a single pair by the exact scalar path, where its instance only counts: one instance per
    name serves every such call (nobody holds it to read the counts)."""
    if isinstance(mode, str):
        m = _COMPLETE.get(mode)
        if m is not None:
            return m
        m = get_mode(mode)
        if m.complete:
            _COMPLETE[mode] = m
        return m
    return get_mode(mode)


def _no_options(kind: str, options: dict[str, Any]) -> None:
    given = [k for k, v in options.items() if v not in (None, "auto")]
    if given:
        raise ValueError(
            f"{', '.join(given)} apply to a single pair in the certified or exact mode only ({kind}); "
            "for pairs known to be small use corollary_10"
        )


def _record_exact(m: NumberMode) -> None:
    """Count the exact scalar decision in ``m`` when the caller holds it (an instance passed as
    ``mode``): the shared instance of a mode named by a string is read by nobody."""
    if _COMPLETE.get(m.name) is not m:
        counts = StageCounts()
        counts.add(Provenance(Step.EXACT_PAIR), 1)
        m._record(counts)


def replace(result: Any, **changes: Any) -> Any:
    """A copy of the frozen result ``result`` with ``changes`` (``result`` itself when they
    change nothing).

    The copy takes the instance's attributes as they are (no ``__init__``, and without
    ``copy.copy``'s pickling protocol, a third of the time on the exact scalar path)."""
    if all(getattr(result, name) == value for name, value in changes.items()):
        return result
    new = object.__new__(type(result))
    new.__dict__.update(result.__dict__)
    for name, value in changes.items():
        object.__setattr__(new, name, value)
    return new


def ask(
    question: Question, E: Any, Q: Any, mode: str | NumberMode, client: Any, compute: bool, **options: Any
) -> Any:
    """Answer ``question`` about ``E`` and ``Q`` (a stack or a single pair) in ``mode``, with the
    predicate's keyword ``options``: see the module's summary."""
    question.validate(**options)
    exact_only = {name: options[name] for name in question.exact_only}
    if is_stack(E) or is_stack(Q):
        _no_options("stacks", exact_only)
        return question.stack(run_stack(question.name, E, Q, mode, client, compute), **options)
    m = _mode(mode)
    if m.complete and question.exact is not None:
        result = question.exact(E, Q, **options)
        _record_exact(m)
        return replace(result, mode=m.name) if question.relabel else result
    _no_options(f"mode {m.name!r}", exact_only)
    E, Q, held = question.prepare(E, Q)
    pairs, _ = make_pairs(as_stack(E, "E"), as_stack(Q, "Q"))
    decided = m.decide(MODE_QUESTIONS[question.name], pairs)
    return question.build(
        Single(int(decided.codes[0]), decided.counts.deciding(), m.name, E, Q, held, options)
    )
