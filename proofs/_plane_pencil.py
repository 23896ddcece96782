"""The pencil of an ellipsoid and a plane, symbolically (shared by Theorem 14,
Corollary 15 and Remark 16).

The ellipsoid ``(x - m)^T A (x - m) = 1`` and the plane ``n . x = d`` in
homogeneous coordinates, and the coefficients ``c0 .. c4`` of
``det(l E + P)`` from sympy's Berkowitz determinant.  The general pencil (all
entries symbols) is computed once per process: it is the most expensive
expansion of these proofs.
"""

from __future__ import annotations

import functools

import sympy as sp

LAM = sp.Symbol("lambda")


def ellipsoid_matrix(A: sp.Matrix, m: sp.Matrix) -> sp.Matrix:
    """The 4x4 matrix of ``(x - m)^T A (x - m) - 1``."""
    E = sp.zeros(4, 4)
    E[:3, :3] = A
    E[:3, 3] = -A * m
    E[3, :3] = (-A * m).T
    E[3, 3] = (m.T * A * m)[0, 0] - 1
    return E


def plane_matrix(n: sp.Matrix, d: sp.Expr) -> sp.Matrix:
    """The 4x4 matrix of ``n . x - d``."""
    P = sp.zeros(4, 4)
    P[:3, 3] = n / 2
    P[3, :3] = n.T / 2
    P[3, 3] = -d
    return P


def plane_pencil(A: sp.Matrix, m: sp.Matrix, n: sp.Matrix, d: sp.Expr) -> list[sp.Expr]:
    """``[c0, .., c4]`` of ``det(l E + P)``, expanded."""
    poly = sp.Poly(
        sp.expand((LAM * ellipsoid_matrix(A, m) + plane_matrix(n, d)).det(method="berkowitz")), LAM
    )
    return [sp.expand(poly.coeff_monomial(LAM**k)) for k in range(5)]


@functools.cache
def general_plane_pencil() -> tuple[list[sp.Expr], sp.Matrix, sp.Matrix, sp.Matrix, sp.Symbol]:
    """``(c, A, m, n, d)`` with every entry of ``A`` (symmetric), ``m``, ``n`` and ``d`` a
    real symbol."""
    a00, a01, a02, a11, a12, a22 = sp.symbols("a00 a01 a02 a11 a12 a22", real=True)
    A = sp.Matrix([[a00, a01, a02], [a01, a11, a12], [a02, a12, a22]])
    m = sp.Matrix(sp.symbols("m1:4", real=True))
    n = sp.Matrix(sp.symbols("n1:4", real=True))
    d = sp.Symbol("d", real=True)
    return plane_pencil(A, m, n, d), A, m, n, d
