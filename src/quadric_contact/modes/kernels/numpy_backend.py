"""The numpy variant of the binary64 stages: the same functions on whole columns.

The fallback when numba is missing (``backend="numpy"``) and the reference the compiled
kernels are tested against: every quantity is computed with the same programs, in the same
order, on columns of pairs, so the codes are identical (tested).  ``filter_quantities`` and
``screen_quantities`` expose what the filter and its semi-static screen compute.

What runs here is the kernels' own source wherever that source runs on columns (one source, two
backends: :mod:`~quadric_contact.modes.kernels._jit`): the generated programs
(:mod:`quadric_contact._generated`), the three-valued signs and the index of the decision tables
(:mod:`~quadric_contact.modes.kernels.signs`), Dekker's product of
:mod:`~quadric_contact.modes.kernels.double_double` and the double-double programs.  The rest
mirrors, operation for operation, what the kernels write per pair with Python conditionals and
``min``/``max`` of scalars, which numpy cannot apply to columns: the input guard, the exact
test of proportional quadratic parts, the power-of-two scaling (bit work in the kernels,
``frexp``/``ldexp`` here), the filter's and the screen's guards and bounds, and the certified
ellipsoid test.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from quadric_contact._generated import blocks, dd_programs, formulas, kernels
from quadric_contact.exact.entries import ENTRY_INDICES
from quadric_contact.modes.codes import INVALID, UNCERTAIN
from quadric_contact.modes.decision.answers import (
    CONTACT_TABLE,
    ELLIPSOID_NOT,
    ELLIPSOID_UNCERTAIN,
    ELLIPSOID_YES,
    ellipsoid_from_signs,
)
from quadric_contact.modes.kernels import errorbounds as eb
from quadric_contact.modes.kernels.double_double import OPERATIONS, two_prod
from quadric_contact.modes.kernels.signs import columns, dd_sign_within, plain_sign, sign_index, sign_within
from quadric_contact.modes.kernels.support_drivers import region_codes_from_signs

__all__ = [
    "dd_invariant_quantities",
    "filter_quantities",
    "numpy_ellipsoid_signs",
    "numpy_invariant_signs",
    "numpy_pairs",
    "proportional_quadratic_parts",
    "screen_quantities",
    "table_index",
]

_QUADRATIC_PART = (0, 1, 2, 4, 5, 7)
"""Positions of ``q00, q01, q02, q11, q12, q22`` among the ten upper entries."""
_NO_EXPONENT = -100000


_NUMPY_CHUNK = 1 << 16


_sign_columns = columns(sign_within)
_plain_columns = columns(plain_sign)
_dd_sign_columns = columns(dd_sign_within)


def table_index(signs: list[np.ndarray]) -> np.ndarray:
    """The index into :data:`~quadric_contact.modes.decision.answers.CONTACT_TABLE` of the signs of
    ``Delta_2, Delta_3, Delta_4`` (columns), as the kernels make it with
    :func:`~quadric_contact.modes.kernels.signs.sign_index`."""
    s2, s3, s4 = (sign_index(np.asarray(s, dtype=np.intp)) for s in signs)
    index: np.ndarray = s2 + 4 * s3 + 16 * s4
    return index


def _outside(entries: list[np.ndarray]) -> np.ndarray:
    """The input guard of the kernels (``outside_count`` of the generated blocks), per column:
    an entry is above INPUT_MAX, not finite, or non-zero below INPUT_MIN."""
    absx = np.abs(np.stack(entries))
    return ((absx > eb.INPUT_MAX) | ~np.isfinite(absx) | ((absx < eb.INPUT_MIN) & (absx != 0))).any(axis=0)


def proportional_quadratic_parts(A_e: np.ndarray, A_q: np.ndarray) -> np.ndarray:
    """numpy variant of the kernels' exact test that ``A_q = k A_e`` (``(6, k)`` arrays of the
    quadratic parts' upper entries ``00, 01, 02, 11, 12, 22``): ``q_ij e00 == q00 e_ij``
    exactly, by Dekker's TwoProduct (:func:`~quadric_contact.modes.kernels.double_double.two_prod`,
    the kernels' product and error term), for entries that are zero or in ``[2^-400, 2^400]``."""
    with np.errstate(all="ignore"):
        absv = np.abs(np.concatenate([A_e, A_q]))
        tame = ((absv == 0) | ((absv >= 2.0**-400) & (absv <= 2.0**400))).all(axis=0) & (A_e[0] != 0)
        e00, q00 = A_e[0], A_q[0]
        ok = tame.copy()
        for t in range(1, 6):
            p, e1 = two_prod(A_q[t], e00)
            q, e2 = two_prod(q00, A_e[t])
            ok &= (p == q) & (e1 == e2)
    return ok


