"""A certified broad phase for scenes: which pencils need not be formed at all.

For one moving ellipsoid, one object and one motion segment, the broad phase
bounds the volume the ellipsoid sweeps over a time interval by an
axis-parallel box with rational corners (:func:`swept_box`): the centre's
polynomial path is enclosed coordinate by coordinate (a Taylor expansion at
the interval's midpoint, exact in rationals), then widened by a rational
upper bound of the ellipsoid's half-extents (of its largest semi-axis when it
turns).  Against that box, in exact interval arithmetic:

* a separating plane ``n . x = d`` is certified on one side when ``n . x - d``
  has one strict sign on the box: the ellipsoid is then in ``R+`` (Zone 1) or
  ``R-`` (Zone 2) of the plane throughout, never touching it, which is
  exactly what Corollary 15 would find (Theorem 14);
* a quadric piece ``X^T Q X = 0`` is certified when ``X^T Q X`` has one
  strict sign on the box (a centred form: the value at the box's centre, the
  gradient term and the quadratic term bounded separately): the ellipsoid lies
  strictly in ``R+`` or ``R-`` of the piece, with no contact of any kind.

The object's tree is walked as Algorithm 1 walks it, on the box: below a
certified plane only the certified side is visited, so a piece behind it is
*unreachable* on the interval and is not tested at all; the region a piece is
tested in is thus its cell of the tree (its separating planes), intersected
with the neighbourhood of its surface.  Where something is uncertain the
interval is bisected (up to ``max_depth`` times) and the test repeated on the
halves with the certified facts inherited.

The result (:class:`Coverage`) cuts the segment into consecutive parts per
target (plane or piece): *certified* parts, whose state is known without the
target's pencil in time, and *tracked* parts, where the exact event machinery
(:mod:`quadric_contact.scenes.events`) runs, on that part only.  Nothing is pruned
unless proved: a real contact always lies in a tracked part.

References
----------
Section 5.2 (pencils "computed only if needed"), Algorithms 1 and 2,
Theorem 14, Corollary 15.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import flint
import numpy as np

from quadric_contact.exact.rational import fmpq_of, fraction_of
from quadric_contact.model.quadric import Quadric
from quadric_contact.scenes.composite import Composite, Piece, Split
from quadric_contact.scenes.ledger import Ledger
from quadric_contact.scenes.trajectory import MotionSegment
from quadric_contact.theory.results import Region

__all__ = [
    "Box",
    "Coverage",
    "Part",
    "cover",
    "ellipsoid_extents",
    "plane_sign_on_box",
    "poly_range",
    "quadric_sign_on_box",
    "swept_box",
    "zone_of_sign",
]

Box = tuple[tuple[Fraction, Fraction], tuple[Fraction, Fraction], tuple[Fraction, Fraction]]
"""An axis-parallel box: ``((x_lo, x_hi), (y_lo, y_hi), (z_lo, z_hi))``, rational corners."""

UNCERTAIN = "uncertain"
UNREACHABLE = "unreachable"


def _sqrt_up(x: Fraction, bits: int = 24) -> Fraction:
    """A rational upper bound of ``sqrt(x)`` (``x >= 0``) within ``2^-bits`` relative."""
    if x <= 0:
        return Fraction(0)
    scale = 1 << (2 * bits)
    n = math.ceil(x * scale)
    r = math.isqrt(n)
    if r * r < n:
        r += 1
    return Fraction(r, 1 << bits)


def _leading_minors_positive(A: Sequence[Sequence[Fraction]]) -> bool:
    a, b, c = A[0][0], A[0][1], A[0][2]
    d, e, f = A[1][1], A[1][2], A[2][2]
    m1 = a
    m2 = a * d - b * b
    m3 = a * (d * f - e * e) - b * (b * f - e * c) + c * (b * e - d * c)
    return m1 > 0 and m2 > 0 and m3 > 0


def ellipsoid_extents(E: Quadric) -> tuple[tuple[Fraction, Fraction, Fraction], Fraction]:
    """Rational upper bounds of an ellipsoid's half-extents along the axes and of its
    largest semi-axis (its extent in any direction, whatever its orientation).

    With ``E`` written ``(x - c)^T A (x - c) <= m``, the half-extent along axis
    ``i`` is ``sqrt(m (A^-1)_ii)`` and the largest semi-axis ``sqrt(m / lambda_min(A))``;
    ``lambda_min`` is bounded below by a rational ``L`` for which ``A - L I`` is
    checked positive definite exactly (Sylvester's criterion).

    Examples
    --------
    >>> (rx, ry, rz), rho = ellipsoid_extents(Quadric.ellipsoid(3, 2, 1, center=(5, 0, 0)))
    >>> 3 <= rx < 3.0001 and 2 <= ry < 2.0001 and 1 <= rz < 1.0001 and 3 <= rho < 3.0001
    True
    """
    e = E.as_ellipsoid()
    M = e.matrix
    A = [[M[i][j] for j in range(3)] for i in range(3)]
    c = e.center()
    assert c is not None
    value = sum(M[i][j] * (c[i] if i < 3 else 1) * (c[j] if j < 3 else 1) for i in range(4) for j in range(4))
    if A[0][0] < 0:  # inside positive: flip
        A = [[-v for v in row] for row in A]
        value = -value
    m = -value
    assert m > 0, "a real ellipsoid"
    # inverse diagonal by cofactors
    det = (
        A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1])
        - A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0])
        + A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0])
    )
    cof = (
        A[1][1] * A[2][2] - A[1][2] * A[2][1],
        A[0][0] * A[2][2] - A[0][2] * A[2][0],
        A[0][0] * A[1][1] - A[0][1] * A[1][0],
    )
    half = tuple(_sqrt_up(m * cof[i] / det) for i in range(3))

    lam = float(np.linalg.eigvalsh(np.array([[float(v) for v in row] for row in A]))[0])
    L = Fraction(lam) * (1 - Fraction(1, 1 << 30)) if lam > 0 else Fraction(0)
    while L > 0 and not _leading_minors_positive(
        [[A[i][j] - (L if i == j else 0) for j in range(3)] for i in range(3)]
    ):
        L /= 2
    # a real ellipsoid has A positive definite, so L > 0; the sum of the half-extents bounds rho anyway
    rho = max(_sqrt_up(m / L), *half) if L > 0 else sum(half, Fraction(0))
    return (half[0], half[1], half[2]), rho


def _poly_range_q(p: Any, a: Any, b: Any) -> tuple[Any, Any]:
    """:func:`poly_range` on ``fmpq`` values (the broad phase's arithmetic: exact, in C)."""
    deg = p.degree()
    if deg <= 0:
        v = p[0] if deg == 0 else flint.fmpq(0)
        return v, v
    if deg == 1:
        va, vb = p(a), p(b)
        return (va, vb) if va <= vb else (vb, va)
    m = (a + b) / 2
    h = (b - a) / 2
    cs = p(flint.fmpq_poly([m, 1])).coeffs()
    a0 = cs[0]
    spread = flint.fmpq(0)
    hk = flint.fmpq(1)
    for c in cs[1:]:
        hk *= h
        spread += abs(c) * hk
    return a0 - spread, a0 + spread


def poly_range(p: Any, a: Fraction, b: Fraction) -> tuple[Fraction, Fraction]:
    """An enclosure ``[lo, hi]`` of the values of the polynomial ``p`` (``fmpq_poly``)
    on ``[a, b]``: the Taylor expansion at the midpoint, ``p(m + s) = sum a_k s^k``,
    with ``|s| <= h``; exact for degree 1.

    Examples
    --------
    >>> poly_range(flint.fmpq_poly([0, 0, 1]), Fraction(-1), Fraction(2))   # t^2 on [-1, 2]
    (Fraction(-7, 2), Fraction(4, 1))
    """
    lo, hi = _poly_range_q(flint.fmpq_poly(p), fmpq_of(a), fmpq_of(b))
    return fraction_of(lo), fraction_of(hi)


def _swept_box_q(seg: MotionSegment, r: Sequence[Any], a: Any, b: Any) -> list[tuple[Any, Any]]:
    out = []
    for i in range(3):
        lo, hi = _poly_range_q(seg.center[i], a, b)
        out.append((lo - r[i], hi + r[i]))
    return out


def swept_box(
    seg: MotionSegment, half: tuple[Fraction, Fraction, Fraction], rho: Fraction, a: Fraction, b: Fraction
) -> Box:
    """A box containing every placement of the ellipsoid on ``[a, b]``: the
    enclosure of the centre's path widened by the half-extents (by the largest
    semi-axis in every direction when the segment turns the ellipsoid)."""
    r = [fmpq_of(v) for v in (half if seg.quaternion is None else (rho, rho, rho))]
    box = _swept_box_q(seg, r, fmpq_of(a), fmpq_of(b))
    return (
        (fraction_of(box[0][0]), fraction_of(box[0][1])),
        (fraction_of(box[1][0]), fraction_of(box[1][1])),
        (fraction_of(box[2][0]), fraction_of(box[2][1])),
    )


def _entries(Q: Quadric) -> tuple[Any, ...]:
    return tuple(fmpq_of(v) for v in Q.upper)


def _plane_sign_q(u: Sequence[Any], box: Sequence[tuple[Any, Any]]) -> int:
    # u: upper entries (q00, q01, q02, q03, q11, q12, q13, q22, q23, q33); n . x - d = 2 q.3 . x + q33
    lo = hi = u[9]
    for i, k in enumerate((3, 6, 8)):
        n = 2 * u[k]
        v0, v1 = n * box[i][0], n * box[i][1]
        if v0 <= v1:
            lo += v0
            hi += v1
        else:
            lo += v1
            hi += v0
    return 1 if lo > 0 else -1 if hi < 0 else 0


def plane_sign_on_box(plane: Quadric, box: Box) -> int:
    """``+1`` (``-1``) if ``n . x - d > 0`` (``< 0``) on the whole box, else ``0``.

    Examples
    --------
    >>> F = Fraction
    >>> plane_sign_on_box(Quadric.plane((0, 0, 1), 6), ((F(0), F(1)), (F(0), F(1)), (F(6, 5), F(7, 5))))
    -1
    """
    return _plane_sign_q(_entries(plane), [(fmpq_of(lo), fmpq_of(hi)) for lo, hi in box])


_IDX = ((0, 1, 2), (1, 4, 5), (2, 5, 7))  # upper index of the 3x3 block's entry (i, j)


def _quadric_sign_q(u: Sequence[Any], box: Sequence[tuple[Any, Any]]) -> int:
    m = [(box[i][0] + box[i][1]) / 2 for i in range(3)]
    r = [(box[i][1] - box[i][0]) / 2 for i in range(3)]
    b = (u[3], u[6], u[8])
    Am = [u[_IDX[i][0]] * m[0] + u[_IDX[i][1]] * m[1] + u[_IDX[i][2]] * m[2] for i in range(3)]
    fm = m[0] * Am[0] + m[1] * Am[1] + m[2] * Am[2] + 2 * (b[0] * m[0] + b[1] * m[1] + b[2] * m[2]) + u[9]
    spread = abs(2 * (Am[0] + b[0])) * r[0] + abs(2 * (Am[1] + b[1])) * r[1] + abs(2 * (Am[2] + b[2])) * r[2]
    qlo = qhi = flint.fmpq(0)
    for i in range(3):
        d = u[_IDX[i][i]] * r[i] * r[i]
        if d > 0:
            qhi += d
        else:
            qlo += d
        for j in range(i + 1, 3):
            off = 2 * abs(u[_IDX[i][j]]) * r[i] * r[j]
            qlo -= off
            qhi += off
    if fm - spread + qlo > 0:
        return 1
    if fm + spread + qhi < 0:
        return -1
    return 0


def quadric_sign_on_box(Q: Quadric, box: Box) -> int:
    """``+1`` (``-1``) if ``X^T Q X > 0`` (``< 0``) on the whole box, else ``0``.

    Centred form at the box's centre ``m`` with half-widths ``r``:
    ``f(m + y) = f(m) + g . y + y^T A y`` with ``g = 2 (A m + b)``; the linear
    term is bounded by ``sum |g_i| r_i``, the quadratic one by its diagonal
    terms' ranges and ``2 |A_ij| r_i r_j`` off the diagonal.  Exact rational
    arithmetic throughout.

    Examples
    --------
    >>> unit = Quadric.sphere(1)
    >>> F = Fraction
    >>> quadric_sign_on_box(unit, ((F(2), F(3)), (F(0), F(1)), (F(0), F(1))))
    1
    >>> quadric_sign_on_box(unit, ((F(-1, 4), F(1, 4)),) * 3), quadric_sign_on_box(unit, ((F(0), F(2)),) * 3)
    (-1, 0)
    """
    return _quadric_sign_q(_entries(Q), [(fmpq_of(lo), fmpq_of(hi)) for lo, hi in box])


@dataclass(frozen=True)
class Part:
    """A stretch ``[start, end]`` of a segment for one target: ``tracked`` (the exact
    machinery runs there) or certified with ``sign`` (``+1``: ``R+``, ``-1``: ``R-``).

    A certified stretch may include times where the target is out of reach (never
    asked about); ``witness`` is a time where it was certified, not out of reach.
    """

    start: Fraction
    end: Fraction
    tracked: bool
    sign: int = 0
    witness: Fraction | None = None


@dataclass
class Coverage:
    """The broad phase's verdict for one (ellipsoid, object, segment).

    ``parts[label]`` cuts the segment into consecutive :class:`Part` s for each
    target label (planes and pieces, as :mod:`quadric_contact.scenes.simulate` labels
    them); ``leaves`` is the number of time intervals the segment was cut into.
    """

    parts: dict[str, list[Part]]
    leaves: int
    tests: int = 0
    pruned: list[str] = field(default_factory=list)

    def needs_track(self, label: str) -> bool:
        """Some part of the segment needs the target's pencil in time."""
        return any(p.tracked for p in self.parts[label])


def _labels(obj: Composite) -> dict[int, str]:
    out: dict[int, str] = {}
    for s in obj.splits():
        out[id(s)] = f"{obj.name}: plane {s.name}"
    for p in obj.pieces:
        out[id(p)] = f"{obj.name}/{p.name}"
    return out


def cover(
    obj: Composite,
    seg: MotionSegment,
    half: tuple[Fraction, Fraction, Fraction],
    rho: Fraction,
    *,
    max_depth: int = 2,
    ledger: Ledger | None = None,
) -> Coverage:
    """Run the broad phase for one ellipsoid (extents ``half``, ``rho``) against
    ``obj`` on the motion segment ``seg``.

    Parameters
    ----------
    obj : Composite
    seg : MotionSegment
    half, rho
        From :func:`ellipsoid_extents`.
    max_depth : int
        How many times an interval with an uncertain target may be bisected.
    ledger : Ledger, optional
        Counts the box tests (``broad_phase_tests``).

    Returns
    -------
    Coverage

    Examples
    --------
    The bee of Example 17 resting below the plane ``z = 6``, beside the trunk: the
    plane is certified (Zone 2), the crown is out of reach, the trunk is certified
    outside (``R+``): no pencil in time is needed at all.

    >>> from quadric_contact.scenes.scene_toml import builtin_scene
    >>> from quadric_contact.scenes.trajectory import Stationary
    >>> scene = builtin_scene()
    >>> (tree,), bee = scene.objects, scene.ellipsoids[0]
    >>> (seg,) = Stationary().segments(Fraction(0), Fraction(1), bee.center)
    >>> c = cover(tree, seg, *ellipsoid_extents(bee.quadric))
    >>> c.pruned, [(p.tracked, p.sign) for p in c.parts["tree/trunk"]]
    (['tree: plane z - 6', 'tree/crown', 'tree/trunk'], [(False, 1)])
    """
    labels = _labels(obj)
    targets: list[Split | Piece] = [*obj.splits(), *obj.pieces]
    entries = {id(n): _entries(n.plane if isinstance(n, Split) else n.quadric) for n in targets}
    radii = [fmpq_of(v) for v in (half if seg.quaternion is None else (rho, rho, rho))]
    leaves: list[tuple[Fraction, Fraction, dict[str, Any]]] = []
    tests = 0

    def walk(a: Fraction, b: Fraction, known: dict[str, int]) -> dict[str, Any]:
        box = _swept_box_q(seg, radii, fmpq_of(a), fmpq_of(b))
        status: dict[str, Any] = {}

        def visit(node: Split | Piece | None) -> None:
            nonlocal tests
            if node is None:
                return
            label = labels[id(node)]
            if label in status:
                return
            if label in known:
                s = known[label]
            else:
                tests += 1
                u = entries[id(node)]
                s = _plane_sign_q(u, box) if isinstance(node, Split) else _quadric_sign_q(u, box)
            status[label] = s if s != 0 else UNCERTAIN
            if isinstance(node, Split):
                if s >= 0:
                    visit(node.plus)
                if s <= 0:
                    visit(node.minus)

        visit(obj.root)
        for p in obj.extra_pieces:
            visit(p)
        return status

    def refine(a: Fraction, b: Fraction, known: dict[str, int], depth: int) -> None:
        status = walk(a, b, known)
        if depth < max_depth and any(v == UNCERTAIN for v in status.values()):
            inherited = {k: v for k, v in status.items() if v != UNCERTAIN}
            mid = (a + b) / 2
            refine(a, mid, inherited, depth + 1)
            refine(mid, b, inherited, depth + 1)
            return
        leaves.append((a, b, status))

    refine(seg.t0, seg.t1, {}, 0)
    if ledger is not None:
        ledger.add("broad_phase_tests", tests)
    parts: dict[str, list[Part]] = {}
    pruned: list[str] = []
    for node in targets:
        label = labels[id(node)]
        seq = [(a, b, st.get(label, UNREACHABLE)) for a, b, st in leaves]
        # an unreachable stretch is never asked about: it joins its neighbours
        first = next((s for _, _, s in seq if s != UNREACHABLE), None)
        merged: list[list[Any]] = []  # [start, end, status, witness]
        for a, b, s in seq:
            witness = None if s == UNREACHABLE else (a + b) / 2
            if s == UNREACHABLE:
                s = merged[-1][2] if merged else first
            if merged and merged[-1][2] == s:
                merged[-1][1] = b
                if merged[-1][3] is None:
                    merged[-1][3] = witness
            else:
                merged.append([a, b, s, witness])
        if first is None:  # never reachable on this segment
            plist = [Part(seg.t0, seg.t1, False, 0)]
        else:
            tracked = [k for k, m in enumerate(merged) if m[2] == UNCERTAIN]
            if len(tracked) > 1:  # one pencil in time for the target: one tracked stretch
                lo, hi = tracked[0], tracked[-1]
                merged[lo : hi + 1] = [[merged[lo][0], merged[hi][1], UNCERTAIN, None]]
            plist = [Part(a, b, True) if s == UNCERTAIN else Part(a, b, False, s, w) for a, b, s, w in merged]
        parts[label] = plist
        if not any(p.tracked for p in plist):
            pruned.append(label)
    return Coverage(parts, len(leaves), tests, pruned)


def zone_of_sign(sign: int) -> Region:
    """The region of a plane or piece certified with ``sign``."""
    return Region.R_PLUS if sign > 0 else Region.R_MINUS
