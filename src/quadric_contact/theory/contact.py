"""Transversal contact (Theorem 2, Corollary 10, Remark 9, Theorem 14).

The decision (``method="auto"``, the default) is the table of
:mod:`quadric_contact.theory.decision`, read off the signatures of the pencil: a definite
member means no contact, non-real roots or four simple roots without a definite member mean
transversal contact, for every pair, small or not; a singular intersection (a multiple root
without a definite member) goes to the exact geometric decision.

The paper's route stays here under its own name (``method="theory"``, or a caller's
``small=`` assertion), for an ellipsoid ``E`` and a quadric ``Q``:

1. ``P`` has a non-real root: transversal contact, for *any* pair
   (Remark 9).  In the paper's terms: ``Delta_4 < 0`` or ``Delta_4 = 0`` and
   ``Delta_3 < 0`` (Corollary 10); the package classifies the roots with the
   complete discrimination system, which also covers the degenerate cases.
2. ``Q`` is a plane: no non-real root means no transversal contact, for any
   ellipsoid (Theorem 14).
3. ``Q`` has no real points: no contact.
4. All roots real and ``E`` small with respect to ``Q`` (Tables 1, 2, or the
   caller's assertion): no transversal contact (Theorem 2).
5. All roots real and ``E`` not known to be small: the paper does not decide
   (Remark 9).  With a ``small=False`` assertion and ``method="auto"`` the exact separation
   certificate (:mod:`quadric_contact.theory.certificate`) settles it, and where it cannot (a
   tangency, a multiple root) the exact geometric decision does; the result says which.  With
   ``method="theory"`` the result is undecided.
"""

from __future__ import annotations

from functools import partial
from typing import Any

from quadric_contact.exact.errors import ExcludedQuadricError
from quadric_contact.model.classification import NO_REAL_POINTS, REFUSED_KINDS, QuadricKind
from quadric_contact.model.quadric import Quadric
from quadric_contact.theory.certificate import separation_certificate
from quadric_contact.theory.decision import PencilDecision, Rule, decide_pencil
from quadric_contact.theory.geometric import decide_geometrically
from quadric_contact.theory.pencil import CharacteristicPolynomial, characteristic_polynomial
from quadric_contact.theory.results import ContactResult, Region
from quadric_contact.theory.smallness import smallness

__all__ = ["decide_pencil_checked", "decide_transversal", "refuse", "transversal_contact_exact"]


def refuse(Q: Quadric, what: str = "Q") -> None:
    """Raise :class:`ExcludedQuadricError` for the types no predicate answers for
    (:data:`~quadric_contact.model.classification.REFUSED_KINDS`)."""
    kind = Q.kind
    if kind in REFUSED_KINDS:
        raise ExcludedQuadricError(f"{what} is {kind.value}: {kind.excluded_reason}", Q, kind=kind)


METHODS = ("auto", "theory")


def _corollary_10_reading(P: CharacteristicPolynomial) -> str:
    _, s3, s4 = P.delta_signs()
    sym = {-1: "< 0", 0: "= 0", 1: "> 0"}
    return f"Delta4 {sym[s4]}" + ("" if s4 else f", Delta3 {sym[s3]}")


def _known_smallness(E: Any, Q: Any) -> tuple[bool | None, Any]:
    """Exact smallness of ``E`` w.r.t. ``Q`` when the smallness module can decide it."""
    report = smallness(E, Q)
    return report.small, report


def _geometric(E: Any, Q: Any) -> Any:
    """The exact geometric decision (:mod:`quadric_contact.theory.geometric`)."""
    return decide_geometrically(E, Q)


def decide_transversal(
    P: CharacteristicPolynomial, *, small: bool | None = None, method: str = "auto"
) -> ContactResult:
    """Decide transversal contact from an already computed characteristic polynomial.

    Parameters
    ----------
    P : CharacteristicPolynomial
        ``det(lambda E + Q)`` with ``E`` normalised (``det E < 0``).
    small, method
        As for :func:`transversal_contact`.

    Returns
    -------
    ContactResult

    Raises
    ------
    ExcludedQuadricError
        ``Q`` is of a type the theory excludes (a cone, intersecting planes,
        ...), all roots are real, and ``method="theory"`` or the geometric
        decision is not available.

    References
    ----------
    Remark 9, Theorem 2, Corollary 10, Theorem 14.

    Examples
    --------
    Example 17, the bee and the trunk: all roots real, ``Delta_4 > 0``.

    >>> from quadric_contact import characteristic_polynomial
    >>> bee = "(x-3)**2 + (y-3)**2 + 3*(z-5.5)**2 - 0.1"
    >>> P = characteristic_polynomial(bee, "x**2 + y**2 - 0.25*(z-3)**2 - 1")
    >>> r = decide_transversal(P, small=True)
    >>> r.transversal, r.decided_by
    (False, 'Corollary 10')

    Without smallness the paper's results do not conclude (Remark 9):

    >>> decide_transversal(P, small=False, method="theory").transversal is None
    True
    """
    if method not in METHODS:
        raise ValueError(f"method must be one of {METHODS}, got {method!r}")
    if method == "auto" and small is None:
        return _signature_route(P)
    return paper_route(P, small=small, method=method)


