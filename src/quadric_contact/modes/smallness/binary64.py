"""Smallness on stacks in binary64: the plain ``float`` stage and the certified ``filter``.

Every condition of Tables 1-2 (corrected) compares two monomials in positive
primitives of one matrix each (:mod:`~quadric_contact.modes.smallness.tables`):
invariants (``det``, ``det M00``, ``J``, ``E3``, ``E2``, ``tr M00``) and the
eigenvalues of the quadratic part.  Whatever depends on one matrix is computed once
per distinct matrix (:func:`e_row_quantities`, :func:`q_row_quantities`), and a pair
only compares two intervals per condition (:func:`pair_codes`).  When every pair has
its own ellipsoid (many ellipsoids against an environment) the ellipsoids' sides are
computed block by block inside the pair loop and never stored (:func:`_fused_loop`).

How the filter is certified
---------------------------
*Invariants.*  The generated program ``quadric_invariants`` and its magnitude
companion give a value and a rigorous bound ``fl(K M)`` of its rounding error
(:data:`~quadric_contact.modes.kernels.errorbounds.INVARIANTS_ERRBOUND`, with the constants for
rounded inputs when the stack holds exact rationals rounded to binary64).

*Eigenvalues.*  An approximation ``t`` of each eigenvalue (closed form, below) is
certified, never trusted: the number of eigenvalues of ``A`` below a point ``t`` is
the number of negative eigenvalues of ``B = A - t I``, that is Descartes' count of
sign variations of ``(1, tr B, J(B), det B)`` (exact: the characteristic polynomial
of a symmetric matrix is real-rooted; multiple eigenvalues, as for spheres and
spheroids, are counted with their multiplicity).  The three signs come from the
straight-line program :func:`shift_invariants` with its magnitude companion; the
diagonal ``fl(a_ii - t)`` of ``B`` is a rounded input (relative error ``u``; Sterbenz
makes it exact when ``t`` is near ``a_ii``), and :data:`SHIFT_ERRBOUND` is derived from
the rounding counts read off the program's text, as for the generated programs.
Counting at ``t - w`` and ``t + w`` (``w = WIDTH |t|``) encloses the ``i``-th eigenvalue
in ``[t - w, t + w]`` whenever the counts are ``<= i - 1`` and ``>= i``; an uncertain
sign counts as any of -1, 0 and 1 (:func:`_below_at_most`, :func:`_below_at_least`),
and the enclosure fails if that matters.  For rounded input the enclosures of the
float matrix ``A^`` are widened by Weyl's inequality,
``|lambda_i(A) - lambda_i(A^)| <= ||A - A^||_2 <= u/(1-u) sum |a^_ij|``; a row with an
exact non-zero entry that rounds to zero (no relative perturbation) is not trusted.

*Monomials.*  Each primitive enclosure ``[lo, hi]`` (positive, in
``[FACTOR_MIN, FACTOR_MAX]``) carries at most one rounding of its own (``fl(v -+ e)``,
a Weyl widening); a monomial with ``k`` factors takes at most ``k - 1`` more
roundings, so its computed value is within the factor ``(1 - u)^(+-2k)`` of the
exact value at the true ends, and one multiplication by :data:`CHAIN_DOWN` /
:data:`CHAIN_UP` (derived below in exact arithmetic) makes the ends rigorous.  The
guard keeps every intermediate normal: ``k <= MAX_DEGREE = 5`` factors in
``[2^-120, 2^120]``.

*Decisions.*  A condition holds when the intervals are ordered (``lo_Q >= hi_E`` for
a size condition), fails when they are strictly ordered the other way, and is
``UNCERTAIN`` otherwise: equality cases (two equal spheres, a pair on the boundary
``u = 1`` of Table 1) are left to the next stage, as are pairs whose matrices fail a
guard.

*Per matrix, once.*  The type of a quadric comes from the mode's
:meth:`~quadric_contact.modes.numbers.number_mode.NumberMode.classify`, and where that is uncertain
(or the row is not trusted) from exact integer arithmetic
(:func:`~quadric_contact.modes.facts.exact_facts`); a quadric whose sides the float
code cannot certify (a degenerate type rounded off its exact zero eigenvalue, or close
to it) gets them from ball arithmetic, rounded outward (:func:`_refine`).  Pairs still
uncertain get a second try with Newton-polished approximations and much narrower
enclosures (:data:`TIGHT_WIDTH`).  All of it is counted as the filter's.

The plain ``float`` stage runs the same code with no bounds: zero-width intervals at
the approximations, so it always answers and may be wrong near the boundary (and for a
degenerate type rounded off its zero eigenvalue, which plain numbers take for another).

Eigenvalue approximations without ``acos``/``cos``
---------------------------------------------------
The trigonometric solution of the characteristic cubic (``lambda = q + 2 p cos(phi +
2 k pi / 3)``, ``cos 3 phi = r``) is evaluated with two polynomials in
``x = (1 - |r|)/2 in [0, 1/2]``: ``H(x) = cos(2/3 asin sqrt x)`` and
``G(x) = sin(2/3 asin sqrt x) / sqrt x`` (both analytic there), fitted at import by
Chebyshev interpolation (degree :data:`APPROX_DEGREE`, error about ``1e-12``).  Only
the filter's escalation rate depends on their accuracy, never its answers.

One source, two backends
------------------------
The row and pair arithmetic is written once as plain functions of scalars or numpy arrays
(``select`` is ``numpy.where``; no Python branch depends on the data), each registered as a
pair (``quadric_contact.modes.kernels._jit.jitable`` with ``inline``).  The numpy backend
calls them on whole columns; the compiled loops over blocks of rows call their compiled sides
(``forceinline``, and ``select`` an LLVM ``select``), which LLVM inlines and vectorises.  The
first call compiles the loops (about a minute; numba caches them on disk), unless the library
of native kernels has them.
"""

from __future__ import annotations

import ast
import inspect
import math
from fractions import Fraction
from typing import Any

import numpy as np
from numpy.polynomial import chebyshev as C

from quadric_contact._generated import kernels
from quadric_contact.exact.entries import ENTRY_INDICES
from quadric_contact.exact.errors import ChoiceError
from quadric_contact.exact.straight_line import rounding_counts
from quadric_contact.model.classification import TABLE_1_KINDS
from quadric_contact.modes.codes import EXCLUDED, INVALID, UNCERTAIN
from quadric_contact.modes.facts import exact_facts, table_kinds
from quadric_contact.modes.kernels import errorbounds as eb
from quadric_contact.modes.kernels._jit import HAVE_NUMBA, jitable, njit, select
from quadric_contact.modes.kernels.signs import sign_within
from quadric_contact.modes.kernels.threads import run_parallel
from quadric_contact.modes.smallness.numbers import ball_sides
from quadric_contact.modes.smallness.tables import (
    E_SIDES,
    MAX_ALTERNATIVE,
    MAX_CONDITIONS,
    MAX_DEGREE,
    Q_SIDES,
    kind_arrays,
)
from quadric_contact.modes.stacks.pairs import MatrixStack, Pairs
from quadric_contact.modes.stacks.rows import unique_rows
from quadric_contact.modes.stacks.validation import diagnose

__all__ = [
    "APPROX_DEGREE",
    "CHAIN_DOWN",
    "CHAIN_UP",
    "FACTOR_MAX",
    "FACTOR_MIN",
    "SHIFT_ERRBOUND",
    "TIGHT_WIDTH",
    "WIDTH",
    "e_row_quantities",
    "eigen_approx",
    "float_smallness",
    "pair_codes",
    "q_row_quantities",
    "shift_invariants",
]

_U = eb.UNIT_ROUNDOFF

# -- constants, derived in exact arithmetic --------------------------------------------------------


def round_down(x: Fraction) -> float:
    """The largest binary64 number ``<= x`` (for positive, representable ``x``)."""
    f = float(x)
    if Fraction(f) > x:
        f = math.nextafter(f, -math.inf)
    assert Fraction(f) <= x
    return f


# A monomial with k factors: k pending roundings of its ends and at most k - 1 operations,
# each a factor (1 + d)^(+-1), |d| <= u, so computed/exact lies in [(1-u)^(2k), (1-u)^(-2k)].
# lo = fl(v CHAIN_DOWN[k]) <= v CHAIN_DOWN[k] (1 + u) <= exact when
# CHAIN_DOWN[k] <= (1-u)^(2k) / (1 + u); hi = fl(v CHAIN_UP[k]) >= exact when
# CHAIN_UP[k] >= (1-u)^-(2k+1).
CHAIN_DOWN = np.array([round_down((1 - _U) ** (2 * k) / (1 + _U)) for k in range(MAX_DEGREE + 1)])
"""Factor making the computed lower end of a ``k``-factor monomial rigorous."""
CHAIN_UP = np.array([eb.round_up((1 - _U) ** -(2 * k + 1)) for k in range(MAX_DEGREE + 1)])
"""Factor making the computed upper end of a ``k``-factor monomial rigorous."""

