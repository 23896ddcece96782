"""The separation certificate on binary64 stacks, in blocks: the pencil's signature sequence at
the speed of the criterion kernel.

:mod:`quadric_contact.modes.decision.separation` states the certificate and the facts behind it; this
module computes the same facts for many pairs at once, laid out for the vector unit:

1. a gather copies a block of :data:`NB` pairs into column buffers (one row per upper entry);
2. a straight-line loop over the block, with no branch and no call to a transcendental
   function (so that LLVM vectorises it), computes for each pair the coefficients of
   ``P(lambda) = det(lambda E + Q)``, three sample points (:func:`critical_points_fast`), and
   at each point the leading principal minors ``d1 .. d4`` of the member ``s E + Q`` with the
   semi-static bounds :data:`~quadric_contact.modes.kernels.errorbounds.MEMBER_MINORS_SEMI` (one product
   of row maxima per minor instead of a magnitude program);
3. a short scalar loop turns the signs into the facts of the decision table and looks the
   answer up in :data:`quadric_contact.theory.decision.REGION_OF`, the table every other path
   reads.

The facts, for ``E`` an ellipsoid (``det E < 0``, so ``P`` tends to ``-inf`` at both ends):

* a member certainly definite at a sample point is a witness: ``E`` strictly on one side
  (Finsler; positive: ``R+``, negative: ``R-``), whatever the roots;
* signs ``+, -, +`` of ``P`` certain at sample points ``s1 < s2 < s3`` make four sign changes:
  four simple real roots ``r1 < s1 < r2 < s2 < r3 < s3 < r4``.  Then the number of positive
  eigenvalues of the member is 1 before ``r1``, 3 after ``r4``, and moves by exactly one at each
  root, so it is 0 or 2 on ``(r1, r2)``, 1 or 3 on ``(r2, r3)`` and 2 or 4 on ``(r3, r4)``: only
  the first gap can hold a negative definite member and only the last a positive definite one.
  Members at ``s1`` and ``s3`` certainly not definite mean no definite member at all: the
  surfaces cross (the table's row for four simple roots and no definite member).  The inertia
  paths are enumerated in ``proofs/twmw_2009_signature_decision.py`` (check ``inertia_paths``).

Where the fast reading is not certain (a tangency, a multiple root, a sample point too close to
a root for the semi-static bound), the pair is read again by the scalar certificate of
:mod:`quadric_contact.modes.decision.separation` (trigonometric sample points, magnitude programs), and
what that cannot settle stays ``UNCERTAIN`` for the exact stage.  The plain ``float`` mode
reads the computed signs as they are and answers every pair, as the scalar certificate does.
"""

from __future__ import annotations

import math
import threading
from typing import Any

import numpy as np

from quadric_contact._generated import blocks, kernels
from quadric_contact.modes.codes import UNCERTAIN
from quadric_contact.modes.decision.separation import _separation_one
from quadric_contact.modes.kernels import errorbounds as eb
from quadric_contact.modes.kernels._jit import HAVE_NUMBA, plain
from quadric_contact.modes.kernels._jit import njit as _njit
from quadric_contact.modes.kernels.signs import plain_sign, sign_within
from quadric_contact.modes.kernels.threads import run_parallel
from quadric_contact.modes.stacks.pairs import Pairs
from quadric_contact.theory import decision

__all__ = [
    "CRITICAL_POLYNOMIAL",
    "NB",
    "WITNESS_FIRST",
    "WITNESS_LAST",
    "critical_points_fast",
    "decide_signature",
    "member_minors_bounded",
    "signature_finish",
    "signature_finish_called",
    "signature_first",
    "signature_float",
    "signature_prepare",
    "signature_rows",
    "witness",
]

NB = 32
"""Pairs per block (as the criterion kernels)."""

