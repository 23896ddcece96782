"""Contact maps: the answers of the predicates over a grid of two parameters, and a picture
with the exact boundary curves.

What a cell means
-----------------
The rectangle ``[a, b] x [c, d]`` of the two parameters ``(u, w)`` is cut into
``n_u x n_w`` cells.  The *centre* of cell ``(i, j)`` is the point
``(u_i, w_j)`` where ``u_i`` is the binary64 number nearest to the exact rational
``a + (i + 1/2)(b - a)/n_u`` (and ``w_j`` likewise).  The cell's answer is the answer of
the public predicates, certified, for the exact pair ``(E(u_i, w_j), Q(u_i, w_j))`` (the
entries evaluated exactly at that binary64 point), with the values of the other parameters
fixed exactly:

* :data:`MapAnswer.CONTACT`: transversal contact (``relative_position`` says contact);
* :data:`MapAnswer.TOUCHING`: no transversal contact but the surfaces touch
  (``contact_kind`` gives one or two tangent points or a curve of tangency);
* :data:`MapAnswer.R_MINUS` / :data:`MapAnswer.R_PLUS`: ``E`` lies in ``R-`` / ``R+``
  without touching ``Q`` (``relative_position``);
* :data:`MapAnswer.UNDEFINED`: ``E`` is not a real ellipsoid there, an entry has a pole, or
  the predicates refuse ``Q`` (a cone, for instance).

``contact_kind`` is asked only where a tangency is possible: a tangency gives ``P`` a
multiple root (see :attr:`Family.boundaries`), so where the certified sign of
``Delta_4`` (of the plane discriminant for a plane) at the centre is not zero, the pair
does not touch; where ``Delta_4`` vanishes identically it is asked everywhere.

Refinement for display
----------------------
A cell whose answer differs from a neighbour's, or across which a boundary polynomial
(:attr:`Family.boundaries`) may change sign (its certified signs at the four corners and
the centre are not one and the same non-zero sign), is cut into ``2^refine x 2^refine``
subcells, each decided in the same way at its own centre.  The picture draws each cell
(and each subcell) in the colour of the answer at its centre: a colour is never wrong,
for its centre; a cell that is not refined may still contain points with another answer
beyond the resolution (the boundary curves drawn on top show where).
"""

from __future__ import annotations

import contextlib
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from enum import IntEnum
from fractions import Fraction
from typing import TYPE_CHECKING, Any

import flint
import numpy as np

from quadric_contact.exact.entries import ENTRY_INDICES
from quadric_contact.exact.errors import QuadricContactError, ShapeError
from quadric_contact.exact.optional import pyplot
from quadric_contact.exact.rational import to_fraction
from quadric_contact.families.family_numeric import _numpy_signs, compile_quantity
from quadric_contact.families.rational_functions import RationalFunction
from quadric_contact.modes.numbers.registry import get_mode
from quadric_contact.modes.stacks.batch import as_stack, make_pairs
from quadric_contact.modes.stacks.pairs import MatrixStack

if TYPE_CHECKING:
    from quadric_contact.families.family import Family

__all__ = ["MAP_COLOURS", "ContactMap", "MapAnswer", "contact_map"]


class MapAnswer(IntEnum):
    """The answer drawn in a cell of a :class:`ContactMap` (int8 codes)."""

    R_MINUS = -1
    CONTACT = 0
    R_PLUS = 1
    TOUCHING = 3
    UNDEFINED = 4


MAP_COLOURS: dict[MapAnswer, str] = {
    MapAnswer.R_MINUS: "#9ecae1",
    MapAnswer.CONTACT: "#d62728",
    MapAnswer.R_PLUS: "#c7e9c0",
    MapAnswer.TOUCHING: "#000000",
    MapAnswer.UNDEFINED: "#d9d9d9",
}
"""Colour of each answer in :meth:`ContactMap.plot`."""

_LABELS = {
    MapAnswer.R_MINUS: "R- (X^T Q X <= 0)",
    MapAnswer.CONTACT: "transversal contact",
    MapAnswer.R_PLUS: "R+ (X^T Q X >= 0)",
    MapAnswer.TOUCHING: "touching",
    MapAnswer.UNDEFINED: "E not an ellipsoid / undefined",
}


