"""Transversal contact (Theorem 2, Corollary 10, Remark 9, Theorem 14).

The decision, for an ellipsoid ``E`` and a quadric ``Q``:

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
   (Remark 9).  With ``method="auto"`` the exact geometric decision settles
   it and says so; with ``method="theory"`` the result is undecided.
"""

from __future__ import annotations

from typing import Any

from .classification import QuadricKind
from .errors import ExcludedQuadricError
from .pencil import CharacteristicPolynomial, characteristic_polynomial
from .results import ContactResult

__all__ = ["decide_transversal", "transversal_contact"]

NO_REAL_POINTS = frozenset(
    {
        QuadricKind.IMAGINARY_ELLIPSOID,
        QuadricKind.IMAGINARY_ELLIPTIC_CYLINDER,
        QuadricKind.IMAGINARY_PARALLEL_PLANES,
        QuadricKind.EMPTY,
    }
)
"""Types whose real point set is empty: nothing to touch."""

METHODS = ("auto", "theory")


def _corollary_10_reading(P: CharacteristicPolynomial) -> str:
    _, s3, s4 = P.delta_signs()
    sym = {-1: "< 0", 0: "= 0", 1: "> 0"}
    return f"Delta4 {sym[s4]}" + ("" if s4 else f", Delta3 {sym[s3]}")


def _known_smallness(E: Any, Q: Any) -> tuple[bool | None, Any]:
    """Exact smallness of ``E`` w.r.t. ``Q`` when the smallness module can decide it."""
    from .smallness import smallness

    report = smallness(E, Q)
    return report.small, report


def _geometric(E: Any, Q: Any) -> Any:
    """The exact geometric decision (:mod:`quadric_contact.geometric`)."""
    from .geometric import decide_geometrically

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
    structure = P.structure
    reading = _corollary_10_reading(P)
    if not structure.all_real:
        return ContactResult(
            True,
            "Remark 9",
            f"P has {2 * structure.nonreal_pairs} non-real roots ({reading}): "
            "transversal contact for any pair",
            P,
        )
    kind = P.Q.kind
    if kind is QuadricKind.PLANE:
        return ContactResult(
            False, "Theorem 14", f"all roots of P are real ({reading}): no transversal contact", P
        )
    if kind in NO_REAL_POINTS:
        return ContactResult(False, "no real points", f"Q is an {kind.value}: it has no real points", P)
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


def transversal_contact(
    E: Any,
    Q: Any,
    *,
    small: bool | None = None,
    method: str = "auto",
    mode: str = "certified",
) -> Any:
    """Are the ellipsoid ``E`` and the quadric ``Q`` in transversal contact?

    Parameters
    ----------
    E : Quadric, matrix-like or equation; or a stack ``(..., 4, 4)``
        A real ellipsoid (either sign of its matrix).
    Q : Quadric, matrix-like or equation; or a stack ``(..., 4, 4)``
        Any quadric; planes are handled by Theorem 14.
    small : bool, optional
        Assert that ``E`` is (or is not) small with respect to ``Q``.  By
        default smallness is decided exactly (Table 2).
    method : {"auto", "theory"}
        ``"theory"`` uses only the paper's results and reports undecided
        where they do not apply; ``"auto"`` falls back on the exact geometric
        decision.
    mode : {"certified", "exact", "float", "ball", "mpmath"}
        Number mode.  For a single pair ``"certified"`` and ``"exact"`` give
        the exact answer; stacks go to the array predicates.

    Returns
    -------
    ContactResult
        For a single pair: usable as a bool (``bool()`` raises
        :class:`~quadric_contact.errors.UndecidedError` if undecided), with
        the deciding result and the values it looked at.  For stacks: a
        numpy array.

    Raises
    ------
    NotAnEllipsoidError, ExcludedQuadricError, and the input errors of :class:`Quadric`.

    References
    ----------
    Theorem 2, Corollary 10, Remark 9, Theorem 14.

    Examples
    --------
    Example 11 (``Delta_4 = 0``, ``Delta_3 < 0``):

    >>> r = transversal_contact("2*x**2 + 2*y**2 + 3*z**2 - 1", "x**2 + y**2 + 8*z")
    >>> bool(r), r.decided_by
    (True, 'Remark 9')

    Example 17, the bee and the trunk (small, all roots real):

    >>> r = transversal_contact("(x-3)**2 + (y-3)**2 + 3*(z-5.5)**2 - 0.1", "x**2 + y**2 - 0.25*(z-3)**2 - 1")
    >>> bool(r), r.decided_by
    (False, 'Corollary 10')

    A flat ellipsoid pressed into the throat of a hyperboloid is not small:
    all roots are real, yet the surfaces cross (Remark 9); the geometric
    decision settles it.

    >>> disc, throat = "100*(x - 17/20)**2 + y**2 + z**2 - 1", "x**2 + y**2 - z**2/100 - 1"
    >>> transversal_contact(disc, throat, method="theory").decided
    False
    >>> r = transversal_contact(disc, throat)
    >>> bool(r), r.decided_by
    (True, 'geometric decision')
    """
    from .batch import is_stack

    if is_stack(E) or is_stack(Q) or mode not in ("certified", "exact"):
        from .batch import transversal_contact_batch

        return transversal_contact_batch(E, Q, mode=mode)
    P = characteristic_polynomial(E, Q)
    return decide_transversal(P, small=small, method=method)
