"""Float sampling of X^T Q X over the surface of an ellipsoid: an independent,
approximate cross-check of the exact geometric decision (tests only).

The surface is parametrised by spherical angles on a (theta, phi) grid; the
connected components of {f > 0} and {f < 0} on the grid (phi periodic, each
pole one point) give the number of intersection curves by the tree formula
k = c(f < 0) + c(f > 0) - 1 of the sphere.
"""

from __future__ import annotations

import numpy as np


def surface_grid(E, n_theta: int = 120, n_phi: int = 240):
    """Points of the surface of E (float), shape (n_theta, n_phi, 3), poles included."""
    e = E.as_ellipsoid()
    M = np.array([[float(e[i, j]) for j in range(4)] for i in range(4)])
    A, b, c = M[:3, :3], M[:3, 3], M[3, 3]
    x0 = -np.linalg.solve(A, b)
    r = float(x0 @ A @ x0 - c)
    w, V = np.linalg.eigh(A)
    th = np.linspace(0, np.pi, n_theta)
    ph = np.linspace(0, 2 * np.pi, n_phi, endpoint=False)
    T, P = np.meshgrid(th, ph, indexing="ij")
    u = np.stack([np.sin(T) * np.cos(P), np.sin(T) * np.sin(P), np.cos(T)], axis=-1)
    return x0 + (u * np.sqrt(r / w)) @ V.T


def values(Q, pts):
    M = np.array([[float(Q[i, j]) for j in range(4)] for i in range(4)])
    X = np.concatenate([pts, np.ones((*pts.shape[:-1], 1))], axis=-1)
    return np.einsum("...i,ij,...j->...", X, M, X)


def _components(mask: np.ndarray) -> int:
    nt, nphi = mask.shape
    parent = list(range(nt * nphi + 2))  # two extra nodes: north and south pole

    def find(a: int) -> int:
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    def union(a: int, b: int) -> None:
        ra, rb = find(a), find(b)
        if ra != rb:
            parent[ra] = rb

    north, south = nt * nphi, nt * nphi + 1
    for i in range(nt):
        for j in range(nphi):
            if not mask[i, j]:
                continue
            k = i * nphi + j
            if i == 0:
                union(k, north)
            if i == nt - 1:
                union(k, south)
            jn = (j + 1) % nphi
            if mask[i, jn]:
                union(k, i * nphi + jn)
            if i + 1 < nt and mask[i + 1, j]:
                union(k, (i + 1) * nphi + j)
    roots = {find(i * nphi + j) for i in range(nt) for j in range(nphi) if mask[i, j]}
    return len(roots)


def sampled(E, Q, n_theta: int = 120, n_phi: int = 240) -> dict:
    """Sampled min, max and (when both signs occur) the grid count of curves."""
    f = values(Q, surface_grid(E, n_theta, n_phi))
    out = {"min": float(f.min()), "max": float(f.max()), "scale": float(np.abs(f).max()) or 1.0}
    if f.min() < 0 < f.max():
        out["curves"] = _components(f < 0) + _components(f > 0) - 1
    return out