FACTOR_MIN = 2.0**-120
FACTOR_MAX = 2.0**120
"""Range of the primitive enclosures: a monomial of at most MAX_DEGREE factors and its
partial products stay normal."""
assert MAX_DEGREE * 120 < 1022

WIDTH = 2.0**-20
"""Half-width of the eigenvalue enclosures relative to the approximation.  Wide enough
for a double eigenvalue (``det B`` is then about ``w^2`` times a gap, far above its
rounding error), narrow enough that random pairs rarely straddle a boundary."""
TIGHT_WIDTH = 2.0**-36
"""The second try for the few ellipsoids whose pairs the first leaves uncertain: a Newton step
polishes the approximations, and enclosures this narrow separate sides down to relative gaps
of about ``1e-10`` (simple eigenvalues; a double one then fails and the pair escalates)."""

# Weyl: ||A - A^||_2 <= ||A - A^||_F <= u/(1-u) sum_ij |a^_ij|; the sum takes 5 roundings
# (every term non-negative: computed >= exact (1-u)^5) and the product one more.
WEYL = eb.round_up(_U / (1 - _U) / (1 - _U) ** 6)

INPUT_MIN = eb.INPUT_MIN
INPUT_MAX = eb.INPUT_MAX


# -- the closed-form approximations ----------------------------------------------------------------

APPROX_DEGREE = 12


def _fit(f: Any) -> tuple[float, ...]:
    """Power coefficients in ``t = 4x - 1`` of the Chebyshev interpolant of ``f`` on
    ``x in [0, 1/2]`` (lowest first)."""
    c = C.chebinterpolate(lambda t: f((np.asarray(t) + 1) / 4), APPROX_DEGREE)
    return tuple(float(v) for v in C.cheb2poly(c))


def _h(x: np.ndarray) -> np.ndarray:
    return np.cos(2 / 3 * np.arcsin(np.sqrt(x)))


def _g(x: np.ndarray) -> np.ndarray:
    s = np.sqrt(x)
    with np.errstate(all="ignore"):
        return np.where(s > 0, np.sin(2 / 3 * np.arcsin(s)) / np.where(s > 0, s, 1.0), 2 / 3)


H_COEFFS = _fit(_h)
G_COEFFS = _fit(_g)
_SQRT3 = math.sqrt(3.0)
_HALF_SQRT3 = _SQRT3 / 2


@jitable(inline=True)
def _horner(c: Any, t: Any) -> Any:
    """``sum c[k] t^k`` for the 13 coefficients of an approximation (unrolled, so that the
    compiled loops around it vectorise)."""
    acc = c[12] * t + c[11]
    acc = acc * t + c[10]
    acc = acc * t + c[9]
    acc = acc * t + c[8]
    acc = acc * t + c[7]
    acc = acc * t + c[6]
    acc = acc * t + c[5]
    acc = acc * t + c[4]
    acc = acc * t + c[3]
    acc = acc * t + c[2]
    acc = acc * t + c[1]
    return acc * t + c[0]


assert APPROX_DEGREE == 12


@jitable(inline=True)
def eigen_approx(a00: Any, a01: Any, a02: Any, a11: Any, a12: Any, a22: Any) -> Any:
    """Approximate eigenvalues ``l1 <= l2 <= l3`` of the symmetric 3x3 matrix (closed form,
    no trigonometric calls; see the module docstring).  Never trusted by the filter."""
    q = (a00 + a11 + a22) * (1.0 / 3.0)
    b00 = a00 - q
    b11 = a11 - q
    b22 = a22 - q
    p2 = b00 * b00 + b11 * b11 + b22 * b22 + 2.0 * (a01 * a01 + a02 * a02 + a12 * a12)
    p = np.sqrt(p2 * (1.0 / 6.0))
    det = b00 * (b11 * b22 - a12 * a12) - a01 * (a01 * b22 - a12 * a02) + a02 * (a01 * a12 - b11 * a02)
    den = 2.0 * p * p * p
    r = select(den > 0.0, det / select(den > 0.0, den, 1.0), 0.0)
    r = np.minimum(1.0, np.maximum(-1.0, r))
    x = (1.0 - np.abs(r)) * 0.5
    t = 4.0 * x - 1.0
    h = _horner(H_COEFFS, t)
    gs = np.sqrt(x) * _horner(G_COEFFS, t)
    # r >= 0: phi = (2/3) asin sqrt x; r < 0: phi = pi/3 - (2/3) asin sqrt x
    cphi = select(r >= 0.0, h, 0.5 * h + _HALF_SQRT3 * gs)
    sphi = select(r >= 0.0, gs, _HALF_SQRT3 * h - 0.5 * gs)
    l3 = q + 2.0 * p * cphi
    l1 = q - p * (cphi + _SQRT3 * sphi)
    l2 = q - p * (cphi - _SQRT3 * sphi)
    return l1, l2, l3


# -- the eigenvalue counts -------------------------------------------------------------------------


@jitable(inline=True)
def shift_invariants(b00, b01, b02, b11, b12, b22):  # type: ignore[no-untyped-def]
    """(tr, J, det) of the symmetric 3x3 matrix with upper entries bij (straight-line)."""
    tr = b00 + b11 + b22
    J = b00*b11 + b00*b22 - b01*b01 - b02*b02 + b11*b22 - b12*b12  # fmt: skip
    det = b00*(b11*b22 - b12*b12) - b01*(b01*b22 - b12*b02) + b02*(b01*b12 - b11*b02)  # fmt: skip
    return (tr, J, det)


@jitable(inline=True)
def shift_invariants_magnitude(b00, b01, b02, b11, b12, b22):  # type: ignore[no-untyped-def]
    """Magnitude companion of ``shift_invariants``: call it with the absolute values of the
    arguments; same operations in the same order, with every minus turned into a plus."""
    tr = b00 + b11 + b22
    J = b00*b11 + b00*b22 + b01*b01 + b02*b02 + b11*b22 + b12*b12  # fmt: skip
    det = b00*(b11*b22 + b12*b12) + b01*(b01*b22 + b12*b02) + b02*(b01*b12 + b11*b02)  # fmt: skip
    return (tr, J, det)


def _function_ast(fn: Any) -> ast.FunctionDef:
    node = ast.parse(inspect.getsource(fn)).body[0]
    assert isinstance(node, ast.FunctionDef)
    return node


def _shift_errbound() -> tuple[float, ...]:
    """``K`` for ``(tr, J, det)`` of ``B = A - t I``: ``|computed - exact| <= fl(K M)``.  The
    diagonal ``fl(a_ii - t)`` is a rounded input (the off-diagonal entries are exact, and
    counting them as rounded only enlarges the bound); the counts are read off the program
    text as :mod:`quadric_contact.codegen` reads the generated ones."""
    value = rounding_counts(_function_ast(shift_invariants), 1)
    magnitude = rounding_counts(_function_ast(shift_invariants_magnitude), 0)
    return tuple(
        eb.program_errbound(nv, nm, d, rounded_inputs=True)
        for (nv, d), (nm, dm) in zip(value, magnitude, strict=True)
        if d == dm
    )


SHIFT_ERRBOUND = _shift_errbound()
"""Error-bound constants of :func:`shift_invariants` (rounded inputs)."""
assert len(SHIFT_ERRBOUND) == 3

# The constants as tables read by the compiled code as constants (no array arguments, so no
# reference counting in the vectorised loops), indexed by int(certify) (the plain stage has
# zero bounds and no widening) and int(rounded).
_KINV = np.array(
    [[np.zeros(7), np.zeros(7)], [eb.INVARIANTS_ERRBOUND[False], eb.INVARIANTS_ERRBOUND[True]]],
    dtype=np.float64,
)
_KB = np.array(SHIFT_ERRBOUND)
_WIDEN = np.array([[np.ones(MAX_DEGREE + 1), np.ones(MAX_DEGREE + 1)], [CHAIN_DOWN, CHAIN_UP]])
_TABLES = kind_arrays()
_EXPS = _TABLES["exponents"]
_KSIGNS = _TABLES["signs"]
_COND = _TABLES["cond"]
_NCOND = _TABLES["ncond"]
_ALT = _TABLES["alt"]
_NALT = _TABLES["nalt"]

