"""Modes that run the generated formulas on Python number objects: ``exact``
(integers), ``ball`` (python-flint ``arb``) and ``mpmath`` (``mpf`` at a chosen
precision).

The formulas of :mod:`quadric_contact._generated` are straight-line ``+ - *``
code, so numpy applies them to object arrays element by element: the loops
run in C and each operation is one call of the number type.  A mode only says
how to turn exact input entries into its numbers (:meth:`ObjectMode.convert`,
one matrix at a time, so that it may scale a matrix by a positive factor: signs,
root signs and the real/non-real nature of the roots do not change) and how to
read a sign (:meth:`ObjectMode.signs`).
"""

from __future__ import annotations

import contextlib
import math
from contextlib import AbstractContextManager
from fractions import Fraction
from typing import Any

import numpy as np

from quadric_contact._generated import blocks, formulas, kernels
from quadric_contact.exact.errors import ChoiceError
from quadric_contact.exact.precision import working_precision
from quadric_contact.modes.codes import UNCERTAIN
from quadric_contact.modes.decision.answers import (
    ELLIPSOID_NOT,
    ELLIPSOID_UNCERTAIN,
    contact_from_signs,
    ellipsoid_from_signs,
    masks_from_invariant_signs,
)
from quadric_contact.modes.decision.separation import separation_isolated, separation_objects
from quadric_contact.modes.facts import (
    exact_invariant_signs,
    exact_signs,
    proportional_exact,
    structural_facts,
)
from quadric_contact.modes.kernels import errorbounds as eb
from quadric_contact.modes.kernels import exact_pencil
from quadric_contact.modes.kernels.signs import sign_within
from quadric_contact.modes.kernels.support_drivers import region_from_signs
from quadric_contact.modes.numbers.number_mode import NumberMode
from quadric_contact.modes.smallness.objects import (
    BallNumbers,
    MpmathNumbers,
    exact_smallness,
    object_smallness,
)
from quadric_contact.modes.stacks.integers import dyadic_integers, dyadic_rows, integer_rows
from quadric_contact.modes.stacks.pairs import MatrixStack, Pairs
from quadric_contact.modes.stacks.validation import raise_not_ellipsoid, validate_rows

__all__ = ["BallMode", "ExactMode", "MpmathMode", "ObjectMode"]


