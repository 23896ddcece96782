"""Small compiled kernels around the criterion: invariant signs of quadrics (binary64, then
double-double where binary64 cannot tell), checking stacks, region codes from signs, and the
memory-bandwidth floor (a streaming sum)."""

from __future__ import annotations

from typing import Any

import numpy as np

from quadric_contact._generated import blocks, dd_programs, kernels
from quadric_contact.modes.codes import UNCERTAIN
from quadric_contact.modes.decision.answers import ROWS, region_code_masked
from quadric_contact.modes.kernels import double_double as dd
from quadric_contact.modes.kernels import errorbounds as eb
from quadric_contact.modes.kernels._jit import HAVE_NUMBA, numba
from quadric_contact.modes.kernels._jit import njit as _njit
from quadric_contact.modes.kernels.signs import dd_sign_within, plain_sign, sign_within

__all__ = [
    "certified_ellipsoid",
    "check_stack_kernel",
    "ellipsoid_signs_kernel",
    "invariant_signs_kernel",
    "read_all_kernel",
    "region_codes_kernel",
]

_INPUT_MIN = eb.INPUT_MIN
_INPUT_MAX = eb.INPUT_MAX
_FLOAT_MAX = float(np.finfo(np.float64).max)

_invariants = _njit(kernels.quadric_invariants, inline=True)
_invariants_mag = _njit(kernels.quadric_invariants_magnitude, inline=True)
_adjugate_dd = _njit(dd_programs.adjugate_3_dd, inline=True)
_invariants_dd = _njit(dd_programs.quadric_invariants_dd, inline=True)
_cofactor_mag = _njit(dd_programs.quadric_invariants_cofactor_magnitude, inline=True)
_two_sum, _two_prod, _dd_add, _dd_sub, _dd_mul_d, _dd_scale = dd.OPERATIONS
_upper_full = _njit(blocks.upper_full, inline=True)
_abs10 = _njit(blocks.abs_upper, inline=True)
_outside = _njit(blocks.outside_count, inline=True)
_row_maxima = _njit(blocks.row_maxima, inline=True)
_smallest = _njit(blocks.smallest_nonzero, inline=True)
_row_bound = _njit(blocks.row_bound, inline=True)
_e_part = _njit(blocks.pencil_e_part, inline=True)
_minors = _njit(kernels.leading_minors_3, inline=True)
_SM2, _SM3 = eb.SEMI_MINORS
_SP4 = eb.SEMI_PENCIL[4]


def _invariant_signs_impl(
    Q: Any, lo: int, hi: int, K: Any, KD: Any, KC: Any, filtered: bool, dd: bool, out: Any
) -> None:
    """Signs of ``(trA, J, detA, E1, E2, E3, E4, q33)`` for the flat ``(m, 16)`` quadrics
    ``Q[lo:hi]``; with ``filtered`` the bounded ones, and all ``UNCERTAIN`` outside the guard.
    With ``dd`` (binary64 input, not rounded from exact input), a quadric with a sign binary64
    cannot tell is read again in double-double (``dd_programs``): the bound is the smaller of
    ``KD`` (:data:`~quadric_contact.modes.kernels.errorbounds.INVARIANTS_DD_ERRBOUND`) times the binary64
    magnitude and, for ``JA``, ``detA``, ``E4``, ``KC``
    (:data:`~quadric_contact.modes.kernels.errorbounds.INVARIANTS_DD_COFACTOR_ERRBOUND`) times the
    magnitude of their cofactor forms.  What stays ``UNCERTAIN`` is, in practice, an exact zero."""
    for p in range(lo, hi):
        q = _upper_full(Q, p)
        q00, q01, q02, q03, q11, q12, q13, q22, q23, q33 = q
        v = _invariants(q00, q01, q02, q03, q11, q12, q13, q22, q23, q33)
        out[p, 7] = plain_sign(q33)
        if not filtered:
            for k in range(7):
                out[p, k] = plain_sign(v[k])
            continue
        a = _abs10(q)
        g = _outside(a, _INPUT_MIN, _INPUT_MAX)
        mags = _invariants_mag(a[0], a[1], a[2], a[3], a[4], a[5], a[6], a[7], a[8], a[9])
        unsure = g != 0
        for k in range(7):
            s = UNCERTAIN if g != 0 else sign_within(v[k], K[k] * mags[k])
            out[p, k] = s
            unsure |= s == UNCERTAIN
        if dd and unsure and g == 0:
            C = _adjugate_dd(
                _two_sum, _two_prod, _dd_add, _dd_sub, _dd_mul_d, _dd_scale, q00, q01, q02, q11, q12, q22
            )
            w = _invariants_dd(
                _two_sum, _two_prod, _dd_add, _dd_sub, _dd_mul_d, _dd_scale,
                q00, q01, q02, q03, q11, q12, q13, q22, q23, q33, C[0], C[1], C[2], C[3], C[4], C[5],
            )  # fmt: skip
            mc = _cofactor_mag(
                a[0], a[1], a[2], a[3], a[4], a[5], a[6], a[7], a[8], a[9],
                abs(C[0][0]), abs(C[1][0]), abs(C[2][0]), abs(C[3][0]), abs(C[4][0]), abs(C[5][0]),
            )  # fmt: skip
            for k in range(7):
                if out[p, k] == UNCERTAIN:
                    b = KD[k] * mags[k]
                    for j in range(3):
                        if eb.COFACTOR_AT[j] == k:
                            b = min(b, KC[j] * mc[j])
                    out[p, k] = dd_sign_within(w[k], b)