_inv = jitable(kernels.quadric_invariants, inline=True)
_inv_mag = jitable(kernels.quadric_invariants_magnitude, inline=True)


@jitable(inline=True)
def _shift_signs(a00: Any, a01: Any, a02: Any, a11: Any, a12: Any, a22: Any, t: Any) -> Any:
    """Signs of ``(tr B, J(B), det B)`` for ``B = A - t I``, certified (see the module docstring)."""
    b00 = a00 - t
    b11 = a11 - t
    b22 = a22 - t
    v = shift_invariants(b00, a01, a02, b11, a12, b22)
    m = shift_invariants_magnitude(
        np.abs(b00), np.abs(a01), np.abs(a02), np.abs(b11), np.abs(a12), np.abs(b22)
    )
    return (
        sign_within(v[0], _KB[0] * m[0]), sign_within(v[1], _KB[1] * m[1]), sign_within(v[2], _KB[2] * m[2])
    )  # fmt: skip


@jitable(inline=True)
def _in_range(x: Any) -> Any:
    a = np.abs(x)
    return (a >= INPUT_MIN) & (a <= INPUT_MAX)


@jitable(inline=True)
def _entry_ok(x: Any) -> Any:
    a = np.abs(x)
    return (a == 0.0) | ((a >= INPUT_MIN) & (a <= INPUT_MAX))


@jitable(inline=True)
def _entries_ok(a00: Any, a01: Any, a02: Any, a03: Any, a11: Any, a12: Any, a13: Any, a22: Any, a23: Any,
                a33: Any) -> Any:  # fmt: skip
    """Every entry zero or in ``[INPUT_MIN, INPUT_MAX]`` (the guard of the invariant bounds)."""
    return (
        _entry_ok(a00) & _entry_ok(a01) & _entry_ok(a02) & _entry_ok(a03) & _entry_ok(a11)
        & _entry_ok(a12) & _entry_ok(a13) & _entry_ok(a22) & _entry_ok(a23) & _entry_ok(a33)
    )  # fmt: skip


@jitable(inline=True)
def _below_at_most(s1: Any, s2: Any, s3: Any, j: int) -> Any:
    """Certainly at most ``j`` eigenvalues below ``t``, from the three-valued signs of
    ``(tr, J, det)`` of ``B = A - t I``.

    The count is Descartes' number of sign variations of ``(1, s1, s2, s3)`` (zeros skipped;
    exact, the characteristic polynomial being real-rooted).  An uncertain sign may be -1, 0 or
    1, independently: the count is certainly at most 0 when no sign can be negative, at most 1
    when no sign that can be negative comes before one that can be positive (two variations
    need a ``-`` followed by a ``+``), at most 2 unless the signs can be ``-, +, -``."""
    n1, n2, n3 = (
        (s1 == -1) | (s1 == UNCERTAIN),
        (s2 == -1) | (s2 == UNCERTAIN),
        (s3 == -1) | (s3 == UNCERTAIN),
    )
    p2, p3 = (s2 == 1) | (s2 == UNCERTAIN), (s3 == 1) | (s3 == UNCERTAIN)
    if j == 0:
        return ~(n1 | n2 | n3)
    if j == 1:
        return ~((n1 & (p2 | p3)) | (n2 & p3))
    return ~(n1 & p2 & n3)


@jitable(inline=True)
def _below_at_least(s1: Any, s2: Any, s3: Any, j: int) -> Any:
    """Certainly at least ``j`` eigenvalues below ``t``: the certain signs alone have ``j``
    variations (an adversary sets every uncertain sign to 0, which removes it)."""
    n1, n2, n3 = s1 == -1, s2 == -1, s3 == -1
    p2, p3 = s2 == 1, s3 == 1
    if j == 1:
        return n1 | n2 | n3
    if j == 2:
        return (n1 & (p2 | p3)) | (n2 & p3)
    return n1 & p2 & n3


@jitable(inline=True)
def _enclose(a00: Any, a01: Any, a02: Any, a11: Any, a12: Any, a22: Any, lam: Any, i: int, width: Any) -> Any:
    """``(lo, hi, ok)``: the ``i``-th eigenvalue (1-based, increasing) lies in ``[lo, hi]`` where
    ``ok``: at most ``i - 1`` eigenvalues below ``lo``, at least ``i`` below ``hi``.  (Below
    ``lo > 0`` none at all means ``A`` is positive definite: the ellipsoid test of ``E``.)"""
    w = np.abs(lam) * width
    lo = lam - w
    hi = lam + w
    s1, s2, s3 = _shift_signs(a00, a01, a02, a11, a12, a22, lo)
    ok = _below_at_most(s1, s2, s3, i - 1)
    s1, s2, s3 = _shift_signs(a00, a01, a02, a11, a12, a22, hi)
    ok = ok & _below_at_least(s1, s2, s3, i)
    return lo, hi, ok & _in_range(lo) & _in_range(hi)


@jitable(inline=True)
def _weyl(a00: Any, a01: Any, a02: Any, a11: Any, a12: Any, a22: Any) -> Any:
    """A bound of ``||A - A^||_2`` for the correctly rounded ``A^`` of an exact ``A``."""
    s = np.abs(a00) + np.abs(a11) + np.abs(a22) + 2.0 * np.abs(a01) + 2.0 * np.abs(a02) + 2.0 * np.abs(a12)
    return WEYL * s


@jitable(inline=True)
def _factor_ok(lo: Any, hi: Any) -> Any:
    return (lo >= FACTOR_MIN) & (hi <= FACTOR_MAX)


@jitable(inline=True)
def _bad(m: Any) -> Any:
    """True where an entry is not finite (``x * 0`` is NaN for inf and NaN) or the matrix
    (16 entries, row-major) is not symmetric.  Branch-free."""
    z = (
        m[0] * 0.0 + m[1] * 0.0 + m[2] * 0.0 + m[3] * 0.0 + m[4] * 0.0 + m[5] * 0.0 + m[6] * 0.0
        + m[7] * 0.0 + m[8] * 0.0 + m[9] * 0.0 + m[10] * 0.0 + m[11] * 0.0 + m[12] * 0.0 + m[13] * 0.0
        + m[14] * 0.0 + m[15] * 0.0
    )  # fmt: skip
    z = z + np.abs(m[1] - m[4]) + np.abs(m[2] - m[8]) + np.abs(m[3] - m[12])
    z = z + np.abs(m[6] - m[9]) + np.abs(m[7] - m[13]) + np.abs(m[11] - m[14])
    return ~(z == 0.0)


# -- per matrix ------------------------------------------------------------------------------------


@jitable(inline=True)
def _newton(v: Any, t: Any) -> Any:
    """One Newton step towards an eigenvalue on ``t^3 - tr t^2 + J t - det`` (``v``: the
    invariants ``(tr, J, det, ...)``); ``t`` unchanged where the derivative vanishes."""
    p = ((t - v[0]) * t + v[1]) * t - v[2]
    dp = (3.0 * t - 2.0 * v[0]) * t + v[1]
    return select(dp != 0.0, t - p / select(dp != 0.0, dp, 1.0), t)