CRITICAL_POLYNOMIAL = (
    0.5000000032068507,
    0.5773497220421494,
    -0.1110957112213272,
    0.0532888117887671,
    -0.0319617489440338,
    0.019676451273645104,
    -0.010326148527710868,
    0.0037079844505658365,
    -0.0006393664617970223,
)
"""Coefficients (increasing degree) of a polynomial ``g(t)`` within ``4e-9`` of
``cos(2 acos(t) / 3)`` on ``[0, 1]``: the least-squares fit of degree 8 at 513 Chebyshev points.
With ``t = sqrt((1 + x) / 2)`` it gives ``cos(acos(x) / 3)``, the largest root of a depressed
cubic in the trigonometric form, without a transcendental function (the substitution removes
the square-root singularity at ``x = -1``, which makes ``g`` analytic on the whole interval).
The accuracy is checked by the tests; nothing trusts the points it gives."""

_G0, _G1, _G2, _G3, _G4, _G5, _G6, _G7, _G8 = CRITICAL_POLYNOMIAL
_INF = math.inf
_IN_MIN = eb.INPUT_MIN
_IN_MAX = eb.INPUT_MAX
_S_MIN = eb.SAMPLE_MIN
_S_MAX = eb.SAMPLE_MAX

_load = _njit(blocks.load_upper, inline=True)
_gather_full = _njit(blocks.gather_full, inline=True)
_pencil = _njit(blocks.pencil, inline=True)
_minors4 = _njit(kernels.leading_minors_4, inline=True)
_REGION_OF = decision.REGION_OF
_table_index = _njit(decision.table_index, inline=True)
_SURFACE_UNKNOWN = int(decision.Surface.UNKNOWN)
_PLANE_UNKNOWN = int(decision.Plane.UNKNOWN)
_POSITIVE = float(decision.Definite.POSITIVE)
_NEGATIVE = float(decision.Definite.NEGATIVE)
_NONE = float(decision.Definite.NONE)
_DEF_UNKNOWN = float(decision.Definite.UNKNOWN)
_SIMPLE, _NONREAL = int(decision.Roots.SIMPLE), int(decision.Roots.NONREAL)
_ROOTS_UNKNOWN = int(decision.Roots.UNKNOWN)
_UNC = float(UNCERTAIN)


@_njit(inline=True)
def critical_points_fast(c1: float, c2: float, c3: float, c4: float) -> tuple[float, float, float, bool]:
    """Approximations of the three real roots of ``P' = 4 c4 x^3 + 3 c3 x^2 + 2 c2 x + c1`` in
    increasing order, as :func:`quadric_contact.theory.decision.critical_points` gives them, but
    without a branch or a transcendental function: the largest root of the depressed cubic from
    :data:`CRITICAL_POLYNOMIAL`, the other two from the quadratic left after dividing it out,
    then one Newton step on each.  The flag is False when ``P'`` has fewer than three distinct
    real roots as computed, or the numbers are not finite.

    >>> [round(x, 9) for x in critical_points_fast(-50.0, 35.0, -10.0, 1.0)[:3]]
    [1.381966011, 2.5, 3.618033989]
    """
    inv = 1.0 / c4
    a = 0.75 * c3 * inv
    b = 0.5 * c2 * inv
    c = 0.25 * c1 * inv
    a3 = a * (1.0 / 3.0)
    p = b - a * a3
    q = a3 * (2.0 * a3 * a3 - b) + c
    pn = min(p, 0.0)
    m = 2.0 * math.sqrt(-pn * (1.0 / 3.0))
    arg = 3.0 * q / (pn * m)
    arg = min(1.0, max(-1.0, arg))
    t = math.sqrt(0.5 + 0.5 * arg)
    g = (((((((_G8 * t + _G7) * t + _G6) * t + _G5) * t + _G4) * t + _G3) * t + _G2) * t + _G1) * t + _G0
    T2 = m * g
    sq = math.sqrt(max(-3.0 * T2 * T2 - 4.0 * pn, 0.0))
    T0 = 0.5 * (-T2 - sq)
    T1 = 0.5 * (-T2 + sq)
    T0 = T0 - (T0 * T0 * T0 + pn * T0 + q) / (3.0 * T0 * T0 + pn)
    T1 = T1 - (T1 * T1 * T1 + pn * T1 + q) / (3.0 * T1 * T1 + pn)
    T2 = T2 - (T2 * T2 * T2 + pn * T2 + q) / (3.0 * T2 * T2 + pn)
    x0 = T0 - a3
    x1 = T1 - a3
    x2 = T2 - a3
    ok = (p < 0.0) & (x0 < x1) & (x1 < x2) & (abs(x0) < _INF) & (abs(x2) < _INF)
    return x0, x1, x2, ok


