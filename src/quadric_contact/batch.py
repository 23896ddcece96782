"""Array predicates over stacks of matrices (number modes)."""

from __future__ import annotations

from typing import Any

__all__ = ["is_stack", "relative_position_batch", "transversal_contact_batch"]


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


def transversal_contact_batch(E: Any, Q: Any, *, mode: str = "certified") -> Any:
    raise NotImplementedError("array predicates are not available yet")


def relative_position_batch(E: Any, Q: Any, *, mode: str = "certified") -> Any:
    raise NotImplementedError("array predicates are not available yet")