@jitable(inline=True)
def _e_row(m: Any, certify: bool, rounded: bool, guard: Any, width: Any, polish: bool) -> Any:
    """The four squared sides of ``E`` (:data:`~quadric_contact.modes.smallness.tables.E_SIDES`:
    ``alpha^2``, ``(gamma/alpha^2)^2``, ``gamma^2``, ``(alpha/gamma^2)^2``) as intervals
    ``lo, hi``, and a status: 0 certain, 1 uncertain, INVALID (bad input, or ``E`` not
    certified (plain: not seen) as an ellipsoid; the caller diagnoses it).

    ``m``: the 16 entries row-major; ``guard``: the row's inputs are exact rationals whose
    rounding is no relative perturbation; ``width``: of the eigenvalue enclosures, relative
    (WIDTH, or TIGHT_WIDTH with ``polish``: one Newton step on the approximations first).
    With ``certify`` the ellipsoid is certified on the way: ``A - lo1 I`` positive definite
    with ``lo1 > 0`` and ``det E < 0``."""
    bad = _bad(m)
    o = select(m[0] < 0.0, -1.0, 1.0)
    a00, a01, a02, a03 = o * m[0], o * m[1], o * m[2], o * m[3]
    a11, a12, a13, a22, a23, a33 = o * m[5], o * m[6], o * m[7], o * m[10], o * m[11], o * m[15]
    v = _inv(a00, a01, a02, a03, a11, a12, a13, a22, a23, a33)
    l1, _, l3 = eigen_approx(a00, a01, a02, a11, a12, a22)
    if polish:
        l1 = _newton(v, l1)
        l3 = _newton(v, l3)
    if certify:
        mg = _inv_mag(
            np.abs(a00), np.abs(a01), np.abs(a02), np.abs(a03), np.abs(a11), np.abs(a12),
            np.abs(a13), np.abs(a22), np.abs(a23), np.abs(a33),
        )  # fmt: skip
        r = int(rounded)
        ep = _KINV[1, r, 6] * mg[6]
        ea = _KINV[1, r, 2] * mg[2]
        plo = -v[6] - ep
        phi = -v[6] + ep
        alo = v[2] - ea
        ahi = v[2] + ea
        # lambda_1 and lambda_3; every eigenvalue above lo1 > 0 certifies A positive definite
        lo1, hi1, ok1 = _enclose(a00, a01, a02, a11, a12, a22, l1, 1, width)
        lo3, hi3, ok3 = _enclose(a00, a01, a02, a11, a12, a22, l3, 3, width)
        ok = ok1 & ok3 & ~guard
        ok = ok & _entries_ok(a00, a01, a02, a03, a11, a12, a13, a22, a23, a33)
        eps = select(rounded, _weyl(a00, a01, a02, a11, a12, a22), 0.0)
        lo1 = lo1 - eps
        hi1 = hi1 + eps
        lo3 = lo3 - eps
        hi3 = hi3 + eps
        ellipsoid = ok & (m[0] != 0.0) & (lo1 > 0.0) & (plo > 0.0)
        ok = (
            ellipsoid
            & _factor_ok(plo, phi)
            & _factor_ok(alo, ahi)
            & _factor_ok(lo1, hi1)
            & _factor_ok(lo3, hi3)
        )
    else:
        plo = -v[6]
        phi = plo
        alo = v[2]
        ahi = alo
        lo1 = l1
        hi1 = l1
        lo3 = l3
        hi3 = l3
        ellipsoid = (m[0] != 0.0) & (l1 > 0.0) & (plo > 0.0) & (alo > 0.0)
        ok = ellipsoid
    # the monomials of E_SIDES, with their factors in primitive order (P, A3, L1, L3)
    c = int(certify)
    dn3, up3, dn5, up5 = _WIDEN[c, 0, 3], _WIDEN[c, 1, 3], _WIDEN[c, 0, 5], _WIDEN[c, 1, 5]
    al2_lo = (plo / (ahi * hi1)) * dn3
    al2_hi = (phi / (alo * lo1)) * up3
    ke_lo = ((alo * lo1 * lo1) / (phi * hi3)) * dn5
    ke_hi = ((ahi * hi1 * hi1) / (plo * lo3)) * up5
    ga2_lo = (plo / (ahi * hi3)) * dn3
    ga2_hi = (phi / (alo * lo3)) * up3
    ak_lo = ((alo * lo3 * lo3) / (phi * hi1)) * dn5
    ak_hi = ((ahi * hi3 * hi3) / (plo * lo1)) * up5
    status = select(bad | ~ellipsoid, INVALID, select(ok, 0, 1))
    return status, al2_lo, al2_hi, ke_lo, ke_hi, ga2_lo, ga2_hi, ak_lo, ak_hi


_MAX_POWER = 3
"""The largest exponent of a primitive in a monomial."""
assert max(abs(e) for m in (*E_SIDES, *(m for v in Q_SIDES.values() for m in v)) for e in m) <= _MAX_POWER


@jitable(inline=True)
def _power(x: Any, e: Any) -> Any:
    """``x^e`` for ``e`` in ``0 .. 3`` by repeated multiplication (``e - 1`` roundings; 1 exactly for 0)."""
    x2 = x * x
    return select(e == 1, x, select(e == 2, x2, select(e == 3, x2 * x, 1.0)))


@jitable(inline=True)
def _monomial(lo: Any, hi: Any, kind: Any, slot: int) -> Any:
    """``(lo, hi, k)`` of the monomial of ``Q_SIDES`` for ``kind`` and ``slot`` over the
    primitive intervals ``lo``, ``hi`` (9-tuples), before the final widening; ``k`` its number of
    factors.  Numerator and denominator take ``k_num - 1`` and ``k_den - 1`` roundings (a
    factor 1 is exact), the quotient one more: ``k - 1`` in all, as CHAIN_DOWN and CHAIN_UP
    assume.  Unrolled over the primitives, so that the compiled loops vectorise."""
    e0, e1, e2 = _EXPS[kind, slot, 0], _EXPS[kind, slot, 1], _EXPS[kind, slot, 2]
    e3, e4, e5 = _EXPS[kind, slot, 3], _EXPS[kind, slot, 4], _EXPS[kind, slot, 5]
    e6, e7, e8 = _EXPS[kind, slot, 6], _EXPS[kind, slot, 7], _EXPS[kind, slot, 8]
    p0, p1, p2, p3, p4 = (
        np.maximum(e0, 0),
        np.maximum(e1, 0),
        np.maximum(e2, 0),
        np.maximum(e3, 0),
        np.maximum(e4, 0),
    )
    p5, p6, p7, p8 = np.maximum(e5, 0), np.maximum(e6, 0), np.maximum(e7, 0), np.maximum(e8, 0)
    n0, n1, n2, n3, n4 = (
        np.maximum(-e0, 0),
        np.maximum(-e1, 0),
        np.maximum(-e2, 0),
        np.maximum(-e3, 0),
        np.maximum(-e4, 0),
    )
    n5, n6, n7, n8 = np.maximum(-e5, 0), np.maximum(-e6, 0), np.maximum(-e7, 0), np.maximum(-e8, 0)
    num_lo = _power(lo[0], p0) * _power(lo[1], p1) * _power(lo[2], p2) * _power(lo[3], p3) * _power(lo[4], p4)
    num_lo = num_lo * _power(lo[5], p5) * _power(lo[6], p6) * _power(lo[7], p7) * _power(lo[8], p8)
    num_hi = _power(hi[0], p0) * _power(hi[1], p1) * _power(hi[2], p2) * _power(hi[3], p3) * _power(hi[4], p4)
    num_hi = num_hi * _power(hi[5], p5) * _power(hi[6], p6) * _power(hi[7], p7) * _power(hi[8], p8)
    den_lo = _power(lo[0], n0) * _power(lo[1], n1) * _power(lo[2], n2) * _power(lo[3], n3) * _power(lo[4], n4)
    den_lo = den_lo * _power(lo[5], n5) * _power(lo[6], n6) * _power(lo[7], n7) * _power(lo[8], n8)
    den_hi = _power(hi[0], n0) * _power(hi[1], n1) * _power(hi[2], n2) * _power(hi[3], n3) * _power(hi[4], n4)
    den_hi = den_hi * _power(hi[5], n5) * _power(hi[6], n6) * _power(hi[7], n7) * _power(hi[8], n8)
    k = p0 + p1 + p2 + p3 + p4 + p5 + p6 + p7 + p8 + n0 + n1 + n2 + n3 + n4 + n5 + n6 + n7 + n8
    return num_lo / den_hi, num_hi / den_lo, k


@jitable(inline=True)
def _invariant_primitive(v: Any, mg: Any, j: int, kind: Any, certify: bool, rounded: bool) -> Any:
    """``(lo, hi, ok)``: primitive ``j`` (``P .. T``) of ``kind``, the signed invariant with its
    bound (1 for a primitive the kind does not use)."""
    inv = _INVARIANT_OF_PRIMITIVE[j]
    sg = _KSIGNS[kind, j]
    val = sg * v[inv]
    err = _KINV[int(certify), int(rounded), inv] * mg[inv]
    lo = val - err
    hi = val + err
    need = sg != 0
    ok = ~need | _factor_ok(lo, hi) | (not certify)
    return select(need, lo, 1.0), select(need, hi, 1.0), ok


@jitable(inline=True)
def _eigen_primitive(
    a00: Any, a01: Any, a02: Any, a11: Any, a12: Any, a22: Any, lam: Any, i: int, kind: Any, certify: bool,
    eps: Any, bad: Any, width: Any,
) -> Any:  # fmt: skip
    """``(lo, hi, ok)``: ``|lambda_i|`` (1-based, increasing) for ``kind`` (1 if unused)."""
    sg = _KSIGNS[kind, 5 + i]
    need = sg != 0
    if certify:
        lo, hi, good = _enclose(a00, a01, a02, a11, a12, a22, lam, i, width)
        lo = lo - eps
        hi = hi + eps
    else:
        lo = lam
        hi = lam
        good = ~bad | bad
    alo = select(sg > 0, lo, -hi)
    ahi = select(sg > 0, hi, -lo)
    ok = ~need | (good & _factor_ok(alo, ahi)) | (not certify)
    return select(need, alo, 1.0), select(need, ahi, 1.0), ok