def filter_quantities(
    Em: np.ndarray,
    Qm: np.ndarray,
    *,
    rounded: bool = False,
    zflags: np.ndarray | None = None,
    same_ok: bool = True,
) -> dict[str, Any]:
    """Everything the filter computes for the pairs ``(Em[k], Qm[k])`` (numpy variant; the
    compiled kernels compute the same numbers in the same order).

    Keys: ``c``, ``r`` (coefficients for the paper's sign of E and their bounds),
    ``s`` (the power of two that scales each), ``x``, ``y`` (scaled), ``rho``, ``d`` (Delta_2..4 of
    ``x``), ``bound_relative``, ``bound_absolute`` (their two bounds), ``same``
    (equal quadratic parts), ``outside`` (a guard failed), ``ell`` (ellipsoid status),
    ``signs`` (the signs the filter reports for c0..c4 and Delta_2..4).
    """
    KP, KL, DR, DA = eb.filter_constants(rounded)
    k = Em.shape[0]
    z = np.zeros(k, dtype=np.int8) if zflags is None else zflags
    e = [Em[:, i, j] for i, j in ENTRY_INDICES]
    q = [Qm[:, i, j] for i, j in ENTRY_INDICES]
    with np.errstate(all="ignore"):
        c = list(formulas.pencil_coefficients(*e, *q))
        mi = kernels.leading_minors_3(e[0], e[1], e[2], e[4], e[5], e[7])
        c[0] = np.where(z & 1, 0.0, c[0])
        c[1] = np.where(z & 2, 0.0, c[1])
        A_e = np.stack([e[t] for t in (0, 1, 2, 4, 5, 7)])
        A_q = np.stack([q[t] for t in (0, 1, 2, 4, 5, 7)])
        same = same_ok & proportional_quadratic_parts(A_e, A_q)
        mc = kernels.pencil_coefficients_magnitude(*(np.abs(v) for v in e + q))
        mm = kernels.leading_minors_3_magnitude(*(np.abs(e[t]) for t in (0, 1, 2, 4, 5, 7)))
        r = [KP[t] * mc[t] for t in range(5)]
        r[0] = np.where(z & 1, 0.0, r[0])
        r[1] = np.where(z & 2, 0.0, r[1])
        sm = [_sign_columns(mi[t], KL[t] * mm[t]) for t in range(2)]
        outside = _outside(e + q)
        sa = _plain_columns(e[0])
        ell = ellipsoid_from_signs(sa, sm[0], sm[1], _sign_columns(c[4], r[4]))
        o = np.where(e[0] < 0, -1.0, 1.0)
        c[1] = o * c[1]
        c[3] = o * c[3]
        # c_k times 2^(g + m k), as the kernels scale (see there)
        tk = [np.abs(c[t]) + r[t] for t in range(5)]
        ek = [np.where(v == 0, _NO_EXPONENT, np.frexp(v)[1] - 1) for v in tk]
        low = np.where(ek[0] != _NO_EXPONENT, ek[0], np.where(ek[1] != _NO_EXPONENT, ek[1], ek[2]))
        m = np.where(low != _NO_EXPONENT, np.clip((low - ek[4]) >> 2, -400, 400), 0)
        g = -np.maximum.reduce([ek[t] + t * m for t in range(5)])
        s = [np.where(tk[t] == 0, 1.0, np.ldexp(1.0, np.clip(g + t * m, -1022, 1023))) for t in range(5)]
        x = [c[t] * s[t] for t in range(5)]
        y = [r[t] * s[t] for t in range(5)]
        a = [np.abs(v) for v in x]
        for t in range(5):
            outside |= ((c[t] != 0) & (a[t] < eb.COEFFICIENT_MIN)) | (
                (r[t] != 0) & (a[t] + y[t] < eb.COEFFICIENT_MIN)
            )
            outside |= (r[t] != 0) & (y[t] < 2.0**-1022)
        den = [np.where(a[t] != 0, a[t], np.where(y[t] == 0, 1e300, eb.COEFFICIENT_MIN)) for t in range(5)]
        rho = np.maximum.reduce(y) / np.minimum.reduce(den)
        d = list(formulas.paper_deltas(*x))
        A = list(kernels.paper_deltas_magnitude(*a))
        d[2] = np.where(same, 0.0, d[2])
        A[2] = np.where(same, 0.0, A[2])
        b = [(a[t] + y[t]) * eb.ROUND_UP for t in range(5)]
        Bm = kernels.paper_deltas_magnitude(*b)
        bound_rel = [(DR[j, 0] * rho + DR[j, 1]) * A[j] for j in range(3)]
        bound_abs = [DA[j, 0] * (Bm[j] - A[j]) + DA[j, 1] * A[j] for j in range(3)]
        bound_abs[2] = np.where(same, 0.0, bound_abs[2])
        rel = [_sign_columns(d[j], bound_rel[j]) for j in range(3)]
        absolute = [_sign_columns(d[j], bound_abs[j]) for j in range(3)]
        tier_a = CONTACT_TABLE[table_index(rel)]
        use_b = (rho > eb.RHO_MAX) | (tier_a == UNCERTAIN)
        ds = [np.where(use_b, absolute[j], rel[j]).astype(np.int8) for j in range(3)]
        cs = [_sign_columns(x[t], y[t]) for t in range(5)]
    return {
        "c": c,
        "r": r,
        "s": s,
        "x": x,
        "y": y,
        "rho": rho,
        "d": d,
        "bound_relative": bound_rel,
        "bound_absolute": bound_abs,
        "same": same,
        "outside": outside,
        "ell": ell,
        "signs": cs + ds,
    }


