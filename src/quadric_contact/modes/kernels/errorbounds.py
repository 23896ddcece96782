"""Rigorous error bounds for the float filter, derived in the open.

Every constant below is computed here, in exact rational arithmetic, from the
rounding counts that :mod:`quadric_contact.codegen` reads off the generated
straight-line programs (``kernels.ROUNDING_COUNTS``), and rounded *up* to a
float.  Nothing is typed in.

Model (Higham, *Accuracy and Stability of Numerical Algorithms*, 2nd ed.
2002, §2.2, eq. (2.4)): in IEEE 754 binary64 with rounding to nearest,
``fl(x op y) = (x op y)(1 + d)`` with ``|d| <= u = 2^-53`` for ``op`` in
``+ - *``, provided the result is neither subnormal nor overflows.  The guards
(:data:`INPUT_MIN`, :data:`INPUT_MAX`, :data:`COEFFICIENT_MIN`) make sure of
that, by the *quantum* argument: a float ``x`` with ``|x| >= 2^e`` is an
integer multiple of ``2^(e-52)``; products and sums of multiples of ``2^q``
and ``2^r`` are multiples of ``2^(q+r)`` and ``2^min(q,r)``, and rounding to
nearest keeps a multiple of ``2^q`` a multiple of ``2^q`` (when ``2^q`` is a
float).  So every non-zero intermediate of a degree-``D`` program whose
non-zero inputs are at least ``2^e`` in magnitude is at least ``2^(D(e-52))``.

Straight-line programs (Higham, Lemma 3.1 and §3.1).  Expand the computed
value of a program over ``+ - *`` as a sum over *paths*: each path is one
product of the expanded polynomial (with its integer coefficient) times one
factor ``(1 + d)`` per rounded operation it went through; a sum adds one factor
to every path of both operands (``N = max + 1``), a product multiplies paths
(``N = N_left + N_right + 1``).  With ``N`` that count for the output,
``|fl(p) - p| <= gamma_N * p~`` where ``gamma_N = N u / (1 - N u)`` and ``p~`` is
the sum over paths of the absolute values: exactly what the *magnitude
companion* (same program, ``-`` turned into ``+``, absolute inputs) computes.
Computed in floating point it gives ``M >= (1 - u)^N' p~`` (all terms are
non-negative, ``N'`` its own count), so ``p~ <= M / (1 - u)^N'``.  A fused
multiply-add only removes roundings from paths, so the bounds hold whether or
not the compiler contracts.

The double-double reading of the invariants of a quadric (where binary64 cannot tell their
signs) has its own model, the published bounds of the double-word operations, stated with its
constants in the section below :func:`_check_input_guard`.

Everything here is used by the binary64 kernels (:mod:`quadric_contact.modes.numbers.binary64`); the tests
check every bound against exact arithmetic on adversarial inputs.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any, cast

import numpy as np

from quadric_contact._generated import blocks, kernels
from quadric_contact._generated.blocks import BLOCK_COUNTS
from quadric_contact._generated.dd_programs import DD_COUNTS
from quadric_contact._generated.kernels import ROUNDING_COUNTS

__all__ = [
    "COEFFICIENT_MIN",
    "COFACTOR_AT",
    "COFACTOR_OUTPUTS",
    "DD_ADD_ERROR",
    "DD_MUL_ERROR",
    "DELTA_ABSOLUTE",
    "DELTA_RELATIVE",
    "INPUT_MAX",
    "INPUT_MIN",
    "INVARIANTS_DD_COFACTOR_ERRBOUND",
    "INVARIANTS_DD_ERRBOUND",
    "MEMBER_MINORS_ERRBOUND",
    "MEMBER_MINORS_SEMI",
    "MINORS_ERRBOUND",
    "PENCIL_ERRBOUND",
    "RHO_MAX",
    "ROUND_UP",
    "SEMI_COEFFICIENT_MAX",
    "SEMI_DELTA",
    "SEMI_MINORS",
    "SEMI_PENCIL",
    "UNIT_ROUNDOFF",
    "dd_program_errbound",
    "filter_constants",
    "gamma",
    "program_errbound",
    "round_up",
]

UNIT_ROUNDOFF = Fraction(1, 2**53)
"""``u``: the unit roundoff of binary64 with rounding to nearest."""

_U = UNIT_ROUNDOFF


def gamma(n: int) -> Fraction:
    """``gamma_n = n u / (1 - n u)`` (Higham, Lemma 3.1): ``|prod (1 + d_i)^(+-1) - 1| <= gamma_n``."""
    if n * _U >= 1:
        raise ValueError(f"gamma_{n} is undefined")
    return n * _U / (1 - n * _U)


def round_up(x: Fraction) -> float:
    """The smallest binary64 number ``>= x`` (for positive, representable ``x``)."""
    f = float(x)
    if Fraction(f) < x:
        f = math.nextafter(f, math.inf)
    assert Fraction(f) >= x
    return f


def program_errbound(n_value: int, n_magnitude: int, degree: int, rounded_inputs: bool = False) -> float:
    """``K`` with ``|fl(p) - p| <= fl(K * M)`` for a program output (``M`` its computed magnitude).

    * exact inputs: ``|fl(p) - p| <= gamma_N p~ <= gamma_N (1-u)^-N' M``;
    * inputs that are themselves rounded (``x^ = x (1 + d)``, exact rationals
      converted to floats): each path also carries one factor per input it
      multiplies, which the count with inputs weighing 1 includes
      (``value_rounded_inputs``), and the magnitude at the true inputs is at
      most ``(1-u)^-degree`` times the one at the rounded inputs;
    * the final product ``fl(K M)`` may lose a factor ``(1 - u)``, hence the last division.
    """
    k = gamma(n_value) / (1 - _U) ** n_magnitude
    if rounded_inputs:
        k /= (1 - _U) ** degree
    return round_up(k / (1 - _U))


def _counts(name: str) -> dict[str, Any]:
    """The rounding counts of one generated function (see :mod:`quadric_contact.codegen`)."""
    return dict(ROUNDING_COUNTS[name])


def _program_bounds(name: str, rounded: bool) -> tuple[float, ...]:
    rc = _counts(name)
    value = rc["value_rounded_inputs"] if rounded else rc["value"]
    return tuple(
        program_errbound(nv, nm, d, rounded)
        for nv, nm, d in zip(value, rc["magnitude"], rc["degree"], strict=True)
    )


PENCIL_ERRBOUND = {rounded: _program_bounds("pencil_coefficients", rounded) for rounded in (False, True)}
"""``K_k`` for ``c0 .. c4`` (keyed by "inputs are rounded"): ``|c^_k - c_k| <= fl(K_k * M_k)``."""

MINORS_ERRBOUND = {rounded: _program_bounds("leading_minors_3", rounded) for rounded in (False, True)}
"""``K`` for the leading minors ``m2, m3`` of the quadratic part of ``E`` (Sylvester)."""

INVARIANTS_ERRBOUND = {rounded: _program_bounds("quadric_invariants", rounded) for rounded in (False, True)}
"""``K`` for ``trA, J, detA, E1 .. E4`` (the affine type of ``Q``)."""

# -- guards ------------------------------------------------------------------------

INPUT_MIN_EXPONENT = -180
INPUT_MAX_EXPONENT = 180
INPUT_MIN = 2.0**INPUT_MIN_EXPONENT
"""Non-zero matrix entries must be at least this in magnitude for the filter."""
INPUT_MAX = 2.0**INPUT_MAX_EXPONENT
"""Matrix entries must be at most this in magnitude for the filter (NaN fails too)."""


def _check_input_guard() -> None:
    # Lower guard: entries are multiples of 2^(-180-52); every program is of degree <= 4
    # in them, so every non-zero intermediate (value or magnitude) is >= 2^(4 * -232) =
    # 2^-928, normal; the error bound fl(K M) >= 2^-928 * K >= 2^-981 is normal too.
    q = INPUT_MIN_EXPONENT - 52
    assert 4 * q >= -1022 and 4 * q + math.log2(min(PENCIL_ERRBOUND[False])) >= -1022
    # Upper guard: |intermediate| <= magnitude <= (number of paths) * 2^(4*180); the
    # number of paths is the magnitude program at all ones (exact integers).

    paths = max(kernels.pencil_coefficients_magnitude(*([1] * 20)))
    assert math.log2(paths) + 4 * INPUT_MAX_EXPONENT + 1 < 1023


_check_input_guard()


# -- the invariants of a quadric in double-double ---------------------------------------------
#
# Where binary64 cannot tell the sign of an invariant of a binary64 quadric (rounding moved it off
# a structural zero: det Q of a rotated cylinder is ~1e-16 times its magnitude), the generated
# programs of ``dd_programs`` evaluate the invariants in double-double arithmetic
# (:mod:`quadric_contact.modes.kernels.double_double`): ``adjugate_3_dd`` the cofactors ``C_ij`` of the
# quadratic part, ``quadric_invariants_dd`` the seven invariants, ``JA``, ``detA`` and ``E4`` from
# the cofactors (``codegen.derive_cofactor_forms``), the others from the monomials of the
# binary64 program.
#
# Operations (Joldes, Muller, Popescu, "Tight and rigorous error bounds for basic building
# blocks of double-word arithmetic", ACM TOMS 44(2), 2017): on double-word operands (``xh =
# RN(xh + xl)``, which every operation returns) and without underflow or overflow,
# AccurateDWPlusDW (their Algorithm 6; ``dd_add``, and ``dd_sub`` on the exactly negated
# operand) returns ``(x + y)(1 + d)`` with ``|d| <= DD_ADD_ERROR = 3u^2 + 13u^3``, and DWTimesFP1
# (their Algorithm 7; ``dd_mul_d``) returns ``x y (1 + d)`` with ``|d| <= DD_MUL_ERROR = 3/2 u^2 +
# 4u^3``.  2Sum and Dekker's product of two binary64 numbers and the scaling by a power of two
# are exact (error-free transformations).
#
# Paths (as for binary64 above).  The computed value is the sum over the paths of the programs
# (the cofactors' paths substituted) of their products times ``prod (1 + d_i)`` over the
# rounding operations on the path; with A and M the largest numbers of double-double additions
# and multiplications on any path (``dd_programs.DD_COUNTS``, an AST walk of the emitted
# programs: a sum takes the larger count of its operands, a product adds them),
#     |dd(p) - p| <= ((1 + DD_ADD_ERROR)^A (1 + DD_MUL_ERROR)^M - 1) p~.
# Static bound (every output): expanded, the programs add up the monomials of the binary64
# ``quadric_invariants`` with their integer coefficients, so ``p~`` is the value of the binary64
# magnitude companion at the absolute entries (``codegen.verify_dd_programs`` checks it,
# polynomial for polynomial); its computed value is ``M^ >= (1 - u)^N' p~`` (N' its rounding
# count, under the binary64 filter's guard), and the bound ``fl(K M^)`` loses one more factor
# ``(1 - u)``: INVARIANTS_DD_ERRBOUND.
#
# Cofactor bound (``JA``, ``detA``, ``E4``).  Each computed cofactor is one AccurateDWPlusDW of
# two exact products, so ``C^ = C (1 + t)`` with ``|t| <= DD_ADD_ERROR`` *relative to the
# cofactor itself*; read the paths from the cofactors instead of the entries: a path is a term
# ``c m(q) C`` of the cofactor form, and the same count (the cofactor's own addition is on every
# such path) gives ``|dd(p) - p| <= ((1 + DD_ADD_ERROR)^A (1 + DD_MUL_ERROR)^M - 1) p~_C(|q|,
# |C|)``, ``p~_C`` the magnitude of the cofactor form (``quadric_invariants_cofactor_magnitude``,
# checked against the program's paths the same way).  It is linear in the cofactors, ``|C| <=
# |C^| / (1 - DD_ADD_ERROR)`` and ``|C^| = |Ch + Cl| <= (1 + u) |Ch|``, and the binary64
# computation at the high words loses ``(1 - u)^N_C`` and the final product ``(1 - u)``:
# INVARIANTS_DD_COFACTOR_ERRBOUND.  Where the quadratic part is close to rank 1 (a rotated
# parabolic cylinder, parallel planes), the cofactors are of the order of the rounding and
# ``detA``, ``E4`` of its square, ~1e-33 of the static magnitude and below the static bound;
# ``p~_C`` is of the order of the cofactors, and the cofactor bound certifies them.
#
# The sign of ``v = vh + vl`` is certain when ``v > b`` (or ``v < -b``), read exactly from the
# two words: ``vh > b``, or ``vh = b`` and ``vl > 0`` (``vh = RN(v)``, and rounding is
# monotonic).  A zero is certified only where a magnitude is exactly zero: then every term of
# the (static or cofactor) form is zero, and so is the value, exactly (a zero high word of a
# cofactor means a zero cofactor).
#
# Guard: the binary64 filter's, every non-zero entry in [INPUT_MIN, INPUT_MAX] = [2^-180,
# 2^180] (:func:`_check_dd_guard`).  Underflow: a non-zero entry is a multiple of 2^(-180-52);
# every quantity the programs form for an output of degree d <= 4, inside the operations too
# (the halves of Veltkamp's splitting, the partial products of Dekker's product, the error
# terms of 2Sum and Fast2Sum), is a rounded sum of products of d such multiples (times the
# integers 2^27 + 1, 2, -1), so a multiple of 2^(4 (-232)) = 2^-928: a non-zero one is normal,
# every error-free transformation is exact and the computation is the one in an unbounded
# exponent range, where the published bounds hold.  The same holds for the magnitudes, whose
# non-zero terms are at least 2^(4 (-180)) (static) and 2^(2 (-180) + 2 (-232)) (cofactor), so
# that the bounds are normal numbers too.  Overflow: a product of four entries is at most
# 2^720, every value of the programs at most (1 + 2^-100) times a sum of at most ``paths`` (the
# magnitude program at all ones) of them, times 2 (the coefficients), and inside an operation
# nothing exceeds 2^28 (the splitting) or 4 times its operands.


DD_ADD_ERROR = 3 * _U**2 + 13 * _U**3
"""Relative error bound of AccurateDWPlusDW (JMP 2017, Algorithm 6): ``dd_add``, ``dd_sub``."""

DD_MUL_ERROR = Fraction(3, 2) * _U**2 + 4 * _U**3
"""Relative error bound of DWTimesFP1 (JMP 2017, Algorithm 7): ``dd_mul_d``."""


def _dd_growth(n_add: int, n_mul: int) -> Fraction:
    """``(1 + DD_ADD_ERROR)^n_add (1 + DD_MUL_ERROR)^n_mul - 1``: the relative error of a path."""
    return (1 + DD_ADD_ERROR) ** n_add * (1 + DD_MUL_ERROR) ** n_mul - 1


def dd_program_errbound(n_add: int, n_mul: int, n_magnitude: int) -> float:
    """``K`` with ``|dd(p) - p| <= fl(K * M)`` for an output of a double-double program with at
    most ``n_add`` double-double additions and ``n_mul`` multiplications on a path, ``M`` the
    computed binary64 magnitude (rounding count ``n_magnitude``) of the same paths:
    ``K = ((1 + DD_ADD_ERROR)^n_add (1 + DD_MUL_ERROR)^n_mul - 1) / (1 - u)^(n_magnitude + 1)``."""
    return round_up(_dd_growth(n_add, n_mul) / (1 - _U) ** n_magnitude / (1 - _U))


def _dd_counts(name: str) -> dict[str, Any]:
    """The double-double counts of one generated program (see :mod:`quadric_contact.codegen`)."""
    return dict(cast("dict[str, Any]", DD_COUNTS[name]))


def _dd_bounds() -> tuple[float, ...]:
    dd = _dd_counts("quadric_invariants_dd")
    rc = _counts("quadric_invariants")
    if tuple(dd["outputs"]) != tuple(rc["outputs"]) or tuple(dd["degree"]) != tuple(rc["degree"]):
        raise AssertionError("the double-double program is not the binary64 program's companion")
    return tuple(
        dd_program_errbound(a, m, nm)
        for a, m, nm in zip(dd["dd_add"], dd["dd_mul_d"], rc["magnitude"], strict=True)
    )


def _dd_cofactor_bounds() -> tuple[float, ...]:
    adj = _dd_counts("adjugate_3_dd")
    if set(adj["dd_add"]) != {1} or set(adj["dd_mul_d"]) != {0}:
        raise AssertionError("a cofactor is not one rounded difference of two exact products")
    dd = _dd_counts("quadric_invariants_dd")
    mag = _dd_counts("quadric_invariants_cofactor_magnitude")
    out = []
    for name, n_mag in zip(mag["outputs"], mag["magnitude"], strict=True):
        j = dd["outputs"].index(name)
        k = _dd_growth(dd["dd_add"][j], dd["dd_mul_d"][j]) * (1 + _U) / (1 - DD_ADD_ERROR)
        out.append(round_up(k / (1 - _U) ** n_mag / (1 - _U)))
    return tuple(out)


INVARIANTS_DD_ERRBOUND = _dd_bounds()
"""``K`` for ``trA, J, detA, E1 .. E4`` in double-double (binary64 input, not rounded from exact
input): ``|dd - exact| <= fl(K * M)`` with ``M`` the binary64 magnitude companion of
``quadric_invariants``, for input within the guard."""

COFACTOR_OUTPUTS: tuple[str, ...] = tuple(_dd_counts("quadric_invariants_cofactor_magnitude")["outputs"])
"""The invariants with a cofactor bound too: ``JA``, ``detA``, ``E4``."""

COFACTOR_AT: tuple[int, ...] = tuple(
    _counts("quadric_invariants")["outputs"].index(n) for n in COFACTOR_OUTPUTS
)
"""Where :data:`COFACTOR_OUTPUTS` sit among the seven invariants of ``quadric_invariants``."""

INVARIANTS_DD_COFACTOR_ERRBOUND = _dd_cofactor_bounds()
"""``K`` for :data:`COFACTOR_OUTPUTS` in double-double: ``|dd - exact| <= fl(K * M_C)`` with ``M_C``
the value of ``dd_programs.quadric_invariants_cofactor_magnitude`` at the absolute entries and
the absolute high words of the double-double cofactors (the same input)."""


def _check_dd_guard() -> None:
    # every quantity a multiple of 2^(4 (INPUT_MIN_EXPONENT - 52)): normal when non-zero
    assert 4 * (INPUT_MIN_EXPONENT - 52) >= -1022
    # the bound of a non-zero magnitude (static: a product of four entries; cofactor: two
    # entries and a cofactor, a multiple of 2^(2 (INPUT_MIN_EXPONENT - 52))) is normal
    assert 4 * INPUT_MIN_EXPONENT + math.log2(min(INVARIANTS_DD_ERRBOUND)) - 1 >= -1022
    low = 2 * INPUT_MIN_EXPONENT + 2 * (INPUT_MIN_EXPONENT - 52)
    assert low + math.log2(min(INVARIANTS_DD_COFACTOR_ERRBOUND)) - 1 >= -1022
    # no overflow: sums of at most `paths` products of four entries, times 2, split (2^28), summed (4)
    paths = max(kernels.quadric_invariants_magnitude(*([1] * 10)))
    assert math.log2(paths) + 4 * INPUT_MAX_EXPONENT + 1 + 28 + 2 < 1023


_check_dd_guard()

COEFFICIENT_MIN = 2.0**-118
"""After scaling the coefficients to ``[0, 2)``, non-zero ``|c_k|`` and their upper
bounds must be at least this for the Delta stage."""


def _check_coefficient_guard() -> None:
    # Multiples of 2^(-118-52) to the 6th power (Delta_4 has degree 6) stay >= 2^-1020:
    # no subnormal intermediate.  A non-zero magnitude is >= one product >= 2^(-118*6)
    # (1-u)^N >= 2^-709, so K * M stays normal; a difference of two such magnitudes is a
    # multiple of 2^-1020.
    assert 6 * (-118 - 52) >= -1022


_check_coefficient_guard()

ROUND_UP = 1.0 + 4.0 * 2.0**-53
"""``b = fl(fl(a + e) * ROUND_UP) >= a + e`` for non-negative normal ``a, e``:
``fl(a + e) >= (a + e)(1 - u)`` and ``fl(s * ROUND_UP) >= s (1 + 4u)(1 - u)``, and
``(1 - u)^2 (1 + 4u) >= 1``."""
assert (1 - _U) ** 2 * (1 + 4 * _U) >= 1 and Fraction(ROUND_UP) == 1 + 4 * _U

# -- the Delta stage -------------------------------------------------------------------
#
# The coefficients c^_k carry absolute errors e_k (from PENCIL_ERRBOUND), are scaled by
# the same power of two s (exact) so that a_k = |c^_k| s < 1, and Delta_j (degree d_j,
# counts N_j, N'_j) is evaluated at c^ s.  Two ways to bound |Delta^_j - Delta_j(c s)|:
#
# Relative (one magnitude program): with c_k = c^_k (1 + t_k), |t_k| <= rho (rho the
# largest e_k / |c^_k| over the non-zero c^_k; c^_k = e_k = 0 means c_k = 0 exactly and
# drops out), every product of degree <= d_j moves by at most (1 + rho)^d - 1 <= d rho
# (1 + rho)^(d-1) times its size, so
#     |Delta^ - Delta| <= (d (1 + RHO_MAX)^(d-1) rho + gamma_N) p~(a),   p~(a) <= A (1-u)^-N'.
# The float computation fl(fl(fl(R rho^) + G) A) with rho^ = max fl(e_k / a_k) (each
# quotient >= (1 - u) times the true one) loses at most (1 - u)^3, and rho <= rho^ / (1-u).
#
# Absolute (two magnitude programs, a and b >= a + e): every product moves by at most
# p~_m(b) - p~_m(a), so |Delta^ - Delta| <= p~(b) - p~(a) + gamma_N p~(a)
#     <= (B - A)(1-u)^-N' + A ((1-u)^-N' - (1+u)^-N' + gamma_N (1-u)^-N'),
# with B - A <= fl(B - A) / (1 - u) and the final fl(fl(K1 D) + fl(K3 A)) losing (1-u)^2.

RHO_MAX = 2.0**-10
"""The relative bound is used only when ``rho^ <= RHO_MAX`` (otherwise the absolute one)."""


def _delta_relative(j: int) -> tuple[float, float]:
    rc = _counts("paper_deltas")
    d, n, nm = rc["degree"][j], rc["value"][j], rc["magnitude"][j]
    rho_max = Fraction(RHO_MAX) / (1 - _U)  # the true rho is at most rho^ / (1 - u)
    loss = (1 - _U) ** 3
    r = d * (1 + rho_max) ** (d - 1) / (1 - _U) / (1 - _U) ** nm / loss
    g = gamma(n) / (1 - _U) ** nm / loss
    return round_up(r), round_up(g)


def _delta_absolute(j: int) -> tuple[float, float]:
    rc = _counts("paper_deltas")
    n, nm = rc["value"][j], rc["magnitude"][j]
    loss = (1 - _U) ** 2
    k1 = 1 / (1 - _U) ** (nm + 1) / loss
    k3 = (1 / (1 - _U) ** nm - 1 / (1 + _U) ** nm + gamma(n) / (1 - _U) ** nm) / loss
    return round_up(k1), round_up(k3)


DELTA_RELATIVE = tuple(_delta_relative(j) for j in range(3))
"""``(R_j, G_j)`` for ``Delta_2, Delta_3, Delta_4``: bound ``fl(fl(fl(R rho^) + G) A)``."""

DELTA_ABSOLUTE = tuple(_delta_absolute(j) for j in range(3))
"""``(K1_j, K3_j)`` for ``Delta_2, Delta_3, Delta_4``: bound ``fl(fl(K1 fl(B - A)) + fl(K3 A))``."""


# -- the separation certificate: members s E + Q of the pencil -------------------------------
#
# The separation stage (:mod:`quadric_contact.modes.decision.separation`) reads the inertia of a member
# M* = s E + Q of the pencil at a float sample point s from the signs of the sums E1 .. E4 of
# its principal minors (``quadric_invariants`` applied to the member).  The member is computed
# as M^ = fl(fl(s e^) + q^), where e^, q^ are the float entries and, when the inputs are
# roundings of exact rationals (r = 1), e^ = e (1 + t), q^ = q (1 + t'), |t|, |t'| <= u.  With
# W* = |s e| + |q| (entrywise) and a = (1 + u)^(2 + r) - 1:
#     |M^ - M*| <= a W*,   |M^| <= (1 + a) W*.
# For E_k (degree k, value count N, magnitude count N'):
#     |E_k^ - E_k(M^)| <= gamma_N p~(|M^|) <= gamma_N (1 + a)^k p~(W*)          (evaluation)
#     |E_k(M^) - E_k(M*)| <= p~(|M*| + a W*) - p~(|M*|) <= ((1 + a)^k - 1) p~(W*)  (inputs)
# (p~ has non-negative coefficients and is homogeneous of degree k, and |M*| <= W*).  The
# magnitude entries are computed as W^ = fl(fl(|s| |e^|) + |q^|) >= (1 - u)^(2 + r) W*, and
# the magnitude program on W^ gives M^_k >= (1 - u)^N' p~(W^), so
#     |E_k^ - E_k(M*)| <= K_k fl(M^_k),
#     K_k = ((1 + gamma_N)(1 + a)^k - 1) / (1 - u)^(N' + (2 + r) k) / (1 - u)
# (the last factor for the rounding of the final product).  Guards: every non-zero entry of
# M^ and of W^ lies in [INPUT_MIN, INPUT_MAX] (then, as for the inputs above, every non-zero
# intermediate of the degree-4 programs and every bound is a normal number), and the products
# s e must not underflow: |s| and the non-zero |e| lie in [2^-300, 2^300] and [INPUT_MIN,
# INPUT_MAX], so a non-zero |s e| >= 2^-480 is normal and the standard model holds for it.


SAMPLE_MIN = 2.0**-300
SAMPLE_MAX = 2.0**300
"""A non-zero sample point ``s`` of the separation stage must lie in ``[SAMPLE_MIN, SAMPLE_MAX]``."""


def _member_errbound(k: int, rounded: bool) -> float:
    rc = _counts("quadric_invariants")
    j = rc["outputs"].index(f"E{k}")
    n, nm, d = rc["value"][j], rc["magnitude"][j], rc["degree"][j]
    assert d == k
    r = 1 if rounded else 0
    a = (1 + _U) ** (2 + r) - 1
    numerator = (1 + gamma(n)) * (1 + a) ** k - 1
    return round_up(numerator / (1 - _U) ** (nm + (2 + r) * k) / (1 - _U))


def _member_minor_errbound(k: int, rounded: bool) -> float:
    """As :func:`_member_errbound`, for the leading principal minor ``d_k`` (degree ``k``) of the
    program ``leading_minors_4`` run on the member's computed entries."""
    rc = _counts("leading_minors_4")
    j = rc["outputs"].index(f"d{k}")
    n, nm, d = rc["value"][j], rc["magnitude"][j], rc["degree"][j]
    assert d == k
    r = 1 if rounded else 0
    a = (1 + _U) ** (2 + r) - 1
    numerator = (1 + gamma(n)) * (1 + a) ** k - 1
    return round_up(numerator / (1 - _U) ** (nm + (2 + r) * k) / (1 - _U))