def _centres(lo: Fraction, hi: Fraction, n: int, k: int = 1) -> np.ndarray:
    """Binary64 nearest to ``lo + (i + 1/2)(hi - lo)/(n k)`` for ``i < n k``."""
    step = (hi - lo) / (n * k)
    return np.array([float(lo + (i + Fraction(1, 2)) * step) for i in range(n * k)], dtype=np.float64)


def _edges(lo: Fraction, hi: Fraction, n: int) -> np.ndarray:
    return np.array([float(lo + i * (hi - lo) / n) for i in range(n + 1)], dtype=np.float64)


class _Decider:
    """Decides the answer at binary64 points of a two-parameter family (see the module docstring).

    The pairs go to the certified mode's stack questions exactly as
    :func:`~quadric_contact.relative_position` and :func:`~quadric_contact.contact_kind`
    send a stack (:func:`~quadric_contact.modes.stacks.batch.run_stack`); only the conversion of the
    input is done here, from the exact entries, with the binary64 roundings the float
    stages read (as :func:`~quadric_contact.modes.stacks.batch.as_stack` makes them for exact input).
    """

    def __init__(self, fam: Family) -> None:
        self.fam = fam
        self.mode = get_mode("certified")
        self.calls = 0
        self.touch_checks = 0
        # Is E a real ellipsoid?  The leading minors of its quadratic part and det E.
        self.checks = [fam.quantity(n).value for n in ("E minor 1", "E minor 2", "E minor 3", "c4")]
        if fam.q_is_plane:
            self.discriminant = "plane discriminant"
        elif not fam.quantity("Delta4").value.is_zero():
            self.discriminant = "Delta4"
        else:
            self.discriminant = ""  # a multiple root everywhere: ask contact_kind everywhere
        self.disc_sign = fam.lambdify(self.discriminant, "certified") if self.discriminant else None

    @staticmethod
    def _exact(value: Any, args: list[list[Any]]) -> list[Fraction | None]:
        """Exact values at the points (flint rationals per point); None at a pole."""
        if value.is_constant:
            c = value.evaluate([0] * len(value.context.names()))
            return [c] * len(args)
        num, den = value.num, value.den
        out: list[Fraction | None] = []
        if value.is_polynomial:
            for a in args:
                q = num(*a)
                out.append(Fraction(int(q.p), int(q.q)))
            return out
        for a in args:
            d = den(*a)
            if d == 0:
                out.append(None)
                continue
            q = num(*a) / d
            out.append(Fraction(int(q.p), int(q.q)))
        return out

    def _stack(self, entries: Sequence[Any], args: list[list[Any]], name: str) -> tuple[Any, np.ndarray]:
        n = len(args)
        exact = np.empty((n, 10), dtype=object)
        floats = np.empty((n, 4, 4), dtype=np.float64)
        ok = np.ones(n, dtype=bool)
        dyadic = True
        for t, ((i, j), v) in enumerate(zip(ENTRY_INDICES, entries, strict=True)):
            vals = self._exact(v, args)
            if v.is_constant:
                c = vals[0] if n else Fraction(0)
                assert c is not None
                f = float(c)
                exact[:, t] = c
                floats[:, i, j] = floats[:, j, i] = f
                dyadic = dyadic and Fraction(f) == c
                continue
            col = np.empty(n, dtype=np.float64)
            for k, x in enumerate(vals):
                if x is None:
                    ok[k] = False
                    x = Fraction(0)
                exact[k, t] = x
                p, q = x.numerator, x.denominator
                col[k] = p / q  # correctly rounded (integer true division)
                dyadic = dyadic and q & (q - 1) == 0 and -(2**53) < p < 2**53
            floats[:, i, j] = floats[:, j, i] = col
        return MatrixStack(floats, None if dyadic else exact, True, name, (n,)), ok

    def decide(self, us: np.ndarray, ws: np.ndarray) -> np.ndarray:
        """The answers at the points ``(us[k], ws[k])`` (binary64)."""
        n = len(us)
        out = np.full(n, MapAnswer.UNDEFINED, dtype=np.int8)
        if n == 0:
            return out
        args = [
            [flint.fmpq(*float(u).as_integer_ratio()), flint.fmpq(*float(w).as_integer_ratio())]
            for u, w in zip(us, ws, strict=True)
        ]
        signs = []
        for v in self.checks:
            vals = self._exact(v, args)
            signs.append(np.array([0 if x is None else (x > 0) - (x < 0) for x in vals], dtype=np.int8))
        m1, m2, m3, det = signs
        valid = ((m1 > 0) & (m2 > 0) & (m3 > 0) & (det < 0)) | ((m1 < 0) & (m2 > 0) & (m3 < 0) & (det > 0))
        idx = np.flatnonzero(valid)
        if idx.size == 0:
            return out
        sub = [args[k] for k in idx]
        E, ok_e = self._stack(self.fam._e, sub, "E")
        if all(v.is_constant for v in self.fam._q):
            Q, ok_q = as_stack(self.fam.Q_reference, "Q"), np.ones(len(sub), dtype=bool)
        else:
            Q, ok_q = self._stack(self.fam._q, sub, "Q")
        if not ok_e.all() or not ok_q.all():  # a pole: leave those points undefined
            keep = ok_e & ok_q
            return self._decide_subset(us, ws, idx[keep], out)
        pairs, _ = make_pairs(E, Q)
        self.calls += int(idx.size)
        try:
            region = np.asarray(self.mode.region(pairs), dtype=np.int8)
        except QuadricContactError:
            region = self._one_by_one("region", E, Q)
        out[idx] = region
        # touching: only where a multiple root is possible
        undefined = region == MapAnswer.UNDEFINED
        if self.disc_sign is not None:
            s = self.disc_sign(us[idx], ws[idx])
            cand = np.flatnonzero(((s == 0) | (s == 2)) & (region != MapAnswer.CONTACT) & ~undefined)
        else:
            cand = np.flatnonzero((region != MapAnswer.CONTACT) & ~undefined)
        if cand.size:
            self.touch_checks += int(cand.size)
            try:
                kinds = np.asarray(self.mode.kind(pairs.take(cand)), dtype=np.int8)
            except QuadricContactError:
                kinds = self._one_by_one("kind", E, Q)[cand]
            touching = np.isin(kinds, (3, 4, 5))
            out[idx[cand[touching]]] = MapAnswer.TOUCHING
        return out

    def _decide_subset(self, us: np.ndarray, ws: np.ndarray, idx: np.ndarray, out: np.ndarray) -> np.ndarray:
        out[idx] = self.decide(us[idx], ws[idx])
        return out

    def _one_by_one(self, question: str, E: Any, Q: Any) -> np.ndarray:
        """Pair by pair, where a stack was refused (the refused pairs are undefined)."""
        pairs, _ = make_pairs(E, Q)
        res = np.full(pairs.n, MapAnswer.UNDEFINED, dtype=np.int8)
        for k in range(pairs.n):
            with contextlib.suppress(QuadricContactError):
                res[k] = int(np.asarray(getattr(self.mode, question)(pairs.take(np.array([k]))))[0])
        return res


