"""Random pairs of matrices in binary64, generated with numpy for benchmarks and tests.

The matrices are built in floating point (their rounding errors are part of
the input: a float matrix is the exact dyadic rational it stores, and every
answer is measured against the exact answer for it).  Besides the building blocks
(:func:`random_ellipsoids`, :func:`random_pairs`), the populations the benchmark
measures are built here (:func:`complete_populations`, :func:`kernel_population`), so
that tests draw the same pairs.

>>> import numpy as np
>>> E, Q, kinds = random_pairs(4, np.random.default_rng(0))
>>> E.shape, Q.shape, E.dtype
((4, 4, 4), (4, 4, 4), dtype('float64'))
"""

from __future__ import annotations

from typing import Any

import numpy as np

from quadric_contact.model.classification import TABLE_1_KINDS, QuadricKind

__all__ = [
    "GENERIC_KINDS",
    "SAMPLE_KINDS",
    "complete_populations",
    "ellipsoid_matrix",
    "float_depth",
    "kernel_population",
    "random_ellipsoids",
    "random_pairs",
    "random_rotations",
]

SAMPLE_KINDS: tuple[QuadricKind, ...] = (*TABLE_1_KINDS, QuadricKind.PLANE)
"""The types of ``Q`` that :func:`random_pairs` draws from (Table 1 and the plane)."""

GENERIC_KINDS: tuple[QuadricKind, ...] = (
    QuadricKind.ELLIPSOID,
    QuadricKind.HYPERBOLOID_ONE_SHEET,
    QuadricKind.HYPERBOLOID_TWO_SHEETS,
    QuadricKind.ELLIPTIC_PARABOLOID,
    QuadricKind.HYPERBOLIC_PARABOLOID,
    QuadricKind.PLANE,
)
"""The types of :data:`SAMPLE_KINDS` that rounding to binary64 does not make nearly degenerate
for the contact question (the rotated cylinders and parallel planes it does)."""


def random_rotations(n: int, rng: np.random.Generator) -> np.ndarray:
    """``(n, 3, 3)`` rotation matrices from uniformly random unit quaternions."""
    q = rng.normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    w, x, y, z = q.T
    return np.stack(
        [
            np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], axis=-1),
            np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], axis=-1),
            np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], axis=-1),
        ],
        axis=1,
    )


def _moved(S: np.ndarray, R: np.ndarray, t: np.ndarray) -> np.ndarray:
    """``H^-T S H^-1`` for ``H = [[R, t], [0, 1]]`` (the quadric moved by ``x -> R x + t``)."""
    n = S.shape[0]
    Hinv = np.zeros((n, 4, 4))
    Rt = np.swapaxes(R, 1, 2)
    Hinv[:, :3, :3] = Rt
    Hinv[:, :3, 3] = -np.einsum("nij,nj->ni", Rt, t)
    Hinv[:, 3, 3] = 1.0
    M = np.swapaxes(Hinv, 1, 2) @ S @ Hinv
    return (M + np.swapaxes(M, 1, 2)) / 2  # exactly symmetric


def random_ellipsoids(
    n: int, rng: np.random.Generator, *, axes: tuple[float, float] = (0.1, 1.0), box: float = 3.0
) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """``(n, 4, 4)`` ellipsoids (semi-axes log-uniform in ``axes``, random orientation,
    centre uniform in ``[-box, box]^3``) and their geometry (``axes``, ``rotation``, ``center``)."""
    ax = np.exp(rng.uniform(np.log(axes[0]), np.log(axes[1]), size=(n, 3)))
    R = random_rotations(n, rng)
    c = rng.uniform(-box, box, size=(n, 3))
    S = np.zeros((n, 4, 4))
    S[:, 0, 0], S[:, 1, 1], S[:, 2, 2] = 1 / ax[:, 0] ** 2, 1 / ax[:, 1] ** 2, 1 / ax[:, 2] ** 2
    S[:, 3, 3] = -1.0
    return _moved(S, R, c), {"axes": ax, "rotation": R, "center": c}


