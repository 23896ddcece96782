"""Independent references that tests and benchmarks check the package's fast paths against.

:func:`plane_distance_reference` is the closed form of an ellipsoid's distance from a plane as
it was first written, in real algebraic arithmetic (tensor products of number fields, then a
root isolation of each result): slow, but it shares nothing with the direct construction of
:mod:`quadric_contact.theory.distance` except the formula.  :func:`exact_overlap` is the
exact overlap of two solid ellipsoids from their exact contact codes, the truth the
benchmark measures the python-fcl peer (:func:`~quadric_contact.testing.peers.peer_fcl`)
against.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from quadric_contact.exact.algebraic import RealAlgebraic
from quadric_contact.model.quadric import Quadric
from quadric_contact.theory.contact_scale import centred_form
from quadric_contact.theory.distance import _solve3

__all__ = ["exact_overlap", "plane_distance_reference"]


def plane_distance_reference(E: Any, K: Any) -> tuple[Any, tuple[Any, ...], tuple[Any, ...], tuple[Any, ...]]:
    """The signed distance of the ellipsoid ``E`` (the paper's sign) from the half-space ``K``
    (a plane's solid, ``K(x) <= 0``), and its witnesses ``point_Q``, the unit normal and
    ``point_E``, as real algebraic numbers: with ``E = (x - c)^T A (x - c) - r`` and
    ``K = n . x - d``, the point of ``E`` farthest along ``-n`` is
    ``c - sqrt(r k) A^-1 n / k`` (``k = n^T A^-1 n``) and the distance is
    ``(n . c - d - sqrt(r k)) / |n|``."""
    A, c, r = centred_form(E)
    n = [2 * K[i, 3] for i in range(3)]
    d = -K[3, 3]
    Ainv_n = _solve3(A, n)
    k = sum(n[i] * Ainv_n[i] for i in range(3))
    N = sum(x * x for x in n)
    nc = sum(n[i] * c[i] for i in range(3))
    root_rk, norm = RealAlgebraic.sqrt(r * k), RealAlgebraic.sqrt(N)
    gap = root_rk * -1 + (nc - d)
    dist = gap / norm
    point_E = tuple(root_rk * (-Ainv_n[i] / k) + c[i] for i in range(3))
    point_Q = tuple(point_E[i] - gap * (n[i] / N) for i in range(3))
    normal = tuple(RealAlgebraic(n[i]) / norm for i in range(3))
    return dist, point_Q, normal, point_E


def exact_overlap(E: np.ndarray, Q: np.ndarray, contact: np.ndarray) -> np.ndarray:
    """Do the solid ellipsoids overlap, exactly: transversal contact, or the centre of
    one inside the other (without contact one is then inside the other)."""
    out = np.empty(len(E), dtype=np.int8)
    for k in range(len(E)):
        if contact[k]:
            out[k] = 1
            continue
        e, q = Quadric.from_matrix(E[k]), Quadric.from_matrix(Q[k])
        ce, cq = e.center(), q.center()
        assert ce is not None and cq is not None
        out[k] = int(q.value_at(ce) * q[0, 0] < 0 or e.value_at(cq) * e[0, 0] < 0)
    return out
