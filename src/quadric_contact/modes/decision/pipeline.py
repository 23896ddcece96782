"""The complete decision on stacks: one meaning, whatever the numbers.

Every array predicate answers the *geometric* question for every pair (do the
surfaces cross? on which side of ``Q`` is ``E``? how do they touch?), small or
not.  The paper's criterion is the fast way to the answer where it applies, not
the answer itself.  A number mode supplies the arithmetic of each step; the
steps and the order in which they hand pairs on are written once, here:

1. **criterion** (:meth:`~quadric_contact.modes.numbers.number_mode.NumberMode.criterion_contact`):
   the pencil's root structure.  Non-real roots mean transversal contact for any
   pair (Remark 9); for a plane all roots real means no transversal contact
   (Theorem 14) and the side comes from Corollary 15; a quadric without a real
   surface (an imaginary quadric, a point, a line) is never crossed and ``X^T Q X``
   has one sign on all of space.  For two ellipsoids with all roots real, the root signs
   (Wang-Wang-Kim, for every pair) settle ``E`` outside ``Q`` or touching it from outside:
   two positive roots mean no crossing and ``E`` in the closed ``R+`` of ``Q``'s canonical
   sign.  For the contact and the region questions the first stage of a cascade reads the
   region of every pair in the same pass as the contact code (its kernels compute both
   together); the rest of the cascade decides the contact code where that reading is unsure,
   and only the first stage's reading settles a side here (a plane's, or an ellipsoid's
   ``R+``): a later stage's reading of the coefficients' signs would be exact arithmetic on
   pairs that the separation step settles in binary64.  This is most pairs of an environment and of
   ellipsoids of similar sizes.
   In the plain modes a crossing read from non-real roots that the certified filter cannot
   confirm goes on to step 2 (a symmetric placement's multiple root looks non-real after
   rounding; step 2 finds its definite member if it has one).
2. **separation** (:mod:`quadric_contact.modes.decision.separation`): the pencil's signature sequence,
   looked up in the decision table (:mod:`quadric_contact.theory.decision`): a definite member
   proves strict separation, four simple real roots without one prove a crossing; no smallness
   and no type of ``Q`` needed.
3. **exact pair**: what no earlier step settled (tangencies, multiple roots) is
   decided by the exact scalar predicates, pair by pair (the same table, with exact facts,
   then the exact geometric decision for a singular intersection), in the modes that always
   decide exactly (``certified``, ``exact``).  The modes that abstain (``filter``,
   ``ball``) answer ``UNCERTAIN`` there; the plain ones (``float``, ``mpmath``)
   have answered everything at step 2.

Smallness (Definition 1, Tables 1-2) is not a step: the decision does not need it.  It stays a
public report (:func:`quadric_contact.smallness`) and, with Corollary 10, a cross-check.

The question "do the solids overlap?" (:func:`decide_overlap`) uses the same steps: the
criterion (non-real roots: the surfaces cross; a plane's side by Theorem 14; for two
ellipsoids the Wang-Wang-Kim reading of the root signs, valid for every pair), the
separation certificate, and the exact pair (:func:`quadric_contact.theory.overlap.overlap_exact`).

Every step is counted in a :class:`~quadric_contact.modes.codes.StageCounts` that
:func:`decide` and :func:`decide_overlap` return with the codes, under the
:class:`~quadric_contact.modes.codes.Provenance` of the step (a
:class:`~quadric_contact.modes.codes.Step` and the numbers it ran in), named
``"<step> (<numbers>)"``, e.g. ``"criterion (filter)"``, ``"separation (exact)"``,
``"exact pair"``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from quadric_contact.exact.errors import ExcludedQuadricError
from quadric_contact.model.classification import (
    NO_REAL_POINTS,
    REFUSED_KINDS,
    TABLE_1_KINDS,
    QuadricKind,
)
from quadric_contact.modes.codes import (
    UNCERTAIN,
    ContactCode,
    ContactKindCode,
    OverlapCode,
    Provenance,
    RegionCode,
    StageCounts,
    StageMethod,
    Step,
)
from quadric_contact.modes.decision.answers import KINDS, UNCERTAIN_ROW, rows_from_masks
from quadric_contact.modes.decision.separation import CROSSING, SEP_MINUS, SEP_PLUS
from quadric_contact.modes.kernels.decision import CODE_RANGES
from quadric_contact.modes.kernels.range import rows_in_range
from quadric_contact.modes.stacks.integers import integer_rows
from quadric_contact.modes.stacks.pairs import Pairs
from quadric_contact.modes.stacks.rows import unique_rows
from quadric_contact.modes.stacks.validation import exact_matrix
from quadric_contact.theory.contact import transversal_contact_exact
from quadric_contact.theory.contact_kind import analyze_contact
from quadric_contact.theory.overlap import overlap_exact, solid_of
from quadric_contact.theory.regions import relative_position_exact

if TYPE_CHECKING:
    from quadric_contact.modes.numbers.number_mode import NumberMode

__all__ = ["QUESTIONS", "decide", "decide_overlap"]


QUESTIONS = ("contact", "region", "kind")

_CLASS_TABLE, _CLASS_PLANE, _CLASS_NO_SURFACE, _CLASS_OTHER, _CLASS_UNCERTAIN = 0, 1, 2, 3, 4


def _class_of_kind(kind: QuadricKind) -> int:
    if kind in TABLE_1_KINDS:
        return _CLASS_TABLE
    if kind is QuadricKind.PLANE:
        return _CLASS_PLANE
    if kind in NO_REAL_POINTS:
        return _CLASS_NO_SURFACE
    return _CLASS_OTHER


# Per row of decisions.ROWS: the class, the canonical sign, whether the type is refused.
_ROW_CLASS = np.array([_class_of_kind(k) for k in KINDS for _ in (1, -1)] + [_CLASS_UNCERTAIN], dtype=np.int8)
_ROW_SIGN = np.array([s for _ in KINDS for s in (1, -1)] + [0], dtype=np.int8)
_ROW_ELLIPSOID = np.array([k is QuadricKind.ELLIPSOID for k in KINDS for _ in (1, -1)] + [False], dtype=bool)
_ROW_REFUSED = np.array([k in REFUSED_KINDS for k in KINDS for _ in (1, -1)] + [False], dtype=bool)
_ROW_PLANE = np.array([k is QuadricKind.PLANE for k in KINDS for _ in (1, -1)] + [False], dtype=bool)
_ROW_CHECK_SOLID = np.array(
    [k not in TABLE_1_KINDS and k is not QuadricKind.PLANE for k in KINDS for _ in (1, -1)] + [False],
    dtype=bool,
)


def _classes(mode: NumberMode, pairs: Pairs) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per pair: the class of ``Q`` (Table 1 type, plane, no real points, other, uncertain),
    its canonical sign (+1/-1; 0 when uncertain) and whether it is an ellipsoid.  Raises for a
    refused type."""
    used, where = _q_used(pairs)
    rows = rows_from_masks(mode.classify(pairs.Q, used)).astype(np.intp)
    klass = _ROW_CLASS[rows]
    sign = _ROW_SIGN[rows]
    ellipsoid = _ROW_ELLIPSOID[rows]
    suspect = np.flatnonzero(_ROW_REFUSED[rows] | (rows == UNCERTAIN_ROW))
    for k in suspect:
        # Refusing input is not the mode's business: where the mode cannot rule a refused
        # type out, the exact type decides (once per quadric).

        q = exact_matrix(pairs.Q, int(used[k]))
        kind = q.kind
        if kind not in REFUSED_KINDS:
            continue  # leave it as the mode says (uncertain)
        raise ExcludedQuadricError(
            f"{pairs.Q.where(int(used[k]))} is {kind.value}: "
            + (
                "a plane counted twice; pass the plane itself"
                if kind is QuadricKind.COINCIDENT_PLANES
                else "the zero matrix is not a surface"
            ),
            q,
            kind=kind,
            index=int(used[k]),
        )
    if where is None:
        if used.size == pairs.n:
            return klass, sign, ellipsoid
        return tuple(np.broadcast_to(a, (pairs.n,)) for a in (klass, sign, ellipsoid))  # type: ignore[return-value]
    where = np.asarray(where).reshape(-1)
    return klass[where], sign[where], ellipsoid[where]