@dataclass
class ContactMap:
    """The answers over a grid of two parameters (see the module docstring for what a cell means).

    Attributes
    ----------
    family : Family
        The two-parameter family (the others fixed).
    names : tuple of str
        The two parameters, horizontal then vertical.
    ranges : tuple of (Fraction, Fraction)
    u, w : numpy arrays
        The binary64 cell centres.
    codes : int8 array, shape (n_u, n_w)
        :class:`MapAnswer` at each cell centre.
    refine : int
        Levels of subdivision of the refined cells.
    fine : int8 array, shape (n_u 2^refine, n_w 2^refine)
        The picture: the answer at each subcell centre in refined cells, the cell's answer
        elsewhere.
    refined : bool array, shape (n_u, n_w)
    fixed : dict
        The other parameters' values.
    stats : dict
        Cells, subcells, predicate calls, touching checks, seconds.
    """

    family: Family
    names: tuple[str, str]
    ranges: tuple[tuple[Fraction, Fraction], tuple[Fraction, Fraction]]
    u: np.ndarray
    w: np.ndarray
    codes: np.ndarray
    refine: int
    fine: np.ndarray
    refined: np.ndarray
    fixed: dict[str, Fraction] = field(default_factory=dict)
    stats: dict[str, Any] = field(default_factory=dict)

    def counts(self) -> dict[str, int]:
        """How many cells have each answer."""
        return {a.name: int(np.sum(self.codes == a)) for a in MapAnswer if np.any(self.codes == a)}

    def cell(self, i: int, j: int) -> tuple[dict[str, float], MapAnswer]:
        """The centre of cell ``(i, j)`` and its answer."""
        return {self.names[0]: float(self.u[i]), self.names[1]: float(self.w[j])}, MapAnswer(
            int(self.codes[i, j])
        )

    def subcell_centres(self) -> tuple[np.ndarray, np.ndarray]:
        """The binary64 centres of the columns and rows of :attr:`fine`."""
        k = 2**self.refine
        (a, b), (c, d) = self.ranges
        return _centres(a, b, len(self.u), k), _centres(c, d, len(self.w), k)

    def plot(
        self,
        path: Any = None,
        *,
        ax: Any = None,
        curves: bool = True,
        extra_curves: Sequence[str] = (),
        points: int = 48,
        title: str | None = None,
    ) -> Any:
        """Draw the map with the boundary curves on top; save it to ``path`` if given.

        The curves are the zero sets of the irreducible factors of the boundary polynomials
        (:attr:`Family.boundaries`, and the quantities named in ``extra_curves``, e.g. a
        smallness condition): drawn as the zero contour of the exact polynomial evaluated on
        a fine grid, with points of the curve located exactly (certified real roots of the
        polynomial on ``points`` vertical and horizontal lines) marked on it.

        Returns
        -------
        matplotlib Figure
        """
        plt = pyplot("contact maps")
        from matplotlib.colors import ListedColormap  # optional (the plot extra)
        from matplotlib.lines import Line2D  # optional (the plot extra)
        from matplotlib.patches import Patch  # optional (the plot extra)

        if ax is None:
            fig, ax = plt.subplots(figsize=(7, 6))
        else:
            fig = ax.figure
        (a, b), (c, d) = self.ranges
        order = [
            MapAnswer.R_MINUS,
            MapAnswer.CONTACT,
            MapAnswer.R_PLUS,
            MapAnswer.TOUCHING,
            MapAnswer.UNDEFINED,
        ]
        index = {int(x): k for k, x in enumerate(order)}
        img = np.vectorize(index.get)(self.fine).astype(float)
        cmap = ListedColormap([MAP_COLOURS[x] for x in order])
        ax.imshow(
            img.T,
            origin="lower",
            extent=(float(a), float(b), float(c), float(d)),
            cmap=cmap,
            vmin=-0.5,
            vmax=len(order) - 0.5,
            interpolation="nearest",
            aspect="auto",
        )
        handles: list[Any] = [
            Patch(color=MAP_COLOURS[x], label=_LABELS[x]) for x in order if np.any(self.fine == x)
        ]
        if curves:
            styles = ["-", "--", ":", "-."]
            colours = ["#4d004b", "#08306b", "#7f2704", "#00441b", "#3f007d"]
            polys = [(bd.name, bd.factors) for bd in self.family.boundaries]
            for name in extra_curves:
                q = self.family.quantity(name)
                _, factors = q.numerator.factor()
                polys.append((name, tuple(f for f, _ in factors if not f.is_constant())))
            for k, (name, factors) in enumerate(polys):
                style, colour = styles[k % len(styles)], colours[k % len(colours)]
                drawn = False
                for f in factors:
                    drawn |= _draw_curve(
                        ax, f, (float(a), float(b)), (float(c), float(d)), colour, style, points
                    )
                if drawn:
                    label = f"{name} = 0"
                    if "=" in name:  # a smallness condition: where its two sides are equal
                        label = name.replace(" <= ", " = ").replace(" >= ", " = ")
                    handles.append(Line2D([], [], color=colour, linestyle=style, label=label))
        ax.set_xlim(float(a), float(b))
        ax.set_ylim(float(c), float(d))
        ax.set_xlabel(self.names[0])
        ax.set_ylabel(self.names[1])
        fixed = ", ".join(f"{k} = {v}" for k, v in self.fixed.items())
        ax.set_title(title or ("contact map" + (f" ({fixed})" if fixed else "")), fontsize=10)
        ax.legend(handles=handles, fontsize=7, loc="upper right", framealpha=0.85)
        if path is not None:
            fig.savefig(path, dpi=120, bbox_inches="tight")
        return fig