MEMBER_ERRBOUND = {
    rounded: tuple(_member_errbound(k, rounded) for k in range(1, 5)) for rounded in (False, True)
}
"""``K_k`` for ``E1 .. E4`` of a member ``s E + Q`` (keyed by "inputs are rounded"):
``|E_k^ - E_k(s E + Q)| <= fl(K_k * M_k)`` with ``M_k`` the magnitude program at ``W^``."""

MEMBER_MINORS_ERRBOUND = {
    rounded: tuple(_member_minor_errbound(k, rounded) for k in range(1, 5)) for rounded in (False, True)
}
"""``K_k`` for the leading principal minors ``d1 .. d4`` of a member ``s E + Q`` (Sylvester's
criterion, :func:`~quadric_contact._generated.kernels.leading_minors_4`), keyed by "inputs are
rounded": ``|d_k^ - d_k(s E + Q)| <= fl(K_k * M_k)`` with ``M_k`` the magnitude program at ``W^``
(the same argument as for ``E1 .. E4``: the member's entries carry ``(1 + u)^(2 + r)`` each, the
program ``k`` of them on every path)."""


# Semi-static form (the signature kernel, :mod:`quadric_contact.modes.kernels.signature`): instead
# of the magnitude program at W^, one product of row maxima.  With R*_r the largest entry of row
# r of W* (the whole row of the symmetric matrix), every path of the program leading_minors_4 for
# d_k takes one entry from each of the rows 0 .. k-1 (codegen.verify_member_minor_row_bounds), so
# p~(W*) <= k! R*_0 .. R*_(k-1).  The kernel's row maxima of W^ are at least (1 - u)^(2 + r) R*_r,
# their product takes k - 1 roundings and the final product by the constant one more, so
#     |d_k^ - d_k(s E + Q)| <= fl(S_k * fl(..fl(R^_0 R^_1)..R^_(k-1))),
#     S_k = ((1 + gamma_N)(1 + a)^k - 1) k! / (1 - u)^((2 + r) k + k).
# The guards are those of the member (every non-zero entry of M^ and W^ in [INPUT_MIN,
# INPUT_MAX], s in [SAMPLE_MIN, SAMPLE_MAX]); a non-zero product of k <= 4 row maxima is then at
# least 2^-720 and the bound a normal number.  A row of W^ that is all zeros is a row of exact
# zeros of M^: every path of d_k (k past that row) has a zero factor, so d_k^ = 0 exactly, and so
# is its bound.


