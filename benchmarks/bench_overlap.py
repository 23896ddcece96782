"""Do two solid ellipsoids overlap?  ``quadric_contact.theory.overlap`` against the peers.

Run from the repository root::

    PYTHONPATH=src python benchmarks/bench_overlap.py [--pairs N] [--fcl-pairs M] [--seed S]

The pairs are given the way HOOMD-blue and FCL take them: semi-axes, a unit quaternion
``(w, x, y, z)`` and a position, in binary64.  Each method gets what it would get in its own
program:

* ``overlap certified`` / ``float`` / ``filter``: :func:`quadric_contact.theory.overlap` on the
  ``(N, 4, 4)`` binary64 stacks of the two ellipsoids (the matrices rounded from the exact
  ones); ``overlap exact input``: the same on exact rational matrices (object arrays; the
  ladder only, it is the reference);
* ``HOOMD-blue``: a faithful binary64 reimplementation (vectorised over the pairs with numpy)
  of ``test_overlap<ShapeEllipsoid, ShapeEllipsoid>`` of HOOMD-blue's ``ShapeEllipsoid.h``:
  the sphere shortcut, ``compute_ellipsoid_matrix`` (``rotmat3`` of the quaternion), the
  coefficients of ``det(x M_a + M_b)`` by its 2x2 and 3x3 minors, the Descartes test, the
  Sturm sequence with HOOMD's relative precision ``1e-6`` both ways round, and its error
  return (counted as "no overlap", as HOOMD does, and reported);
* ``FCL (libccd)`` / ``FCL (GJK)``: python-fcl's ``collide`` of two ``fcl.Ellipsoid`` with
  ``fcl.Transform(quaternion, position)``, pair by pair (a Python loop: the time per pair
  includes the binding's overhead);
* ``numpy eig``: the Wang-Wang-Kim test in binary64, the roots of ``det(l E + Q)`` as
  ``-eig(E^-1 Q)`` (``numpy.linalg.eigvals`` on the stack), two positive real ones with an
  imaginary part below ``1e-9`` mean apart.

Two tables:

1. *random pairs* (semi-axes 0.5-2, random orientations, positions in a box where about
   half the pairs overlap): nanoseconds per pair and the number of answers that differ from
   the certified one (which is exact for the binary64 matrices: on random pairs the rounding
   of the parameters almost never matters);
2. *the hard-case ladder*: exact constructions at distance ``0`` and ``+-10^-k``
   (``k = 1..16``) from an exact touch, moved by a rational rotation and translation so that
   the binary64 inputs are rounded: HOOMD-blue's own test pair (semi-axes ``(3, 1, 2)`` and
   ``(2, 3, 1)``, five apart along ``x``), and the ladder of
   :mod:`quadric_contact.testing.hardcases` (a small ellipsoid outside, and inside, the ellipsoid
   ``(4, 3, 2)``).  The truth is :func:`quadric_contact.theory.overlap.overlap_exact` on the exact
   pair, read with the peers' convention (a touch is no overlap); a method is wrong where its
   yes/no differs.  Rows on binary64 input cannot be right below the rounding of their input
   (about ``1e-16`` relative): ``overlap certified`` is exact for the rounded matrices it is
   given, so its "wrong" answers are the pairs the rounding moved across the touch, and its
   ``TOUCHING`` count is the touches it could still prove.

Timings are wall clock on a shared machine (best of ``--repeat``): indicative only.
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Callable
from fractions import Fraction
from pathlib import Path
from typing import Any

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))

import quadric_contact as qc  # noqa: E402
from quadric_contact import OverlapCode, Quadric  # noqa: E402
from quadric_contact.testing.hardcases import _LADDER_Q, DISTANCES, _probe  # noqa: E402
from quadric_contact.theory.overlap import overlap_exact  # noqa: E402

F = Fraction
QUATERNION = (2, -1, 3, 1)  # the ladder's rotation (not normalised: it is exact)
TRANSLATION = (F(1, 3), F(-2, 7), F(5, 11))
PRECISION = 1e-6  # HOOMD-blue's ELLIPSOID_OVERLAP_PRECISION in double precision


# -- the pairs ----------------------------------------------------------------------------------


def random_pairs(rng: np.random.Generator, n: int, box: float) -> tuple[dict[str, np.ndarray], ...]:
    """Two sets of ``n`` ellipsoids as parameters: ``axes (n, 3)``, unit ``quat (n, 4)``,
    ``pos (n, 3)``."""

    def one(centred: bool) -> dict[str, np.ndarray]:
        q = rng.normal(size=(n, 4))
        q /= np.linalg.norm(q, axis=1, keepdims=True)
        pos = np.zeros((n, 3)) if centred else rng.uniform(-box, box, size=(n, 3))
        return {"axes": rng.uniform(0.5, 2.0, size=(n, 3)), "quat": q, "pos": pos}

    return one(True), one(False)


def rotation(quat: np.ndarray) -> np.ndarray:
    """Rotation matrices of unit quaternions ``(w, x, y, z)`` (HOOMD's ``rotmat3``)."""
    a, b, c, d = quat.T
    R = np.empty((len(quat), 3, 3))
    R[:, 0] = np.stack([a * a + b * b - c * c - d * d, 2 * b * c - 2 * a * d, 2 * b * d + 2 * a * c], axis=1)
    R[:, 1] = np.stack([2 * b * c + 2 * a * d, a * a - b * b + c * c - d * d, 2 * c * d - 2 * a * b], axis=1)
    R[:, 2] = np.stack([2 * b * d - 2 * a * c, 2 * c * d + 2 * a * b, a * a - b * b - c * c + d * d], axis=1)
    return R


def matrices(p: dict[str, np.ndarray]) -> np.ndarray:
    """``(n, 4, 4)`` binary64 matrices of ``(x - c)^T R D R^T (x - c) - 1`` (inside negative)."""
    R = rotation(p["quat"])
    A = np.einsum("nik,nk,njk->nij", R, 1 / p["axes"] ** 2, R)
    A = (A + np.swapaxes(A, 1, 2)) / 2
    c = p["pos"]
    M = np.zeros((len(c), 4, 4))
    M[:, :3, :3] = A
    b = -np.einsum("nij,nj->ni", A, c)
    M[:, :3, 3] = b
    M[:, 3, :3] = b
    M[:, 3, 3] = np.einsum("ni,ni->n", c, -b) - 1
    return M


def exact_ellipsoid(axes: tuple[Any, ...], quat: tuple[Any, ...], pos: tuple[Any, ...]) -> Quadric:
    return Quadric.ellipsoid(
        *(F(a) for a in axes), center=tuple(F(x) for x in pos), rotation=tuple(F(t) for t in quat)
    )


def ladder() -> list[tuple[str, Any, Quadric, Quadric]]:
    """``(family, offset, E, Q)``: exact pairs at ``offset`` from an exact touch, moved."""
    motion = qc.RigidMotion(qc.rotation_from_quaternion(*QUATERNION), TRANSLATION)
    offsets = [F(0)] + [s * d for d in (F(1, 10), *DISTANCES) for s in (1, -1)]
    out = []
    for off in offsets:
        a = Quadric.ellipsoid(3, 1, 2)
        b = Quadric.ellipsoid(2, 3, 1, center=(5 + off, 0, 0))
        out.append(("HOOMD pair (3,1,2)-(2,3,1)", off, a.moved(motion), b.moved(motion)))
        for side in ("R+", "R-"):
            e, q, _, _ = _probe(_LADDER_Q, qc.QuadricKind.ELLIPSOID, side, off)
            name = "small ellipsoid " + ("outside" if side == "R+" else "inside") + " (4,3,2)"
            out.append((name, off, e.moved(motion), q.moved(motion)))
    return out


def parameters(q: Quadric) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Semi-axes, unit quaternion and centre of an exact ellipsoid, rounded to binary64 (what a
    HOOMD or FCL user would hand over)."""
    A = np.array([[float(v) for v in row[:3]] for row in q.matrix[:3]])
    centre = q.center()
    assert centre is not None
    A = A / -float(q.value_at(centre))
    w, V = np.linalg.eigh(A)
    if np.linalg.det(V) < 0:
        V[:, 0] = -V[:, 0]
    return 1 / np.sqrt(w), _quaternion(V), np.array([float(c) for c in centre])


def _quaternion(R: np.ndarray) -> np.ndarray:
    t = np.trace(R)
    if t > 0:
        s = np.sqrt(t + 1) * 2
        q = [s / 4, (R[2, 1] - R[1, 2]) / s, (R[0, 2] - R[2, 0]) / s, (R[1, 0] - R[0, 1]) / s]
    else:
        i = int(np.argmax(np.diag(R)))
        j, k = (i + 1) % 3, (i + 2) % 3
        s = np.sqrt(1 + R[i, i] - R[j, j] - R[k, k]) * 2
        q = [0.0] * 4
        q[0] = (R[k, j] - R[j, k]) / s
        q[1 + i] = s / 4
        q[1 + j] = (R[j, i] + R[i, j]) / s
        q[1 + k] = (R[k, i] + R[i, k]) / s
    v = np.array(q)
    return v / np.linalg.norm(v)


# -- HOOMD-blue's test, reimplemented in binary64 -------------------------------------------------


def _hoomd10(M: np.ndarray) -> list[np.ndarray]:
    """HOOMD's packed layout ``[M00, M10, M11, M20, M21, M22, M30, M31, M32, M33]``."""
    return [
        M[:, 0, 0],
        M[:, 1, 0],
        M[:, 1, 1],
        M[:, 2, 0],
        M[:, 2, 1],
        M[:, 2, 2],
        M[:, 3, 0],
        M[:, 3, 1],
        M[:, 3, 2],
        M[:, 3, 3],
    ]


def hoomd_matrices(p: dict[str, np.ndarray]) -> list[np.ndarray]:
    """``compute_ellipsoid_matrix``, operation by operation."""
    R = rotation(p["quat"])
    r0, r1, r2 = R[:, 0], R[:, 1], R[:, 2]
    a, b, c = (1.0 / (p["axes"][:, k] * p["axes"][:, k]) for k in range(3))

    def m(u: np.ndarray, v: np.ndarray) -> np.ndarray:
        return a * u[:, 0] * v[:, 0] + b * u[:, 1] * v[:, 1] + c * u[:, 2] * v[:, 2]

    M = [m(r0, r0), m(r1, r0), m(r1, r1), m(r2, r0), m(r2, r1), m(r2, r2)]
    x, y, z = p["pos"].T
    M0x0, M1x0, M1x1, M2x1 = M[0] * x, M[1] * x, M[1] * y, M[2] * y
    M3x0, M3x2, M4x1, M4x2, M5x2 = M[3] * x, M[3] * z, M[4] * y, M[4] * z, M[5] * z
    M += [-M0x0 - M1x1 - M3x2, -M1x0 - M2x1 - M4x2, -M3x0 - M4x1 - M5x2]
    M.append(-1.0 + x * (M0x0 + 2.0 * M1x1) + y * (M2x1 + 2.0 * M4x2) + z * (M5x2 + 2.0 * M3x0))
    return M


def hoomd_overlap(pa: dict[str, np.ndarray], pb: dict[str, np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """``(overlap, error)`` of HOOMD-blue's ``test_overlap`` for ellipsoid ``b`` at ``pos_b - pos_a``."""
    rel = {"axes": pb["axes"], "quat": pb["quat"], "pos": pb["pos"] - pa["pos"]}
    at0 = {"axes": pa["axes"], "quat": pa["quat"], "pos": np.zeros_like(pa["pos"])}
    with np.errstate(all="ignore"):
        codes = _hoomd_codes(hoomd_matrices(at0), hoomd_matrices(rel))
    sa = (pa["axes"][:, 0] == pa["axes"][:, 1]) & (pa["axes"][:, 0] == pa["axes"][:, 2])
    sb = (pb["axes"][:, 0] == pb["axes"][:, 1]) & (pb["axes"][:, 0] == pb["axes"][:, 2])
    spheres = sa & sb
    ab = pa["axes"][:, 0] + pb["axes"][:, 0]
    dr = rel["pos"]
    out = codes == 1
    out[spheres] = (np.einsum("ni,ni->n", dr, dr) <= ab * ab)[spheres]
    return out, (codes == 2) & ~spheres


def _hoomd_codes(M1: list[np.ndarray], M2: list[np.ndarray]) -> np.ndarray:
    """``test_overlap_ellipsoids``: 1 overlap, 0 none, 2 error; every branch in the order of the
    C++ code, evaluated for every pair and settled by the first branch that returns."""

    def minor2(i: int, j: int, k: int, m: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        return (
            M1[i] * M1[j] - M1[k] * M1[m],
            M1[i] * M2[j] - M1[k] * M2[m] + M2[i] * M1[j] - M2[k] * M1[m],
            M2[i] * M2[j] - M2[k] * M2[m],
        )

    s01 = minor2(3, 7, 4, 6)
    s02 = minor2(3, 8, 5, 6)
    s03 = minor2(3, 9, 8, 6)
    s12 = minor2(4, 8, 5, 7)
    s13 = minor2(4, 9, 8, 7)
    s23 = minor2(5, 9, 8, 8)

    def minor3(i: int, j: int, k: int, sa: tuple, sb: tuple, sc: tuple) -> tuple[np.ndarray, ...]:
        return (
            M1[i] * sa[0] - M1[j] * sb[0] + M1[k] * sc[0],
            M1[i] * sa[1] - M1[j] * sb[1] + M1[k] * sc[1] + M2[i] * sa[0] - M2[j] * sb[0] + M2[k] * sc[0],
            M1[i] * sa[2] - M1[j] * sb[2] + M1[k] * sc[2] + M2[i] * sa[1] - M2[j] * sb[1] + M2[k] * sc[1],
            M2[i] * sa[2] - M2[j] * sb[2] + M2[k] * sc[2],
        )

    t0 = minor3(2, 4, 7, s23, s13, s12)
    t1 = minor3(1, 4, 7, s23, s03, s02)
    t2 = minor3(1, 2, 7, s13, s03, s01)
    t3 = minor3(1, 2, 4, s12, s02, s01)
    a4 = M1[0] * t0[0] - M1[1] * t1[0] + M1[3] * t2[0] - M1[6] * t3[0]
    a3 = (
        M1[0] * t0[1]
        - M1[1] * t1[1]
        + M1[3] * t2[1]
        - M1[6] * t3[1]
        + M2[0] * t0[0]
        - M2[1] * t1[0]
        + M2[3] * t2[0]
        - M2[6] * t3[0]
    )
    a2 = (
        M1[0] * t0[2]
        - M1[1] * t1[2]
        + M1[3] * t2[2]
        - M1[6] * t3[2]
        + M2[0] * t0[1]
        - M2[1] * t1[1]
        + M2[3] * t2[1]
        - M2[6] * t3[1]
    )
    a1 = (
        M1[0] * t0[3]
        - M1[1] * t1[3]
        + M1[3] * t2[3]
        - M1[6] * t3[3]
        + M2[0] * t0[2]
        - M2[1] * t1[2]
        + M2[3] * t2[2]
        - M2[6] * t3[2]
    )
    a0 = M2[0] * t0[3] - M2[1] * t1[3] + M2[3] * t2[3] - M2[6] * t3[3]

    n = len(a0)
    out = np.full(n, -1, dtype=np.int8)

    def settle(mask: np.ndarray, value: int) -> None:
        m = mask & (out < 0)
        out[m] = value

    settle((a1 < 0.0) & (a2 < 0.0) & (a3 < 0.0), 1)
    for lead, c3, c2, c1, c0 in ((a4, a3, a2, a1, a0), (a0, a1, a2, a3, a4)):
        inv = 1.0 / lead
        a, b, c, d = c3 * inv, c2 * inv, c1 * inv, c0 * inv
        e = 3 * a * a - 8 * b
        settle((np.abs(e) > PRECISION * np.maximum(np.abs(3 * a * a), np.abs(8 * b))) & (e < 0.0), 1)
        f = 2 * a * b - 12 * c
        g = a * c - 16 * d
        h = 3 * a * e * f - 2 * b * e * e + 4 * (g * e - f * f)
        big = np.maximum(np.maximum(np.abs(3 * a * e * f), np.abs(2 * b * e * e)), 4 * (g * e - f * f))
        settle((np.abs(h) > PRECISION * big) & (h < 0.0), 1)
        k = 3 * a * g * e - c * e * e - 4 * f * g
        ta, tb, tc = f * k * h, h * h * g, e * k * k
        l0 = ta - (tb + tc)
        decided = np.abs(l0) > PRECISION * np.maximum(np.maximum(np.abs(ta), np.abs(tb)), np.abs(tc))
        settle(decided & (l0 < 0.0), 1)
        settle(decided, 0)
    settle(np.ones(n, dtype=bool), 2)
    return out


# -- the other peers ----------------------------------------------------------------------------


def fcl_overlap(pa: dict[str, np.ndarray], pb: dict[str, np.ndarray], solver: str) -> np.ndarray:
    import fcl

    kind = {"libccd": fcl.GJKSolverType.GST_LIBCCD, "GJK": fcl.GJKSolverType.GST_INDEP}[solver]
    out = np.empty(len(pa["pos"]), dtype=bool)
    for k in range(len(out)):
        objs = [
            fcl.CollisionObject(
                fcl.Ellipsoid(*map(float, p["axes"][k])), fcl.Transform(p["quat"][k], p["pos"][k])
            )
            for p in (pa, pb)
        ]
        request = fcl.CollisionRequest(gjk_solver_type=kind)
        out[k] = fcl.collide(objs[0], objs[1], request, fcl.CollisionResult()) > 0
    return out


def eig_overlap(E: np.ndarray, Q: np.ndarray) -> np.ndarray:
    """Wang-Wang-Kim in binary64: overlap unless two distinct positive real roots."""
    roots = -np.linalg.eigvals(np.linalg.solve(E, Q))
    real = np.abs(roots.imag) <= 1e-9 * np.maximum(1.0, np.abs(roots.real))
    positive = real & (roots.real > 0)
    two = positive.sum(axis=1) >= 2
    r = np.sort(np.where(positive, roots.real, np.inf), axis=1)
    with np.errstate(invalid="ignore"):
        distinct = two & (np.abs(r[:, 1] - r[:, 0]) > 1e-9 * np.abs(r[:, 1]))
    return ~distinct


# -- running ------------------------------------------------------------------------------------


def timed(fn: Callable[[], Any], repeat: int) -> tuple[float, Any]:
    out = fn()
    best = np.inf
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t)
    return best, out


def overlap_codes(E: Any, Q: Any, mode: str) -> np.ndarray:
    return np.asarray(qc.overlap(E, Q, mode=mode))


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pairs", type=int, default=20000)
    parser.add_argument("--fcl-pairs", type=int, default=2000)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--box", type=float, default=2.5)
    args = parser.parse_args(argv)
    rng = np.random.default_rng(args.seed)

    # 1. random pairs
    pa, pb = random_pairs(rng, args.pairs, args.box)
    E, Q = matrices(pa), matrices(pb)
    sub = slice(0, args.fcl_pairs)
    pa_s = {k: v[sub] for k, v in pa.items()}
    pb_s = {k: v[sub] for k, v in pb.items()}
    t_cert, cert = timed(lambda: overlap_codes(E, Q, "certified"), args.repeat)
    truth = cert != OverlapCode.SEPARATE  # no touches among random pairs: checked below
    assert not np.any(cert == OverlapCode.TOUCHING)
    rows: list[tuple[str, float, int, int]] = [("overlap certified", t_cert, 0, len(truth))]
    for mode in ("float", "filter"):
        t, codes = timed(lambda mode=mode: overlap_codes(E, Q, mode), args.repeat)
        decided = codes != OverlapCode.UNCERTAIN
        rows.append(
            (
                f"overlap {mode}",
                t,
                int(np.count_nonzero((codes[decided] == OverlapCode.OVERLAPPING) != truth[decided])),
                len(truth),
            )
        )
    t, (hoomd, _) = timed(lambda: hoomd_overlap(pa, pb), args.repeat)
    rows.append(("HOOMD-blue (numpy)", t, int(np.count_nonzero(hoomd != truth)), len(truth)))
    t, eig = timed(lambda: eig_overlap(E, Q), args.repeat)
    rows.append(("numpy eig (WWK in binary64)", t, int(np.count_nonzero(eig != truth)), len(truth)))
    for solver in ("libccd", "GJK"):
        t, got = timed(lambda solver=solver: fcl_overlap(pa_s, pb_s, solver), 1)
        rows.append((f"FCL ({solver}, Python loop)", t, int(np.count_nonzero(got != truth[sub])), len(got)))
    share = float(np.mean(truth))
    print(f"random pairs: {args.pairs} ({share:.0%} overlapping; FCL on the first {args.fcl_pairs})")
    print(f"{'method':34s} {'ns/pair':>10s} {'differ from certified':>24s}")
    for name, t, wrong, n in rows:
        print(f"{name:34s} {t / n * 1e9:10.0f} {wrong:>17d} / {n}")
    filt = qc.modes.FilterMode()
    qc.overlap(E, Q, mode=filt)
    mode = qc.modes.CertifiedMode()
    qc.overlap(E, Q, mode=mode)
    print(
        "stages of the certified cascade: " + ", ".join(f"{k} {v}" for k, v in mode.last.decided.items() if v)
    )
    print(f"filter left undecided: {filt.last.undecided}")

    # 2. the hard-case ladder
    pairs = ladder()
    exact = [overlap_exact(e, q) for _, _, e, q in pairs]
    want = np.array([r.code is OverlapCode.OVERLAPPING for r in exact])  # a touch is no overlap
    params = [tuple(parameters(x) for x in (e, q)) for _, _, e, q in pairs]
    la = {k: np.array([p[0][i] for p in params]) for i, k in enumerate(("axes", "quat", "pos"))}
    lb = {k: np.array([p[1][i] for p in params]) for i, k in enumerate(("axes", "quat", "pos"))}
    Ef = np.array([e.to_numpy() for _, _, e, _ in pairs])
    Qf = np.array([q.to_numpy() for _, _, _, q in pairs])
    Eo = np.array([e.matrix for _, _, e, _ in pairs], dtype=object)
    Qo = np.array([q.matrix for _, _, _, q in pairs], dtype=object)
    print()
    print(f"hard-case ladder: {len(pairs)} pairs, offsets 0 and +-1e-1 .. +-1e-16 from a touch, 3 families")
    head = f"{'method':34s} {'wrong':>8s} {'uncertain':>10s} {'touching':>9s}"
    print(head + "  wrong at offsets (overlapping < 0 < apart)")
    results: list[tuple[str, np.ndarray, np.ndarray, np.ndarray]] = []
    for label, E_in, Q_in, mode in (
        ("overlap exact input", Eo, Qo, "certified"),
        ("overlap certified (binary64 input)", Ef, Qf, "certified"),
        ("overlap float", Ef, Qf, "float"),
        ("overlap filter", Ef, Qf, "filter"),
    ):
        codes = overlap_codes(E_in, Q_in, mode)
        unc = codes == OverlapCode.UNCERTAIN
        got = codes == OverlapCode.OVERLAPPING
        results.append((label, got, unc, codes == OverlapCode.TOUCHING))
    hoomd, err = hoomd_overlap(la, lb)
    results.append(("HOOMD-blue (numpy)", hoomd, np.zeros_like(hoomd), np.zeros_like(hoomd)))
    results.append(
        (
            "numpy eig (WWK in binary64)",
            eig_overlap(Ef, Qf),
            np.zeros(len(pairs), bool),
            np.zeros(len(pairs), bool),
        )
    )
    for solver in ("libccd", "GJK"):
        results.append(
            (
                f"FCL ({solver})",
                fcl_overlap(la, lb, solver),
                np.zeros(len(pairs), bool),
                np.zeros(len(pairs), bool),
            )
        )
    offsets = [off for _, off, _, _ in pairs]
    for label, got, unc, touch in results:
        wrong = (got != want) & ~unc
        bad = sorted({o for o, w in zip(offsets, wrong, strict=True) if w})
        neg, pos = [o for o in bad if o < 0], [o for o in bad if o > 0]
        parts = [f"{float(min(neg)):.0e}..{float(max(neg)):.0e}" if neg else ""]
        parts += ["0" if 0 in bad else "", f"{float(min(pos)):.0e}..{float(max(pos)):.0e}" if pos else ""]
        shown = ", ".join(p for p in parts if p)
        print(f"{label:34s} {int(wrong.sum()):8d} {int(unc.sum()):10d} {int(touch.sum()):9d}  {shown}")
    print(f"HOOMD-blue error returns (counted as no overlap, as HOOMD does): {int(err.sum())}")


if __name__ == "__main__":
    main()
