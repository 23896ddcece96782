"""Relative position R-/R+ (Theorem 13, Table 4; Theorem 14 for planes).

For a small ellipsoid not in transversal contact with ``Q`` (tangency
allowed), the signs of the roots of ``P`` tell where it is.  The table below
was *derived* (:func:`derive_root_sign_table`), the way Lemma 12 does: place
a small ellipsoid at one point of ``R-`` and one of ``R+`` of each standard
form of Table 1 and read off the root signs exactly; the pattern cannot
change inside a region because no root crosses 0 there (for the cylinders
and parallel planes the zero roots are structural).  A test re-derives it.

The patterns hold for ``Q`` with the sign of its standard form
(:attr:`Quadric.canonical_sign`); for ``-Q`` the roots change sign and
``R-``/``R+`` swap, which is how the caller's matrix is handled.  The patterns of
root signs (Table 4):

* ellipsoid, hyperboloid of two sheets, elliptic paraboloid: ``R-`` ``----``,
  ``R+`` ``--++``;
* hyperboloid of one sheet, hyperbolic paraboloid: ``R-`` ``---+``, ``R+`` ``-+++``;
* elliptic cylinder, parabolic cylinder: ``R-`` ``---0``, ``R+`` ``-0++``;
* hyperbolic cylinder: ``R-`` ``--0+``, ``R+`` ``0+++``;
* parallel planes; a plane (Theorem 14): ``R-`` ``--00``, ``R+`` ``00++``.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

from quadric_contact.exact.errors import ExcludedQuadricError
from quadric_contact.model.classification import NO_REAL_POINTS, TABLE_1_KINDS, QuadricKind
from quadric_contact.model.quadric import Quadric
from quadric_contact.theory.certificate import separation_certificate
from quadric_contact.theory.contact import _geometric, decide_transversal, refuse
from quadric_contact.theory.decision import PencilDecision
from quadric_contact.theory.pencil import CharacteristicPolynomial, characteristic_polynomial
from quadric_contact.theory.results import Region, RegionResult

__all__ = [
    "ROOT_SIGN_TABLE",
    "decide_region",
    "derive_root_sign_table",
    "region_patterns",
    "relative_position_exact",
]

K = QuadricKind
ROOT_SIGN_TABLE: dict[QuadricKind, dict[Region, str]] = {
    K.ELLIPSOID: {Region.R_MINUS: "----", Region.R_PLUS: "--++"},
    K.HYPERBOLOID_TWO_SHEETS: {Region.R_MINUS: "----", Region.R_PLUS: "--++"},
    K.ELLIPTIC_PARABOLOID: {Region.R_MINUS: "----", Region.R_PLUS: "--++"},
    K.HYPERBOLOID_ONE_SHEET: {Region.R_MINUS: "---+", Region.R_PLUS: "-+++"},
    K.HYPERBOLIC_PARABOLOID: {Region.R_MINUS: "---+", Region.R_PLUS: "-+++"},
    K.ELLIPTIC_CYLINDER: {Region.R_MINUS: "---0", Region.R_PLUS: "-0++"},
    K.PARABOLIC_CYLINDER: {Region.R_MINUS: "---0", Region.R_PLUS: "-0++"},
    K.HYPERBOLIC_CYLINDER: {Region.R_MINUS: "--0+", Region.R_PLUS: "0+++"},
    K.PARALLEL_PLANES: {Region.R_MINUS: "--00", Region.R_PLUS: "00++"},
    K.PLANE: {Region.R_MINUS: "--00", Region.R_PLUS: "00++"},
}
"""Root-sign pattern of ``det(lambda*E + s*Q)`` (``s`` the canonical sign) in each region."""

# Where to put a probe ellipsoid in each region of the standard forms used by
# derive_root_sign_table (parameters a=3, b=2, c=1): far from the surface.
_PROBES: dict[QuadricKind, tuple[tuple[int, ...], tuple[int, int, int], tuple[int, int, int]]] = {
    K.ELLIPSOID: ((3, 2, 1), (0, 0, 0), (10, 0, 0)),
    K.HYPERBOLOID_ONE_SHEET: ((3, 2, 1), (0, 0, 0), (10, 0, 0)),
    K.HYPERBOLOID_TWO_SHEETS: ((3, 2, 1), (0, 0, 10), (0, 0, 0)),
    K.ELLIPTIC_PARABOLOID: ((3, 2), (0, 0, 10), (0, 0, -10)),
    K.HYPERBOLIC_PARABOLOID: ((3, 2), (0, 0, 10), (0, 0, -10)),
    K.ELLIPTIC_CYLINDER: ((3, 2), (0, 0, 0), (10, 0, 0)),
    K.HYPERBOLIC_CYLINDER: ((3, 2), (0, 0, 0), (10, 0, 0)),
    K.PARABOLIC_CYLINDER: ((3,), (0, 0, 10), (0, 0, -10)),
    K.PARALLEL_PLANES: ((3,), (0, 0, 0), (10, 0, 0)),
}


def region_patterns(kind: QuadricKind, canonical_sign: int) -> dict[Region, str]:
    """The root-sign pattern of each region for ``Q`` of type ``kind`` given with the sign
    ``canonical_sign`` (:attr:`Quadric.canonical_sign`) of its standard form.

    For ``-Q_std`` the roots are negated and ``R-``/``R+`` swap.  Empty for a type
    without a row of Table 4.

    Examples
    --------
    >>> region_patterns(QuadricKind.HYPERBOLOID_ONE_SHEET, -1)
    {<Region.R_PLUS: 'R+'>: '-+++', <Region.R_MINUS: 'R-'>: '---+'}
    """
    expected = ROOT_SIGN_TABLE.get(kind, {})
    if canonical_sign > 0:
        return dict(expected)
    flip = str.maketrans("-+", "+-")
    return {r.swapped(): "".join(sorted(p.translate(flip), key="-0+".index)) for r, p in expected.items()}


def derive_root_sign_table(
    probe: Quadric | None = None,
) -> dict[QuadricKind, dict[Region, str]]:
    """Re-derive :data:`ROOT_SIGN_TABLE` by exact construction.

    A small ellipsoid (semi-axes 1/10, 1/20, 1/30, rotated by the quaternion
    (1, 2, 3, 4)) is centred at a point of ``R-`` and a point of ``R+`` of each
    standard form; the root signs are read off exactly, after checking that
    the probe is inside the region (sign of ``Q`` at the centre) and not in
    transversal contact (all roots real).

    Parameters
    ----------
    probe : Quadric, optional
        Another probe ellipsoid (centred at the origin), translated to the
        probe points instead of the default one.

    Returns
    -------
    dict
        ``QuadricKind -> {Region.R_MINUS: pattern, Region.R_PLUS: pattern}``.

    References
    ----------
    Lemma 12 (the argument), Theorem 13 and Table 4, Theorem 14 (planes).

    Examples
    --------
    >>> derive_root_sign_table() == ROOT_SIGN_TABLE
    True
    """
    table: dict[QuadricKind, dict[Region, str]] = {}
    for kind in TABLE_1_KINDS:
        params, p_minus, p_plus = _PROBES[kind]
        q = Quadric.standard(kind, **dict(zip("abc", params, strict=False)))
        row: dict[Region, str] = {}
        for region, point in ((Region.R_MINUS, p_minus), (Region.R_PLUS, p_plus)):
            e = (
                probe.translated(point)
                if probe is not None
                else Quadric.ellipsoid(
                    Fraction(1, 10), Fraction(1, 20), Fraction(1, 30), center=point, rotation=(1, 2, 3, 4)
                )
            )
            value = q.value_at(point)
            assert (value < 0) == (region is Region.R_MINUS), (kind, point)
            P = characteristic_polynomial(e, q)
            assert P.structure.all_real, (kind, point)
            row[region] = P.signs.pattern
        table[kind] = row
    plane = Quadric.plane((0, 0, 1), 0)
    row = {}
    for region, z in ((Region.R_MINUS, -1), (Region.R_PLUS, 1)):
        P = characteristic_polynomial(Quadric.sphere(Fraction(1, 2), (0, 0, z)), plane)
        row[region] = P.signs.pattern
    table[K.PLANE] = row
    return table


def decide_region(
    P: CharacteristicPolynomial, *, small: bool | None = None, method: str = "auto"
) -> RegionResult:
    """Decide the region from an already computed characteristic polynomial.

    See :func:`relative_position` (which calls it) for ``small`` and ``method``.

    Returns
    -------
    RegionResult
    """
    if method == "auto" and small is None:
        return _region_by_signatures(P)
    Q = P.Q
    kind = Q.kind
    refuse(Q)
    if kind in NO_REAL_POINTS:
        # X^T Q X keeps one sign on all of space: E lies on that side (tangency allowed).
        contact = decide_transversal(P, small=small, method=method)
        region = Region.R_PLUS if Q.canonical_sign > 0 else Region.R_MINUS
        return RegionResult(
            region,
            "no real points",
            f"Q is {kind.value}: X^T Q X is {'>=' if region is Region.R_PLUS else '<='} 0 on all of space",
            P,
            contact,
            {},
        )
    if kind not in ROOT_SIGN_TABLE and P.structure.all_real and method == "theory":
        raise ExcludedQuadricError(
            f"relative position needs Q of a type of Table 1 or a plane; Q is {kind.value}"
            + (f" ({kind.excluded_reason})" if kind.excluded_reason else ""),
            Q,
            kind=kind,
        )
    contact = decide_transversal(P, small=small, method=method)
    expected = {r.value: p for r, p in region_patterns(kind, Q.canonical_sign).items()}
    if contact.transversal:
        return RegionResult(Region.CONTACT, contact.decided_by, contact.reason, P, contact, expected)
    if contact.transversal is None:
        return RegionResult(None, None, contact.reason, P, contact, expected)
    if contact.geometric is not None:
        region = contact.geometric.region
        return RegionResult(region, contact.decided_by, contact.reason, P, contact, expected)
    if getattr(contact.smallness, "table_4_applies", True) is False:
        # E is small only in the enclosing sense (two ellipsoids, Q small w.r.t. E):
        # Corollary 10 holds but Theorem 13 / Table 4 do not (erratum table-1-ellipsoid-enclosing).
        why = (
            f"{contact.reason}; but E can enclose Q (it is small only because Q is small with respect "
            "to E), where Theorem 13 / Table 4 do not apply"
        )
        if method == "auto":
            cert = separation_certificate(P)
            if cert.decided:
                by = "separation certificate"
                return RegionResult(cert.region, by, f"{why}; {cert}", P, contact, expected)
            geo = _geometric(P.E, P.Q)
            return RegionResult(geo.region, "geometric decision", f"{why}; {geo}", P, contact, expected)
        return RegionResult(None, None, why, P, contact, expected)
    pattern = P.signs.pattern
    for region_value, p in expected.items():
        if p == pattern:
            by = "Theorem 14" if kind is K.PLANE else "Theorem 13 / Table 4"
            return RegionResult(
                Region(region_value),
                by,
                f"root signs {pattern} ({contact.decided_by}: no transversal contact)",
                P,
                contact,
                expected,
            )
    return RegionResult(
        None,
        None,
        f"root-sign pattern {pattern} matches no row of Table 4 for {kind.value} ({expected}); "
        "the smallness hypothesis must be failing",
        P,
        contact,
        expected,
    )


def _region_by_signatures(P: CharacteristicPolynomial) -> RegionResult:
    """The region from the table of :mod:`quadric_contact.theory.decision`: a definite member
    names it strictly, a crossing is ``contact``; a plane that touches ``E`` is on the side its
    root signs name (Theorem 14, for any ellipsoid), and a singular intersection is decided by
    the exact geometric decision."""
    contact = decide_transversal(P)
    Q = P.Q
    expected = {r.value: p for r, p in region_patterns(Q.kind, Q.canonical_sign).items()}
    d = contact.geometric
    if contact.transversal:
        return RegionResult(Region.CONTACT, contact.decided_by, contact.reason, P, contact, expected)
    if isinstance(d, PencilDecision):
        if d.region_value is not None:
            return RegionResult(d.region_value, d.decided_by, str(d), P, contact, expected)
        # a touching plane (Rule.PLANE_TOUCHING): Theorem 14 reads the side off the root signs
        pattern = P.signs.pattern
        for region_value, p in expected.items():
            if p == pattern:
                return RegionResult(
                    Region(region_value), "Theorem 14", f"{d}; root signs {pattern}", P, contact, expected
                )
        raise AssertionError(f"a touching plane with root signs {pattern} outside Theorem 14's rows")
    return RegionResult(d.region, contact.decided_by, contact.reason, P, contact, expected)


def relative_position_exact(
    E: Any, Q: Any, *, small: bool | None = None, method: str = "auto"
) -> RegionResult:
    """Where the ellipsoid ``E`` is with respect to ``Q``, decided exactly for one pair
    (the scalar path of the ``certified`` and ``exact`` modes of
    :func:`quadric_contact.relative_position`).

    Parameters
    ----------
    E, Q : Quadric, matrix-like or equation
    small : bool, optional
        Assert smallness instead of deciding it (Table 2).
    method : {"auto", "theory"}
        As for :func:`~quadric_contact.theory.contact.decide_transversal`.

    Returns
    -------
    RegionResult

    Raises
    ------
    NotAnEllipsoidError, ExcludedQuadricError

    References
    ----------
    Theorem 13 and Table 4 (root signs), Lemma 12, Theorem 14 (planes).

    Examples
    --------
    Lemma 12: a unit sphere and the hyperboloid of two sheets with
    ``a, b, c = 2, 3, 1``, centred between the sheets (``R+``, roots
    ``--++``) and touching the vertex from inside a sheet (``R-``, ``----``):

    >>> from quadric_contact import Quadric
    >>> H = Quadric.hyperboloid_two_sheets(2, 3, 1)
    >>> for centre in [(0, 0, 0), (0, 0, 2)]:
    ...     r = relative_position_exact(Quadric.sphere(1, center=centre), H)
    ...     print(centre, r.region, r.polynomial.signs.pattern)
    (0, 0, 0) R+ --++
    (0, 0, 2) R- ----
    """
    return decide_region(characteristic_polynomial(E, Q), small=small, method=method)