class ObjectMode(NumberMode):
    """Shared evaluation for the object modes."""

    stage = "object"
    structural = False
    """Read the exact structural zeros (set for the plain ``mpmath`` mode, whose rounding
    would otherwise give them a random sign)."""

    # -- what a subclass provides -------------------------------------------------------

    def convert(self, stack: MatrixStack, rows: np.ndarray) -> list[np.ndarray]:
        """The ten upper-entry columns of the matrices ``rows`` in this mode's numbers
        (each matrix may be multiplied by its own positive factor)."""
        raise NotImplementedError

    def signs(self, values: np.ndarray) -> np.ndarray:
        """int8 signs (``UNCERTAIN`` where the mode cannot tell)."""
        raise NotImplementedError

    def context(self) -> AbstractContextManager[None]:
        """Scope precision changes to one evaluation (through
        :func:`~quadric_contact.exact.precision.working_precision`, the one lock-holding context)."""
        return contextlib.nullcontext()

    def deltas(self, c: list[np.ndarray]) -> tuple[np.ndarray, ...]:
        """``(Delta_2, Delta_3, Delta_4)`` or positive multiples of them."""
        return tuple(formulas.paper_deltas(*c))

    def delta_signs(self, c: list[np.ndarray]) -> np.ndarray:
        """``(n, 3)`` int8 signs of :meth:`deltas` (``UNCERTAIN`` where the mode cannot tell)."""
        return np.stack([self.signs(x) for x in self.deltas(c)], axis=1)

    # -- shared -------------------------------------------------------------------------

    def _pair_signs(self, pairs: Pairs) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """``(ellipsoid status, c signs (n, 5) for the paper's sign of E, Delta signs (n, 3),
        E rows)``."""
        e_rows, q_rows = pairs.e_rows(), pairs.q_rows()
        ue, ie = np.unique(e_rows, return_inverse=True)
        uq, iq = np.unique(q_rows, return_inverse=True)
        validate_rows(pairs.E, ue, "E")
        validate_rows(pairs.Q, uq, "Q")
        with self.context():
            e_cols, c = self.pencil(pairs, ue, ie, uq, iq)
            if self.structural:
                # The exact structural zeros the filter reads: c0 = 0 (det Q = 0), c1 = 0
                # (rank Q <= 2), and Delta_4 = 0 for proportional quadratic parts.
                facts = structural_facts(pairs.Q, uq)[iq]
                zero = self.number(0.0)
                c[0] = np.where(facts & 1, zero, c[0])
                c[1] = np.where(facts & 2, zero, c[1])
            m2, m3 = kernels.leading_minors_3(*(e_cols[k] for k in (0, 1, 2, 4, 5, 7)))
            sa = exact_signs(e_cols[0])
            sc = np.stack([self.signs(x) for x in c], axis=1)
            ell = ellipsoid_from_signs(sa, self.signs(m2), self.signs(m3), sc[:, 4])
            # The paper's sign of E: for -E the odd coefficients (and their signs) flip.
            flip = sa < 0
            sc[flip, 1] = _neg(sc[flip, 1])
            sc[flip, 3] = _neg(sc[flip, 3])
            sd = self.delta_signs(c)
            if self.structural:
                sd[proportional_exact(pairs, e_rows, q_rows), 2] = 0
        return ell, sc, sd, e_rows

    def pencil(
        self, pairs: Pairs, ue: np.ndarray, ie: np.ndarray, uq: np.ndarray, iq: np.ndarray
    ) -> tuple[list[np.ndarray], list[np.ndarray]]:
        """``(E columns, [c0 .. c4])`` per pair in this mode's numbers, for the pairs
        ``(ue[ie], uq[iq])``: the generated expansion of ``det(lambda E + Q)``."""
        e_cols = [c[ie] for c in self.convert(pairs.E, ue)]
        q_cols = [c[iq] for c in self.convert(pairs.Q, uq)]
        return e_cols, list(formulas.pencil_coefficients(*e_cols, *q_cols))

    def _finish(self, pairs: Pairs, ell: np.ndarray, codes: np.ndarray, e_rows: np.ndarray) -> np.ndarray:
        bad = ell == ELLIPSOID_NOT
        if bad.any():
            raise_not_ellipsoid(pairs.E, int(e_rows[np.argmax(bad)]))
        return np.where(ell == ELLIPSOID_UNCERTAIN, UNCERTAIN, codes).astype(np.int8)

    def number(self, value: float) -> Any:
        """A float sample point as a number of this mode (exactly)."""
        raise NotImplementedError

    def separation(self, pairs: Pairs) -> np.ndarray:
        return separation_objects(self, pairs, certified=self.certified)

    def criterion_contact(self, pairs: Pairs) -> np.ndarray:
        if pairs.n == 0:
            return np.empty(0, dtype=np.int8)
        ell, _, sd, e_rows = self._pair_signs(pairs)
        codes = contact_from_signs(sd[:, 0], sd[:, 1], sd[:, 2])
        return self._finish(pairs, ell, codes, e_rows)

    def criterion_region(self, pairs: Pairs) -> np.ndarray:
        if pairs.n == 0:
            return np.empty(0, dtype=np.int8)
        ell, sc, sd, e_rows = self._pair_signs(pairs)
        contact = contact_from_signs(sd[:, 0], sd[:, 1], sd[:, 2])
        used, where = np.unique(pairs.q_rows(), return_inverse=True)
        masks = self.classify(pairs.Q, used)[np.asarray(where).reshape(-1)]
        codes = region_from_signs(contact, sc, masks)
        return self._finish(pairs, ell, codes, e_rows)

    def invariant_signs(self, Q: MatrixStack, rows: np.ndarray) -> np.ndarray:
        """``(k, 8)`` signs of ``(trA, J, detA, E1 .. E4, q33)`` of the quadrics ``rows``."""
        validate_rows(Q, rows, "Q")
        with self.context():
            cols = self.convert(Q, rows)
            v = kernels.quadric_invariants(*cols)
            out = np.stack([self.signs(x) for x in v] + [exact_signs(cols[9])], axis=1)
        return out.astype(np.int8)

    def classify(self, Q: MatrixStack, rows: np.ndarray | None = None) -> np.ndarray:
        index = np.arange(len(Q)) if rows is None else np.asarray(rows)
        return masks_from_invariant_signs(self.invariant_signs(Q, index))


