"""The :class:`Quadric`: an immutable, exact, symmetric 4x4 matrix over Q.

A quadric is the zero set of ``X^T Q X`` with homogeneous coordinates
``X = (x, y, z, 1)``.  Entries are stored as :class:`fractions.Fraction`; a
float given by the caller is kept as the exact dyadic rational it is.

Sign conventions
----------------
The matrix is kept exactly as given: ``R- = {X^T Q X <= 0}`` and
``R+ = {X^T Q X >= 0}`` (paper eq. (8)) always refer to *this* matrix, so
``-Q`` describes the same surface with ``R-`` and ``R+`` swapped.  Only where
the paper assumes ``det(E) < 0`` (the ellipsoid's inside negative) does the
package normalise, in :meth:`Quadric.as_ellipsoid`, and it says so in every
result that used it.
"""

from __future__ import annotations

import inspect
import math
import operator
from collections.abc import Iterable, Sequence
from fractions import Fraction
from typing import Any

import numpy as np

from quadric_contact._generated.formulas import det_symmetric_4
from quadric_contact.exact.entries import ENTRY_INDICES
from quadric_contact.exact.errors import (
    SYMMETRIZE_HINT,
    EquationError,
    NonFiniteError,
    NotAnEllipsoidError,
    NotANumberError,
    NotRationalError,
    NotSymmetricError,
    QuadricContactError,
    ShapeError,
)
from quadric_contact.exact.rational import as_square_matrix, common_denominator, to_fraction
from quadric_contact.model.classification import QuadricKind, classify, principal_minor_sums_3
from quadric_contact.model.motions import RigidMotion, rotation_from_quaternion
from quadric_contact.model.parsing import parse_quadric_equation, quadric_entries

__all__ = ["Quadric", "as_quadric"]

_UPPER_POS = {ij: k for k, ij in enumerate(ENTRY_INDICES)}
_FULL_TO_UPPER = tuple(_UPPER_POS[(min(i, j), max(i, j))] for i in range(4) for j in range(4))


def _index(i: int, j: int) -> int:
    return _FULL_TO_UPPER[4 * i + j]


def _inverse_square(value: Any, name: str) -> Fraction:
    """``1 / value**2`` exactly; ``value`` may be a sympy expression such as
    ``sqrt(20/3)`` whose square is rational."""
    mod = type(value).__module__ or ""
    if mod.startswith("sympy"):
        import sympy  # sympy is heavy: only for sympy input

        square = to_fraction(sympy.nsimplify(sympy.expand(value**2)))
        if not getattr(value, "is_positive", False):
            raise NotANumberError(f"parameter {name} must be positive, got {value}", value)
    else:
        v = to_fraction(value)
        if v <= 0:
            raise NotANumberError(f"parameter {name} must be positive, got {value}", value)
        square = v * v
    return 1 / square


