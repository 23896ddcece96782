"""The native kernels: the array kernels compiled ahead of time into a shared library, at install.

The kernels have one source, the Python of :mod:`quadric_contact.modes` and the generated
programs of :mod:`quadric_contact._generated`, which numba compiles.  Compiled at run time, the
first calls of a machine paid for the compile (about 40 s of CPU for the complete decision).
Here numba compiles them once, when the package is built (``pip install .``,
``python -m build``): every kernel the calls of :func:`calls` reach, with every signature they
call it with, becomes a C function of the library ``quadric_contact._native``:

* its arguments are plain C values: each array is its data pointer followed by its shape (the
  kernels take C-contiguous arrays only), each scalar is itself;
* its body is the kernel's own code: numba's optimised LLVM module of the kernel, as the run-time
  compile makes it, linked under a small ``cfunc`` that wraps the arrays (``numba.carray``) and
  calls the kernel (the whole not optimised a second time), with every other symbol made internal,
  emitted as a position-independent object for the machine that builds;
* the library links numba's C runtime (the allocator the kernels' scratch arrays use, its
  helper functions) from numba's own sources, as ``numba.pycc`` does.

A manifest next to the library (``_native_manifest.json``) lists each function with the
kernel and signature it stands for and the digest of the sources it was made from
(``quadric_contact.modes.kernels._jit.kernel_sources``); :mod:`quadric_contact.modes.kernels.native`
reads it and calls a function only where the running sources have that digest and the machine
is the one it was built for.  So the answers are those of the run-time compile, and a kernel
whose sources changed since the build is compiled at run time as before.

``python -m quadric_contact.codegen.native --out DIR`` writes the objects, the manifest and
``build.json`` (what the extension is built from) into ``DIR``; ``setup.py`` runs it.
"""

from __future__ import annotations

import argparse
import functools
import hashlib
import json
import os
import subprocess
import sys
import sysconfig
import time
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np

from quadric_contact.interfaces.warmup import calls as warm_calls
from quadric_contact.modes.kernels import _jit
from quadric_contact.modes.kernels.native import MANIFEST_NAME, kernel_identity, manifest_digest

__all__ = ["MANIFEST_NAME", "RUNTIME_SOURCE", "build", "calls", "kernel_identity", "main"]

RUNTIME_SOURCE = Path(__file__).with_name("native_runtime.c")
"""The C source of the library's own part: numba's runtime (included from numba's sources) and
the module's initialisation."""

_SCALARS = ("int64", "bool", "float64")
_RETURNS = ("none", "int64", "bool", "float64")


def wanted(what: str) -> bool:
    """Whether the library holds the kernels of the warm-up's call ``what``: every question of
    the array API in the default ``certified`` mode, on every input form, the first-contact scale
    and the distance (not the other modes, nor the benchmark's read of memory)."""
    return not any(o in what for o in ("mode='filter'", "mode='float'", "read_all"))


def calls() -> list[tuple[str, Callable[[], Any]]]:
    """The calls whose kernels the library holds (:func:`wanted` of the warm-up's list,
    :func:`quadric_contact.interfaces.warmup.calls`)."""
    return [(what, call) for what, call in warm_calls() if wanted(what)]


def _compile_in_two(log: Callable[[str], None]) -> None:
    """numba compiles on one core: two processes fill its on-disk cache with the kernels of
    :func:`calls`, one from each end of the list (the warm-up's way: a kernel the other is
    compiling is put off and loaded from the cache later), before this process records them."""
    t0 = time.perf_counter()
    code = (
        "import sys; from quadric_contact.codegen.native import wanted; "
        "from quadric_contact.interfaces.warmup import warm_kernels; "
        "warm_kernels(lambda line: None, reverse=sys.argv[1] == 'reverse', only=wanted)"
    )
    env = dict(os.environ, QUADRIC_CONTACT_KERNELS="wait", QUADRIC_CONTACT_NATIVE="0")
    orders = ("forward", "reverse")
    runs = [subprocess.Popen([sys.executable, "-c", code, order], env=env) for order in orders]
    for run in runs:
        run.wait()
    seconds = time.perf_counter() - t0
    log(f"quadric-contact: the kernels compiled (or loaded) in two processes in {seconds:.0f} s")


