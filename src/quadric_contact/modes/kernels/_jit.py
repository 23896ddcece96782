"""numba when it is installed, plain Python when it is not."""

from __future__ import annotations

import ast
import hashlib
import os
import re
import subprocess
import sys
import threading
import types
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np

from quadric_contact.modes.kernels import native

PACKAGE_ROOT = Path(__file__).resolve().parents[2]
"""The directory of this copy of the package (a checkout's ``src/quadric_contact``, or an
installed one)."""


try:  # pragma: no cover - depends on the environment
    import numba

    HAVE_NUMBA = True
except ImportError:  # pragma: no cover
    numba = None  # type: ignore[assignment,unused-ignore]
    HAVE_NUMBA = False

__all__ = [
    "CALL_OBSERVERS",
    "HAVE_NUMBA",
    "PACKAGE_ROOT",
    "compile_on_a_fresh_stack",
    "compiled",
    "forget_native",
    "jitable",
    "kernel_cache_dir",
    "kernel_sources",
    "native_kernel",
    "njit",
    "pairs",
    "plain",
    "route_native",
    "select",
    "sources_digest",
    "stamp_with_sources",
    "turned_off",
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

    So the Python around the kernels (the cascade of :mod:`quadric_contact.modes.decision.pipeline`, the
    predicates, the modes' classes, the lookup of native kernels) is no kernel's source, and a
    kernel's own module and what it inlines are: editing the scale kernel does not recompile the
    decision kernel.  This module is a source of every kernel; what it imports is not."""

    root = PACKAGE_ROOT if root is None else Path(root)
    compiled = {f"_generated/{p.name}" for p in (root / "_generated").glob("*.py")}
    compiled |= {
        p.relative_to(root).as_posix()
        for p in (root / "modes").rglob("*.py")
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
        if rel in compiled and rel != _THIS:
            todo.extend(sorted(_package_imports(root, rel) - seen))
    return sorted(seen)


_THIS = "modes/kernels/_jit.py"
"""This module: a source of every kernel (the options it compiles them with), whose own imports
are not (the library of native kernels it looks kernels up in is no kernel's code)."""


def _sources_digest(root: Any = None, module: str | None = None) -> str:
    """A digest of :func:`kernel_sources` (of ``module``): their names and bytes."""

    root = PACKAGE_ROOT if root is None else Path(root)
    digest = hashlib.sha256()
    for rel in kernel_sources(root, module):
        digest.update(rel.encode())
        digest.update(_read(root / rel)[1])
    return digest.hexdigest()


_SOURCES: dict[str, str] = {}


def sources_digest(module: str) -> str:
    """The digest of the sources the kernels of ``module`` (a dotted name) are made of, once per
    process: what a cached or a native kernel is keyed on."""
    if module not in _SOURCES:
        _SOURCES[module] = _sources_digest(module=module or None)
    return _SOURCES[module]


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
    holder._source_stamp = (holder._source_stamp, sources_digest(module))


TWIN_ELEMENTS = 1 << 20
"""A call whose array arguments hold at most this many elements in all, and whose kernel is not
compiled yet, runs the kernel's Python twin (:func:`plain`) instead of waiting for the
compile: for the complete decision that is about 27 000 pairs, which its twin answers in about
a second, where the compile takes about 40 s.  A larger call compiles what it needs."""

KERNEL_POLICIES = ("background", "wait", "twins")
"""What a call does when its kernel is not compiled (``QUADRIC_CONTACT_KERNELS`` in the
environment, or :func:`set_kernel_policy`):

* ``background`` (the default): a small call runs the twin, and the first such call starts the
  background warm-up (:mod:`quadric_contact.interfaces.warmup`), which fills the on-disk cache
  once per machine; later calls load each kernel from the cache as soon as it is there;
* ``wait``: every call waits for its kernel, compiled in this process (the test suite, whose
  tests of a compiled kernel must run it, and the warm-up itself);
* ``twins``: as ``background``, without starting the warm-up (small calls run the twins until
  ``quadric-contact compile`` has filled the cache).

The answers are the same bits whatever the policy: it chooses how long the first calls take."""


def _policy_from_environment() -> str:
    value = os.environ.get("QUADRIC_CONTACT_KERNELS", "background")
    if value not in KERNEL_POLICIES:
        raise ValueError(f"QUADRIC_CONTACT_KERNELS must be one of {KERNEL_POLICIES}, got {value!r}")
    return value


_POLICY = _policy_from_environment()


def set_kernel_policy(policy: str) -> None:
    """Choose what a call does when its kernel is not compiled (:data:`KERNEL_POLICIES`)."""
    global _POLICY
    if policy not in KERNEL_POLICIES:
        raise ValueError(f"the kernel policy must be one of {KERNEL_POLICIES}, got {policy!r}")
    _POLICY = policy


class _Compiles:
    """One dispatcher's compiles under way in this process, by signature, and its twin."""

    def __init__(self, dispatcher: Any) -> None:
        self.dispatcher = dispatcher
        self.lock = threading.Lock()
        self.jobs: dict[Any, tuple[threading.Thread, dict[str, Any]]] = {}
        self.twin: Callable[..., Any] | None = None

    def start(
        self, sig: Any, compile_for_args: Callable[..., Any], args: Any
    ) -> tuple[threading.Thread, dict[str, Any]]:
        """The compile for the arguments ``args`` (of the types ``sig``) in a thread of its own,
        started now if it is not under way.  numba reads their types only; the thread keeps
        them until it ends."""
        with self.lock:
            job = self.jobs.get(sig)
            if job is None:
                outcome: dict[str, Any] = {}

                def run() -> None:
                    try:
                        outcome["value"] = compile_for_args(*args)
                    except BaseException as exc:  # re-raised in a calling thread
                        outcome["error"] = exc

                worker = threading.Thread(target=run, name="quadric-contact compiler", daemon=True)
                job = self.jobs[sig] = (worker, outcome)
                worker.start()
            return job

    def wait(self, sig: Any, compile_for_args: Callable[..., Any], args: Any) -> Any:
        worker, outcome = self.start(sig, compile_for_args, args)
        worker.join()
        if "error" in outcome:
            with self.lock:
                self.jobs.pop(sig, None)  # the next call tries again (and says why)
            raise outcome["error"]
        return outcome["value"]

    def twin_of(self) -> Callable[..., Any]:
        with self.lock:
            if self.twin is None:
                self.twin = plain(self.dispatcher)
            return self.twin

    def load(self, sig: Any) -> Any:
        """The compiled kernel for ``sig`` if the on-disk cache has it (added to the dispatcher
        as numba's own ``compile`` adds it), else None; nothing is compiled.  None too while
        a compile holds numba's compiler lock in this process: waiting for it to load a
        kernel would wait for the whole compile."""
        from numba.core.compiler_lock import global_compiler_lock  # numba only

        lock = getattr(global_compiler_lock, "_lock", None)
        if lock is None or not lock.acquire(blocking=False):
            return None
        try:
            d = self.dispatcher
            existing = d.overloads.get(tuple(sig))
            if existing is not None:
                return existing.entry_point
            cres = d._cache.load_overload(sig, d.targetctx)
            if cres is None:
                return None
            d._cache_hits[sig] += 1
            if not cres.objectmode:
                d.targetctx.insert_user_function(cres.entry_point, cres.fndesc, [cres.library])
            d.add_overload(cres)
            return cres.entry_point
        finally:
            lock.release()


def _elements(args: Any) -> int:

    return sum(int(a.size) for a in args if isinstance(a, np.ndarray))


CALL_OBSERVERS: list[Callable[[Any, Any], None]] = []
"""Functions told of every call of a kernel from Python that finds no compiled version in the
dispatcher, with the dispatcher and the argument types (the build of the native kernels
records what the calls need this way)."""

_NATIVE: dict[tuple[int, Any], Any] = {}
_NATIVE_BY_PRINT: dict[tuple[int, tuple[Any, ...]], Any] = {}
"""The native kernels found, by dispatcher and :func:`_fingerprint` of the arguments: numba
calls the hook of a dispatcher at every call that finds no compiled version in it, and typing
the arguments again (``typeof_pyval``, about 5 us an argument) cost more than the native call."""


def _fingerprint(args: tuple[Any, ...]) -> tuple[Any, ...]:
    """What numba's type of each argument depends on: an array's class, dtype, dimensions,
    layout, whether it is writable and aligned; a scalar's class."""

    out: list[Any] = []
    for a in args:
        if isinstance(a, np.ndarray):
            f = a.flags
            out.append((type(a), a.dtype, a.ndim, f.c_contiguous, f.f_contiguous, f.writeable, f.aligned))
        else:
            out.append(type(a))
    return tuple(out)


def forget_native() -> None:
    """Forget which kernels have a native version (asked again at their next call)."""
    _NATIVE.clear()
    _NATIVE_BY_PRINT.clear()


def _native_for_call(dispatcher: Any, args: tuple[Any, ...]) -> tuple[Any, Any]:
    """``(native, sig)``: the native kernel of ``dispatcher`` for these arguments if the library
    has one (else None), found by their fingerprint when a call of the same kinds found it, else
    by their numba types ``sig`` (told to :data:`CALL_OBSERVERS`, and returned for numba; None
    when found by fingerprint or when the arguments cannot be typed)."""
    key = (id(dispatcher), _fingerprint(args))
    found = _NATIVE_BY_PRINT.get(key)
    if found is not None:
        return found, None
    try:
        sig = tuple(dispatcher.typeof_pyval(a) for a in args)
    except Exception:  # numba's own call says what is wrong with the arguments
        return None, None
    for observe in CALL_OBSERVERS:
        observe(dispatcher, sig)
    native = native_kernel(dispatcher, sig)
    if native is not None:
        _NATIVE_BY_PRINT[key] = native
    return native, sig


def native_kernel(dispatcher: Any, sig: Any) -> Any:
    """The kernel of ``dispatcher`` for the argument types ``sig`` in the library of native
    kernels (:mod:`quadric_contact.modes.kernels.native`), as a Python callable; None when the library
    has none that matches the running sources."""
    key = (id(dispatcher), sig)
    if key not in _NATIVE:
        _NATIVE[key] = native.lookup(dispatcher, sig, sources_digest)
    return _NATIVE[key]


def route_native(dispatcher: Any) -> None:
    """Let a kernel that is compiled in the calling thread (no twin, no thread of its own:
    ``njit(twin=False)``, the loops of :mod:`~quadric_contact.modes.smallness.binary64`) run its
    native version where the library has one (:func:`native_kernel`), telling
    :data:`CALL_OBSERVERS` first."""
    compile_for_args = dispatcher._compile_for_args

    def native_first(*args: Any, **kws: Any) -> Any:
        if not kws:
            native, _ = _native_for_call(dispatcher, args)
            if native is not None:
                return native
        return compile_for_args(*args, **kws)

    dispatcher._compile_for_args = native_first


def compile_on_a_fresh_stack(dispatcher: Any, twin_elements: int = TWIN_ELEMENTS) -> None:
    """Compile (or load from the cache) in a new thread, whose Python stack starts empty; and
    where the kernel is not in the cache, answer small calls by its Python twin (the
    ``background`` and ``twins`` policies, :data:`KERNEL_POLICIES`).

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
    for its argument types, and calls what it returns with the caller's arguments.  Here:

    * a call with more than ``twin_elements`` array elements (:data:`TWIN_ELEMENTS` unless the
      kernel says otherwise: one whose twin is slow a pair says less), or under the ``wait``
      policy, compiles (or loads) in the compiler's thread and waits for it;
    * a smaller call loads the kernel if the on-disk cache has it; if not, it gets the
      kernel's Python twin, which computes the same bits (the oracle the tests hold the
      compiled kernels to) in Python.  The first such call starts the background warm-up
      (:func:`start_background_warmup`); once that has finished, a kernel still missing
      (a signature it does not call) is compiled in a thread of this process, the twin
      answering meanwhile.

    A kernel that calls another compiles it through ``compile``, inside the same thread, so
    the compiler's lock (held by the compiling thread) is never waited for by a thread it
    waits on."""
    compile_for_args = dispatcher._compile_for_args
    compiles = _Compiles(dispatcher)
    cached = bool(getattr(getattr(dispatcher, "_cache", None), "_cache_path", None))

    def compile_elsewhere(*args: Any, **kws: Any) -> Any:
        sig = None
        if not kws:
            native, sig = _native_for_call(dispatcher, args)
            if native is not None:
                return native
        if sig is None or not cached or _POLICY == "wait" or _elements(args) > twin_elements:
            if sig is None:
                return compile_for_args(*args, **kws)
            if not cached:
                return compiles.wait(sig, compile_for_args, args)
            with _compile_lock(dispatcher):
                return compiles.wait(sig, compile_for_args, args)
        entry = compiles.load(sig)
        if entry is not None:
            return entry
        if _POLICY == "background":
            state = warmup_state()
            if state == "none":
                start_background_warmup()
            elif state == "done":  # the warm-up does not call this signature: compile it here
                compiles.start(sig, compile_for_args, args)
        _say_twins()
        return compiles.twin_of()

    dispatcher._compile_for_args = compile_elsewhere


# -- one compile of a kernel at a time on the machine ------------------------------------------


class KernelBusy(Exception):
    """Another process is compiling the kernel a call needs, and this process defers such calls
    (:func:`deferring`): the warm-up runs another call meanwhile and this one later, when it
    loads the kernel from the cache instead of compiling it a second time."""


_DEFERRING = False


@contextmanager
def deferring() -> Iterator[None]:
    """Within the block, a call whose kernel another process is compiling raises
    :class:`KernelBusy` instead of waiting for it."""
    global _DEFERRING
    before, _DEFERRING = _DEFERRING, True
    try:
        yield
    finally:
        _DEFERRING = before


@contextmanager
def _compile_lock(dispatcher: Any) -> Iterator[None]:
    """Hold the machine-wide lock of one kernel while it is compiled (or loaded) here: a second
    process that needs it waits, then loads what the first wrote to the cache (numba looks in the
    cache before it compiles), instead of compiling it again at the same time; or, deferring,
    raises :class:`KernelBusy`.  Where no lock can be had, nothing is held."""
    try:
        import fcntl  # POSIX only

        f = getattr(dispatcher, "py_func", None)
        name = f"{getattr(f, '__module__', '?')}.{getattr(f, '__qualname__', '?')}"
        fd = os.open(
            os.path.join(_cache_root(), f"quadric-contact-compile.{name}.lock"), os.O_RDWR | os.O_CREAT, 0o644
        )
    except (ImportError, OSError):
        yield
        return
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            if _DEFERRING:
                raise KernelBusy(name) from None
            fcntl.flock(fd, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(fd, fcntl.LOCK_UN)
    finally:
        os.close(fd)


# -- one cache for every copy of the package ---------------------------------------------------


def kernel_cache_dir() -> str:
    """The directory every copy of this package keeps its compiled kernels in.

    ``QUADRIC_CONTACT_CACHE_DIR`` if set; else ``quadric-contact`` in ``NUMBA_CACHE_DIR`` if
    that is set; else ``quadric-contact/kernels`` in the user's cache directory
    (``$XDG_CACHE_HOME``, or ``~/.cache``; ``%LOCALAPPDATA%`` on Windows).

    numba's default keeps a kernel next to its source file, so a checkout's tests and an
    installed copy of the same sources each compiled every kernel (minutes of CPU time each).
    numba stamps a cache entry with the digest of the source's bytes (and :func:`stamp_with_sources`
    with those of every source the kernel is made of), not with its path or time: copies with
    the same sources can share the compiled code, and copies with other sources replace each
    other's entries instead of loading them."""
    own = os.environ.get("QUADRIC_CONTACT_CACHE_DIR")
    if own:
        return own
    numba_dir = os.environ.get("NUMBA_CACHE_DIR")
    if numba_dir:
        return os.path.join(numba_dir, "quadric-contact")
    if os.name == "nt":  # pragma: no cover - not this platform
        base = os.environ.get("LOCALAPPDATA") or os.path.expanduser("~")
    else:
        base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return os.path.join(base, "quadric-contact", "kernels")


if HAVE_NUMBA:  # pragma: no branch
    from numba.core import caching as _caching

    class _PackageCacheLocator(_caching._SourceFileBackedLocatorMixin, _caching._CacheLocator):  # type: ignore[misc,name-defined,unused-ignore]
        """numba's cache locator for the kernels of this package: :func:`kernel_cache_dir`, then
        the source's folder inside the package (``modes``, ``_generated``), whichever copy the
        source is in.  The stamp and the name of a cache file are numba's own (the digest of the
        source, the function's name and first line).  A source outside this package, or a cache
        directory that cannot be written, is left to numba's other locators."""

        def __init__(self, py_func: Any, py_file: str) -> None:
            self._py_file = py_file
            self._lineno = py_func.__code__.co_firstlineno
            rel = Path(py_file).resolve().relative_to(PACKAGE_ROOT).parent
            self._cache_path = os.path.join(kernel_cache_dir(), *rel.parts)

        def get_cache_path(self) -> str:
            return self._cache_path

        @classmethod
        def from_function(cls, py_func: Any, py_file: str) -> Any:
            if not Path(py_file).resolve().is_relative_to(PACKAGE_ROOT):
                return None
            return super().from_function(py_func, py_file)

    if _PackageCacheLocator not in _caching.CacheImpl._locator_classes:
        _caching.CacheImpl._locator_classes.insert(0, _PackageCacheLocator)


# -- the background warm-up: its lock, its marker, its start ----------------------------------


def _cache_root() -> str:
    """The directory numba keeps this package's kernels in (that of the decision kernel's
    module, :mod:`quadric_contact.modes.kernels.decision`; :func:`kernel_cache_dir` where it can be written):
    the warm-up's lock, log and marker, and the compile locks, live there."""
    from numba.core.caching import CacheImpl  # numba only

    source = str(Path(__file__).with_name("decision.py"))
    for locator in CacheImpl._locator_classes:  # numba's order, this package's locator first
        found = locator.from_function(_cache_root, source)
        if found is not None:
            return str(found.get_cache_path())
    raise OSError("no writable cache directory for the compiled kernels")


def warmup_path(what: str) -> str:
    """The warm-up's ``lock``, ``log`` or ``done`` marker (next to the kernels' cache)."""
    return os.path.join(_cache_root(), f"quadric-contact-warmup.{what}")


@contextmanager
def warmup_lock(*, wait: bool = False) -> Iterator[bool]:
    """Hold the warm-up's lock while the block runs (yields False, holding nothing, where
    another process holds it; ``wait``: wait for it instead)."""
    try:
        import fcntl  # POSIX only
    except ImportError as exc:  # pragma: no cover - not a POSIX system: no lock, no warm-up
        raise OSError("no file locks here") from exc

    fd = os.open(warmup_path("lock"), os.O_RDWR | os.O_CREAT, 0o644)
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | (0 if wait else fcntl.LOCK_NB))
        except OSError:
            yield False
            return
        try:
            yield True
        finally:
            fcntl.flock(fd, fcntl.LOCK_UN)
    finally:
        os.close(fd)


def _all_sources() -> str:
    """:func:`_sources_digest` of every compiled module, computed once a process."""
    if "" not in _SOURCES_ALL:
        _SOURCES_ALL[""] = _sources_digest()
    return _SOURCES_ALL[""]


_SOURCES_ALL: dict[str, str] = {}


def warmup_done() -> None:
    """Leave the marker: the cache holds every kernel the warm-up calls, for these sources."""
    with open(warmup_path("done"), "w", encoding="ascii") as f:
        f.write(_all_sources() + "\n")


def warmup_state() -> str:
    """``done`` (the marker names these sources), ``running`` (another process holds the
    lock), or ``none``."""
    try:
        with open(warmup_path("done"), encoding="ascii") as f:
            if f.read().strip() == _all_sources():
                return "done"
        # a marker of other sources says nothing about these
    except OSError:
        pass
    try:
        with warmup_lock() as held:
            return "none" if held else "running"
    except OSError:
        return "running"  # no lock to take: nothing to start either


_started = False


def start_background_warmup() -> bool:
    """Start the background warm-up (:mod:`quadric_contact.interfaces.warmup`), once per
    process: a process of its own, in a new session (it outlives this one, and an interrupt
    of this one does not stop it), at the lowest priority, importing this same copy of the
    package and writing to the same cache.  Returns whether it was started."""
    global _started
    if _started:
        return False
    _started = True

    here = str(PACKAGE_ROOT.parent)  # the directory the package is in
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(filter(None, [here, os.environ.get("PYTHONPATH")])))
    env["QUADRIC_CONTACT_KERNELS"] = "wait"
    try:
        subprocess.Popen(
            [sys.executable, "-m", "quadric_contact.interfaces.warmup", "--background"],
            env=env,
            stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            start_new_session=True,
        )
    except OSError:
        return False
    return True


def njit(
    fn: Callable[..., Any] | None = None,
    *,
    inline: bool = False,
    cache: bool = True,
    twin_elements: int = TWIN_ELEMENTS,
    twin: bool = True,
) -> Any:
    """The compiled side of a function (:func:`compiled`): ``numba.njit`` (``forceinline`` for
    the helpers the kernels inline; ``nogil`` and cached for the kernels themselves), or the
    function unchanged without numba.

    ``forceinline`` marks a helper ``alwaysinline`` for LLVM: numba types and lowers it once
    per signature and LLVM inlines it into every caller, the same code in the end as numba's
    own ``inline="always"``, which typed the helper again at every call site and through every
    level of helpers (all 42 kernels of the warm-up: 629 s of CPU that way, 99 s this way, at
    the same throughput).  Without either, LLVM's inliner leaves the large generated programs
    as calls, and the kernels run three times slower.  A helper is one of the pairs of
    :func:`jitable` (the name bound to its compiled side): one compiled helper per function,
    whichever module asks for it.

    ``error_model="numpy"``: division follows IEEE 754 (no zero check raising
    ``ZeroDivisionError``, whose branch would keep the loops from vectorising); the
    kernels guard every quotient they use.  A cached kernel is keyed on every source it is
    made of (:func:`stamp_with_sources`), not only its own file.  ``twin_elements``: the
    largest call (array elements in all) that the kernel's Python twin answers while the
    kernel is not compiled (:func:`compile_on_a_fresh_stack`).  ``twin=False``: a kernel
    without a Python twin, compiled in the calling thread where the library of native kernels
    has no version of it (:func:`route_native`; the loops of
    :mod:`~quadric_contact.modes.smallness.binary64`, whose Python twins would run row by row)."""

    def wrap(f: Callable[..., Any]) -> Any:
        if not HAVE_NUMBA:
            return f
        if inline:
            pair = _pair(f, inline=True)
            # a function registered without forceinline (jitable) gets a helper of its own here
            return pair.compiled if pair.inline else _compile_helper(f, True)
        dispatcher = numba.njit(nogil=True, cache=cache, error_model="numpy")(f)
        if cache:
            stamp_with_sources(dispatcher)
        if twin:
            compile_on_a_fresh_stack(dispatcher, twin_elements)
        else:
            route_native(dispatcher)
        return dispatcher

    return wrap(fn) if fn is not None else wrap


# -- one source, two backends -----------------------------------------------------------------
#
# A formula of the kernels is written once, as a Python function of numbers, and run two ways:
# compiled by numba into the kernels, and by Python, on scalars (the kernels' Python twins) or
# element by element on whole numpy columns (the numpy backend).  Such a function is a *pair*:
# its plain side (the function itself) and its compiled side (a numba dispatcher made from it).
# A module binds the name to one side, :func:`jitable` to the plain one and ``njit(inline=True)``
# to the compiled one, and :func:`plain` and :func:`compiled` give the other:
#
# * compiled code may name either side: numba types the plain side of a pair as its compiled
#   side, so a kernel calling a plain helper inlines the compiled helper, which calls its own
#   helpers the same way (numba compiles each once per signature, under its compiler lock);
# * Python code runs the plain side, and :func:`plain` makes the Python twin of a compiled
#   kernel or helper: its source, with every compiled function it reaches read as the plain
#   side of its pair, so nothing is compiled.
#
# :func:`select` is the one choice both sides make without a branch: ``numpy.where`` on columns,
# an LLVM ``select`` compiled.


class _Pair:
    """The two sides of a function: ``plain`` (Python) and ``compiled`` (numba)."""

    __slots__ = ("compiled", "inline", "plain")

    def __init__(self, plain: Callable[..., Any], compiled: Any, inline: bool) -> None:
        self.plain = plain
        self.compiled = compiled
        self.inline = inline


_PAIRS: dict[Any, _Pair] = {}
"""The pairs, by plain function (which the dictionary keeps alive, and with it the compiled side
numba's type of the plain side refers to weakly)."""
_PAIRS_LOCK = threading.RLock()


def _compile_helper(fn: Callable[..., Any], inline: bool) -> Any:
    """``numba.njit`` of a helper: IEEE division, ``forceinline`` if ``inline``."""
    if inline:
        return numba.njit(forceinline=True, error_model="numpy")(fn)
    return numba.njit(error_model="numpy")(fn)


def _pair(fn: Callable[..., Any], *, inline: bool, compiled_side: Any = None) -> _Pair:
    """The pair of the plain function ``fn`` (a dispatcher: its function), made the first time:
    its compiled side is ``compiled_side`` or :func:`_compile_helper` of ``fn``, and numba types
    ``fn`` in compiled code as that side (once: numba's typing of a value cannot change).  A
    pair made with another ``inline`` is returned as it is; the caller decides."""
    fn = getattr(fn, "py_func", fn)
    with _PAIRS_LOCK:
        pair = _PAIRS.get(fn)
        if pair is not None:
            return pair
        if not HAVE_NUMBA:
            pair = _Pair(fn, fn, inline)
        else:
            from numba.core import types as nbtypes  # numba only
            from numba.core.typing.templates import infer_global  # numba only

            side = _compile_helper(fn, inline) if compiled_side is None else compiled_side
            infer_global(fn, nbtypes.Dispatcher(side))
            pair = _Pair(fn, side, inline)
        _PAIRS[fn] = pair
        return pair


def jitable(fn: Callable[..., Any] | None = None, *, inline: bool = False) -> Any:
    """One source for both backends: register the plain function ``fn`` as a pair and return it
    unchanged.

    The name stays bound to the Python function, so it runs on Python numbers and element by
    element on numpy columns (the ``numpy`` backend), and the calls inside it resolve to Python
    functions there; compiled code that calls it calls its compiled side (:func:`compiled`),
    numba's with the kernels' ``error_model="numpy"``, compiled once per signature.  With
    ``inline`` the compiled side is ``forceinline`` (as :func:`njit` makes the kernels' helpers:
    the straight-line helpers of :mod:`~quadric_contact.modes.smallness.binary64`, the signs of
    :mod:`~quadric_contact.modes.kernels.signs`); without it LLVM decides (the double-double
    primitives of :mod:`~quadric_contact.modes.kernels.double_double`).  A generated program is
    registered as it is (``jitable(program, inline=True)`` returns the program).  Without numba,
    nothing is registered.  Usable as ``@jitable`` and ``@jitable(inline=True)``."""

    def wrap(f: Callable[..., Any]) -> Any:
        pair = _pair(f, inline=inline)
        if pair.inline != inline:
            raise ValueError(f"{f.__qualname__} already has a compiled side with inline={pair.inline}")
        return pair.plain

    return wrap(fn) if fn is not None else wrap


def compiled(fn: Callable[..., Any]) -> Any:
    """The compiled side of ``fn``: a numba dispatcher as it is, the compiled side of a plain
    function registered by :func:`jitable`; without numba, ``fn`` itself."""
    if not HAVE_NUMBA or isinstance(fn, numba.core.dispatcher.Dispatcher):
        return fn
    pair = _PAIRS.get(fn)
    if pair is None:
        raise TypeError(
            f"{getattr(fn, '__qualname__', fn)!r} has no compiled side (not made by jitable or njit)"
        )
    return pair.compiled


_PLAIN: dict[Any, Callable[..., Any]] = {}
"""The Python twins made, by the function they were made for (kept alive with them)."""


def plain(fn: Callable[..., Any]) -> Callable[..., Any]:
    """``fn`` (a kernel, a helper of either side, a plain function) run by Python all the way
    down: the Python twin of a compiled kernel, and the plain side of a pair.

    A kernel's Python variant (the ``numpy`` backend, the oracle of equal bits) calls its
    helpers by the names its module binds, some to numba dispatchers.  A dispatcher called from
    Python is compiled on its own, and an inline helper is not cached: every process that ran
    the Python variant compiled its helpers again (38 s for the signature kernel's).  The twin
    reads every such name, in ``fn`` and in the helpers it reaches (dispatchers, and plain
    sides of pairs, whose own helpers may be dispatchers), as a twin of the plain function, so
    nothing is compiled; the compiled kernel is untouched.  It runs with the kernels' IEEE 754
    (``error_model="numpy"``): an overflow or a division by zero of numpy numbers gives inf or
    NaN, which the guards read, and says nothing.  Made once per function (thread-safe)."""

    key = getattr(fn, "py_func", fn)
    with _PAIRS_LOCK:
        done = _PLAIN.get(key)
        if done is not None:
            return done

    made: dict[int, Callable[..., Any]] = {}

    def names(code: types.CodeType) -> set[str]:
        found = set(code.co_names)
        for const in code.co_consts:
            if isinstance(const, types.CodeType):
                found |= names(const)
        return found

    def source(value: Any) -> types.FunctionType | None:
        """The function to twin for a value a function reads: a dispatcher's, a plain side's."""
        found = getattr(value, "py_func", None)
        if found is None and isinstance(value, types.FunctionType) and value in _PAIRS:
            found = value
        return found if isinstance(found, types.FunctionType) else None

    def twin(f: types.FunctionType) -> Callable[..., Any]:
        done = made.get(id(f))
        if done is not None:
            return done
        scope = dict(f.__globals__)
        closure = None if f.__closure__ is None else tuple(types.CellType() for _ in f.__closure__)
        new = types.FunctionType(f.__code__, scope, f.__name__, f.__defaults__, closure)
        new.__kwdefaults__ = f.__kwdefaults__
        made[id(f)] = new
        for name in names(f.__code__):
            found = source(scope.get(name))
            if found is not None:
                scope[name] = twin(found)
        # a kernel made by a factory holds its helpers (and its settings) in its cells
        for old, cell in zip(f.__closure__ or (), closure or (), strict=True):
            try:
                value = old.cell_contents
            except ValueError:  # an empty cell stays empty
                continue
            found = source(value)
            cell.cell_contents = value if found is None else twin(found)
        return new

    assert isinstance(key, types.FunctionType)
    body = twin(key)

    def run(*args: Any, **kws: Any) -> Any:
        with np.errstate(all="ignore"):
            return body(*args, **kws)

    run.__name__ = key.__name__
    run.__qualname__ = key.__qualname__
    run.__doc__ = key.__doc__
    with _PAIRS_LOCK:
        return _PLAIN.setdefault(key, run)


def pairs() -> list[tuple[Callable[..., Any], Any, bool]]:
    """Every pair registered so far: ``(plain side, compiled side, inline)``."""
    with _PAIRS_LOCK:
        return [(p.plain, p.compiled, p.inline) for p in _PAIRS.values()]


def select(c: Any, a: Any, b: Any) -> Any:
    """``a`` where ``c``, else ``b``, without a branch: ``numpy.where`` on columns (and on
    scalars, as a 0-d array), an LLVM ``select`` in compiled code (which keeps a straight-line
    loop vectorisable)."""
    return np.where(c, a, b)


if HAVE_NUMBA:  # pragma: no branch
    from numba.core import types as _nbtypes

    @numba.extending.intrinsic  # type: ignore[untyped-decorator,unused-ignore]
    def _select_intrinsic(typingctx: Any, c: Any, a: Any, b: Any) -> Any:
        rt = typingctx.unify_types(a, b)

        def codegen(context: Any, builder: Any, signature: Any, args: Any) -> Any:  # pragma: no cover
            cv = context.cast(builder, args[0], c, _nbtypes.boolean)
            av = context.cast(builder, args[1], a, rt)
            bv = context.cast(builder, args[2], b, rt)
            return builder.select(cv, av, bv)

        return rt(c, a, b), codegen

    def _select_compiled(c: Any, a: Any, b: Any) -> Any:  # pragma: no cover - compiled
        return _select_intrinsic(c, a, b)

    _pair(select, inline=True, compiled_side=numba.njit(forceinline=True)(_select_compiled))
else:  # pragma: no cover
    _pair(select, inline=True)


# -- first use: one line when a kernel is not in the cache ------------------------------------
#
# numba compiles a kernel the first time it is called with a new signature and keeps the
# machine code in its on-disk cache (``cache=True``; :func:`kernel_cache_dir`, one directory for
# every copy of the package).  Later processes load it in milliseconds.  The first
# compilation of the complete decision takes about 40 s of CPU time, so the first time a kernel
# of this package misses the cache the process says so, once, on stderr: that it runs the
# twins meanwhile, or that it compiles (a large call, or the ``wait`` policy).

TWINS_NOTICE = (
    "quadric-contact: the compiled kernels are not in the on-disk cache{where} yet; {who}; "
    "meanwhile calls of up to about 27 000 pairs run the same code in Python (the same answers, "
    "slower) and larger ones compile what they need first"
)
"""The line printed (stderr) the first time a call of a process runs a kernel's twin."""

_WHO = {
    "background": "a background process fills it, once for this machine (about two minutes of CPU "
    "time at the lowest priority)",
    "twins": "`quadric-contact compile` fills it (QUADRIC_CONTACT_KERNELS=twins: no background process)",
}

COMPILE_NOTICE = (
    "quadric-contact: compiling the numba kernels once for this machine (about 40 s of CPU time "
    "for the first complete decision, two minutes for every layout and mode, spread over the first "
    "calls that need them); later processes load them from the on-disk cache{where}"
)
"""The line printed (stderr) the first time a kernel of the package is compiled in a process."""

_notice_printed = False


def _cache_dir(dispatcher: Any) -> str:
    cache = getattr(dispatcher, "_cache", None)
    path = getattr(cache, "_cache_path", None)
    return f" ({path})" if path else ""


def _say_twins() -> None:
    global _notice_printed
    if _notice_printed:
        return
    _notice_printed = True

    try:
        where = f" ({_cache_root()})"
    except Exception:
        where = ""
    print(TWINS_NOTICE.format(where=where, who=_WHO.get(_POLICY, "")), file=sys.stderr, flush=True)


if HAVE_NUMBA:  # pragma: no branch
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
                # not a cache miss: an uncached helper (forceinline) called from Python is
                # compiled in every process, in a few seconds, and no cache would keep it
                return
            _notice_printed = True
            print(COMPILE_NOTICE.format(where=_cache_dir(dispatcher)), file=sys.stderr, flush=True)

        def on_end(self, ev: Any) -> None:
            pass

    _event.register("numba:compile", _CompileNotice())


@contextmanager
def turned_off() -> Iterator[None]:
    """Within the block, kernel calls compile (or load from numba's cache) at run time instead of
    running the native kernels: the benchmark's and the tests' comparison of the two.  A kernel
    that compiled there stays compiled in its dispatcher, which then runs it, not the native
    one, for the rest of the process."""
    before = os.environ.get("QUADRIC_CONTACT_NATIVE")
    os.environ["QUADRIC_CONTACT_NATIVE"] = "0"
    forget_native()
    try:
        yield
    finally:
        if before is None:
            del os.environ["QUADRIC_CONTACT_NATIVE"]
        else:
            os.environ["QUADRIC_CONTACT_NATIVE"] = before
        forget_native()