def decide_pencil_checked(P: CharacteristicPolynomial) -> PencilDecision:
    """:func:`~quadric_contact.theory.decision.decide_pencil` after refusing the types no
    predicate answers for.  A refused ``Q`` (a double plane, the zero matrix) has rank at most
    one, so ``lambda^3`` divides ``P``; only then is its type read."""
    C = P.integer_coefficients
    if C[0] == 0 and C[1] == 0 and C[2] == 0:
        refuse(P.Q)
    return decide_pencil(P)


def _nonreal_reason(P: CharacteristicPolynomial) -> str:
    return (
        f"P has {2 * P.structure.nonreal_pairs} non-real roots ({_corollary_10_reading(P)}): "
        "transversal contact for any pair"
    )


def _signature_route(P: CharacteristicPolynomial) -> ContactResult:
    """The table of :mod:`quadric_contact.theory.decision`, then the exact geometric decision
    for a singular intersection."""
    d = decide_pencil_checked(P)
    if d.transversal is not None:
        # the sentence is written when read (``ContactResult.reason``)
        because = partial(_nonreal_reason, P) if d.rule is Rule.NONREAL_ROOTS else d.__str__
        return ContactResult(d.transversal, d.decided_by, because, P, None, d)
    geo = _geometric(P.E, P.Q)
    return ContactResult(
        geo.transversal,
        "geometric decision",
        f"{d}; decided by the exact extremes of X^T Q X on E ({geo})",
        P,
        None,
        geo,
    )


def paper_route(
    P: CharacteristicPolynomial, *, small: bool | None = None, method: str = "theory"
) -> ContactResult:
    """The paper's decision: Remark 9, Theorem 14, Corollary 10 with the smallness of
    Tables 1-2 (decided, or asserted by the caller); where it does not apply, undecided
    (``method="theory"``) or, with ``method="auto"``, the separation certificate and the
    exact geometric decision."""
    refuse(P.Q)
    if P.Q.kind in NO_REAL_POINTS:
        return ContactResult(False, "no real points", f"Q is {P.Q.kind.value}: it has no real surface", P)
    structure = P.structure
    reading = _corollary_10_reading(P)
    if not structure.all_real:
        return ContactResult(True, "Remark 9", _nonreal_reason(P), P)
    kind = P.Q.kind
    if kind is QuadricKind.PLANE:
        return ContactResult(
            False, "Theorem 14", f"all roots of P are real ({reading}): no transversal contact", P
        )
    if not kind.in_table_1 and method == "theory":
        raise ExcludedQuadricError(
            f"Q is {kind.value}: {kind.excluded_reason}; all roots of P are real, so only the theory of "
            "Theorem 2 could decide, and it excludes this type",
            P.Q,
            kind=kind,
        )
    report: Any = None
    if small is None and kind.in_table_1:
        small, report = _known_smallness(P.E, P.Q)
    elif small is not None:
        report = "asserted by caller"
    if small and kind.in_table_1:
        return ContactResult(
            False,
            "Corollary 10",
            f"all roots of P are real ({reading}) and E is small with respect to Q (Theorem 2)",
            P,
            report,
        )
    why = (
        f"all roots of P are real ({reading}) but "
        + (
            "E is not small with respect to Q"
            if small is False
            else "E is not known to be small with respect to Q"
        )
        + ": Corollary 10 cannot rule out two intersection curves (Remark 9)"
    )
    if method == "auto":
        cert = separation_certificate(P)
        if cert.decided:
            return ContactResult(
                cert.region is Region.CONTACT, "separation certificate", f"{why}; {cert}", P, report, cert
            )
        geo = _geometric(P.E, P.Q)
        return ContactResult(
            geo.transversal,
            "geometric decision",
            f"{why}; decided by the exact extremes of X^T Q X on E ({geo})",
            P,
            report,
            geo,
        )
    if not kind.in_table_1:
        raise ExcludedQuadricError(f"Q is {kind.value}: {kind.excluded_reason}", P.Q, kind=kind)
    return ContactResult(None, None, why, P, report)


def transversal_contact_exact(
    E: Any, Q: Any, *, small: bool | None = None, method: str = "auto"
) -> ContactResult:
    """Transversal contact of one pair, decided exactly (the scalar path of the
    ``certified`` and ``exact`` modes of :func:`quadric_contact.transversal_contact`).

    Parameters
    ----------
    E : Quadric, matrix-like or equation
        A real ellipsoid (either sign of its matrix).
    Q : Quadric, matrix-like or equation
        Any quadric but a double plane or the zero matrix.
    small, method
        As for :func:`decide_transversal`.

    Returns
    -------
    ContactResult

    Raises
    ------
    NotAnEllipsoidError, ExcludedQuadricError, and the input errors of :class:`Quadric`.

    Examples
    --------
    Example 11 (``Delta_4 = 0``, ``Delta_3 < 0``):

    >>> r = transversal_contact_exact("2*x**2 + 2*y**2 + 3*z**2 - 1", "x**2 + y**2 + 8*z")
    >>> bool(r), r.decided_by
    (True, 'Remark 9')
    """
    return decide_transversal(characteristic_polynomial(E, Q), small=small, method=method)
