"""Shared test configuration: the array kernels compiled (or loaded) once before the tests,
hypothesis profiles (``default`` for CI, ``slow`` for the exhaustive runs selected with
``-m slow``), the working precision restored around every test, and Example 17's scene text."""

from __future__ import annotations

import os
import sys
from collections.abc import Callable, Iterator

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


@pytest.hookimpl(tryfirst=True)
def pytest_sessionstart(session: pytest.Session) -> None:
    """Compile the array kernels into numba's on-disk cache, or load them from it, once, in the
    process that starts the run: under pytest-xdist the controller, before its workers start
    (they then load the kernels from the cache instead of each compiling them at once, behind
    the capture that would hide the package's compile notice).  Cold, this takes minutes, and
    says so; warm, seconds."""
    config = session.config
    if hasattr(config, "workerinput") or config.option.collectonly:
        return  # an xdist worker (the controller warmed the kernels), or nothing will run
    from tests.kernel_warmup import warm_kernels

    from quadric_contact.modes import _jit

    if not _jit.HAVE_NUMBA:
        return
    reporter = config.pluginmanager.get_plugin("terminalreporter")

    def say(line: str) -> None:
        if reporter is not None:
            reporter.write_line(line)
        else:  # pragma: no cover - the terminal reporter is disabled
            print(line, file=sys.stderr, flush=True)

    say("quadric-contact: compiling the array kernels once (cached afterwards), or loading them ...")
    seconds = warm_kernels(log=say)
    how = "compiled" if _jit._notice_printed else "loaded from numba's on-disk cache"
    say(f"quadric-contact: array kernels {how} in {seconds:.1f} s")


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