def _record(
    todo: Sequence[tuple[str, Callable[[], Any]]], log: Callable[[str], None]
) -> list[tuple[Any, Any]]:
    """Run the calls; return every (dispatcher, signature) they called from Python."""
    seen: dict[tuple[int, Any], tuple[Any, Any]] = {}

    def note(dispatcher: Any, sig: Any) -> None:
        seen.setdefault((id(dispatcher), sig), (dispatcher, sig))

    _jit.set_kernel_policy("wait")
    _jit.CALL_OBSERVERS.append(note)
    try:
        for what, call in todo:
            t0 = time.perf_counter()
            call()
            log(f"  {what}: {time.perf_counter() - t0:.1f} s")
    finally:
        _jit.CALL_OBSERVERS.remove(note)
    return list(seen.values())


def _describe(t: Any) -> list[Any]:
    from numba.core import types  # optional numba: only the build needs it

    if isinstance(t, types.Array):
        if t.layout != "C":
            raise TypeError(f"a {t.layout}-layout array: the native kernels take C-contiguous arrays")
        return ["array", str(t.dtype), t.ndim]
    name = "bool" if isinstance(t, types.Boolean) else str(t)
    if name not in _SCALARS:
        raise TypeError(f"an argument of type {t}")
    return ["scalar", name]


@functools.cache
def _read_only() -> Any:
    """A numba intrinsic that gives its array argument back typed read-only (the data model of
    the two is the same): the wrapper passes ``numba.carray``'s writable arrays where the kernel
    was called with read-only ones, so that it calls the very version that was recorded (not a
    writable one compiled for it).  One intrinsic for the whole build (numba types each
    intrinsic object once)."""
    from numba.core.imputils import impl_ret_borrowed  # optional numba: only the build needs it
    from numba.extending import intrinsic  # optional numba: only the build needs it

    @intrinsic
    def read_only(typingctx: Any, a: Any) -> Any:
        def codegen(context: Any, builder: Any, signature: Any, args: Any) -> Any:
            return impl_ret_borrowed(context, builder, signature.return_type, args[0])

        return a.copy(readonly=True)(a), codegen

    return read_only


@contextmanager
def _kernels_linked_as_optimised() -> Iterator[None]:
    """While a wrapper compiles, numba links the kernel's module into the wrapper's and does not
    optimise the whole again: the kernel's module is numba's optimised one already (the run-time
    compile's code, bit for bit), and optimising it a second time cost two thirds of the
    emission's time.  The wrapper's own function is optimised as numba adds it."""
    from numba.core import codegen  # optional numba: only the build needs it

    original = codegen.CPUCodeLibrary._optimize_final_module
    codegen.CPUCodeLibrary._optimize_final_module = lambda self: None
    try:
        yield
    finally:
        codegen.CPUCodeLibrary._optimize_final_module = original


def _wrapper(dispatcher: Any, sig: Any) -> tuple[Any, list[list[Any]], str]:
    """The ``cfunc`` that takes plain C values and calls the kernel, its arguments' layout and
    its return kind."""
    from numba import carray, cfunc, types  # optional numba: only the build needs it

    kinds = [_describe(t) for t in sig]
    ret = dispatcher.overloads[sig].signature.return_type
    ret_name = "none" if isinstance(ret, types.NoneType) else str(ret)
    ret_name = "bool" if isinstance(ret, types.Boolean) else ret_name
    if ret_name not in _RETURNS:
        raise TypeError(f"it returns {ret}")
    params: list[str] = []
    ctypes_: list[Any] = []
    lines: list[str] = []
    args: list[str] = []
    scalar_types = {"int64": types.int64, "bool": types.boolean, "float64": types.float64}
    for i, kind in enumerate(kinds):
        if kind[0] == "array":
            shape = [f"s{i}_{d}" for d in range(kind[2])]
            params += [f"p{i}", *shape]
            ctypes_ += [types.voidptr] + [types.intp] * kind[2]
            array = f"carray(p{i}, ({', '.join(shape)},), np.{kind[1]})"
            array = f"read_only({array})" if sig[i].mutable is False else array
            lines.append(f"    a{i} = {array}")
            args.append(f"a{i}")
        else:
            params.append(f"x{i}")
            ctypes_.append(scalar_types[kind[1]])
            args.append(f"x{i}")
    call = f"kernel({', '.join(args)})"
    body = f"    {call}\n    return 0\n" if ret_name == "none" else f"    return {call}\n"
    source = f"def wrapper({', '.join(params)}):\n" + "\n".join(lines) + ("\n" if lines else "") + body
    namespace: dict[str, Any] = {"carray": carray, "np": np, "kernel": dispatcher, "read_only": _read_only()}
    # the source is generated here, from the kernel's numba types: no text from anyone else
    exec(compile(source, f"<native wrapper of {kernel_identity(dispatcher)}>", "exec"), namespace)
    restype = types.int64 if ret_name == "none" else scalar_types[ret_name]
    with _kernels_linked_as_optimised():
        wrapped = cfunc(restype(*ctypes_), nopython=True, error_model="numpy")(namespace["wrapper"])
    return wrapped, kinds, ret_name


