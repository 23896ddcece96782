"""The ``distance`` effect of a scene: the least signed distance of a moving ellipsoid from a
piece's solid over the time span, and when it is reached, certified.

For each (moving ellipsoid, piece) pair that asks for it (the scene, the ellipsoid and the
piece all do), :func:`piece_distances` runs
:func:`~quadric_contact.scenes.path_distance.path_distance` on the scene's time span: an
enclosure ``[lo, hi]`` of ``min_t d(t)``, with ``d`` the signed distance of
:func:`quadric_contact.distance` (negative: minus the penetration depth), and time intervals
whose union holds every time at which the minimum is reached.  The enclosure is at most the
scene's ``distance_tolerance`` wide unless the budget of ``distance_evaluations`` distances
runs out first; then the report gives the enclosure reached and says so.

The solid is the piece's inside (``inside = "R-"`` or ``"R+"`` of its quadric as given).  A
piece cut by planes of its object's tree is its solid intersected with the half-spaces on its
path (``plus``: ``R+`` of the plane as given, ``minus``: ``R-``); a piece in several leaves is
the union of its cut parts.  Where the solid is convex, ``d`` is the certified distance of
:func:`quadric_contact.modes.distance.pieces.cut_piece_distance` (the least of the parts'),
in either reading of the scene.  Where the method does not answer, the pair is reported as
*not available*, with the reason, and nothing else is put in its place:

* the piece is cut by planes and its solid is not convex (hyperboloids, the hyperbolic
  paraboloid and cylinder): the distance to a non-convex solid as cut is not computed (the
  whole quadric's is only a lower bound of it);
* the piece's inside is the complement of its quadric's solid (an ``R+`` ellipsoid, say),
  except for a plane, whose other side is a half-space too;
* a distance along the path is not decided (a crossing of a solid that is not convex where
  the bracket of its depth does not close; an ellipsoid crossing or touching a cut piece,
  whose penetration depth is not computed; a symmetric configuration of critical points):
  the reason names the time.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from quadric_contact.exact.errors import QuadricContactError
from quadric_contact.model.classification import QuadricKind
from quadric_contact.model.quadric import Quadric
from quadric_contact.modes.distance.pieces import HalfSpace, half_space, union_distance
from quadric_contact.scenes.composite import Composite, Piece, Split
from quadric_contact.scenes.ledger import Ledger
from quadric_contact.scenes.path_distance import path_distance
from quadric_contact.scenes.scene_model import (
    DISTANCE_EVALUATIONS,
    DISTANCE_TOLERANCE,
    MovingEllipsoid,
    Scene,
)
from quadric_contact.theory.distance import CONVEX_SOLIDS
from quadric_contact.theory.overlap import SOLID_KINDS
from quadric_contact.theory.results import Region

__all__ = ["PieceDistance", "piece_distances"]

TIMES_SHOWN = 4
"""Time intervals of closest approach listed per pair in the text report (``--json`` lists all)."""


@dataclass(frozen=True)
class PieceDistance:
    """The least signed distance of one moving ellipsoid from one piece over the time span.

    Attributes
    ----------
    ellipsoid, object, piece : str
    minimum : (Fraction, Fraction) or None
        ``lo <= min_t d(t) <= hi``; None when not available.
    times : tuple of (Fraction, Fraction)
        Disjoint time intervals, in order, whose union holds every time at which the minimum
        is reached.
    evaluations : int
        Distances evaluated.
    tolerance : Fraction
        The width asked for.
    budget : int
        The most evaluations allowed.
    reason : str
        Why the distance is not available ("" when it is).
    """

    ellipsoid: str
    object: str
    piece: str
    minimum: tuple[Fraction, Fraction] | None
    times: tuple[tuple[Fraction, Fraction], ...] = ()
    evaluations: int = 0
    tolerance: Fraction = DISTANCE_TOLERANCE
    budget: int = DISTANCE_EVALUATIONS
    reason: str = ""

    @property
    def available(self) -> bool:
        """The enclosure was computed."""
        return self.minimum is not None

    @property
    def tolerance_reached(self) -> bool | None:
        """The enclosure is at most the tolerance wide (None when not available)."""
        if self.minimum is None:
            return None
        return self.minimum[1] - self.minimum[0] <= self.tolerance

    def describe(self, places: int = 10) -> str:
        """One line of the text report (numbers rounded outwards to ``places`` decimals).

        Examples
        --------
        >>> d = PieceDistance("ball", "floor", "ground", (Fraction(-1, 4), Fraction(-1, 4)),
        ...                   ((Fraction(2), Fraction(2)),), 12, Fraction(1, 1000), 200)
        >>> for part in d.describe().split("; "):
        ...     print(part)
        least signed distance from ground: -0.25 (a penetration), at t = 2
        12 distances evaluated, within the tolerance 1/1000
        >>> PieceDistance("ball", "roof", "saddle", None, reason="the piece is cut").describe()
        'least signed distance from saddle: not available: the piece is cut'
        """
        head = f"least signed distance from {self.piece}"
        if self.minimum is None:
            return f"{head}: not available: {self.reason}"
        lo, hi = self.minimum
        value = _decimal(lo, places, up=False) if lo == hi else _enclosure(lo, hi, places)
        if hi < 0:
            value += " (a penetration)"
        elif lo > 0:
            value += " (apart)"
        shown = [_time_text(a, b, places) for a, b in self.times[:TIMES_SHOWN]]
        when = " ∪ ".join(shown)
        if len(self.times) > TIMES_SHOWN:
            when += f" ∪ ... ({len(self.times)} intervals in all; --json lists every one)"
        instant = len(self.times) == 1 and self.times[0][0] == self.times[0][1]
        when = f"at t = {when}" if instant else f"at t in {when}"
        work = f"{self.evaluations} distances evaluated"
        if self.tolerance_reached:
            work += f", within the tolerance {self.tolerance}"
        else:
            width = _decimal(hi - lo, places, up=True)
            work += f": the budget of {self.budget} ran out before the tolerance {self.tolerance}"
            work += f" (width {width})"
        return f"{head}: {value}, {when}; {work}"

    def to_dict(self, places: int = 10) -> dict[str, Any]:
        """JSON-ready: exact rationals as text, and decimals rounded outwards."""
        minimum = None
        if self.minimum is not None:
            lo, hi = self.minimum
            minimum = {
                "lo": str(lo),
                "hi": str(hi),
                "decimal": [_decimal(lo, places, up=False), _decimal(hi, places, up=True)],
            }
        return {
            "ellipsoid": self.ellipsoid,
            "object": self.object,
            "piece": self.piece,
            "available": self.available,
            "reason": self.reason or None,
            "minimum": minimum,
            "times": [[str(a), str(b)] for a, b in self.times],
            "tolerance": str(self.tolerance),
            "tolerance_reached": self.tolerance_reached,
            "evaluations": self.evaluations,
            "budget": self.budget,
        }


def _decimal(x: Fraction, places: int, *, up: bool) -> str:
    """``x`` rounded up (or down) to ``places`` decimals, trailing zeros dropped.

    >>> third = Fraction(-1, 3)
    >>> _decimal(third, 4, up=False), _decimal(third, 4, up=True), _decimal(Fraction(5, 2), 3, up=True)
    ('-0.3334', '-0.3333', '2.5')
    """
    scale = 10**places
    k = math.ceil(x * scale) if up else math.floor(x * scale)
    sign = "-" if k < 0 else ""
    whole, frac = divmod(abs(k), scale)
    tail = f"{frac:0{places}d}".rstrip("0") if places else ""
    return f"{sign}{whole}" + (f".{tail}" if tail else "")


def _enclosure(lo: Fraction, hi: Fraction, places: int) -> str:
    return f"[{_decimal(lo, places, up=False)}, {_decimal(hi, places, up=True)}]"


def _time_text(a: Fraction, b: Fraction, places: int) -> str:
    return _decimal(a, places, up=False) if a == b else _enclosure(a, b, places)


def _merged(times: Sequence[tuple[Fraction, Fraction]]) -> tuple[tuple[Fraction, Fraction], ...]:
    """Sorted, with touching or overlapping intervals joined (the same union)."""
    out: list[tuple[Fraction, Fraction]] = []
    for a, b in sorted(times):
        if out and a <= out[-1][1]:
            out[-1] = (out[-1][0], max(out[-1][1], b))
        else:
            out.append((a, b))
    return tuple(out)


def _cutting_planes(obj: Composite) -> dict[str, list[str]]:
    """Piece name -> the planes on its paths in the object's tree (none: the whole quadric)."""
    out: dict[str, list[str]] = {}

    def walk(node: Split | Piece | None, planes: tuple[str, ...]) -> None:
        if node is None:
            return
        if isinstance(node, Piece):
            names = out.setdefault(node.name, [])
            names += [n for n in planes if n not in names]
            return
        walk(node.plus, (*planes, node.name))
        walk(node.minus, (*planes, node.name))

    walk(obj.root, ())
    return out