def screen_quantities(Em: np.ndarray, Qm: np.ndarray) -> dict[str, Any]:
    """The semi-static screen's quantities for the pairs ``(Em[k], Qm[k])`` of binary64 matrices
    (numpy variant of :func:`~quadric_contact.modes.kernels.criterion._screen_core`: the same
    programs in the same order, hence the same bits).

    Keys: ``c`` (coefficients, the paper's sign of ``E``), ``r`` (their bounds), ``rho``, ``d``
    (the compact ``Delta_2, Delta_3, 27 Delta_4``), ``bound`` (their bounds), ``ok`` (every
    guard passed and ``E`` is certainly an ellipsoid), ``signs`` (of ``c0 .. c4`` and the three
    Deltas, three-valued).
    """
    e = [Em[:, i, j] for i, j in ENTRY_INDICES]
    q = [Qm[:, i, j] for i, j in ENTRY_INDICES]
    SP = eb.SEMI_PENCIL
    SD = eb.SEMI_DELTA
    with np.errstate(all="ignore"):
        ae = [np.abs(v) for v in e]
        aq = [np.abs(v) for v in q]
        R = _row_maxima(ae)
        T = _row_maxima(aq)
        asym = ~(
            (Em == np.swapaxes(Em, 1, 2)).all(axis=(1, 2)) & (Qm == np.swapaxes(Qm, 1, 2)).all(axis=(1, 2))
        )
        guard = _guard(ae, R) & _guard(aq, T) & ~asym
        c = list(blocks.pencil(tuple(e), tuple(q)))
        W = blocks.row_bound(*R, *T)
        plane = np.maximum.reduce([aq[t] for t in (0, 1, 2, 4, 5, 7)]) == 0
        r = [SP[k] * W[k] for k in range(5)]
        r[0] = np.where(plane, 0.0, r[0])
        r[1] = np.where(plane, 0.0, r[1])
        ell, o = _certified_ellipsoid(e, R, c[4], r[4])
        c[1] = o * c[1]
        c[3] = o * c[3]
        a = [np.abs(v) for v in c]
        small = np.minimum.reduce([np.where(v != 0, v, 1.0) for v in a])
        rng = (a[0] + a[1] + a[2] + a[3] + a[4] <= eb.SEMI_COEFFICIENT_MAX) & (small >= eb.COEFFICIENT_MIN)
        tiny = 2.0**-1000
        rho = np.maximum(
            np.maximum(
                np.maximum(r[0] / (a[0] + tiny), r[1] / (a[1] + tiny)),
                np.maximum(r[2] / (a[2] + tiny), r[3] / (a[3] + tiny)),
            ),
            r[4] / (a[4] + tiny),
        )
        ok = guard & ell & rng & (rho <= eb.RHO_MAX)
        both = blocks.paper_deltas_compact_and_magnitude(*c)  # the magnitudes at a = |c|
        d, A = list(both[:3]), list(both[3:])
        d[2] = np.where(plane, 0.0, d[2])
        A[2] = np.where(plane, 0.0, A[2])
        bound = [(SD[j][0] * rho + SD[j][1]) * A[j] for j in range(3)]
    signs = [_plain_columns(v) for v in c] + [_sign_columns(d[j], bound[j]) for j in range(3)]
    return {"c": c, "r": r, "rho": rho, "d": d, "bound": bound, "ok": ok, "signs": signs}


