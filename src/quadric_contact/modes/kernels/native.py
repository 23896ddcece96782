"""The native kernels: the array kernels as the package's build compiled them, called through C.

``pip install .`` (and ``python -m build``) compiles every kernel that the default ``certified``
mode calls, with every signature it calls it with, into the extension ``quadric_contact._native``
(how: :mod:`quadric_contact.codegen.native`).  A kernel call that finds no compiled version in
its numba dispatcher (``quadric_contact.modes.kernels._jit.compile_on_a_fresh_stack``) asks
:func:`lookup` first; when the library has that kernel for those argument types, made from the
sources that are running, on this machine, the call runs it and nothing is compiled.  Elsewhere
(another mode, a kernel whose sources changed since the build, no library) the kernel is compiled
at run time as before.

The library is looked for next to this package, then in the installed distribution of
``quadric-contact`` (the test suite runs the sources of a checkout, whose kernels the installed
library holds when the sources are the same: the digest says so).  ``QUADRIC_CONTACT_NATIVE=0``
in the environment turns it off.

Each native function takes each array as its data pointer and its shape (the kernels take
C-contiguous arrays, which the signature says) and each scalar as itself; ctypes releases the
GIL for the call, so the threads of :mod:`quadric_contact.modes.kernels.threads` run in parallel as
they do with numba's ``nogil`` kernels.
"""

from __future__ import annotations

import ctypes
import hashlib
import json
import os
import sys
import threading
from collections.abc import Callable
from importlib import metadata
from pathlib import Path
from typing import Any

import numpy as np

__all__ = [
    "MANIFEST_NAME",
    "NativeLibrary",
    "enabled",
    "kernel_identity",
    "library",
    "lookup",
    "manifest_digest",
]

MANIFEST_NAME = "_native_manifest.json"
"""The manifest of the library, next to it in the package."""

_CTYPES = {"int64": ctypes.c_int64, "bool": ctypes.c_bool, "float64": ctypes.c_double}
_PLAIN = {"int64": int, "bool": bool, "float64": float}


def kernel_identity(fn: Any) -> str:
    """The name a kernel goes by in the manifest: its module and qualified name, and the values
    its closure holds (kernels made by a factory, one per setting, share a qualified name)."""
    fn = getattr(fn, "py_func", fn)
    cells = []
    for cell in fn.__closure__ or ():
        value = cell.cell_contents
        if isinstance(value, bool | int | float | str):
            cells.append(repr(value))
        else:  # a function or a table: its kind (the settings above tell the kernels apart)
            cells.append(type(value).__name__)
    closure = f"[{', '.join(cells)}]" if cells else ""
    return f"{fn.__module__}:{fn.__qualname__}{closure}"


def manifest_digest(text: bytes) -> str:
    """The digest a library carries of the manifest it was linked with."""
    return hashlib.sha256(text).hexdigest()


def enabled() -> bool:
    """Whether calls may run native kernels (``QUADRIC_CONTACT_NATIVE`` is not ``0``)."""
    return os.environ.get("QUADRIC_CONTACT_NATIVE", "1") != "0"


class NativeLibrary:
    """The loaded library and its manifest.

    Attributes
    ----------
    path : Path
        The shared library.
    manifest : dict
        What :mod:`quadric_contact.codegen.native` wrote: the machine it was built for
        (``cpu``, ``features``), and for each kernel its name, signature, symbol, the layout of
        its arguments, what it returns and the digest of its sources.
    usable : bool
        The library was built for this machine's processor and features.
    """

    def __init__(self, path: Path, manifest_text: bytes) -> None:
        self.path = path
        self.manifest = json.loads(manifest_text)
        self._dll: ctypes.CDLL | None = None
        self.usable = _same_machine(self.manifest) and self._linked_with(manifest_digest(manifest_text))
        self._by_key = {(k["kernel"], tuple(k["signature"])): k for k in self.manifest.get("kernels", [])}

    def entry(self, kernel: str, signature: tuple[str, ...]) -> dict[str, Any] | None:
        """The manifest's entry for ``kernel`` with argument types ``signature``, if any."""
        return self._by_key.get((kernel, signature))

    def _linked_with(self, digest: str) -> bool:
        """Load the library (numba's allocator initialised) and check that it was linked with
        this manifest."""
        try:
            dll = ctypes.CDLL(str(self.path))
            says = dll.qc_native_manifest
            says.restype = ctypes.c_char_p
            if says() != digest.encode():
                return False
            dll.qc_native_init()
        except (OSError, AttributeError):
            return False
        self._dll = dll
        return True

    def function(self, symbol: str) -> Any:
        """The C function ``symbol`` of the library (a usable one: loaded)."""
        assert self._dll is not None
        return getattr(self._dll, symbol)


def _same_machine(manifest: dict[str, Any]) -> bool:
    try:
        import llvmlite.binding as ll  # numba only
    except ImportError:  # pragma: no cover - numba (and llvmlite) are dependencies
        return False
    features = ll.get_host_cpu_features().flatten()
    return bool(manifest.get("cpu") == ll.get_host_cpu_name() and manifest.get("features") == features)


