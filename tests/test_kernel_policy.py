"""What a call does when its compiled kernel is not in numba's on-disk cache
(:data:`quadric_contact.modes.kernels._jit.KERNEL_POLICIES`): the kernels' Python twins answer small
calls with the compiled kernels' bits, a kernel that is in the cache is loaded rather than run
as a twin, and the background warm-up is started once, guarded by its lock and its marker.

The suite itself runs under the ``wait`` policy (``tests/conftest.py``); these tests choose the
other policies in processes of their own, each with an empty cache directory."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest
from tests.compile_events import RECORD_COMPILES

import quadric_contact as qc
from quadric_contact.modes.kernels import _jit
from quadric_contact.modes.kernels._jit import COMPILE_NOTICE, HAVE_NUMBA, TWINS_NOTICE
from quadric_contact.testing.samples import complete_populations

pytestmark = pytest.mark.skipif(not HAVE_NUMBA, reason="numba not installed")

ROOT = Path(__file__).resolve().parents[1]

ANSWERS = (
    RECORD_COMPILES
    + """
import json, sys
import numpy as np
import quadric_contact as qc
from quadric_contact.testing.samples import complete_populations
out = {}
for pop, (E, Q, _) in complete_populations(int(sys.argv[1]), np.random.default_rng(3)).items():
    for name in ("transversal_contact", "relative_position", "overlap"):
        for mode in ("certified", "filter", "float"):
            out[f"{pop} {name} {mode}"] = np.asarray(getattr(qc, name)(E, Q, mode=mode)).tolist()
out["compiled"] = compiled
print(json.dumps(out))
"""
)


def _run(code: str, cache: Path, policy: str, *args: str) -> subprocess.CompletedProcess[str]:
    env = dict(
        os.environ,
        NUMBA_CACHE_DIR=str(cache),  # a kernel outside the package
        QUADRIC_CONTACT_CACHE_DIR=str(cache),  # the package's kernels (this variable comes first)
        QUADRIC_CONTACT_KERNELS=policy,
        PYTHONPATH=os.pathsep.join([str(ROOT / "src"), str(ROOT)]),
    )
    return subprocess.run(
        [sys.executable, "-c", code, *args], capture_output=True, text=True, env=env, check=True, timeout=600
    )


def _kernel_files(cache: Path) -> list[Path]:
    return [p for p in cache.rglob("*") if p.suffix in (".nbi", ".nbc")]


def test_the_twins_answer_with_the_compiled_kernels_bits(tmp_path):
    """A fresh process with an empty cache and the ``twins`` policy answers every question in
    every mode on the three bench populations without invoking the compiler at all (numba's
    compile event never fires, no cache file is written, the compiler's notice is not
    printed) and gives the answers this process gets from the compiled kernels."""
    n = 120
    proc = _run(ANSWERS, tmp_path, "twins", str(n))
    assert TWINS_NOTICE.split("{")[0] in proc.stderr
    assert proc.stderr.count("quadric-contact:") == 1  # said once
    assert COMPILE_NOTICE.split("{")[0] not in proc.stderr
    assert _kernel_files(tmp_path) == []
    got = json.loads(proc.stdout)
    assert got["compiled"] == []
    for pop, (E, Q, _) in complete_populations(n, np.random.default_rng(3)).items():
        for name in ("transversal_contact", "relative_position", "overlap"):
            for mode in ("certified", "filter", "float"):
                want = np.asarray(getattr(qc, name)(E, Q, mode=mode)).tolist()
                assert got[f"{pop} {name} {mode}"] == want, (pop, name, mode)


KERNEL_MODULE = """
from quadric_contact.modes.kernels._jit import njit

@njit
def twice(x):
    return 2.0 * x