def _draw_curve(
    ax: Any, f: Any, ur: tuple[float, float], wr: tuple[float, float], colour: str, style: str, points: int
) -> bool:
    """The zero set of the polynomial ``f`` in two variables: a zero contour of its exact
    value (float evaluation of the generated program) and certified points on lines."""
    cq = compile_quantity("curve", RationalFunction(f), 2)
    n = 600
    U, W = np.meshgrid(np.linspace(*ur, n), np.linspace(*wr, n), indexing="ij")
    F = cq.functions["quantity"](U, W)[0] * np.ones_like(U)
    drawn = False
    if np.nanmin(F) <= 0 <= np.nanmax(F):
        ax.contour(U, W, F, levels=[0.0], colors=[colour], linestyles=[style], linewidths=1.3)
        drawn = True
    us: list[float] = []
    ws: list[float] = []
    for axis in (0, 1):
        lo, hi = (ur, wr)[axis]
        olo, ohi = (wr, ur)[axis]
        for t in np.linspace(lo, hi, points + 2)[1:-1]:
            for r in _real_roots_on_line(f, axis, Fraction(float(t)), olo, ohi):
                (us, ws)[axis].append(float(t))
                (ws, us)[axis].append(r)
    if us:
        ax.plot(us, ws, linestyle="none", marker=".", markersize=2.5, color=colour)
        drawn = True
    return drawn


