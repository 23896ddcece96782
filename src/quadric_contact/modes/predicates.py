"""The public predicates: one question each, whatever the numbers and the input form.

Every predicate here answers the geometric question for every pair, small or not
(:mod:`quadric_contact.modes.decision.pipeline` says how); the number mode chooses the
arithmetic of each stage, never the question.  Each predicate is a
:class:`~quadric_contact.modes.dispatch.Question` (its exact scalar function, how its result
is built from a code and the :class:`~quadric_contact.modes.codes.Provenance` of the stage that
decided it) handed to one dispatcher, :func:`~quadric_contact.modes.dispatch.ask`, which
decides scalar or stack by the *type of the input*, never by the mode:

* a single pair (a :class:`~quadric_contact.Quadric`, an equation, a sympy
  expression, a ``(4, 4)`` array or nested list, a ``(4, 4)`` object array of
  Fractions) gives one result object in every mode, with its explanation at hand
  (:class:`~quadric_contact.ContactResult`, :class:`~quadric_contact.RegionResult`,
  :class:`~quadric_contact.PlaneSideResult`, :class:`~quadric_contact.ContactKind`,
  :class:`~quadric_contact.SmallnessReport`, :class:`~quadric_contact.OverlapResult`); in
  the ``certified`` and ``exact`` modes it is decided by the exact scalar path, in the
  others by the mode's stages on a stack of one (the exact characteristic polynomial is attached for audit);
* a stack (an array ``(..., 4, 4)``, a list or object array of matrices,
  Quadrics or equations, a dask array) gives an int8 array of codes
  (:class:`~quadric_contact.modes.ContactCode`, :class:`~quadric_contact.modes.RegionCode`,
  :class:`~quadric_contact.modes.ContactKindCode`,
  :class:`~quadric_contact.modes.SmallnessCode`, :class:`~quadric_contact.modes.OverlapCode`),
  broadcasting the batch shapes as
  numpy does; a stack of one gives an array of one.

:func:`corollary_10` is the one function that answers the paper's criterion rather
than the geometry (for teaching, and for callers who know their pairs are small).

Which stages decided is counted in the mode instance a caller passes (``mode.last``, the last
call to finish; ``mode.counts``, all calls): a convenience of the caller's own instance.  The
predicates read nothing back from it (one instance may serve several threads): each call of a
mode, :meth:`~quadric_contact.modes.NumberMode.decide`, returns its counts with its codes.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, overload

import numpy as np

from quadric_contact.exact.errors import NotAPlaneError
from quadric_contact.model.classification import QuadricKind
from quadric_contact.model.quadric import Quadric
from quadric_contact.modes.codes import (
    ContactCode,
    ContactKindCode,
    CriterionCode,
    OverlapCode,
    Provenance,
    RegionCode,
    SmallnessCode,
    Step,
)
from quadric_contact.modes.dispatch import Question, Single, ask, replace
from quadric_contact.modes.numbers.number_mode import NumberMode
from quadric_contact.theory.contact import transversal_contact_exact
from quadric_contact.theory.contact_kind import ContactKind, contact_kind_exact
from quadric_contact.theory.overlap import (
    OverlapResult,
    apply_touching,
    check_touching,
    overlap_exact,
    solid_of,
)
from quadric_contact.theory.pencil import CharacteristicPolynomial, as_quadric, characteristic_polynomial
from quadric_contact.theory.plane import plane_side_exact
from quadric_contact.theory.regions import relative_position_exact
from quadric_contact.theory.results import (
    ContactResult,
    PlaneSideResult,
    Region,
    RegionResult,
)
from quadric_contact.theory.smallness import SmallnessReport
from quadric_contact.theory.smallness import smallness as smallness_exact

__all__ = [
    "CriterionResult",
    "contact_kind",
    "corollary_10",
    "overlap",
    "plane_side",
    "relative_position",
    "smallness",
    "transversal_contact",
]

ScalarInput = Quadric | str

_BY_STEP = {Step.SEPARATION: "separation certificate", Step.NO_REAL_POINTS: "no real points"}


def _decided_by(
    provenance: Provenance | None, criterion: Callable[[], str], smallness: str = "Corollary 10"
) -> str:
    """The result of the paper (or of the package) the deciding stage stands for: ``criterion()``
    for the criterion step (which result depends on the question and the answer),
    ``smallness`` for the smallness step, and for the others what they are (an exact pair: its
    stage's name)."""
    if provenance is None:
        return "undecided"
    if provenance.step is Step.CRITERION:
        return criterion()
    if provenance.step is Step.SMALLNESS:
        return smallness
    return _BY_STEP.get(provenance.step, str(provenance))


# -- transversal contact ------------------------------------------------------------------------


def _contact(s: Single) -> ContactResult:
    """One pair's :class:`ContactResult` from the code of a mode's stages."""
    P = characteristic_polynomial(s.E, s.Q)
    c = ContactCode(s.code)
    if c is ContactCode.UNCERTAIN:
        return ContactResult(None, None, s.cannot_tell, P, mode=s.mode)
    # the criterion: non-real roots (Remark 9), or all roots real against a plane (Theorem 14)
    by = _decided_by(
        s.provenance,
        lambda: "Remark 9" if c.transversal or P.Q.kind is not QuadricKind.PLANE else "Theorem 14",
    )
    what = "transversal contact" if c.transversal else "no transversal contact"
    return ContactResult(c.transversal, by, f"{what}, {s.decided_in}", P, mode=s.mode)


_CONTACT = Question("contact", _contact, exact=transversal_contact_exact, exact_only=("small", "method"))


@overload
def transversal_contact(
    E: ScalarInput,
    Q: ScalarInput,
    *,
    small: bool | None = ...,
    method: str = ...,
    mode: str | NumberMode = ...,
    client: Any = ...,
    compute: bool = ...,
) -> ContactResult: ...


@overload
def transversal_contact(
    E: Any,
    Q: Any,
    *,
    small: bool | None = ...,
    method: str = ...,
    mode: str | NumberMode = ...,
    client: Any = ...,
    compute: bool = ...,
) -> ContactResult | np.ndarray: ...


def transversal_contact(
    E: Any,
    Q: Any,
    *,
    small: bool | None = None,
    method: str = "auto",
    mode: str | NumberMode = "certified",
    client: Any = None,
    compute: bool = True,
) -> Any:
    """Do the surfaces of the ellipsoid ``E`` and the quadric ``Q`` cross (transversal contact)?

    The geometric answer for every pair, small or not: Remark 9 (non-real roots of
    ``P``), Theorem 14 for planes, Corollary 10 where ``E`` is small, otherwise a
    decision that needs no smallness (the separation certificate on stacks, the exact
    geometric decision on the exact scalar path).

    Parameters
    ----------
    E : Quadric, equation, matrix-like; or a stack ``(..., 4, 4)``
        A real ellipsoid (either sign of its matrix).
    Q : Quadric, equation, matrix-like; or a stack ``(..., 4, 4)``
        Any quadric but a double plane or the zero matrix.
    small : bool, optional
        Single pair, ``certified``/``exact`` modes: assert that ``E`` is (or is not)
        small with respect to ``Q`` instead of deciding it (Table 2).
    method : {"auto", "theory"}
        Single pair, ``certified``/``exact`` modes: ``"theory"`` uses only the
        paper's results and reports undecided where they do not apply.
    mode : str or NumberMode
        ``"certified"`` (default, never wrong), ``"exact"``, ``"filter"``, ``"ball"``
        (may answer ``UNCERTAIN``), ``"float"``, ``"mpmath"`` (always answer; may be
        wrong near tangency), or an instance (to set options or read its stage counts:
        ``mode.last`` and ``mode.counts``, a convenience of the caller's own instance; when
        threads share one, ``last`` is whichever call finished last, and
        :meth:`NumberMode.decide <quadric_contact.modes.NumberMode.decide>` returns each
        call's counts with its codes).
    client, compute
        For dask input: the ``dask.distributed`` client, and whether to compute.

    Returns
    -------
    ContactResult for a single pair (usable as a bool; ``bool()`` raises
    :class:`~quadric_contact.exact.errors.UndecidedError` when undecided); for a stack an
    int8 array of :class:`~quadric_contact.modes.ContactCode`.

    Raises
    ------
    NotAnEllipsoidError, ExcludedQuadricError, ShapeError, NonFiniteError,
    NotSymmetricError, NotANumberError

    References
    ----------
    Theorem 2, Corollary 10, Remark 9, Theorem 14.

    Examples
    --------
    Example 11 (``Delta_4 = 0``, ``Delta_3 < 0``):

    >>> r = transversal_contact("2*x**2 + 2*y**2 + 3*z**2 - 1", "x**2 + y**2 + 8*z")
    >>> bool(r), r.decided_by
    (True, 'Remark 9')

    A flat ellipsoid pressed into the throat of a hyperboloid is not small: all roots
    are real, yet the surfaces cross.  Every mode and every input form says so:

    >>> disc, throat = "100*(x - 17/20)**2 + y**2 + z**2 - 1", "x**2 + y**2 - z**2/100 - 1"
    >>> [bool(transversal_contact(disc, throat, mode=m)) for m in ("certified", "exact", "filter", "float")]
    [True, True, True, True]
    >>> transversal_contact([disc, disc], throat)
    array([1, 1], dtype=int8)
    """
    return ask(_CONTACT, E, Q, mode, client, compute, small=small, method=method)


# -- relative position ---------------------------------------------------------------------------


def _region(s: Single) -> RegionResult:
    """One pair's :class:`RegionResult` from the code of a mode's stages."""
    P = characteristic_polynomial(s.E, s.Q)
    region = RegionCode(s.code).region
    if region is None:
        return RegionResult(None, None, s.cannot_tell, P, None, mode=s.mode)
    by = _decided_by(
        s.provenance,
        lambda: "Remark 9" if region is Region.CONTACT else "Theorem 14",
        smallness="Theorem 13 / Table 4",
    )
    return RegionResult(region, by, f"{region.value}, {s.decided_in}", P, None, mode=s.mode)


_REGION = Question("region", _region, exact=relative_position_exact, exact_only=("small", "method"))


@overload
def relative_position(
    E: ScalarInput,
    Q: ScalarInput,
    *,
    small: bool | None = ...,
    method: str = ...,
    mode: str | NumberMode = ...,
    client: Any = ...,
    compute: bool = ...,
) -> RegionResult: ...


@overload
def relative_position(
    E: Any,
    Q: Any,
    *,
    small: bool | None = ...,
    method: str = ...,
    mode: str | NumberMode = ...,
    client: Any = ...,
    compute: bool = ...,
) -> RegionResult | np.ndarray: ...


def relative_position(
    E: Any,
    Q: Any,
    *,
    small: bool | None = None,
    method: str = "auto",
    mode: str | NumberMode = "certified",
    client: Any = None,
    compute: bool = True,
) -> Any:
    """Where is the surface of the ellipsoid ``E`` with respect to ``Q``: ``R-``, ``R+``, or crossing it?

    ``R- = {X^T Q X <= 0}`` and ``R+ = {X^T Q X >= 0}`` for the matrix as given
    (eq. (8)); tangency counts as being in a region; ``contact`` means the surfaces
    cross.  The geometric answer for every pair: Theorem 13 / Table 4 where ``E`` is
    small, Theorem 14 for planes, otherwise a decision that needs no smallness.  A
    quadric without a real surface has ``X^T Q X`` of one sign everywhere: ``E`` is on
    that side.

    Parameters
    ----------
    E, Q, small, method, mode, client, compute
        As for :func:`transversal_contact`.

    Returns
    -------
    RegionResult for a single pair (compares equal to its :class:`Region`); for a
    stack an int8 array of :class:`~quadric_contact.modes.RegionCode` (``-1`` ``R-``,
    ``0`` contact, ``1`` ``R+``, ``2`` uncertain).

    Raises
    ------
    NotAnEllipsoidError, ExcludedQuadricError, and the input errors.

    References
    ----------
    Theorem 13 and Table 4 (root signs), Lemma 12, Theorem 14 (planes).

    Examples
    --------
    Example 17: the bee is outside the hyperboloid S2 (``R+``), on a single pair or a
    stack, in every mode:

    >>> bee = "(x-3)**2 + (y-3)**2 + 3*(z-5.5)**2 - 0.1"
    >>> S2 = "x**2 + y**2 - 0.25*(z-3)**2 - 1"
    >>> r = relative_position(bee, S2)
    >>> r.region, r.decided_by, r.polynomial.signs.pattern
    (<Region.R_PLUS: 'R+'>, 'signature sequence', '-+++')
    >>> relative_position(bee, S2, method="theory").decided_by     # the paper's route agrees
    'Theorem 13 / Table 4'
    >>> relative_position(bee, S2, mode="float").region, relative_position([bee], S2)
    (<Region.R_PLUS: 'R+'>, array([1], dtype=int8))
    """
    return ask(_REGION, E, Q, mode, client, compute, small=small, method=method)


# -- a plane -------------------------------------------------------------------------------------


def _a_plane(E: Any, P: Any) -> tuple[Any, Any, Any]:
    """``E`` and the plane ``P`` (:class:`NotAPlaneError` if it is not one)."""
    plane = as_quadric(P, "P")
    if plane.kind is not QuadricKind.PLANE:
        raise NotAPlaneError(f"expected a plane, got {plane.kind.value}", plane, kind=plane.kind)
    return E, plane, None


def _plane_side(s: Single) -> PlaneSideResult:
    """One pair's :class:`PlaneSideResult` from the region code of a mode's stages."""
    poly = characteristic_polynomial(s.E, s.Q)
    c0, c1, c2, c3, c4 = poly.coefficients
    center = poly.E.center()
    assert center is not None
    zone = RegionCode(s.code).region
    return PlaneSideResult(
        zone,
        None,
        None if zone is None else "Corollary 15",
        s.cannot_tell if zone is None else s.decided_in,
        poly,
        c2,
        c3,
        c4,
        s.Q.value_at(center),
        mode=s.mode,
    )


_PLANE = Question("plane", _plane_side, exact=plane_side_exact, prepare=_a_plane)


def plane_side(
    E: Any, P: Any, *, mode: str | NumberMode = "certified", client: Any = None, compute: bool = True
) -> Any:
    """Which side of the plane ``P`` is the ellipsoid ``E`` on, or does it cross it (any ellipsoid)?

    Parameters
    ----------
    E : Quadric, equation, matrix-like; or a stack
        A real ellipsoid (either sign).
    P : Quadric, equation, matrix-like; or a stack
        Planes (matrices with zero quadratic part); ``R-`` is ``X^T P X <= 0``.
    mode, client, compute
        As for :func:`transversal_contact`.

    Returns
    -------
    PlaneSideResult for a single pair (``.zone`` ``R-`` = Algorithm 1's Zone 2, ``R+``
    = Zone 1, ``contact`` = Zone 0; ``.tangent``); for a stack an int8 array of
    :class:`~quadric_contact.modes.RegionCode`.

    Raises
    ------
    NotAPlaneError
        If a ``P`` is not a plane.
    NotAnEllipsoidError
        If an ``E`` is not a real ellipsoid.

    References
    ----------
    Theorem 14, Corollary 15, Remark 16, Algorithm 1.

    Examples
    --------
    Example 17, the bee against the plane ``z = 6``: ``c3 = -3/2 < 0``, Zone 2.

    >>> r = plane_side("(x-3)**2 + (y-3)**2 + 3*(z-5.5)**2 - 0.1", "z - 6")
    >>> r.zone, r.algorithm_1_zone, r.c3
    (<Region.R_MINUS: 'R-'>, 2, Fraction(-3, 2))
    >>> plane_side(["(x-3)**2 + (y-3)**2 + 3*(z-5.5)**2 - 0.1"], ["z - 6", "z - 5.5", "z - 5"])
    array([-1,  0,  1], dtype=int8)
    """
    return ask(_PLANE, E, P, mode, client, compute)


# -- the kind of contact -------------------------------------------------------------------------


_KIND = Question(
    "kind",
    lambda s: ContactKindCode(s.code).to_kind(),
    exact=contact_kind_exact,
    exact_only=("small",),
    relabel=False,  # a ContactKind names no mode
)


@overload
def contact_kind(
    E: ScalarInput,
    Q: ScalarInput,
    *,
    small: bool | None = ...,
    mode: str | NumberMode = ...,
    client: Any = ...,
    compute: bool = ...,
) -> ContactKind: ...


@overload
def contact_kind(
    E: Any,
    Q: Any,
    *,
    small: bool | None = ...,
    mode: str | NumberMode = ...,
    client: Any = ...,
    compute: bool = ...,
) -> ContactKind | np.ndarray: ...


def contact_kind(
    E: Any,
    Q: Any,
    *,
    small: bool | None = None,
    mode: str | NumberMode = "certified",
    client: Any = None,
    compute: bool = True,
) -> Any:
    """How the surfaces of ``E`` and ``Q`` meet: a row of Table 3.

    :func:`~quadric_contact.theory.contact_kind.analyze_contact` gives the evidence (the
    singular members of the pencil, the tangent points) for a single pair.

    Parameters
    ----------
    E, Q, small, mode, client, compute
        As for :func:`transversal_contact`.

    Returns
    -------
    ContactKind for a single pair (``UNCERTAIN`` only from the abstaining modes); for a
    stack an int8 array of :class:`~quadric_contact.modes.ContactKindCode`.

    References
    ----------
    Table 3, proof of Theorem 2.

    Examples
    --------
    A unit sphere inside a circular one-sheet hyperboloid, touching its throat, and
    Example 11:

    >>> contact_kind("x**2 + y**2 + z**2 - 1", "x**2 + y**2 - z**2/4 - 1")
    <ContactKind.TANGENT_CURVE: 'tangent_curve'>
    >>> contact_kind(["2*x**2 + 2*y**2 + 3*z**2 - 1"], "x**2 + y**2 + 8*z")
    array([1], dtype=int8)
    """
    return ask(_KIND, E, Q, mode, client, compute, small=small)


# -- do the solids overlap? ----------------------------------------------------------------------


def _with_solid(E: Any, Q: Any) -> tuple[Any, Any, Any]:
    """The pair as given, and ``Q`` with the sign of its solid (refusing a type without one)."""
    return E, Q, solid_of(Q)


def _overlap(s: Single) -> OverlapResult:
    """One pair's :class:`OverlapResult` from the code of a mode's stages, read by the
    ``touching`` convention."""
    q = s.held
    P = characteristic_polynomial(s.E, q)
    raw = OverlapCode(s.code)
    if raw is OverlapCode.UNCERTAIN:
        return OverlapResult(raw, None, None, s.cannot_tell, P, mode=s.mode)
    # the criterion: non-real roots (Remark 9), a plane's side (Theorem 14), two ellipsoids'
    # positive roots (Wang-Wang-Kim)
    by = _decided_by(
        s.provenance,
        lambda: (
            "Remark 9"
            if not P.structure.all_real
            else ("Theorem 14" if q.kind is QuadricKind.PLANE else "Wang-Wang-Kim")
        ),
    )
    result = OverlapResult(
        raw, raw is OverlapCode.TOUCHING, by, f"{raw.name.lower()}, {s.decided_in}", P, mode=s.mode
    )
    touching = s.options["touching"]
    target = check_touching(touching)
    if result.touching and target is not None:
        return replace(result, code=target, convention=touching)
    return result if touching is None else replace(result, convention=touching)


_OVERLAP = Question(
    "overlap",
    _overlap,
    exact=overlap_exact,
    prepare=_with_solid,
    validate=check_touching,
    stack=apply_touching,
)


@overload
def overlap(
    E: ScalarInput,
    Q: ScalarInput,
    *,
    touching: str | None = ...,
    mode: str | NumberMode = ...,
    client: Any = ...,
    compute: bool = ...,
) -> OverlapResult: ...


@overload
def overlap(
    E: Any,
    Q: Any,
    *,
    touching: str | None = ...,
    mode: str | NumberMode = ...,
    client: Any = ...,
    compute: bool = ...,
) -> OverlapResult | np.ndarray: ...


def overlap(
    E: Any,
    Q: Any,
    *,
    touching: str | None = None,
    mode: str | NumberMode = "certified",
    client: Any = None,
    compute: bool = True,
) -> Any:
    """Do the solids of the ellipsoid ``E`` and of the quadric ``Q`` overlap?

    The solid of ``E`` is its inside; the solid of ``Q`` is its region ``R-`` for the sign
    of its standard form (Table 1): the inside of an ellipsoid, of a cylinder, of a
    one-sheet hyperboloid's tube or of a paraboloid, the two cups of a two-sheet
    hyperboloid, the slab between parallel planes, the region between the sheets of a
    hyperbolic cylinder; for a plane and a hyperbolic paraboloid (two congruent sides) the
    side ``X^T Q X <= 0`` of the matrix as given (``n . x <= d`` for ``n . x - d``).  See
    :mod:`quadric_contact.theory.overlap`.

    Parameters
    ----------
    E : Quadric, equation, matrix-like; or a stack ``(..., 4, 4)``
        A real ellipsoid (either sign of its matrix).
    Q : Quadric, equation, matrix-like; or a stack ``(..., 4, 4)``
        A quadric of Table 1 or a plane (either sign of its matrix but for a plane and a
        hyperbolic paraboloid, whose sign picks the side).
    touching : {None, "separate", "no-overlap", "overlap"}
        How to read a touch: reported as ``TOUCHING`` (default); ``"separate"`` (synonym
        ``"no-overlap"``), no overlap (HOOMD-blue's ellipsoid test, FCL's libccd solver);
        ``"overlap"``, an overlap (FCL's GJK solver).  Applied after the decision, in every
        mode and input form.
    mode, client, compute
        As for :func:`transversal_contact`.

    Returns
    -------
    OverlapResult for a single pair (usable as a bool, which raises for ``TOUCHING`` without
    a convention and for ``UNCERTAIN``); for a stack an int8 array of
    :class:`~quadric_contact.modes.OverlapCode` (``0`` separate, ``1`` overlapping, ``2``
    uncertain, ``3`` touching).

    Raises
    ------
    NotAnEllipsoidError, ExcludedQuadricError (cones, intersecting or coincident planes,
    imaginary quadrics), and the input errors.

    References
    ----------
    Wang, Wang and Kim (2001), for two ellipsoids; the separation certificate, Theorems 13
    and 14, Remark 9 for the others.

    Examples
    --------
    HOOMD-blue's unit test: ellipsoids with semi-axes ``(3, 1, 2)`` and ``(2, 3, 1)``, the
    second moved along ``x``; a touch read the HOOMD way in one call:

    >>> a = "x**2/9 + y**2 + z**2/4 - 1"
    >>> b = ["(x - 4.9)**2/4 + y**2/9 + z**2 - 1", "(x - 5)**2/4 + y**2/9 + z**2 - 1",
    ...      "(x - 5.1)**2/4 + y**2/9 + z**2 - 1"]
    >>> overlap(a, b)
    array([1, 3, 0], dtype=int8)
    >>> overlap(a, b, touching="no-overlap"), overlap(a, b, touching="overlap")
    (array([1, 0, 0], dtype=int8), array([1, 1, 0], dtype=int8))
    >>> r = overlap(a, b[1])
    >>> r.code, r.decided_by, r.tangent_points
    (<OverlapCode.TOUCHING: 3>, 'Wang-Wang-Kim', ((3, 0, 0),))
    """
    return ask(_OVERLAP, E, Q, mode, client, compute, touching=touching)


# -- smallness -----------------------------------------------------------------------------------


def _ellipsoid_and_table_1(E: Any, Q: Any) -> tuple[Any, Any, Any]:
    """``E`` as an ellipsoid and ``Q`` of a type of Table 1 (refused otherwise, with the reason)."""
    q = as_quadric(Q, "Q")
    e = as_quadric(E, "E").as_ellipsoid()
    if not q.kind.in_table_1:
        smallness_exact(e, q)  # raises ExcludedQuadricError with the reason
    return e, q, None


def _smallness(s: Single) -> SmallnessReport:
    """One pair's :class:`SmallnessReport` from the code of a mode's stages (no conditions)."""
    sc = SmallnessCode(s.code)
    return SmallnessReport(sc.small, s.Q.kind, (), (), None, sc is SmallnessCode.SMALL, {}, mode=s.mode)


_SMALLNESS = Question("smallness", _smallness, exact=smallness_exact, prepare=_ellipsoid_and_table_1)


@overload
def smallness(
    E: ScalarInput, Q: ScalarInput, *, mode: str | NumberMode = ..., client: Any = ..., compute: bool = ...
) -> SmallnessReport: ...


@overload
def smallness(
    E: Any, Q: Any, *, mode: str | NumberMode = ..., client: Any = ..., compute: bool = ...
) -> SmallnessReport | np.ndarray: ...


def smallness(
    E: Any, Q: Any, *, mode: str | NumberMode = "certified", client: Any = None, compute: bool = True
) -> Any:
    """Is the ellipsoid ``E`` small with respect to the quadric ``Q`` (Definition 1)?

    Tables 1 and 2, corrected (see :mod:`quadric_contact.theory.smallness`).

    Parameters
    ----------
    E, Q, mode, client, compute
        As for :func:`transversal_contact`; ``Q`` of a type of Table 1 (for a single
        pair; a stack gives ``EXCLUDED`` for the others).

    Returns
    -------
    SmallnessReport for a single pair (every condition with both sides, exact, in the
    ``certified`` and ``exact`` modes); for a stack an int8 array of
    :class:`~quadric_contact.modes.SmallnessCode`.

    Raises
    ------
    NotAnEllipsoidError, ExcludedQuadricError (single pair, ``Q`` without a row of Table 1)

    References
    ----------
    Definition 1, Lemma 4, Theorem 5, Tables 1 and 2.

    Examples
    --------
    Example 17: the bee is small with respect to both pieces of the tree.

    >>> bee = "(x-3)**2 + (y-3)**2 + 3*(z-5.5)**2 - 0.1"
    >>> smallness(bee, "x**2 + y**2 - 0.25*(z-3)**2 - 1").small
    True
    """
    return ask(_SMALLNESS, E, Q, mode, client, compute)


# -- the raw criterion ---------------------------------------------------------------------------


class CriterionResult:
    """The paper's raw criterion for one pair (:func:`corollary_10`).

    Attributes
    ----------
    code : CriterionCode
    polynomial : CharacteristicPolynomial
    mode : str
    """

    def __init__(self, code: CriterionCode, polynomial: CharacteristicPolynomial, mode: str) -> None:
        self.code = code
        self.polynomial = polynomial
        self.mode = mode

    @property
    def non_real(self) -> bool | None:
        """``P`` has a pair of non-real roots (None when the mode cannot tell)."""
        return None if self.code is CriterionCode.UNCERTAIN else self.code is CriterionCode.NON_REAL

    @property
    def delta3(self) -> Any:
        return self.polynomial.deltas()[1]

    @property
    def delta4(self) -> Any:
        return self.polynomial.deltas()[2]

    def __repr__(self) -> str:
        return f"CriterionResult({self.code.name}, mode={self.mode!r})"


_CRITERION = Question(  # no exact path: the criterion is the mode's, in every mode
    "criterion",
    lambda s: CriterionResult(CriterionCode(s.code), characteristic_polynomial(s.E, s.Q), s.mode),
)


def corollary_10(
    E: Any, Q: Any, *, mode: str | NumberMode = "certified", client: Any = None, compute: bool = True
) -> Any:
    """The paper's criterion alone: does ``P(lambda) = det(lambda E + Q)`` have non-real roots?

    Corollary 10 (``Delta_4 < 0``, or ``Delta_4 = 0`` and ``Delta_3 < 0``; the package
    reads the complete discrimination system, which also covers degenerate pencils)
    with Remark 9: ``NON_REAL`` means transversal contact for any pair; ``ALL_REAL``
    means no transversal contact **only when ``E`` is small with respect to ``Q``**
    (Theorem 2) or ``Q`` is a plane (Theorem 14).  This is the one function that answers
    the criterion rather than the geometry: for teaching, and for callers who know
    their pairs are small.  :func:`transversal_contact` answers the geometry.

    Parameters
    ----------
    E, Q, mode, client, compute
        As for :func:`transversal_contact`.

    Returns
    -------
    CriterionResult for a single pair; for a stack an int8 array of
    :class:`~quadric_contact.modes.CriterionCode` (``0`` all real, ``1`` non-real,
    ``2`` uncertain).

    References
    ----------
    Corollary 10, Remark 9, Theorem 2, Theorem 14.

    Examples
    --------
    The flat disc in the hyperboloid's throat crosses it in two curves although all
    roots are real: the criterion says ``ALL_REAL`` (it assumes smallness, which fails),
    the geometry says contact.

    >>> disc, throat = "100*(x - 17/20)**2 + y**2 + z**2 - 1", "x**2 + y**2 - z**2/100 - 1"
    >>> corollary_10(disc, throat).code, bool(transversal_contact(disc, throat))
    (<CriterionCode.ALL_REAL: 0>, True)
    """
    return ask(_CRITERION, E, Q, mode, client, compute)