def _only_read(dispatcher: Any, sig: Any) -> list[bool]:
    """For each array argument of the kernel, whether LLVM proved that the kernel only reads
    through its data pointer: the ``readonly`` attribute its analysis put on that parameter of
    the kernel's function, in numba's optimised module (numba passes an array as its members,
    one parameter each, after the return and exception pointers).  Such an argument may be a
    read-only array of the caller's, passed as it is."""
    from numba.core import types  # optional numba: only the build needs it

    overload = dispatcher.overloads[sig]
    module = overload.library._get_module_for_linking()
    function = module.get_function(overload.fndesc.mangled_name)
    context = dispatcher.targetctx
    packer = context.get_arg_packer(overload.fndesc.argtypes)
    members = packer._unflattener.unflatten(list(function.arguments)[2:])
    only_read: list[bool] = []
    for t, member in zip(sig, members, strict=True):
        if isinstance(t, types.Array):
            data = member[context.data_model_manager[t]._fields.index("data")]
            only_read.append(b"readonly" in set(data.attributes))
    return only_read


def _object(wrapped: Any, symbol: str, target: Any) -> bytes:
    """The wrapper's module, the kernel linked in, as an object: the entry renamed ``symbol``,
    every other definition internal (each object carries its own copy of the helpers it uses)."""
    import llvmlite.binding as ll  # numba's, optional: only the build needs it

    library = wrapped._library
    library._ensure_finalized()
    module = ll.parse_bitcode(library._final_module.as_bitcode())
    entry = wrapped.native_name
    for fn in module.functions:
        if not fn.is_declaration and fn.name != entry:
            fn.linkage = "internal"
    for gv in module.global_variables:
        if not gv.is_declaration:
            gv.linkage = "internal"
    module.get_function(entry).name = symbol
    return bytes(target.emit_object(module))


def _target() -> tuple[Any, str, str]:
    """The target machine of the objects: this machine's processor and features (as the run-time
    compile has them), position-independent code for a shared library."""
    import llvmlite.binding as ll  # numba's, optional: only the build needs it

    cpu = ll.get_host_cpu_name()
    features = ll.get_host_cpu_features().flatten()
    target = ll.Target.from_default_triple().create_target_machine(
        cpu=cpu, features=features, opt=3, reloc="pic", codemodel="default"
    )
    return target, cpu, features


def _emit(
    out: Path, log: Callable[[str], None], part: tuple[int, int]
) -> tuple[list[dict[str, Any]], list[str]]:
    """Record the kernels of :func:`calls` and emit the objects of share ``part = (k, n)`` of
    them (those whose symbol's digest is ``k`` modulo ``n``) into ``out``; return their manifest
    entries and object files."""
    t0 = time.perf_counter()
    recorded = _record(calls(), lambda line: None)
    target, _, _ = _target()
    entries: list[dict[str, Any]] = []
    objects: list[str] = []
    for dispatcher, sig in recorded:
        name = kernel_identity(dispatcher)
        signature = [str(t) for t in sig]
        digest = hashlib.sha256(json.dumps([name, signature]).encode()).hexdigest()[:16]
        if int(digest, 16) % part[1] != part[0]:
            continue
        try:
            wrapped, kinds, ret = _wrapper(dispatcher, sig)
        except TypeError as exc:  # left to the run-time compile, and said
            log(f"  not native (compiled at run time): {name}: {exc}")
            continue
        symbol = f"qc_kernel_{digest}"
        path = out / f"{symbol}.o"
        path.write_bytes(_object(wrapped, symbol, target))
        only_read = _only_read(dispatcher, sig)
        for kind, read in zip((k for k in kinds if k[0] == "array"), only_read, strict=True):
            kind.append(read)  # ["array", dtype, ndim, only read]
        objects.append(str(path))
        entries.append(
            {
                "kernel": name,
                "signature": signature,
                "symbol": symbol,
                "arguments": kinds,
                "returns": ret,
                "sources": _jit.sources_digest(dispatcher.py_func.__module__),
            }
        )
    log(f"quadric-contact: {len(entries)} native kernels emitted in {time.perf_counter() - t0:.0f} s")
    return entries, objects


