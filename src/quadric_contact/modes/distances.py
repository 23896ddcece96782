"""How far from contact, as public predicates: :func:`~quadric_contact.contact_scale` and
:func:`~quadric_contact.distance`, for one pair and for stacks.

One meaning for every input form and mode: the exact number of
:mod:`quadric_contact.theory.contact_scale` or :mod:`quadric_contact.theory.distance`.  For a
pair, ``mode="exact"`` gives it as a real algebraic number with exact witnesses and
``mode="certified"`` (the distance) as arb balls enclosing it to ``digits`` digits
(:mod:`quadric_contact.modes.distance.certified`; the exact path answers the symmetric
configurations the balls leave).  A stack answers with, for every pair, an enclosure
``[lo, hi]`` of that same number in binary64 (``lo <= value <= hi``, rounded outwards), in an
array of shape ``(..., 2)``: a stack of one holds the enclosure of the pair's value.  A stack
is any form the other array predicates take (:func:`~quadric_contact.modes.stacks.batch.is_stack`):
arrays ``(..., 4, 4)`` of any real dtype (object arrays of Fractions or ints are exact input,
each pair answered as the pair itself is), lists, object arrays of Quadrics or equations,
:class:`~quadric_contact.Packed` stacks (their unpacked matrices, float64 where the entries are
binary64 numbers) and dask arrays (computed first); the batch shapes broadcast as numpy's do,
and shapes that do not are a :class:`~quadric_contact.ShapeError`.

The first-contact scale (``scale="E"``) of float64 stacks runs a compiled kernel that certifies
each pair's enclosure (:mod:`quadric_contact.modes.distance.scale_kernel`) and leaves the pairs it cannot
certify (a centre on the surface, a degenerate ``Q`` other than a plane) to the exact path;
with ``scale="both"`` (two ellipsoids) a kernel of its own certifies the Perram-Wertheim scale
by a lower and an upper bound that meet at the optimal multiplier
(:mod:`quadric_contact.modes.distance.scale_both`), and leaves nearly concentric pairs and pairs that are
not two ellipsoids to the exact path.
The distance of float64 stacks runs a compiled kernel for separated ellipsoid pairs (a
duality certificate, :mod:`quadric_contact.modes.distance.apart_kernel`), then one for the crossing
ellipsoid pairs it leaves (the depth between a support enclosure at a minimiser and a covering
of the sphere by cells each certified by a point of the Minkowski difference,
:mod:`quadric_contact.modes.distance.depth_kernel`), both with enclosures at most
``max(10^-digits, 1e-12)`` relative wide; the pairs neither certifies (touching or nearly so,
too shallow for the tolerance, not two ellipsoids), and every other stack, run the scalar path
pair by pair.  One pair of binary64 ellipsoids in the ``float`` mode runs the same two kernels
first: its answer is the stack of one's enclosure.  One crossing pair in the ``certified``
mode runs the depth kernel for a global lower bound and a minimiser, isolates the one root of
the support system near it, and runs the kernel again to cover the rest of the sphere
(:func:`~quadric_contact.modes.distance.certified.crossing_ellipsoids`).
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import flint
import numpy as np

from quadric_contact.exact.algebraic import RealAlgebraic
from quadric_contact.exact.errors import (
    SYMMETRIZE_HINT,
    ChoiceError,
    NonFiniteError,
    NotANumberError,
    NotSymmetricError,
    QuadricContactError,
    ShapeError,
    UndecidedError,
)
from quadric_contact.exact.precision import working_precision
from quadric_contact.model.classification import QuadricKind
from quadric_contact.model.quadric import as_quadric
from quadric_contact.modes.distance.apart_kernel import separated_ellipsoids
from quadric_contact.modes.distance.certified import DistanceEnclosure, apart_ellipsoids, distance_certified
from quadric_contact.modes.distance.certified import crossing_ellipsoids as crossing_pair
from quadric_contact.modes.distance.depth_kernel import crossing_ellipsoids
from quadric_contact.modes.distance.scale_blocks import scale_stack
from quadric_contact.modes.distance.scale_both import scale_both_stack
from quadric_contact.modes.stacks.batch import _is_dask, _is_single, _quadric_array, is_stack, matrix_array
from quadric_contact.modes.stacks.packing import Packed, unpack
from quadric_contact.theory.contact_scale import contact_scale_exact
from quadric_contact.theory.distance import CONVEX_SOLIDS, DistanceResult, distance_exact, is_sphere
from quadric_contact.theory.distance_critical import critical_distance_binary64
from quadric_contact.theory.overlap import overlap_exact, solid_of
from quadric_contact.theory.results import OverlapCode

__all__ = ["FloatDistance", "contact_scale", "distance", "enclosure"]

_MODES = ("certified", "exact", "float")


@dataclass(frozen=True)
class FloatDistance:
    """The signed distance in binary64, with a bound on its error.

    Attributes
    ----------
    distance : float
        The midpoint of a rigorous binary64 enclosure (nan where ``uncertain``).
    error : float
        ``|distance - exact| <= error``, rounded up; ``inf`` where ``uncertain``.
    uncertain : bool
        The critical points were not all isolated (a degenerate, symmetric configuration):
        no claim is made; the certified or exact mode decides such a pair.
    """

    distance: float
    error: float
    uncertain: bool

    def __float__(self) -> float:
        return self.distance

    @property
    def bounds(self) -> tuple[float, float]:
        return _down(Fraction(self.distance) - Fraction(self.error)), _up(
            Fraction(self.distance) + Fraction(self.error)
        )

    @staticmethod
    def of(lo: float, hi: float) -> FloatDistance:
        """The midpoint and a rounded-up half-width of ``[lo, hi]``."""
        if not (math.isfinite(lo) and math.isfinite(hi)):
            return FloatDistance(math.nan, math.inf, True)
        mid = 0.5 * lo + 0.5 * hi
        err = max(Fraction(mid) - Fraction(lo), Fraction(hi) - Fraction(mid))
        return FloatDistance(mid, _up(err), False)


def enclosure(x: RealAlgebraic, bits: int = 60) -> tuple[float, float]:
    """Binary64 bounds ``lo <= x <= hi``, from an isolating interval refined below ``2^-bits``
    relative, each end rounded outwards.

    Examples
    --------
    >>> lo, hi = enclosure(RealAlgebraic.sqrt(2))
    >>> lo < 2 ** 0.5 < hi or lo == 2 ** 0.5 or hi == 2 ** 0.5, hi - lo < 1e-15
    (True, True)
    """
    if x.is_rational:
        v = x.as_fraction()
        return _down(v), _up(v)
    lo, hi = x.interval
    scale = max(abs(lo), abs(hi), Fraction(1, 1 << 1000))
    x.refine(scale / (1 << bits))
    lo, hi = x.interval
    return _down(lo), _up(hi)


def _down(v: Fraction) -> float:
    f = float(v)
    return f if Fraction(f) <= v else math.nextafter(f, -math.inf)


def _up(v: Fraction) -> float:
    f = float(v)
    return f if Fraction(f) >= v else math.nextafter(f, math.inf)


def _stack_form(v: Any, name: str) -> Any:
    """One side of a stack call in the form the kernels and :func:`_pairs` read: a
    :class:`~quadric_contact.Packed` stack as its unpacked matrices (float64 where its entries
    are binary64 numbers, as the other predicates read it), a dask array computed into numpy;
    anything else as it is."""
    if isinstance(v, Packed):
        arr = v.array
        kind = arr.dtype.kind
        if kind in "bc":
            raise NotANumberError(f"{name} is not a stack of real matrices (dtype {arr.dtype})", v)
        full = unpack(arr)
        if (kind == "f" and arr.dtype.itemsize <= 8) or (
            kind in "iu" and (not arr.size or int(np.abs(arr).max()) <= 2**53)
        ):
            return np.ascontiguousarray(full, dtype=np.float64)
        return full
    if _is_dask(v):
        return np.asarray(v)
    return v


def _batch_shape(se: tuple[int, ...], sq: tuple[int, ...]) -> tuple[int, ...]:
    """The broadcast of the batch shapes of ``E`` and ``Q`` (``()`` for one matrix), or the
    :class:`ShapeError` the other predicates raise."""
    try:
        return tuple(np.broadcast_shapes(se, sq))
    except ValueError as exc:
        raise ShapeError(f"batch shapes {se} of E and {sq} of Q do not broadcast", (se, sq)) from exc


def _items(v: Any, name: str) -> tuple[list[Any], tuple[int, ...]]:
    """The matrices (or Quadrics, equations) of one side and its batch shape (``()`` for one
    matrix): an array ``(..., 4, 4)`` of any dtype (object arrays of Fractions or ints
    included) gives its ``(4, 4)`` sub-arrays, an object array of Quadrics or equations and a
    list of them their items, a (nested) list of matrices the sub-arrays of its array."""
    if not is_stack(v):
        return [v], ()
    if isinstance(v, (list, tuple)) and (not v or any(_is_single(x) for x in v)):
        return list(v), (len(v),)
    if isinstance(v, np.ndarray) and v.dtype == object and _quadric_array(v):
        return list(v.reshape(-1)), tuple(v.shape)
    arr = matrix_array(v, name)
    return list(arr.reshape(-1, 4, 4)), tuple(arr.shape[:-2])


def _pairs(E: Any, Q: Any) -> tuple[list[Any], list[Any], tuple[int, ...]]:
    """The pairs of a stack, broadcast as numpy broadcasts the batch shapes (either side may
    be one matrix), and the output batch shape."""
    es, se = _items(E, "E")
    qs, sq = _items(Q, "Q")
    shape = _batch_shape(se, sq)

    def spread(items: list[Any], own: tuple[int, ...]) -> list[Any]:
        index = np.broadcast_to(np.arange(len(items)).reshape(own), shape).reshape(-1)
        return [items[int(k)] for k in index]

    return spread(es, se), spread(qs, sq), shape


@contextmanager
def _naming_pair(k: int, shape: tuple[int, ...]) -> Iterator[None]:
    """An error of the pair at flat position ``k`` of a stack's answer (batch shape ``shape``),
    raised again naming the pair: the same class, ``.value`` and details, and ``index=k``."""
    try:
        yield
    except QuadricContactError as exc:
        at = ", ".join(str(int(i)) for i in np.unravel_index(k, shape)) if shape else ""
        raise type(exc)(f"the pair at [{at}]: {exc}", exc.value, **{**exc.details, "index": k}) from exc


def _check(mode: str, modes: tuple[str, ...] = _MODES) -> None:
    if mode not in modes:
        raise ChoiceError(f"mode must be one of {', '.join(modes)}, got {mode!r}", mode, choices=modes)


def _check_digits(digits: Any) -> None:
    if not isinstance(digits, int) or isinstance(digits, bool) or digits < 1:
        raise NotANumberError(f"digits must be a positive integer, got {digits!r}", digits)


def contact_scale(E: Any, Q: Any, *, scale: str = "E", mode: str = "certified") -> Any:
    """The factor ``s* >= 0`` by which ``E``, scaled about its centre, first touches ``Q``.

    ``s* > 1``: ``E`` is clear of ``Q`` (it could grow by ``s*``); ``s* = 1``: it touches;
    ``s* < 1``: its solid already reaches the surface of ``Q``.  With ``scale="both"`` (two
    ellipsoids) both are scaled about their own centres and ``s*^2`` is the Perram-Wertheim
    contact function.

    Parameters
    ----------
    E : Quadric, equation, matrix-like; or a stack ``(..., 4, 4)``
        A real ellipsoid.  A stack in any form of the array predicates (a
        :class:`~quadric_contact.Packed` stack, an object array of Fractions, ...).
    Q : Quadric, equation, matrix-like; or a stack
        A quadric of Table 1 or a plane; an ellipsoid with ``scale="both"``.
    scale : {"E", "both"}
    mode : {"certified", "exact"}
        The same exact answer; on stacks both give enclosures.

    Returns
    -------
    ContactScaleResult for a pair (``.scale`` a :class:`~quadric_contact.RealAlgebraic`);
    for a stack a float64 array ``(..., 2)`` of enclosures ``[lo, hi]`` of ``s*``.

    Raises
    ------
    NotAnEllipsoidError, ExcludedQuadricError, UndecidedError
    ShapeError
        Stacks whose batch shapes do not broadcast (or not ``(..., 4, 4)``).

    Examples
    --------
    >>> contact_scale("x**2 + y**2 + z**2 - 1", "x - 3").scale
    RealAlgebraic(3)
    >>> contact_scale(["x**2 + y**2 + z**2 - 1"] * 2, "x - 3")
    array([[3., 3.],
           [3., 3.]])
    """
    _check(mode, ("certified", "exact"))
    if not (is_stack(E) or is_stack(Q)):
        return contact_scale_exact(E, Q, scale=scale)
    E, Q = _stack_form(E, "E"), _stack_form(Q, "Q")
    if scale in ("E", "both") and _float_stack(E) and _float_stack(Q):
        return _scale_kernel(E, Q, scale)
    es, qs, shape = _pairs(E, Q)
    out = np.empty((len(es), 2))
    for k, (e, q) in enumerate(zip(es, qs, strict=True)):
        with _naming_pair(k, shape):
            out[k] = enclosure(contact_scale_exact(e, q, scale=scale).scale)
    return out.reshape(*shape, 2)


def _float_stack(v: Any) -> bool:
    """A float64 array ``(..., 4, 4)`` (a stack, or one matrix broadcast)."""
    return isinstance(v, np.ndarray) and v.dtype == np.float64 and v.ndim >= 2 and v.shape[-2:] == (4, 4)


def _validated(v: np.ndarray, name: str) -> np.ndarray:
    flat = v.reshape(-1, 4, 4)
    finite = np.isfinite(flat).all(axis=(1, 2))
    if not finite.all():
        k = int(np.argmin(finite))
        i, j = (int(x) for x in np.argwhere(~np.isfinite(flat[k]))[0])
        raise NonFiniteError(
            f"{name}[{k}] has a non-finite entry at ({i}, {j})", flat[k], entry=(i, j), index=k
        )
    sym = (flat == flat.transpose(0, 2, 1)).all(axis=(1, 2))
    if not sym.all():
        k = int(np.argmin(sym))
        raise NotSymmetricError(f"{name}[{k}] is not symmetric; {SYMMETRIZE_HINT}", flat[k], index=k)
    return flat


def _distance_kernel(E: np.ndarray, Q: np.ndarray, mode: str, digits: int) -> np.ndarray:
    """Float64 stacks: separated ellipsoid pairs by the compiled duality certificate
    (:mod:`quadric_contact.modes.distance.apart_kernel`), crossing ellipsoid pairs by the compiled
    depth certificate (:mod:`quadric_contact.modes.distance.depth_kernel`), enclosures at most
    ``max(10^-digits, 1e-12)`` relative wide; the other pairs by the scalar path."""

    shape = _batch_shape(E.shape[:-2], Q.shape[:-2])
    Es = _validated(np.broadcast_to(E, (*shape, 4, 4)), "E")
    Qs = _validated(np.broadcast_to(Q, (*shape, 4, 4)), "Q")
    tol = max(10.0**-digits, 1e-12)
    out, rest = separated_ellipsoids(Es, Qs, tol)
    left = np.flatnonzero(rest)
    if left.size:
        enc, still = crossing_ellipsoids(Es[left], Qs[left], tol)
        done = left[~still]
        out[done] = enc[~still]
        rest[done] = False
    for k in np.flatnonzero(rest):
        with _naming_pair(int(k), shape):
            out[k] = _pair_enclosure(Es[k], Qs[k], mode, digits)
    return out.reshape(*shape, 2)


def _pair_enclosure(e: Any, q: Any, mode: str, digits: int) -> tuple[float, float]:
    """The enclosure a stack holds for one pair it answers by the scalar path (``float``:
    ``(-inf, inf)`` where that mode cannot tell)."""
    if mode == "float":
        f = _float(e, q)
        return (-math.inf, math.inf) if f.uncertain else f.bounds
    c = _certified(e, q, max(digits, 17)) if mode == "certified" else None
    return _float_bounds(*c.bounds) if c is not None else enclosure(distance_exact(e, q).distance)


def _scale_kernel(E: np.ndarray, Q: np.ndarray, scale: str = "E") -> np.ndarray:
    """The compiled kernels on float64 stacks (:mod:`quadric_contact.modes.distance.scale_kernel` for
    ``scale="E"``, :mod:`quadric_contact.modes.distance.scale_both` for ``scale="both"``); the pairs they
    leave go to the exact scalar path (which raises for a pair that is not one of two real
    ellipsoids with ``scale="both"``)."""

    shape = _batch_shape(E.shape[:-2], Q.shape[:-2])
    Es = _validated(np.broadcast_to(E, (*shape, 4, 4)), "E")
    Qs = _validated(np.broadcast_to(Q, (*shape, 4, 4)), "Q")
    out, rest = (scale_both_stack if scale == "both" else scale_stack)(Es, Qs)
    for k in np.flatnonzero(rest):
        with _naming_pair(int(k), shape):
            out[k] = enclosure(contact_scale_exact(Es[k], Qs[k], scale=scale).scale)
    return out.reshape(*shape, 2)


def _certified(E: Any, Q: Any, digits: int) -> DistanceEnclosure | None:
    """The certified enclosure, or None for a symmetric configuration of a pair the exact path
    answers (an ellipsoid against a plane, a sphere against a quadric)."""
    try:
        return distance_certified(E, Q, digits=digits)
    except UndecidedError as exc:
        if "symmetric configuration" in str(exc) and _exact_answers(E, Q):
            return None
        raise


def _exact_answers(E: Any, Q: Any) -> bool:
    e = as_quadric(E, "E").as_ellipsoid()
    return is_sphere(e) or solid_of(Q).kind is QuadricKind.PLANE


def _kernel_pair(e: Any, K: Any) -> FloatDistance | None:
    """Two ellipsoids whose entries are binary64 numbers: the compiled kernels a stack of one
    runs (the duality certificate of :mod:`quadric_contact.modes.distance.apart_kernel` for a
    separated pair, the depth certificate of :mod:`quadric_contact.modes.distance.depth_kernel` for a
    crossing one), the same enclosure as the stack's; or None (not certified there)."""

    mats = []
    for q in (e, K):
        m = np.array([[float(q[i, j]) for j in range(4)] for i in range(4)])
        if any(Fraction(m[i, j]) != q[i, j] for i in range(4) for j in range(4)):
            return None  # not binary64 numbers: the kernel would answer another pair
        mats.append(m[None])
    for kernel in (separated_ellipsoids, crossing_ellipsoids):
        enc, rest = kernel(mats[0], mats[1])
        if not rest[0]:
            return FloatDistance.of(float(enc[0, 0]), float(enc[0, 1]))
    return None