def _real_roots_on_line(f: Any, axis: int, t: Fraction, lo: float, hi: float) -> list[float]:
    """The real roots in ``[lo, hi]`` of ``f`` with variable ``axis`` set to ``t`` (certified
    isolation by python-flint), as floats."""
    coeffs: dict[int, Any] = {}
    tq = flint.fmpq(t.numerator, t.denominator)
    for mono, c in f.to_dict().items():
        e_fixed, e_free = int(mono[axis]), int(mono[1 - axis])
        coeffs[e_free] = coeffs.get(e_free, flint.fmpq(0)) + c * tq**e_fixed
    if not coeffs:
        return []
    g = flint.fmpq_poly([coeffs.get(k, 0) for k in range(max(coeffs) + 1)])
    if g.degree() < 1:
        return []
    out = []
    for root, _ in g.complex_roots():
        if root.imag.is_exact() and root.imag == 0:
            x = float(root.real.mid())
            if lo <= x <= hi:
                out.append(x)
    return out


def _boundary_cells(
    fam: Family, codes: np.ndarray, u_edges: np.ndarray, w_edges: np.ndarray, u: np.ndarray, w: np.ndarray
) -> np.ndarray:
    """Cells to refine: an answer that differs from a neighbour's, or a boundary polynomial
    whose certified signs at the corners and the centre are not one non-zero sign."""
    mark = np.zeros(codes.shape, dtype=bool)
    diff_u = codes[1:, :] != codes[:-1, :]
    diff_w = codes[:, 1:] != codes[:, :-1]
    mark[1:, :] |= diff_u
    mark[:-1, :] |= diff_u
    mark[:, 1:] |= diff_w
    mark[:, :-1] |= diff_w
    Ue, We = np.meshgrid(u_edges, w_edges, indexing="ij")
    Uc, Wc = np.meshgrid(u, w, indexing="ij")
    for bd in fam.boundaries:
        for f in bd.factors:
            cq = compile_quantity("boundary", RationalFunction(f), 2)  # numpy: no compilation
            se, sc = _numpy_signs(cq, [Ue, We]), _numpy_signs(cq, [Uc, Wc])
            corners = [se[:-1, :-1], se[1:, :-1], se[:-1, 1:], se[1:, 1:], sc]
            same = np.ones(codes.shape, dtype=bool)
            for s in corners:
                same &= (s == corners[-1]) & ((s == 1) | (s == -1))
            mark |= ~same
    return mark