def _neg(s: np.ndarray) -> np.ndarray:
    return np.where(s == UNCERTAIN, UNCERTAIN, -s).astype(np.int8)


_RHO_EXACT = 2.0**-52
"""A bound of the relative error of an exact integer coefficient converted to binary64: Python's
``int`` to ``float`` rounds correctly (``u = 2^-53``); a column of mixed integer types goes
through ``int`` first."""
assert _RHO_EXACT <= eb.RHO_MAX


def filtered_delta_signs(c: list[np.ndarray]) -> np.ndarray:
    """``(n, 3)`` int8 signs of the compact ``Delta_2, Delta_3, 27 Delta_4`` of exact coefficients
    ``c0 .. c4`` (object arrays of integers), from their binary64 roundings: ``UNCERTAIN`` where
    the rigorous bound does not settle the sign.

    Each coefficient rounds to binary64 with relative error at most ``u`` (:data:`_RHO_EXACT`
    bounds it); one power of two per pair (exact) brings the largest to ``[1/2, 1)``.  The compact
    programs and their magnitude programs then run in binary64 and the relative form of the
    screen's bound (:data:`~quadric_contact.modes.kernels.errorbounds.SEMI_DELTA`, derived there from the
    programs' rounding counts for coefficients known to within a relative ``rho <= RHO_MAX``)
    bounds the error; it holds when every non-zero scaled coefficient is at least
    :data:`~quadric_contact.modes.kernels.errorbounds.COEFFICIENT_MIN` (no subnormal intermediate).  A
    coefficient beyond binary64's range, or a pair outside that guard, is ``UNCERTAIN``."""
    n = len(c[0])
    out = np.full((n, 3), UNCERTAIN, dtype=np.int8)
    if n == 0:
        return out
    cols_in = [np.asarray(x, dtype=object) for x in c]
    try:
        if not all(type(v) is int for x in cols_in for v in x):
            raise OverflowError  # other types (fmpz, a Fraction zero): one by one
        a = np.stack([x.astype(np.float64) for x in cols_in], axis=1)
    except OverflowError:
        a = np.stack([_float_or_inf(x) for x in cols_in], axis=1)
    with np.errstate(all="ignore"):
        top = np.abs(a).max(axis=1)
        exponent = np.frexp(top)[1]  # top in [2^(e-1), 2^e)
        a = np.ldexp(a, -exponent[:, None])  # exact: a power of two, no result below 2^-1022
        mag = np.abs(a)
        low = np.where(mag != 0, mag, 1.0).min(axis=1)
        ok = np.isfinite(top) & (low >= eb.COEFFICIENT_MIN)
        cols = [a[:, k] for k in range(5)]
        both = blocks.paper_deltas_compact_and_magnitude(*cols)  # the magnitudes at |cols|
        d, A = both[:3], both[3:]
        for j, ((R, G), dj, Aj) in enumerate(zip(eb.SEMI_DELTA, d, A, strict=True)):
            bound = (R * _RHO_EXACT + G) * Aj
            sign = sign_within(dj, bound)
            out[:, j] = np.where(ok, sign, UNCERTAIN)
    return out


