"""Shared test configuration: the array kernels compiled (or loaded) once before the tests,
hypothesis profiles (``default`` for CI, ``slow`` for the exhaustive runs selected with
``-m slow``), the working precision restored around every test, and Example 17's scene text."""

from __future__ import annotations

import os
import queue
import subprocess
import sys
import threading
from collections.abc import Callable, Iterator
from pathlib import Path

import flint
import mpmath
import pytest
from hypothesis import HealthCheck, settings
from tests.bee_and_tree import bee_and_tree as _bee_and_tree

settings.register_profile(
    "default",
    max_examples=60,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.register_profile(
    "slow",
    max_examples=2000,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "default"))


def pytest_configure(config: pytest.Config) -> None:
    """Every call waits for its compiled kernel (the ``wait`` policy of
    :data:`quadric_contact.modes.kernels._jit.KERNEL_POLICIES`), in this process, its workers and the
    processes the tests start: a test of a compiled kernel must run the compiled kernel, not
    its Python twin, and no test starts the background warm-up."""
    from quadric_contact.modes.kernels import _jit

    os.environ["QUADRIC_CONTACT_KERNELS"] = "wait"
    _jit.set_kernel_policy("wait")


@pytest.hookimpl(tryfirst=True)
def pytest_sessionstart(session: pytest.Session) -> None:
    """Compile the array kernels into numba's on-disk cache, or load them from it, once, before
    the tests: under pytest-xdist in the controller, before its workers start (they then load
    the kernels from the cache instead of each compiling them at once, behind the capture that
    would hide the package's compile notice).  Cold, this takes minutes, and says so; warm, a
    few seconds.  The work runs in processes of their own
    (:mod:`quadric_contact.interfaces.warmup`) that import the package from ``src/`` as the
    tests do, so it fills the cache they read.
    ``QUADRIC_CONTACT_WARMUP=0`` skips it."""
    config = session.config
    if hasattr(config, "workerinput") or config.option.collectonly:
        return  # an xdist worker (the controller warmed the kernels), or nothing will run
    if os.environ.get("QUADRIC_CONTACT_WARMUP", "1") == "0":
        return  # asked not to (a run of tests that need no kernel, with a cold cache)
    reporter = config.pluginmanager.get_plugin("terminalreporter")

    def say(line: str) -> None:
        if reporter is not None:
            reporter.write_line(line)
            reporter.flush()  # now, not when the output buffer fills (a pipe in CI)
        else:  # pragma: no cover - the terminal reporter is disabled
            print(line, file=sys.stderr, flush=True)

    say("quadric-contact: compiling the array kernels once (cached afterwards), or loading them ...")
    root = Path(__file__).resolve().parents[1]
    paths = [str(root / "src"), str(root), os.environ.get("PYTHONPATH", "")]
    # numba compiles on one core: with two or more, a second process runs the list from its
    # other end, so that the two compile different kernels (cold: about half the time)
    orders = [[], ["--reverse"]] if (os.cpu_count() or 1) >= 2 else [[]]
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(filter(None, paths)))
    runs = [
        subprocess.Popen(
            [sys.executable, "-m", "quadric_contact.interfaces.warmup", *extra],
            cwd=root,
            env=env,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
        )
        for extra in orders
    ]
    # their lines as they come (a cold compile takes minutes: the run shows what it is doing)
    lines: queue.Queue[str | None] = queue.Queue()

    def relay(run: subprocess.Popen[str]) -> None:
        assert run.stdout is not None
        for line in run.stdout:
            lines.put(line.rstrip("\n"))
        lines.put(None)

    for run in runs:
        threading.Thread(target=relay, args=(run,), daemon=True).start()
    ended = 0
    while ended < len(runs):
        line = lines.get()
        if line is None:
            ended += 1
        else:
            say(line)
    for run in runs:
        if run.wait():
            say(f"quadric-contact: the warm-up failed (exit status {run.returncode}); the tests compile them")


@pytest.fixture(autouse=True)
def _restore_precision() -> Iterator[None]:
    """Every test starts at, and leaves behind, the precision it found (flint balls,
    mpmath): a test that changes it without the package's context manager
    (:func:`quadric_contact.exact.precision.working_precision`) cannot change what the
    next test computes."""
    bits, prec = flint.ctx.prec, mpmath.mp.prec
    yield
    flint.ctx.prec, mpmath.mp.prec = bits, prec


@pytest.fixture
def bee_and_tree() -> Callable[..., str]:
    """The builder of Example 17's bee-and-tree scene text (:func:`tests.bee_and_tree.bee_and_tree`)."""
    return _bee_and_tree