@_njit(inline=True)
def _g(x: float) -> bool:
    """The filter's guard of one number: zero, or in ``[INPUT_MIN, INPUT_MAX]`` (NaN fails)."""
    a = abs(x)
    return (a == 0.0) | ((a >= _IN_MIN) & (a <= _IN_MAX))


@_njit(inline=True)
def _guarded_sign(d: float, bound: float, ok: bool) -> float:
    """:func:`~quadric_contact.modes.kernels.signs.sign_within` of ``d`` and its ``bound``, as a
    double (the straight-line loop works in doubles); ``UNCERTAIN`` whenever the guard failed."""
    return 1.0 * sign_within(d, bound) if ok else _UNC


@_njit(inline=True)
def _definite(s1: float, s2: float, s3: float, s4: float) -> float:
    """:class:`~quadric_contact.theory.decision.Definite` from the three-valued signs of
    ``d1 .. d4`` (Sylvester: positive definite iff all are positive, negative definite iff
    they alternate ``-, +, -, +``), as :func:`quadric_contact.modes.decision.separation._definite_from_signs`
    says it, branch-free."""
    u1 = s1 == _UNC
    u2 = s2 == _UNC
    u3 = s3 == _UNC
    u4 = s4 == _UNC
    pos = ((s1 == 1.0) | u1) & ((s2 == 1.0) | u2) & ((s3 == 1.0) | u3) & ((s4 == 1.0) | u4)
    neg = ((s1 == -1.0) | u1) & ((s2 == 1.0) | u2) & ((s3 == -1.0) | u3) & ((s4 == 1.0) | u4)
    certain = (not u1) & (not u2) & (not u3) & (not u4)
    none = (not pos) & (not neg)
    return (
        _NONE
        if none
        else (
            _POSITIVE
            if (pos & (not neg) & certain)
            else (_NEGATIVE if (neg & (not pos) & certain) else _DEF_UNKNOWN)
        )
    )


@_njit(inline=True)
def member_minors_bounded(
    s: float, e: Any, q: Any, SK: tuple[float, float, float, float], inputs_ok: bool
) -> tuple[float, float, float, float, float, float, float, float, bool]:
    """The leading principal minors ``d1 .. d4`` of the member ``s E + Q`` as computed
    (:func:`~quadric_contact._generated.kernels.leading_minors_4` on ``fl(fl(s e) + q)``), their
    semi-static error bounds ``fl(S_k fl(R0 .. R_(k-1)))`` (``SK``:
    :data:`~quadric_contact.modes.kernels.errorbounds.MEMBER_MINORS_SEMI`) and whether the guards hold
    (``inputs_ok``: those of ``E`` and ``Q``).  ``e``, ``q``: the ten upper entries."""
    e00, e01, e02, e03, e11, e12, e13, e22, e23, e33 = e
    q00, q01, q02, q03, q11, q12, q13, q22, q23, q33 = q
    m00 = s * e00 + q00
    m01 = s * e01 + q01
    m02 = s * e02 + q02
    m03 = s * e03 + q03
    m11 = s * e11 + q11
    m12 = s * e12 + q12
    m13 = s * e13 + q13
    m22 = s * e22 + q22
    m23 = s * e23 + q23
    m33 = s * e33 + q33
    d1, d2, d3, d4 = _minors4(m00, m01, m02, m03, m11, m12, m13, m22, m23, m33)
    a = abs(s)
    w00 = a * abs(e00) + abs(q00)
    w01 = a * abs(e01) + abs(q01)
    w02 = a * abs(e02) + abs(q02)
    w03 = a * abs(e03) + abs(q03)
    w11 = a * abs(e11) + abs(q11)
    w12 = a * abs(e12) + abs(q12)
    w13 = a * abs(e13) + abs(q13)
    w22 = a * abs(e22) + abs(q22)
    w23 = a * abs(e23) + abs(q23)
    w33 = a * abs(e33) + abs(q33)
    R0 = max(max(w00, w01), max(w02, w03))
    R1 = max(max(w01, w11), max(w12, w13))
    R2 = max(max(w02, w12), max(w22, w23))
    R3 = max(max(w03, w13), max(w23, w33))
    p2 = R0 * R1
    p3 = p2 * R2
    p4 = p3 * R3
    ok = inputs_ok & ((a == 0.0) | ((a >= _S_MIN) & (a <= _S_MAX)))
    ok = ok & _g(m00) & _g(m01) & _g(m02) & _g(m03) & _g(m11) & _g(m12) & _g(m13) & _g(m22) & _g(m23)
    ok = ok & _g(m33) & _g(w00) & _g(w01) & _g(w02) & _g(w03) & _g(w11) & _g(w12) & _g(w13) & _g(w22)
    ok = ok & _g(w23) & _g(w33)
    return d1, d2, d3, d4, SK[0] * R0, SK[1] * p2, SK[2] * p3, SK[3] * p4, ok


