"""numba when it is installed, plain Python when it is not."""

from __future__ import annotations

import re
import threading
from collections.abc import Callable
from typing import Any

try:  # pragma: no cover - depends on the environment
    import numba

    HAVE_NUMBA = True
except ImportError:  # pragma: no cover
    numba = None  # type: ignore[assignment,unused-ignore]
    HAVE_NUMBA = False

__all__ = [
    "HAVE_NUMBA",
    "compile_on_a_fresh_stack",
    "jitable",
    "kernel_sources",
    "njit",
    "python_twin",
    "stamp_with_sources",
]


_READ: dict[tuple[str, int, int], tuple[bytes, set[str] | None]] = {}
"""A source file's bytes and, once parsed, the package modules it imports, by path and the
stat that says it has not changed: every kernel module's digest reads the same files, and
parsing them again for each (about 60 ms a module) would be paid at every import."""


def _read(path: Any) -> tuple[tuple[str, int, int], bytes]:
    st = path.stat()
    key = (str(path), st.st_mtime_ns, st.st_size)
    if key not in _READ:
        _READ[key] = (path.read_bytes(), None)
    return key, _READ[key][0]


def _package_imports(root: Any, rel: str) -> set[str]:
    """The package modules ``rel`` imports (at module level or in a function), as paths
    relative to the package root ``root``."""
    import ast

    key, text = _read(root / rel)
    known = _READ[key][1]
    if known is not None:
        return known
    found: set[str] = set()
    for node in ast.walk(ast.parse(text)):
        names: list[str] = []
        if isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            names = [node.module] + [f"{node.module}.{a.name}" for a in node.names]
        elif isinstance(node, ast.Import):
            names = [a.name for a in node.names]
        for name in names:
            if name.startswith("quadric_contact."):
                path = name.removeprefix("quadric_contact.").replace(".", "/") + ".py"
                if (root / path).is_file():
                    found.add(path)
    _READ[key] = (text, found)
    return found


def kernel_sources(root: Any = None, module: str | None = None) -> list[str]:
    """The sources compiled kernels are made of, as paths relative to the package.

    The *compiled modules* are every module of :mod:`quadric_contact.modes` that compiles code
    (it names ``njit`` or ``jitable``) and every module of :mod:`quadric_contact._generated`
    (the programs the kernels inline).  The sources of the kernels of ``module`` (a dotted
    name; all compiled modules if None) are that module, the compiled modules it imports, and
    so on, with every package module any of them imports, at module level or in a function:
    the tables, codes and error constants the kernels read as frozen globals come from there
    (the decision table of :mod:`quadric_contact.theory.decision`, the root-sign table of
    :mod:`quadric_contact.theory.regions`, ...).  A module that does not compile code is read,
    not followed.

    So the Python around the kernels (the cascade of :mod:`quadric_contact.modes.pipeline`, the
    predicates, the modes' classes) is no kernel's source, and a kernel's own module and what
    it inlines are: editing the scale kernel does not recompile the decision kernel."""
    from pathlib import Path

    root = Path(__file__).resolve().parents[1] if root is None else Path(root)
    compiled = {f"_generated/{p.name}" for p in (root / "_generated").glob("*.py")}
    compiled |= {
        f"modes/{p.name}"
        for p in (root / "modes").glob("*.py")
        if re.search(rb"\b(njit|jitable)\b", _read(p)[1])
    }
    start = set(compiled)
    if module is not None:
        rel = module.removeprefix("quadric_contact.").replace(".", "/") + ".py"
        if (root / rel).is_file():
            start = {rel}
    seen: set[str] = set()
    todo = sorted(start)
    while todo:
        rel = todo.pop()
        if rel in seen:
            continue
        seen.add(rel)
        if rel in compiled:
            todo.extend(sorted(_package_imports(root, rel) - seen))
    return sorted(seen)


def _sources_digest(root: Any = None, module: str | None = None) -> str:
    """A digest of :func:`kernel_sources` (of ``module``): their names and bytes."""
    import hashlib
    from pathlib import Path

    root = Path(__file__).resolve().parents[1] if root is None else Path(root)
    digest = hashlib.sha256()
    for rel in kernel_sources(root, module):
        digest.update(rel.encode())
        digest.update(_read(root / rel)[1])
    return digest.hexdigest()


_SOURCES: dict[str, str] = {}