def numpy_ellipsoid_signs(Qm: np.ndarray) -> np.ndarray:
    """numpy variant of :func:`~quadric_contact.modes.kernels.support._ellipsoid_signs_impl`
    (the same programs in the same order, hence the same bits): +1/-1 where the binary64
    quadric ``Qm[k]`` is certainly an ellipsoid of that canonical sign, 0 where the test cannot
    tell."""
    q = [Qm[:, i, j] for i, j in ENTRY_INDICES]
    with np.errstate(all="ignore"):
        a = [np.abs(v) for v in q]
        R = _row_maxima(a)
        guard = _guard(a, R)
        W = blocks.row_bound(R[0], R[1], R[2], R[3], 0.0, 0.0, 0.0, 0.0)
        ell, o = _certified_ellipsoid(q, R, blocks.pencil_e_part(tuple(q))[12], eb.SEMI_PENCIL[4] * W[4])
    return np.where(guard & ell, o, 0.0).astype(np.int8)


def _certified_ellipsoid(
    e: list[np.ndarray], R: list[np.ndarray], det: np.ndarray, det_bound: np.ndarray | float
) -> tuple[np.ndarray, np.ndarray]:
    """numpy variant of :func:`~quadric_contact.modes.kernels.support.certified_ellipsoid`."""
    m2, m3 = kernels.leading_minors_3(e[0], e[1], e[2], e[4], e[5], e[7])
    o = np.where(e[0] < 0, -1.0, 1.0)
    SM2, SM3 = eb.SEMI_MINORS
    definite = (e[0] != 0) & (m2 > SM2 * (R[0] * R[1])) & (o * m3 > SM3 * ((R[0] * R[1]) * R[2]))
    return definite & (det < -det_bound), o


def _row_maxima(a: list[np.ndarray]) -> list[np.ndarray]:
    m = [[a[ENTRY_INDICES.index((min(r, s), max(r, s)))] for s in range(4)] for r in range(4)]
    return [np.maximum(np.maximum(row[0], row[1]), np.maximum(row[2], row[3])) for row in m]


def _guard(a: list[np.ndarray], R: list[np.ndarray]) -> np.ndarray:
    top = np.maximum(np.maximum(R[0], R[1]), np.maximum(R[2], R[3]))
    low = np.minimum.reduce([np.where(v != 0, v, eb.INPUT_MAX) for v in a])
    return (top <= eb.INPUT_MAX) & (low >= eb.INPUT_MIN)


