"""The native kernels: the default mode's kernels as the build compiled them (``setup.py``,
:mod:`quadric_contact.codegen.native`), run through C with no compiler at run time.

* The default path never invokes a JIT: in a fresh process with an empty kernel cache, every
  question of the array API in the default mode, on every input form and on pairs that reach the
  exact stage, answers without numba compiling anything.
* The answers are the run-time compile's, bit for bit (the same machine code: both come from
  numba's optimised module of the same sources), for read-only inputs too.
* A kernel whose sources are not those the library was built from is not run natively, and the
  manifest tells the kernels made by one factory apart.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from tests.compile_events import RECORD_COMPILES

from quadric_contact.modes.kernels import _jit, native
from quadric_contact.modes.kernels._jit import HAVE_NUMBA

ROOT = Path(__file__).resolve().parents[1]

pytestmark = pytest.mark.skipif(not HAVE_NUMBA, reason="numba not installed")

BUILD_HINT = (
    "the native kernels of these sources are not built: `pip install .` builds them (the README's "
    "commands), `python setup.py build_ext --inplace` in a checkout"
)

CALLS = (
    RECORD_COMPILES
    + """
import json, sys
import numpy as np
import quadric_contact as qc
from quadric_contact.testing.samples import kernel_population
from quadric_contact.interfaces.warmup import calls
from quadric_contact.modes.kernels import native

done = []
for what, call in calls():
    if any(o in what for o in ("mode='filter'", "mode='float'", "read_all")):
        continue
    call()
    done.append(what)
E, Q = kernel_population(1000, np.random.default_rng(0))
answers = {
    "contact": qc.transversal_contact(E, Q).tolist(),
    "region": qc.relative_position(E, Q).tolist(),
    "overlap": qc.overlap(E, Q[:, :, :]).tolist(),
}
lib = native.library()
print(json.dumps({"compiled": compiled, "calls": done, "answers": answers,
                  "library": None if lib is None else str(lib.path)}))
"""
)


def _run(tmp_path: Path, **env_vars: str) -> dict:
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT / "src"), str(ROOT)]))
    env["QUADRIC_CONTACT_CACHE_DIR"] = str(tmp_path / "empty cache")
    env["QUADRIC_CONTACT_KERNELS"] = "wait"  # a kernel not in the library is compiled, and seen
    env.update(env_vars)
    proc = subprocess.run(
        [sys.executable, "-c", CALLS], env=env, capture_output=True, text=True, timeout=900, check=True
    )
    return json.loads(proc.stdout)


def _library() -> native.NativeLibrary:
    lib = native.library()
    if lib is None or not lib.usable:
        pytest.fail(BUILD_HINT)
    return lib


def test_the_default_path_never_invokes_a_jit_and_answers_as_the_run_time_compile(tmp_path):
    """A fresh process with an empty kernel cache runs every call of the default mode without
    numba compiling anything; its answers are those of numba's run-time compile of the same
    kernels, here (the tests' cache)."""
    import quadric_contact as qc
    from quadric_contact.testing.samples import kernel_population

    _library()
    got = _run(tmp_path)
    assert got["library"] is not None, BUILD_HINT
    assert len(got["calls"]) > 40
    assert got["compiled"] == [], f"{BUILD_HINT} (numba compiled {got['compiled']})"
    E, Q = kernel_population(1000, np.random.default_rng(0))
    with _jit.turned_off():
        compiled = {
            "contact": qc.transversal_contact(E, Q).tolist(),
            "region": qc.relative_position(E, Q).tolist(),
            "overlap": qc.overlap(E, Q).tolist(),
        }
    assert got["answers"] == compiled


def test_read_only_inputs_run_natively_too(tmp_path):
    """Read-only arrays (a broadcast, a read-only buffer) run the kernels built for writable ones:
    as they are where LLVM proved the kernel only reads them, else copied; never compiled, and
    never written."""
    script = (
        RECORD_COMPILES
        + """
import json
import numpy as np
import quadric_contact as qc
from quadric_contact.testing.samples import kernel_population
E, Q = kernel_population(500, np.random.default_rng(1))
before = (E.copy(), Q.copy())
E.setflags(write=False)
Q.setflags(write=False)
out = [qc.transversal_contact(E, Q).tolist(), qc.overlap(E, Q).tolist(), qc.relative_position(E, Q).tolist(),
       qc.transversal_contact(np.broadcast_to(E[0], (7, 4, 4)), Q[:7]).tolist()]
same = bool(np.array_equal(before[0], E) and np.array_equal(before[1], Q))
print(json.dumps({"compiled": compiled, "out": out, "same": same}))
"""
    )
    _library()
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT / "src"), str(ROOT)]))
    env["QUADRIC_CONTACT_CACHE_DIR"] = str(tmp_path / "empty cache")
    env["QUADRIC_CONTACT_KERNELS"] = "wait"
    proc = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True, text=True, check=True)
    got = json.loads(proc.stdout)
    assert got["compiled"] == [] and got["same"]
    import quadric_contact as qc
    from quadric_contact.testing.samples import kernel_population

    E, Q = kernel_population(500, np.random.default_rng(1))
    want = [
        qc.transversal_contact(E, Q).tolist(),
        qc.overlap(E, Q).tolist(),
        qc.relative_position(E, Q).tolist(),
    ]
    want.append(qc.transversal_contact(np.repeat(E[:1], 7, axis=0), Q[:7]).tolist())
    assert got["out"] == want


def test_a_kernel_whose_sources_changed_is_not_run_natively():
    from quadric_contact.modes.kernels.support import check_stack_kernel as dispatcher

    lib = _library()
    entries = [e for e in lib.manifest["kernels"] if e["kernel"] == native.kernel_identity(dispatcher)]
    assert entries, "the stack check is a kernel of the default path"
    sig = tuple(dispatcher.typeof_pyval(a) for a in (np.zeros((1, 4, 4)), 0, 1, np.zeros(1, np.int8)))
    assert native.lookup(dispatcher, sig, _jit.sources_digest) is not None
    assert native.lookup(dispatcher, sig, lambda module: "not these sources") is None


def test_the_manifest_tells_factory_kernels_apart():
    lib = _library()
    names = [e["kernel"] for e in lib.manifest["kernels"]]
    keys = [(e["kernel"], tuple(e["signature"])) for e in lib.manifest["kernels"]]
    assert len(set(keys)) == len(keys)
    factory = [n for n in names if "_make_pairs.<locals>.kernel" in n]
    assert factory and all(n.endswith("]") for n in factory)


def test_a_missing_library_is_said_once(capsys, monkeypatch):
    """Without a usable library (a build without a C compiler says so only in the installer's
    output, which pip hides), the first kernel call says it on stderr, once."""
    monkeypatch.setattr(native, "_SAID", [])
    native._say_missing(None)
    native._say_missing(None)
    err = capsys.readouterr().err
    assert err.count("quadric-contact: no native kernels") == 1
    assert "compiled at run time" in err
