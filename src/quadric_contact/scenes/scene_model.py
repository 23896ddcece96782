"""The scene model: objects, moving ellipsoids, a time span and the effects wanted.

A :class:`Scene` is read from TOML by :mod:`quadric_contact.scenes.scene_toml` (or built
directly) and run by :mod:`quadric_contact.scenes.simulate`; its smallness checks
(Tables 1, 2) are recorded as :class:`SmallnessCheck` s.
"""

from __future__ import annotations

import warnings
from collections.abc import Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

from quadric_contact.exact.bounds import MAX_DISTANCE_EVALUATIONS, MIN_DISTANCE_TOLERANCE
from quadric_contact.exact.errors import ChoiceError, QuadricContactError, SceneError
from quadric_contact.exact.rational import to_fraction
from quadric_contact.model.classification import QuadricKind
from quadric_contact.model.quadric import Quadric
from quadric_contact.scenes.composite import Composite
from quadric_contact.scenes.ledger import Ledger
from quadric_contact.scenes.trajectory import Trajectory
from quadric_contact.theory.smallness import smallness

__all__ = [
    "DISTANCE_EVALUATIONS",
    "DISTANCE_TOLERANCE",
    "EFFECTS",
    "EXCLUDED_KINDS",
    "ON_NOT_SMALL",
    "THEOREM_2_EFFECTS",
    "MovingEllipsoid",
    "Scene",
    "SmallnessCheck",
]

READINGS: tuple[str, ...] = ("geometry", "paper")
"""How a piece is read: as its quadric cut by the planes on its path (the
default), or, as Algorithm 1 does, as its whole quadric."""

ON_NOT_SMALL: tuple[str, ...] = ("refuse", "warn")
"""What a scene does with a pair that is not small: refuse the scene, or keep it with a
warning (its contacts with all roots real are then undecided)."""


def check_on_not_small(on_not_small: Any) -> None:
    """Check an override of a scene's smallness policy: one of :data:`ON_NOT_SMALL`, or None
    (the scene's own).

    Raises
    ------
    ChoiceError
        Naming the valid values.

    Examples
    --------
    >>> check_on_not_small("warn")
    >>> try:
    ...     check_on_not_small("ignore")
    ... except ChoiceError as exc:
    ...     print(exc)
    on_not_small must be one of 'refuse', 'warn' or None, got 'ignore'
    """
    check_choice("on_not_small", on_not_small, (*ON_NOT_SMALL, None))


def check_choice(name: str, value: Any, choices: tuple[str | None, ...]) -> None:
    """Raise :class:`ChoiceError` unless ``value`` is one of ``choices`` (strings, and None
    where None is one), naming them; ``.details['choices']`` holds them.

    >>> try:
    ...     check_choice("reading", "whole", READINGS)
    ... except ChoiceError as exc:
    ...     print(exc)
    reading must be one of 'geometry', 'paper', got 'whole'
    """
    words = [c for c in choices if c is not None]
    if (value is None and None in choices) or (isinstance(value, str) and value in words):
        return
    listed = ", ".join(map(repr, words)) + (" or None" if None in choices else "")
    raise ChoiceError(f"{name} must be one of {listed}, got {value!r}", value, choices=choices)


EFFECTS: tuple[str, ...] = (
    "zone",
    "contact",
    "contact_kind",
    "relative_position",
    "first_contact",
    "smallness",
    "distance",
)
"""The effects a scene can ask for."""

DISTANCE_TOLERANCE = Fraction(1, 1000)
"""The default width of the enclosure of a least distance (``distance_tolerance``)."""

DISTANCE_EVALUATIONS = 400
"""The default budget of distance evaluations per (ellipsoid, piece) (``distance_evaluations``)."""

THEOREM_2_EFFECTS = frozenset({"contact", "contact_kind", "relative_position", "first_contact", "smallness"})
"""Effects that rely on the smallness hypothesis (through Theorem 2, Corollary 10, Theorem 13)."""

EXCLUDED_KINDS = frozenset(
    {
        QuadricKind.CONE,
        QuadricKind.INTERSECTING_PLANES,
        QuadricKind.COINCIDENT_PLANES,
        QuadricKind.IMAGINARY_ELLIPSOID,
        QuadricKind.IMAGINARY_CONE,
        QuadricKind.IMAGINARY_ELLIPTIC_CYLINDER,
        QuadricKind.IMAGINARY_INTERSECTING_PLANES,
        QuadricKind.IMAGINARY_PARALLEL_PLANES,
        QuadricKind.EMPTY,
        QuadricKind.ZERO,
    }
)
"""Piece types the scene loader refuses: the theory excludes them, or they have no real surface."""


