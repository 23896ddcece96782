"""The package as a user installs it: ``python -m build`` makes an sdist and a wheel with the
native kernels, the wheel installs into a fresh virtual environment, and there, from a
directory outside the checkout, the first array calls answer at once with the answers this
process gets, nothing compiled.  Built without a C compiler, the wheel has no native kernels and
says so; its first small calls run the kernels' Python twins, and with the cache this checkout
compiled its kernels into, it loads them."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tarfile
import zipfile
from pathlib import Path

import numpy as np
import pytest
from tests.compile_events import RECORD_COMPILES

import quadric_contact as qc
from quadric_contact.modes.kernels import _jit
from quadric_contact.modes.kernels._jit import HAVE_NUMBA, TWINS_NOTICE, kernel_cache_dir
from quadric_contact.testing.samples import kernel_population

ROOT = Path(__file__).resolve().parents[1]
PIP_OFFLINE = ("--no-deps", "--no-index", "--ignore-installed", "-q")

SMOKE = (
    RECORD_COMPILES
    + """
import json
import numpy as np
import quadric_contact as qc
from quadric_contact.testing.samples import kernel_population
E, Q = kernel_population(1000, np.random.default_rng(0))
contact = qc.transversal_contact(E, Q).tolist()
overlap = qc.overlap(E, Q).tolist()
from quadric_contact.modes.kernels import _jit, native
lib = native.library() if native.enabled() else None
where = None if lib is None or not lib.usable else str(lib.path)
print(json.dumps({"file": qc.__file__, "contact": contact, "overlap": overlap, "compiled": compiled,
                  "native": where}))
"""
)


def _build(tmp_path: Path, name: str, **env_vars: str) -> tuple[Path, Path, str]:
    dist = tmp_path / name
    env = dict(os.environ, **env_vars)
    proc = subprocess.run(
        [sys.executable, "-m", "build", "--no-isolation", "--outdir", str(dist), str(ROOT)],
        check=True,
        capture_output=True,
        text=True,
        timeout=900,
        env=env,
    )
    (wheel,) = dist.glob("quadric_contact-*.whl")
    (sdist,) = dist.glob("quadric_contact-*.tar.gz")
    return wheel, sdist, proc.stdout + proc.stderr


def _venv(tmp_path: Path, name: str, wheel: Path) -> Path:
    venv = tmp_path / name
    # the dependencies come from this environment; the package itself only from the wheel,
    # installed by this environment's pip into the new one (no pip of its own to set up)
    subprocess.run(
        [sys.executable, "-m", "venv", "--without-pip", "--system-site-packages", str(venv)],
        check=True,
        timeout=300,
    )
    python = venv / "bin" / "python"
    subprocess.run(
        [sys.executable, "-m", "pip", "--python", str(python), "install", *PIP_OFFLINE, str(wheel)],
        check=True,
        capture_output=True,
        timeout=300,
    )
    return venv


def _smoke(tmp_path: Path, venv: Path, cache: str, **env_vars: str) -> tuple[dict, str]:
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "NUMBA_CACHE_DIR")}
    env.update(env_vars)
    env["QUADRIC_CONTACT_KERNELS"] = "twins"  # the default, without its background process
    env["QUADRIC_CONTACT_CACHE_DIR"] = cache
    work = tmp_path / "elsewhere"
    work.mkdir(exist_ok=True)
    run = [str(venv / "bin" / "python"), "-c", SMOKE]
    proc = subprocess.run(run, cwd=work, env=env, capture_output=True, text=True, check=True, timeout=600)
    got = json.loads(proc.stdout)
    assert Path(got["file"]).resolve().is_relative_to(venv.resolve())
    return got, proc.stderr


@pytest.mark.skipif(not HAVE_NUMBA, reason="numba not installed")
def test_the_wheel_installs_and_answers_in_a_fresh_environment(tmp_path):
    """The wheel carries the native kernels: installed in a fresh environment, with an empty
    kernel cache, the first calls compile nothing and run no twin."""
    wheel, sdist, _ = _build(tmp_path, "dist")
    with tarfile.open(sdist) as tar:
        names = {n.split("/", 1)[1] for n in tar.getnames() if "/" in n}
    assert {
        "pyproject.toml",
        "setup.py",
        "README.md",
        "src/quadric_contact/__init__.py",
        "src/quadric_contact/codegen/native_runtime.c",
        "proofs/REPORT.md",
    } <= names
    with zipfile.ZipFile(wheel) as whl:
        inside = whl.namelist()
    assert any(n.startswith("quadric_contact/_native.") and n.endswith(".so") for n in inside)
    assert "quadric_contact/_native_manifest.json" in inside

    venv = _venv(tmp_path, "venv", wheel)
    got, err = _smoke(tmp_path, venv, str(tmp_path / "empty cache"))
    assert got["compiled"] == []
    assert TWINS_NOTICE.split("{")[0] not in err
    assert Path(got["native"]).resolve().is_relative_to(venv.resolve())
    E, Q = kernel_population(1000, np.random.default_rng(0))
    assert got["contact"] == qc.transversal_contact(E, Q).tolist()
    assert got["overlap"] == qc.overlap(E, Q).tolist()
    # the entry point is installed too
    cli = subprocess.run(
        [str(venv / "bin" / "quadric-contact"), "--help"], cwd=tmp_path, capture_output=True, text=True
    )
    assert cli.returncode == 0 and "compile" in cli.stdout


@pytest.mark.skipif(not HAVE_NUMBA, reason="numba not installed")
def test_without_a_compiler_the_wheel_compiles_its_kernels_at_run_time(tmp_path):
    """No C compiler (``CC`` a command that fails): the build says the native kernels were not
    built and goes on; the installed package answers the same, its first small calls by the
    kernels' Python twins (nothing compiled), and with the cache this checkout compiled its
    kernels into, it loads them."""
    wheel, _, log = _build(tmp_path, "dist", CC="false", CXX="false")
    assert "the native kernels were not built" in log
    with zipfile.ZipFile(wheel) as whl:
        assert not any(n.startswith("quadric_contact/_native") for n in whl.namelist())
    venv = _venv(tmp_path, "venv", wheel)
    # the environment sees this one's packages, whose copy of the package may have native kernels
    # of the same sources (which it would rightly use): as on a machine with none, it is told
    # not to look
    off = {"QUADRIC_CONTACT_NATIVE": "0"}
    got, err = _smoke(tmp_path, venv, str(tmp_path / "empty cache"), **off)
    assert got["compiled"] == [] and got["native"] is None
    assert TWINS_NOTICE.split("{")[0] in err
    E, Q = kernel_population(1000, np.random.default_rng(0))
    assert got["contact"] == qc.transversal_contact(E, Q).tolist()
    assert got["overlap"] == qc.overlap(E, Q).tolist()
    # the cache this checkout's kernels are in (these calls put them there, compiled at run
    # time): the installed copy loads them, no twin, no compile
    with _jit.turned_off():
        qc.transversal_contact(E, Q), qc.overlap(E, Q)
    got, err = _smoke(tmp_path, venv, kernel_cache_dir(), **off)
    assert got["compiled"] == []
    assert TWINS_NOTICE.split("{")[0] not in err
    assert got["contact"] == qc.transversal_contact(E, Q).tolist()
