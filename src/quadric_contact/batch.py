"""Array predicates: stacks of matrices, broadcasting, number modes, dask.

:func:`transversal_contact_batch` and :func:`relative_position_batch` take one
``(4, 4)`` matrix or a stack ``(..., 4, 4)`` for ``E``, ``Q`` or both (numpy
arrays of any real dtype, nested sequences, object arrays of exact rationals,
:class:`~quadric_contact.Quadric` objects, dask arrays), broadcast the batch
shapes as numpy does, and return int8 arrays of codes (or one code for a
single pair).  :func:`~quadric_contact.transversal_contact` and
:func:`~quadric_contact.relative_position` call them for stacks and for the
number modes other than the exact default.

What is evaluated on a stack
----------------------------
The paper's criterion, as it stands, with no smallness test (the Tables 1-2
test is not vectorised):

* contact: does ``P(lambda) = det(lambda E + Q)`` have non-real roots?  Yes
  means transversal contact for *any* pair (Remark 9); no means no transversal
  contact when ``E`` is small with respect to ``Q`` (Theorem 2, Corollary 10),
  and always when ``Q`` is a plane (Theorem 14) or has no real points.
* region: the contact answer, then the root-sign pattern (Descartes' rule, exact
  when all roots are real) matched against Table 4 for the type of ``Q``
  (Theorem 13; Theorem 14 for planes), exactly as
  :func:`~quadric_contact.relative_position` does when smallness is asserted.

The codes are :class:`~quadric_contact.modes.ContactCode` and
:class:`~quadric_contact.modes.RegionCode` (regions are the sign of ``X^T Q X``
on ``E``: ``R- = -1``, ``contact = 0``, ``R+ = 1``).  ``UNCERTAIN`` (2) appears
only with the modes that are not certified (``filter`` and ``ball`` answer
``UNCERTAIN`` where they are not sure; ``float`` and ``mpmath`` answer everything
and may be wrong).  The default ``certified`` mode always answers and its
answer equals the exact evaluation of the criterion on the given matrices (a
float is the exact dyadic rational it stores).

Input validation raises the errors of :mod:`quadric_contact.errors`:
:class:`ShapeError` (not ``(..., 4, 4)``, or batch shapes that do not
broadcast), :class:`NonFiniteError`, :class:`NotSymmetricError`,
:class:`NotANumberError`, and :class:`NotAnEllipsoidError` (decided exactly in
the certified and exact modes) naming the offending matrix, e.g. ``E[3, 1]``.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any

import numpy as np

from .errors import NotANumberError, NotSymmetricError, ShapeError
from .modes import ContactCode, MatrixStack, NumberMode, Pairs, RegionCode, get_mode

__all__ = [
    "ContactCode",
    "RegionCode",
    "as_stack",
    "is_stack",
    "make_pairs",
    "relative_position_batch",
    "transversal_contact_batch",
]


def is_stack(value: Any) -> bool:
    """True for a stack of matrices ``(..., 4, 4)`` with at least one batch axis
    (numpy or dask arrays, or nested sequences three levels deep)."""
    ndim = getattr(value, "ndim", None)
    if ndim is not None and hasattr(value, "shape"):
        return int(ndim) >= 3
    if isinstance(value, (list, tuple)) and value:
        first = value[0]
        if isinstance(first, (list, tuple)) and first:
            inner = first[0]
            return isinstance(inner, (list, tuple)) or getattr(inner, "ndim", 0) >= 1
    return False


def _is_dask(value: Any) -> bool:
    return type(value).__module__.startswith("dask.") and hasattr(value, "chunks")


# -- input conversion ---------------------------------------------------------------------


def as_stack(value: Any, name: str = "M") -> MatrixStack:
    """Validate and convert one matrix or a stack to a :class:`MatrixStack`.

    Binary64 input is used as it is (its symmetry and finiteness are checked by
    the kernels that read it); integers that binary64 holds exactly, float32
    and float16 are widened exactly; anything else (object arrays of
    Fractions, ints beyond 2^53, long doubles, strings, :class:`Quadric`) is
    converted to exact rationals and checked here, and its binary64 rounding is
    what the float stages see (with error bounds that account for it).

    Raises
    ------
    ShapeError, NotANumberError, NonFiniteError, NotRationalError, NotSymmetricError
    """
    from .pencil import as_quadric
    from .quadric import Quadric

    if isinstance(value, (str, Quadric)) or (type(value).__module__ or "").startswith("sympy"):
        return _exact_stack([as_quadric(value, name).upper], (), name)
    if isinstance(value, (list, tuple)) and value and all(isinstance(v, Quadric) for v in value):
        return _exact_stack([v.upper for v in value], (len(value),), name)
    try:
        arr = np.asarray(value)
    except (ValueError, TypeError) as exc:
        raise ShapeError(f"{name} is not a matrix or a stack of matrices: {exc}", value) from exc
    if arr.ndim < 2 or arr.shape[-2:] != (4, 4):
        raise ShapeError(f"{name} must have shape (4, 4) or (..., 4, 4), got {arr.shape}", value)
    batch = arr.shape[:-2]
    kind = arr.dtype.kind
    if kind == "b":
        raise NotANumberError(f"{name} is a boolean array, not a matrix of numbers", value)
    if kind == "c":
        raise NotANumberError(f"{name} is complex, not real", value)
    if kind == "f" and arr.dtype.itemsize <= 8:
        floats = np.ascontiguousarray(arr.reshape(-1, 4, 4), dtype=np.float64)
        return MatrixStack(floats, None, False, name, batch)
    if kind in "iu" and arr.size and int(np.abs(arr).max()) <= 2**53:
        floats = np.ascontiguousarray(arr.reshape(-1, 4, 4), dtype=np.float64)
        return MatrixStack(floats, None, False, name, batch)
    if kind in "iu":
        return _exact_stack(_object_upper(arr.reshape(-1, 4, 4).astype(object), name), batch, name)
    return _exact_stack(_object_upper(arr.reshape(-1, 4, 4), name), batch, name)


def _object_upper(arr: np.ndarray, name: str) -> list[tuple[Fraction, ...]]:
    from .codegen import ENTRY_INDICES
    from .rational import as_square_matrix

    out = []
    for k, m in enumerate(arr):
        try:
            rows = as_square_matrix(m.tolist(), 4)
        except Exception as exc:
            where = f"{name}[{k}]" if arr.shape[0] > 1 else name
            raise type(exc)(f"{where}: {exc}", m) from exc
        for i in range(4):
            for j in range(i + 1, 4):
                if rows[i][j] != rows[j][i]:
                    raise NotSymmetricError(
                        f"{name}[{k}] is not symmetric: "
                        f"M[{i},{j}] = {rows[i][j]} but M[{j},{i}] = {rows[j][i]}",
                        m,
                        entry=(i, j),
                        index=k,
                    )
        out.append(tuple(rows[i][j] for i, j in ENTRY_INDICES))
    return out


def _exact_stack(uppers: list[tuple[Fraction, ...]], batch: tuple[int, ...], name: str) -> MatrixStack:
    """Exact matrices: binary64 roundings for the float stages; if every entry is a
    binary64 number the stack *is* float input (no rounding at all)."""
    from .codegen import ENTRY_INDICES

    n = len(uppers)
    exact = np.empty((n, 10), dtype=object)
    floats = np.empty((n, 4, 4), dtype=np.float64)
    dyadic = True
    for k, upper in enumerate(uppers):
        for t, (i, j) in enumerate(ENTRY_INDICES):
            v = Fraction(upper[t])
            exact[k, t] = v
            f = _round(v)
            floats[k, i, j] = floats[k, j, i] = f
            dyadic = dyadic and math.isfinite(f) and Fraction(f) == v and (f != 0.0 or v == 0)
    if dyadic:
        return MatrixStack(floats, None, True, name, batch)
    return MatrixStack(floats, exact, True, name, batch)


def _round(v: Fraction) -> float:
    """Correctly rounded binary64 value of ``v``, or inf when it overflows (the filter
    then leaves the entry to the later stages)."""
    try:
        return float(v)
    except OverflowError:
        return math.inf if v > 0 else -math.inf


def make_pairs(E: MatrixStack, Q: MatrixStack) -> tuple[Pairs, tuple[int, ...]]:
    """Broadcast two stacks: the pairs and the output batch shape."""
    try:
        shape = np.broadcast_shapes(E.shape, Q.shape)
    except ValueError as exc:
        raise ShapeError(
            f"batch shapes {E.shape} of E and {Q.shape} of Q do not broadcast", (E.shape, Q.shape)
        ) from exc
    n = int(np.prod(shape, dtype=np.int64))
    indices: list[np.ndarray | None] = []
    for stack in (E, Q):
        if (len(stack) == n and stack.shape == shape) or len(stack) == 1:
            indices.append(None)
        else:
            full = np.arange(len(stack), dtype=np.intp).reshape(stack.shape)
            indices.append(np.ascontiguousarray(np.broadcast_to(full, shape)).reshape(-1))
    return Pairs(E, Q, n, indices[0], indices[1]), tuple(shape)


# -- the predicates ---------------------------------------------------------------------------


def transversal_contact_batch(
    E: Any, Q: Any, *, mode: str | NumberMode = "certified", client: Any = None, compute: bool = True
) -> Any:
    """Transversal contact for every pair of a broadcast of ``E`` and ``Q``.

    Parameters
    ----------
    E : array_like, shape (4, 4) or (..., 4, 4)
        Real ellipsoids (either sign of the matrix).
    Q : array_like, shape (4, 4) or (..., 4, 4)
        Quadrics.
    mode : str or NumberMode
        ``"certified"`` (default, never wrong), ``"exact"``, ``"filter"``,
        ``"float"``, ``"ball"``, ``"mpmath"``, or a mode instance (pass one to
        read its :attr:`~quadric_contact.modes.NumberMode.counts` afterwards).
    client : dask.distributed.Client, optional
        For dask input: compute on this cluster (default: dask's local threads).
    compute : bool
        For dask input: return the computed numpy array (default) or the lazy dask array.

    Returns
    -------
    numpy.ndarray of int8, shape = broadcast batch shape; or one ContactCode
        :class:`~quadric_contact.modes.ContactCode`: 1 non-real roots
        (transversal contact, Remark 9), 0 all roots real (no transversal contact
        under smallness, Corollary 10; for planes, Theorem 14), 2 uncertain.

    Raises
    ------
    ShapeError, NonFiniteError, NotSymmetricError, NotANumberError, NotAnEllipsoidError

    References
    ----------
    Theorem 2, Corollary 10, Remark 9, Theorem 14.

    Examples
    --------
    Example 11 (``Delta_4 = 0``, ``Delta_3 < 0``: contact), and the same ellipsoid
    moved up by 10:

    >>> import numpy as np
    >>> E = np.diag([2.0, 2.0, 3.0, -1.0])
    >>> E_up = E.copy(); E_up[2, 3] = E_up[3, 2] = -30.0; E_up[3, 3] = 299.0
    >>> Q = np.array([[1.0, 0, 0, 0], [0, 1, 0, 0], [0, 0, 0, 4], [0, 0, 4, 0]])
    >>> transversal_contact_batch(np.stack([E, E_up]), Q)
    array([1, 0], dtype=int8)
    """
    return _run("contact", E, Q, mode, client, compute)


def relative_position_batch(
    E: Any, Q: Any, *, mode: str | NumberMode = "certified", client: Any = None, compute: bool = True
) -> Any:
    """Where each ellipsoid lies with respect to its quadric (Table 4), as codes.

    Parameters are those of :func:`transversal_contact_batch`.

    Returns
    -------
    numpy.ndarray of int8 (or one RegionCode)
        :class:`~quadric_contact.modes.RegionCode`: -1 ``R-``, 0 transversal
        contact, 1 ``R+``; 2 uncertain, 3 no row of Table 4 matches (``E`` is
        not small with respect to ``Q``), 4 ``Q`` has no row (cones, intersecting
        or coincident planes, no real points).

    Raises
    ------
    ShapeError, NonFiniteError, NotSymmetricError, NotANumberError, NotAnEllipsoidError

    References
    ----------
    Theorem 13, Table 4, Lemma 12, Theorem 14.

    Examples
    --------
    Example 17: the bee and the hyperboloid S2 (outside: ``R+``) and the
    separating plane ``z = 6`` (below it: ``R-``):

    >>> from quadric_contact import Quadric
    >>> bee = Quadric.from_equation("(x-3)**2 + (y-3)**2 + 3*(z-5.5)**2 - 0.1")
    >>> S2 = Quadric.from_equation("x**2 + y**2 - 0.25*(z-3)**2 - 1")
    >>> plane = Quadric.from_equation("z - 6")
    >>> relative_position_batch(bee, [S2, plane])
    array([ 1, -1], dtype=int8)
    """
    return _run("region", E, Q, mode, client, compute)


def _run(what: str, E: Any, Q: Any, mode: Any, client: Any, compute: bool) -> Any:
    if _is_dask(E) or _is_dask(Q):
        return _run_dask(what, E, Q, mode, client, compute)
    m = get_mode(mode)
    pairs, shape = make_pairs(as_stack(E, "E"), as_stack(Q, "Q"))
    if what == "contact":
        codes = m.contact(pairs)
        return ContactCode(int(codes[0])) if shape == () else codes.reshape(shape)
    codes = m.region(pairs)
    return RegionCode(int(codes[0])) if shape == () else codes.reshape(shape)


# -- dask ---------------------------------------------------------------------------------------


def _run_dask(what: str, E: Any, Q: Any, mode: Any, client: Any, compute: bool) -> Any:
    import dask
    import dask.array as da

    m = get_mode(mode)
    arrays = []
    for value, name in ((E, "E"), (Q, "Q")):
        arr = value if _is_dask(value) else da.from_array(np.asarray(value), chunks=-1)
        if arr.ndim < 2 or tuple(arr.shape[-2:]) != (4, 4):
            raise ShapeError(f"{name} must have shape (..., 4, 4), got {arr.shape}", value)
        arrays.append(arr.rechunk({arr.ndim - 2: 4, arr.ndim - 1: 4}))
    try:
        shape = np.broadcast_shapes(arrays[0].shape[:-2], arrays[1].shape[:-2])
    except ValueError as exc:
        raise ShapeError("batch shapes of E and Q do not broadcast", (E, Q)) from exc
    Eb = da.broadcast_to(arrays[0], (*shape, 4, 4))
    Qb = da.broadcast_to(arrays[1], (*shape, 4, 4))
    if not shape:
        Eb, Qb = Eb[None], Qb[None]
    Eb, Qb = da.core.unify_chunks(Eb, tuple(range(Eb.ndim)), Qb, tuple(range(Qb.ndim)))[1]
    fn = transversal_contact_batch if what == "contact" else relative_position_batch

    def block(e: np.ndarray, q: np.ndarray) -> np.ndarray:
        from .modes.float64 import single_threaded

        with single_threaded():
            return np.asarray(fn(e, q, mode=m), dtype=np.int8).reshape(e.shape[:-2])

    out = da.map_blocks(block, Eb, Qb, drop_axis=[Eb.ndim - 2, Eb.ndim - 1], dtype=np.int8)
    if not shape:
        out = out[0]
    if not compute:
        return out
    if client is not None:
        return np.asarray(client.compute(out).result())
    (result,) = dask.compute(out, scheduler="threads")
    return np.asarray(result)