def _member_minor_semi(k: int, rounded: bool) -> float:
    rc = _counts("leading_minors_4")
    j = rc["outputs"].index(f"d{k}")
    n = rc["value"][j]
    r = 1 if rounded else 0
    a = (1 + _U) ** (2 + r) - 1
    numerator = ((1 + gamma(n)) * (1 + a) ** k - 1) * math.factorial(k)
    return round_up(numerator / (1 - _U) ** ((2 + r) * k + k))


MEMBER_MINORS_SEMI = {
    rounded: tuple(_member_minor_semi(k, rounded) for k in range(1, 5)) for rounded in (False, True)
}
"""``S_k`` for the leading principal minors ``d1 .. d4`` of a member ``s E + Q`` from the row
maxima of its magnitudes (keyed by "inputs are rounded"): ``|d_k^ - d_k(s E + Q)| <= fl(S_k *
fl(R0 .. R_(k-1)))``, the product of row maxima rounded left to right."""


def _check_member_guard() -> None:
    # |s e| >= 2^-300 * 2^-180 = 2^-480: normal, so fl(s e) = s e (1 + d).  The members'
    # entries are guarded like the inputs, so _check_input_guard's argument applies.
    assert math.log2(SAMPLE_MIN) + INPUT_MIN_EXPONENT >= -1022
    assert math.log2(SAMPLE_MAX) + INPUT_MAX_EXPONENT <= 1000

    paths = max(kernels.quadric_invariants_magnitude(*([1] * 10)))
    assert math.log2(paths) + 4 * INPUT_MAX_EXPONENT + 1 < 1023
    assert 4 * (INPUT_MIN_EXPONENT - 52) + math.log2(min(MEMBER_ERRBOUND[False])) >= -1022
    paths = max(kernels.leading_minors_4_magnitude(*([1] * 10)))
    assert math.log2(paths) + 4 * INPUT_MAX_EXPONENT + 1 < 1023
    assert 4 * (INPUT_MIN_EXPONENT - 52) + math.log2(min(MEMBER_MINORS_ERRBOUND[False][1:])) >= -1022