@jitable(inline=True)
def _q_row(
    m: Any, kind: Any, sign: Any, certify: bool, rounded: bool, guard: Any, width: Any, polish: bool
) -> Any:  # fmt: skip
    """The squared sides of ``Q`` (:data:`~quadric_contact.modes.smallness.tables.Q_SIDES`,
    up to four slots, as intervals) for its Table 1 ``kind`` (index into TABLE_1_KINDS) with
    canonical ``sign``, and a status (0 certain, 1 uncertain, INVALID for bad input)."""
    bad = _bad(m)
    s = sign * 1.0
    a00, a01, a02, a03 = s * m[0], s * m[1], s * m[2], s * m[3]
    a11, a12, a13, a22, a23, a33 = s * m[5], s * m[6], s * m[7], s * m[10], s * m[11], s * m[15]
    v = _inv(a00, a01, a02, a03, a11, a12, a13, a22, a23, a33)
    l1, l2, l3 = eigen_approx(a00, a01, a02, a11, a12, a22)
    if polish:
        l1 = _newton(v, l1)
        l2 = _newton(v, l2)
        l3 = _newton(v, l3)
    if certify:
        mg = _inv_mag(
            np.abs(a00), np.abs(a01), np.abs(a02), np.abs(a03), np.abs(a11), np.abs(a12),
            np.abs(a13), np.abs(a22), np.abs(a23), np.abs(a33),
        )  # fmt: skip
        ok = _entries_ok(a00, a01, a02, a03, a11, a12, a13, a22, a23, a33) & ~guard
        eps = select(rounded, _weyl(a00, a01, a02, a11, a12, a22), 0.0)
    else:
        mg = v
        ok = ~bad | bad
        eps = 0.0 * a00
    lo0, hi0, ok0 = _invariant_primitive(v, mg, 0, kind, certify, rounded)
    lo1, hi1, ok1 = _invariant_primitive(v, mg, 1, kind, certify, rounded)
    lo2, hi2, ok2 = _invariant_primitive(v, mg, 2, kind, certify, rounded)
    lo3, hi3, ok3 = _invariant_primitive(v, mg, 3, kind, certify, rounded)
    lo4, hi4, ok4 = _invariant_primitive(v, mg, 4, kind, certify, rounded)
    lo5, hi5, ok5 = _invariant_primitive(v, mg, 5, kind, certify, rounded)
    lo6, hi6, ok6 = _eigen_primitive(a00, a01, a02, a11, a12, a22, l1, 1, kind, certify, eps, bad, width)
    lo7, hi7, ok7 = _eigen_primitive(a00, a01, a02, a11, a12, a22, l2, 2, kind, certify, eps, bad, width)
    lo8, hi8, ok8 = _eigen_primitive(a00, a01, a02, a11, a12, a22, l3, 3, kind, certify, eps, bad, width)
    ok = ok & ok0 & ok1 & ok2 & ok3 & ok4 & ok5 & ok6 & ok7 & ok8
    los = (lo0, lo1, lo2, lo3, lo4, lo5, lo6, lo7, lo8)
    his = (hi0, hi1, hi2, hi3, hi4, hi5, hi6, hi7, hi8)
    s0lo, s0hi, k0 = _monomial(los, his, kind, 0)
    s1lo, s1hi, k1 = _monomial(los, his, kind, 1)
    s2lo, s2hi, k2 = _monomial(los, his, kind, 2)
    s3lo, s3hi, k3 = _monomial(los, his, kind, 3)
    status = select(bad, INVALID, select(ok, 0, 1))
    c = int(certify)
    return (
        status, s0lo * _WIDEN[c, 0, k0], s0hi * _WIDEN[c, 1, k0], s1lo * _WIDEN[c, 0, k1],
        s1hi * _WIDEN[c, 1, k1], s2lo * _WIDEN[c, 0, k2], s2hi * _WIDEN[c, 1, k2], s3lo * _WIDEN[c, 0, k3],
        s3hi * _WIDEN[c, 1, k3],
    )  # fmt: skip


_INVARIANT_OF_PRIMITIVE = (6, 2, 1, 5, 4, 0)
"""The output of ``quadric_invariants`` (``trA, JA, detA, E1, E2, E3, E4``) behind the primitives
``P, A3, J2, K3, J1, T`` (see :mod:`~quadric_contact.modes.smallness.tables`)."""


# -- per pair --------------------------------------------------------------------------------------


@jitable(inline=True)
def _compare(qlo: Any, qhi: Any, elo: Any, ehi: Any, rel: Any) -> Any:
    """Three-valued ``Q >= E`` (``rel == 0``) or ``Q <= E`` (``rel == 1``) on intervals:
    1 holds, 0 fails, 2 uncertain."""
    ge = select(qlo >= ehi, 1, select(qhi < elo, 0, UNCERTAIN))
    le = select(qhi <= elo, 1, select(qlo > ehi, 0, UNCERTAIN))
    return select(rel == 0, ge, le)


@jitable(inline=True)
def _and3(a: Any, b: Any) -> Any:
    return select((a == 0) | (b == 0), 0, select((a == 1) & (b == 1), 1, UNCERTAIN))


@jitable(inline=True)
def _pick(values: Any, k: Any) -> Any:
    """``values[k]`` for an 8-tuple and ``k`` a scalar or one index per pair (a select chain)."""
    out = values[7]
    for j in range(6, -1, -1):
        out = select(k == j, values[j], out)
    return out


@jitable(inline=True)
def _conjunction(qv: Any, ev: Any, conds: Any, n: Any, kind: Any, width: int) -> Any:
    """All of the first ``n`` conditions ``conds[kind, c] = (q_slot, e_slot, relation)``, ``c <
    width`` (a constant, so that the compiled loop unrolls), three-valued.  ``qv``, ``ev``: the
    sides of the quadric and of the ellipsoid, 8-tuples ``(lo, hi)`` by slot."""
    acc = select(kind == kind, 1, 1)
    for c in range(width):
        qs = conds[kind, c, 0]
        es = conds[kind, c, 1]
        r = _compare(_pick(qv, 2 * qs), _pick(qv, 2 * qs + 1), _pick(ev, 2 * es), _pick(ev, 2 * es + 1),
                     conds[kind, c, 2])  # fmt: skip
        acc = select(c < n, _and3(acc, r), acc)
    return acc


@jitable(inline=True)
def _verdict(inner: Any, outer: Any) -> Any:
    """The code from the three-valued direct conditions and enclosing alternative."""
    return select(
        inner == 1, 1, select(inner == 0, select(outer == 1, 4, select(outer == 0, 0, UNCERTAIN)), UNCERTAIN)
    )


@jitable(inline=True)
def _pair_code(est: Any, ev: Any, qst: Any, qv: Any, qkind: Any) -> Any:
    """:class:`~quadric_contact.modes.codes.SmallnessCode` of a pair from its rows' statuses and
    sides (8-tuples; ``qkind``: index into TABLE_1_KINDS, -1 excluded, -2 uncertain); INVALID
    when a row is."""
    k = np.maximum(qkind, 0)
    inner = _conjunction(qv, ev, _COND, _NCOND[k], k, MAX_CONDITIONS)
    outer = select(_NALT[k] > 0, _conjunction(qv, ev, _ALT, _NALT[k], k, MAX_ALTERNATIVE), 0)
    code = _verdict(inner, outer)
    code = select((est == 1) | (qst == 1) | (qkind == -2), UNCERTAIN, code)
    code = select(qkind == -1, EXCLUDED, code)
    return select((est == INVALID) | (qst == INVALID), INVALID, code)


_FIXED = MAX_CONDITIONS + MAX_ALTERNATIVE
assert _FIXED == 5  # the fused loop unpacks five conditions