def _q_used(pairs: Pairs) -> tuple[np.ndarray, np.ndarray | None]:
    """The distinct quadrics the pairs use and where each pair finds its own among them
    (None: pair ``p`` uses the ``p``-th, or all use the one quadric)."""
    if pairs.q_index is None:
        m = len(pairs.Q)
        return (np.arange(m, dtype=np.intp) if m == pairs.n else np.zeros(1, dtype=np.intp)), None
    return unique_rows(pairs.q_index, len(pairs.Q), return_inverse=True)


def _blend(out: np.ndarray, which: np.ndarray, values: Any) -> None:
    """``out[which] = values`` (int8 codes; ``values`` a scalar or one per entry of ``out``) by
    arithmetic, ``out += which * (values - out)``: numpy's masked assignment and ``copyto(...,
    where=)`` are not vectorised (about 1 ms per 1e6 entries, this about a tenth of that)."""
    if isinstance(values, (int, np.integer)):
        delta = np.subtract(np.int8(int(values)), out)
    else:
        delta = np.subtract(np.asarray(values, dtype=np.int8), out)
    np.multiply(delta, which.view(np.int8), out=delta)
    np.add(out, delta, out=out)


def _is(values: np.ndarray, value: int) -> np.ndarray | bool:
    """``values == value``; the Python ``False`` when no entry can be (``values`` one entry
    broadcast: a single quadric), the Python ``True`` when every entry is."""
    if values.ndim == 1 and values.size and values.strides[0] == 0:
        return bool(values[0] == value)
    return values == value


def _deciding_stages(which: np.ndarray, m: int) -> set[int]:
    """The stages (of ``m``) that decided at least one entry (``which``: index or -1)."""
    if m == 1:
        return {0} if bool((which == 0).any()) else set()
    seen = np.bincount(which.astype(np.intp) + 1, minlength=m + 1)
    return {k for k in range(m) if seen[k + 1]}


def _staged(mode: NumberMode, method: StageMethod, pairs: Pairs) -> tuple[np.ndarray, list[str], np.ndarray]:
    return mode.staged(method, pairs)


def _remember(mode: NumberMode, start: bool) -> None:
    """Let the mode (and its cascade) remember facts about this call's stacks (``start``), or
    drop them (at the end of the call)."""
    for m in (mode, *getattr(mode, "stages", ())):
        method = getattr(m, "remember" if start else "forget", None)
        if method is not None:
            method()


def decide(mode: NumberMode, pairs: Pairs, question: str) -> tuple[np.ndarray, StageCounts]:
    """Codes answering ``question`` (``"contact"``, ``"region"`` or ``"kind"``) for every pair.

    Returns :class:`ContactCode`, :class:`RegionCode` or :class:`ContactKindCode`
    values (int8), and the counts of the steps that settled them."""
    _remember(mode, True)
    try:
        return _decide(mode, pairs, question)
    finally:
        _remember(mode, False)