def _standard_forms(kinds: np.ndarray, p: np.ndarray) -> np.ndarray:
    """Standard forms of Table 1 (and the plane ``z = 0``) with parameters ``p`` (n, 3)."""
    n = kinds.shape[0]
    S = np.zeros((n, 4, 4))
    inv = 1 / p**2
    K = QuadricKind
    for code, kind in enumerate(SAMPLE_KINDS):
        m = kinds == code
        if not m.any():
            continue
        a, b, c = inv[m, 0], inv[m, 1], inv[m, 2]
        s = np.zeros((int(m.sum()), 4, 4))
        if kind in (K.ELLIPSOID, K.HYPERBOLOID_ONE_SHEET, K.HYPERBOLOID_TWO_SHEETS):
            s[:, 0, 0], s[:, 1, 1] = a, b
            s[:, 2, 2] = c if kind is K.ELLIPSOID else -c
            s[:, 3, 3] = 1.0 if kind is K.HYPERBOLOID_TWO_SHEETS else -1.0
        elif kind in (K.ELLIPTIC_PARABOLOID, K.HYPERBOLIC_PARABOLOID, K.PARABOLIC_CYLINDER):
            s[:, 0, 0] = a
            s[:, 1, 1] = {K.ELLIPTIC_PARABOLOID: b, K.HYPERBOLIC_PARABOLOID: -b}.get(kind, 0.0)
            s[:, 2, 3] = s[:, 3, 2] = -0.5
        elif kind in (K.ELLIPTIC_CYLINDER, K.HYPERBOLIC_CYLINDER):
            s[:, 0, 0], s[:, 1, 1] = a, (b if kind is K.ELLIPTIC_CYLINDER else -b)
            s[:, 3, 3] = -1.0
        elif kind is K.PARALLEL_PLANES:
            s[:, 0, 0], s[:, 3, 3] = a, -1.0
        else:  # the plane z = 0
            s[:, 2, 3] = s[:, 3, 2] = 0.5
        S[m] = s
    return S


def random_pairs(
    n: int,
    rng: np.random.Generator,
    *,
    kinds: tuple[QuadricKind, ...] = SAMPLE_KINDS,
    ellipsoid_axes: tuple[float, float] = (0.1, 1.0),
    box: float = 3.0,
    with_geometry: bool = False,
) -> Any:
    """``n`` random pairs ``(E, Q)`` in binary64, and the type index of each ``Q``.

    ``E`` as in :func:`random_ellipsoids`; ``Q`` of a type drawn uniformly from
    ``kinds``, standard form with parameters in ``[1, 4]``, moved by a random rigid
    motion (translation in ``[-box, box]^3``) and negated with probability 1/2.
    With ``with_geometry`` also returns the geometry of ``E`` and ``Q`` (``Q``'s is
    meaningful where it is an ellipsoid and was not negated).
    """
    E, geo_e = random_ellipsoids(n, rng, axes=ellipsoid_axes, box=box)
    codes = np.array([SAMPLE_KINDS.index(k) for k in kinds])
    kind = codes[rng.integers(0, len(codes), size=n)]
    p = np.sort(rng.uniform(1.0, 4.0, size=(n, 3)), axis=1)[:, ::-1]
    R = random_rotations(n, rng)
    t = rng.uniform(-box, box, size=(n, 3))
    Q = _moved(_standard_forms(kind, p), R, t)
    sign = np.where(rng.random(n) < 0.5, -1.0, 1.0)
    Q *= sign[:, None, None]
    if with_geometry:
        geo_q = {"axes": p, "rotation": R, "center": t, "sign": sign}
        return E, Q, kind, geo_e, geo_q
    return E, Q, kind


def complete_populations(n: int, rng: np.random.Generator) -> dict[str, tuple[np.ndarray, np.ndarray, Any]]:
    """The populations of the benchmark's complete-decision measurement, ``n`` pairs each:

    * ``environment``: small ellipsoids (semi-axes 0.05-0.2, centres in [-4, 4]^3) against one
      ellipsoid of semi-axes 3-5 at the origin (the paper's use case, nearly every pair small);
    * ``similar sizes``: ellipsoids of semi-axes 0.5-2 (centres in [-3, 3]^3) against ellipsoids
      of semi-axes 2-5 at the origin, random rotations (about three quarters in contact, many
      pairs not small), with the geometry for peers that take shapes;
    * ``every type``: :func:`random_pairs`, a quadric of every type of :data:`SAMPLE_KINDS`
      against small ellipsoids.
    """
    small, _ = random_ellipsoids(n, rng, axes=(0.05, 0.2), box=4.0)
    env, _ = random_ellipsoids(1, rng, axes=(3.0, 5.0), box=0.0)
    E, geo_e = random_ellipsoids(n, rng, axes=(0.5, 2.0), box=3.0)
    Q, geo_q = random_ellipsoids(n, rng, axes=(2.0, 5.0), box=0.0)
    Er, Qr, _ = random_pairs(n, rng)
    return {
        "environment": (small, env[0], None),
        "similar sizes": (E, Q, (geo_e, geo_q)),
        "every type": (Er, Qr, None),
    }