def _cutting_paths(obj: Composite) -> dict[str, list[list[HalfSpace]]]:
    """Piece name -> one list of half-spaces per leaf holding it (``plus`` is ``R+`` of the
    ``Split``'s plane as given, ``minus`` is ``R-``); an empty list for a piece that is not cut
    (the root, or a piece outside the tree)."""
    out: dict[str, list[list[HalfSpace]]] = {}

    def walk(node: Split | Piece | None, path: tuple[HalfSpace, ...]) -> None:
        if node is None:
            return
        if isinstance(node, Piece):
            out.setdefault(node.name, []).append(list(path))
            return
        walk(node.plus, (*path, half_space(node.plane, Region.R_PLUS, node.name)))
        walk(node.minus, (*path, half_space(node.plane, Region.R_MINUS, node.name)))

    walk(obj.root, ())
    for p in obj.extra_pieces:
        out.setdefault(p.name, []).append([])
    return out


def _solid(piece: Piece) -> tuple[Quadric | None, str]:
    """The quadric whose solid (that of :func:`quadric_contact.distance`) is the piece's
    inside, or None and why there is none."""
    q = piece.quadric
    kind = q.kind
    if kind not in SOLID_KINDS:
        return None, f"the piece is {kind.value}, which has no solid"
    solid_side = Region.R_MINUS if q.canonical_sign > 0 else Region.R_PLUS
    if piece.inside == solid_side:
        return q, ""
    if kind is QuadricKind.PLANE:
        return -q, ""  # the other half-space
    return None, (
        f"the piece's inside is {piece.inside.value} of its {kind.value}, the complement of its solid, "
        "whose distance is not computed"
    )