_check_member_guard()


# -- the semi-static screen -------------------------------------------------------------------
#
# The first stage of the filter on binary64 input (CGAL's static filters, Shewchuk's stage A,
# with one bound per coefficient from the rows of the two matrices).  Guard: every non-zero
# entry in [INPUT_MIN, INPUT_MAX], so that, as for the filter, no intermediate of the pencil
# program or of the row bound is subnormal or overflows.
#
# Coefficients.  With R_r, T_r the largest |entry| of row r of E and of Q (exact: maxima of
# floats), the magnitude program of c_k is at most 24 W_k(R, T), W_k the coefficient of
# lambda^k in prod_r (R_r lambda + T_r) (codegen.verify_row_bound: the general determinant has
# 24 permutations, each taking one entry per row, and the symmetric program's magnitude is at
# most the general one).  So |c^_k - c_k| <= gamma_N 24 W_k (Higham, Lemma 3.1, N the value
# count of c_k).  ``row_bound`` adds non-negative products: its computed W^_k >= (1-u)^n W_k
# (n its own count), and r_k = fl(SEMI_PENCIL[k] W^_k) loses one more factor (1 - u).
#
# Delta stage, without rescaling.  Every non-zero |c^_k| must lie in [COEFFICIENT_MIN,
# SEMI_COEFFICIENT_MAX] (then the compact Delta programs neither underflow (the quantum
# argument of the coefficient guard) nor overflow (below)).  With rho_k = r_k / |c^_k| and
# c^_k = 0 allowed only with r_k = 0 (an exact zero), c_k = c^_k (1 + t_k), |t_k| <= rho =
# max rho_k, and the relative form of the Delta bounds applies (as DELTA_RELATIVE, with the
# counts of ``paper_deltas_compact``, whose Delta4_27 = 27 Delta_4 has the sign of Delta_4):
#     |Delta^_j - Delta_j(c)| <= fl(fl(fl(R_j rho^) + G_j) A_j),   rho^ = max fl(r_k / |c^_k|),
# A_j the computed magnitude program at |c^| (every path of the program, not only the
# monomials of the polynomial, is perturbed by at most d rho (1 + rho)^(d-1)).  rho^ >= 2^-930
# whenever it is not zero (r_k >= 2^-720 SEMI_PENCIL[k] for a non-zero W_k, |c^_k| <= 2^160),
# so the quotients are normal.  For a plane (Q with a zero quadratic part) c0 and c1 are exact
# zeros with zero bounds and Delta_4 vanishes identically (codegen.verify_plane_zeros).

