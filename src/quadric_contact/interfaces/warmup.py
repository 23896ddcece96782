"""The array kernels compiled into numba's on-disk cache (or loaded from it), all at once.

numba compiles a kernel the first time it is called with a new signature and keeps the machine
code in its on-disk cache; the first compilation of the complete decision takes about 40 s of
CPU time, of every kernel about 100 s.  :func:`warm_kernels` calls every
question of the array API in the float, filter and certified modes, on distinct pairs, on one
matrix against a stack (either side), float64 and packed, and on nearly touching pairs (the
later stages), the first-contact scale and the distance of separated and of crossing
ellipsoids on stacks, and the bench's read of its inputs, so that every kernel is in the cache
afterwards.

Who runs it:

* ``quadric-contact compile``, in the foreground, with a line for each call that compiled;
* the test suite, before its workers start (``python -m quadric_contact.interfaces.warmup``,
  twice at once on two cores: ``--reverse`` runs the list from its other end);
* the package itself, once per machine and per version of the kernels' sources, in a
  background process (``--background``: lowest priority, no output but a log next to the
  cache, one at a time): the first call of a process that finds a kernel missing from the
  cache starts it, and meanwhile answers small calls with the kernels' Python twins
  (``quadric_contact.modes.kernels._jit.compile_on_a_fresh_stack``).
"""

from __future__ import annotations

import contextlib
import functools
import os
import sys
import time
from collections.abc import Callable
from typing import Any

import numpy as np

import quadric_contact as qc
from quadric_contact.modes.kernels import _jit
from quadric_contact.modes.kernels.support_drivers import read_all
from quadric_contact.testing.samples import random_ellipsoids, random_pairs

WARM_PAIRS = 64


