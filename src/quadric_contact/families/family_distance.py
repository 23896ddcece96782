"""The signed distance and the first-contact scale of a parametric family at its points.

A :class:`~quadric_contact.families.family.Family` gives an exact pair ``(E(p), Q(p))`` at
every rational point ``p``; the two quantities of :mod:`quadric_contact.modes.distances` are
evaluated there, with the same definitions and modes.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any

from quadric_contact.families.family import Family
from quadric_contact.modes.distances import contact_scale, distance

__all__ = ["family_contact_scale", "family_distance"]


def family_distance(
    fam: Family, points: Iterable[Mapping[str, Any]], *, mode: str = "certified", digits: int = 15
) -> list[Any]:
    """``qc.distance`` of the family's pair at each point (a mapping parameter -> number).

    Examples
    --------
    >>> from quadric_contact.families.family import family
    >>> fam = family("x**2 + y**2 + z**2 - 1", "a - x", ["a"])   # the half-space x >= a
    >>> [str(r.distance) for r in family_distance(fam, [{"a": 3}, {"a": "1/2"}], mode="exact")]
    ['2', '-1/2']
    """
    out = []
    for p in points:
        E, Q = fam.at(**p)
        out.append(distance(E, Q, mode=mode, digits=digits))
    return out


def family_contact_scale(fam: Family, points: Iterable[Mapping[str, Any]], *, scale: str = "E") -> list[Any]:
    """``qc.contact_scale`` of the family's pair at each point, exactly.

    Examples
    --------
    >>> from quadric_contact.families.family import family
    >>> fam = family("x**2 + y**2 + z**2 - 1", "x - a", ["a"])
    >>> [str(r.scale) for r in family_contact_scale(fam, [{"a": 3}, {"a": 5}])]
    ['3', '5']
    """
    out = []
    for p in points:
        E, Q = fam.at(**p)
        out.append(contact_scale(E, Q, scale=scale))
    return out