def stamp_with_sources(dispatcher: Any) -> None:
    """numba keys a cached kernel on its own source file only, so a kernel whose file did not
    change but whose inlined helpers or generated programs did (new formulas, new error-bound
    constants) would load stale machine code.  The cache's source stamp is widened to the
    digest of every source the kernel is made of (:func:`kernel_sources` of its module); an
    older cache entry then no longer matches and is compiled again.  (If a numba version keeps
    its stamp elsewhere, nothing is changed.)"""
    cache = getattr(dispatcher, "_cache", None)
    # numba 0.68 keeps the stamp on the index file of the cache; look on the cache itself too
    holder = getattr(cache, "_cache_file", cache)
    if holder is None or not hasattr(holder, "_source_stamp"):
        return
    module = str(getattr(getattr(dispatcher, "py_func", None), "__module__", "") or "")
    if module not in _SOURCES:
        _SOURCES[module] = _sources_digest(module=module or None)
    holder._source_stamp = (holder._source_stamp, _SOURCES[module])


def compile_on_a_fresh_stack(dispatcher: Any) -> None:
    """Compile (or load from the cache) in a new thread, whose Python stack starts empty.

    CPython 3.11 keeps each thread's frames in 16 KiB chunks that it maps when a call
    crosses the end of a chunk and unmaps when that call returns.  numba's compiler makes
    millions of short calls; when the depth at which it runs puts one of its hot loops
    astride a chunk boundary, every call maps and unmaps a chunk.  Measured on the float
    kernels: 8.3 million mmap/munmap pairs, 9.3 million page faults and 42 s of system time
    when compiled under pytest, against 0.27 million, 1.3 million and 9 s from a plain
    script; the first complete decision in a pytest-xdist worker took 325 s (146 s of it
    system time) instead of 130 s.  Where that happens depends only on how deep the
    caller's stack is, so the caller (a test runner, a notebook, a web server) decided
    whether the first use took two minutes or five.  Run from a thread of its own, the
    compiler starts at the same depth whatever called it (the same worker: 130 s, 9 s of
    system time, 1.3 million page faults).

    numba calls ``_compile_for_args`` when a Python-level call finds no compiled version
    for its argument types (compiling, or loading the cache entry); a kernel that calls
    another compiles it through ``compile``, inside the same thread, so the compiler's
    lock (held by the compiling thread) is never waited for by a thread it waits on."""
    compile_for_args = dispatcher._compile_for_args

    def compile_elsewhere(*args: Any, **kws: Any) -> Any:
        outcome: dict[str, Any] = {}

        def run() -> None:
            try:
                outcome["value"] = compile_for_args(*args, **kws)
            except BaseException as exc:  # re-raised in the calling thread
                outcome["error"] = exc

        worker = threading.Thread(target=run, name="quadric-contact compiler", daemon=True)
        worker.start()
        worker.join()
        if "error" in outcome:
            raise outcome["error"]
        return outcome["value"]

    dispatcher._compile_for_args = compile_elsewhere


def njit(fn: Callable[..., Any] | None = None, *, inline: bool = False, cache: bool = True) -> Any:
    """``numba.njit`` (``inline="always"`` for the small helpers the kernels inline;
    ``nogil`` and cached for the kernels themselves), or the function unchanged.

    ``error_model="numpy"``: division follows IEEE 754 (no zero check raising
    ``ZeroDivisionError``, whose branch would keep the loops from vectorising); the
    kernels guard every quotient they use.  A cached kernel is keyed on every source it is
    made of (:func:`stamp_with_sources`), not only its own file."""

    def wrap(f: Callable[..., Any]) -> Any:
        if not HAVE_NUMBA:
            return f
        if inline:
            return numba.njit(inline="always", error_model="numpy")(f)
        dispatcher = numba.njit(nogil=True, cache=cache, error_model="numpy")(f)
        if cache:
            stamp_with_sources(dispatcher)
        compile_on_a_fresh_stack(dispatcher)
        return dispatcher

    return wrap(fn) if fn is not None else wrap


def jitable(fn: Callable[..., Any]) -> Callable[..., Any]:
    """Make a plain function callable from compiled kernels and return it unchanged.

    For small building blocks that call one another (the double-double primitives of
    :mod:`~quadric_contact.modes.double_double`): unlike :func:`njit`, which returns a numba
    dispatcher, the name stays bound to the Python function, so the same function runs on
    Python floats and on numpy arrays (the ``numpy`` backend) and the calls inside it resolve
    to Python functions there; numba compiles it (``numba.extending.register_jitable``, with
    the kernels' ``error_model="numpy"``) where a compiled function calls it, once per
    signature, and LLVM inlines it into the caller.  Without numba, nothing is registered."""
    if HAVE_NUMBA:
        from numba.extending import register_jitable

        register_jitable(error_model="numpy")(fn)
    return fn