def calls() -> list[tuple[str, Callable[[], Any]]]:
    """The warm-up's calls, each with a line that says what it asks (also the list whose
    certified calls the native kernels are built from: :mod:`quadric_contact.codegen.native`)."""
    rng = np.random.default_rng(0)
    E, Q, _ = random_pairs(WARM_PAIRS, rng)
    Es, _ = random_ellipsoids(WARM_PAIRS, rng, axes=(0.5, 2.0))
    Qs, _ = random_ellipsoids(WARM_PAIRS, rng, axes=(2.0, 5.0))
    Et, Qt = _near_touching()
    PE, PQ = qc.Packed(qc.pack(Es)), qc.Packed(qc.pack(Qs))
    inputs = {
        "distinct": (E, Q),
        "one against a stack": (E, Q[0]),
        "a stack against one": (E[0], Q),
        "ellipsoids": (Es, Qs),
        "ellipsoids, one against a stack": (Es, Qs[0]),
        "ellipsoids, a stack against one": (Es[0], Qs),
        "ellipsoids, nearly touching": (Et, Qt),
        "packed": (PE, PQ),
    }
    questions: dict[str, Callable[..., Any]] = {
        "corollary_10": qc.corollary_10,
        "transversal_contact": qc.transversal_contact,
        "relative_position": qc.relative_position,
        "smallness": qc.smallness,
        "overlap": qc.overlap,
    }
    first: list[tuple[str, Callable[[], Any]]] = []
    # Ellipsoids of equal size ranges, many of them: some pairs leave the decision kernel's lane
    # (an uncertain reading), so the general steps' separation kernel is reached on ellipsoid
    # pairs as well (the lane takes every pair of the small stacks below).  First in the list:
    # the decision kernel is the longest compile, and the second process, which starts from the
    # tail, compiles other kernels meanwhile.
    rng = np.random.default_rng(4)
    Em, _ = random_ellipsoids(3000, rng, axes=(0.5, 2.0), box=2.0)
    Qm, _ = random_ellipsoids(3000, rng, axes=(0.5, 2.0), box=2.0)
    for name in ("transversal_contact", "relative_position", "overlap"):
        call = functools.partial(questions[name], Em, Qm, mode="certified")
        first.append((f"{name}(ellipsoids of equal sizes, 3000, mode='certified')", call))
    calls = []
    # mode by mode, certified first and float last: the second process, from the tail, starts
    # with the float kernels (unfiltered criterion, plain signature), the first with the
    # certified ones, so that the two seldom compile the same kernel at the same time
    for mode in ("certified", "filter", "float"):
        for label, (e, q) in inputs.items():
            for name, fn in questions.items():
                if name == "overlap" and not label.startswith(("ellipsoids", "packed")):
                    continue  # overlap asks about two ellipsoids
                call = functools.partial(fn, e, q, mode=mode)
                calls.append((f"{name}({label}, mode={mode!r})", call))
    # the first-contact scale (one-sided: distinct pairs and one quadric against the stack;
    # two-sided) and the distance of separated and crossing ellipsoids (the duality and the
    # depth kernels), which the tests of those functions otherwise compile in a worker, each
    # worker that reaches them first
    far = np.stack([_ellipsoid((0.5, 0.7, 0.9), (6.0 + k, 0.0, 0.0)) for k in range(4)])
    near = np.stack([_ellipsoid((1.0, 2.0, 1.5), (0.0, 0.0, 0.0))] * 4)
    calls.append(("contact_scale(ellipsoids)", functools.partial(qc.contact_scale, Es, Qs)))
    calls.append(
        ("contact_scale(ellipsoids, one against a stack)", functools.partial(qc.contact_scale, Es, Qs[0]))
    )
    calls.append(
        ("contact_scale(ellipsoids, scale='both')", functools.partial(qc.contact_scale, Es, Qs, scale="both"))
    )
    calls.append(("distance(ellipsoids apart)", functools.partial(qc.distance, far, near)))
    crossing = np.stack([_ellipsoid((0.5, 0.7, 0.9), (0.5 + 0.2 * k, 0.0, 0.0)) for k in range(4)])
    calls.append(("distance(ellipsoids crossing)", functools.partial(qc.distance, crossing, near)))

    calls.append(("read_all (the bench's read-bandwidth limit)", functools.partial(read_all, Es, Qs)))
    return first + calls


def _near_touching() -> tuple[Any, Any]:
    """Pairs of spheres and ellipsoids touching from outside, moved apart by ``1e-12`` to
    ``1e-16`` of their size, equal sizes among them: the float stages cannot decide them, so the
    later stages (tighter enclosures, the exact pencil) are compiled too."""
    pairs = []
    for a, b in (((1.0, 1.0, 1.0), (1.0, 1.0, 1.0)), ((0.5, 0.7, 0.9), (2.0, 3.0, 4.0))):
        for d in (1e-12, 1e-14, 1e-15, 1e-16, -1e-15):
            shift = (a[0] + b[0]) * (1 + d)
            pairs.append((_ellipsoid(a, (shift, 0.0, 0.0)), _ellipsoid(b, (0.0, 0.0, 0.0))))
    return np.stack([e for e, _ in pairs]), np.stack([q for _, q in pairs])


def _ellipsoid(axes: tuple[float, float, float], center: tuple[float, float, float]) -> Any:
    """``sum ((x_i - c_i) / a_i)^2 - 1`` as a 4 x 4 matrix (homogeneous coordinate last)."""
    M = np.zeros((4, 4))
    for i, (a, c) in enumerate(zip(axes, center, strict=True)):
        M[i, i] = 1 / a**2
        M[i, 3] = M[3, i] = -c / a**2
        M[3, 3] += c**2 / a**2
    M[3, 3] -= 1.0
    return M