def fixed_conditions(qst: int, qkind: int, qv: np.ndarray) -> tuple[np.ndarray, ...]:
    """The decision against one quadric, resolved once: ``(code, offsets, q, relations, groups)``
    with ``code`` the answer for every valid ellipsoid when it does not depend on it (-1
    otherwise), and per condition the offset of the ellipsoid's side in the block buffer, the
    quadric's side ``[lo, hi]``, the relation and the group (0 direct, 1 enclosing, 2 none)."""
    offsets = np.zeros(_FIXED, dtype=np.int64)
    q = np.ones((_FIXED, 2))
    relations = np.zeros(_FIXED, dtype=np.int64)
    groups = np.full(_FIXED, 2, dtype=np.int64)
    if qst == INVALID:
        code = INVALID
    elif qkind == -1:
        code = EXCLUDED
    elif qst == 1 or qkind == -2:
        code = UNCERTAIN
    else:
        code = -1
        rows = [(c, 0) for c in _COND[qkind, : _NCOND[qkind]]] + [(c, 1) for c in _ALT[qkind, : _NALT[qkind]]]
        for j, ((qs, es, rel), group) in enumerate(rows):
            offsets[j] = (2 * es + 1) * _NB
            q[j] = qv[2 * qs], qv[2 * qs + 1]
            relations[j] = rel
            groups[j] = group
    return np.array([code], dtype=np.int64), offsets, q, relations, groups


@jitable(inline=True)
def _only(r: Any, group: Any, wanted: int) -> Any:
    """A condition's value within its group; true (neutral for the conjunction) outside it."""
    return select(group == wanted, r, 1)


@jitable(inline=True)
def _fixed_code(est: Any, e: Any, code: Any, q: Any, relations: Any, groups: Any) -> Any:
    """:func:`_pair_code` against the one quadric of :func:`fixed_conditions`: ``e`` the
    ellipsoid's side ``(lo, hi)`` of each condition, ``q`` the quadric's (flat tuples)."""
    r0 = _compare(q[0], q[1], e[0], e[1], relations[0])
    r1 = _compare(q[2], q[3], e[2], e[3], relations[1])
    r2 = _compare(q[4], q[5], e[4], e[5], relations[2])
    r3 = _compare(q[6], q[7], e[6], e[7], relations[3])
    r4 = _compare(q[8], q[9], e[8], e[9], relations[4])
    inner = _and3(_and3(_and3(_only(r0, groups[0], 0), _only(r1, groups[1], 0)), _only(r2, groups[2], 0)),
                  _and3(_only(r3, groups[3], 0), _only(r4, groups[4], 0)))  # fmt: skip
    outer = _and3(_and3(_and3(_only(r0, groups[0], 1), _only(r1, groups[1], 1)), _only(r2, groups[2], 1)),
                  _and3(_only(r3, groups[3], 1), _only(r4, groups[4], 1)))  # fmt: skip
    alt = (groups[0] == 1) | (groups[1] == 1) | (groups[2] == 1) | (groups[3] == 1) | (groups[4] == 1)
    out = _verdict(inner, select(alt, outer, 0))
    out = select(est == 1, UNCERTAIN, out)
    out = select(code >= 0, code, out)
    return select(est == INVALID, INVALID, out)


# -- loops (run compiled) --------------------------------------------------------------------------
#
# The loops are kernels without a Python twin (``njit(twin=False)``: a twin would run them row by
# row): cached, keyed on every source they inline, and run natively where the library of native
# kernels has them.  Every helper above they call by name is inlined as its compiled side.

_NB = 256
"""Rows per block of the compiled loops (row ``k`` of a block buffer at ``k * _NB``)."""


@njit(twin=False)
def _e_rows_loop(
    M: Any, rows: Any, lo: int, hi: int, certify: bool, rounded: bool, guard: Any, width: float, polish: bool,
    out_s: Any, out_v: Any,
) -> None:  # fmt: skip
    """The sides of the ellipsoids ``M[rows[k]]`` (``M[k]`` when ``rows`` is empty), ``k`` in
    ``lo .. hi``, in blocks: gather the entries into column buffers, compute in a
    straight-line (vectorised) loop, scatter."""
    eb_ = np.empty(16 * _NB)
    gb = np.zeros(_NB, dtype=np.bool_)
    ob = np.empty(9 * _NB)
    for blo in range(lo, hi, _NB):
        m = min(_NB, hi - blo)
        for t in range(m):
            r = rows[blo + t] if rows.shape[0] > 0 else blo + t
            for k in range(16):
                eb_[k * _NB + t] = M[r, k]
            gb[t] = guard[blo + t]
        _e_block(eb_, gb, m, certify, rounded, width, polish, ob)
        for t in range(m):
            out_s[blo + t] = np.int8(ob[t])
        for k in range(8):
            for t in range(m):
                out_v[k, blo + t] = ob[(k + 1) * _NB + t]


@njit(twin=False)
def _e_block(
    eb_: Any, gb: Any, m: int, certify: bool, rounded: bool, width: float, polish: bool, ob: Any
) -> None:  # fmt: skip
    """The straight-line loop over one gathered block of ellipsoids (status, then the 8 ends)."""
    for i in range(m):
        mm = (
            eb_[i], eb_[_NB + i], eb_[2 * _NB + i], eb_[3 * _NB + i], eb_[4 * _NB + i], eb_[5 * _NB + i],
            eb_[6 * _NB + i], eb_[7 * _NB + i], eb_[8 * _NB + i], eb_[9 * _NB + i], eb_[10 * _NB + i],
            eb_[11 * _NB + i], eb_[12 * _NB + i], eb_[13 * _NB + i], eb_[14 * _NB + i], eb_[15 * _NB + i],
        )  # fmt: skip
        st, v0, v1, v2, v3, v4, v5, v6, v7 = _e_row(mm, certify, rounded, gb[i], width, polish)
        ob[i] = st
        ob[_NB + i] = v0
        ob[2 * _NB + i] = v1
        ob[3 * _NB + i] = v2
        ob[4 * _NB + i] = v3
        ob[5 * _NB + i] = v4
        ob[6 * _NB + i] = v5
        ob[7 * _NB + i] = v6
        ob[8 * _NB + i] = v7


@njit(twin=False)
def _q_rows_loop(
    M: Any, rows: Any, kinds: Any, signs_: Any, lo: int, hi: int, certify: bool, rounded: bool, guard: Any,
    width: float, polish: bool, out_s: Any, out_v: Any,
) -> None:  # fmt: skip
    """The sides of the quadrics ``M[rows[k]]``, ``k`` in ``lo .. hi``, in blocks (as the
    ellipsoids': gather, a straight-line loop, scatter)."""
    qb = np.empty(16 * _NB)
    kb_ = np.empty(_NB, dtype=np.int64)
    sb = np.empty(_NB, dtype=np.int64)
    gb = np.zeros(_NB, dtype=np.bool_)
    ob = np.empty(9 * _NB)
    for blo in range(lo, hi, _NB):
        m = min(_NB, hi - blo)
        for t in range(m):
            r = rows[blo + t]
            for k in range(16):
                qb[k * _NB + t] = M[r, k]
            kb_[t] = max(kinds[blo + t], 0)
            sb[t] = signs_[blo + t]
            gb[t] = guard[blo + t]
        for i in range(m):
            mm = (
                qb[i], qb[_NB + i], qb[2 * _NB + i], qb[3 * _NB + i], qb[4 * _NB + i], qb[5 * _NB + i],
                qb[6 * _NB + i], qb[7 * _NB + i], qb[8 * _NB + i], qb[9 * _NB + i], qb[10 * _NB + i],
                qb[11 * _NB + i], qb[12 * _NB + i], qb[13 * _NB + i], qb[14 * _NB + i], qb[15 * _NB + i],
            )  # fmt: skip
            row = _q_row(mm, kb_[i], sb[i], certify, rounded, gb[i], width, polish)
            st, v0, v1, v2, v3, v4, v5, v6, v7 = row
            ob[i] = st
            ob[_NB + i] = v0
            ob[2 * _NB + i] = v1
            ob[3 * _NB + i] = v2
            ob[4 * _NB + i] = v3
            ob[5 * _NB + i] = v4
            ob[6 * _NB + i] = v5
            ob[7 * _NB + i] = v6
            ob[8 * _NB + i] = v7
        for t in range(m):
            out_s[blo + t] = np.int8(ob[t])
        for k in range(8):
            for t in range(m):
                out_v[k, blo + t] = ob[(k + 1) * _NB + t]


@njit(twin=False)
def _pairs_loop(
    eidx: Any, qidx: Any, es: int, qs: int, lo: int, hi: int, est: Any, ev: Any, qst: Any, qkind: Any,
    qv: Any, out: Any,
) -> None:  # fmt: skip
    for p in range(lo, hi):
        ie = eidx[p] if eidx.shape[0] > 0 else p * es
        iq = qidx[p] if qidx.shape[0] > 0 else p * qs
        e = (ev[0, ie], ev[1, ie], ev[2, ie], ev[3, ie], ev[4, ie], ev[5, ie], ev[6, ie], ev[7, ie])
        q = (qv[0, iq], qv[1, iq], qv[2, iq], qv[3, iq], qv[4, iq], qv[5, iq], qv[6, iq], qv[7, iq])
        out[p] = _pair_code(est[ie], e, qst[iq], q, qkind[iq])