def _float_or_inf(x: np.ndarray) -> np.ndarray:
    """Binary64 roundings of the integers ``x``, infinity for those beyond its range."""
    big = 2**1023

    def one(v: Any) -> float:
        v = v if isinstance(v, Fraction) else int(v)  # Fraction: a structural zero put in
        return float(v) if -big < v < big else float("inf")

    return np.frompyfunc(one, 1, 1)(x).astype(np.float64)


# -- exact ---------------------------------------------------------------------------------


class ExactMode(ObjectMode):
    """Exact integer arithmetic: the answer for the matrices exactly as given.

    Parameters
    ----------
    backend : {"int", "fmpz"}
        ``"int"`` (default): the pencil coefficients ``c0 .. c4`` in compiled multi-digit
        integer arithmetic (:mod:`quadric_contact.modes.kernels.exact_pencil`: the same expansion,
        equal values; numba), then ``Delta_2 .. Delta_4`` on Python integers.  ``"fmpz"``:
        the generated formulas on python-flint ``fmpz`` throughout.  On 2000 random float
        pairs (``criterion_stack``, best of 3, indicative): ``"int"`` 13 us a pair, where
        Python integers throughout took 22 us; ``"fmpz"`` 32 us.  Both read the Delta signs
        in binary64 with a rigorous bound first (:func:`filtered_delta_signs`), the integers
        only where that cannot tell: ``"int"`` 8-10 us a pair.
    """

    name = "exact"
    stage = "exact"
    certified = True
    complete = True

    def __init__(self, backend: str = "int") -> None:
        super().__init__()
        if backend not in ("int", "fmpz"):
            choices = ("int", "fmpz")
            raise ChoiceError(f"backend must be one of int, fmpz, got {backend!r}", backend, choices=choices)
        self.backend = backend

    def invariant_signs(self, Q: MatrixStack, rows: np.ndarray) -> np.ndarray:
        """The exact signs are facts about the matrices, whatever the backend: read once per
        quadric of the stack (:func:`~quadric_contact.modes.facts.exact_invariant_signs`)."""
        return exact_invariant_signs(Q, rows)

    def convert(self, stack: MatrixStack, rows: np.ndarray) -> list[np.ndarray]:
        cols = integer_rows(stack, rows)
        if self.backend == "fmpz":
            import flint  # import cost

            to = np.frompyfunc(flint.fmpz, 1, 1)
            cols = [to(c) for c in cols]
        return cols

    def pencil(
        self, pairs: Pairs, ue: np.ndarray, ie: np.ndarray, uq: np.ndarray, iq: np.ndarray
    ) -> tuple[list[np.ndarray], list[np.ndarray]]:
        """Backend ``"int"``: the coefficients in compiled multi-digit integer arithmetic
        (:mod:`quadric_contact.modes.kernels.exact_pencil`, the same expansion, equal values),
        read from the binary64 entries as ``m * 2^shift``; backend ``"fmpz"``: the
        generated expansion on ``fmpz``."""
        if self.backend != "int" or not exact_pencil.HAVE_KERNEL:
            return super().pencil(pairs, ue, ie, uq, iq)
        if pairs.E.exact is None and pairs.Q.exact is None:
            me, se = dyadic_rows(pairs.E, ue)
            mq, sq = dyadic_rows(pairs.Q, uq)
            c = exact_pencil.pencil_coefficients_dyadic(me[ie], se[ie], mq[iq], sq[iq])
            e_cols = [col[ie] for col in dyadic_integers(me, se)]
            return e_cols, c
        e_cols = [col[ie] for col in integer_rows(pairs.E, ue)]
        q_cols = [col[iq] for col in integer_rows(pairs.Q, uq)]
        c = exact_pencil.pencil_coefficients_int(np.stack(e_cols, axis=1), np.stack(q_cols, axis=1))
        return e_cols, c

    def signs(self, values: np.ndarray) -> np.ndarray:
        return exact_signs(values)

    def deltas(self, c: list[np.ndarray]) -> tuple[np.ndarray, ...]:
        # Exact arithmetic may use the short form (27 Delta_4 = 4 I^3 - J^2): same signs.
        return tuple(kernels.paper_deltas_compact(*c))

    def delta_signs(self, c: list[np.ndarray]) -> np.ndarray:
        """The signs of the Deltas of the exact coefficients: binary64 first, with a rigorous
        bound (:func:`filtered_delta_signs`), the exact integers where that cannot tell (near
        a multiple root: tangencies).  Exact either way; the integer Deltas of coefficients of
        hundreds of bits were most of the exact stage's time."""
        sd = filtered_delta_signs(c)
        todo = np.flatnonzero((sd == UNCERTAIN).any(axis=1))
        if todo.size:
            sub = [x[todo] for x in c]
            sd[todo] = np.stack([self.signs(x) for x in self.deltas(sub)], axis=1)
        return sd

    def number(self, value: float) -> Any:
        return Fraction(value)

    def separation(self, pairs: Pairs) -> np.ndarray:
        """Float sample points first (cheap); where they do not separate the roots, exact
        sample points between the exactly isolated roots."""
        codes = super().separation(pairs)
        todo = np.flatnonzero(codes == UNCERTAIN)
        if todo.size:
            codes[todo] = separation_isolated(pairs.take(todo))
        return codes

    def smallness(self, pairs: Pairs) -> np.ndarray:
        return exact_smallness(self, pairs)

    def __repr__(self) -> str:
        return f"ExactMode(backend={self.backend!r})"