@dataclass(frozen=True)
class MovingEllipsoid:
    """A moving ellipsoid: its initial placement (normalised so that ``det E < 0``) and trajectory."""

    name: str
    quadric: Quadric
    trajectory: Trajectory
    center: tuple[Fraction, Fraction, Fraction] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        c = self.quadric.center()
        assert c is not None, "an ellipsoid has a centre"
        object.__setattr__(self, "center", c)


@dataclass(frozen=True)
class SmallnessCheck:
    """Smallness of one moving ellipsoid with respect to one piece.

    ``small`` is the exact verdict of :func:`~quadric_contact.theory.smallness.smallness`
    (False also when the piece's type admits no small ellipsoid: ``note``
    says why); ``report`` is the smallness report.
    """

    ellipsoid: str
    object: str
    piece: str
    small: bool
    report: Any = None
    note: str = ""

    @property
    def table_4_applies(self) -> bool:
        """Small, and not only in the enclosing sense (erratum ``table-1-ellipsoid-enclosing``)."""
        return self.small and bool(getattr(self.report, "table_4_applies", True))

    def __str__(self) -> str:
        verdict = "small" if self.small else "NOT small"
        if self.small and not self.table_4_applies:
            verdict += " (only in the enclosing sense: Table 4 does not apply)"
        text = f"{self.ellipsoid} vs {self.object}/{self.piece}: {verdict}"
        if self.note:
            text += f" ({self.note})"
        return text


