"""The array kernels, compiled (or loaded from numba's on-disk cache) once before the tests run.

numba compiles a kernel the first time it is called with a new signature and keeps the machine
code in its cache; the first compilation of the complete decision takes minutes.  Under
pytest-xdist every worker that reaches a kernel first would compile it at the same time, each
behind pytest's capture, so the notice the package prints (:data:`quadric_contact.modes._jit.
COMPILE_NOTICE`) would not be seen.  :func:`warm_kernels` calls every question of the array
API in the float, filter and certified modes, on distinct pairs and on one matrix against a
stack, float64 and packed, so that the workers load the kernels from the cache.
"""

from __future__ import annotations

import functools
import time
from collections.abc import Callable
from typing import Any

WARM_PAIRS = 64


def _calls() -> list[tuple[str, Callable[[], Any]]]:
    import numpy as np

    import quadric_contact as qc
    from quadric_contact.testing.samples import random_ellipsoids, random_pairs

    rng = np.random.default_rng(0)
    E, Q, _ = random_pairs(WARM_PAIRS, rng)
    Es, _ = random_ellipsoids(WARM_PAIRS, rng, axes=(0.5, 2.0))
    Qs, _ = random_ellipsoids(WARM_PAIRS, rng, axes=(2.0, 5.0))
    PE, PQ = qc.Packed(qc.pack(Es)), qc.Packed(qc.pack(Qs))
    inputs = {
        "distinct": (E, Q),
        "one against a stack": (E, Q[0]),
        "ellipsoids": (Es, Qs),
        "ellipsoids, one against a stack": (Es, Qs[0]),
        "packed": (PE, PQ),
    }
    questions: dict[str, Callable[..., Any]] = {
        "corollary_10": qc.corollary_10,
        "transversal_contact": qc.transversal_contact,
        "relative_position": qc.relative_position,
        "smallness": qc.smallness,
        "overlap": qc.overlap,
    }
    calls = []
    for label, (e, q) in inputs.items():
        for name, fn in questions.items():
            if name == "overlap" and not label.startswith(("ellipsoids", "packed")):
                continue  # overlap asks about two ellipsoids
            for mode in ("float", "filter", "certified"):
                call = functools.partial(fn, e, q, mode=mode)
                calls.append((f"{name}({label}, mode={mode!r})", call))
    return calls


def warm_kernels(log: Callable[[str], None] = print) -> float:
    """Call every kernel the array API compiles, once; return the seconds it took.  A call that
    raises is reported on ``log`` and skipped (the tests will say what is wrong with it)."""
    start = time.perf_counter()
    for what, call in _calls():
        try:
            call()
        except Exception as exc:  # reported, not raised: the tests themselves fail on it
            log(f"  {what}: {type(exc).__name__}: {exc}")
    return time.perf_counter() - start


if __name__ == "__main__":
    print(f"{warm_kernels():.1f} s")
