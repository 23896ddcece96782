"""The Segre characteristic of the pencil ``lambda*E + Q``, exactly.

For the regular pencil ``lambda*E + Q`` (``det E != 0``) the *determinantal
divisors* ``D_k`` (the monic gcd of all ``k x k`` minors, a polynomial in
``lambda`` over Q) give the *invariant factors* ``i_k = D_k / D_(k-1)``.
For each irreducible factor ``p`` of ``D_4 = det`` the exponents of ``p`` in
``i_4, i_3, i_2, i_1`` (non-increasing) are the sizes of the Jordan blocks
of ``-E^-1 Q`` at each root of ``p``: the *Segre group* of those
eigenvalues.  The symbol writes each group as its block sizes, in
parentheses when a root carries several blocks, e.g. ``[(11)11]``: a double
root with two blocks of size 1 (its member of the pencil has rank 2) and two
simple roots.  Groups are listed by decreasing multiplicity, then decreasing
largest block, which reproduces the paper's notation (``[2(11)]``,
``[(21)1]``, ``[(211)]``).  The paper's subscript is the number of distinct
real roots (``[(11)11]_3``).

Everything is exact: minors are polynomials over Q (python-flint), gcds are
exact, eigenvalues are :class:`~quadric_contact.exact.algebraic.RealAlgebraic`
(non-real roots are counted, not isolated).
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import combinations
from typing import Any

import flint

from quadric_contact.exact.algebraic import RealAlgebraic, real_roots
from quadric_contact.exact.errors import DegeneratePencilError
from quadric_contact.exact.rational import fmpq_of, monic
from quadric_contact.theory.pencil import as_quadric

__all__ = ["SegreGroup", "SegreSymbol", "segre_symbol"]


@dataclass(frozen=True)
class SegreGroup:
    """The Jordan block sizes at one eigenvalue of the pencil.

    Attributes
    ----------
    blocks : tuple of int
        Non-increasing block sizes (the partial multiplicities).
    eigenvalue : RealAlgebraic or None
        The eigenvalue ``lambda`` with ``det(lambda*E + Q) = 0`` when real
        (None for a non-real one).
    factor : str
        The irreducible factor of ``det`` it is a root of.
    """

    blocks: tuple[int, ...]
    eigenvalue: RealAlgebraic | None
    factor: str

    @property
    def multiplicity(self) -> int:
        """Multiplicity of the eigenvalue as a root of ``det(lambda*E + Q)``."""
        return sum(self.blocks)

    @property
    def is_real(self) -> bool:
        """The eigenvalue is real."""
        return self.eigenvalue is not None

    @property
    def rank_drop(self) -> int:
        """``4 - rank(lambda*E + Q)`` at this eigenvalue (the number of blocks)."""
        return len(self.blocks)

    def __str__(self) -> str:
        s = "".join(str(b) for b in self.blocks)
        return s if len(self.blocks) == 1 else f"({s})"


@dataclass(frozen=True)
class SegreSymbol:
    """The Segre characteristic of ``lambda*E + Q``.

    ``str(s)`` is the paper's notation with the subscript, e.g. ``"[(11)11]_3"``;
    ``s.symbol`` is the bracket alone.
    """

    groups: tuple[SegreGroup, ...]
    invariant_factors: tuple[str, str, str, str]

    @property
    def symbol(self) -> str:
        """The bracket without the subscript, e.g. ``"[(11)11]"``."""
        return "[" + "".join(str(g) for g in self.groups) + "]"

    @property
    def real_roots(self) -> int:
        """Number of distinct real roots of ``det(lambda*E + Q)`` (the paper's subscript)."""
        return sum(1 for g in self.groups if g.is_real)

    def __str__(self) -> str:
        return f"{self.symbol}_{self.real_roots}"

    def __eq__(self, other: object) -> bool:
        if isinstance(other, str):
            return other in (str(self), self.symbol)
        if isinstance(other, SegreSymbol):
            return str(self) == str(other)
        return NotImplemented

    def __hash__(self) -> int:
        return hash(str(self))


def _pencil(E: Any, Q: Any) -> list[list[Any]]:
    lam = flint.fmpq_poly([0, 1])
    return [[lam * fmpq_of(E[i, j]) + fmpq_of(Q[i, j]) for j in range(4)] for i in range(4)]


def _det(M: list[list[Any]]) -> Any:
    n = len(M)
    if n == 1:
        return M[0][0]
    if n == 2:
        return M[0][0] * M[1][1] - M[0][1] * M[1][0]
    total = flint.fmpq_poly([0])
    for j in range(n):
        if M[0][j].is_zero():
            continue
        minor = [row[:j] + row[j + 1 :] for row in M[1:]]
        term = M[0][j] * _det(minor)
        total = total + term if j % 2 == 0 else total - term
    return total


def _gcd_minors(M: list[list[Any]], k: int) -> Any:
    g = flint.fmpq_poly([0])
    for rows in combinations(range(4), k):
        for cols in combinations(range(4), k):
            d = _det([[M[i][j] for j in cols] for i in rows])
            if not d.is_zero():
                g = d if g.is_zero() else g.gcd(d)
                if g.degree() == 0:
                    return flint.fmpq_poly([1])
    return monic(g) if not g.is_zero() else g


def _multiplicity(f: Any, p: Any) -> int:
    m = 0
    while f.degree() >= p.degree() and (f % p).is_zero():
        f = f / p
        m += 1
    return m


def segre_symbol(E: Any, Q: Any) -> SegreSymbol:
    """The Segre characteristic of ``lambda*E + Q`` (exact).

    Parameters
    ----------
    E : Quadric, matrix-like or equation
        A real ellipsoid (any non-degenerate quadric works; the pencil must be regular).
    Q : Quadric, matrix-like or equation

    Returns
    -------
    SegreSymbol

    References
    ----------
    Proof of Theorem 2, Remark 9 and Table 3 (Segre types of the pencil).

    Examples
    --------
    Example 11 (a double root with a rank-2 member, two complex roots):

    >>> str(segre_symbol("2*x**2 + 2*y**2 + 3*z**2 - 1", "x**2 + y**2 + 8*z"))
    '[(11)11]_1'

    A unit sphere in a circular cylinder of radius 1 (a curve of tangency):

    >>> str(segre_symbol("x**2 + y**2 + z**2 - 1", "x**2 + y**2 - 1"))
    '[(111)1]_2'
    """
    e = as_quadric(E, "E")
    q = as_quadric(Q, "Q")
    M = _pencil(e, q)
    D = [flint.fmpq_poly([1])]
    for k in (1, 2, 3):
        D.append(_gcd_minors(M, k))
    det = _det(M)
    if det.is_zero():
        raise DegeneratePencilError("det(lambda*E + Q) vanishes identically: the pencil is singular", (e, q))
    D.append(monic(det))
    inv = [D[k] / D[k - 1] for k in range(1, 5)]
    groups: list[SegreGroup] = []
    _, factors = D[4].factor()
    for f, _m in factors:
        p = monic(flint.fmpq_poly(f))
        blocks = tuple(b for b in (_multiplicity(inv[k], p) for k in (3, 2, 1, 0)) if b > 0)
        reals = real_roots(p)
        name = str(p)
        for r in reals:
            groups.append(SegreGroup(blocks, r, name))
        for _ in range(p.degree() - len(reals)):
            groups.append(SegreGroup(blocks, None, name))
    groups.sort(key=lambda g: (-g.multiplicity, -g.blocks[0], len(g.blocks)))
    return SegreSymbol(tuple(groups), (str(inv[0]), str(inv[1]), str(inv[2]), str(inv[3])))