@_njit(inline=True)
def _member(
    s: float, e: Any, q: Any, SK: tuple[float, float, float, float], inputs_ok: bool, certified: bool
) -> tuple[float, float]:
    """What the member ``s E + Q`` is (a :class:`~quadric_contact.theory.decision.Definite`
    code) and the three-valued sign of its determinant ``P(s)``: certain signs only
    (``certified``), or the computed signs as they are."""
    d1, d2, d3, d4, b1, b2, b3, b4, ok = member_minors_bounded(s, e, q, SK, inputs_ok)
    if certified:
        g1 = _guarded_sign(d1, b1, ok)
        g2 = _guarded_sign(d2, b2, ok)
        g3 = _guarded_sign(d3, b3, ok)
        g4 = _guarded_sign(d4, b4, ok)
    else:
        g1 = 1.0 * plain_sign(d1)
        g2 = 1.0 * plain_sign(d2)
        g3 = 1.0 * plain_sign(d3)
        g4 = 1.0 * plain_sign(d4)
    return _definite(g1, g2, g3, g4), g4


_member_called = _njit(getattr(_member, "py_func", _member))
""":func:`_member` as a function the scalar loops call rather than inline: those loops run for
few pairs, and each inlined copy of the member's program is compile time (LLVM copies the
inlined code for every call site)."""


@_njit(inline=True)
def decide_signature(
    ok: bool, def1: float, def2: float, def3: float, p1: float, p2: float, p3: float, certified: bool
) -> int:
    """The separation code (:data:`~quadric_contact.modes.decision.separation.SEP_MINUS`, ``CROSSING``,
    ``SEP_PLUS``, ``UNCERTAIN``) of one pair from what the members at the sample points
    ``s1 < s2 < s3`` are (``def*``) and the signs of ``P`` there (``p*``), looked up in the
    decision table.  ``ok``: the sample points are finite and increasing."""
    simple = ok and p1 == 1.0 and p2 == -1.0 and p3 == 1.0
    if def3 == _POSITIVE or (def1 != _NEGATIVE and (def1 == _POSITIVE or def2 == _POSITIVE)):
        definite, roots = int(_POSITIVE), (_SIMPLE if simple else _ROOTS_UNKNOWN)
    elif def1 == _NEGATIVE or def2 == _NEGATIVE or def3 == _NEGATIVE:
        definite, roots = int(_NEGATIVE), (_SIMPLE if simple else _ROOTS_UNKNOWN)
    elif simple:
        # only the first gap can be negative definite and only the last positive definite
        definite = int(_NONE) if (def1 == _NONE and def3 == _NONE) else int(_DEF_UNKNOWN)
        roots = _SIMPLE
    elif certified:
        definite, roots = int(_DEF_UNKNOWN), _ROOTS_UNKNOWN
    else:
        # a plain mode takes binary64's reading as it is: no definite member, and roots that are
        # non-real or simple as far as it can see (both mean a crossing)
        definite, roots = int(_NONE), _NONREAL
    return int(_REGION_OF[_table_index(_SURFACE_UNKNOWN, roots, definite, _PLANE_UNKNOWN)])