def numpy_pairs(
    E: np.ndarray,
    Q: np.ndarray,
    eidx: np.ndarray,
    qidx: np.ndarray,
    es: int,
    qs: int,
    n: int,
    filtered: bool,
    rounded: bool,
    rows: np.ndarray,
    masks: np.ndarray,
    want_region: bool,
    qflags: np.ndarray,
    same_ok: bool,
    prop: np.ndarray,
    screen: bool = False,
) -> np.ndarray:
    """Codes of ``n`` pairs (numpy variant of the compiled kernels; ``screen``: the filter's
    first pass on binary64 input, where the semi-static screen decides first)."""
    out = np.empty(n, dtype=np.int8)
    for lo in range(0, n, _NUMPY_CHUNK):
        hi = min(n, lo + _NUMPY_CHUNK)
        p = np.arange(lo, hi)
        ie = eidx[lo:hi] if eidx.shape[0] else p * es
        iq = qidx[lo:hi] if qidx.shape[0] else p * qs
        Em, Qm = E[ie], Q[iq]
        bad = ~(np.isfinite(Em).all(axis=(1, 2)) & np.isfinite(Qm).all(axis=(1, 2)))
        bad |= ~(
            (Em == np.swapaxes(Em, 1, 2)).all(axis=(1, 2)) & (Qm == np.swapaxes(Qm, 1, 2)).all(axis=(1, 2))
        )
        if filtered:
            fq = filter_quantities(Em, Qm, rounded=rounded, zflags=qflags[iq], same_ok=same_ok)
            signs, ell = fq["signs"], fq["ell"]
            sq = screen_quantities(Em, Qm) if screen else None
        else:
            e = [Em[:, i, j] for i, j in ENTRY_INDICES]
            q = [Qm[:, i, j] for i, j in ENTRY_INDICES]
            with np.errstate(all="ignore"):
                c = list(formulas.pencil_coefficients(*e, *q))
                z = qflags[iq]
                c[0] = np.where(z & 1, 0.0, c[0])
                c[1] = np.where(z & 2, 0.0, c[1])
                mi = kernels.leading_minors_3(e[0], e[1], e[2], e[4], e[5], e[7])
                ell = ellipsoid_from_signs(
                    _plain_columns(e[0]),
                    _plain_columns(mi[0]),
                    _plain_columns(mi[1]),
                    _plain_columns(c[4]),
                )
                o = np.where(e[0] < 0, -1.0, 1.0)
                c[1] = o * c[1]
                c[3] = o * c[3]
                d = list(formulas.paper_deltas(*c))
                if prop.shape[0] > 0:
                    d[2] = np.where(prop[lo:hi] != 0, 0.0, d[2])
                elif same_ok:
                    A_e = np.stack([e[t] for t in (0, 1, 2, 4, 5, 7)])
                    A_q = np.stack([q[t] for t in (0, 1, 2, 4, 5, 7)])
                    d[2] = np.where(proportional_quadratic_parts(A_e, A_q), 0.0, d[2])
                signs = [_plain_columns(v) for v in c] + [_plain_columns(v) for v in d]
        contact = CONTACT_TABLE[table_index(signs[5:])]
        if want_region:
            code = region_codes_from_signs(
                contact.astype(np.int8), np.stack(signs[:5], axis=1), rows[iq], masks[iq]
            )
        else:
            code = contact.astype(np.int8)
        if filtered:
            code = np.where(fq["outside"] | (ell == ELLIPSOID_UNCERTAIN), UNCERTAIN, code)
            invalid = bad | (ell == ELLIPSOID_NOT)
            if sq is not None:
                # the screen first: where it is sure, its answer (the filter agrees where both are)
                s_contact = CONTACT_TABLE[table_index(sq["signs"][5:])]
                if want_region:
                    s_code = region_codes_from_signs(
                        s_contact.astype(np.int8), np.stack(sq["signs"][:5], axis=1), rows[iq], masks[iq]
                    )
                else:
                    s_code = s_contact.astype(np.int8)
                screened = sq["ok"] & (s_code != UNCERTAIN)
                code = np.where(screened, s_code, code)
        else:
            invalid = bad | (ell != ELLIPSOID_YES)
        out[lo:hi] = np.where(invalid, INVALID, code)
    return out


