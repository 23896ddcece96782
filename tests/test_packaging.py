"""The package as a user installs it: ``python -m build`` makes an sdist and a wheel, the wheel
installs into a fresh virtual environment, and there, from a directory outside the checkout,
the first array calls answer at once (the kernels' Python twins: no compiler invoked) with the
answers this process gets; and with the cache this checkout compiled its kernels into, the
installed copy loads them (one compiled code for the tests and the installed package)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tarfile
from pathlib import Path

import numpy as np
import pytest
from tests.compile_events import RECORD_COMPILES

import quadric_contact as qc
from quadric_contact.interfaces.benchmark import kernel_population
from quadric_contact.modes._jit import HAVE_NUMBA, TWINS_NOTICE, kernel_cache_dir

ROOT = Path(__file__).resolve().parents[1]
PIP_OFFLINE = ("--no-deps", "--no-index", "--ignore-installed", "-q")

SMOKE = (
    RECORD_COMPILES
    + """
import json
import numpy as np
import quadric_contact as qc
from quadric_contact.interfaces.benchmark import kernel_population
E, Q = kernel_population(1000, np.random.default_rng(0))
contact = qc.transversal_contact(E, Q).tolist()
overlap = qc.overlap(E, Q).tolist()
print(json.dumps({"file": qc.__file__, "contact": contact, "overlap": overlap, "compiled": compiled}))
"""
)


@pytest.mark.skipif(not HAVE_NUMBA, reason="numba not installed")
def test_the_wheel_installs_and_answers_in_a_fresh_environment(tmp_path):
    dist = tmp_path / "dist"
    subprocess.run(
        [sys.executable, "-m", "build", "--no-isolation", "--outdir", str(dist), str(ROOT)],
        check=True,
        capture_output=True,
        text=True,
        timeout=600,
    )
    (wheel,) = dist.glob("quadric_contact-*.whl")
    (sdist,) = dist.glob("quadric_contact-*.tar.gz")
    with tarfile.open(sdist) as tar:
        names = {n.split("/", 1)[1] for n in tar.getnames() if "/" in n}
    assert {"pyproject.toml", "README.md", "src/quadric_contact/__init__.py", "proofs/REPORT.md"} <= names

    venv = tmp_path / "venv"
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
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "NUMBA_CACHE_DIR")}
    env["QUADRIC_CONTACT_KERNELS"] = "twins"  # the default, without its background process
    env["QUADRIC_CONTACT_CACHE_DIR"] = str(tmp_path / "empty cache")
    work = tmp_path / "elsewhere"
    work.mkdir()

    def smoke() -> tuple[dict, str]:
        run = [str(python), "-c", SMOKE]
        proc = subprocess.run(run, cwd=work, env=env, capture_output=True, text=True, check=True, timeout=600)
        return json.loads(proc.stdout), proc.stderr

    # an empty cache: the twins answer, nothing is compiled
    got, err = smoke()
    assert Path(got["file"]).resolve().is_relative_to(venv.resolve())
    assert got["compiled"] == []
    assert TWINS_NOTICE.split("{")[0] in err
    E, Q = kernel_population(1000, np.random.default_rng(0))
    assert got["contact"] == qc.transversal_contact(E, Q).tolist()
    assert got["overlap"] == qc.overlap(E, Q).tolist()
    # the cache this checkout's kernels are in (the calls above put these ones there): the
    # installed copy loads them, with no twin and no compile
    env["QUADRIC_CONTACT_CACHE_DIR"] = kernel_cache_dir()
    got, err = smoke()
    assert got["compiled"] == []
    assert TWINS_NOTICE.split("{")[0] not in err
    assert got["contact"] == qc.transversal_contact(E, Q).tolist()
    # the entry point is installed too
    cli = subprocess.run(
        [str(venv / "bin" / "quadric-contact"), "--help"], cwd=work, env=env, capture_output=True, text=True
    )
    assert cli.returncode == 0 and "compile" in cli.stdout