@_njit(inline=True)
def signature_prepare(eb_: Any, qb_: Any, m: int, cb: Any) -> None:
    """For the ``m`` pairs in the column buffers (``E`` in the paper's sign; rows of
    :data:`NB`): the coefficients ``c1 .. c4`` of ``P``, the input guard and the sign row (1:
    ``E`` is in the paper's sign already), into ``cb`` as :func:`signature_first` reads them
    (first sample point: the first critical point).  A straight-line loop."""
    S = NB
    for i in range(m):
        e = _load(eb_, i, S)
        q = _load(qb_, i, S)
        inputs_ok = _g(e[0]) & _g(e[1]) & _g(e[2]) & _g(e[3]) & _g(e[4]) & _g(e[5]) & _g(e[6])
        inputs_ok = inputs_ok & _g(e[7]) & _g(e[8]) & _g(e[9]) & _g(q[0]) & _g(q[1]) & _g(q[2])
        inputs_ok = inputs_ok & _g(q[3]) & _g(q[4]) & _g(q[5]) & _g(q[6]) & _g(q[7]) & _g(q[8]) & _g(q[9])
        c0, c1, c2, c3, c4 = _pencil(e, q)
        cb[i] = c1
        cb[S + i] = c2
        cb[2 * S + i] = c3
        cb[3 * S + i] = c4
        cb[4 * S + i] = 1.0 if inputs_ok else 0.0
        cb[5 * S + i] = 0.0
        cb[6 * S + i] = 1.0


@_njit(inline=True)
def signature_first(eb_: Any, qb_: Any, cb: Any, m: int, SKt: Any, certified: bool, fb: Any) -> None:
    """The straight-line stage of the signature for the ``m`` pairs of the column buffers (rows
    of :data:`NB`): the sample points and the member at the first point to try, into ``fb`` for
    :func:`signature_finish`.

    The rows are :data:`NB` wide, a constant, not a parameter: every access to one buffer is
    then at a known distance from the others, and the vectoriser checks the buffers against
    each other once.  With the width a run-time number each row is a pointer of its own, the
    checks between the five rows written and the twenty-seven read exceed what LLVM allows
    ("too many memory checks needed"), and the loop ran as scalar code.

    ``cb`` holds seven rows of :data:`NB`: the coefficients ``c1 .. c4`` of ``P`` for ``E`` in the
    paper's sign (they only place the sample points, which nothing trusts), whether both
    matrices pass the input guard (1/0), which sample point to try first (1: the last critical
    point, where a positive definite member lies when ``E`` is outside; 0: the first, where a
    negative definite one lies when ``E`` is inside), and the sign ``f = +-1`` that puts the
    ``E`` of the buffer in the paper's sign.  The member ``s (f E) + Q`` is computed as
    ``(f s) E + Q``: the same bits (a change of sign is exact), without a copy of ``E``."""
    S = NB
    for i in range(m):
        e = _load(eb_, i, S)
        q = _load(qb_, i, S)
        s1, s2, s3, ok = critical_points_fast(cb[i], cb[S + i], cb[2 * S + i], cb[3 * S + i])
        last = cb[5 * S + i] == 1.0
        f = cb[6 * S + i]
        da, ga = _member(f * (s3 if last else s1), e, q, SKt, cb[4 * S + i] == 1.0, certified)
        fb[i] = 1.0 if ok else 0.0
        fb[S + i] = da
        fb[2 * S + i] = s2
        fb[3 * S + i] = s1 if last else s3
        fb[4 * S + i] = ga


signature_first_called = _njit(getattr(signature_first, "py_func", signature_first))
""":func:`signature_first` as a function the decision kernel calls rather than inlines: inlined
into that kernel its loop ran at the speed of scalar code (about 60 ns a pair); called, its loop
is vectorised (four doubles a vector on AVX2, the rest of the block in scalar code, so the kernel
hands it multiples of eight pairs).  On a Xeon with AVX-512 it takes about 28 ns a pair,
vectorised or not: the three square roots and five divisions of the sample points bound it."""