# -- ball ----------------------------------------------------------------------------------


class BallMode(ObjectMode):
    """Ball arithmetic (python-flint ``arb``) at ``prec`` bits.

    A sign is reported only when the ball excludes zero, or when the ball is
    exactly zero (arb propagates exact zeros: a product with an exact zero is an
    exact zero); otherwise ``UNCERTAIN``.  Float entries convert exactly, exact
    rationals are rounded into balls that contain them.
    """

    name = "ball"
    stage = "ball"
    certified = True
    before_exact_on_binary64: frozenset[str] = frozenset()
    """The methods worth running on binary64 input before the exact stage of a cascade: none of
    the criterion's.  The exact stage reads binary64 input with its compiled pencil and binary64
    Delta signs (:meth:`ExactMode.delta_signs`) and costs less than 128-bit balls, whether a few
    pairs reach it (5 pairs of the environment population: 0.51 ms against 0.68 ms) or many
    (17619 pairs the filter left of 2e5 random pairs: 270 ms against 665 ms)."""

    def __init__(self, prec: int = 128) -> None:
        super().__init__()
        if int(prec) < 2:
            raise ValueError("prec must be at least 2 bits")
        self.prec = int(prec)

    def context(self) -> AbstractContextManager[None]:
        """The working precision of the balls (:func:`~quadric_contact.exact.precision.working_precision`)."""
        return working_precision(self.prec)

    def number(self, value: float) -> Any:
        import flint  # import cost

        return flint.arb(value)

    def convert(self, stack: MatrixStack, rows: np.ndarray) -> list[np.ndarray]:
        import flint  # import cost

        def ball(v: Any) -> Any:
            if isinstance(v, Fraction):
                return flint.arb(flint.fmpq(v.numerator, v.denominator))
            return flint.arb(v)

        to = np.frompyfunc(ball, 1, 1)
        return [to(c) for c in stack.upper_exact(rows)]

    def signs(self, values: np.ndarray) -> np.ndarray:
        pos = np.asarray(values > 0, dtype=bool)
        neg = np.asarray(values < 0, dtype=bool)
        zero = np.frompyfunc(lambda x: x.is_zero(), 1, 1)(values).astype(bool)
        return np.where(pos, 1, np.where(neg, -1, np.where(zero, 0, UNCERTAIN))).astype(np.int8)

    def smallness(self, pairs: Pairs) -> np.ndarray:
        return object_smallness(self, pairs, BallNumbers(self.prec))

    def __repr__(self) -> str:
        return f"BallMode(prec={self.prec})"


