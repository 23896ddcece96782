"""Smallness (Definition 1; Tables 1-2 as corrected) for stacks of matrices, in every number mode.

:func:`smallness_codes` takes what :func:`~quadric_contact.batch.transversal_contact_batch`
takes (one ``(4, 4)`` matrix or a stack ``(..., 4, 4)`` for each of ``E`` and ``Q``,
numpy arrays of any real dtype, nested lists, object arrays of exact rationals, lists of
:class:`~quadric_contact.Quadric`, equations), broadcasts them, and returns
:class:`~quadric_contact.modes.base.SmallnessCode` values, the same meaning for every
input form and every mode:

=====================  ===========================================================
``NOT_SMALL`` (0)      the corrected Table 1 row of ``Q`` fails (and, for two ellipsoids,
                       so does the enclosing alternative)
``SMALL`` (1)          the row holds: Corollary 10 and Theorem 13 / Table 4 apply
``UNCERTAIN`` (2)      only from ``filter`` and ``ball``, which abstain where unsure
``EXCLUDED`` (3)       ``Q`` has no row in Table 1 (plane, cone, intersecting or coincident
                       planes, no real points): the scalar decision raises there
``SMALL_ENCLOSING`` (4) two ellipsoids, ``Q`` small with respect to ``E`` only: Corollary 10
                       applies, Table 4 does not
=====================  ===========================================================

In the certified modes (``certified``, ``exact``) every code equals what the exact
scalar :func:`quadric_contact.smallness.smallness` says of the pair (``EXCLUDED`` where
it raises :class:`~quadric_contact.errors.ExcludedQuadricError`); ``filter`` and
``ball`` agree with it wherever they answer; ``float`` and ``mpmath`` always answer and
may be wrong near the boundary of a condition.

The certified mode runs the cascade of :class:`~quadric_contact.modes.CertifiedMode`:
the binary64 filter (:mod:`~quadric_contact.modes.smallness_float`: eigenvalue
enclosures certified by Descartes' rule, interval monomials), then ball arithmetic,
then the exact scalar decision for the pairs still undecided (ties such as two equal
spheres); pass a mode instance to read :attr:`~quadric_contact.modes.NumberMode.last`.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .base import NumberMode, SmallnessCode

__all__ = ["SmallnessCode", "smallness_codes"]


def smallness_codes(
    E: Any, Q: Any, *, mode: str | NumberMode = "certified", client: Any = None, compute: bool = True
) -> Any:
    """Is each ellipsoid ``E`` small with respect to its quadric ``Q`` (Definition 1)?

    Parameters
    ----------
    E : array_like, shape (4, 4) or (..., 4, 4), Quadric, equation, or a list of them
        Real ellipsoids (either sign of the matrix).
    Q : array_like, shape (4, 4) or (..., 4, 4), Quadric, equation, or a list of them
        Quadrics (either sign).
    mode : str or NumberMode
        ``"certified"`` (default, never wrong), ``"exact"``, ``"filter"``, ``"ball"``,
        ``"float"``, ``"mpmath"``, or a mode instance.
    client : dask.distributed.Client, optional
        For dask input: compute on this cluster (default: dask's local threads).
    compute : bool
        For dask input: the computed numpy array (default) or the lazy dask array.

    Returns
    -------
    numpy.ndarray of int8 with the broadcast batch shape, or one SmallnessCode for one pair

    Raises
    ------
    ShapeError, NonFiniteError, NotSymmetricError, NotANumberError
        Bad input, naming the matrix at fault.
    NotAnEllipsoidError
        An ``E`` that is not a real ellipsoid.

    References
    ----------
    Definition 1, Lemma 3, Lemma 4, Theorem 5, Tables 1 and 2 (with the corrections of
    :mod:`quadric_contact.smallness`).

    Examples
    --------
    Example 17: the bee is small with respect to both pieces of the tree; a plane has no
    row in Table 1; a sphere of radius 2 around the unit sphere is small only the other
    way round:

    >>> bee = "(x-3)**2 + (y-3)**2 + 3*(z-5.5)**2 - 0.1"
    >>> crown = "x**2 + y**2 + 3*(z - 8.36291)**2 - 20"
    >>> trunk = "x**2 + y**2 - 0.25*(z-3)**2 - 1"
    >>> from quadric_contact import Quadric
    >>> smallness_codes(bee, [Quadric.from_equation(s) for s in (crown, trunk, "z - 6")])
    array([1, 1, 3], dtype=int8)
    >>> smallness_codes(Quadric.sphere(2), Quadric.sphere(1))
    <SmallnessCode.SMALL_ENCLOSING: 4>
    """
    from ..batch import _is_dask, as_stack, make_pairs
    from . import get_mode

    m = get_mode(mode)
    if _is_dask(E) or _is_dask(Q):
        return _dask_codes(E, Q, m, client, compute)
    pairs, shape = make_pairs(as_stack(E, "E"), as_stack(Q, "Q"))
    codes = m.smallness(pairs)
    if shape == ():
        return SmallnessCode(int(codes[0]))
    return np.asarray(codes, dtype=np.int8).reshape(shape)


def _dask_codes(E: Any, Q: Any, mode: NumberMode, client: Any, compute: bool) -> Any:
    """Chunk by chunk, as :func:`~quadric_contact.batch.transversal_contact_batch` does for dask input."""
    import dask
    import dask.array as da

    from ..batch import _is_dask
    from ..errors import ShapeError
    from .float64 import single_threaded

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
            return np.asarray(smallness_codes(e, q, mode=mode), dtype=np.int8).reshape(e.shape[:-2])

    out = da.map_blocks(block, Eb, Qb, drop_axis=[Eb.ndim - 2, Eb.ndim - 1], dtype=np.int8)
    if not shape:
        out = out[0]
    if not compute:
        return out
    if client is not None:
        return np.asarray(client.compute(out).result())
    (result,) = dask.compute(out, scheduler="threads")
    return np.asarray(result)