def piece_distances(
    scene: Scene,
    ell: MovingEllipsoid,
    obj: Composite,
    ledger: Ledger,
    wanted: Callable[[Piece], bool],
) -> list[PieceDistance]:
    """The ``distance`` effect for one moving ellipsoid against the pieces of one object that
    ask for it (``wanted``), on the scene's time span.

    Each evaluated distance is counted in ``ledger`` (``distance_evaluations``, for the
    target ``object/piece``).
    """
    cut = _cutting_planes(obj)
    paths = _cutting_paths(obj)
    return [
        _piece_distance(scene, ell, obj, piece, cut.get(piece.name, []), ledger, paths.get(piece.name, [[]]))
        for piece in obj.pieces
        if wanted(piece)
    ]


def _piece_distance(
    scene: Scene,
    ell: MovingEllipsoid,
    obj: Composite,
    piece: Piece,
    planes: Sequence[str],
    ledger: Ledger,
    parts: Sequence[Sequence[HalfSpace]] = ((),),
) -> PieceDistance:
    def result(**found: Any) -> PieceDistance:
        return PieceDistance(
            ell.name,
            obj.name,
            piece.name,
            tolerance=scene.distance_tolerance,
            budget=scene.distance_evaluations,
            **found,
        )

    solid, why = _solid(piece)
    reasons = []
    cut = bool(planes) and all(parts)  # a part with no plane is the whole solid, holding the others
    if cut and solid is not None and solid.kind not in CONVEX_SOLIDS:
        reasons.append(
            f"the piece is cut by the plane(s) {', '.join(planes)} of its object and its solid "
            f"({solid.kind.value}) is not convex: the distance to the quadric as cut is not computed "
            "(the whole quadric's is only a lower bound of it)"
        )
    if why:
        reasons.append(why)
    if reasons or solid is None:
        return result(minimum=None, reason="; ".join(reasons))
    target_solid: Any = solid
    if cut:
        convex = solid
        cut_parts = [list(p) for p in parts]

        def target_solid(placed: Quadric) -> tuple[Fraction, Fraction]:
            return union_distance(placed, convex, cut_parts).bounds

    target = f"{obj.name}/{piece.name}"
    try:
        r = path_distance(
            ell.quadric,
            target_solid,
            ell.trajectory,
            scene.span[0],
            scene.span[1],
            tolerance=scene.distance_tolerance,
            max_evaluations=scene.distance_evaluations,
        )
    except QuadricContactError as exc:
        done = int(exc.details.get("evaluations", 0))
        ledger.add("distance_evaluations", done, target=target)
        return result(minimum=None, evaluations=done, reason=str(exc).splitlines()[0])
    ledger.add("distance_evaluations", len(r.samples), target=target)
    return result(minimum=r.minimum, times=_merged(r.times), evaluations=len(r.samples))