def _witness_code(last: bool) -> int:
    """The separation code of a pair whose first member tried is a witness (positive definite
    at the last critical point, ``last``; negative definite at the first): what
    :func:`decide_signature` says whatever the other members and the signs of ``P`` (unknown
    here).  Read by the function's Python twin: at import, nothing is compiled."""
    f = plain(decide_signature)
    if last:
        return int(f(False, _DEF_UNKNOWN, _DEF_UNKNOWN, _POSITIVE, _UNC, _UNC, _UNC, True))
    return int(f(False, _NEGATIVE, _DEF_UNKNOWN, _DEF_UNKNOWN, _UNC, _UNC, _UNC, True))


WITNESS_LAST = _witness_code(True)
"""The separation code of a pair with a positive definite member at the last critical point."""
WITNESS_FIRST = _witness_code(False)
"""The separation code of a pair with a negative definite member at the first critical point."""


@_njit(inline=True)
def witness(last: bool, da: float) -> bool:
    """The member first tried (``da``, a :class:`~quadric_contact.theory.decision.Definite`
    code) is a witness: positive definite at the last critical point (``last``), negative
    definite at the first; the code is then :data:`WITNESS_LAST` or :data:`WITNESS_FIRST`."""
    return (da == _POSITIVE) if last else (da == _NEGATIVE)


@_njit(inline=True)
def signature_finish(
    eb_: Any, qb_: Any, cb: Any, fb: Any, i: int, S: int, SKt: Any, K: Any, KD: Any, certified: bool,
    e1: Any, q1: Any,
) -> int:  # fmt: skip
    """The separation code of the pair in column ``i`` after :func:`signature_first`: the other
    members only where no witness was found (the last or first, then the middle), the facts
    looked up in the decision table, and a second reading by the scalar certificate
    (:func:`~quadric_contact.modes.decision.separation._separation_one`) where the fast one is uncertain.
    ``e1``, ``q1`` (10): scratch."""
    last = cb[5 * S + i] == 1.0
    f = cb[6 * S + i]
    da = fb[S + i]
    ga = fb[4 * S + i]
    if witness(last, da):
        # a witness at the first point tried: the other members are not needed
        return WITNESS_LAST if last else WITNESS_FIRST
    e = _load(eb_, i, S)
    q = _load(qb_, i, S)
    inputs_ok = cb[4 * S + i] == 1.0
    db, gb = _member_called(f * fb[3 * S + i], e, q, SKt, inputs_ok, certified)
    if (db == _NEGATIVE) if last else (db == _POSITIVE):
        d2, g2 = _DEF_UNKNOWN, _UNC
    else:
        d2, g2 = _member_called(f * fb[2 * S + i], e, q, SKt, inputs_ok, certified)
    if last:
        code = decide_signature(fb[i] == 1.0, db, d2, da, gb, g2, ga, certified)
    else:
        code = decide_signature(fb[i] == 1.0, da, d2, db, ga, g2, gb, certified)
    if code == UNCERTAIN and certified:
        # a second reading: trigonometric sample points and magnitude programs
        for k in range(10):
            e1[k] = f * eb_[k * S + i]
            q1[k] = qb_[k * S + i]
        code = _separation_one(e1, q1, K, KD, True)
    return code


signature_finish_called = _njit(getattr(signature_finish, "py_func", signature_finish))
""":func:`signature_finish` as a function the decision kernel calls rather than inlines: it runs
for the few pairs without a witness at the first member tried, and inlined into the loop over
the listed pairs its size made that loop several times slower for all of them."""


@_njit(inline=True)
def signature_rows(
    eb_: Any, qb_: Any, cb: Any, m: int, S: int, SK: Any, K: Any, KD: Any, certain_only: float, fb: Any,
    e1: Any, q1: Any, at: Any, out: Any,
) -> None:  # fmt: skip
    """The separation codes of the ``m`` pairs in the column buffers ``eb_``, ``qb_`` (one row of
    ``S`` per upper entry), written to ``out[at[i]]``: :func:`signature_first` over the block,
    then :func:`signature_finish` pair by pair.  ``cb``: seven rows of ``S``, as
    :func:`signature_first` reads them; ``certain_only``: 1.0 for certain signs only (the
    certified reading), 0.0 for the plain one (a run-time number: one signature kernel serves
    both readings).  ``fb`` (``5 S``), ``e1``, ``q1`` (10): scratch."""
    SKt = (SK[0], SK[1], SK[2], SK[3])  # scalars: no store in the loop may alias them
    certified = certain_only == 1.0
    signature_first(eb_, qb_, cb, m, SKt, certified, fb)
    for i in range(m):
        out[at[i]] = signature_finish(eb_, qb_, cb, fb, i, S, SKt, K, KD, certified, e1, q1)