@dataclass
class Scene:
    """A scene: objects, moving ellipsoids, a time span and the effects wanted.

    Build one with :func:`load_scene` / :func:`builtin_scene` or directly.
    """

    name: str
    objects: tuple[Composite, ...]
    ellipsoids: tuple[MovingEllipsoid, ...]
    span: tuple[Fraction, Fraction]
    effects: tuple[str, ...] = ("zone", "contact", "first_contact")
    description: str = ""
    source: str = "<scene>"
    on_not_small: str = "refuse"
    places: int = 12
    smallness: dict[tuple[str, str, str], SmallnessCheck] = field(default_factory=dict)
    warnings: list[str] = field(default_factory=list)
    work: Ledger = field(default_factory=Ledger)
    """Work done on the scene itself (the smallness checks), whenever it was done."""
    ellipsoid_effects: dict[str, tuple[str, ...]] = field(default_factory=dict)
    """Ellipsoid name -> the effects it asks for (of the scene's; default: all of them)."""
    piece_effects: dict[tuple[str, str], tuple[str, ...]] = field(default_factory=dict)
    """(object, piece) -> the effects asked for on it (of the scene's; default: all of them).
    A pair (ellipsoid, piece) gets the effects that the scene, the ellipsoid and the
    piece all ask for."""
    mutual: tuple[str, ...] = ()
    """The moving ellipsoids whose contacts with each other are wanted (``mutual``
    in the scene file: ``true`` for all of them, or a list of names)."""
    reading: str = "geometry"
    """``"geometry"``: a piece is its quadric as cut by the planes on its path
    (:mod:`quadric_contact.scenes.cut_pieces`); ``"paper"``: Algorithm 1's reading,
    a piece reached by the descent counts as its whole quadric."""
    distance_tolerance: Fraction = DISTANCE_TOLERANCE
    """The ``distance`` effect stops once the enclosure of a least distance is this narrow
    (in the scene's units; at least :data:`~quadric_contact.exact.bounds.MIN_DISTANCE_TOLERANCE`)."""
    distance_evaluations: int = DISTANCE_EVALUATIONS
    """The ``distance`` effect evaluates at most this many distances per (ellipsoid, piece)
    (at most :data:`~quadric_contact.exact.bounds.MAX_DISTANCE_EVALUATIONS`)."""

    def __post_init__(self) -> None:
        t0, t1 = (to_fraction(v) for v in self.span)
        if not t0 < t1:
            raise SceneError(f"{self.source}: scene.time: expected [start, end] with start < end", self.span)
        self.span = (t0, t1)
        bad = [e for e in self.effects if e not in EFFECTS]
        if bad:
            raise SceneError(
                f"{self.source}: scene.effects: unknown effect(s) {bad}; expected some of {EFFECTS}"
            )
        if self.on_not_small not in ("refuse", "warn"):
            raise SceneError(
                f"{self.source}: scene.on_not_small: expected 'refuse' or 'warn'", self.on_not_small
            )
        for who, asked in [*self.ellipsoid_effects.items(), *self.piece_effects.items()]:
            bad = [e for e in asked if e not in EFFECTS]
            if bad:
                raise SceneError(
                    f"{self.source}: effects of {who}: unknown effect(s) {bad}; expected some of {EFFECTS}"
                )
        self.distance_tolerance, self.distance_evaluations = distance_options(
            self.distance_tolerance, self.distance_evaluations, self.source
        )

    def needs_smallness(self, effects: Sequence[str] | None = None) -> bool:
        """Some effect (the scene's, or ``effects``) relies on Theorem 2, hence on smallness."""
        return bool(THEOREM_2_EFFECTS & set(self.effects if effects is None else effects))

    def check_smallness(self, *, on_not_small: str | None = None) -> None:
        """Check every (moving ellipsoid, quadric piece) pair once (Tables 1, 2).

        Planes need no smallness (Theorem 14).  Raises :class:`SceneError`
        if a pair is not small and the policy is ``"refuse"``; with ``"warn"``
        the pair is kept, a warning is recorded, and its contacts with all
        roots real are undecided (Remark 9).  ``on_not_small`` overrides the
        scene's policy (None: the scene's own; anything but :data:`ON_NOT_SMALL`
        is a :class:`ChoiceError`).
        """
        check_on_not_small(on_not_small)
        policy = on_not_small or self.on_not_small
        # smallness depends on the ellipsoid's shape and size, not on where it is
        # (Definition 1, Tables 1-2): congruent translates share one check
        known: dict[tuple[Any, ...], SmallnessCheck] = {}
        pieces = [(o, p) for o in self.objects for p in o.pieces if not p.is_plane]
        todo = [
            e
            for e in self.ellipsoids
            if any((e.name, o.name, p.name) not in self.smallness for o, p in pieces)
        ]
        if not todo:
            return
        centred = {e.name: _centred(e) for e in self.ellipsoids}
        for (e_name, o_name, p_name), done in self.smallness.items():
            if e_name in centred:
                known.setdefault((centred[e_name], o_name, p_name), done)
        for ell in todo:
            for obj in self.objects:
                for piece in obj.pieces:
                    key = (ell.name, obj.name, piece.name)
                    if piece.is_plane or key in self.smallness:
                        continue
                    shape = (centred[ell.name], obj.name, piece.name)
                    if shape in known:
                        same = known[shape]
                        self.smallness[key] = SmallnessCheck(
                            ell.name, obj.name, piece.name, same.small, same.report, same.note
                        )
                        continue
                    self.work.add("smallness_checks", target=f"{obj.name}/{piece.name}")
                    try:
                        report = smallness(ell.quadric, piece.quadric)
                        check = SmallnessCheck(ell.name, obj.name, piece.name, bool(report.small), report)
                    except QuadricContactError as exc:
                        check = SmallnessCheck(ell.name, obj.name, piece.name, False, None, str(exc))
                    known[shape] = check
                    if not check.small:
                        why = str(check.report) if check.report is not None else check.note
                        text = (
                            f"{self.source}: ellipsoid {ell.name!r} is not small with respect to piece "
                            f"{piece.name!r} of object {obj.name!r}:\n  " + why.replace("\n", "\n  ")
                        )
                        if policy == "refuse":
                            raise SceneError(
                                text + "\n(set scene.on_not_small = 'warn' to keep the scene; its contacts "
                                "with all roots real are then undecided)",
                                check,
                                file=self.source,
                                key="scene.on_not_small",
                            )
                        warnings.warn(text, stacklevel=2)
                        self.warnings.append(text)
                    self.smallness[key] = check

    def small(self, ellipsoid: str, obj: str, piece: str) -> bool | None:
        """The checked smallness of this pair (None if it was not checked)."""
        check = self.smallness.get((ellipsoid, obj, piece))
        return None if check is None else check.small

    def table_4_applies(self, ellipsoid: str, obj: str, piece: str) -> bool:
        """Theorem 13 / Table 4 may be used for this pair: small, and not only in the
        enclosing sense of two ellipsoids (erratum ``table-1-ellipsoid-enclosing``)."""
        check = self.smallness.get((ellipsoid, obj, piece))
        return check is not None and check.table_4_applies

    def describe(self) -> str:
        """A few lines: the objects, the ellipsoids and their motions, the effects."""
        lines = [f"scene: {self.name}  ({self.source})"]
        if self.description:
            lines.append(f"  {self.description}")
        lines.append(f"  time span: [{self.span[0]}, {self.span[1]}]; effects: {', '.join(self.effects)}")
        for name, asked in self.ellipsoid_effects.items():
            lines.append(f"  effects asked for by ellipsoid {name}: {', '.join(asked) or 'none'}")
        for (obj_name, piece_name), asked in self.piece_effects.items():
            what = ", ".join(asked) or "none"
            lines.append(f"  effects asked for on piece {obj_name}/{piece_name}: {what}")
        for o in self.objects:
            lines.append(f"  object {o.describe()}")
        shown = self.ellipsoids if len(self.ellipsoids) <= 12 else self.ellipsoids[:5]
        for e in shown:
            lines.append(
                f"  ellipsoid {e.name}: {e.quadric.equation()} = 0; motion: {e.trajectory.describe()}"
            )
        if len(shown) < len(self.ellipsoids):
            lines.append(f"  ... and {len(self.ellipsoids) - len(shown)} more ellipsoids")
        return "\n".join(lines)