@njit(twin=False)
def _fused_loop(
    E: Any, eidx: Any, lo: int, hi: int, certify: bool, rounded: bool, guard: Any, qidx: Any, qs: int,
    qst: Any, qkind: Any, qv: Any, fixed_code: Any, offsets: Any, fq: Any, relations: Any, groups: Any,
    out: Any,
) -> None:  # fmt: skip
    """Pairs ``lo .. hi`` whose ellipsoids are all distinct (pair ``p`` uses ``E[eidx[p]]``, or
    ``E[p]`` when ``eidx`` is empty: the paper's many ellipsoids against an environment): each
    block computes its ellipsoids' sides into block buffers and decides the pairs against the
    quadrics' precomputed sides; nothing per ellipsoid goes to memory.  ``guard`` is per pair."""
    eb_ = np.empty(16 * _NB)
    gb = np.zeros(_NB, dtype=np.bool_)
    ob = np.empty(9 * _NB)
    single = qidx.shape[0] == 0 and qs == 0
    # the one quadric's conditions, as scalars (arrays passed on would be reference-counted)
    o0, o1, o2, o3, o4 = offsets[0], offsets[1], offsets[2], offsets[3], offsets[4]
    fqt = (fq[0, 0], fq[0, 1], fq[1, 0], fq[1, 1], fq[2, 0], fq[2, 1], fq[3, 0], fq[3, 1], fq[4, 0], fq[4, 1])
    rels = (relations[0], relations[1], relations[2], relations[3], relations[4])
    grps = (groups[0], groups[1], groups[2], groups[3], groups[4])
    code = fixed_code[0]
    for blo in range(lo, hi, _NB):
        m = min(_NB, hi - blo)
        for t in range(m):
            r = eidx[blo + t] if eidx.shape[0] > 0 else blo + t
            for k in range(16):
                eb_[k * _NB + t] = E[r, k]
            gb[t] = guard[blo + t] if guard.shape[0] > 0 else False
        _e_block(eb_, gb, m, certify, rounded, WIDTH, False, ob)
        if single:  # one quadric for every pair: a short loop that vectorises
            for t in range(m):
                sides = (
                    ob[o0 + t], ob[o0 + _NB + t], ob[o1 + t], ob[o1 + _NB + t], ob[o2 + t], ob[o2 + _NB + t],
                    ob[o3 + t], ob[o3 + _NB + t], ob[o4 + t], ob[o4 + _NB + t],
                )  # fmt: skip
                out[blo + t] = _fixed_code(ob[t], sides, code, fqt, rels, grps)
        else:
            for t in range(m):
                p = blo + t
                iq = qidx[p] if qidx.shape[0] > 0 else p * qs
                e = (
                    ob[_NB + t], ob[2 * _NB + t], ob[3 * _NB + t], ob[4 * _NB + t], ob[5 * _NB + t],
                    ob[6 * _NB + t], ob[7 * _NB + t], ob[8 * _NB + t],
                )  # fmt: skip
                q = (qv[0, iq], qv[1, iq], qv[2, iq], qv[3, iq], qv[4, iq], qv[5, iq], qv[6, iq], qv[7, iq])
                out[p] = _pair_code(ob[t], e, qst[iq], q, qkind[iq])


# -- drivers ---------------------------------------------------------------------------------------


def _use_numba(backend: str) -> bool:
    if backend not in ("numba", "numpy"):
        choices = ("numba", "numpy")
        raise ChoiceError(f"backend must be one of numba, numpy, got {backend!r}", backend, choices=choices)
    return backend == "numba" and HAVE_NUMBA


def _flat(stack: MatrixStack) -> np.ndarray:
    return np.ascontiguousarray(stack.floats).reshape(-1, 16)


def _guard(stack: MatrixStack, rows: np.ndarray | None) -> np.ndarray:
    """Per row: exact input with a non-zero entry that rounds to zero (its rounding is then no
    relative perturbation, which the bounds for rounded inputs assume)."""
    n = len(stack) if rows is None else rows.size
    if stack.exact is None:
        return np.zeros(n, dtype=np.bool_)

    idx = slice(None) if rows is None else rows
    exact = stack.exact[idx]
    floats = stack.floats[idx]
    upper = np.stack([floats[:, i, j] for i, j in ENTRY_INDICES], axis=1)
    return np.asarray(((upper == 0.0) & (exact != 0)).any(axis=1), dtype=np.bool_)


def e_row_quantities(
    stack: MatrixStack, rows: np.ndarray | None, *, certify: bool, backend: str = "numba",
    threads: int | None = None, width: float = WIDTH, polish: bool = False,
) -> tuple[np.ndarray, np.ndarray]:  # fmt: skip
    """``(status, values)`` of the ellipsoids ``rows`` of ``stack`` (all when None): status 0
    certain, 1 uncertain, INVALID; values ``(8, k)``: ``[lo, hi]`` of the four squared sides of
    :data:`~quadric_contact.modes.smallness.tables.E_SIDES`.  ``width``, ``polish``: see
    :data:`TIGHT_WIDTH`."""
    M = _flat(stack)
    n = len(stack) if rows is None else rows.size
    ridx = np.zeros(0, dtype=np.intp) if rows is None else np.ascontiguousarray(rows, dtype=np.intp)
    guard = _guard(stack, rows)
    out_s = np.empty(n, dtype=np.int8)
    out_v = np.empty((8, n))
    if _use_numba(backend):
        run_parallel(
            lambda lo, hi: _e_rows_loop(
                M, ridx, lo, hi, certify, stack.rounded, guard, width, polish, out_s, out_v
            ),
            n,
            threads,
        )
        return out_s, out_v
    sub = M if rows is None else M[ridx]
    with np.errstate(all="ignore"):
        st, *vals = _e_row([sub[:, k] for k in range(16)], certify, stack.rounded, guard, width, polish)
    out_s[:] = st
    out_v[:] = np.stack(vals)
    return out_s, out_v


def q_row_quantities(
    stack: MatrixStack, rows: np.ndarray, kinds: np.ndarray, signs: np.ndarray, *, certify: bool,
    backend: str = "numba", width: float = WIDTH, polish: bool = False,
) -> tuple[np.ndarray, np.ndarray]:  # fmt: skip
    """``(status, values)`` of the quadrics ``rows`` of Table 1 types ``kinds`` (indices into
    TABLE_1_KINDS; the sides of a negative entry are meaningless) with canonical signs
    ``signs``: values ``(8, k)``, ``[lo, hi]`` of the (up to four) squared sides of
    :data:`~quadric_contact.modes.smallness.tables.Q_SIDES`."""
    M = _flat(stack)
    n = rows.size
    ridx = np.ascontiguousarray(rows, dtype=np.intp)
    guard = _guard(stack, ridx)
    kinds = np.ascontiguousarray(kinds, dtype=np.int64)
    signs = np.ascontiguousarray(signs, dtype=np.int64)
    out_s = np.empty(n, dtype=np.int8)
    out_v = np.empty((8, n))
    if _use_numba(backend):
        run_parallel(
            lambda lo, hi: _q_rows_loop(
                M, ridx, kinds, signs, lo, hi, certify, stack.rounded, guard, width, polish, out_s, out_v
            ),
            n,
        )
        return out_s, out_v
    sub = M[ridx]
    with np.errstate(all="ignore"):
        columns = [sub[:, k] for k in range(16)]
        st, *vals = _q_row(columns, np.maximum(kinds, 0), signs, certify, stack.rounded, guard, width, polish)
    out_s[:] = st
    out_v[:] = np.stack(vals)
    return out_s, out_v


def _row_map(index: np.ndarray | None, m: int, n: int) -> tuple[np.ndarray | None, np.ndarray, int]:
    """``(rows, pair_index, stride)``: the distinct rows the pairs use (None: all ``m``, pair ``p``
    uses row ``p``) and where pair ``p`` finds its row among them (``pair_index[p]``, or
    ``p * stride`` when ``pair_index`` is empty)."""
    empty = np.zeros(0, dtype=np.intp)
    if index is None:
        if m == n:
            return None, empty, 1
        return np.zeros(1, dtype=np.intp), empty, 0
    rows, inverse = unique_rows(index, m, return_inverse=True)
    return rows, inverse, 0


