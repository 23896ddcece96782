"""Rigid trajectories of a moving ellipsoid, exact in time.

A trajectory is cut into :class:`MotionSegment` s on each of which the motion
is *polynomial* (translation) or *rational* (rotation) in the time ``t``:

* the centre follows ``p(t)``, a polynomial curve with rational coefficients;
* the orientation is the rotation of the quaternion ``q(t)``, whose four
  components are polynomials in ``t``: ``R(t) = M(q(t)) / |q(t)|^2`` with
  ``M`` quadratic in ``q`` (:func:`~quadric_contact.model.motions.rotation_from_quaternion`),
  a rational parametrisation of the rotation.

A point ``x0`` of the ellipsoid in its initial placement (centre ``c0``)
goes to ``x = R(t) (x0 - c0) + p(t)``.  With ``n(t) = |q(t)|^2`` and
``M(t) = n(t) R(t)``, the matrix

    G(t) = n(t) H(t)^-1 = [[M^T, n c0 - M^T p], [0, n]]

has polynomial entries, and ``n(t)^2 E(t) = G^T E0 G``
(:meth:`MotionSegment.moved_upper`): a *positive* multiple of the moved
ellipsoid's matrix with polynomial entries.  A positive factor changes
neither the surface, nor its inside, nor the signs or the real/non-real
nature of the roots of ``det(lambda E + Q)``, so every decision of the paper
can be taken on it; this is what makes event times exact
(:mod:`quadric_contact.scenes.events`).

Kinds of trajectory
-------------------
:class:`Stationary`; :class:`PolynomialMotion` (centre and quaternion
polynomial in ``t``; :meth:`PolynomialMotion.linear` for constant velocity);
:class:`Keyframes` (piecewise-linear centre path through timed positions,
with optional orientations whose quaternion components are interpolated
linearly, again a rational rotation).
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import flint

from quadric_contact.exact.algebraic import real_roots
from quadric_contact.exact.bounds import MAX_MOTION_DEGREE
from quadric_contact.exact.errors import SceneError, ShapeError
from quadric_contact.exact.rational import fmpq_of, fmpq_poly_of, to_fraction
from quadric_contact.exact.reading import parse_univariate
from quadric_contact.model.motions import RigidMotion, rotation_from_quaternion
from quadric_contact.model.quadric import Quadric

__all__ = [
    "Keyframes",
    "MotionSegment",
    "PolynomialMotion",
    "Stationary",
    "Trajectory",
    "poly_eval",
]

Vec3 = tuple[Fraction, Fraction, Fraction]
Poly = Any  # flint.fmpq_poly


def poly_eval(p: Any, t: Fraction) -> Fraction:
    """Exact value of an ``fmpq_poly`` at a rational ``t``."""
    v = p(fmpq_of(t))
    return Fraction(int(v.p), int(v.q))


def _poly_coeffs(p: Any) -> list[Fraction]:
    return [Fraction(int(c.p), int(c.q)) for c in p.coeffs()]


@dataclass(frozen=True)
class MotionSegment:
    """A piece of trajectory on ``[t0, t1]``, polynomial in the (global) time ``t``.

    Attributes
    ----------
    t0, t1 : Fraction
        The time interval (``t0 < t1``).
    center : tuple of three fmpq_poly
        The centre ``p(t)``.
    quaternion : tuple of four fmpq_poly, or None
        ``q(t) = (w, x, y, z)``, never zero on ``[t0, t1]``; None means no
        rotation (the initial orientation is kept).
    """

    t0: Fraction
    t1: Fraction
    center: tuple[Poly, Poly, Poly]
    quaternion: tuple[Poly, Poly, Poly, Poly] | None = None

    @property
    def degree(self) -> int:
        """Degree of the motion: of the centre path, and twice that of the
        quaternion (the rotation is quadratic in it)."""
        d = max((p.degree() for p in self.center), default=0)
        if self.quaternion is not None:
            d = max(d, 2 * max(p.degree() for p in self.quaternion))
        return max(d, 0)

    def norm_poly(self) -> Any:
        """``n(t) = |q(t)|^2`` (positive on the segment), or None without rotation."""
        if self.quaternion is None:
            return None
        return sum((c * c for c in self.quaternion), flint.fmpq_poly([]))

    def center_at(self, t: Any) -> Vec3:
        t = to_fraction(t)
        x, y, z = (poly_eval(p, t) for p in self.center)
        return (x, y, z)

    def quaternion_at(self, t: Any) -> tuple[Fraction, ...] | None:
        if self.quaternion is None:
            return None
        t = to_fraction(t)
        return tuple(poly_eval(p, t) for p in self.quaternion)

    def rigid_motion(self, t: Any, pivot: Sequence[Any]) -> RigidMotion:
        """The exact rigid motion at a rational time ``t`` that takes the
        initial placement (centre ``pivot``) to the placement at ``t``."""
        t = to_fraction(t)
        c0 = tuple(to_fraction(v) for v in pivot)
        p = self.center_at(t)
        q = self.quaternion_at(t)
        to_origin = RigidMotion.from_translation(tuple(-v for v in c0))
        rot = RigidMotion() if q is None else RigidMotion(rotation_from_quaternion(*q))
        return RigidMotion.from_translation(p) @ rot @ to_origin

    def moved_upper(self, E0: Quadric, pivot: Sequence[Fraction]) -> tuple[Poly, ...]:
        """The ten upper entries of ``n(t)^2 E(t) = G^T E0 G`` as ``fmpq_poly`` in ``t``.

        A positive multiple of the moved ellipsoid's matrix (``n = |q|^2 > 0``;
        ``n = 1`` without rotation).
        """
        one = flint.fmpq_poly([1])
        zero = flint.fmpq_poly([])
        c0 = [fmpq_of(to_fraction(v)) for v in pivot]
        if self.quaternion is None:
            Mt = [[one if i == j else zero for j in range(3)] for i in range(3)]  # M^T = I
            n = one
        else:
            w, x, y, z = self.quaternion
            M = [
                [w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y)],
                [2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x)],
                [2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z],
            ]
            Mt = [[M[j][i] for j in range(3)] for i in range(3)]
            n = w * w + x * x + y * y + z * z
        p = self.center
        # G = [[M^T, n c0 - M^T p], [0, n]]
        G: list[list[Any]] = []
        for i in range(3):
            shift = n * c0[i] - sum((Mt[i][k] * p[k] for k in range(3)), zero)
            G.append([Mt[i][0], Mt[i][1], Mt[i][2], shift])
        G.append([zero, zero, zero, n])
        E = [[flint.fmpq_poly([fmpq_of(E0[i, j])]) for j in range(4)] for i in range(4)]
        # T = E0 G, result = G^T T
        T = [[sum((E[i][k] * G[k][j] for k in range(4)), zero) for j in range(4)] for i in range(4)]
        out = []
        for i in range(4):
            for j in range(i, 4):
                out.append(sum((G[k][i] * T[k][j] for k in range(4)), zero))
        return tuple(out)


class Trajectory:
    """Base class: a rigid motion of the moving ellipsoid, defined for all ``t``.

    Subclasses implement :meth:`segments`.
    """

    def segments(self, t0: Fraction, t1: Fraction, origin: Vec3) -> list[MotionSegment]:
        """Segments covering ``[t0, t1]`` in time order, for an ellipsoid whose
        initial centre is ``origin``."""
        raise NotImplementedError

    def describe(self) -> str:
        return type(self).__name__

    def segment_at(self, t: Any, t0: Fraction, t1: Fraction, origin: Vec3) -> MotionSegment:
        t = to_fraction(t)
        for seg in self.segments(t0, t1, origin):
            if seg.t0 <= t <= seg.t1:
                return seg
        raise ValueError(f"t = {t} is outside [{t0}, {t1}]")

    def placed(self, E0: Quadric, t: Any, t0: Fraction, t1: Fraction) -> Quadric:
        """The ellipsoid at time ``t`` (exact), built with :meth:`Quadric.moved`
        (independently of :meth:`MotionSegment.moved_upper`)."""
        c = E0.center()
        assert c is not None
        seg = self.segment_at(t, t0, t1, c)
        return E0.moved(seg.rigid_motion(t, c))


class Stationary(Trajectory):
    """The ellipsoid stays where it is."""

    def segments(self, t0: Fraction, t1: Fraction, origin: Vec3) -> list[MotionSegment]:
        return [MotionSegment(t0, t1, tuple(fmpq_poly_of([c]) for c in origin))]

    def describe(self) -> str:
        return "stationary"


def _check_quaternion_nonzero(q: Sequence[Any], t0: Fraction, t1: Fraction, what: str) -> None:
    """Raise if the polynomial quaternion ``q`` vanishes somewhere on ``[t0, t1]``."""
    g = flint.fmpq_poly([])
    for comp in q:
        g = comp if g.is_zero() else g.gcd(comp)
    if g.is_zero():
        raise SceneError(f"{what}: the quaternion is identically zero", q)
    if g.degree() <= 0:
        return
    roots = real_roots(g, t0, t1, closed=True)
    if roots:
        raise SceneError(
            f"{what}: the quaternion vanishes at t = {roots[0].decimal(12)} in [{t0}, {t1}], "
            "where it defines no rotation",
            q,
        )


def _coefficients(component: Any, what: str) -> tuple[Fraction, ...]:
    """Coefficients (ascending powers of ``t``) of a coefficient sequence or of
    a polynomial in ``t`` written as text, of degree at most
    :data:`~quadric_contact.exact.bounds.MAX_MOTION_DEGREE`: a list is cut
    after one entry too many, before any entry is read."""
    if isinstance(component, str):
        return parse_univariate(component, "t", max_degree=MAX_MOTION_DEGREE, what=what)
    try:
        items = list(itertools.islice(iter(component), MAX_MOTION_DEGREE + 2))
    except TypeError:
        raise ShapeError(f"{what}: expected a list of coefficients or a polynomial in t", component) from None
    if len(items) > MAX_MOTION_DEGREE + 1:
        raise ShapeError(
            f"{what}: more than {MAX_MOTION_DEGREE + 1} coefficients, a degree above "
            f"{MAX_MOTION_DEGREE} in t (MAX_MOTION_DEGREE)",
            component,
        )
    return tuple(to_fraction(c) for c in items)


class PolynomialMotion(Trajectory):
    """Centre and orientation polynomial in ``t``.

    Parameters
    ----------
    translation : three sequences of numbers, or polynomials in ``t`` as text
        ``d_x, d_y, d_z``: coefficients (ascending powers of ``t``) of the
        displacement of the centre from its initial position: ``p(t) = c0 + d(t)``;
        a component may be text such as ``"2*t - 5*t^2"`` (read by
        :func:`~quadric_contact.exact.reading.parse_polynomial`).  Each
        component has degree at most
        :data:`~quadric_contact.exact.bounds.MAX_MOTION_DEGREE` (a list at most
        one entry more).
    quaternion : four sequences of numbers, or polynomials in ``t`` as text, optional
        Components ``w, x, y, z`` of ``q(t)`` (ascending powers of ``t``); the
        ellipsoid is turned about its centre by the rotation of ``q(t)``
        relative to its initial orientation.  Must not vanish on the span.

    Examples
    --------
    A constant velocity, then a quadratic drop:

    >>> m = PolynomialMotion.linear((1, 0, 0))
    >>> seg = m.segments(Fraction(0), Fraction(2), (Fraction(0),) * 3)[0]
    >>> seg.center_at(2)
    (Fraction(2, 1), Fraction(0, 1), Fraction(0, 1))
    >>> seg = PolynomialMotion(((0,), (0,), (0, 0, -5))).segments(Fraction(0), Fraction(1), (0, 0, 10))[0]
    >>> seg.center_at(1)[2]
    Fraction(5, 1)
    >>> PolynomialMotion(("t", "0", "-5*t^2")).translation[2]
    (Fraction(0, 1), Fraction(0, 1), Fraction(-5, 1))
    """

    def __init__(
        self, translation: Sequence[Sequence[Any]], quaternion: Sequence[Sequence[Any]] | None = None
    ):
        if len(translation) != 3:
            raise ShapeError("translation needs three coefficient lists (x, y, z)", translation)
        self.translation = tuple(
            _coefficients(comp, f"translation {axis}") for axis, comp in zip("xyz", translation, strict=True)
        )
        if quaternion is not None:
            if len(quaternion) != 4:
                raise ShapeError("quaternion needs four coefficient lists (w, x, y, z)", quaternion)
            self.quaternion: tuple[tuple[Fraction, ...], ...] | None = tuple(
                _coefficients(comp, f"quaternion {part}")
                for part, comp in zip("wxyz", quaternion, strict=True)
            )
        else:
            self.quaternion = None

    @classmethod
    def linear(cls, velocity: Sequence[Any], start_time: Any = 0) -> PolynomialMotion:
        """Constant ``velocity``; the centre is at its initial position at ``start_time``."""
        v = [to_fraction(c) for c in velocity]
        if len(v) != 3:
            raise ShapeError("velocity must have 3 components", velocity)
        s = to_fraction(start_time)
        return cls(tuple((-c * s, c) for c in v))

    def segments(self, t0: Fraction, t1: Fraction, origin: Vec3) -> list[MotionSegment]:
        center = tuple(fmpq_poly_of([origin[i]]) + fmpq_poly_of(self.translation[i]) for i in range(3))
        quat = None
        if self.quaternion is not None:
            quat = tuple(fmpq_poly_of(c) for c in self.quaternion)
            _check_quaternion_nonzero(quat, t0, t1, "polynomial rotation")
        return [MotionSegment(t0, t1, center, quat)]

    def describe(self) -> str:
        deg = max((len(c) - 1 for c in self.translation), default=0)
        rot = "" if self.quaternion is None else ", polynomial quaternion rotation"
        return f"polynomial translation of degree {max(deg, 0)}{rot}"


@dataclass(frozen=True)
class Keyframe:
    time: Fraction
    position: Vec3
    rotation: tuple[Fraction, Fraction, Fraction, Fraction] | None = None


class Keyframes(Trajectory):
    """Piecewise-linear path through timed keyframes.

    Parameters
    ----------
    keys : sequence of (time, position) or (time, position, quaternion)
        Strictly increasing times; ``position`` is where the *centre* is;
        ``quaternion`` (optional, ``(w, x, y, z)``) is the orientation
        relative to the initial one (a missing one keeps the previous).
        Between keys the centre moves linearly and the quaternion
        components are interpolated linearly (after replacing the next
        quaternion by its negative, which is the same rotation, when that
        shortens the path, so the interpolated quaternion never vanishes).
        Before the first and after the last key the ellipsoid rests.

    Examples
    --------
    >>> k = Keyframes([(0, (0, 0, 0)), (2, (4, 0, 0))])
    >>> [s.center_at(1) for s in k.segments(Fraction(0), Fraction(2), (0, 0, 0))]
    [(Fraction(2, 1), Fraction(0, 1), Fraction(0, 1))]
    """

    def __init__(self, keys: Sequence[Sequence[Any]]):
        if len(keys) < 1:
            raise ShapeError("keyframes need at least one key", keys)
        parsed: list[Keyframe] = []
        rot: tuple[Fraction, ...] | None = None
        for k in keys:
            if len(k) not in (2, 3):
                raise ShapeError("a key is (time, position) or (time, position, quaternion)", k)
            t = to_fraction(k[0])
            pos = tuple(to_fraction(v) for v in k[1])
            if len(pos) != 3:
                raise ShapeError("a key position has 3 coordinates", k)
            if len(k) == 3 and k[2] is not None:
                rot = tuple(to_fraction(v) for v in k[2])
                if len(rot) != 4 or not any(rot):
                    raise ShapeError("a key rotation is a non-zero quaternion (w, x, y, z)", k)
            if parsed and t <= parsed[-1].time:
                raise ShapeError(f"key times must increase: {t} after {parsed[-1].time}", keys)
            parsed.append(Keyframe(t, pos, rot))  # type: ignore[arg-type]
        self.keys = tuple(parsed)
        self.rotates = any(k.rotation is not None for k in parsed)

    def _quat(self, k: Keyframe) -> tuple[Fraction, ...]:
        return k.rotation if k.rotation is not None else (Fraction(1), Fraction(0), Fraction(0), Fraction(0))

    def segments(self, t0: Fraction, t1: Fraction, origin: Vec3) -> list[MotionSegment]:
        keys = self.keys
        segs: list[MotionSegment] = []
        # oriented quaternions along the path (sign chosen for the short way)
        quats = [self._quat(keys[0])]
        for k in keys[1:]:
            q = self._quat(k)
            if sum(a * b for a, b in zip(quats[-1], q, strict=True)) < 0:
                q = tuple(-v for v in q)
            quats.append(q)

        def rest(a: Fraction, b: Fraction, i: int) -> MotionSegment:
            c = tuple(fmpq_poly_of([v]) for v in keys[i].position)
            q = tuple(fmpq_poly_of([v]) for v in quats[i]) if self.rotates else None
            return MotionSegment(a, b, c, q)

        if t0 < keys[0].time:
            segs.append(rest(t0, min(t1, keys[0].time), 0))
        for i in range(len(keys) - 1):
            a, b = keys[i].time, keys[i + 1].time
            lo, hi = max(a, t0), min(b, t1)
            if lo >= hi:
                continue
            span = b - a
            tpoly = flint.fmpq_poly([fmpq_of(-a / span), fmpq_of(1 / span)])  # s(t)
            center = tuple(
                fmpq_poly_of([keys[i].position[j]])
                + tpoly * fmpq_of(keys[i + 1].position[j] - keys[i].position[j])
                for j in range(3)
            )
            quat = None
            if self.rotates:
                quat = tuple(
                    fmpq_poly_of([quats[i][j]]) + tpoly * fmpq_of(quats[i + 1][j] - quats[i][j])
                    for j in range(4)
                )
            segs.append(MotionSegment(lo, hi, center, quat))
        if t1 > keys[-1].time:
            segs.append(rest(max(t0, keys[-1].time), t1, len(keys) - 1))
        if not segs:  # the whole span lies inside one resting part
            segs.append(rest(t0, t1, 0 if t1 <= keys[0].time else len(keys) - 1))
        del origin  # keyframes are absolute positions
        return segs

    def describe(self) -> str:
        rot = " with interpolated orientations" if self.rotates else ""
        return f"keyframes ({len(self.keys)} keys, piecewise linear{rot})"