def warm_kernels(
    log: Callable[[str], None] = print,
    *,
    reverse: bool = False,
    only: Callable[[str], bool] | None = None,
) -> tuple[float, int]:
    """Call every kernel the array API compiles, once; return the seconds it took and how many
    kernels missed numba's on-disk cache (were compiled).  A call that raises is reported on
    ``log`` and skipped (the tests will say what is wrong with it).  ``reverse``: the calls in
    the opposite order (a second process, started alongside, compiles the kernels of the other
    end of the list first; where the two meet, each loads what the other has cached).  ``only``:
    the calls whose description it accepts (all if None)."""
    from numba.core import event  # numba is optional: only the warm-up's listener imports it

    missed = []

    class CacheMisses(event.Listener):
        """Compilations of the package's cached kernels (its uncached inline helpers, which a
        Python-level call compiles in every process, do not count)."""

        def on_start(self, ev: Any) -> None:
            dispatcher = (ev.data or {}).get("dispatcher")
            module = getattr(getattr(dispatcher, "py_func", None), "__module__", "") or ""
            cache = getattr(dispatcher, "_cache", None)
            if module.startswith("quadric_contact") and getattr(cache, "_cache_path", None):
                missed.append(dispatcher)

        def on_end(self, ev: Any) -> None:
            pass

    listener = CacheMisses()
    event.register("numba:compile", listener)
    start = time.perf_counter()
    try:
        listed = [c for c in calls() if only is None or only(c[0])]
        todo = list(reversed(listed) if reverse else listed)
        # first pass: a call whose kernel another process is compiling (the other warm-up of
        # the test run, a user's process) is put off rather than compiled twice at once; the
        # second pass runs what was put off, which then mostly loads from the cache
        later: list[tuple[str, Callable[[], Any]]] = []
        for last in (False, True):
            for what, call in todo:
                before, t0 = len(missed), time.perf_counter()
                try:
                    if last:
                        call()
                    else:
                        with _jit.deferring():
                            call()
                except _jit.KernelBusy:
                    later.append((what, call))
                    continue
                except Exception as exc:  # reported, not raised: the tests themselves fail on it
                    log(f"  {what}: {type(exc).__name__}: {exc}")
                if len(missed) > before:  # progress, where a compile makes the wait long
                    log(f"  {what}: {len(missed) - before} compiled in {time.perf_counter() - t0:.0f} s")
            todo, later = later, []
    finally:
        event.unregister("numba:compile", listener)
    return time.perf_counter() - start, len(missed)


def run(*, reverse: bool = False, log: Callable[[str], None] = print) -> int:
    """Warm the kernels in this process, every call waiting for its kernel (no twins); say on
    ``log`` how long it took; return how many kernels were compiled."""
    _jit.set_kernel_policy("wait")
    seconds, compiled = warm_kernels(log=log, reverse=reverse)
    how = f"{compiled} compiled" if compiled else "loaded from numba's on-disk cache"
    order = " (from the end of the list)" if reverse else ""
    log(f"quadric-contact: array kernels {how} in {seconds:.1f} s{order}")
    return compiled


def background() -> None:
    """The background warm-up the package starts (see the module's docstring): at once if
    another one holds the lock; else at the lowest priority, logging to a file next to the
    cache, and leaving the marker that says the cache holds every kernel of these sources."""
    with _jit.warmup_lock() as held:
        if not held:
            return
        with contextlib.suppress(OSError):  # not allowed: run at the priority we have
            os.nice(19)
        with open(_jit.warmup_path("log"), "a", encoding="utf-8") as log:

            def say(line: str) -> None:
                print(line, file=log, flush=True)

            run(log=say)
        _jit.warmup_done()


def main() -> None:
    """``python -m quadric_contact.interfaces.warmup [--reverse | --background]``: what the
    test run's first process calls (in processes of their own, whose memory, several GB while
    numba compiles, is returned when they end), one line with the time it took; or the
    package's background warm-up."""
    if "--background" in sys.argv[1:]:
        background()
        return
    run(reverse="--reverse" in sys.argv[1:], log=lambda line: print(line, flush=True))


if __name__ == "__main__":
    main()