def pair_codes(
    est: np.ndarray, ev: np.ndarray, qst: np.ndarray, qkind: np.ndarray, qv: np.ndarray, eidx: np.ndarray,
    qidx: np.ndarray, es: int, qs: int, n: int, *, backend: str = "numba", threads: int | None = None,
) -> np.ndarray:  # fmt: skip
    """Codes of ``n`` pairs from the rows' quantities (INVALID where a row is)."""
    out = np.empty(n, dtype=np.int8)
    if n == 0:
        return out
    qkind = np.ascontiguousarray(qkind, dtype=np.int64)
    if _use_numba(backend):
        run_parallel(
            lambda lo, hi: _pairs_loop(eidx, qidx, es, qs, lo, hi, est, ev, qst, qkind, qv, out), n, threads
        )
        return out
    p = np.arange(n)
    ie = eidx if eidx.size else p * es
    iq = qidx if qidx.size else p * qs
    out[:] = _pair_code(est[ie], tuple(ev[:, ie]), qst[iq], tuple(qv[:, iq]), qkind[iq])
    return out


def _fused_codes(
    E: MatrixStack, eidx: np.ndarray, qst: np.ndarray, qkind: np.ndarray, qv: np.ndarray, qidx: np.ndarray,
    qs: int, n: int, *, certify: bool, threads: int | None,
) -> np.ndarray:  # fmt: skip
    """Codes of ``n`` pairs whose ellipsoids are distinct rows of ``E`` (``eidx``, or all rows
    in order when empty), with their sides computed in the pair loop (:func:`_fused_loop`)."""
    guard = _guard(E, eidx if eidx.size else None) if E.rounded else np.zeros(0, dtype=np.bool_)
    M = _flat(E)
    qkind = np.ascontiguousarray(qkind, dtype=np.int64)
    out = np.empty(n, dtype=np.int8)
    fixed = fixed_conditions(int(qst[0]), int(qkind[0]), qv[:, 0])
    run_parallel(
        lambda lo, hi: _fused_loop(
            M, eidx, lo, hi, certify, E.rounded, guard, qidx, qs, qst, qkind, qv, *fixed, out
        ),
        n,
        threads,
    )
    return out


def _distinct(index: np.ndarray | None) -> bool:
    """The pairs' rows are distinct because they increase (a sub-batch taken in order)."""
    if index is None:
        return False
    index = np.asarray(index).reshape(-1)
    return index.size < 2 or bool((index[1:] > index[:-1]).all())


def float_smallness(
    pairs: Pairs, *, certify: bool, classify: Any, backend: str = "numba", threads: int | None = None
) -> np.ndarray:
    """:class:`~quadric_contact.modes.codes.SmallnessCode` of every pair in binary64, certified
    (``UNCERTAIN`` where unsure) or plain; INVALID where an input needs diagnosing.
    ``classify`` is the mode's :meth:`~quadric_contact.modes.numbers.number_mode.NumberMode.classify`."""
    n = pairs.n
    if n == 0:
        return np.empty(0, dtype=np.int8)
    q_rows, qidx, qs = _row_map(pairs.q_index, len(pairs.Q), n)
    rows_q = np.arange(len(pairs.Q), dtype=np.intp) if q_rows is None else q_rows
    kinds, signs = table_kinds(classify(pairs.Q, rows_q))
    if certify:
        # The exact types, once per quadric (integer arithmetic), where the filter's are
        # uncertain or untrustworthy (an exact entry rounded to zero looks like an exact zero).
        unsure = np.flatnonzero((kinds == -2) | _guard(pairs.Q, rows_q))
        if unsure.size:
            kinds[unsure], signs[unsure] = table_kinds(exact_facts(pairs.Q, rows_q[unsure])[1])
    qst, qv = q_row_quantities(pairs.Q, rows_q, kinds, signs, certify=certify, backend=backend)
    if certify:
        _refine(pairs.Q, rows_q, qst, qv, kinds, signs)
    if rows_q.size == 1:
        qidx, qs = np.zeros(0, dtype=np.intp), 0  # one quadric for every pair
    if _use_numba(backend) and (_distinct(pairs.e_index) or (pairs.e_index is None and len(pairs.E) == n)):
        # distinct ellipsoids (all of E, or a sub-batch of them taken in order): their sides are
        # computed inside the pair loop, never stored
        eidx = np.zeros(0, dtype=np.intp) if pairs.e_index is None else np.asarray(pairs.e_index, np.intp)
        codes = _fused_codes(pairs.E, eidx, qst, kinds, qv, qidx, qs, n, certify=certify, threads=threads)
    else:
        e_rows, eidx, es = _row_map(pairs.e_index, len(pairs.E), n)
        est, ev = e_row_quantities(pairs.E, e_rows, certify=certify, backend=backend, threads=threads)
        if certify and e_rows is not None:
            _refine(pairs.E, e_rows, est, ev, None, None)
        codes = pair_codes(est, ev, qst, kinds, qv, eidx, qidx, es, qs, n, backend=backend, threads=threads)
    if certify:
        _second_try(pairs, codes, qst, kinds, signs, qv, backend)
    return codes


def _second_try(
    pairs: Pairs,
    codes: np.ndarray,
    qst: np.ndarray,
    kinds: np.ndarray,
    signs: np.ndarray,
    qv: np.ndarray,
    backend: str,
) -> None:
    """The pairs the filter left uncertain (or whose ellipsoid it could not certify), again with
    TIGHT_WIDTH enclosures of their ellipsoids and quadrics (the quadric's wide ones where the
    tight ones fail): a pair with sides within a relative ``1e-6`` of each other is decided here
    rather than by the next stage."""
    todo = np.flatnonzero((codes == UNCERTAIN) | (codes == INVALID))
    if todo.size == 0:
        return
    sub = pairs.take(todo)
    e_rows, eidx, es = _row_map(sub.e_index, len(sub.E), sub.n)
    est, ev = e_row_quantities(sub.E, e_rows, certify=True, backend=backend, width=TIGHT_WIDTH, polish=True)
    q_rows, qidx, qs = _row_map(pairs.q_index, len(pairs.Q), pairs.n)
    iq = (qidx[todo] if qidx.size else todo * qs).astype(np.intp)
    # the quadrics of these pairs with tight enclosures too, where they succeed
    used = np.unique(iq)
    rows_q = used if q_rows is None else q_rows[used]
    tst, tqv = q_row_quantities(
        pairs.Q, rows_q, kinds[used], signs[used], certify=True, backend=backend, width=TIGHT_WIDTH,
        polish=True,
    )  # fmt: skip
    qv = qv.copy()
    better = tst == 0
    qv[:, used[better]] = tqv[:, better]
    again = pair_codes(est, ev, qst, kinds, qv, eidx, iq, es, 0, sub.n, backend=backend)
    codes[todo] = np.where(again == INVALID, codes[todo], again)


def _refine(
    stack: MatrixStack, rows: np.ndarray, status: np.ndarray, values: np.ndarray, kinds: np.ndarray | None,
    signs: np.ndarray | None,
) -> None:  # fmt: skip
    """The sides of the matrices the float stage could not certify (status 1), once per matrix
    with ball arithmetic (exact invariants, isolated eigenvalues), rounded outward: a quadric
    whose type is degenerate (its exact zero eigenvalue rounded off in binary64) or close to
    it is used by every pair of its stack, and should not send them all to the next stage.

    Every such matrix is refined, whatever its place in the stack: a pair's code does not depend
    on the other pairs of its call (a stack of one and a long stack answer it alike).  The work
    is one refinement per distinct matrix, under a millisecond each, never more than the exact
    stage would spend on its pairs."""

    todo = np.flatnonzero(status == 1)
    if kinds is not None:
        todo = todo[kinds[todo] >= 0]
    for k in todo:
        upper = tuple(c[0] for c in stack.upper_exact(rows[k : k + 1]))
        if kinds is None or signs is None:
            sides = ball_sides(upper, 1 if upper[0] > 0 else -1, None)
        else:
            sides = ball_sides(upper, int(signs[k]), TABLE_1_KINDS[int(kinds[k])])
        if sides is not None:
            values[:, k] = sides
            status[k] = 0


def run(mode: Any, pairs: Pairs) -> np.ndarray:
    """:meth:`FloatMode.smallness` and :meth:`FilterMode.smallness`: the codes, invalid input
    diagnosed (the package's errors are raised; an ellipsoid the stage could not certify
    becomes ``UNCERTAIN``), the counts recorded."""
    codes = float_smallness(
        pairs, certify=mode.filtered, classify=mode.classify, backend=mode.backend, threads=mode.threads
    )
    invalid = codes == INVALID
    if invalid.any():
        codes[invalid] = diagnose(pairs, np.flatnonzero(invalid))
    return codes
