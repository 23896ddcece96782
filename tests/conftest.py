"""Shared test configuration: hypothesis profiles (``default`` for CI,
``slow`` for the exhaustive runs selected with ``-m slow``), the working
precision restored around every test, and Example 17's scene text."""

from __future__ import annotations

import os
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