@_njit(inline=True)
def certified_ellipsoid(e: Any, R: Any, det: float, det_bound: float) -> Any:
    """``(ok, o)``: the binary64 matrix with upper entries ``e`` and row maxima ``R`` is certainly
    an ellipsoid, ``o`` the sign of its quadratic part.  Sylvester's minors of the quadratic part
    against their bounds :data:`~quadric_contact.modes.kernels.errorbounds.SEMI_MINORS` (definite, of
    sign ``o``) and ``det`` below ``-det_bound``: inertia (3, 1) or (1, 3).  Valid for input that
    passes the input guard (the caller's)."""
    m2, m3 = _minors(e[0], e[1], e[2], e[4], e[5], e[7])
    o = -1.0 if e[0] < 0.0 else 1.0
    definite = (e[0] != 0.0) & (m2 > _SM2 * (R[0] * R[1])) & (o * m3 > _SM3 * ((R[0] * R[1]) * R[2]))
    ok = definite & (det < -det_bound)
    return ok, o


def _ellipsoid_signs_impl(Q: Any, lo: int, hi: int, out: Any) -> None:
    """For the flat ``(m, 16)`` binary64 quadrics ``Q[lo:hi]``: +1 or -1 where the quadric is
    certainly an ellipsoid of that canonical sign (the sign of its definite quadratic part), 0
    where this short test cannot tell.  The test is the semi-static screen's for ``E``
    (:func:`~quadric_contact.modes.kernels.criterion._screen_core`): the input guard, Sylvester's
    minors of the quadratic part against :data:`~quadric_contact.modes.kernels.errorbounds.SEMI_MINORS`
    and ``det Q`` -- computed by the pencil's own program for ``c4`` -- below minus its bound
    :data:`~quadric_contact.modes.kernels.errorbounds.SEMI_PENCIL` ``[4]`` times the product of the row
    maxima.  A definite quadratic part with ``det Q < 0`` has inertia (3, 1) or (1, 3): a real
    ellipsoid, whatever the rest of the invariants say."""
    for p in range(lo, hi):
        q = _upper_full(Q, p)
        a = _abs10(q)
        R = _row_maxima(a)
        top = max(max(R[0], R[1]), max(R[2], R[3]))
        guard = (top <= _INPUT_MAX) & (_smallest(a, _INPUT_MAX) >= _INPUT_MIN)
        W = _row_bound(R[0], R[1], R[2], R[3], 0.0, 0.0, 0.0, 0.0)
        ell, o = certified_ellipsoid(q, R, _e_part(q)[12], _SP4 * W[4])
        out[p] = int(o) if (guard & ell) else 0


def _check_stack_impl(M: Any, lo: int, hi: int, out: Any) -> None:
    """1 where a matrix has a non-finite entry, 2 where it is not symmetric, else 0."""
    for p in range(lo, hi):
        flag = 0
        for i in range(4):
            for j in range(4):
                x = M[p, i, j]
                if not (abs(x) <= _FLOAT_MAX):
                    flag = 1
        if flag == 0:
            for i in range(4):
                for j in range(i + 1, 4):
                    if M[p, i, j] != M[p, j, i]:
                        flag = 2
        out[p] = flag


def _region_codes_impl(contact: Any, csigns: Any, rows: Any, masks: Any, out: Any) -> None:
    for p in range(contact.shape[0]):
        out[p] = region_code_masked(
            contact[p], csigns[p, 0], csigns[p, 1], csigns[p, 2], csigns[p, 3], csigns[p, 4], rows[p],
            masks[p],
            ROWS,
        )  # fmt: skip


def _read_all_impl(a: Any, lo: int, hi: int) -> float:
    """The sum of ``a[lo:hi]`` (a flat float64 array) with eight independent accumulators, so
    that the loop streams at the speed of memory."""
    s0 = s1 = s2 = s3 = s4 = s5 = s6 = s7 = 0.0
    k = lo
    while k + 8 <= hi:
        s0 += a[k]
        s1 += a[k + 1]
        s2 += a[k + 2]
        s3 += a[k + 3]
        s4 += a[k + 4]
        s5 += a[k + 5]
        s6 += a[k + 6]
        s7 += a[k + 7]
        k += 8
    while k < hi:
        s0 += a[k]
        k += 1
    return ((s0 + s1) + (s2 + s3)) + ((s4 + s5) + (s6 + s7))


invariant_signs_kernel = _njit(_invariant_signs_impl)
ellipsoid_signs_kernel = _njit(_ellipsoid_signs_impl)
check_stack_kernel = _njit(_check_stack_impl)
region_codes_kernel = _njit(_region_codes_impl)
read_all_kernel = numba.njit(nogil=True, cache=True)(_read_all_impl) if HAVE_NUMBA else _read_all_impl
