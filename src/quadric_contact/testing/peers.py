"""The peers: other ways to answer the contact question, which the benchmark measures the number
modes against (and the notebooks compare them with).

``numpy eigvals`` (:func:`peer_numpy_eigvals`): batched eigenvalues of ``-Q E^-1``, non-real
when an imaginary part exceeds :data:`EIG_TOL` of the modulus; ``numpy roots``
(:func:`peer_numpy_roots`): ``numpy.roots`` of the float pencil coefficients, pair by pair,
same tolerance; ``sympy`` (:func:`peer_sympy`): sympy's determinant of ``lambda E + Q`` over
the rationals, its discriminant and a Sturm count of the real roots (exact, slow); ``fcl GJK``
(:func:`peer_fcl`): python-fcl's ellipsoid-ellipsoid collision (solid overlap, to be compared
with :func:`~quadric_contact.testing.references.exact_overlap`).
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction
from typing import Any

import numpy as np

from quadric_contact._generated import formulas
from quadric_contact.exact.entries import ENTRY_INDICES

__all__ = ["EIG_TOL", "peer_fcl", "peer_numpy_eigvals", "peer_numpy_roots", "peer_sympy"]

EIG_TOL = 1e-9
"""The numpy peers' test for a non-real eigenvalue or root: an imaginary part above ``EIG_TOL``
times the largest modulus (at least 1)."""


def peer_numpy_eigvals(E: np.ndarray, Q: np.ndarray, tol: float = EIG_TOL) -> np.ndarray:
    """Contact codes from the batched eigenvalues of ``-Q E^-1`` (same as of ``-E^-1 Q``)."""
    w = np.linalg.eigvals(-np.linalg.solve(E, Q))
    scale = np.maximum(1.0, np.abs(w).max(axis=-1, keepdims=True))
    return (np.abs(w.imag) > tol * scale).any(axis=-1).astype(np.int8)


def _float_coefficients(E: np.ndarray, Q: np.ndarray) -> np.ndarray:
    e = [E[:, i, j] for i, j in ENTRY_INDICES]
    q = [Q[:, i, j] for i, j in ENTRY_INDICES]
    return np.stack(formulas.pencil_coefficients(*e, *q), axis=1)


def peer_numpy_roots(E: np.ndarray, Q: np.ndarray, tol: float = EIG_TOL) -> np.ndarray:
    """Contact codes from ``numpy.roots`` of the float pencil coefficients, pair by pair."""
    c = _float_coefficients(E, Q)
    out = np.empty(len(c), dtype=np.int8)
    for k, row in enumerate(c):
        r = np.roots(row[::-1])
        out[k] = bool((np.abs(r.imag) > tol * max(1.0, float(np.abs(r).max(initial=0.0)))).any())
    return out


def peer_sympy(E: np.ndarray, Q: np.ndarray) -> np.ndarray:
    """Exact contact codes by sympy: the determinant of ``lambda E + Q`` over the
    rationals, its discriminant, and a Sturm count of the real roots when needed."""
    import sympy  # heavy: loaded only when this peer runs

    lam = sympy.Symbol("lambda")
    out = np.empty(len(E), dtype=np.int8)
    for k in range(len(E)):
        entries = [
            lam * sympy.Rational(Fraction(float(E[k, i, j]))) + sympy.Rational(Fraction(float(Q[k, i, j])))
            for i in range(4)
            for j in range(4)
        ]
        M = sympy.Matrix(4, 4, entries)
        P = sympy.Poly(M.det(method="berkowitz"), lam)
        disc = sympy.discriminant(P)
        if disc < 0:
            out[k] = 1
            continue
        real = sum(m * f.count_roots() for f, m in P.sqf_list()[1])
        out[k] = int(bool(int(real) < P.degree()))
    return out


def _fcl_objects(geometry: dict[str, np.ndarray], k: int) -> Any:
    import fcl  # optional (python-fcl, the bench extra)

    a = geometry["axes"][k]
    return fcl.CollisionObject(
        fcl.Ellipsoid(float(a[0]), float(a[1]), float(a[2])),
        fcl.Transform(
            np.asarray(geometry["rotation"][k], dtype=float), np.asarray(geometry["center"][k], dtype=float)
        ),
    )


def peer_fcl(geo_e: dict[str, np.ndarray], geo_q: dict[str, np.ndarray], which: Sequence[int]) -> np.ndarray:
    """Solid overlap of two ellipsoids by python-fcl's GJK (libccd), pair by pair."""
    import fcl  # optional (python-fcl, the bench extra)

    out = np.empty(len(which), dtype=np.int8)
    for t, k in enumerate(which):
        request, result = fcl.CollisionRequest(), fcl.CollisionResult()
        out[t] = fcl.collide(_fcl_objects(geo_e, k), _fcl_objects(geo_q, k), request, result) > 0
    return out