"""

CALL_IT = """
import sys
sys.path.insert(0, sys.argv[1])
import numpy as np
import kernel_here
x = np.arange(3.0)
print(kernel_here.twice(x).tolist(), len(kernel_here.twice.signatures), flush=True)
"""


def test_a_cached_kernel_is_loaded_and_a_missing_one_is_twinned(tmp_path):
    """Under the ``twins`` policy, a small call whose kernel the cache lacks runs the twin (the
    same value, nothing compiled: no signature added); once a ``wait`` process has compiled it
    into the cache, the same call loads it (one signature, no compile)."""
    (tmp_path / "mod").mkdir()
    (tmp_path / "mod" / "kernel_here.py").write_text(textwrap.dedent(KERNEL_MODULE))
    cache = tmp_path / "cache"
    first = _run(CALL_IT, cache, "twins", str(tmp_path / "mod"))
    assert first.stdout.split("]")[1].split() == ["0"]  # the twin answered
    assert first.stdout.startswith("[0.0, 2.0, 4.0]")
    assert _kernel_files(cache) == []
    _run(CALL_IT, cache, "wait", str(tmp_path / "mod"))
    assert _kernel_files(cache)
    loaded = _run(CALL_IT, cache, "twins", str(tmp_path / "mod"))
    assert loaded.stdout.startswith("[0.0, 2.0, 4.0]")
    assert loaded.stdout.split("]")[1].split() == ["1"]  # loaded from the cache
    assert "quadric-contact:" not in loaded.stderr


def test_the_warmup_state_follows_its_lock_and_marker(tmp_path, monkeypatch):
    monkeypatch.setattr(_jit, "_cache_root", lambda: str(tmp_path))
    assert _jit.warmup_state() == "none"
    with _jit.warmup_lock() as held:
        assert held
        assert _jit.warmup_state() == "running"  # another open file of the lock: refused
        with _jit.warmup_lock() as again:
            assert not again
    assert _jit.warmup_state() == "none"
    _jit.warmup_done()
    assert _jit.warmup_state() == "done"
    (tmp_path / "quadric-contact-warmup.done").write_text("the digest of other sources\n")
    assert _jit.warmup_state() == "none"


def test_the_background_warmup_starts_once_a_process(monkeypatch):
    started = []

    class Popen:
        def __init__(self, args, **kws):
            started.append((args, kws))

    monkeypatch.setattr(subprocess, "Popen", Popen)
    monkeypatch.setattr(_jit, "_started", False)
    assert _jit.start_background_warmup()
    assert not _jit.start_background_warmup()
    (args, kws), *rest = started
    assert rest == []
    assert args[1:] == ["-m", "quadric_contact.interfaces.warmup", "--background"]
    assert kws["start_new_session"] and kws["env"]["QUADRIC_CONTACT_KERNELS"] == "wait"
    assert str(ROOT / "src") in kws["env"]["PYTHONPATH"].split(os.pathsep)


def test_the_policy_is_checked():
    with pytest.raises(ValueError, match="kernel policy must be one of"):
        _jit.set_kernel_policy("sometimes")
    env = dict(os.environ, QUADRIC_CONTACT_KERNELS="sometimes", PYTHONPATH=str(ROOT / "src"))
    proc = subprocess.run(
        [sys.executable, "-c", "import quadric_contact"], capture_output=True, text=True, env=env
    )
    assert proc.returncode != 0
    assert "QUADRIC_CONTACT_KERNELS must be one of" in proc.stderr


def test_the_compile_command_warms_under_the_lock_and_leaves_the_marker(tmp_path, monkeypatch, capsys):
    """``quadric-contact compile`` runs the warm-up (here a stand-in that records whether the
    lock is held while it runs) and leaves the marker that says the cache holds every kernel."""
    from quadric_contact.interfaces import warmup
    from quadric_contact.interfaces.cli import main

    monkeypatch.setattr(_jit, "_cache_root", lambda: str(tmp_path))
    seen = []

    def run(**kws):
        seen.append(_jit.warmup_state())  # another holder of the lock: "running"
        kws["log"]("quadric-contact: array kernels loaded from numba's on-disk cache in 0.0 s")
        return 0

    monkeypatch.setattr(warmup, "run", run)
    assert main(["compile"]) == 0
    assert seen == ["running"]
    assert _jit.warmup_state() == "done"
    out = capsys.readouterr().out
    assert str(tmp_path) in out and "loaded from numba's on-disk cache" in out


def test_a_kernel_another_process_compiles_is_waited_for_or_put_off(tmp_path, monkeypatch):
    """The machine-wide lock of one kernel's compile: held elsewhere (another open file of the
    lock, as another process holds it), a deferring caller gets ``KernelBusy`` at once, any
    other caller waits until it is released."""
    import fcntl
    import threading
    import types

    monkeypatch.setattr(_jit, "_cache_root", lambda: str(tmp_path))
    stub = types.SimpleNamespace(py_func=test_the_policy_is_checked)
    name = f"{__name__}.test_the_policy_is_checked"
    fd = os.open(tmp_path / f"quadric-contact-compile.{name}.lock", os.O_RDWR | os.O_CREAT)
    fcntl.flock(fd, fcntl.LOCK_EX)
    with pytest.raises(_jit.KernelBusy), _jit.deferring(), _jit._compile_lock(stub):
        pass
    released = []

    def release():
        released.append(True)
        fcntl.flock(fd, fcntl.LOCK_UN)

    threading.Timer(0.2, release).start()
    with _jit._compile_lock(stub):
        assert released  # it got the lock only once the other holder let it go
    os.close(fd)


@pytest.mark.skipif(not HAVE_NUMBA, reason="numba is not installed")
def test_the_kernels_helpers_are_inlined_by_llvm_not_retyped_at_every_call_site():
    """Every helper the kernels inline is ``forceinline`` (LLVM's ``alwaysinline``: typed once
    per signature), never numba's ``inline="always"`` (typed again at every call site: six
    times the compile time of the warm-up's kernels, at the same throughput), whichever side of
    its pair the module binds: the compiled one (``njit(inline=True)``) or the plain one
    (``jitable(inline=True)``, the smallness helpers and the signs)."""
    import importlib
    import types

    import numba

    helpers = []
    for name in ("kernels.criterion", "kernels.filter", "kernels.signature", "kernels.support",
                 "kernels.decision", "kernels.signs", "decision.separation", "decision.answers",
                 "distance.scale_kernel", "distance.scale_blocks", "distance.scale_both",
                 "distance.apart_kernel", "distance.depth_kernel", "smallness.binary64"):  # fmt: skip
        module = importlib.import_module(f"quadric_contact.modes.{name}")
        for value in vars(module).values():
            if isinstance(value, types.FunctionType) and value.__module__ == module.__name__:
                try:
                    value = _jit.compiled(value)  # the compiled side of a plain helper
                except TypeError:
                    continue  # Python only
            if (
                isinstance(value, numba.core.registry.CPUDispatcher)
                and value.py_func.__module__ == module.__name__
            ):
                options = value.targetoptions
                assert options.get("inline", "never") == "never", (name, value.__name__)
                if options.get("forceinline"):
                    helpers.append((name, value.__name__))
    assert len(helpers) > 130, len(helpers)
    assert {("kernels.signs", "sign_within"), ("smallness.binary64", "_e_row")} <= set(helpers)
    # the pairs made so far: a plain side that numba types as its compiled side
    for plain_side, compiled_side, inline in _jit.pairs():
        assert compiled_side.py_func is plain_side or plain_side is _jit.select
        assert bool(compiled_side.targetoptions.get("forceinline")) == inline, plain_side