def _float(E: Any, Q: Any) -> FloatDistance:
    """The float mode for one pair: binary64 intervals where the pair needs the search (a
    curved quadric against an ellipsoid that is not a sphere), the certified balls rounded
    outwards otherwise; uncertain where the critical points are not isolated."""
    e = as_quadric(E, "E").as_ellipsoid()
    K = solid_of(Q)
    try:
        if K.kind is QuadricKind.ELLIPSOID:
            fast = _kernel_pair(e, K)
            if fast is not None:
                return fast
            # not binary64 entries, or left by the kernels (touching, shallow): two ellipsoids
            # have certified routes faster than the float search (one isolated root; for a
            # crossing pair, with the kernel's covering of the rest), rounded outwards
            found = apart_ellipsoids(e, K, 17) or crossing_pair(e, K, 17)
            if found is not None:
                return FloatDistance.of(*_float_bounds(*found.bounds))
        if K.kind is QuadricKind.PLANE or is_sphere(e):
            c = _certified(e, K, 17)  # None: a symmetric configuration, the exact answer
            bounds = _float_bounds(*c.bounds) if c is not None else enclosure(distance_exact(e, K).distance)
            return FloatDistance.of(*bounds)
        convex = K.kind in CONVEX_SOLIDS
        if not convex:
            code = overlap_exact(e, K).code
            if code is OverlapCode.OVERLAPPING:
                # the depth into a solid that is not convex: the certified bracket (an inscribed
                # ellipsoid, a free translation), rounded outwards; raises with the reason
                return FloatDistance.of(*_float_bounds(*distance_certified(e, K, digits=17).bounds))
            if code is OverlapCode.TOUCHING:
                return FloatDistance(0.0, 0.0, False)
        return FloatDistance.of(*critical_distance_binary64(e, K, convex=convex))
    except UndecidedError as exc:
        if "not convex" in str(exc):
            raise
        return FloatDistance(math.nan, math.inf, True)