def kernel_population(n: int, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    """The population of the benchmark's kernel measurements: ``n`` small ellipsoids (semi-axes
    0.5-2, random rotations, centres in [-3, 3]^3) against ``n`` ellipsoids of semi-axes 2-5
    (centres likewise)."""
    E, _ = random_ellipsoids(n, rng, axes=(0.5, 2.0), box=3.0)
    Q, _ = random_ellipsoids(n, rng, axes=(2.0, 5.0), box=3.0)
    return E, Q


def ellipsoid_matrix(axes: Any, R: np.ndarray, centre: Any) -> np.ndarray:
    """``(x - c)^T R diag(axes^-2) R^T (x - c) - 1`` as a symmetric ``4 x 4`` matrix: the
    ellipsoid of semi-axes ``axes`` along the columns of the rotation ``R``, centred at ``c``.

    >>> ellipsoid_matrix((1.0, 2.0, 4.0), np.eye(3), (0.0, 0.0, 1.0)).diagonal().tolist()
    [1.0, 0.25, 0.0625, -0.9375]
    """
    A = R @ np.diag(1 / np.asarray(axes, dtype=float) ** 2) @ R.T
    A = (A + A.T) / 2
    c = np.asarray(centre, dtype=float)
    M = np.zeros((4, 4))
    M[:3, :3] = A
    M[:3, 3] = M[3, :3] = -A @ c
    M[3, 3] = c @ A @ c - 1
    return M


def float_depth(
    E: np.ndarray, K: np.ndarray, *, grid: int = 4000, steps: int = 30
) -> tuple[float, np.ndarray]:
    """``min phi(u)`` over unit ``u`` in binary64, ``phi(u) = h_E(u) + h_K(-u)`` (the support
    functions of two ellipsoids given as ``4 x 4`` matrices, inside negative), and its
    minimiser: a Fibonacci grid of ``grid`` directions, then ``steps`` of Newton's method on the
    sphere.  Positive: the depth of two crossing ellipsoids; negative: minus their distance.  An
    estimate, uncertified: for building pairs of a given depth, not for answers."""
    geo = []
    for M in (E, K):
        A = M[:3, :3]
        c = -np.linalg.solve(A, M[:3, 3])
        geo.append((c, (c @ A @ c - M[3, 3]) * np.linalg.inv(A)))
    (c1, M1), (c2, M2) = geo
    cd = c1 - c2
    k = np.arange(grid) + 0.5
    z = 1 - 2 * k / grid
    s = np.sqrt(1 - z * z)
    V = np.stack([s * np.cos(np.pi * (1 + 5**0.5) * k), s * np.sin(np.pi * (1 + 5**0.5) * k), z], -1)
    vals = V @ cd + np.sqrt(np.einsum("ij,jk,ik->i", V, M1, V)) + np.sqrt(np.einsum("ij,jk,ik->i", V, M2, V))
    u = V[np.argmin(vals)]
    for _ in range(steps):
        n1, n2 = np.sqrt(u @ M1 @ u), np.sqrt(u @ M2 @ u)
        m1, m2 = M1 @ u, M2 @ u
        g = cd + m1 / n1 + m2 / n2
        H = M1 / n1 - np.outer(m1, m1) / n1**3 + M2 / n2 - np.outer(m2, m2) / n2**3
        P = np.eye(3) - np.outer(u, u)
        p = np.linalg.solve(P @ H @ P - (u @ g) * P + np.outer(u, u), -P @ g)
        u = (u + p) / np.linalg.norm(u + p)
    return float(u @ cd + np.sqrt(u @ M1 @ u) + np.sqrt(u @ M2 @ u)), u
