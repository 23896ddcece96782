"""The number modes by name: ``mode="certified"`` and the like, and the one function that turns a
name (or an instance) into a mode."""

from __future__ import annotations

from typing import Any

from quadric_contact.exact.errors import ChoiceError
from quadric_contact.modes.numbers.binary64 import FilterMode, FloatMode
from quadric_contact.modes.numbers.certified import CertifiedMode
from quadric_contact.modes.numbers.number_mode import NumberMode
from quadric_contact.modes.numbers.objects import BallMode, ExactMode, MpmathMode

__all__ = ["MODES", "get_mode"]

MODES: dict[str, type[NumberMode]] = {
    "certified": CertifiedMode,
    "filter": FilterMode,
    "float": FloatMode,
    "ball": BallMode,
    "mpmath": MpmathMode,
    "exact": ExactMode,
}
"""Mode names and their classes."""


def get_mode(mode: str | NumberMode = "certified", **options: Any) -> NumberMode:
    """A mode instance from a name (with ``options`` for its constructor) or an instance.

    Raises
    ------
    ValueError
        For an unknown name.
    """
    if isinstance(mode, NumberMode):
        if options:
            raise ValueError("options are only accepted with a mode name")
        return mode
    if not isinstance(mode, str) or mode not in MODES:
        raise ChoiceError(
            f"mode must be one of {', '.join(MODES)} or a NumberMode, got {mode!r}",
            mode,
            choices=tuple(MODES),
        )
    return MODES[mode](**options)
