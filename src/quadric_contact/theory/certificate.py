"""The separation certificate, exactly: a definite member of the pencil, or four simple roots.

For an ellipsoid ``E`` (the paper's sign) and any quadric ``Q``, with ``f = X^T Q X`` on
the surface of ``E`` (see :mod:`quadric_contact.modes.decision.separation` for the three facts
behind it):

* some member ``lambda E + Q`` positive definite  <=>  ``f > 0`` on ``E`` (strictly in ``R+``);
* some member negative definite  <=>  ``f < 0`` on ``E`` (strictly in ``R-``);
* four simple real roots and no definite member  =>  the surfaces cross.

Here the real roots of ``P`` are isolated exactly (disjoint rational intervals), one
rational point is taken in each gap between consecutive roots, and the inertia of the
member there is exact (Descartes' rule on the sums of its principal minors).  The
certificate decides every pair whose roots are simple, and every strictly separated
pair whatever its roots; it says nothing (``decided`` False) for a tangency or a
crossing with a multiple root, which :mod:`quadric_contact.theory.geometric` then settles.
It needs no smallness and no type of ``Q``.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from itertools import pairwise

from quadric_contact.exact.algebraic import rational_between, real_roots
from quadric_contact.model.classification import Inertia, inertia_from_minor_sums, principal_minor_sums_4
from quadric_contact.theory.pencil import CharacteristicPolynomial
from quadric_contact.theory.results import Region

__all__ = ["SeparationCertificate", "separation_certificate"]


@dataclass(frozen=True)
class SeparationCertificate:
    """What the members of the pencil say about where ``E`` lies.

    Attributes
    ----------
    region : Region or None
        ``R+`` (a positive definite member: ``f > 0`` on ``E``), ``R-`` (negative
        definite: ``f < 0``), ``CONTACT`` (four simple real roots, no definite member:
        the surfaces cross), None (no certificate: a multiple root without a definite
        member).
    samples : tuple of (Fraction, Inertia)
        The rational points between consecutive distinct real roots of ``P`` and the
        inertia of the member there.
    simple : bool
        ``P`` has four simple real roots.

    Examples
    --------
    Two unit spheres, centres 3 apart: the member at ``lambda`` between the two positive
    roots is positive definite.

    >>> from quadric_contact import Quadric, characteristic_polynomial
    >>> c = separation_certificate(characteristic_polynomial(Quadric.sphere(1), Quadric.sphere(1, (3, 0, 0))))
    >>> c.region, str(c)
    (<Region.R_PLUS: 'R+'>, 'the member 3 E + Q is positive definite: X^T Q X > 0 on E (R+, strictly)')
    """

    region: Region | None
    samples: tuple[tuple[Fraction, Inertia], ...]
    simple: bool

    @property
    def decided(self) -> bool:
        return self.region is not None

    def __str__(self) -> str:
        for s, i in self.samples:
            if i.positive == 4 or i.negative == 4:
                sign = "positive" if i.positive == 4 else "negative"
                side = "R+" if i.positive == 4 else "R-"
                rel = ">" if i.positive == 4 else "<"
                return f"the member {s} E + Q is {sign} definite: X^T Q X {rel} 0 on E ({side}, strictly)"
        if self.region is Region.CONTACT:
            seq = ", ".join(str(i.positive) for _, i in self.samples)
            return (
                f"four simple real roots and no definite member (positive eigenvalues {seq} between "
                "them): X^T Q X takes both signs on E"
            )
        return "no definite member and a multiple root: no certificate"


def separation_certificate(P: CharacteristicPolynomial) -> SeparationCertificate:
    """The exact separation certificate of the pair of ``P`` (``P.E`` with the paper's sign).

    Parameters
    ----------
    P : CharacteristicPolynomial

    Returns
    -------
    SeparationCertificate

    References
    ----------
    Finsler's lemma (the S-lemma); the signature sequence of a real symmetric pencil.
    """
    e, q = P.E.upper, P.Q.upper
    roots = real_roots(list(P.coefficients), multiplicities=True)
    values = [r for r, _ in roots]
    samples: list[tuple[Fraction, Inertia]] = []
    for a, b in pairwise(values):
        s = rational_between(a, b)
        member = tuple(s * x + y for x, y in zip(e, q, strict=True))
        samples.append((s, inertia_from_minor_sums(principal_minor_sums_4(member))))
    simple = len(roots) == 4 and all(m == 1 for _, m in roots)
    region: Region | None = None
    if any(i.positive == 4 for _, i in samples):
        region = Region.R_PLUS
    elif any(i.negative == 4 for _, i in samples):
        region = Region.R_MINUS
    elif simple:
        region = Region.CONTACT
    return SeparationCertificate(region, tuple(samples), simple)