def _dd_read(
    q: list[np.ndarray], mags: list[np.ndarray], static: np.ndarray, cofactor: np.ndarray
) -> tuple[Any, list[np.ndarray]]:
    """The double-double invariants of the columns ``q`` (the ten upper entries) and their
    bounds: the smaller of ``static`` times the binary64 magnitudes ``mags`` and, for ``JA``,
    ``detA``, ``E4``, ``cofactor`` times the magnitudes of their cofactor forms (as the kernel)."""
    C = dd_programs.adjugate_3_dd(*OPERATIONS, *(q[k] for k in _QUADRATIC_PART))
    w = dd_programs.quadric_invariants_dd(*OPERATIONS, *q, *C)
    mc = dd_programs.quadric_invariants_cofactor_magnitude(
        *(np.abs(x) for x in q), *(np.abs(c[0]) for c in C)
    )
    bounds = [static[k] * mags[k] for k in range(7)]
    for j, at in enumerate(eb.COFACTOR_AT):
        bounds[at] = np.minimum(bounds[at], cofactor[j] * mc[j])
    return w, bounds


def dd_invariant_quantities(Qm: np.ndarray) -> dict[str, Any]:
    """The double-double reading of the invariants of the ``(m, 4, 4)`` binary64 quadrics ``Qm``,
    on columns, for every quadric (for tests and measurements; the modes run it only where
    binary64 cannot tell): ``hi``, ``lo`` (seven arrays each: the words of ``trA, JA, detA, E1 ..
    E4``), ``bound`` (seven arrays: ``|hi + lo - exact| <= bound``), ``signs`` (``(m, 7)``, as
    :func:`numpy_invariant_signs` reads them) and ``outside`` (the input guard: where it is set,
    nothing holds)."""
    q = [np.asarray(Qm[:, i, j], dtype=np.float64) for i, j in ENTRY_INDICES]
    with np.errstate(all="ignore"):
        mags = kernels.quadric_invariants_magnitude(*(np.abs(x) for x in q))
        outside = _outside(q)
        w, bounds = _dd_read(
            q, list(mags), np.array(eb.INVARIANTS_DD_ERRBOUND), np.array(eb.INVARIANTS_DD_COFACTOR_ERRBOUND)
        )
        signs = np.stack([_dd_sign_columns(w[k], bounds[k]) for k in range(7)], axis=1)
    return {
        "hi": [v[0] for v in w],
        "lo": [v[1] for v in w],
        "bound": bounds,
        "signs": np.where(outside[:, None], UNCERTAIN, signs).astype(np.int8),
        "outside": outside,
    }


def numpy_invariant_signs(
    Q: np.ndarray, filtered: bool, K: np.ndarray, KD: tuple[np.ndarray, np.ndarray] | None = None
) -> np.ndarray:
    """As the kernel ``invariant_signs_kernel``, on columns; ``KD`` (binary64 input only): read
    the quadrics with a sign binary64 cannot tell again in double-double, with these bounds
    (static, and for the cofactor forms)."""
    q = [Q[:, i, j] for i, j in ENTRY_INDICES]
    out = np.empty((Q.shape[0], 8), dtype=np.int8)
    with np.errstate(all="ignore"):
        v = kernels.quadric_invariants(*q)
        if filtered:
            mags = kernels.quadric_invariants_magnitude(*(np.abs(x) for x in q))
            outside = _outside(q)
        for k in range(7):
            if filtered:
                out[:, k] = np.where(outside, UNCERTAIN, _sign_columns(v[k], K[k] * mags[k]))
            else:
                out[:, k] = _plain_columns(v[k])
        if filtered and KD is not None:
            todo = np.flatnonzero(~outside & (out[:, :7] == UNCERTAIN).any(axis=1))
            if todo.size:
                w, bounds = _dd_read([x[todo] for x in q], [m[todo] for m in mags], *KD)
                for k in range(7):
                    s = _dd_sign_columns(w[k], bounds[k])
                    out[todo, k] = np.where(out[todo, k] == UNCERTAIN, s, out[todo, k])
    out[:, 7] = _plain_columns(q[9])
    return out
