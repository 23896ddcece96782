"""Symmetric placements: spheres and spheroids on the axes of circular quadrics.

The configurations users meet most (a ball in a pipe, a probe on the axis of a cone, a
spheroid under a dish) are the symmetric ones, and symmetry gives the pencil a multiple root
that has nothing to do with tangency: a sphere on the axis of the cylinder ``x^2 + y^2 = r^2``
gives ``P(lambda)`` the double root of the two equal directions across the axis.  Binary64
rounding turns such a root into a pair of non-real roots, and a decision that trusts the
rounded discriminants answers "transversal contact" for a ball far inside the pipe.

:func:`axis_family` lays out such pairs, exactly representable in binary64 (every entry a
dyadic rational), at distances from ``10^-1`` to ``10`` on both sides of the surface.  Where
the distance is only bounded (cones, paraboloids, hyperboloids of two sheets) a placement can
happen to touch; :func:`stable` picks out the placements whose answer survives a small
perturbation, and on those every number mode must give the exact answer.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

import numpy as np

__all__ = ["AxisPair", "axis_family", "stable"]

DISTANCES = (0.125, 0.5, 1.0, 4.0, 10.0)
"""Clearances (or overlaps) between the body and the surface, dyadic, ``10^-1 .. 10``."""


@dataclass(frozen=True)
class AxisPair:
    """One placement: ``E`` (the body) and ``Q`` as float64 ``(4, 4)`` matrices, exact in binary64."""

    name: str
    E: np.ndarray
    Q: np.ndarray


def _diag(a: float, b: float, c: float, d: float) -> np.ndarray:
    return np.diag([a, b, c, d]).astype(np.float64)


def _body(radius: float, polar: float, height: float) -> np.ndarray:
    """The spheroid ``(x^2 + y^2) / radius^2 + (z - height)^2 / polar^2 = 1`` scaled to
    ``polar^2 (x^2 + y^2) + radius^2 (z - h)^2 - radius^2 polar^2``: integer-like entries."""
    a, c = polar * polar, radius * radius
    m = _diag(a, a, c, c * height * height - a * c)
    m[2, 3] = m[3, 2] = -c * height
    return m


def _quadrics() -> Iterator[tuple[str, np.ndarray, str]]:
    """Circular quadrics about the z axis, and on which side of them the axis lies."""
    yield "cylinder r=4", _diag(1, 1, 0, -16), "inside"
    yield "cone x^2+y^2=z^2", _diag(1, 1, -1, 0), "inside"
    yield "hyperboloid x^2+y^2-z^2=16", _diag(1, 1, -1, -16), "inside"
    yield "hyperboloid of two sheets z^2-x^2-y^2=16", _diag(-1, -1, 1, -16), "inside"
    paraboloid = _diag(1, 1, 0, 0)
    paraboloid[2, 3] = paraboloid[3, 2] = -2.0  # x^2 + y^2 = 4 z
    yield "paraboloid x^2+y^2=4z", paraboloid, "inside"


def _clearance_placements(kind: str) -> Iterator[tuple[float, float]]:
    """``(height, room)`` on the axis and the distance from there to the surface."""
    if kind.startswith("cylinder"):
        for h in (0.0, 3.0):
            yield h, 4.0
    elif kind.startswith("cone"):
        for h in (16.0, 40.0):
            yield h, h / 2**0.5
    elif kind.startswith("hyperboloid x"):
        for h in (0.0,):
            yield h, 4.0
    elif kind.startswith("hyperboloid of two"):
        for h in (24.0, 40.0):
            yield h, float(h - 4.0)  # bounded below by the vertex gap along the axis
    else:
        for h in (16.0, 40.0):
            yield h, 8.0  # the paraboloid's room at these heights exceeds 8 (a lower bound)


def axis_family() -> list[AxisPair]:
    """Spheres and spheroids (polar axis half and twice the equator) centred on the axis of
    each circular quadric, of sizes that leave the distances of :data:`DISTANCES` to the
    surface or overlap it by them (the exact answer is computed by whoever uses the family;
    where the room is only a bound the placement still has a stable answer)."""
    out: list[AxisPair] = []
    for qname, Q, _ in _quadrics():
        for height, room in _clearance_placements(qname):
            for d in DISTANCES:
                for shape, polar_ratio in (("sphere", 1.0), ("prolate", 2.0), ("oblate", 0.5)):
                    for sign, label in ((-1.0, "clear"), (1.0, "overlap")):
                        radius = room + sign * d
                        if radius <= 0:
                            continue
                        polar = radius * polar_ratio
                        E = _body(radius, polar, height)
                        out.append(
                            AxisPair(f"{shape} r={radius} at z={height} vs {qname} ({label} {d})", E, Q)
                        )
    return out


def stable(pairs: list[AxisPair], answer: Any, scale: float = 2.0**-30) -> np.ndarray:
    """Which placements keep their answer when the body grows or shrinks by the relative
    amount ``scale`` (its constant term moved by that fraction of its own size): ``answer(E, Q)``
    is an exact predicate on stacks.  The room of a cone, a paraboloid or a hyperboloid of two
    sheets above is only a bound, so an overlapping placement may happen to touch the surface;
    the answers that matter are the ones that survive a perturbation."""
    E = np.stack([p.E for p in pairs])
    Q = np.stack([p.Q for p in pairs])
    base = answer(E, Q)
    out = np.ones(len(pairs), dtype=bool)
    for f in (1.0 - scale, 1.0 + scale):
        moved = E.copy()
        moved[:, 3, 3] = E[:, 3, 3] * f
        out &= answer(moved, Q) == base
    return out