def contact_map(
    fam: Family,
    *,
    resolution: int | tuple[int, int] = 100,
    refine: int = 2,
    **ranges: Any,
) -> ContactMap:
    """The grid of answers of a family over two of its parameters.

    Parameters
    ----------
    fam : Family
    resolution : int or (int, int)
        Cells along each axis.
    refine : int
        Levels of subdivision (``2^refine`` per axis) of the cells on a boundary.
    **ranges
        Exactly two parameters given as ``(low, high)`` (the axes, in this order), and every
        other parameter given a number (fixed exactly).

    Returns
    -------
    ContactMap

    Raises
    ------
    ShapeError
        Not exactly two ranges, a parameter left without a value, or an empty range.

    Examples
    --------
    >>> from quadric_contact import family
    >>> fam = family("(x - u)^2 + y^2 + (z - w)^2 - 1/4", "z", "u w")
    >>> m = fam.contact_map(u=(-1, 1), w=(-1, 1), resolution=4, refine=0)
    >>> m.codes[0].tolist()     # w centres -0.75, -0.25, 0.25, 0.75 (radius 1/2, the plane z = 0)
    [-1, 0, 0, 1]
    >>> sorted(m.counts().items())
    [('CONTACT', 8), ('R_MINUS', 4), ('R_PLUS', 4)]
    """
    start = time.perf_counter()
    axes = [k for k, v in ranges.items() if isinstance(v, (tuple, list))]
    if len(axes) != 2:
        raise ShapeError(f"give exactly two parameters as (low, high) ranges, got {axes}", ranges)
    fixed = {k: to_fraction(v) for k, v in ranges.items() if k not in axes}
    missing = [p for p in fam.parameters if p not in ranges]
    unknown = [k for k in ranges if k not in fam.parameters]
    if missing or unknown:
        raise ShapeError(
            f"every parameter of {fam.parameters} needs a range or a value; "
            f"missing {missing}, unknown {unknown}",
            ranges,
        )
    bounds = []
    for k in axes:
        lo, hi = (to_fraction(x) for x in ranges[k])
        if not lo < hi:
            raise ShapeError(f"the range of {k} must have low < high, got {ranges[k]}", ranges[k])
        bounds.append((lo, hi))
    sub = fam.fix(**fixed) if fixed else fam
    if sub.parameters != tuple(axes):  # the axes in the order asked
        sub = _reorder(sub, tuple(axes))
    nu, nw = (resolution, resolution) if isinstance(resolution, int) else resolution
    (a, b), (c, d) = bounds
    u, w = _centres(a, b, nu), _centres(c, d, nw)
    decider = _Decider(sub)
    Uc, Wc = np.meshgrid(u, w, indexing="ij")
    codes = decider.decide(Uc.reshape(-1), Wc.reshape(-1)).reshape(nu, nw)
    k = 2**refine
    fine = np.repeat(np.repeat(codes, k, axis=0), k, axis=1)
    refined = np.zeros((nu, nw), dtype=bool)
    if refine > 0:
        refined = _boundary_cells(sub, codes, _edges(a, b, nu), _edges(c, d, nw), u, w)
        fu, fw = _centres(a, b, nu, k), _centres(c, d, nw, k)
        cells = np.argwhere(refined)
        if len(cells):
            ii = cells[:, 0:1] * k + np.arange(k)[None, :]  # (m, k) fine columns
            jj = cells[:, 1:2] * k + np.arange(k)[None, :]
            I = np.repeat(ii, k, axis=1).reshape(-1)  # noqa: E741
            J = np.tile(jj, (1, k)).reshape(-1)
            fine[I, J] = decider.decide(fu[I], fw[J])
    stats = {
        "cells": nu * nw,
        "refined cells": int(refined.sum()),
        "subcells": int(refined.sum()) * k * k if refine else 0,
        "predicate calls (pairs)": decider.calls,
        "touching checks (pairs)": decider.touch_checks,
        "seconds": round(time.perf_counter() - start, 3),
    }
    return ContactMap(
        sub, (axes[0], axes[1]), (bounds[0], bounds[1]), u, w, codes, refine, fine, refined, fixed, stats
    )


def _reorder(fam: Family, order: tuple[str, ...]) -> Family:
    """The same family with its parameters in another order."""
    perm = [fam.parameters.index(p) for p in order]
    ctx = flint.fmpq_mpoly_ctx.get(order, "lex")

    def move(p: Any) -> Any:
        d = {tuple(int(m[i]) for i in perm): c for m, c in p.to_dict().items()}
        return ctx.from_dict(d) if d else ctx.constant(0)

    def rf(v: RationalFunction) -> RationalFunction:
        return RationalFunction(move(v.num), move(v.den))

    at = {p: fam.reference[p] for p in order}
    return type(fam)(order, [rf(v) for v in fam._e], [rf(v) for v in fam._q], at=at)
