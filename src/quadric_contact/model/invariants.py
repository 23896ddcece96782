"""The Euclidean invariants of a quadric used by Table 2 (Section 2.4).

For ``Q = [[Q00, b], [b^T, c]]`` (eq. (6)):

* ``det Q``;
* the eigenvalues ``mu_1 <= mu_2 <= mu_3`` of ``Q00``, exact real algebraic
  numbers (roots of ``t^3 - tr(Q00) t^2 + J t - det(Q00)``, which is
  real-rooted: ``Q00`` is symmetric);
* ``J``: the sum of the principal 2x2 minors of ``Q00``;
* ``K``: the sum of the principal 3x3 minors of ``Q`` that contain the last
  row and column (the paper's ``det Q~_11 + det Q~_22 + det Q~_33``);
* ``J'``: the sum of the principal 2x2 minors of ``Q`` that contain the last
  row and column.

``det Q``, the eigenvalues and ``J`` are invariant under rigid motions;
``K`` only when ``det Q00 = det Q = 0`` (the cylinders, the rows of Table 2
that use it) and ``J'`` only when ``Q00`` has rank 1 and ``K = 0`` (parallel
planes): under translations they change in general.  Theorem 5's proof
relies on this; ``tests/test_table_2_symbolic.py`` checks it symbolically.
All scale with ``Q``:
``det Q`` by ``k^4``, ``K`` by ``k^3``, ``J, J'`` by ``k^2``, eigenvalues by
``k``.  They are computed from the sums of principal minors of
:mod:`~quadric_contact.model.classification`:
``E_2(Q) = J + J'`` and ``E_3(Q) = K + det Q00``.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from quadric_contact.exact.algebraic import RealAlgebraic, real_roots
from quadric_contact.model.classification import principal_minor_sums_3, principal_minor_sums_4
from quadric_contact.model.quadric import as_quadric

__all__ = ["QuadricInvariants", "invariants"]


@dataclass(frozen=True)
class QuadricInvariants:
    """The invariants of Section 2.4 of one quadric matrix (exact).

    Attributes
    ----------
    det : Fraction
        ``det Q``.
    eigenvalues : tuple of RealAlgebraic
        Eigenvalues of ``Q00`` with multiplicity, increasing.
    trace, J, det00 : Fraction
        ``tr Q00``, the sum of its principal 2x2 minors, ``det Q00``.
    K, J_prime : Fraction
        As in Section 2.4.
    """

    det: Fraction
    eigenvalues: tuple[RealAlgebraic, RealAlgebraic, RealAlgebraic]
    trace: Fraction
    J: Fraction
    det00: Fraction
    K: Fraction
    J_prime: Fraction

    @property
    def characteristic_polynomial(self) -> tuple[Fraction, Fraction, Fraction, Fraction]:
        """Coefficients ``(c0, c1, c2, c3)`` of ``det(t I - Q00)``."""
        return (-self.det00, self.J, -self.trace, Fraction(1))

    def nonzero_eigenvalues(self) -> list[RealAlgebraic]:
        """The eigenvalues of ``Q00`` that are not zero (exactly)."""
        return [m for m in self.eigenvalues if m.sign() != 0]

    def to_dict(self) -> dict[str, Any]:
        return {
            "det": str(self.det),
            "eigenvalues": [str(m) for m in self.eigenvalues],
            "trace": str(self.trace),
            "J": str(self.J),
            "det00": str(self.det00),
            "K": str(self.K),
            "J_prime": str(self.J_prime),
        }


def invariants(Q: Any) -> QuadricInvariants:
    """The invariants ``det Q``, eigenvalues of ``Q00``, ``J``, ``K``, ``J'`` (Section 2.4).

    Parameters
    ----------
    Q : Quadric, matrix-like or equation

    Returns
    -------
    QuadricInvariants

    Examples
    --------
    The hyperboloid ``S2`` of Example 17:

    >>> inv = invariants("x**2 + y**2 - 0.25*(z-3)**2 - 1")
    >>> [str(m) for m in inv.eigenvalues], inv.det, inv.J, inv.K, inv.J_prime
    (['-1/4', '1', '1'], Fraction(1, 4), Fraction(1, 2), Fraction(-11, 4), Fraction(-25, 4))
    """
    q = as_quadric(Q, "Q")
    u = q.upper
    a = (u[0], u[1], u[2], u[4], u[5], u[7])
    tr, J, det00 = principal_minor_sums_3(a)
    _, E2, E3, E4 = principal_minor_sums_4(u)
    eig: list[RealAlgebraic] = []
    for r, m in real_roots([-det00, J, -tr, Fraction(1)], multiplicities=True):
        eig.extend([r] * m)
    assert len(eig) == 3, "a symmetric matrix has real eigenvalues"
    return QuadricInvariants(
        det=Fraction(E4),
        eigenvalues=(eig[0], eig[1], eig[2]),
        trace=Fraction(tr),
        J=Fraction(J),
        det00=Fraction(det00),
        K=Fraction(E3 - det00),
        J_prime=Fraction(E2 - J),
    )
