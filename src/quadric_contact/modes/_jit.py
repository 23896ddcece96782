"""numba when it is installed, plain Python when it is not."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

try:  # pragma: no cover - depends on the environment
    import numba

    HAVE_NUMBA = True
except ImportError:  # pragma: no cover
    numba = None  # type: ignore[assignment,unused-ignore]
    HAVE_NUMBA = False

__all__ = ["HAVE_NUMBA", "njit"]


def njit(fn: Callable[..., Any] | None = None, *, inline: bool = False, cache: bool = True) -> Any:
    """``numba.njit`` (``inline="always"`` for the small helpers the kernels inline;
    ``nogil`` and cached for the kernels themselves), or the function unchanged.

    ``error_model="numpy"``: division follows IEEE 754 (no zero check raising
    ``ZeroDivisionError``, whose branch would keep the loops from vectorising); the
    kernels guard every quotient they use."""

    def wrap(f: Callable[..., Any]) -> Any:
        if not HAVE_NUMBA:
            return f
        if inline:
            return numba.njit(inline="always", error_model="numpy")(f)
        return numba.njit(nogil=True, cache=cache, error_model="numpy")(f)

    return wrap(fn) if fn is not None else wrap