def _decide(mode: NumberMode, pairs: Pairs, question: str) -> tuple[np.ndarray, StageCounts]:
    """:func:`decide`: the pairs of two ellipsoids in one pass (:func:`_lane`), the others, and
    what the lane leaves, step by step (:func:`_decide_steps`)."""
    if question not in QUESTIONS:
        raise ValueError(f"question must be one of {QUESTIONS}, got {question!r}")
    counts = StageCounts()
    if pairs.n == 0:
        return np.full(0, UNCERTAIN, dtype=np.int8), counts
    lane = _lane(mode, pairs, question, counts)
    if lane is None:
        out = _decide_steps(mode, pairs, question, counts)
    else:
        out, rest = lane
        if rest.size:
            out[rest] = _decide_steps(mode, pairs.take(rest), question, counts)
    return out, counts


_OUTSIDE = Provenance(Step.EXACT_PAIR, "outside binary64's range")
_NO_REAL_POINTS = Provenance(Step.NO_REAL_POINTS, "type")
_EXACT_PAIR = Provenance(Step.EXACT_PAIR)


def _outside_range(mode: NumberMode, pairs: Pairs) -> np.ndarray:
    """For a plain mode: the pairs with a non-zero entry outside ``[INPUT_MIN, INPUT_MAX]``
    (:func:`~quadric_contact.modes.kernels.range.rows_in_range`), where the binary64 programs of
    the criterion and the separation can overflow or underflow and read signs of nothing (a
    matrix scaled by ``1e78``, the same quadric, read as a crossing), or an exact entry binary64
    cannot hold (rounded to inf by :func:`~quadric_contact.modes.stacks.batch._round`): the steps decide
    them exactly.  A certified mode's filters leave such pairs by the same guard: none here."""
    if mode.certified or pairs.n == 0:
        return np.zeros(0, dtype=np.intp)
    bad = np.zeros(pairs.n, dtype=bool)
    for stack, rows in ((pairs.E, pairs.e_rows()), (pairs.Q, pairs.q_rows())):
        used, back = unique_rows(rows, len(stack), return_inverse=True)
        whole = stack.packed is None and 2 * len(used) >= len(stack)  # no copy of the rows used
        inside = rows_in_range(stack.floats)[used] if whole else rows_in_range(stack.rows_floats(used))
        bad |= ~inside[back]
    return np.flatnonzero(bad)


def _lane(
    mode: NumberMode, pairs: Pairs, question: str, counts: StageCounts
) -> tuple[np.ndarray, np.ndarray] | None:
    """Steps 1 and 2 for the pairs of two ellipsoids, in one pass over the input: the decision
    kernel (:mod:`quadric_contact.modes.kernels.decision`) reads the criterion and, where it
    does not settle the pair, the signature sequence; the answers follow from its codes by the
    rules of the steps, read through :func:`_lane_table` (the overlap question's own rules for
    ``question="overlap"``).  Returns the codes and the pairs left to the steps (not two
    certain ellipsoids, a guard failed, or uncertain), or None where the mode has no such
    kernel."""
    first = getattr(mode, "stages", (mode,))[0]
    kernel = getattr(first, "decide_ellipsoids", None)
    if kernel is None:
        return None
    outside_too = question != "contact" and question != "region"
    facts = kernel(pairs, outside_too=outside_too, table=_lane_table(question))
    if facts is None:
        return None
    _, _, _, out, left, by_step = facts
    name = str(getattr(first, "stage", first.name))
    counts.add(Provenance(Step.CRITERION, name), int(by_step[0]))
    counts.add(Provenance(Step.SEPARATION, name), int(by_step[1]))
    return out, left


def _lane_rules(
    crit: np.ndarray, sep: np.ndarray, qsign: np.ndarray, question: str
) -> tuple[np.ndarray, np.ndarray]:
    """The answers to ``question`` (contact, region, kind) that the decision kernel's codes give
    by the rules of steps 1 and 2 (:func:`_criterion_answers`, :func:`_from_separation`), and
    which step gave each (0: the criterion, 1: the separation, 2: neither, the pair goes on
    to the general steps).  The lane reads them from :func:`_lane_table`."""
    out = np.full(crit.shape, UNCERTAIN, dtype=np.int8)
    todo = qsign != 0
    _criterion_answers(crit, qsign, question, out, todo)
    step = np.where(todo | (qsign == 0), 2, 0).astype(np.int8)
    values = _from_separation(sep, question)
    hit = todo & (values != UNCERTAIN)
    out[hit] = values[hit]
    step[hit] = 1
    return out, step