SEMI_COEFFICIENT_MAX = 2.0**160
"""The screen's Delta stage needs ``fl(|c0| + .. + |c4|)`` at most this (no rescaling; each
``|c_k|`` is then below ``2^161``), and every non-zero ``|c_k|`` at least COEFFICIENT_MIN."""


def _semi_pencil() -> tuple[float, ...]:
    pencil = _counts("pencil_coefficients")["value"]
    rows: tuple[int, ...] = BLOCK_COUNTS["row_bound"]["value"]  # type: ignore[index]
    return tuple(round_up(24 * gamma(n) / (1 - _U) ** (w + 1)) for n, w in zip(pencil, rows, strict=True))


SEMI_PENCIL = _semi_pencil()
"""``r_k = fl(SEMI_PENCIL[k] * W^_k)`` bounds ``|c^_k - c_k|`` (binary64 input, guarded)."""


def _semi_minors() -> tuple[float, float]:
    # The magnitude programs of m2 and m3 are at most 2 R0 R1 and 6 R0 R1 R2
    # (codegen.verify_minor_row_bounds); the products of the row maxima take 1 and 2 roundings,
    # the final product by the constant one more.
    value = _counts("leading_minors_3")["value"]
    return tuple(  # type: ignore[return-value]
        round_up(math.factorial(k) * gamma(n) / (1 - _U) ** k) for k, n in zip((2, 3), value, strict=True)
    )