def _make_signature() -> Any:
    """The block kernel (``certain_only``: 1.0 for the certified reading, 0.0 for the plain one,
    see :func:`signature_rows`)."""

    def kernel(
        E: Any,
        Q: Any,  # (n, 16): row-major 4x4 matrices
        eidx: Any,
        qidx: Any,
        es: int,
        qs: int,
        lo: int,
        hi: int,
        SK: Any,
        K: Any,
        KD: Any,
        certain_only: float,
        out: Any,
    ) -> None:
        S = NB
        eb_ = np.empty(10 * S)
        qb_ = np.empty(10 * S)
        fb = np.empty(5 * S)
        cb = np.empty(7 * S)
        e1 = np.empty(10)
        q1 = np.empty(10)
        at = np.empty(S, np.intp)
        for blo in range(lo, hi, S):
            m = min(S, hi - blo)
            for t in range(m):
                p = blo + t
                ie = eidx[p] if eidx.shape[0] > 0 else p * es
                iq = qidx[p] if qidx.shape[0] > 0 else p * qs
                _gather_full(E, ie, eb_, t, S)
                _gather_full(Q, iq, qb_, t, S)
                if eb_[t] < 0.0:  # the paper's sign: det E < 0
                    for k in range(10):
                        eb_[k * S + t] = -eb_[k * S + t]
                at[t] = p
            signature_prepare(eb_, qb_, m, cb)
            _signature_rows_called(eb_, qb_, cb, m, S, SK, K, KD, certain_only, fb, e1, q1, at, out)

    return kernel


_signature_rows_called = _njit(getattr(signature_rows, "py_func", signature_rows))
""":func:`signature_rows` as a function of its own, for the signature kernel: that kernel
serves the general steps (the pairs the decision kernel leaves, and packed input), where its
speed matters less than the minute of compile time a second inlined copy would cost."""

_KERNELS: dict[bool, Any] = {}
_KERNELS_LOCK = threading.Lock()


def _kernel(compiled: bool) -> Any:
    """The block kernel, compiled or as Python (made once, on first use)."""
    k = _KERNELS.get(compiled)
    if k is None:
        with _KERNELS_LOCK:
            k = _KERNELS.get(compiled)
            if k is None:
                f = _make_signature()
                # the Python variant runs the two straight-line loops by Python as well
                k = _KERNELS[compiled] = _njit(f) if compiled else plain(f)
    return k


def signature_float(
    pairs: Pairs, *, certified: bool, backend: str = "numba", threads: int | None = None
) -> np.ndarray:
    """Separation codes of every pair in binary64 (as
    :func:`~quadric_contact.modes.decision.separation.separation_float`, the same facts and the same
    table): certified (``UNCERTAIN`` where neither reading is sure) or plain (always an answer).
    Inputs are assumed validated (finite, symmetric, ``E`` an ellipsoid)."""
    n = pairs.n
    out = np.empty(n, dtype=np.int8)
    if n == 0:
        return out
    rounded = pairs.E.rounded or pairs.Q.rounded
    SK = np.array(eb.MEMBER_MINORS_SEMI[rounded])
    K = np.array(eb.MEMBER_ERRBOUND[rounded])
    KD = np.array(eb.MEMBER_MINORS_ERRBOUND[rounded])
    eidx, qidx, es, qs = pairs.kernel_indices()
    E, Q = pairs.E.floats.reshape(-1, 16), pairs.Q.floats.reshape(-1, 16)  # flat rows, as gathered
    flag = 1.0 if certified else 0.0
    if backend == "numpy" or not HAVE_NUMBA:
        _kernel(False)(E, Q, eidx, qidx, es, qs, 0, n, SK, K, KD, flag, out)
        return out
    k = _kernel(True)
    run_parallel(lambda lo, hi: k(E, Q, eidx, qidx, es, qs, lo, hi, SK, K, KD, flag, out), n, threads)
    return out