class Quadric:
    """An exact quadric ``X^T Q X = 0``.

    Build one with a constructor (:meth:`from_matrix`, :meth:`from_equation`,
    :meth:`from_coefficients`, :meth:`ellipsoid`, :meth:`sphere`,
    :meth:`plane`, :meth:`standard` and the named standard forms of Table 1);
    ``Quadric(M)`` is :meth:`from_matrix`.

    Examples
    --------
    The bee of Example 17:

    >>> bee = Quadric.from_equation("(x-3)**2 + (y-3)**2 + 3*(z-5.5)**2 - 0.1")
    >>> bee.kind
    <QuadricKind.ELLIPSOID: 'ellipsoid'>
    >>> bee[3, 3]   # 9 + 9 + 3 * 5.5**2 - 0.1
    Fraction(2173, 20)
    """

    __slots__ = ("_hash", "_ints", "_kind", "_uf")

    def __init__(self, matrix: Any) -> None:
        q = matrix if isinstance(matrix, Quadric) else Quadric.from_matrix(matrix)
        self._uf: tuple[Fraction, ...] | None = q._uf
        self._kind: tuple[QuadricKind, int] | None = None
        self._ints: tuple[tuple[int, ...], int] | None = q._ints
        self._hash: int | None = None

    @property
    def _u(self) -> tuple[Fraction, ...]:
        """The upper entries as Fractions (made from the integer form when first read: a quadric
        from a binary64 array is decided on its integers, and twenty Fractions a pair were a
        tenth of the exact decision's time)."""
        u = self._uf
        if u is None:
            assert self._ints is not None
            ints, den = self._ints
            u = self._uf = tuple(Fraction(n, den) for n in ints)
        return u

    # -- construction ---------------------------------------------------------------

    @classmethod
    def _from_upper(cls, upper: Sequence[Fraction]) -> Quadric:
        obj = cls.__new__(cls)
        obj._uf = tuple(upper)
        obj._kind = None
        obj._ints = None
        obj._hash = None
        return obj

    @classmethod
    def from_matrix(cls, matrix: Any, *, symmetrize: bool = False) -> Quadric:
        """From a 4x4 matrix: nested sequences, numpy array, sympy or flint matrix.

        Entries may be ints, Fractions, floats (taken exactly), decimal strings
        (``"8.36291"``) or sympy rationals.

        Parameters
        ----------
        matrix : matrix-like, shape (4, 4)
        symmetrize : bool, default False
            Replace the matrix by ``(M + M^T) / 2`` (exactly) instead of
            rejecting a non-symmetric one.  The quadratic form is the same.

        Returns
        -------
        Quadric

        Raises
        ------
        ShapeError, NotSymmetricError, NotANumberError, NonFiniteError, NotRationalError

        References
        ----------
        Eq. (6) and the matrix below it (Section 2.4).

        Examples
        --------
        A float is the dyadic rational it stores:

        >>> import numpy as np
        >>> Quadric.from_matrix(np.diag([1.0, 1.0, 1.0, -0.1]))[3, 3]
        Fraction(-3602879701896397, 36028797018963968)
        >>> M = [[1, 2, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, -1]]
        >>> Quadric.from_matrix(M, symmetrize=True).equation()
        'x**2 + 2*x*y + y**2 + z**2 - 1'
        """
        if isinstance(matrix, Quadric):
            return matrix
        fast = _from_float_array(matrix, symmetrize)
        if fast is not None:
            upper, ints = fast
            if ints is None:
                assert upper is not None
                return cls._from_upper(upper)
            obj = cls.__new__(cls)
            obj._uf, obj._ints, obj._kind, obj._hash = None, ints, None, None
            return obj
        m = as_square_matrix(matrix, 4)
        if symmetrize:
            upper = tuple((m[i][j] + m[j][i]) / 2 for i, j in ENTRY_INDICES)
            return cls._from_upper(upper)
        for i in range(4):
            for j in range(i + 1, 4):
                if m[i][j] != m[j][i]:
                    raise NotSymmetricError(
                        f"matrix is not symmetric: M[{i},{j}] = {m[i][j]} but M[{j},{i}] = {m[j][i]};"
                        f" {SYMMETRIZE_HINT}",
                        matrix,
                        entry=(i, j),
                    )
        return cls._from_upper(tuple(m[i][j] for i, j in ENTRY_INDICES))

    @classmethod
    def from_equation(cls, equation: Any) -> Quadric:
        """From an equation in ``x, y, z`` of degree at most 2.

        ``equation`` is a string (``"x**2 + y**2 - (z-3)**2/4 - 1"``; ``^``
        is accepted for ``**``, as is ``"lhs = rhs"``; products are written
        with ``*``) or a sympy expression / equality built by the caller.
        Strings are read by the package's own parser
        (:func:`~quadric_contact.model.parsing.parse_quadric_equation`, grammar and
        bounds in :mod:`quadric_contact.exact.reading`), never evaluated.  Decimal
        literals are read as exact decimals.

        Returns
        -------
        Quadric

        Raises
        ------
        EquationError
            Text the parser refuses (unknown names, functions, implicit
            multiplication, ...: the message names the offending text and
            its position), other symbols than x, y, z, a non-polynomial
            term, degree above 2 after expansion, or an irrational coefficient.

        Examples
        --------
        >>> Quadric.from_equation("x**2 + y**2 - 0.25*(z-3)**2 = 1").kind
        <QuadricKind.HYPERBOLOID_ONE_SHEET: 'hyperboloid of one sheet'>
        """
        if isinstance(equation, str):
            return cls._from_upper(parse_quadric_equation(equation))
        return cls._from_upper(_sympy_equation_entries(equation))

    @classmethod
    def from_coefficients(cls, a: Any, b: Sequence[Any], c: Any) -> Quadric:
        """From the coefficients of eq. (6): ``sum a_ij x_i x_j + sum 2 b_i x_i + c``.

        Parameters
        ----------
        a : 3x3 symmetric matrix-like
        b : sequence of 3 numbers (note the factor 2 in eq. (6))
        c : number

        Returns
        -------
        Quadric

        Raises
        ------
        NotSymmetricError, ShapeError
            ``a`` is not symmetric, ``b`` does not have 3 entries.

        Examples
        --------
        The bee of Example 17 (``"108.65"`` as a string is the decimal; the
        float ``108.65`` would be the nearest binary fraction):

        >>> Quadric.from_coefficients([[1, 0, 0], [0, 1, 0], [0, 0, 3]], [-3, -3, -16.5], "108.65").equation()
        'x**2 - 6*x + y**2 - 6*y + 3*z**2 - 33*z + 2173/20'
        """
        A = as_square_matrix(a, 3)
        for i in range(3):
            for j in range(i + 1, 3):
                if A[i][j] != A[j][i]:
                    raise NotSymmetricError(
                        f"a is not symmetric at ({i},{j}): {A[i][j]} but {A[j][i]}", a, entry=(i, j)
                    )
        bb = [to_fraction(t) for t in b]
        if len(bb) != 3:
            raise ShapeError("b must have 3 entries", b)
        full = [[*A[i], bb[i]] for i in range(3)] + [[*bb, to_fraction(c)]]
        return cls._from_upper(tuple(full[i][j] for i, j in ENTRY_INDICES))

    @classmethod
    def diagonal(cls, d0: Any, d1: Any, d2: Any, d3: Any) -> Quadric:
        """The diagonal matrix ``diag(d0, d1, d2, d3)``: ``d0 x^2 + d1 y^2 + d2 z^2 + d3``.

        Examples
        --------
        >>> Quadric.diagonal(1, 1, -1, 1).kind   # H in the proof of Lemma 12
        <QuadricKind.HYPERBOLOID_TWO_SHEETS: 'hyperboloid of two sheets'>
        """
        z = Fraction(0)
        d = [to_fraction(t) for t in (d0, d1, d2, d3)]
        return cls._from_upper((d[0], z, z, z, d[1], z, z, d[2], z, d[3]))

    # Standard forms of Table 1 (all with the paper's sign: R- is the "inside").

    @classmethod
    def ellipsoid(
        cls,
        a: Any,
        b: Any,
        c: Any,
        center: Sequence[Any] = (0, 0, 0),
        rotation: Any = None,
    ) -> Quadric:
        """``x^2/a^2 + y^2/b^2 + z^2/c^2 = 1`` rotated by ``rotation``, then centred at ``center``.

        Parameters
        ----------
        a, b, c : positive numbers
            Semi-axes; sympy expressions with rational squares
            (``sympy.sqrt(3)``) are accepted.
        center : sequence of 3 numbers
        rotation : 3x3 rational rotation matrix or quaternion ``(w, x, y, z)``, optional

        Returns
        -------
        Quadric
            With the paper's sign (inside negative, ``det < 0``).

        Raises
        ------
        NotANumberError
            A semi-axis is not positive.

        References
        ----------
        Eq. (2), Table 1.

        Examples
        --------
        >>> import sympy
        >>> Quadric.ellipsoid(sympy.sqrt(3), 1, 1).equation()
        'x**2/3 + y**2 + z**2 - 1'
        >>> Quadric.ellipsoid(3, 2, 1, rotation=(1, 0, 0, 1)).equation()   # a quarter turn about z
        'x**2/4 + y**2/9 + z**2 - 1'
        """
        q = cls.diagonal(_inverse_square(a, "a"), _inverse_square(b, "b"), _inverse_square(c, "c"), -1)
        return q._placed(center, rotation)

    @classmethod
    def sphere(cls, radius: Any, center: Sequence[Any] = (0, 0, 0)) -> Quadric:
        """The sphere ``|x - center|^2 = radius^2`` (``radius`` may be a sympy root)."""
        return cls.ellipsoid(radius, radius, radius, center=center)

    @classmethod
    def hyperboloid_one_sheet(cls, a: Any, b: Any, c: Any) -> Quadric:
        """``x^2/a^2 + y^2/b^2 - z^2/c^2 = 1``."""
        return cls.diagonal(_inverse_square(a, "a"), _inverse_square(b, "b"), -_inverse_square(c, "c"), -1)

    @classmethod
    def hyperboloid_two_sheets(cls, a: Any, b: Any, c: Any) -> Quadric:
        """``x^2/a^2 + y^2/b^2 - z^2/c^2 = -1``."""
        return cls.diagonal(_inverse_square(a, "a"), _inverse_square(b, "b"), -_inverse_square(c, "c"), 1)

    @classmethod
    def elliptic_paraboloid(cls, a: Any, b: Any) -> Quadric:
        """``x^2/a^2 + y^2/b^2 - z = 0``."""
        return cls._paraboloid(_inverse_square(a, "a"), _inverse_square(b, "b"))

    @classmethod
    def hyperbolic_paraboloid(cls, a: Any, b: Any) -> Quadric:
        """``x^2/a^2 - y^2/b^2 - z = 0``."""
        return cls._paraboloid(_inverse_square(a, "a"), -_inverse_square(b, "b"))

    @classmethod
    def _paraboloid(cls, p: Fraction, q: Fraction) -> Quadric:
        z, h = Fraction(0), Fraction(-1, 2)
        return cls._from_upper((p, z, z, z, q, z, z, z, h, z))

    @classmethod
    def elliptic_cylinder(cls, a: Any, b: Any) -> Quadric:
        """``x^2/a^2 + y^2/b^2 = 1``."""
        return cls.diagonal(_inverse_square(a, "a"), _inverse_square(b, "b"), 0, -1)

    @classmethod
    def hyperbolic_cylinder(cls, a: Any, b: Any) -> Quadric:
        """``x^2/a^2 - y^2/b^2 = 1``."""
        return cls.diagonal(_inverse_square(a, "a"), -_inverse_square(b, "b"), 0, -1)

    @classmethod
    def parabolic_cylinder(cls, a: Any) -> Quadric:
        """``x^2/a^2 - z = 0``."""
        return cls._paraboloid(_inverse_square(a, "a"), Fraction(0))

    @classmethod
    def parallel_planes(cls, a: Any) -> Quadric:
        """``x^2/a^2 - 1 = 0`` (the planes ``x = +-a``; ``R-`` is the slab between)."""
        return cls.diagonal(_inverse_square(a, "a"), 0, 0, -1)

    @classmethod
    def two_parallel_planes(cls, normal: Sequence[Any], offset1: Any, offset2: Any) -> Quadric:
        """The planes ``n . x = offset1`` and ``n . x = offset2``: the quadric
        ``(n . x - offset1)(n . x - offset2) = 0``, with ``R-`` the slab between them.

        Raises
        ------
        NotANumberError
            If the normal is zero or the offsets are equal (a double plane).
        """
        n = [to_fraction(t) for t in normal]
        if len(n) != 3:
            raise ShapeError("normal must have 3 components", normal)
        if not any(n):
            raise NotANumberError("the normal of a plane must not be zero", normal)
        d1, d2 = to_fraction(offset1), to_fraction(offset2)
        if d1 == d2:
            raise NotANumberError("equal offsets give one double plane, not two parallel planes", (d1, d2))
        m = [[n[i] * n[j] for j in range(3)] + [-(d1 + d2) * n[i] / 2] for i in range(3)]
        m.append([m[i][3] for i in range(3)] + [d1 * d2])
        return cls._from_upper(tuple(m[i][j] for i, j in ENTRY_INDICES))

    @classmethod
    def plane(cls, normal: Sequence[Any], offset: Any = 0) -> Quadric:
        """The plane ``n . x - offset = 0``; ``R-`` is the side ``n . x <= offset``.

        Its matrix has no quadratic part: ``[[0, n/2], [n^T/2, -offset]]``
        (Section 5.1).
        """
        n = [to_fraction(t) for t in normal]
        if len(n) != 3:
            raise ShapeError("normal must have 3 components", normal)
        if not any(n):
            raise NotANumberError("the normal of a plane must not be zero", normal)
        z = Fraction(0)
        return cls._from_upper((z, z, z, n[0] / 2, z, z, n[1] / 2, z, n[2] / 2, -to_fraction(offset)))

    @classmethod
    def _standard_maker(cls, kind: QuadricKind | str) -> Any:
        try:
            kind = QuadricKind(kind)
        except ValueError:
            names = ", ".join(repr(k.value) for k in QuadricKind if k.in_table_1)
            message = f"{kind!r} is not a kind of quadric; Table 1 has {names}"
            raise QuadricContactError(message, kind) from None
        makers: dict[QuadricKind, Any] = {
            QuadricKind.ELLIPSOID: cls.ellipsoid,
            QuadricKind.HYPERBOLOID_ONE_SHEET: cls.hyperboloid_one_sheet,
            QuadricKind.HYPERBOLOID_TWO_SHEETS: cls.hyperboloid_two_sheets,
            QuadricKind.ELLIPTIC_PARABOLOID: cls.elliptic_paraboloid,
            QuadricKind.HYPERBOLIC_PARABOLOID: cls.hyperbolic_paraboloid,
            QuadricKind.ELLIPTIC_CYLINDER: cls.elliptic_cylinder,
            QuadricKind.HYPERBOLIC_CYLINDER: cls.hyperbolic_cylinder,
            QuadricKind.PARABOLIC_CYLINDER: cls.parabolic_cylinder,
            QuadricKind.PARALLEL_PLANES: cls.parallel_planes,
        }
        if kind not in makers:
            raise QuadricContactError(f"{kind} has no standard form in Table 1", kind)
        return makers[kind]

    @classmethod
    def standard(cls, kind: QuadricKind | str, **params: Any) -> Quadric:
        """The standard form of Table 1 for ``kind`` with parameters ``a, b, c``
        (those of :meth:`standard_parameters`).

        Examples
        --------
        >>> Quadric.standard("hyperboloid of one sheet", a=1, b=1, c=2).equation()
        'x**2 + y**2 - z**2/4 - 1'
        """
        maker = cls._standard_maker(kind)
        try:
            return maker(**params)
        except TypeError as exc:
            raise ShapeError(f"wrong parameters for the standard {kind}: {exc}", params) from exc

    @classmethod
    def standard_parameters(cls, kind: QuadricKind | str) -> tuple[str, ...]:
        """The names of the parameters of the standard form of Table 1 for ``kind``
        (read off its constructor's signature).

        Examples
        --------
        >>> Quadric.standard_parameters("elliptic paraboloid")
        ('a', 'b')
        >>> Quadric.standard_parameters("ellipsoid")
        ('a', 'b', 'c')
        """
        signature = inspect.signature(cls._standard_maker(kind))
        return tuple(name for name in signature.parameters if name in ("a", "b", "c"))

    # -- rigid motions -------------------------------------------------------------

    def moved(self, motion: RigidMotion) -> Quadric:
        """The image of this quadric under the rigid motion (``Q' = H^-T Q H^-1``)."""
        Hinv = motion.inverse_homogeneous()
        M = self.matrix
        # T = M Hinv ; result = Hinv^T T
        T = [[sum((M[i][k] * Hinv[k][j] for k in range(4)), Fraction(0)) for j in range(4)] for i in range(4)]
        upper = tuple(sum((Hinv[k][i] * T[k][j] for k in range(4)), Fraction(0)) for i, j in ENTRY_INDICES)
        return Quadric._from_upper(upper)

    def translated(self, vector: Sequence[Any]) -> Quadric:
        """The quadric moved by the translation ``x -> x + vector``.

        Examples
        --------
        >>> Quadric.sphere(1).translated((1, 2, 3)).equation()
        'x**2 - 2*x + y**2 - 4*y + z**2 - 6*z + 13'
        """
        return self.moved(RigidMotion.from_translation(vector))

    def rotated(self, rotation: Any, about: Sequence[Any] = (0, 0, 0)) -> Quadric:
        """Rotate about the point ``about``; ``rotation`` is a quaternion
        ``(w, x, y, z)`` or an exact 3x3 rotation matrix."""
        R = _rotation(rotation)
        p = RigidMotion.from_translation(about)
        return self.moved(p @ RigidMotion(R) @ p.inverse())

    def _placed(self, center: Sequence[Any], rotation: Any) -> Quadric:
        q = self
        if rotation is not None:
            q = q.moved(RigidMotion(_rotation(rotation)))
        if any(to_fraction(t) != 0 for t in center):
            q = q.translated(center)
        return q

    # -- accessors -----------------------------------------------------------------

    @property
    def upper(self) -> tuple[Fraction, ...]:
        """The ten independent entries ``(q00, q01, q02, q03, q11, q12, q13, q22, q23, q33)``."""
        return self._u

    @property
    def matrix(self) -> tuple[tuple[Fraction, ...], ...]:
        """The symmetric 4x4 matrix, as a tuple of rows of Fractions."""
        u = self._u
        return tuple(tuple(u[_index(i, j)] for j in range(4)) for i in range(4))

    def __getitem__(self, ij: tuple[int, int]) -> Fraction:
        i, j = ij
        if not (0 <= i < 4 and 0 <= j < 4):
            raise IndexError(ij)
        return self._u[_index(i, j)]

    @property
    def quadratic_part(self) -> tuple[tuple[Fraction, ...], ...]:
        """``Q00 = (a_ij)``, the 3x3 block of eq. (6)."""
        return tuple(tuple(self[i, j] for j in range(3)) for i in range(3))

    @property
    def linear_part(self) -> tuple[Fraction, Fraction, Fraction]:
        """``(b_1, b_2, b_3)`` of eq. (6)."""
        return (self._u[3], self._u[6], self._u[8])

    @property
    def constant(self) -> Fraction:
        """``c`` of eq. (6): the entry ``Q[3, 3]``."""
        return self._u[9]

    def to_sympy(self) -> Any:
        """The matrix as a ``sympy.Matrix`` of exact rationals."""
        import sympy  # sympy is heavy: only for sympy output

        return sympy.Matrix(4, 4, lambda i, j: sympy.Rational(self[i, j].numerator, self[i, j].denominator))

    def to_numpy(self, dtype: Any = float) -> Any:
        """As a numpy array (``dtype=object`` keeps the Fractions; ``float`` rounds)."""
        return np.array([[self[i, j] for j in range(4)] for i in range(4)], dtype=dtype)

    def value_at(self, point: Sequence[Any]) -> Fraction:
        """``X^T Q X`` at ``X = (point, 1)``, exactly: its sign says ``R-`` or ``R+`` (eq. (8)).

        Examples
        --------
        The centre of the bee of Example 17 is inside it:

        >>> Quadric.from_equation("(x-3)**2 + (y-3)**2 + 3*(z-5.5)**2 - 0.1").value_at((3, 3, 5.5))
        Fraction(-1, 10)
        """
        p = [to_fraction(t) for t in point]
        if len(p) != 3:
            raise ShapeError("a point has 3 coordinates", point)
        X = (*p, Fraction(1))
        M = self.matrix
        return sum((X[i] * M[i][j] * X[j] for i in range(4) for j in range(4)), Fraction(0))

    def equation(self, variables: str = "xyz") -> str:
        """The equation ``X^T Q X`` as a sympy-readable string."""
        import sympy  # sympy is heavy: only for sympy output

        v = sympy.symbols(" ".join(variables))
        X = sympy.Matrix([*v, 1])
        return str(sympy.expand((X.T * self.to_sympy() * X)[0, 0]))

    @property
    def kind(self) -> QuadricKind:
        """Exact affine type (see :mod:`quadric_contact.model.classification`)."""
        if self._kind is None:
            # Inertia is unchanged by the positive factor of the integer form.
            self._kind = classify(self.integer_form()[0])
        return self._kind[0]

    @property
    def canonical_sign(self) -> int:
        """``+1`` if this matrix has the sign of the paper's standard form of
        its type (``-1`` if its negative does)."""
        if self._kind is None:
            self._kind = classify(self.integer_form()[0])
        return self._kind[1]

    def center(self) -> tuple[Fraction, Fraction, Fraction] | None:
        """The centre ``-Q00^-1 b`` when the quadratic part is invertible, else None.

        Exact (Cramer's rule with the adjugate of the symmetric 3x3 block).

        Examples
        --------
        >>> Quadric.from_equation("(x-3)**2 + (y-3)**2 + 3*(z-5.5)**2 - 0.1").center()
        (Fraction(3, 1), Fraction(3, 1), Fraction(11, 2))
        >>> Quadric.elliptic_paraboloid(1, 2).center() is None
        True
        """
        a00, a01, a02, b0, a11, a12, b1, a22, b2, _ = self._u
        det = principal_minor_sums_3((a00, a01, a02, a11, a12, a22))[2]
        if det == 0:
            return None
        # adjugate of [[a00, a01, a02], [a01, a11, a12], [a02, a12, a22]] (symmetric)
        c00 = a11 * a22 - a12 * a12
        c01 = a02 * a12 - a01 * a22
        c02 = a01 * a12 - a02 * a11
        c11 = a00 * a22 - a02 * a02
        c12 = a01 * a02 - a00 * a12
        c22 = a00 * a11 - a01 * a01
        return (
            -(c00 * b0 + c01 * b1 + c02 * b2) / det,
            -(c01 * b0 + c11 * b1 + c12 * b2) / det,
            -(c02 * b0 + c12 * b1 + c22 * b2) / det,
        )

    # -- ellipsoids -------------------------------------------------------------

    def as_ellipsoid(self) -> Quadric:
        """This quadric as a real ellipsoid with the paper's sign (``det E < 0``,
        inside negative): itself, or its negative if its inside is positive.

        Raises
        ------
        NotAnEllipsoidError
            If it is not a real, non-degenerate ellipsoid (``.details['kind']``
            says what it is).

        Examples
        --------
        >>> bee = Quadric.from_equation("(x-3)**2 + (y-3)**2 + 3*(z-5.5)**2 - 0.1")
        >>> (-bee).as_ellipsoid() == bee
        True
        """
        sign = self._ellipsoid_sign()
        if sign == 0:
            raise self._not_an_ellipsoid()
        return self if sign > 0 else -self

    def _not_an_ellipsoid(self) -> NotAnEllipsoidError:
        """The error for this quadric where a real ellipsoid is expected, naming its type."""
        return NotAnEllipsoidError(
            f"expected a real ellipsoid, got {self.kind.value} ({self.kind.real_points})",
            self,
            kind=self.kind,
        )

    def _ellipsoid_sign(self) -> int:
        """+1 if a real ellipsoid with the paper's sign, -1 if its negative is, 0 otherwise.

        Fast exact test on the integer form: Sylvester's criterion on the
        quadratic part (:meth:`_quadratic_part_sign`) and the sign of det(Q)."""
        sign = self._quadratic_part_sign()
        if sign == 0 or det_symmetric_4(*self.integer_form()[0]) >= 0:
            return 0
        return sign

    def _quadratic_part_sign(self) -> int:
        """+1 if the quadratic part is positive definite, -1 if negative definite, else 0
        (Sylvester's criterion on the integer form): with ``det < 0`` the quadric is a real
        ellipsoid, the paper's sign for +1."""
        a00, a01, a02, _, a11, a12, _, a22, _, _ = self.integer_form()[0]
        m2 = a00 * a11 - a01 * a01
        if m2 <= 0 or a00 == 0:
            return 0
        m3 = a00 * (a11 * a22 - a12 * a12) - a01 * (a01 * a22 - a12 * a02) + a02 * (a01 * a12 - a11 * a02)
        if m3 == 0 or (m3 > 0) != (a00 > 0):
            return 0
        return 1 if a00 > 0 else -1

    # -- exact integer form -------------------------------------------------------

    def integer_form(self) -> tuple[tuple[int, ...], int]:
        """``(ints, d)`` with ``upper == ints / d`` (``d > 0`` the least common denominator).

        Every sign decision of the package is taken on these integers.

        Examples
        --------
        >>> Quadric.from_equation("(x-3)**2 + (y-3)**2 + 3*(z-5.5)**2 - 0.1").integer_form()
        ((20, 0, 0, -60, 20, 0, -60, 60, -330, 2173), 20)
        """
        if self._ints is None:
            self._ints = common_denominator(self._u)
        return self._ints

    # -- arithmetic and comparison -----------------------------------------------

    def __neg__(self) -> Quadric:
        neg = Quadric.__new__(Quadric)
        neg._kind, neg._hash = None, None
        # the Fractions only where they are already made (a Quadric from binary64 entries makes
        # them when first read); the integer form is the same common denominator, negated
        neg._uf = None if self._uf is None else tuple(-v for v in self._uf)
        if self._ints is not None:
            ints, den = self._ints
            neg._ints = (tuple(-v for v in ints), den)
        else:
            neg._ints = None
        return neg

    def scaled(self, factor: Any) -> Quadric:
        """``factor * Q`` (same surface; a negative factor swaps R- and R+)."""
        f = to_fraction(factor)
        if f == 0:
            raise NotANumberError("scaling a quadric by 0 destroys it", factor)
        return Quadric._from_upper(tuple(f * v for v in self._u))

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Quadric) and self._u == other._u

    def __hash__(self) -> int:
        if self._hash is None:
            self._hash = hash(self._u)
        return self._hash

    def is_proportional_to(self, other: Quadric) -> bool:
        """``self == k * other`` for some rational ``k != 0`` (the same surface).

        Examples
        --------
        >>> Quadric.sphere(1).scaled(-3).is_proportional_to(Quadric.sphere(1))
        True
        """
        k = None
        for a, b in zip(self._u, other._u, strict=True):
            if (a == 0) != (b == 0):
                return False
            if a != 0:
                r = a / b
                if k is None:
                    k = r
                elif r != k:
                    return False
        return k is not None

    def __repr__(self) -> str:
        return f"Quadric.from_equation({self.equation()!r})"

    def __str__(self) -> str:
        return f"{self.kind.value}: {self.equation()} = 0"

    def __reduce__(self) -> tuple[Any, ...]:
        return (Quadric._from_upper, (self._u,))


