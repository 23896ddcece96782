"""The separation certificate: where ``E`` lies against ``Q``, read off the members of the pencil.

This stage needs no smallness (Definition 1) and no type of ``Q``: it answers the
geometric question for any pair, and it certifies its own answers.  ``E`` is an
ellipsoid with the paper's sign (``det E < 0``, positive definite quadratic part) and
``f(X) = X^T Q X`` is read on the *surface* of ``E``.

Three facts
-----------
1. *S-lemma (Finsler).*  ``f > 0`` on the surface of ``E`` iff some member
   ``lambda E + Q`` of the pencil is positive definite; ``f < 0`` there iff some
   member is negative definite.  One direction is immediate: on the surface
   ``X^T E X = 0``, so ``f(X) = X^T (lambda E + Q) X``.  Conversely, the cone
   ``{X^T E X = 0}`` has no point at infinity (``A_E`` is definite), so ``f >= t > 0``
   on the surface means ``Q - t e4 e4^T >= 0`` on the cone, and since ``E`` is
   indefinite Finsler's lemma gives ``mu`` with ``Q - t e4 e4^T - mu E >= 0``; then
   ``Q - (mu - eps) E`` is positive definite for a small ``eps > 0`` (its null vectors
   for ``eps = 0`` lie at infinity, where ``E`` is positive).
2. *Signature sequence.*  ``n+(lambda)``, the number of positive eigenvalues of
   ``lambda E + Q``, is that of ``-E`` (one) for ``lambda -> -inf`` and that of ``E``
   (three) for ``lambda -> +inf``; it is constant between consecutive roots of
   ``P(lambda) = det(lambda E + Q)`` and changes across a root of multiplicity ``m`` by
   at most ``m`` and by a number of the parity of ``m`` (the eigenvalues are analytic in
   ``lambda``; ``P`` is their product).
3. *Tangency needs a multiple root.*  If the surfaces touch at ``X`` (or ``f`` has a
   zero extremum on ``E`` at ``X``), then ``(lambda0 E + Q) X = 0`` for a real
   ``lambda0`` and ``P'(lambda0) = tr(adj(lambda0 E + Q) E)`` is ``kappa X^T E X = 0``
   (rank 3) or 0 (lower rank): ``lambda0`` is a multiple root.

The certificate
---------------
With approximate roots ``r1 <= r2 <= r3 <= r4`` of ``P`` and the sample points
``s12, s23, s34`` between them:

* a member that is certainly definite at any sample point proves ``f > 0``
  (``R_PLUS``) or ``f < 0`` (``R_MINUS``) on ``E``: strict separation, whatever
  the roots;
* if ``n+`` is certain at the three sample points and ``1, n+(s12), n+(s23), n+(s34), 3``
  moves by exactly one at each step, each of the four intervals holds exactly one
  simple root (an odd multiplicity, four in all): the roots are real and simple, so
  there is no tangency (fact 3), the sampled gaps are all the gaps, and if no member
  is definite ``f`` takes both signs (fact 1): the surfaces cross (``CONTACT``);
* anything else (a tangency, a multiple root, sample points that do not separate the
  roots, a sign a mode cannot tell) is ``UNCERTAIN`` for the certified modes.

The codes are those of :class:`~quadric_contact.modes.codes.RegionCode`: ``-1`` ``E``
in the interior of ``R-``, ``0`` the surfaces cross, ``1`` ``E`` in the interior of
``R+``, ``2`` uncertain.  The inertia of a member comes from the signs of the sums
``E1 .. E4`` of its principal minors (Descartes' rule is exact for the real-rooted
characteristic polynomial), in binary64 with the rigorous bounds of
:data:`~quadric_contact.modes.kernels.errorbounds.MEMBER_ERRBOUND`, or in the numbers of an
object mode (ball, mpmath, exact); :func:`separation_isolated` places exact rational
sample points between the exactly isolated roots.  The plain ``float`` and ``mpmath``
modes answer everything: where they find no definite member they say the surfaces
cross.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from quadric_contact._generated import formulas, kernels
from quadric_contact.modes.codes import UNCERTAIN
from quadric_contact.modes.kernels import errorbounds as eb
from quadric_contact.modes.kernels._jit import njit as _njit
from quadric_contact.modes.kernels._jit import plain
from quadric_contact.modes.kernels.signs import plain_sign, sign_within
from quadric_contact.modes.stacks.pairs import Pairs
from quadric_contact.modes.stacks.validation import exact_matrix
from quadric_contact.theory import decision
from quadric_contact.theory.certificate import separation_certificate
from quadric_contact.theory.pencil import characteristic_polynomial
from quadric_contact.theory.results import Region

__all__ = [
    "CROSSING",
    "SEP_MINUS",
    "SEP_PLUS",
    "UNCERTAIN",
    "decide_from_counts",
    "quartic_roots",
    "separation_float",
    "separation_isolated",
    "separation_objects",
]

SEP_MINUS = -1
CROSSING = 0
SEP_PLUS = 1

_pencil = _njit(formulas.pencil_coefficients, inline=True)
_invariants = _njit(kernels.quadric_invariants, inline=True)
_invariants_mag = _njit(kernels.quadric_invariants_magnitude, inline=True)
_minors4 = _njit(kernels.leading_minors_4, inline=True)
_minors4_mag = _njit(kernels.leading_minors_4_magnitude, inline=True)
_critical = _njit(decision.critical_points, inline=True)
_INPUT_MIN = eb.INPUT_MIN
_INPUT_MAX = eb.INPUT_MAX
_SAMPLE_MIN = eb.SAMPLE_MIN
_SAMPLE_MAX = eb.SAMPLE_MAX
_TWO_PI_3 = 2.0943951023931957
_FOUR_PI_3 = 4.1887902047863905


# -- approximate roots of the quartic --------------------------------------------------------


@_njit(inline=True)
def _cubic_roots(A: float, B: float, C: float) -> tuple[float, float, float]:
    """The roots of ``t^3 + A t^2 + B t + C`` when they are real (trigonometric form);
    approximations only (the certificate does not trust them)."""
    a3 = A / 3.0
    P = B - A * a3
    Qc = a3 * (2.0 * a3 * a3 - B) + C
    if P >= 0.0:
        w = np.cbrt(-Qc)
        return w - a3, w - a3, w - a3
    m = 2.0 * math.sqrt(-P / 3.0)
    arg = 3.0 * Qc / (P * m)
    arg = min(1.0, max(-1.0, arg))
    th = math.acos(arg) / 3.0
    return m * math.cos(th) - a3, m * math.cos(th - _TWO_PI_3) - a3, m * math.cos(th - _FOUR_PI_3) - a3


@_njit(inline=True)
def _polish(x: float, b0: float, b1: float, b2: float, b3: float) -> float:
    """Two Newton steps on the monic ``x^4 + b3 x^3 + b2 x^2 + b1 x + b0``, each kept only if
    it lowers ``|p|``."""
    for _ in range(2):
        p = (((x + b3) * x + b2) * x + b1) * x + b0
        d = ((4.0 * x + 3.0 * b3) * x + 2.0 * b2) * x + b1
        if d == 0.0 or not math.isfinite(p):
            break
        y = x - p / d
        q = (((y + b3) * y + b2) * y + b1) * y + b0
        if not abs(q) < abs(p):
            break
        x = y
    return x


@_njit(inline=True)
def quartic_roots(
    c0: float, c1: float, c2: float, c3: float, c4: float
) -> tuple[float, float, float, float, bool]:
    """Approximate real roots ``r1 <= r2 <= r3 <= r4`` of ``c4 x^4 + .. + c0`` (``c4 != 0``),
    assuming all four are real (Euler's solution through the resolvent cubic, on the
    polynomial scaled by a power of two above Fujiwara's root bound, then polished by
    Newton's method); the flag is False when the numbers are not finite.

    Examples
    --------
    >>> [round(r, 12) for r in quartic_roots(24.0, -50.0, 35.0, -10.0, 1.0)[:4]]
    [1.0, 2.0, 3.0, 4.0]
    """
    a3 = c3 / c4
    a2 = c2 / c4
    a1 = c1 / c4
    a0 = c0 / c4
    bound = 2.0 * max(abs(a3), math.sqrt(abs(a2)), np.cbrt(abs(a1)), math.sqrt(math.sqrt(abs(a0) / 2.0)))
    if not math.isfinite(bound):
        return 0.0, 0.0, 0.0, 0.0, False
    if bound == 0.0:
        return 0.0, 0.0, 0.0, 0.0, True
    scale = 2.0 ** math.ceil(math.log2(bound))
    b3 = a3 / scale
    b2 = a2 / (scale * scale)
    b1 = a1 / (scale * scale * scale)
    b0 = a0 / (scale * scale * scale * scale)
    h = b3 / 4.0
    p = b2 - 6.0 * h * h
    q = b1 - 2.0 * b2 * h + 8.0 * h * h * h
    r = b0 - b1 * h + b2 * h * h - 3.0 * h * h * h * h
    z1, z2, z3 = _cubic_roots(2.0 * p, p * p - 4.0 * r, -q * q)
    a = math.sqrt(max(z1, 0.0))
    b = math.sqrt(max(z2, 0.0))
    c = math.sqrt(max(z3, 0.0))
    if q > 0.0:
        c = -c
    y0 = 0.5 * (a + b + c) - h
    y1 = 0.5 * (a - b - c) - h
    y2 = 0.5 * (-a + b - c) - h
    y3 = 0.5 * (-a - b + c) - h
    y0 = _polish(y0, b0, b1, b2, b3) * scale
    y1 = _polish(y1, b0, b1, b2, b3) * scale
    y2 = _polish(y2, b0, b1, b2, b3) * scale
    y3 = _polish(y3, b0, b1, b2, b3) * scale
    # sort four numbers (a sorting network)
    if y0 > y1:
        y0, y1 = y1, y0
    if y2 > y3:
        y2, y3 = y3, y2
    if y0 > y2:
        y0, y2 = y2, y0
    if y1 > y3:
        y1, y3 = y3, y1
    if y1 > y2:
        y1, y2 = y2, y1
    ok = math.isfinite(y0) and math.isfinite(y1) and math.isfinite(y2) and math.isfinite(y3)
    return y0, y1, y2, y3, ok


# -- inertia of a member -----------------------------------------------------------------------


@_njit(inline=True)
def _variations(a: int, b: int, c: int, d: int) -> int:
    """Sign variations of ``(1, -a, b, -c, d)``: the positive eigenvalues of a symmetric
    matrix whose principal-minor sums have the signs ``a, b, c, d`` (Descartes)."""
    count = 0
    last = 1
    for s in (-a, b, -c, d):
        if s != 0:
            if s != last:
                count += 1
            last = s
    return count


@_njit(inline=True)
def positive_count(s1: int, s2: int, s3: int, s4: int) -> int:
    """Positive eigenvalues of a *nonsingular* member from the three-valued signs of
    ``E1 .. E4`` (``UNCERTAIN = 2``): the count every completion of the uncertain signs agrees
    on, or -1.  The determinant ``E4`` must be certainly non-zero: a singular member (the
    sample point is a root) says nothing about the gap it is meant to sample."""
    if s4 != 1 and s4 != -1:
        return -1
    lo1, hi1 = (-1, 1) if s1 == UNCERTAIN else (s1, s1)
    lo2, hi2 = (-1, 1) if s2 == UNCERTAIN else (s2, s2)
    lo3, hi3 = (-1, 1) if s3 == UNCERTAIN else (s3, s3)
    found = -1
    for a in range(lo1, hi1 + 1):
        for b in range(lo2, hi2 + 1):
            for c in range(lo3, hi3 + 1):
                n = _variations(a, b, c, s4)
                if found == -1:
                    found = n
                elif n != found:
                    return -1
    return found


@_njit(inline=True)
def _guarded(x: float) -> bool:
    a = abs(x)
    return a == 0.0 or (_INPUT_MIN <= a <= _INPUT_MAX)


@_njit(inline=True)
def _member(s: float, e: Any, q: Any) -> tuple[Any, Any, bool]:
    """The computed entries of the member ``s E + Q``, their magnitudes ``|s| |e| + |q|`` (the
    arguments of the magnitude programs) and whether every one of them, and ``s``, passes the
    filter's guard (:mod:`quadric_contact.modes.kernels.errorbounds`)."""
    m = (
        s * e[0] + q[0], s * e[1] + q[1], s * e[2] + q[2], s * e[3] + q[3], s * e[4] + q[4],
        s * e[5] + q[5], s * e[6] + q[6], s * e[7] + q[7], s * e[8] + q[8], s * e[9] + q[9],
    )  # fmt: skip
    a = abs(s)
    w = (
        a * abs(e[0]) + abs(q[0]), a * abs(e[1]) + abs(q[1]), a * abs(e[2]) + abs(q[2]),
        a * abs(e[3]) + abs(q[3]), a * abs(e[4]) + abs(q[4]), a * abs(e[5]) + abs(q[5]),
        a * abs(e[6]) + abs(q[6]), a * abs(e[7]) + abs(q[7]), a * abs(e[8]) + abs(q[8]),
        a * abs(e[9]) + abs(q[9]),
    )  # fmt: skip
    ok = s == 0.0 or _SAMPLE_MIN <= a <= _SAMPLE_MAX
    for k in range(10):
        ok = ok and _guarded(m[k]) and _guarded(w[k])
    return m, w, ok


@_njit(inline=True)
def _member_count(s: float, e: Any, q: Any, K: Any, certified: bool) -> int:
    """``n+`` of the member ``s E + Q`` (-1 if uncertain)."""
    m, w, ok = _member(s, e, q)
    inv = _invariants(m[0], m[1], m[2], m[3], m[4], m[5], m[6], m[7], m[8], m[9])
    if not certified:
        return positive_count(
            plain_sign(inv[3]),
            plain_sign(inv[4]),
            plain_sign(inv[5]),
            plain_sign(inv[6]),
        )
    if not ok:
        return -1
    mag = _invariants_mag(w[0], w[1], w[2], w[3], w[4], w[5], w[6], w[7], w[8], w[9])
    return positive_count(
        sign_within(inv[3], K[0] * mag[3]),
        sign_within(inv[4], K[1] * mag[4]),
        sign_within(inv[5], K[2] * mag[5]),
        sign_within(inv[6], K[3] * mag[6]),
    )


_REGION_OF = decision.REGION_OF
_table_index = _njit(decision.table_index, inline=True)
_SURFACE_UNKNOWN = int(decision.Surface.UNKNOWN)
_PLANE_UNKNOWN = int(decision.Plane.UNKNOWN)
_POSITIVE, _NEGATIVE = int(decision.Definite.POSITIVE), int(decision.Definite.NEGATIVE)
_NONE, _DEF_UNKNOWN = int(decision.Definite.NONE), int(decision.Definite.UNKNOWN)
_SIMPLE, _NONREAL = int(decision.Roots.SIMPLE), int(decision.Roots.NONREAL)
_ROOTS_UNKNOWN = int(decision.Roots.UNKNOWN)


@_njit(inline=True)
def decide_from_counts(n12: int, n23: int, n34: int, certified: bool) -> int:
    """The separation code from ``n+`` at the three sample points (-1: uncertain), looked up
    in the decision table (:data:`quadric_contact.theory.decision.REGION_OF`).

    The counts are facts about the pencil: a count of 4 (0) is a positive (negative) definite
    member; ``1, n12, n23, n34, 3`` moving by exactly one at each step proves four simple real
    roots, one in each interval, so the three points sampled every gap and a definite member
    would have been seen.  Otherwise the roots and the members of unsampled gaps are unknown
    to a certified mode; a plain mode takes binary64's reading as it is: no definite member,
    and roots that are non-real or simple as far as it can see (both mean a crossing)."""
    if n12 == 4 or n23 == 4 or n34 == 4:
        definite, roots = _POSITIVE, _ROOTS_UNKNOWN
    elif n12 == 0 or n23 == 0 or n34 == 0:
        definite, roots = _NEGATIVE, _ROOTS_UNKNOWN
    else:
        steps = abs(n12 - 1) == 1 and abs(n23 - n12) == 1 and abs(n34 - n23) == 1 and abs(3 - n34) == 1
        if n12 >= 0 and n23 >= 0 and n34 >= 0 and steps:
            definite, roots = _NONE, _SIMPLE
        elif certified:
            definite, roots = _DEF_UNKNOWN, _ROOTS_UNKNOWN
        else:
            definite, roots = _NONE, _NONREAL
    return _REGION_OF[_table_index(_SURFACE_UNKNOWN, roots, definite, _PLANE_UNKNOWN)]


@_njit(inline=True)
def _definite_from_signs(s1: int, s2: int, s3: int, s4: int) -> int:
    """:class:`~quadric_contact.theory.decision.Definite` from the three-valued signs of the
    leading principal minors ``d1 .. d4`` (Sylvester: positive definite iff all are positive,
    negative definite iff they alternate ``-, +, -, +``; exact both ways)."""
    pos = (s1 == 1 or s1 == UNCERTAIN) and (s2 == 1 or s2 == UNCERTAIN)
    pos = pos and (s3 == 1 or s3 == UNCERTAIN) and (s4 == 1 or s4 == UNCERTAIN)
    neg = (s1 == -1 or s1 == UNCERTAIN) and (s2 == 1 or s2 == UNCERTAIN)
    neg = neg and (s3 == -1 or s3 == UNCERTAIN) and (s4 == 1 or s4 == UNCERTAIN)
    certain = s1 != UNCERTAIN and s2 != UNCERTAIN and s3 != UNCERTAIN and s4 != UNCERTAIN
    if not pos and not neg:
        return _NONE
    if pos and not neg and certain:
        return _POSITIVE
    if neg and not pos and certain:
        return _NEGATIVE
    return _DEF_UNKNOWN


@_njit(inline=True)
def _member_definite(s: float, e: Any, q: Any, KD: Any, certified: bool) -> int:
    """Is the member ``s E + Q`` definite?  Sylvester's minors of its computed entries against
    :data:`~quadric_contact.modes.kernels.errorbounds.MEMBER_MINORS_ERRBOUND` (certified), or their plain
    signs."""
    m, w, ok = _member(s, e, q)
    d = _minors4(m[0], m[1], m[2], m[3], m[4], m[5], m[6], m[7], m[8], m[9])
    if not certified:
        return _definite_from_signs(plain_sign(d[0]), plain_sign(d[1]), plain_sign(d[2]), plain_sign(d[3]))
    if not ok:
        return _DEF_UNKNOWN
    mag = _minors4_mag(w[0], w[1], w[2], w[3], w[4], w[5], w[6], w[7], w[8], w[9])
    return _definite_from_signs(
        sign_within(d[0], KD[0] * mag[0]),
        sign_within(d[1], KD[1] * mag[1]),
        sign_within(d[2], KD[2] * mag[2]),
        sign_within(d[3], KD[3] * mag[3]),
    )


@_njit(inline=True)
def _separation_one(e: Any, q: Any, K: Any, KD: Any, certified: bool) -> int:
    if e[0] < 0.0:
        for k in range(10):
            e[k] = -e[k]
    if certified:
        for k in range(10):
            if not (_guarded(e[k]) and _guarded(q[k])):
                return UNCERTAIN
    c0, c1, c2, c3, c4 = _pencil(e[0], e[1], e[2], e[3], e[4], e[5], e[6], e[7], e[8], e[9],
                                 q[0], q[1], q[2], q[3], q[4], q[5], q[6], q[7], q[8], q[9])  # fmt: skip
    if c4 == 0.0:
        return UNCERTAIN if certified else CROSSING
    # Sample points: the critical points of P, one in each gap when the four roots are real and
    # simple (the scalar path's points, theory.decision.critical_points); else between approximate
    # roots.
    s1, s2, s3, ok = _critical(c1 / c4, c2 / c4, c3 / c4, 1.0)
    if not ok:
        r0, r1, r2, r3, ok = quartic_roots(c0, c1, c2, c3, c4)
        if not ok:
            return UNCERTAIN if certified else CROSSING
        s1, s2, s3 = 0.5 * (r0 + r1), 0.5 * (r1 + r2), 0.5 * (r2 + r3)
    # The likeliest certificates first, by Sylvester's minors: outside (R+) in the last gap,
    # inside (R-) in the first.
    d = _member_definite(s3, e, q, KD, certified)
    if d == _POSITIVE:
        return SEP_PLUS
    d = _member_definite(s1, e, q, KD, certified)
    if d == _NEGATIVE:
        return SEP_MINUS
    # No definite member there: the inertia at each point tells whether the roots are four and
    # simple (then every gap was sampled) or whether a definite member may hide elsewhere.
    n12 = _member_count(s1, e, q, K, certified)
    n23 = _member_count(s2, e, q, K, certified)
    n34 = _member_count(s3, e, q, K, certified)
    return decide_from_counts(n12, n23, n34, certified)


def _separation_impl(
    E: Any,
    Q: Any,
    eidx: Any,
    qidx: Any,
    es: int,
    qs: int,
    lo: int,
    hi: int,
    K: Any,
    KD: Any,
    certified: bool,
    out: Any,
) -> None:
    e = np.empty(10)
    q = np.empty(10)
    for p in range(lo, hi):
        ie = eidx[p] if eidx.shape[0] > 0 else p * es
        iq = qidx[p] if qidx.shape[0] > 0 else p * qs
        e[0] = E[ie, 0, 0]
        e[1] = E[ie, 0, 1]
        e[2] = E[ie, 0, 2]
        e[3] = E[ie, 0, 3]
        e[4] = E[ie, 1, 1]
        e[5] = E[ie, 1, 2]
        e[6] = E[ie, 1, 3]
        e[7] = E[ie, 2, 2]
        e[8] = E[ie, 2, 3]
        e[9] = E[ie, 3, 3]
        q[0] = Q[iq, 0, 0]
        q[1] = Q[iq, 0, 1]
        q[2] = Q[iq, 0, 2]
        q[3] = Q[iq, 0, 3]
        q[4] = Q[iq, 1, 1]
        q[5] = Q[iq, 1, 2]
        q[6] = Q[iq, 1, 3]
        q[7] = Q[iq, 2, 2]
        q[8] = Q[iq, 2, 3]
        q[9] = Q[iq, 3, 3]
        out[p] = _separation_one(e, q, K, KD, certified)


def separation_float(pairs: Pairs, *, certified: bool) -> np.ndarray:
    """Separation codes of every pair in binary64, pair by pair with :func:`_separation_one`:
    certified (``UNCERTAIN`` where a sign or a guard fails) or plain (always an answer).
    Inputs are assumed validated (finite, symmetric, ``E`` an ellipsoid).

    The reference of the scalar certificate, for tests and proofs: the cascade runs the block
    kernel :func:`~quadric_contact.modes.kernels.signature.signature_float`, which reads the
    same facts through the same table and falls back to this certificate pair by pair where
    its fast reading is not sure (a compiled copy of this loop would only be compiled for the
    tests, a minute of CPU in every cold test run)."""
    n = pairs.n
    out = np.empty(n, dtype=np.int8)
    if n == 0:
        return out
    rounded = pairs.E.rounded or pairs.Q.rounded
    K = np.array(eb.MEMBER_ERRBOUND[rounded])
    KD = np.array(eb.MEMBER_MINORS_ERRBOUND[rounded])
    eidx, qidx, es, qs = pairs.kernel_indices()
    # run by Python all the way down: called from Python, the inline certificate would be
    # compiled on its own, uncached, in every process
    plain(_separation_impl)(pairs.E.floats, pairs.Q.floats, eidx, qidx, es, qs, 0, n, K, KD, certified, out)
    return out


# -- object modes: the same certificate in other numbers ------------------------------------------


def _approx(values: np.ndarray) -> np.ndarray:
    """Floats near the values of an object array (ints, Fractions, mpf, arb midpoints)."""

    def one(v: Any) -> float:
        mid = getattr(v, "mid", None)
        if callable(mid):
            v = mid()
        try:
            return float(v)
        except (OverflowError, ValueError):
            return math.nan

    return np.frompyfunc(one, 1, 1)(values).astype(np.float64)


def sample_points(coefficients: list[np.ndarray]) -> np.ndarray:
    """``(n, 3)`` float sample points ``s12, s23, s34`` between the approximate roots of each
    quartic (``coefficients``: ``c0 .. c4`` as float arrays); NaN where they cannot be had."""
    c = [np.asarray(x, dtype=np.float64) for x in coefficients]
    n = c[0].shape[0]
    out = np.full((n, 3), np.nan)
    # the helper's Python twin: a compiled helper called from Python is compiled in every process
    # (it is inlined into the kernels, not cached)
    roots = np.vectorize(plain(quartic_roots), otypes=[float] * 4 + [bool])
    with np.errstate(all="ignore"):
        good = np.isfinite(np.stack(c)).all(axis=0) & (c[4] != 0.0)
        if good.any():
            r0, r1, r2, r3, ok = roots(*(x[good] for x in c))
            s = np.stack([0.5 * (r0 + r1), 0.5 * (r1 + r2), 0.5 * (r2 + r3)], axis=1)
            s[~np.asarray(ok, dtype=bool)] = np.nan
            out[good] = s
    return out


def separation_objects(mode: Any, pairs: Pairs, *, certified: bool) -> np.ndarray:
    """Separation codes with the numbers of an object mode (``ball``, ``mpmath``, ``exact``):
    sample points from approximate roots (binary64; the mode's own ``separation_samples`` where
    it has them: the mpmath mode's roots at its digits), the members' principal-minor sums in the mode's
    numbers, their signs by :meth:`~quadric_contact.modes.numbers.objects.ObjectMode.signs`."""
    n = pairs.n
    out = np.full(n, UNCERTAIN, dtype=np.int8)
    if n == 0:
        return out
    e_rows, q_rows = pairs.e_rows(), pairs.q_rows()
    ue, ie = np.unique(e_rows, return_inverse=True)
    uq, iq = np.unique(q_rows, return_inverse=True)
    with mode.context():
        e_cols = [col[ie] for col in mode.convert(pairs.E, ue)]
        q_cols = [col[iq] for col in mode.convert(pairs.Q, uq)]
        flip = _approx(e_cols[0]) < 0
        if flip.any():
            e_cols = [np.where(flip, -col, col) for col in e_cols]
        c = formulas.pencil_coefficients(*e_cols, *q_cols)
        samples: np.ndarray = sample_points([_approx(x) for x in c])
        finite = np.isfinite(samples)
        own = getattr(mode, "separation_samples", None)  # sample points in the mode's numbers
        if own is not None:
            mine = own(c)
            found = np.isfinite(_approx(mine[:, 0]))  # all three, or none
            samples = samples.astype(object)
            samples[found] = mine[found]
            finite[found] = True
        counts = np.full((n, 3), -1, dtype=np.int64)
        number = mode.number
        count_positive = plain(positive_count)
        for k in range(3):
            s = samples[:, k]
            ok = finite[:, k]
            if not ok.any():
                continue
            idx = np.flatnonzero(ok)
            sv = np.array([number(float(v)) if isinstance(v, float) else v for v in s[idx]], dtype=object)
            member = [sv * e[idx] + qq[idx] for e, qq in zip(e_cols, q_cols, strict=True)]
            inv = kernels.quadric_invariants(*member)
            signs = [mode.signs(np.asarray(inv[j], dtype=object)) for j in range(3, 7)]
            for t, i in enumerate(idx):
                counts[i, k] = count_positive(
                    int(signs[0][t]), int(signs[1][t]), int(signs[2][t]), int(signs[3][t])
                )
    decide_counts = plain(decide_from_counts)
    for p in range(n):
        out[p] = decide_counts(int(counts[p, 0]), int(counts[p, 1]), int(counts[p, 2]), certified)
    return out


def separation_isolated(pairs: Pairs) -> np.ndarray:
    """Exact separation codes with exact sample points between the exactly isolated roots
    (:func:`quadric_contact.theory.certificate.separation_certificate`): a definite member gives
    ``R_MINUS``/``R_PLUS``; four simple real roots and none definite ``CONTACT``; otherwise
    (a multiple root without a definite member: a tangency or a degenerate pencil)
    ``UNCERTAIN``."""

    codes = {Region.R_MINUS: SEP_MINUS, Region.CONTACT: CROSSING, Region.R_PLUS: SEP_PLUS, None: UNCERTAIN}
    n = pairs.n
    out = np.full(n, UNCERTAIN, dtype=np.int8)
    e_rows, q_rows = pairs.e_rows(), pairs.q_rows()
    cache: dict[tuple[int, int], int] = {}
    for p in range(n):
        key = (int(e_rows[p]), int(q_rows[p]))
        if key not in cache:
            P = characteristic_polynomial(exact_matrix(pairs.E, key[0]), exact_matrix(pairs.Q, key[1]))
            cache[key] = codes[separation_certificate(P).region]
        out[p] = cache[key]
    return out
