"""The array layer of the predicates: stacks of matrices, broadcasting, dask.

:func:`is_stack` decides, from the type of an input alone, whether it is one
matrix or a stack; :func:`as_stack` validates and converts either to a
:class:`~quadric_contact.modes.MatrixStack` (numpy arrays of any real dtype,
nested sequences, object arrays of exact rationals, lists or object arrays of
:class:`~quadric_contact.Quadric` or equations); :func:`make_pairs` broadcasts two
stacks as numpy does; :func:`run_stack` asks a number mode one question about
every pair (eagerly, or chunk by chunk for dask arrays) and returns an int8 array
of codes shaped like the broadcast batch.  The public predicates of
:mod:`quadric_contact.modes.predicates` call it for stacks.

Input validation raises the errors of :mod:`quadric_contact.exact.errors`:
:class:`ShapeError` (not ``(..., 4, 4)``, or batch shapes that do not
broadcast), :class:`NonFiniteError`, :class:`NotSymmetricError`,
:class:`NotANumberError`, and :class:`NotAnEllipsoidError` naming the offending
matrix, e.g. ``E[3, 1]``.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any

import numpy as np

from quadric_contact.exact.entries import ENTRY_INDICES
from quadric_contact.exact.errors import (
    SYMMETRIZE_HINT,
    ChoiceError,
    NotANumberError,
    NotAPlaneError,
    NotSymmetricError,
    ShapeError,
)
from quadric_contact.exact.rational import as_square_matrix
from quadric_contact.model.classification import QuadricKind
from quadric_contact.model.quadric import Quadric
from quadric_contact.modes.decision.answers import KINDS, UNCERTAIN_ROW, rows_from_masks
from quadric_contact.modes.kernels.threads import single_threaded
from quadric_contact.modes.numbers.number_mode import NumberMode
from quadric_contact.modes.numbers.registry import get_mode
from quadric_contact.modes.stacks.packing import Packed, unpack
from quadric_contact.modes.stacks.pairs import MatrixStack, Pairs
from quadric_contact.modes.stacks.validation import exact_matrix
from quadric_contact.theory.pencil import as_quadric

__all__ = [
    "MODE_QUESTIONS",
    "as_stack",
    "is_stack",
    "make_pairs",
    "run_stack",
]


def _is_single(value: Any) -> bool:
    """One quadric given as an object (not a nested sequence or an array)."""
    return isinstance(value, (Quadric, str)) or (type(value).__module__ or "").startswith("sympy")


def _quadric_array(value: Any) -> bool:
    """An object array whose items are Quadrics or equations (not the entries of matrices:
    an object array ending in ``(4, 4)`` holds matrix entries)."""
    if value.ndim >= 2 and tuple(value.shape[-2:]) == (4, 4):
        return False
    return bool(value.size) and _is_single(value.reshape(-1)[0])


def is_stack(value: Any) -> bool:
    """True for a stack of matrices, decided by the type of ``value`` alone.

    A stack is an array (numpy, dask) with at least three dimensions ``(..., 4, 4)``,
    an object array of :class:`~quadric_contact.Quadric` or equations, or a list or
    tuple whose items are matrices (nested sequences or arrays), Quadrics or equations
    (an empty list is an empty stack).  One matrix is a :class:`Quadric`, an equation,
    a sympy expression, a ``(4, 4)`` array or a list of four rows.

    Examples
    --------
    >>> import numpy as np
    >>> is_stack(np.eye(4)), is_stack(np.eye(4)[None]), is_stack(["x**2 - 1"]), is_stack("x - 1")
    (False, True, True, False)
    """
    if type(value) is np.ndarray and value.ndim == 2:
        return False  # one matrix: the commonest single input, read first
    if _is_single(value):
        return False

    if isinstance(value, Packed):
        return True
    ndim = getattr(value, "ndim", None)
    if ndim is not None and hasattr(value, "shape"):
        if int(ndim) >= 3:
            return True
        dtype = getattr(value, "dtype", None)
        if dtype is not None and dtype.kind == "O" and int(ndim) >= 1 and value.size:
            return _quadric_array(value)
        return False
    if isinstance(value, (list, tuple)):
        if not value:
            return True
        first = value[0]
        if _is_single(first):
            return True
        if isinstance(first, (list, tuple)) and first:
            inner = first[0]
            return isinstance(inner, (list, tuple)) or getattr(inner, "ndim", 0) >= 1
        return getattr(first, "ndim", 0) >= 2
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

    if isinstance(value, Packed):
        return _packed_stack(value, name)
    if _is_single(value):
        return _exact_stack([as_quadric(value, name).upper], (), name)
    if isinstance(value, (list, tuple)) and not value:
        return MatrixStack(np.empty((0, 4, 4)), None, True, name, (0,))
    if isinstance(value, (list, tuple)) and any(_is_single(v) for v in value):
        return _exact_stack(
            [as_quadric(v, f"{name}[{k}]").upper for k, v in enumerate(value)], (len(value),), name
        )
    if isinstance(value, np.ndarray) and value.dtype == object and _quadric_array(value):
        flat = value.reshape(-1)
        uppers = [as_quadric(v, f"{name}[{k}]").upper for k, v in enumerate(flat)]
        return _exact_stack(uppers, tuple(value.shape), name)
    arr = matrix_array(value, name)
    batch = arr.shape[:-2]
    kind = arr.dtype.kind
    if kind == "b" or (kind in "iuf" and isinstance(value, (list, tuple)) and _holds_bool(value)):
        # (numpy reads True as 1 in a list of numbers; a single matrix refuses it too)
        raise NotANumberError(f"{name} holds a boolean, not a number", value)
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


def matrix_array(value: Any, name: str) -> np.ndarray:
    """``value`` as a numpy array of shape ``(4, 4)`` or ``(..., 4, 4)``, or the
    :class:`ShapeError` that names ``name`` and what it is instead."""
    try:
        arr = np.asarray(value)
    except (ValueError, TypeError) as exc:
        raise ShapeError(f"{name} is not a matrix or a stack of matrices: {exc}", value) from exc
    if arr.ndim < 2 or arr.shape[-2:] != (4, 4):
        raise ShapeError(f"{name} must have shape (4, 4) or (..., 4, 4), got {arr.shape}", value)
    return arr


def _holds_bool(value: Any) -> bool:
    """A (nested) list or tuple holds a ``bool`` (or ``numpy.bool_``) somewhere."""
    todo = [value]
    while todo:
        v = todo.pop()
        if isinstance(v, (list, tuple)):
            todo.extend(v)
        elif isinstance(v, (bool, np.bool_)):
            return True
    return False


def _packed_stack(value: Any, name: str) -> MatrixStack:
    """A packed stack (:class:`~quadric_contact.modes.stacks.packing.Packed`): binary64 entries are used as
    they are (the fast kernels read them without unpacking); other numbers go through the
    exact conversion of the unpacked matrices."""

    arr = value.array
    batch = tuple(arr.shape[:-1])
    kind = arr.dtype.kind
    if (kind == "f" and arr.dtype.itemsize <= 8) or (
        kind in "iu" and arr.size and int(np.abs(arr).max()) <= 2**53
    ):
        packed = np.ascontiguousarray(arr.reshape(-1, 10), dtype=np.float64)
        return MatrixStack(None, None, False, name, batch, packed=packed)
    if kind in "bc":
        raise NotANumberError(f"{name} is not a stack of real matrices (dtype {arr.dtype})", value)
    full = unpack(arr.reshape(-1, 10))
    return _exact_stack(_object_upper(full.astype(object), name), batch, name)


def _object_upper(arr: np.ndarray, name: str) -> list[tuple[Fraction, ...]]:

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
                        f"M[{i},{j}] = {rows[i][j]} but M[{j},{i}] = {rows[j][i]}; {SYMMETRIZE_HINT}",
                        m,
                        entry=(i, j),
                        index=k,
                    )
        out.append(tuple(rows[i][j] for i, j in ENTRY_INDICES))
    return out


def _exact_stack(uppers: list[tuple[Fraction, ...]], batch: tuple[int, ...], name: str) -> MatrixStack:
    """Exact matrices: binary64 roundings for the float stages; if every entry is a
    binary64 number the stack *is* float input (no rounding at all)."""

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
    """Correctly rounded binary64 value of ``v``, or inf (of its sign) where binary64 cannot
    hold it with a relative error of at most ``u``: beyond its range, or below its normal
    numbers (a non-zero entry rounded to zero or to a subnormal number changed the quadric:
    ``x^2 + y^2 + z^2 - 10^-400`` would become a point).  The filters then leave the entry to
    the later stages, and the plain modes to the exact ones."""
    try:
        f = float(v)
    except OverflowError:
        return math.inf if v > 0 else -math.inf
    if v != 0 and abs(f) < _NORMAL_MIN:
        return math.inf if v > 0 else -math.inf
    return f


_NORMAL_MIN = 2.0**-1022


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


# -- asking a mode about every pair ----------------------------------------------------------

MODE_QUESTIONS = {
    "contact": "contact",
    "region": "region",
    "kind": "kind",
    "overlap": "overlap",
    "plane": "region",
    "smallness": "smallness",
    "criterion": "criterion",
}
"""The questions of :func:`run_stack` and the question of
:meth:`~quadric_contact.modes.NumberMode.decide` each asks (``"plane"``: the region, with every
``Q`` a plane)."""


def run_stack(
    question: str, E: Any, Q: Any, mode: Any = "certified", client: Any = None, compute: bool = True
) -> Any:
    """Ask ``mode`` the question ``question`` about every pair of the broadcast of ``E`` and ``Q``.

    ``question`` is ``"contact"``, ``"region"``, ``"kind"``, ``"overlap"``, ``"plane"``
    (``region`` with every ``Q`` required to be a plane), ``"smallness"`` or ``"criterion"``.  Returns an int8
    array shaped like the broadcast batch (dask input: chunk by chunk, computed unless
    ``compute=False``)."""
    if question not in MODE_QUESTIONS:
        raise ChoiceError(
            f"question must be one of {', '.join(MODE_QUESTIONS)}, got {question!r}",
            question,
            choices=tuple(MODE_QUESTIONS),
        )
    if _is_dask(E) or _is_dask(Q):
        return _run_dask(question, E, Q, mode, client, compute)
    m = get_mode(mode)
    pairs, shape = make_pairs(as_stack(E, "E"), as_stack(Q, "Q"))
    if question == "plane":
        _require_planes(m, pairs)
    codes = m.decide(MODE_QUESTIONS[question], pairs).codes
    return np.asarray(codes, dtype=np.int8).reshape(shape)


def _require_planes(mode: NumberMode, pairs: Pairs) -> None:

    used = np.unique(pairs.q_rows())
    rows = rows_from_masks(mode.classify(pairs.Q, used))
    for k, row in enumerate(rows):
        kind = None if row == UNCERTAIN_ROW else KINDS[int(row) // 2]
        if kind is not QuadricKind.PLANE:
            q = exact_matrix(pairs.Q, int(used[k]))
            kind = q.kind
            if kind is not QuadricKind.PLANE:
                raise NotAPlaneError(
                    f"{pairs.Q.where(int(used[k]))} is not a plane: it is {kind.value}", q, kind=kind
                )


# -- dask ---------------------------------------------------------------------------------------


def _run_dask(what: str, E: Any, Q: Any, mode: Any, client: Any, compute: bool) -> Any:
    import dask  # optional: dask
    import dask.array as da  # optional: dask

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

    def block(e: np.ndarray, q: np.ndarray) -> np.ndarray:
        with single_threaded():
            return np.asarray(run_stack(what, e, q, m), dtype=np.int8).reshape(e.shape[:-2])

    out = da.map_blocks(block, Eb, Qb, drop_axis=[Eb.ndim - 2, Eb.ndim - 1], dtype=np.int8)
    if not shape:
        out = out[0]
    if not compute:
        return out
    if client is not None:
        return np.asarray(client.compute(out).result())
    (result,) = dask.compute(out, scheduler="threads")
    return np.asarray(result)