def python_twin(fn: Callable[..., Any]) -> Callable[..., Any]:
    """``fn`` (a kernel's Python source) run by Python all the way down.

    A kernel's Python variant (the ``numpy`` backend, the oracle of equal bits) calls its
    helpers by the names its module binds to numba dispatchers.  A dispatcher called from
    Python is compiled on its own, and an inline helper is not cached: every process that ran
    the Python variant compiled its helpers again (38 s for the signature kernel's).  The twin
    reads every such name, in ``fn`` and in the helpers it reaches, as a twin of the plain
    function the dispatcher was made from, so nothing is compiled; the compiled kernel is
    untouched."""
    import types

    made: dict[int, Callable[..., Any]] = {}

    def names(code: types.CodeType) -> set[str]:
        found = set(code.co_names)
        for const in code.co_consts:
            if isinstance(const, types.CodeType):
                found |= names(const)
        return found

    def twin(f: types.FunctionType) -> Callable[..., Any]:
        done = made.get(id(f))
        if done is not None:
            return done
        scope = dict(f.__globals__)
        new = types.FunctionType(f.__code__, scope, f.__name__, f.__defaults__, f.__closure__)
        new.__kwdefaults__ = f.__kwdefaults__
        made[id(f)] = new
        for name in names(f.__code__):
            plain = getattr(scope.get(name), "py_func", None)
            if isinstance(plain, types.FunctionType):
                scope[name] = twin(plain)
        return new

    plain = getattr(fn, "py_func", fn)
    assert isinstance(plain, types.FunctionType)
    body = twin(plain)

    def run(*args: Any) -> Any:
        import numpy as np

        # IEEE 754 as the compiled kernels have it (error_model="numpy"): an overflow or a
        # division by zero gives inf or NaN, which the guards read, and says nothing
        with np.errstate(all="ignore"):
            return body(*args)

    return run


# -- first use: one line when the kernels are compiled rather than loaded ---------------------
#
# numba compiles a kernel the first time it is called with a new signature and keeps the
# machine code in its on-disk cache (``cache=True``: next to the package when that directory
# is writable, otherwise the user cache directory, ``~/.cache/numba`` on Linux;
# ``NUMBA_CACHE_DIR`` overrides both).  Later processes load it in milliseconds.  The first
# compilation of the complete decision takes minutes of CPU time, so the first time a kernel
# of this package misses the cache the process says so, once, on stderr.

COMPILE_NOTICE = (
    "quadric-contact: compiling the numba kernels once for this machine (about two minutes of CPU "
    "time for the first complete decision, seven for every layout and mode, spread over the first "
    "calls that need them); later processes load them from the on-disk cache{where}"
)
"""The line printed (stderr) the first time a kernel of the package is compiled in a process."""

_notice_printed = False


def _cache_dir(dispatcher: Any) -> str:
    cache = getattr(dispatcher, "_cache", None)
    path = getattr(cache, "_cache_path", None)
    return f" ({path})" if path else ""


if HAVE_NUMBA:  # pragma: no branch
    import sys

    from numba.core import event as _event

    class _CompileNotice(_event.Listener):  # type: ignore[misc,unused-ignore]
        """Prints :data:`COMPILE_NOTICE` when a dispatcher of this package misses the cache."""

        def on_start(self, ev: Any) -> None:
            global _notice_printed
            if _notice_printed:
                return
            dispatcher = (ev.data or {}).get("dispatcher")
            module = getattr(getattr(dispatcher, "py_func", None), "__module__", "") or ""
            if not module.startswith("quadric_contact"):
                return
            if not _cache_dir(dispatcher):
                # not a cache miss: an uncached helper (inline="always") called from Python is
                # compiled in every process, in a few seconds, and no cache would keep it
                return
            _notice_printed = True
            print(COMPILE_NOTICE.format(where=_cache_dir(dispatcher)), file=sys.stderr, flush=True)

        def on_end(self, ev: Any) -> None:
            pass

    _event.register("numba:compile", _CompileNotice())