def distance_options(tolerance: Any, evaluations: Any, source: str = "<scene>") -> tuple[Fraction, int]:
    """Check the ``distance`` effect's options: the tolerance a positive number of at least
    :data:`~quadric_contact.exact.bounds.MIN_DISTANCE_TOLERANCE` (below it no budget
    reaches it), the budget an integer in ``[2, MAX_DISTANCE_EVALUATIONS]`` (the two ends
    of the span at least; more would not bound the work).

    Raises
    ------
    SceneError
        Naming ``scene.distance_tolerance`` or ``scene.distance_evaluations``.

    Examples
    --------
    >>> distance_options("1/100", 50)
    (Fraction(1, 100), 50)
    >>> try:
    ...     distance_options(0, 50)
    ... except SceneError as exc:
    ...     print(exc.details["key"], "|", exc.details["expected"])
    scene.distance_tolerance | a positive number of at least 1/1000000000000 (MIN_DISTANCE_TOLERANCE)
    """

    def refuse(key: str, expected: str, got: Any, cause: str = "") -> SceneError:
        shown = str(got) if isinstance(got, (Fraction, int)) and not isinstance(got, bool) else repr(got)
        tail = f" ({cause})" if cause else ""
        return SceneError(
            f"{source}: {key}: expected {expected}, got {shown}{tail}",
            got,
            file=source,
            key=key,
            expected=expected,
        )

    key = "scene.distance_tolerance"
    expected = f"a positive number of at least {MIN_DISTANCE_TOLERANCE} (MIN_DISTANCE_TOLERANCE)"
    if isinstance(tolerance, bool):
        raise refuse(key, expected, tolerance)
    try:
        tol = to_fraction(tolerance)
    except QuadricContactError as exc:
        raise refuse(key, expected, tolerance, str(exc)) from exc
    if tol <= 0:
        raise refuse(key, expected, tol)
    if tol < MIN_DISTANCE_TOLERANCE:
        raise refuse(
            key,
            expected,
            tol,
            "the distances are enclosed in binary64: no budget of evaluations would reach it",
        )
    key = "scene.distance_evaluations"
    expected = f"an integer in [2, {MAX_DISTANCE_EVALUATIONS}] (MAX_DISTANCE_EVALUATIONS)"
    if isinstance(evaluations, bool) or not isinstance(evaluations, int):
        raise refuse(key, expected, evaluations)
    if evaluations < 2:
        raise refuse(key, expected, evaluations, "the two ends of the time span are evaluated at least")
    if evaluations > MAX_DISTANCE_EVALUATIONS:
        raise refuse(key, expected, evaluations, "the budget bounds the work of each (ellipsoid, piece)")
    return tol, evaluations


def _centred(ell: MovingEllipsoid) -> tuple[Fraction, ...]:
    """The ellipsoid moved to the origin: with the piece, what smallness depends on."""
    return ell.quadric.translated(tuple(-v for v in ell.center)).upper
