"""Hypothesis strategies for exact quadrics, built by construction.

Everything is built from small rationals and rational rotations (rational
quaternions), so every generated object is exact and shrinks to a small,
readable counterexample.  ``hypothesis`` is a dependency of the package, so
the module imports after a plain ``pip install``.

>>> from hypothesis import given
>>> from quadric_contact.testing.strategies import ellipsoids
>>> @given(ellipsoids())
... def test(e):
...     assert e.kind.value == "ellipsoid"
>>> test()
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

from hypothesis import strategies as st

from quadric_contact.model.classification import TABLE_1_KINDS, QuadricKind
from quadric_contact.model.motions import RigidMotion, rotation_from_quaternion
from quadric_contact.model.quadric import Quadric

__all__ = [
    "ellipsoids",
    "planes",
    "points",
    "quadrics",
    "rationals",
    "rigid_motions",
    "rotations",
    "tangent_pairs",
]


def rationals(
    *, min_value: Any = -10, max_value: Any = 10, max_denominator: int = 12, nonzero: bool = False
) -> st.SearchStrategy[Fraction]:
    """Fractions in ``[min_value, max_value]`` with denominators ``<= max_denominator``."""
    if max_denominator < 1:
        raise ValueError("max_denominator must be >= 1")
    lo, hi = Fraction(min_value), Fraction(max_value)
    if lo > hi:
        raise ValueError("min_value must be <= max_value")

    @st.composite
    def build(draw: Any) -> Fraction:
        den = draw(st.integers(1, max_denominator))
        num = draw(st.integers(int(lo * den) - (lo * den < int(lo * den)), int(hi * den)))
        value = Fraction(num, den)
        value = min(max(value, lo), hi)
        return value

    s = build()
    return s.filter(lambda v: v != 0) if nonzero else s


def rotations(*, max_component: int = 4) -> st.SearchStrategy[Any]:
    """Exact rotation matrices from integer quaternions with small components."""
    comp = st.integers(-max_component, max_component)
    return (
        st.tuples(comp, comp, comp, comp).filter(lambda q: any(q)).map(lambda q: rotation_from_quaternion(*q))
    )


def points(*, bound: Any = 10, max_denominator: int = 8) -> st.SearchStrategy[tuple[Fraction, ...]]:
    r = rationals(min_value=-bound, max_value=bound, max_denominator=max_denominator)
    return st.tuples(r, r, r)


def rigid_motions(*, bound: Any = 10) -> st.SearchStrategy[RigidMotion]:
    """Rational rotation followed by a rational translation."""
    return st.builds(lambda R, t: RigidMotion(R, t), rotations(), points(bound=bound))


def _positive(lo: Any, hi: Any, den: int = 8) -> st.SearchStrategy[Fraction]:
    return rationals(min_value=lo, max_value=hi, max_denominator=den).filter(lambda v: v > 0)


@st.composite
def ellipsoids(
    draw: Any,
    *,
    min_axis: Any = Fraction(1, 4),
    max_axis: Any = 3,
    bound: Any = 10,
    moved: bool = True,
) -> Quadric:
    """Real ellipsoids with rational semi-axes in ``[min_axis, max_axis]``,
    a rational rotation and centre (``moved=False``: axis-aligned at 0)."""
    axes = [draw(_positive(min_axis, max_axis)) for _ in range(3)]
    e = Quadric.ellipsoid(*axes)
    if moved:
        e = e.moved(draw(rigid_motions(bound=bound)))
    return e


def _standard(draw: Any, kind: QuadricKind, lo: Any, hi: Any) -> Quadric:
    nparams = len(Quadric.standard_parameters(kind))
    params = sorted((draw(_positive(lo, hi)) for _ in range(nparams)), reverse=True)
    return Quadric.standard(kind, **dict(zip("abc", params, strict=False)))


@st.composite
def quadrics(
    draw: Any,
    kind: QuadricKind | str | None = None,
    *,
    min_param: Any = Fraction(1, 2),
    max_param: Any = 6,
    bound: Any = 10,
    moved: bool = True,
    flip_sign: bool = True,
) -> Quadric:
    """Quadrics of a Table 1 type (``kind=None``: any of them, or ``"plane"``),
    in standard form with rational parameters (sorted decreasingly as in
    Table 1), moved by a rational rigid motion, possibly negated."""
    k = draw(st.sampled_from(TABLE_1_KINDS)) if kind is None else QuadricKind(kind)
    if k is QuadricKind.PLANE:
        q = draw(planes(bound=bound))
    else:
        q = _standard(draw, k, min_param, max_param)
        if moved:
            q = q.moved(draw(rigid_motions(bound=bound)))
    if flip_sign and draw(st.booleans()):
        q = -q
    return q


@st.composite
def planes(draw: Any, *, bound: Any = 10) -> Quadric:
    """Planes ``n . x = d`` with a non-zero rational normal."""
    n = draw(points(bound=4).filter(lambda p: any(p)))
    d = draw(rationals(min_value=-bound, max_value=bound))
    return Quadric.plane(n, d)


@st.composite
def tangent_pairs(draw: Any, *, inside: bool | None = None) -> tuple[Quadric, Quadric]:
    """``(E, Q)`` exactly tangent: an ellipsoid touching a Table 1 quadric at
    a vertex on its axis (from outside, or from inside when ``inside``), both
    moved by the same rational rigid motion.

    The constructions (parameters a >= b >= c, ellipsoid semi-axes small):

    * ellipsoid / two-sheet hyperboloid / elliptic paraboloid: ``E`` on the
      z-axis touching the vertex ``(0, 0, c)`` (``(0, 0, 0)`` for the
      paraboloid);
    * parallel planes: ``E`` touching the plane ``x = a``.
    """
    kinds = [
        QuadricKind.ELLIPSOID,
        QuadricKind.HYPERBOLOID_TWO_SHEETS,
        QuadricKind.ELLIPTIC_PARABOLOID,
        QuadricKind.PARALLEL_PLANES,
    ]
    k = draw(st.sampled_from(kinds))
    side_inside = draw(st.booleans()) if inside is None else inside
    g = draw(_positive(Fraction(1, 10), Fraction(1, 2)))
    # The other semi-axes are at most g, so the curvatures of E at the touching
    # vertex (g / ax^2 >= 1/g >= 2) exceed those of Q there (<= 1/2): the
    # contact is a single tangent point, from inside as from outside.
    ax = [draw(_positive(Fraction(1, 20), g)) for _ in range(2)]
    if k is QuadricKind.PARALLEL_PLANES:
        a = draw(_positive(2, 5))
        q = Quadric.parallel_planes(a)
        cx = a - g if side_inside else a + g
        e = Quadric.ellipsoid(g, ax[0], ax[1], center=(cx, 0, 0))
    else:
        if k is QuadricKind.ELLIPTIC_PARABOLOID:
            a, b = sorted((draw(_positive(2, 6)) for _ in range(2)), reverse=True)
            q = Quadric.elliptic_paraboloid(a, b)
            vz, outward = Fraction(0), -1
        else:
            a, b, c = sorted((draw(_positive(2, 6)) for _ in range(3)), reverse=True)
            q = Quadric.standard(k, a=a, b=b, c=c)
            vz, outward = c, (1 if k is QuadricKind.ELLIPSOID else -1)
        direction = -outward if side_inside else outward
        e = Quadric.ellipsoid(ax[0], ax[1], g, center=(0, 0, vz + direction * g))
    m = draw(rigid_motions())
    return e.moved(m), q.moved(m)