def _candidates() -> list[Path]:
    """Directories that may hold the library: this package's, then those of the installed copies
    of the distribution (every one on the path: a checkout's ``src/`` may hold the metadata a
    build left there, which shadows the installed copy's)."""
    here = Path(__file__).resolve().parents[2]  # the package's directory
    found = [here]
    for dist in metadata.distributions(name="quadric-contact"):
        for f in dist.files or ():
            if f.name == MANIFEST_NAME:
                where = Path(str(dist.locate_file(f))).resolve().parent
                if where not in found:
                    found.append(where)
    return found


_LOCK = threading.Lock()
_LIBRARY: list[NativeLibrary | None] = []


def library() -> NativeLibrary | None:
    """The library of native kernels (the first of :func:`_candidates` with a manifest and a
    library beside it), loaded on first use; None when there is none."""
    with _LOCK:
        if not _LIBRARY:
            _LIBRARY.append(_find())
        return _LIBRARY[0]


def _find() -> NativeLibrary | None:
    for where in _candidates():
        manifest = where / MANIFEST_NAME
        libs = sorted(where.glob("_native.*.so")) + sorted(where.glob("_native.*.pyd"))
        if manifest.is_file() and libs:
            try:
                return NativeLibrary(libs[0], manifest.read_bytes())
            except (OSError, ValueError):
                continue
    return None


_SAID: list[bool] = []


def _say_missing(lib: NativeLibrary | None) -> None:
    """One line on stderr, once a process, where a kernel call finds no usable library: a build
    without a C compiler says so only in the installer's output, which pip hides."""
    with _LOCK:
        if _SAID:
            return
        _SAID.append(True)
    why = (
        "this copy of the package has none (built without a C compiler, or from a checkout "
        "without `pip install .`)"
        if lib is None
        else f"the library {lib.path} was built for another processor or does not match its manifest"
    )
    print(
        f"quadric-contact: no native kernels: {why}; the kernels are compiled at run time instead",
        file=sys.stderr,
        flush=True,
    )


def lookup(dispatcher: Any, sig: Any, digest: Callable[[str], str]) -> Callable[..., Any] | None:
    """The native kernel of ``dispatcher`` for the numba argument types ``sig``, as a Python
    callable taking the kernel's own arguments; None when native kernels are off, there is no
    library, it was built for another machine, it has no such kernel, or the kernel's sources
    (``digest`` of its module) are not those it was built from."""
    if not enabled():
        return None
    lib = library()
    if lib is None or not lib.usable:
        _say_missing(lib)
        return None
    # a read-only array of the caller's (a broadcast, a read-only buffer) runs the kernel made
    # for a writable one: passed as it is where the kernel only reads it (LLVM proved so at the
    # build), else as a copy, so that nothing of the caller's is ever written
    from numba.core import types

    name = kernel_identity(dispatcher)
    entry = lib.entry(name, tuple(str(t) for t in sig))
    readonly = [False] * len(sig)
    if entry is None:  # built for these types as they are, or for the writable ones
        readonly = [isinstance(t, types.Array) and not t.mutable for t in sig]
        as_writable = [t.copy(readonly=False) if ro else t for t, ro in zip(sig, readonly, strict=True)]
        entry = lib.entry(name, tuple(str(t) for t in as_writable))
    if entry is None or entry["sources"] != digest(dispatcher.py_func.__module__):
        return None
    proved = [len(kind) > 3 and kind[3] for kind in entry["arguments"]]  # only read (arrays)
    copy = [ro and not p for ro, p in zip(readonly, proved, strict=True)]
    return _caller(lib.function(entry["symbol"]), entry, copy)


def _caller(fn: Any, entry: dict[str, Any], copy: list[bool]) -> Callable[..., Any]:
    """A Python function that passes the kernel's arguments to the C function ``fn`` (the
    arrays flagged in ``copy`` as copies)."""
    argtypes: list[Any] = []
    plain: list[Any] = []  # per argument: None for an array, else the Python type of the scalar
    for kind in entry["arguments"]:
        if kind[0] == "array":
            argtypes += [ctypes.c_void_p] + [ctypes.c_ssize_t] * kind[2]
            plain.append(None)
        else:
            argtypes.append(_CTYPES[kind[1]])
            plain.append(_PLAIN[kind[1]])
    fn.argtypes = argtypes
    returns = entry["returns"]
    fn.restype = ctypes.c_int64 if returns == "none" else _CTYPES[returns]
    nothing = returns == "none"

    copies = any(copy)

    def call(*args: Any) -> Any:
        if copies:  # the copies live until the call returns
            args = tuple(np.array(a) if c else a for a, c in zip(args, copy, strict=True))
        flat: list[Any] = []
        for a, kind in zip(args, plain, strict=True):
            if kind is None:
                flat.append(a.ctypes.data)
                flat.extend(a.shape)
            else:
                flat.append(kind(a))
        r = fn(*flat)
        return None if nothing else r

    return call