_UPPER_FLAT = tuple(4 * i + j for i, j in ENTRY_INDICES)
_LOWER_FLAT = tuple(4 * j + i for i, j in ENTRY_INDICES)
_UPPER_OF = operator.itemgetter(*_UPPER_FLAT)
_LOWER_OF = operator.itemgetter(*_LOWER_FLAT)


def _from_float_array(
    matrix: Any, symmetrize: bool
) -> tuple[tuple[Fraction, ...] | None, tuple[tuple[int, ...], int] | None] | None:
    """Fast exact path for a finite float64 numpy (4, 4) array: the integer form when it is
    symmetric (every denominator is a power of two, so the least common one is the largest;
    the Fractions are made when first read), the upper entries of ``(M + M^T) / 2`` when it is
    not and ``symmetrize`` asks for it.  None otherwise."""
    if type(matrix).__module__ != "numpy":
        return None
    dtype = getattr(matrix, "dtype", None)
    # binary64 in either byte order ('d'); float32, float16 and longdouble take the general path
    if dtype is None or dtype.char != "d" or matrix.shape != (4, 4):
        return None
    flat = matrix.ravel().tolist()
    # a NaN or an infinity makes the sum non-finite (so does an overflow: then look entry by entry)
    if not math.isfinite(sum(flat)) and not all(math.isfinite(v) for v in flat):
        return None  # the general path names the offending entry
    upper = _UPPER_OF(flat)
    lower = _LOWER_OF(flat)
    if upper != lower:
        if not symmetrize:
            return None  # the general path raises NotSymmetricError with the entry
        return tuple((Fraction(a) + Fraction(b)) / 2 for a, b in zip(upper, lower, strict=True)), None
    ratios = [v.as_integer_ratio() for v in upper]
    den = max([d for _, d in ratios])
    return None, (tuple([n * (den // d) for n, d in ratios]), den)


def _rotation(rotation: Any) -> Any:
    try:
        items = list(rotation)
    except TypeError as exc:
        raise ShapeError("rotation must be a quaternion (w, x, y, z) or a 3x3 matrix", rotation) from exc
    if len(items) == 4 and not any(isinstance(t, Iterable) and not isinstance(t, str) for t in items):
        return rotation_from_quaternion(*items)
    return RigidMotion.from_matrix(rotation).rotation


def _sympy_equation_entries(equation: Any) -> tuple[Fraction, ...]:
    """The upper entries of a quadric given as a sympy expression or equality
    (a Python object built by the caller, not text: nothing is parsed)."""
    import sympy  # sympy is heavy: only for sympy input

    if isinstance(equation, sympy.Equality):
        expr = equation.lhs - equation.rhs
    elif isinstance(equation, sympy.Basic):
        expr = equation
    else:
        raise EquationError(
            f"expected a string or a sympy expression, got {type(equation).__name__}", equation
        )
    if not isinstance(expr, sympy.Expr):
        raise EquationError(f"{_shown(equation)} is not an algebraic expression", equation)
    xyz = sympy.symbols("x y z")
    others = expr.free_symbols - set(xyz)
    if others:
        raise EquationError(
            f"{_shown(equation)} has other symbols than x, y, z: {sorted(map(str, others))}", equation
        )
    for power in expr.atoms(sympy.Pow):
        # checked before expanding, which (x + 1)**(10**9) would not survive; a power up to
        # _MAX_POWER may cancel out, as in (x + 1)**3 - x**3 (a quadric)
        exponent = power.exp
        if power.base.free_symbols and exponent.is_Number and abs(exponent) > _MAX_POWER:
            raise EquationError(
                f"{_shown(equation)} has a power {_shown(power)}; a quadric has degree <= 2", equation
            )
    if expr.has(sympy.nan, sympy.oo, -sympy.oo, sympy.zoo):
        raise EquationError(f"{_shown(equation)} has a non-finite coefficient", equation)
    try:
        poly = sympy.Poly(sympy.expand(expr), *xyz)
    except sympy.PolynomialError as exc:
        raise EquationError(f"{_shown(equation)} is not a polynomial in x, y, z", equation) from exc
    if poly.total_degree() > 2:
        raise EquationError(
            f"{_shown(equation)} has degree {poly.total_degree()}; a quadric has degree <= 2", equation
        )
    if poly.free_symbols_in_domain:
        others_d = sorted(map(str, poly.free_symbols_in_domain))
        raise EquationError(f"{_shown(equation)} has other symbols than x, y, z: {others_d}", equation)
    terms: dict[tuple[int, ...], Fraction] = {}
    for monomial, c in poly.terms():
        try:
            terms[tuple(int(e) for e in monomial)] = to_fraction(c)
        except (NotRationalError, NotANumberError, NonFiniteError) as exc:
            where = f"coefficient {_shown(c)} of {monomial} in {_shown(equation)}"
            raise EquationError(f"{where}: {exc}", equation) from exc
    return quadric_entries(terms)


_MAX_POWER = 16
"""The largest power of x, y, z a sympy expression may hold before it is expanded."""


def _shown(x: Any, limit: int = 120) -> str:
    """``x`` as text for a message, cut to ``limit`` characters (a number of more digits than
    Python converts to text is named, not printed)."""
    try:
        text = repr(x)
    except ValueError:
        return "<an expression with a number too long to print>"
    return text if len(text) <= limit else text[: limit - 3] + "..."


def as_quadric(value: Any, name: str = "argument") -> Quadric:
    """The argument as a :class:`Quadric`: what every public function accepts.

    Parameters
    ----------
    value : Quadric, 4x4 matrix-like, equation string or sympy expression
    name : str
        The argument's name (for messages).

    Returns
    -------
    Quadric

    Raises
    ------
    EquationError, ShapeError, NotSymmetricError, NotANumberError, NonFiniteError, NotRationalError
        As :meth:`Quadric.from_equation` and :meth:`Quadric.from_matrix`.

    Examples
    --------
    >>> unit = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, -1]]
    >>> as_quadric("x**2 + y**2 + z**2 - 1") == as_quadric(unit)
    True
    """
    if isinstance(value, Quadric):
        return value
    if isinstance(value, str):
        return Quadric.from_equation(value)
    mod = type(value).__module__ or ""
    if mod.startswith("sympy") and not hasattr(value, "shape"):
        return Quadric.from_equation(value)
    return Quadric.from_matrix(value)