# -- mpmath ------------------------------------------------------------------------------------


class MpmathMode(ObjectMode):
    """mpmath floating point at ``dps`` decimal digits (plain: no error bound, so,
    like ``float``, it answers everything and may be wrong where the exact value is
    tiny or zero).  The precision is set with
    :func:`~quadric_contact.exact.precision.working_precision` for each evaluation and restored
    afterwards."""

    name = "mpmath"
    stage = "mpmath"
    certified = False
    structural = True

    def classify(self, Q: MatrixStack, rows: np.ndarray | None = None) -> np.ndarray:
        """The type of each quadric, exactly (once per quadric): a structural zero such as a
        cylinder's ``det Q = 0`` is not left to the rounding of ``dps`` digits."""
        return ExactMode().classify(Q, rows)

    def __init__(self, dps: int = 50) -> None:
        super().__init__()
        if int(dps) < 1:
            raise ValueError("dps must be positive")
        self.dps = int(dps)
        # as for float: the crossings read from non-real roots are confirmed by a certified
        # reading at about the same precision (a double root of a symmetric placement reads as
        # a non-real pair at any number of digits; the pipeline then asks the separation stage)
        self.guard = BallMode(prec=int(self.dps * 3.33) + 8)

    def context(self) -> AbstractContextManager[None]:
        """mpmath's working digits (:func:`~quadric_contact.exact.precision.working_precision`)."""
        return working_precision(dps=self.dps)

    def separation_samples(self, c: list[np.ndarray]) -> np.ndarray:
        """The separation stage's sample points, between the roots of ``P`` found at the
        mode's digits (``mpmath.polyroots``): ``(n, 3)`` mpf midpoints of consecutive real
        roots where ``P`` has four, else NaN.  Binary64 roots of the rounded coefficients
        cannot place a point in a gap narrower than their error, where a definite member may
        lie alone (a spheroid deep in a cone: two roots ``1e-17`` apart), and the plain
        reading then calls the pair a crossing."""
        import mpmath  # import cost

        n = len(c[0])
        out = np.full((n, 3), math.nan, dtype=object)
        for p in range(n):
            coefficients = [c[j][p] for j in range(4, -1, -1)]
            if coefficients[0] == 0:
                continue
            try:
                roots = mpmath.polyroots(coefficients, maxsteps=200, extraprec=2 * mpmath.mp.prec)
            except mpmath.libmp.libhyper.NoConvergence:
                continue
            scale = max(abs(r) for r in roots) or mpmath.mpf(1)
            tiny = scale * mpmath.mpf(2) ** (-mpmath.mp.prec // 2)
            real = sorted(mpmath.re(r) for r in roots if abs(mpmath.im(r)) <= tiny)
            if len(real) == 4:
                out[p] = [(real[k] + real[k + 1]) / 2 for k in range(3)]
        return out

    def number(self, value: float) -> Any:
        import mpmath  # import cost

        return mpmath.mpf(value)

    def convert(self, stack: MatrixStack, rows: np.ndarray) -> list[np.ndarray]:
        import mpmath  # import cost

        def number(v: Any) -> Any:
            if isinstance(v, Fraction):
                return mpmath.mpf(v.numerator) / v.denominator
            return mpmath.mpf(v)

        to = np.frompyfunc(number, 1, 1)
        return [to(c) for c in stack.upper_exact(rows)]

    def signs(self, values: np.ndarray) -> np.ndarray:
        return exact_signs(values)

    def smallness(self, pairs: Pairs) -> np.ndarray:
        return object_smallness(self, pairs, MpmathNumbers(self.dps))

    def __repr__(self) -> str:
        return f"MpmathMode(dps={self.dps})"