SEMI_MINORS = _semi_minors()
"""The screen's test that ``E`` is an ellipsoid: ``|m2^ - m2| <= fl(SEMI_MINORS[0] fl(R0 R1))`` and
``|m3^ - m3| <= fl(SEMI_MINORS[1] fl(fl(R0 R1) R2))`` (binary64 input, guarded)."""


def _relative_form(d: int, n: int, nm: int) -> tuple[float, float]:
    """``(R, G)`` of the relative form of a Delta bound (see above DELTA_RELATIVE) for a program
    of degree ``d``, value count ``n`` and magnitude count ``nm``."""
    rho_max = Fraction(RHO_MAX) / (1 - _U)
    loss = (1 - _U) ** 3
    r = d * (1 + rho_max) ** (d - 1) / (1 - _U) / (1 - _U) ** nm / loss
    g = gamma(n) / (1 - _U) ** nm / loss
    return round_up(r), round_up(g)


def _semi_delta() -> tuple[tuple[float, float], ...]:
    rc: dict[str, tuple[int, ...]] = BLOCK_COUNTS["paper_deltas_compact"]  # type: ignore[assignment]
    return tuple(
        _relative_form(d, n, nm) for d, n, nm in zip(rc["degree"], rc["value"], rc["magnitude"], strict=True)
    )


