"""Objects made of quadric pieces separated by planes (Section 5.2, Fig. 8).

Section 5.2 models an object by pieces of quadric surfaces, with planes
dividing space into zones: Zone 1 (``R+`` of the plane) holds a piece of
``S1``, Zone 2 (``R-``) a piece of ``S2``.  Algorithm 1 locates a (not
necessarily small) ellipsoid with Corollary 15; Algorithm 2 then checks
contact, with Corollary 10, only against the piece(s) of its zone, and
"``P1`` and ``P2`` ... shall be computed only if needed".

Here the single plane is generalised to a *tree of separating planes*
(a binary space partition): each inner node is a plane whose ``R+`` and
``R-`` sides hold a sub-tree, a piece, or nothing.  Algorithm 1 descends the
tree; an ellipsoid in transversal contact with a plane (Zone 0) continues
into both sides, exactly as Algorithm 2 checks both surfaces in Zone 0.
:func:`algorithm_1` and :func:`algorithm_2` read pieces as the paper does,
as whole quadrics: a contact in Zone 0 with the part of a surface that lies
beyond its plane counts as a contact.  Simulated scenes read them as cut by
default (:mod:`quadric_contact.scenes.cut_pieces`; ``reading = "paper"``
keeps the whole quadrics).

An object without planes is a plain combination of quadrics (Section 5.1):
every piece is checked.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from quadric_contact.exact.errors import NotAPlaneError, QuadricContactError
from quadric_contact.model.classification import QuadricKind
from quadric_contact.model.quadric import Quadric
from quadric_contact.scenes.ledger import Ledger
from quadric_contact.theory.contact import decide_transversal
from quadric_contact.theory.pencil import as_quadric, characteristic_polynomial
from quadric_contact.theory.plane import plane_side_exact as plane_side
from quadric_contact.theory.regions import decide_region
from quadric_contact.theory.results import (
    ContactResult,
    PlaneSideResult,
    Region,
    RegionResult,
)
from quadric_contact.theory.smallness import smallness

__all__ = [
    "Composite",
    "CompositeContact",
    "Piece",
    "Split",
    "ZoneReport",
    "algorithm_1",
    "algorithm_2",
]


@dataclass(frozen=True)
class Piece:
    """One quadric surface of an object.

    Attributes
    ----------
    name : str
    quadric : Quadric
    inside : Region
        Which region of ``quadric`` (as given) is the inside of the object
        (``R-`` by default: the inside of an ellipsoid in its usual sign).
    """

    name: str
    quadric: Quadric
    inside: Region = Region.R_MINUS

    def __post_init__(self) -> None:
        if self.inside not in (Region.R_MINUS, Region.R_PLUS):
            raise QuadricContactError(f"piece {self.name}: inside must be R- or R+", self.inside)

    @property
    def is_plane(self) -> bool:
        """The piece is a plane (decided by Corollary 15, no smallness needed)."""
        return self.quadric.kind is QuadricKind.PLANE

    def __str__(self) -> str:
        return f"{self.name} ({self.quadric.kind.value}: {self.quadric.equation()} = 0)"


@dataclass(frozen=True)
class Split:
    """A separating plane: ``plus`` holds what lies in its ``R+`` (Zone 1),
    ``minus`` what lies in its ``R-`` (Zone 2); either may be None (empty)."""

    plane: Quadric
    plus: Split | Piece | None = None
    minus: Split | Piece | None = None
    name: str = ""

    def __post_init__(self) -> None:
        if self.plane.kind is not QuadricKind.PLANE:
            raise NotAPlaneError(
                f"a separating plane must be a plane, got {self.plane.kind.value}",
                self.plane,
                kind=self.plane.kind,
            )
        if not self.name:
            object.__setattr__(self, "name", self.plane.equation())

    @property
    def label(self) -> str:
        """``"plane <name>"`` (the ledger's target for this plane)."""
        return f"plane {self.name}"


Node = Split | Piece


@dataclass(frozen=True)
class Composite:
    """An object: pieces and, optionally, a tree of separating planes.

    Build one with :meth:`single`, :meth:`separated` (Fig. 8) or directly
    with a tree of :class:`Split` nodes whose leaves are :class:`Piece` s.

    Examples
    --------
    The tree of Example 17:

    >>> tree = Composite.separated(
    ...     "tree", "z - 6",
    ...     plus=Piece("crown", Quadric.from_equation("x^2 + y^2 + 3*(z - 8.36291)^2 - 20")),
    ...     minus=Piece("trunk", Quadric.from_equation("x^2 + y^2 - 0.25*(z - 3)^2 - 1")))
    >>> [p.name for p in tree.pieces], [s.name for s in tree.splits()]
    (['crown', 'trunk'], ['z - 6'])
    """

    name: str
    root: Node | None = None
    extra_pieces: tuple[Piece, ...] = field(default=())

    def __post_init__(self) -> None:
        names = [p.name for p in self.pieces]
        if len(set(names)) != len(names):
            raise QuadricContactError(f"object {self.name}: piece names must be unique, got {names}", names)

    @classmethod
    def single(cls, name: str, quadric: Any, inside: Region = Region.R_MINUS) -> Composite:
        """An object that is one whole quadric."""
        return cls(name, Piece(name, as_quadric(quadric), inside))

    @classmethod
    def separated(cls, name: str, plane: Any, *, plus: Piece | None, minus: Piece | None) -> Composite:
        """Two pieces separated by one plane (Fig. 8): ``plus`` in Zone 1 (``R+``), ``minus`` in Zone 2."""
        return cls(name, Split(as_quadric(plane), plus, minus))

    @classmethod
    def union(cls, name: str, pieces: Sequence[Piece]) -> Composite:
        """Pieces without separating planes: each is checked everywhere (Section 5.1)."""
        pieces = tuple(pieces)
        if not pieces:
            raise QuadricContactError(f"object {name} has no pieces", pieces)
        if len(pieces) == 1:
            return cls(name, pieces[0])
        return cls(name, None, pieces)

    def _walk(self, node: Node | None) -> Iterator[Node]:
        if node is None:
            return
        yield node
        if isinstance(node, Split):
            yield from self._walk(node.plus)
            yield from self._walk(node.minus)

    @property
    def pieces(self) -> tuple[Piece, ...]:
        """All pieces, in tree order (each once)."""
        out: list[Piece] = []
        for n in self._walk(self.root):
            if isinstance(n, Piece) and n not in out:
                out.append(n)
        for p in self.extra_pieces:
            if p not in out:
                out.append(p)
        return tuple(out)

    def splits(self) -> list[Split]:
        """The separating planes, in tree order."""
        return [n for n in self._walk(self.root) if isinstance(n, Split)]

    @property
    def always_active(self) -> tuple[Piece, ...]:
        """Pieces outside the tree, checked at every position (a plain union)."""
        if self.root is None or isinstance(self.root, Piece):
            return self.pieces
        return self.extra_pieces

    def describe(self) -> str:
        """One line: the pieces, their types and the separating planes."""
        planes = self.splits()
        kinds = ", ".join(f"{p.name}: {p.quadric.kind.value}" for p in self.pieces)
        sep = f", {len(planes)} separating plane(s): " + ", ".join(s.name for s in planes) if planes else ""
        return f"{self.name}: {len(self.pieces)} piece(s) ({kinds}){sep}"


# -- Algorithms 1 and 2 on a static ellipsoid ------------------------------------------


@dataclass(frozen=True)
class ZoneReport:
    """Result of :func:`algorithm_1`.

    Attributes
    ----------
    sides : dict
        Plane name -> :class:`PlaneSideResult` for every plane visited.
    pieces : tuple of Piece
        The pieces of the zone(s) the ellipsoid is in: what Algorithm 2 must check.
    """

    sides: dict[str, PlaneSideResult]
    pieces: tuple[Piece, ...]

    @property
    def zones(self) -> dict[str, int]:
        """Plane name -> Algorithm 1's zone number (1: R+, 2: R-, 0: transversal contact)."""
        return {k: v.algorithm_1_zone for k, v in self.sides.items()}


def algorithm_1(E: Any, composite: Composite, *, ledger: Ledger | None = None) -> ZoneReport:
    """Algorithm 1, generalised to a tree of planes: in which zone is ``E``?

    At each plane, Corollary 15 on ``P0(lambda) = det(lambda E + P)``:
    transversal contact (Zone 0) iff ``c3^2 < 4 c4 c2`` (equivalently the
    paper's ``Delta_3 < 0``, since here ``Delta_3 = c2^2 (c3^2 - 4 c4 c2)``),
    else Zone 1 (``R+``) iff ``c3 > 0`` and Zone 2 (``R-``) iff ``c3 < 0``.
    No smallness is needed (Theorem 14).

    Parameters
    ----------
    E : Quadric, matrix-like or equation
        A real ellipsoid.
    composite : Composite
    ledger : Ledger, optional
        Counts the pencils and discriminants computed.

    Returns
    -------
    ZoneReport

    References
    ----------
    Algorithm 1, Theorem 14, Corollary 15.

    Examples
    --------
    Example 17: the bee is in Zone 2 (``c3 = -3/2 < 0``), where the trunk is.

    >>> from quadric_contact.scenes.scene_toml import builtin_scene
    >>> tree = builtin_scene("bee_and_tree").objects[0]
    >>> r = algorithm_1("(x-3)^2 + (y-3)^2 + 3*(z-5.5)^2 - 0.1", tree)
    >>> r.zones, [p.name for p in r.pieces]
    ({'z - 6': 2}, ['trunk'])
    """
    e = as_quadric(E, "E")
    sides: dict[str, PlaneSideResult] = {}
    found: list[Piece] = list(composite.extra_pieces)

    def visit(node: Node | None) -> None:
        if node is None:
            return
        if isinstance(node, Piece):
            if node not in found:
                found.append(node)
            return
        side = plane_side(e, node.plane)
        if ledger is not None:
            ledger.add("characteristic_polynomials", target=node.label)
            ledger.add("discriminants", target=node.label)
        sides[node.name] = side
        if side.zone in (Region.R_PLUS, Region.CONTACT):
            visit(node.plus)
        if side.zone in (Region.R_MINUS, Region.CONTACT):
            visit(node.minus)

    visit(composite.root)
    return ZoneReport(sides, tuple(found))


@dataclass(frozen=True)
class CompositeContact:
    """Result of :func:`algorithm_2`.

    Attributes
    ----------
    zone : ZoneReport
    contacts : dict
        Piece name -> :class:`ContactResult`, for the pieces of the zone only.
    regions : dict
        Piece name -> :class:`RegionResult` (when asked for).
    contact : bool or None
        Transversal contact with some piece; None if undecided for some piece
        and no contact was found with the others.
    """

    zone: ZoneReport
    contacts: dict[str, ContactResult]
    regions: dict[str, RegionResult]

    @property
    def contact(self) -> bool | None:
        """Transversal contact with some piece of the zone (None: undecided for some, none found)."""
        values = [c.transversal for c in self.contacts.values()]
        if any(v is True for v in values):
            return True
        if any(v is None for v in values):
            return None
        return False

    @property
    def touching(self) -> list[str]:
        """Names of the pieces in transversal contact."""
        return [k for k, c in self.contacts.items() if c.transversal]


def _corollary_10(P: Any) -> bool:
    _, s3, s4 = P.delta_signs()
    return s4 < 0 or (s4 == 0 and s3 < 0)


def algorithm_2(
    E: Any,
    composite: Composite,
    *,
    small: Any = None,
    region: bool = False,
    ledger: Ledger | None = None,
) -> CompositeContact:
    """Algorithm 2: contact of ``E`` with the object, computing only the pencils its zone needs.

    Runs :func:`algorithm_1`, then, for each piece of the zone only, forms
    ``P_i(lambda) = det(lambda E + S_i)`` and applies Corollary 10
    (``Delta_4 < 0``, or ``Delta_4 = 0`` and ``Delta_3 < 0``).  A piece that
    is a plane is decided by Corollary 15.

    Parameters
    ----------
    E : Quadric, matrix-like or equation
    composite : Composite
    small : bool, smallness report, or mapping piece name -> either, optional
        Smallness of ``E`` with respect to each piece (Corollary 10 needs it
        to conclude "no contact"); by default decided exactly
        (:func:`~quadric_contact.theory.smallness.smallness`).  A report also says
        whether Table 4 applies (not in the enclosing case of two ellipsoids).
    region : bool
        Also decide the relative position (Theorem 13, Table 4) per piece.
    ledger : Ledger, optional

    Returns
    -------
    CompositeContact

    References
    ----------
    Algorithm 2, Corollary 10, Theorem 13, Corollary 15.

    Examples
    --------
    Example 17: in Zone 2 only the trunk's pencil is formed, ``Delta_4 > 0``:
    no contact, and the bee is outside the trunk (``R+``).

    >>> from quadric_contact.scenes.scene_toml import builtin_scene
    >>> tree = builtin_scene("bee_and_tree").objects[0]
    >>> led = Ledger()
    >>> r = algorithm_2("(x-3)^2 + (y-3)^2 + 3*(z-5.5)^2 - 0.1", tree, small=True, region=True, ledger=led)
    >>> r.contact, r.regions["trunk"].region, sorted(r.contacts), led.cost("crown")
    (False, <Region.R_PLUS: 'R+'>, ['trunk'], 0)
    """
    e = as_quadric(E, "E")
    zone = algorithm_1(e, composite, ledger=ledger)
    contacts: dict[str, ContactResult] = {}
    regions: dict[str, RegionResult] = {}
    for piece in zone.pieces:
        if piece.is_plane:
            side = plane_side(e, piece.quadric)
            if ledger is not None:
                ledger.add("characteristic_polynomials", target=piece.name)
                ledger.add("discriminants", target=piece.name)
            contacts[piece.name] = ContactResult(
                side.zone is Region.CONTACT, "Corollary 15", side.reason, side.polynomial
            )
            if region:
                regions[piece.name] = RegionResult(
                    side.zone, "Theorem 14", side.reason, side.polynomial, contacts[piece.name]
                )
            continue
        given = small.get(piece.name) if isinstance(small, Mapping) else small
        if given is None:
            given = smallness(e, piece.quadric)
            if ledger is not None:
                ledger.add("smallness_checks", target=piece.name)
        is_small = given if isinstance(given, bool) else bool(given.small)
        table_4 = True if isinstance(given, bool) else bool(getattr(given, "table_4_applies", is_small))
        P = characteristic_polynomial(e, piece.quadric)
        if ledger is not None:
            ledger.add("characteristic_polynomials", target=piece.name)
            ledger.add("discriminants", target=piece.name)
        result = decide_transversal(P, small=is_small, method="theory")
        if result.transversal is not None:
            assert result.transversal == _corollary_10(P), "Corollary 10 and the root structure disagree"
        contacts[piece.name] = result
        if region:
            if result.transversal is False and not table_4:
                regions[piece.name] = RegionResult(
                    None,
                    None,
                    f"{result.reason}; but E is small only in the enclosing sense, where Theorem 13 / "
                    "Table 4 do not apply",
                    P,
                    result,
                )
            else:
                regions[piece.name] = decide_region(P, small=is_small, method="theory")
    return CompositeContact(zone, contacts, regions)
