"""Rigid motions with rational entries.

A rotation matrix built from a *rational quaternion* ``q = (w, x, y, z)`` by::

    R = (1 / |q|^2) [[w²+x²-y²-z², 2(xy-wz),     2(xz+wy)],
                     [2(xy+wz),     w²-x²+y²-z², 2(yz-wx)],
                     [2(xz-wy),     2(yz+wx),     w²-x²-y²+z²]]

is exactly orthogonal with determinant 1 and has rational entries, so a
quadric moved by it keeps rational coefficients and every answer stays exact.
Every rational rotation arises this way (Cayley), so nothing is lost.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from quadric_contact.exact.errors import NotANumberError, ShapeError
from quadric_contact.exact.rational import as_square_matrix, to_fraction

__all__ = ["RigidMotion", "rotation_from_quaternion"]

Vec3 = tuple[Fraction, Fraction, Fraction]
Mat3 = tuple[Vec3, Vec3, Vec3]

_IDENTITY: Mat3 = (
    (Fraction(1), Fraction(0), Fraction(0)),
    (Fraction(0), Fraction(1), Fraction(0)),
    (Fraction(0), Fraction(0), Fraction(1)),
)
_ZERO: Vec3 = (Fraction(0), Fraction(0), Fraction(0))


def _vec3(v: Any, what: str) -> Vec3:
    try:
        items = list(v)
    except TypeError as exc:
        raise ShapeError(f"{what} must be a sequence of 3 numbers", v) from exc
    if len(items) != 3:
        raise ShapeError(f"{what} must have 3 components, got {len(items)}", v)
    a, b, c = (to_fraction(t) for t in items)
    return (a, b, c)


def rotation_from_quaternion(w: Any, x: Any, y: Any, z: Any) -> Mat3:
    """Exact rotation matrix of the (not necessarily unit) rational quaternion ``w + xi + yj + zk``.

    Parameters
    ----------
    w, x, y, z : rational numbers
        Not all zero; only the direction of the quaternion matters.

    Returns
    -------
    tuple of 3 tuples of Fraction
        ``R``, exactly orthogonal with determinant 1.

    Raises
    ------
    NotANumberError
        If the quaternion is zero.

    Examples
    --------
    >>> R = rotation_from_quaternion(1, 0, 0, 1)   # 90 degrees about z
    >>> [[int(v) for v in row] for row in R]
    [[0, -1, 0], [1, 0, 0], [0, 0, 1]]
    """
    w, x, y, z = (to_fraction(t) for t in (w, x, y, z))
    n = w * w + x * x + y * y + z * z
    if n == 0:
        raise NotANumberError("the zero quaternion defines no rotation", (w, x, y, z))
    return (
        ((w * w + x * x - y * y - z * z) / n, 2 * (x * y - w * z) / n, 2 * (x * z + w * y) / n),
        (2 * (x * y + w * z) / n, (w * w - x * x + y * y - z * z) / n, 2 * (y * z - w * x) / n),
        (2 * (x * z - w * y) / n, 2 * (y * z + w * x) / n, (w * w - x * x - y * y + z * z) / n),
    )


def _matmul3(a: Mat3, b: Mat3) -> Mat3:
    return tuple(  # type: ignore[return-value]
        tuple(sum((a[i][k] * b[k][j] for k in range(3)), Fraction(0)) for j in range(3)) for i in range(3)
    )


def _transpose3(a: Mat3) -> Mat3:
    return tuple(tuple(a[j][i] for j in range(3)) for i in range(3))  # type: ignore[return-value]


def _matvec3(a: Mat3, v: Vec3) -> Vec3:
    return tuple(sum((a[i][k] * v[k] for k in range(3)), Fraction(0)) for i in range(3))  # type: ignore[return-value]


def _det3(a: Mat3) -> Fraction:
    return (
        a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
        - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
        + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0])
    )


@dataclass(frozen=True)
class RigidMotion:
    """The map ``x -> R x + t`` with ``R`` an exact rational rotation.

    Compose with ``@`` (``(m1 @ m2)(x) == m1(m2(x))``); invert with
    :meth:`inverse`.  Apply to a point with :meth:`apply` and to a quadric
    with ``quadric.moved(motion)``.
    """

    rotation: Mat3 = _IDENTITY
    translation: Vec3 = _ZERO

    @classmethod
    def identity(cls) -> RigidMotion:
        """The identity motion."""
        return cls()

    @classmethod
    def from_quaternion(
        cls, w: Any, x: Any, y: Any, z: Any, translation: Sequence[Any] = (0, 0, 0)
    ) -> RigidMotion:
        """Rotation by a rational quaternion, then translation."""
        return cls(rotation_from_quaternion(w, x, y, z), _vec3(translation, "translation"))

    @classmethod
    def from_translation(cls, v: Sequence[Any]) -> RigidMotion:
        """The translation ``x -> x + v``.

        Examples
        --------
        >>> RigidMotion.from_translation((1, 2, 3)).apply((0, 0, 0))
        (Fraction(1, 1), Fraction(2, 1), Fraction(3, 1))
        """
        return cls(_IDENTITY, _vec3(v, "translation"))

    @classmethod
    def from_matrix(cls, rotation: Any, translation: Sequence[Any] = (0, 0, 0)) -> RigidMotion:
        """From an exact 3x3 rotation matrix (checked: ``R^T R = I`` and ``det R = 1``)."""
        R = as_square_matrix(rotation, 3)
        rt_r = _matmul3(_transpose3(R), R)  # type: ignore[arg-type]
        if rt_r != _IDENTITY or _det3(R) != 1:  # type: ignore[arg-type]
            raise ShapeError("rotation must be exactly orthogonal with determinant 1", rotation)
        return cls(R, _vec3(translation, "translation"))  # type: ignore[arg-type]

    def __matmul__(self, other: RigidMotion) -> RigidMotion:
        return RigidMotion(
            _matmul3(self.rotation, other.rotation),
            tuple(  # type: ignore[arg-type]
                a + b
                for a, b in zip(_matvec3(self.rotation, other.translation), self.translation, strict=True)
            ),
        )

    def inverse(self) -> RigidMotion:
        """The inverse motion ``x -> R^T (x - t)``."""
        rt = _transpose3(self.rotation)
        t = _matvec3(rt, self.translation)
        return RigidMotion(rt, (-t[0], -t[1], -t[2]))

    def apply(self, point: Sequence[Any]) -> Vec3:
        """The image ``R p + t`` of a point, exactly."""
        p = _vec3(point, "point")
        r = _matvec3(self.rotation, p)
        return (r[0] + self.translation[0], r[1] + self.translation[1], r[2] + self.translation[2])

    def homogeneous(self) -> tuple[tuple[Fraction, ...], ...]:
        """The 4x4 matrix ``H`` with ``H @ (x, 1) = (R x + t, 1)``."""
        rows = [(*self.rotation[i], self.translation[i]) for i in range(3)]
        rows.append((Fraction(0), Fraction(0), Fraction(0), Fraction(1)))
        return tuple(rows)

    def inverse_homogeneous(self) -> tuple[tuple[Fraction, ...], ...]:
        """``H^-1``: a quadric ``Q`` moves to ``H^-T Q H^-1``."""
        return self.inverse().homogeneous()