def _as_enclosure(r: DistanceResult, digits: int) -> DistanceEnclosure:
    """The exact result as balls (a symmetric configuration in ``certified`` mode: one type of
    answer per mode)."""
    bits = int(digits * 3.33) + 8
    with working_precision(bits):

        def ball(x: RealAlgebraic) -> Any:
            return x.enclosure(bits) if x.sign() != 0 else flint.arb(0)

        def balls(p: Any) -> Any:
            return None if p is None else tuple(ball(x) for x in p)

        return DistanceEnclosure(
            ball(r.distance), balls(r.point_E), balls(r.point_Q), balls(r.normal), bits, r.method
        )


def _float_bounds(lo: Fraction, hi: Fraction) -> tuple[float, float]:
    return _down(lo), _up(hi)


def distance(E: Any, Q: Any, *, mode: str = "certified", digits: int = 15) -> Any:
    """The signed distance of the ellipsoid ``E`` from the solid of ``Q``, with witnesses.

    Positive: the Euclidean distance between the solids; ``0``: touching; negative: minus the
    penetration depth (the length of the shortest translation of ``E`` after which the
    interiors are disjoint).  See :mod:`quadric_contact.theory.distance` for the solids, the
    witnesses and the normal, and for which pairs have an exact answer (an ellipsoid against
    a plane; a sphere against any solid, the depth where the solid is convex).  Any other
    ellipsoid against a curved quadric is answered in the ``certified`` and ``float`` modes
    (:mod:`quadric_contact.theory.distance_critical`).

    Parameters
    ----------
    E : Quadric, equation, matrix-like; or a stack ``(..., 4, 4)``
        A stack in any form of the array predicates (a :class:`~quadric_contact.Packed`
        stack, an object array of Fractions, ...).
    Q : Quadric, equation, matrix-like; or a stack
    mode : {"certified", "exact", "float"}
        ``float``: binary64 interval arithmetic rounded outwards, a
        :class:`FloatDistance` (value and error bound, or marked uncertain); on stacks
        ``[lo, hi]`` as the other modes, ``[-inf, inf]`` where uncertain.
    digits : int
        ``certified``: significant digits of the enclosure.

    Returns
    -------
    For a pair, a :class:`~quadric_contact.DistanceResult` (``exact``) or a
    :class:`~quadric_contact.modes.distance.certified.DistanceEnclosure` (``certified``: arb
    balls; in a symmetric configuration those of the exact answer); for a stack a float64
    array ``(..., 2)`` of enclosures.

    Raises
    ------
    NotAnEllipsoidError, ExcludedQuadricError, UndecidedError
    ShapeError
        Stacks whose batch shapes do not broadcast (or not ``(..., 4, 4)``).

    Examples
    --------
    >>> r = distance("x**2 + y**2 + z**2 - 1", "x**2 + y**2 + (z - 5)**2 - 4", mode="exact")
    >>> r.distance, [str(c) for c in r.normal]
    (RealAlgebraic(2), ['0', '0', '-1'])
    >>> ball, throat = "9*((x - 5)**2 + (y - 3)**2 + (z - 2)**2) - 1", "x**2/4 + y**2 - z**2 - 1"
    >>> distance(ball, throat, digits=20).distance.str(20, radius=False)
    '1.0237793867297612191'
    >>> distance(ball, throat, mode="exact").distance.decimal(19)
    '1.0237793867297612191'
    >>> distance([ball, ball], throat)[0]  # binary64 bounds
    array([1.02377939, 1.02377939])
    """
    _check(mode)
    _check_digits(digits)
    if not (is_stack(E) or is_stack(Q)):
        if mode == "exact":
            return distance_exact(E, Q)
        if mode == "float":
            return _float(E, Q)
        return _certified(E, Q, digits) or _as_enclosure(distance_exact(E, Q), digits)
    E, Q = _stack_form(E, "E"), _stack_form(Q, "Q")
    if mode in ("certified", "float") and _float_stack(E) and _float_stack(Q):
        return _distance_kernel(E, Q, mode, digits)
    es, qs, shape = _pairs(E, Q)
    out = np.empty((len(es), 2))
    for k, (e, q) in enumerate(zip(es, qs, strict=True)):
        with _naming_pair(k, shape):
            out[k] = _pair_enclosure(e, q, mode, digits)
    return out.reshape(*shape, 2)