def _overlap_lane_rules(
    crit: np.ndarray, sep: np.ndarray, qsign: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """As :func:`_lane_rules`, for the overlap question (:func:`_overlap_from_criterion`,
    :func:`_overlap_from_separation`: ``Q`` an ellipsoid, the certified reading of the side)."""
    lane = qsign != 0
    side = _side(crit, qsign)
    out = _overlap_from_criterion(crit, side, True)
    out[~lane] = UNCERTAIN
    by_crit = lane & (out != UNCERTAIN)
    values = _overlap_from_separation(sep, qsign, True, side)
    hit = lane & ~by_crit & (values != UNCERTAIN)
    out[hit] = values[hit]
    step = np.full(crit.shape, 2, dtype=np.int8)
    step[by_crit] = 0
    step[hit] = 1
    return out, step


_LANE_TABLES: dict[str, tuple[np.ndarray, np.ndarray]] = {}


def _lane_table(question: str) -> tuple[np.ndarray, np.ndarray]:
    """The answer and the step (:func:`_lane_rules`, :func:`_overlap_lane_rules`) for every
    combination of the decision kernel's three codes, computed once by the rules themselves:
    the lane then reads one entry a pair instead of running the rules' dozen array passes."""
    table = _LANE_TABLES.get(question)
    if table is None:
        grid = np.indices(CODE_RANGES).reshape(3, -1).astype(np.int8)
        crit, sep, qsign = grid[0] - 1, grid[1] - 1, grid[2] - 1
        if question == "overlap":
            table = _overlap_lane_rules(crit, sep, qsign)
        else:
            table = _lane_rules(crit, sep, qsign, question)
        _LANE_TABLES[question] = table
    return table


def _criterion_answers(crit: np.ndarray, qsign: Any, question: str, out: np.ndarray, todo: np.ndarray) -> int:
    """Steps 1 and 1b on codes of the region criterion for pairs of two ellipsoids (``qsign``:
    the canonical sign of ``Q``): non-real roots of ``P`` are a crossing (Remark 9); two
    positive roots put ``E`` in the closed ``R+`` of ``Q`` (Wang-Wang-Kim), which answers the
    contact and the region questions (not the kind of contact: ``E`` may touch).  Writes the
    answers into ``out`` where ``todo``, clears ``todo`` there; returns how many."""
    crossing = crit == int(RegionCode.CONTACT)
    if question == "region":
        answer: Any = RegionCode.CONTACT
    elif question == "contact":
        answer = ContactCode.CONTACT
    else:
        answer = ContactKindCode.TRANSVERSAL
    hit = todo & crossing
    k = int(np.count_nonzero(hit))
    if k:
        _blend(out, hit, answer)
        np.logical_and(todo, np.logical_not(hit), out=todo)
    if question in ("contact", "region"):
        outside = todo & (crit * qsign == int(RegionCode.R_PLUS)) & (np.abs(crit) == 1)
        j = int(np.count_nonzero(outside))
        if j:
            _blend(out, outside, ContactCode.NO_CONTACT if question == "contact" else crit)
            np.logical_and(todo, np.logical_not(outside), out=todo)
        k += j
    return k


def _decide_steps(mode: NumberMode, pairs: Pairs, question: str, counts: StageCounts) -> np.ndarray:
    """:func:`decide`, step by step (the counts go to ``counts``)."""
    n = pairs.n
    out = np.full(n, UNCERTAIN, dtype=np.int8)
    todo = np.ones(n, dtype=bool)

    def settle(which: np.ndarray | bool, values: Any, label: Provenance) -> None:
        if which is False:  # a class no pair has
            counts.add(label, 0)
            return
        which = which & todo
        k = int(np.count_nonzero(which))
        if k:
            _blend(out, which, values)
            np.logical_and(todo, np.logical_not(which), out=todo)
        counts.add(label, k)

    def settle_at(at: np.ndarray, values: Any, label: Provenance) -> None:
        """Settle the pairs ``at`` (indices of pairs still to do) with ``values`` (one per entry
        of ``at``, or a scalar)."""
        if at.size:
            out[at] = values
            todo[at] = False
        counts.add(label, int(at.size))

    # 0. plain modes: pairs outside the binary64 programs' range, exactly
    far = _outside_range(mode, pairs)
    if far.size:
        settle_at(far, _exact_pairs(pairs, far, question), _OUTSIDE)

    # 1. criterion: the root structure of P (validates the input on the way).
    klass, qsign, ellipsoid = _classes(mode, pairs)
    ell = _is(ellipsoid, True)
    signs_first = None  # the first stage's root-sign reading of every pair
    if question == "region" or (question == "contact" and ell is not False):
        # contact codes from the whole cascade, the region reading from its first stage only:
        # the later stages' region reading (exact arithmetic for the coefficients' signs of a
        # structurally singular Q) would settle nothing that the separation stage does not
        crit, names, which, signs_first, deciding = _contact_with_signs(mode, pairs)
    else:
        crit, names, which = _staged(mode, StageMethod.CRITERION_CONTACT, pairs)
    labels = [Provenance(Step.CRITERION, name) for name in names]
    surfaceless = _is(klass, _CLASS_NO_SURFACE)
    if question == "region":
        settle(surfaceless, np.where(qsign > 0, 1, -1).astype(np.int8), _NO_REAL_POINTS)
    else:
        none = ContactCode.NO_CONTACT if question == "contact" else ContactKindCode.NONE
        settle(surfaceless, none, _NO_REAL_POINTS)
    plane = _is(klass, _CLASS_PLANE)
    if signs_first is None:
        deciding = _deciding_stages(which, len(labels))
    for k, label in enumerate(labels):
        if k not in deciding:
            counts.add(label, 0)
            continue
        here = which == k if len(deciding) > 1 else True  # one stage decided every decided pair
        if question == "region":
            settle(here & (crit == int(ContactCode.CONTACT)), RegionCode.CONTACT, label)
        else:
            answer = ContactCode.CONTACT if question == "contact" else ContactKindCode.TRANSVERSAL
            settle(here & (crit == int(ContactCode.CONTACT)), answer, label)
            if question == "contact":
                settle(
                    False if plane is False else here & (crit == int(ContactCode.NO_CONTACT)) & plane,
                    ContactCode.NO_CONTACT,
                    label,
                )
    all_real = crit == int(ContactCode.NO_CONTACT)
    if question == "region" and plane is not False and signs_first is not None:
        # a plane: the side read by the first stage (Theorem 14 with Corollary 15)
        on_side = (signs_first == int(RegionCode.R_MINUS)) | (signs_first == int(RegionCode.R_PLUS))
        settle(on_side & plane, signs_first, labels[0])

    # 1b. two ellipsoids, all roots real: two positive roots of P (Wang-Wang-Kim, for every
    # pair, read off the criterion's root signs) mean E outside Q or touching it from outside:
    # no crossing, and E in the closed R+ of Q's canonical sign.
    if signs_first is not None and ell is not False:
        # the first stage's reading only (see _contact_with_signs)
        outside = todo & all_real & ell & (signs_first * qsign == int(RegionCode.R_PLUS))
        outside = _confirm_outside(mode, pairs, outside, signs_first)
        settle(outside, signs_first if question == "region" else ContactCode.NO_CONTACT, labels[0])

    # 1c. plain modes: a crossing read from non-real roots that a certified reading cannot
    # confirm waits for the separation stage (for every question: the kind of contact too).
    crossing = {
        "region": int(RegionCode.CONTACT),
        "contact": int(ContactCode.CONTACT),
        "kind": int(ContactKindCode.TRANSVERSAL),
    }[question]
    said = np.flatnonzero(~todo & (out == crossing))
    _confirm_crossings(mode, pairs, said, out, todo, counts, labels[0])

    # 3. separation: definite members, or four simple real roots without one.
    rest = np.flatnonzero(todo)
    if rest.size:
        sep, names, which = _staged(mode, StageMethod.SEPARATION, pairs.take(rest))
        values = _from_separation(sep, question)
        for k, name in enumerate(names):
            hit = np.flatnonzero((which == k) & (values != UNCERTAIN))
            settle_at(rest[hit], values[hit], Provenance(Step.SEPARATION, name))

    # 4. the exact scalar predicates, pair by pair.
    rest = np.flatnonzero(todo)
    if rest.size and getattr(mode, "complete", False):
        settle_at(rest, _exact_pairs(pairs, rest, question), _EXACT_PAIR)
    counts.undecided += int(np.count_nonzero(todo))
    return out


def _confirm_crossings(
    mode: NumberMode,
    pairs: Pairs,
    said: np.ndarray,
    out: np.ndarray,
    todo: np.ndarray,
    counts: StageCounts,
    label: Provenance,
) -> None:
    """Plain modes: the pairs ``said`` were settled because the criterion read non-real roots of
    ``P``.  Those the mode's certified guard (:attr:`NumberMode.guard`) does not confirm are
    opened again for the separation stage: rounding turns the multiple root of a symmetric
    placement into a non-real pair, and a definite member, which the separation stage finds,
    says the surfaces do not meet."""
    guard = getattr(mode, "guard", None)
    if guard is None or said.size == 0:
        return
    sure = guard.criterion_contact(pairs.take(said))
    reopen = said[sure != int(ContactCode.CONTACT)]
    if reopen.size:
        out[reopen] = UNCERTAIN
        todo[reopen] = True
        counts.add(label, -int(reopen.size))


def _confirm_outside(mode: NumberMode, pairs: Pairs, outside: Any, signs: np.ndarray) -> Any:
    """Plain modes: step 1b reads two positive roots off the signs of ``P``'s coefficients as
    binary64 computes them.  Where ``Q`` is an ellipsoid whose quadratic part is nearly singular
    (a rotated cylinder or paraboloid, rounded), those signs can be wrong while the answer is
    not delicate at all (``E`` far from the surface, on the other side).  The pairs the mode's
    certified guard does not read the same way are left to the separation stage, whose members
    are computed from the matrices themselves.  Certified modes: ``outside`` unchanged."""
    guard = getattr(mode, "guard", None)
    if guard is None or isinstance(outside, bool):
        return outside
    at = np.flatnonzero(outside)
    if at.size == 0:
        return outside
    sure = guard.criterion_region(pairs.take(at))
    kept = np.asarray(outside, dtype=bool).copy()
    kept[at[sure != signs[at]]] = False
    return kept


def _contact_with_signs(
    mode: NumberMode, pairs: Pairs
) -> tuple[np.ndarray, list[str], np.ndarray, np.ndarray, set[int]]:
    """The criterion for the contact and region questions, and the root-sign reading of step 1b, in one
    pass over the pairs: the first stage of the cascade reads the region (its kernels compute
    the contact code and the signs of the coefficients together); where that reading is
    uncertain, the whole cascade decides the contact code alone.

    Returns ``(contact codes, stage names, deciding stage, first-stage region codes, the stages
    that decided at least one pair)``.  Only
    the first stage's sign reading is used by step 1b: what it cannot read (a structural zero
    such as proportional quadratic parts, a tangency) goes on to the separation stage,
    which settle it in binary64 more often than a slower stage of the cascade would."""
    first = getattr(mode, "stages", (mode,))[0]
    signs = first.criterion_region(pairs)
    # ContactCode.CONTACT is 1 and NO_CONTACT 0: the comparison's bytes are the codes
    crit = (signs == int(RegionCode.CONTACT)).view(np.int8)
    # UNCERTAIN, and EXCLUDED (a type without a row of Table 4, or without real points: the
    # reading does not say whether the roots are real there), go to the contact criterion
    unsure = np.flatnonzero((signs == UNCERTAIN) | (signs == int(RegionCode.EXCLUDED)))
    names = [str(getattr(s, "stage", s.name)) for s in getattr(mode, "stages", (mode,))]
    which = np.zeros(pairs.n, dtype=np.int8)
    deciding = {0} if unsure.size < pairs.n else set()
    if unsure.size:
        sub, sub_names, sub_which = _staged(mode, StageMethod.CRITERION_CONTACT, pairs.take(unsure))
        names = sub_names
        crit[unsure] = sub
        which[unsure] = sub_which
        deciding |= _deciding_stages(sub_which, len(names))
    return crit, names, which, signs, deciding


def _separation_table(question: str) -> np.ndarray:
    """The answer to ``question`` for each separation code (``SEP_MINUS``, ``CROSSING``,
    ``SEP_PLUS``, ``UNCERTAIN``, and the lane's ``NOT_RUN``), at the code plus one: apart means
    no contact, a crossing transversal contact, the region is the code itself."""
    table = np.full(5, UNCERTAIN, dtype=np.int8)
    for code in (SEP_MINUS, CROSSING, SEP_PLUS):
        crossing = code == CROSSING
        answer: int
        if question == "contact":
            answer = ContactCode.CONTACT if crossing else ContactCode.NO_CONTACT
        elif question == "region":
            answer = code
        else:
            answer = ContactKindCode.TRANSVERSAL if crossing else ContactKindCode.NONE
        table[code + 1] = answer
    return table


_SEPARATION_TABLES = {question: _separation_table(question) for question in ("contact", "region", "kind")}


def _from_separation(sep: np.ndarray, question: str) -> np.ndarray:
    """The answers the separation codes ``sep`` give to ``question`` (:func:`_separation_table`;
    ``UNCERTAIN`` where the code is uncertain or the separation was not run): one lookup a pair."""
    table = _SEPARATION_TABLES["kind" if question not in ("contact", "region") else question]
    return table[sep + np.int8(1)]


def _exact_pairs(pairs: Pairs, rows: np.ndarray, question: str) -> np.ndarray:
    """The exact scalar answer for the pairs ``rows`` (cached per pair of matrices)."""

    e_rows, q_rows = pairs.e_rows_at(rows), pairs.q_rows_at(rows)
    cache: dict[tuple[int, int], int] = {}
    out = np.empty(rows.size, dtype=np.int8)
    for t in range(rows.size):
        key = (int(e_rows[t]), int(q_rows[t]))
        if key not in cache:
            E, Q = exact_matrix(pairs.E, key[0]), exact_matrix(pairs.Q, key[1])
            if question == "contact":
                r = transversal_contact_exact(E, Q)
                cache[key] = int(ContactCode.CONTACT if r.transversal else ContactCode.NO_CONTACT)
            elif question == "region":
                cache[key] = int(RegionCode.from_region(relative_position_exact(E, Q).region))
            else:
                cache[key] = int(ContactKindCode.from_kind(analyze_contact(E, Q).kind))
        out[t] = cache[key]
    return out


# -- do the solids overlap? ---------------------------------------------------------------------


def _solids(mode: NumberMode, pairs: Pairs) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per pair: ``Q`` is a plane, ``Q`` is an ellipsoid, and the sign that makes ``R-`` its
    solid (its canonical sign).  The type is part of the question (which solid), so where the
    mode cannot tell it the exact type decides (once per quadric); a type without a solid is
    refused."""

    used, where = unique_rows(pairs.q_rows(), len(pairs.Q), return_inverse=True)
    rows = rows_from_masks(mode.classify(pairs.Q, used)).astype(np.intp)
    plane = _ROW_PLANE[rows]
    ellipsoid = _ROW_ELLIPSOID[rows]
    sign = np.where(_ROW_SIGN[rows] < 0, -1, 1).astype(np.int8)
    # the quadrics whose type the mode could not tell, and those of a type whose solid must be
    # checked (neither a Table 1 type nor a plane), one by one
    for k in np.flatnonzero((rows == UNCERTAIN_ROW) | _ROW_CHECK_SOLID[rows]):
        row = int(rows[k])
        if row == UNCERTAIN_ROW:
            q = exact_matrix(pairs.Q, int(used[k]))
            kind, s = q.kind, q.canonical_sign
        else:
            kind, s = KINDS[row // 2], (-1 if row % 2 else 1)
        if kind not in TABLE_1_KINDS and kind is not QuadricKind.PLANE:
            q = exact_matrix(pairs.Q, int(used[k]))
            try:
                solid_of(q, pairs.Q.where(int(used[k])))
            except ExcludedQuadricError as exc:
                exc.details["index"] = int(used[k])
                raise
        plane[k] = kind is QuadricKind.PLANE
        ellipsoid[k] = kind is QuadricKind.ELLIPSOID
        sign[k] = s
    where = np.asarray(where).reshape(-1)
    return plane[where], ellipsoid[where], sign[where]


def decide_overlap(mode: NumberMode, pairs: Pairs) -> tuple[np.ndarray, StageCounts]:
    """:class:`~quadric_contact.modes.OverlapCode` of every pair: do the solids overlap?
    (:func:`_decide_overlap`, with the counts of the steps that settled them; the mode forgets
    this call's stacks afterwards.)"""
    _remember(mode, True)
    try:
        return _decide_overlap(mode, pairs)
    finally:
        _remember(mode, False)


def _decide_overlap(mode: NumberMode, pairs: Pairs) -> tuple[np.ndarray, StageCounts]:
    """:class:`~quadric_contact.modes.OverlapCode` of every pair: do the solids overlap?

    The solid of ``E`` is its inside, that of ``Q`` its region ``R-`` for the sign of its
    standard form (:mod:`quadric_contact.theory.overlap`).  With ``Q`` of that sign:

    1. *criterion*: non-real roots of ``P`` mean the surfaces cross: ``OVERLAPPING``
       (Remark 9).  A plane with ``E`` on its ``R-`` side: ``OVERLAPPING`` (Theorem 14).
       Two ellipsoids: the criterion's reading of the root signs counts the positive roots,
       for every pair (Wang-Wang-Kim): none means ``OVERLAPPING``; two mean ``SEPARATE`` or
       ``TOUCHING``, which step 2 tells apart.
    2. *separation*: the surfaces cross, or ``E`` is strictly inside the solid:
       ``OVERLAPPING``; ``E`` strictly outside: ``SEPARATE``, except that an ellipsoid ``Q``
       outside whose surface ``E`` lies may be inside ``E``: there ``SEPARATE`` needs the two
       positive roots of step 1 (a definite member at a positive sample point), or, where
       step 1 read no side, the side of ``E`` its centre is on, exactly (:func:`_centre_side`).
    3. *exact pair*: tangencies and multiple roots, by
       :func:`~quadric_contact.theory.overlap.overlap_exact` (``TOUCHING`` comes from here only).

    The abstaining modes answer ``UNCERTAIN`` where 1-2 leave a pair; the plain modes answer
    everything at step 2 (never ``TOUCHING``: a touch is a tangency, which binary64 cannot
    see).  Returns the codes and the counts of the steps that settled them.

    The pairs of two ellipsoids take steps 1 and 2 in one pass (:func:`_lane`); the
    others, and what it leaves, take them here."""
    counts = StageCounts()
    if pairs.n == 0:
        return np.full(0, UNCERTAIN, dtype=np.int8), counts
    lane = _lane(mode, pairs, "overlap", counts)
    if lane is None:
        out = _overlap_steps(mode, pairs, counts)
    else:
        out, rest = lane
        if rest.size:
            out[rest] = _overlap_steps(mode, pairs.take(rest), counts)
    return out, counts


def _overlap_steps(mode: NumberMode, pairs: Pairs, counts: StageCounts) -> np.ndarray:
    """:func:`_decide_overlap`, step by step (the counts go to ``counts``)."""
    n = pairs.n
    out = np.full(n, UNCERTAIN, dtype=np.int8)
    todo = np.ones(n, dtype=bool)

    def settle(which: np.ndarray, values: Any, label: Provenance) -> None:
        which = which & todo
        k = int(np.count_nonzero(which))
        if k:
            _blend(out, which, values)
            np.logical_and(todo, np.logical_not(which), out=todo)
        counts.add(label, k)

    # 0. plain modes: pairs outside the binary64 programs' range, exactly
    far = _outside_range(mode, pairs)
    if far.size:
        out[far] = _exact_overlaps(pairs, far)
        todo[far] = False
        counts.add(_OUTSIDE, int(far.size))

    # 1. criterion: root structure and signs (validates the input on the way).  Non-real roots
    # come from the whole cascade, the side from its first stage only, as for the region
    # question (_contact_with_signs): the later stages' side reading ran exact arithmetic on the
    # coefficients' signs for 3 % of the pairs of every type (rotated cylinders and paraboloids
    # that binary64 makes nearly singular ellipsoids), which step 2 and the centre of Q settle.
    contact, names, which, signs_first, _ = _contact_with_signs(mode, pairs)
    crit = np.where(contact == int(ContactCode.CONTACT), np.int8(RegionCode.CONTACT), signs_first).astype(
        np.int8
    )
    plane, ellipsoid, qsign = _solids(mode, pairs)
    side = _side(crit, qsign)
    said = _overlap_from_criterion(crit, side, plane | ellipsoid)
    for k, name in enumerate(names):
        here = which == k
        settle(here & (said != UNCERTAIN), said, Provenance(Step.CRITERION, name))
    said = np.flatnonzero(~todo & (crit == int(RegionCode.CONTACT)))
    _confirm_crossings(mode, pairs, said, out, todo, counts, Provenance(Step.CRITERION, names[0]))

    # 2. separation: definite members, or four simple real roots without one.
    rest = np.flatnonzero(todo)
    if rest.size:
        sep, names, which = _staged(mode, StageMethod.SEPARATION, pairs.take(rest))
        values = _overlap_from_separation(sep, qsign[rest], ellipsoid[rest], side[rest])
        # an ellipsoid Q whose side step 1 could not read (a rounded cylinder or paraboloid,
        # nearly singular): the surface of E misses Q's solid, so either the solids are apart
        # or Q is inside E, and the centre of Q (in its solid) tells which
        open_ = np.flatnonzero((values == UNCERTAIN) & (sep * qsign[rest] == SEP_PLUS) & ellipsoid[rest])
        if open_.size:
            where_ = _centre_side(pairs, rest[open_])
            values[open_[where_ > 0]] = OverlapCode.SEPARATE
            values[open_[where_ < 0]] = OverlapCode.OVERLAPPING
        for k, name in enumerate(names):
            here = np.zeros(n, dtype=bool)
            here[rest[which == k]] = True
            full = np.full(n, UNCERTAIN, dtype=np.int8)
            full[rest] = values
            settle(here & (full != UNCERTAIN), full, Provenance(Step.SEPARATION, name))

    # 2b. an ellipsoid or a plane whose side the first stage could not read (a tangency of exact
    # input): the side read by the whole cascade, where step 1's rules use it (E in the solid
    # of an ellipsoid or on the solid's side of a plane: overlapping).
    rest = np.flatnonzero(todo & (side == UNCERTAIN) & (plane | ellipsoid))
    if rest.size:
        crit, names, which = _staged(mode, StageMethod.CRITERION_REGION, pairs.take(rest))
        values = _overlap_from_criterion(crit, _side(crit, qsign[rest]), True)
        for k, name in enumerate(names):
            here = np.zeros(n, dtype=bool)
            here[rest[(which == k) & (values != UNCERTAIN)]] = True
            full = np.full(n, UNCERTAIN, dtype=np.int8)
            full[rest] = values
            settle(here, full, Provenance(Step.CRITERION, name))

    # 3. the exact decision, pair by pair.
    rest = np.flatnonzero(todo)
    if rest.size and getattr(mode, "complete", False):
        full = np.full(n, UNCERTAIN, dtype=np.int8)
        full[rest] = _exact_overlaps(pairs, rest)
        here = np.zeros(n, dtype=bool)
        here[rest] = True
        settle(here, full, _EXACT_PAIR)
    counts.undecided += int(np.count_nonzero(todo))
    return out


def _side(crit: np.ndarray, qsign: Any) -> np.ndarray:
    """The criterion's side of ``Q``'s solid: -1 in it, 1 outside (``R-``/``R+`` of the canonical
    sign), ``UNCERTAIN`` where the criterion read no side."""
    sided = (crit == int(RegionCode.R_MINUS)) | (crit == int(RegionCode.R_PLUS))
    return np.where(sided, crit * qsign, UNCERTAIN).astype(np.int8)


def _overlap_from_criterion(crit: np.ndarray, side: np.ndarray, sided_solid: Any) -> np.ndarray:
    """Step 1 of the overlap question: non-real roots, the surfaces cross (Remark 9); ``E`` on
    the solid's side of a plane (Theorem 14) or, for two ellipsoids, no positive root
    (Wang-Wang-Kim): overlapping (``sided_solid``: ``Q`` a plane or an ellipsoid)."""
    values = np.full(crit.shape, UNCERTAIN, dtype=np.int8)
    values[crit == int(RegionCode.CONTACT)] = OverlapCode.OVERLAPPING
    values[(side == int(RegionCode.R_MINUS)) & np.asarray(sided_solid, dtype=bool)] = OverlapCode.OVERLAPPING
    return values


def _overlap_from_separation(sep: np.ndarray, qsign: Any, ellipsoid: Any, side: np.ndarray) -> np.ndarray:
    """Step 2 of the overlap question, from separation codes: a crossing, or ``E`` strictly in
    the solid, overlapping; ``E`` strictly outside, separate -- except that an ellipsoid ``Q``
    may lie inside ``E``: there every mode needs the two positive roots of step 1 (``side`` 1),
    and without them the side of ``E`` the centre of ``Q`` is on decides (:func:`_centre_side`,
    in :func:`_overlap_steps`).  (A plain mode that took "outside" for "apart" called a small
    ball inside a large one separate.)"""
    sep_side = np.where((sep == SEP_MINUS) | (sep == SEP_PLUS), sep * qsign, sep)
    values = np.full(sep.shape, UNCERTAIN, dtype=np.int8)
    values[(sep_side == CROSSING) | (sep_side == SEP_MINUS)] = OverlapCode.OVERLAPPING
    outside = sep_side == SEP_PLUS
    two_positive = side == int(RegionCode.R_PLUS)
    not_ellipsoid = np.logical_not(np.asarray(ellipsoid, dtype=bool))  # a mask, also for a scalar
    values[outside & (not_ellipsoid | two_positive)] = OverlapCode.SEPARATE
    return values


def _centre_side(pairs: Pairs, rows: np.ndarray) -> np.ndarray:
    """For pairs of two ellipsoids: 1 where the centre of ``Q`` lies strictly outside ``E``, -1
    strictly inside, 0 on its surface; exactly.

    With ``Q = [[A, b], [b^T, q]]``, ``D = det A`` and ``y = adj(A) b``, the centre is
    ``-y / D``, and ``E = [[A_E, a], [a^T, e]]`` at it, times ``D^2 > 0``, is
    ``y^T A_E y - 2 D a^T y + e D^2``: its sign, times that of ``A_E`` (positive definite in the
    paper's sign), is the answer.  Integers throughout (the entries scaled by a common
    denominator).

    Used where the surface of ``E`` misses the solid of ``Q``: that solid, convex and holding
    its centre, is then inside ``E`` or apart from it, as its centre is."""
    es = integer_rows(pairs.E, pairs.e_rows_at(rows))
    qs = integer_rows(pairs.Q, pairs.q_rows_at(rows))
    value = centre_value(es, qs)  # columns of Python integers: every pair in one pass
    sign = (value > 0).astype(np.int8) - (value < 0).astype(np.int8)
    return np.where(es[0] > 0, sign, -sign).astype(np.int8)


def centre_value(e: Any, q: Any) -> Any:
    """``D^2`` times ``E`` at the centre of ``Q``: ``y^T A_E y - 2 D a^T y + e D^2`` with
    ``D = det A`` and ``y = adj(A) b`` (``Q = [[A, b], [b^T, q]]``, ``E = [[A_E, a], [a^T, e]]``),
    from the upper entries of both (row by row); a polynomial in them, so integers give it
    exactly (and symbols give the identity ``proofs/wwk_2001_ellipsoid_separation.py``
    checks).  Meaningful where ``D != 0`` (``Q`` has a centre: the callers' ``Q`` are
    ellipsoids)."""
    e00, e01, e02, a0, e11, e12, a1, e22, a2, e33 = e
    q00, q01, q02, b0, q11, q12, b1, q22, b2, _ = q
    m00, m01, m02 = q11 * q22 - q12 * q12, q02 * q12 - q01 * q22, q01 * q12 - q02 * q11
    m11, m12, m22 = q00 * q22 - q02 * q02, q01 * q02 - q00 * q12, q00 * q11 - q01 * q01
    d = q00 * m00 + q01 * m01 + q02 * m02
    y0 = m00 * b0 + m01 * b1 + m02 * b2
    y1 = m01 * b0 + m11 * b1 + m12 * b2
    y2 = m02 * b0 + m12 * b1 + m22 * b2
    quad = e00 * y0 * y0 + e11 * y1 * y1 + e22 * y2 * y2
    quad += 2 * (e01 * y0 * y1 + e02 * y0 * y2 + e12 * y1 * y2)
    return quad - 2 * d * (a0 * y0 + a1 * y1 + a2 * y2) + e33 * d * d


def _exact_overlaps(pairs: Pairs, rows: np.ndarray) -> np.ndarray:
    """:func:`~quadric_contact.theory.overlap.overlap_exact` for the pairs ``rows`` (cached per pair)."""

    e_rows, q_rows = pairs.e_rows_at(rows), pairs.q_rows_at(rows)
    cache: dict[tuple[int, int], int] = {}
    out = np.empty(rows.size, dtype=np.int8)
    for t in range(rows.size):
        key = (int(e_rows[t]), int(q_rows[t]))
        if key not in cache:
            E, Q = exact_matrix(pairs.E, key[0]), exact_matrix(pairs.Q, key[1])
            cache[key] = int(overlap_exact(E, Q).code)
        out[t] = cache[key]
    return out