SEMI_DELTA = _semi_delta()
"""``(R_j, G_j)`` for the compact ``Delta_2, Delta_3, 27 Delta_4``: bound ``fl(fl(fl(R rho^) + G) A)``."""


def _check_semi_guard() -> None:
    # the compact programs at |c_k| <= 2^160: every value and magnitude is at most the number
    # of paths (the magnitude program at all ones) times 2^(160 d), d <= 6
    paths = max(blocks.paper_deltas_compact_magnitude(*([1] * 5)))
    assert math.log2(paths) + 6 * (math.log2(SEMI_COEFFICIENT_MAX) + 1) + 1 < 1023
    # a non-zero rho^ is normal: r_k >= SEMI_PENCIL 2^(4 * -180), |c| <= 2^160
    assert math.log2(min(SEMI_PENCIL)) + 4 * INPUT_MIN_EXPONENT - math.log2(SEMI_COEFFICIENT_MAX) >= -1000
    assert all(r * RHO_MAX + g < 1 for r, g in SEMI_DELTA)


_check_semi_guard()


def filter_constants(rounded: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The dynamic filter's bounds as the kernels read them: ``(KP, KL, DR, DA)``, the pencil's
    (:data:`PENCIL_ERRBOUND`) and the minors' (:data:`MINORS_ERRBOUND`) for binary64 input or
    input ``rounded`` to it, and the Deltas' relative and absolute terms
    (:data:`DELTA_RELATIVE`, :data:`DELTA_ABSOLUTE`)."""
    KP = np.array(PENCIL_ERRBOUND[rounded])
    KL = np.array(MINORS_ERRBOUND[rounded])
    DR = np.array(DELTA_RELATIVE)
    DA = np.array(DELTA_ABSOLUTE)
    return KP, KL, DR, DA