def build(out: Path, log: Callable[[str], None] = print) -> dict[str, Any]:
    """Compile the kernels of :func:`calls` into objects in ``out`` and write the manifest and
    ``build.json`` there; return the latter's content.  With two cores or more, numba compiles in
    two processes (:func:`_compile_in_two`) and two more emit half the objects each (the machine
    code of every kernel is generated twice there: when numba finalises the wrapper, and as the
    object)."""
    import numba  # optional numba: only the build needs it
    from numba import _helperlib  # optional numba: only the build needs it

    out.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    entries: list[dict[str, Any]] = []
    objects: list[str] = []
    if (os.cpu_count() or 1) >= 2:
        _compile_in_two(log)
        env = dict(os.environ, QUADRIC_CONTACT_KERNELS="wait", QUADRIC_CONTACT_NATIVE="0")
        cmd = [sys.executable, "-m", "quadric_contact.codegen.native", "--out", str(out), "--part"]
        runs = [subprocess.Popen([*cmd, f"{k}/2"], env=env) for k in range(2)]
        if any(run.wait() for run in runs):
            raise RuntimeError("emitting the native kernels failed (see above)")
        for k in range(2):
            part = json.loads((out / f"part-{k}.json").read_text(encoding="utf-8"))
            entries += part["entries"]
            objects += part["objects"]
    else:
        entries, objects = _emit(out, log, (0, 1))
    entries.sort(key=lambda e: e["symbol"])
    _, cpu, features = _target()
    manifest = {"cpu": cpu, "features": features, "numba": numba.__version__, "kernels": entries}
    text = json.dumps(manifest, indent=1)
    (out / MANIFEST_NAME).write_text(text, encoding="utf-8")
    numba_dir = Path(numba.__file__).resolve().parent
    info = {
        "objects": sorted(objects),
        "manifest": str(out / MANIFEST_NAME),
        "sources": [str(RUNTIME_SOURCE), str(numba_dir / "core" / "runtime" / "nrt.cpp")],
        "include_dirs": [str(numba_dir), np.get_include(), sysconfig.get_paths()["include"]],
        # the width of LAPACK's integers numba's helper library was built with (numba.pycc
        # passes it the same way); the kernels call no LAPACK
        "ilp64": str(int(getattr(_helperlib, "LAPACK_BUILD_ILP64", 0))),
        "manifest_digest": manifest_digest(text.encode()),
    }
    (out / "build.json").write_text(json.dumps(info, indent=1), encoding="utf-8")
    log(f"quadric-contact: {len(entries)} native kernels in {time.perf_counter() - t0:.0f} s")
    return info


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m quadric_contact.codegen.native", description=(__doc__ or "").split("\n")[0]
    )
    parser.add_argument("--out", required=True, type=Path, help="directory for the objects and the manifest")
    parser.add_argument("--part", help="K/N: only emit share K of N of the objects (the build's own use)")
    args = parser.parse_args(argv)
    os.environ["QUADRIC_CONTACT_NATIVE"] = "0"  # record what the run-time compile calls

    def log(line: str) -> None:
        print(line, file=sys.stderr, flush=True)

    if args.part:
        k, n = (int(v) for v in args.part.split("/"))
        entries, objects = _emit(args.out, log, (k, n))
        part = {"entries": entries, "objects": objects}
        (args.out / f"part-{k}.json").write_text(json.dumps(part), encoding="utf-8")
        return 0
    build(args.out, log=log)
    return 0


if __name__ == "__main__":
    sys.exit(main())
