"""Numbers, addresses and output paths on the command line, read and checked before any work.

Every number goes through the package's reader
(:func:`~quadric_contact.exact.reading.parse_number`), as numbers in equations
and scene files do, so ``--amplitude 1e100000`` is refused at once (not
computed) and full-width digits are refused here as everywhere else.  Each
option has its range, from :mod:`quadric_contact.exact.bounds`.
"""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Callable
from fractions import Fraction
from pathlib import Path

from quadric_contact.exact.errors import QuadricContactError, SceneError
from quadric_contact.exact.reading import parse_number

__all__ = ["check_output_path", "integer", "rational", "user_cache_dir"]


def _read(option: str, text: str) -> Fraction:
    try:
        return parse_number(text)
    except QuadricContactError as exc:
        first = str(exc).splitlines()[0]
        raise argparse.ArgumentTypeError(f"expected a number, got {text!r}: {first}") from None


def integer(option: str, low: int, high: int) -> Callable[[str], int]:
    """An argparse ``type``: an integer in ``[low, high]``, read by the package's reader."""

    def read(text: str) -> int:
        value = _read(option, text)
        if value.denominator != 1 or not low <= value <= high:
            raise argparse.ArgumentTypeError(f"expected an integer in [{low}, {high}], got {text!r}")
        return int(value)

    read.__name__ = "integer"
    return read


def rational(option: str, low: Fraction, high: Fraction, *, max_digits: int) -> Callable[[str], Fraction]:
    """An argparse ``type``: an exact rational in ``[low, high]`` whose numerator
    and denominator have at most ``max_digits`` digits."""

    def read(text: str) -> Fraction:
        value = _read(option, text)
        if not low <= value <= high:
            raise argparse.ArgumentTypeError(f"expected a number in [{low}, {high}], got {text!r}")
        limit = 10**max_digits
        if abs(value.numerator) >= limit or value.denominator >= limit:
            raise argparse.ArgumentTypeError(
                f"at most {max_digits} digits in the numerator and the denominator, got {text!r}"
            )
        return value

    read.__name__ = "rational"
    return read


def check_output_path(option: str, path: str) -> None:
    """Refuse, before the run, an output path that cannot be written: a directory,
    something other than a regular file, or a missing or read-only folder."""
    target = Path(path)
    folder = target.parent if str(target.parent) else Path(".")
    if target.is_dir():
        raise SceneError(f"{option} {path}: is a directory, not a file", path)
    if target.exists() and not target.is_file():
        raise SceneError(f"{option} {path}: exists and is not a regular file", path)
    if not folder.is_dir():
        raise SceneError(f"{option} {path}: the folder {folder} does not exist", path)
    if not os.access(folder, os.W_OK | os.X_OK):
        raise SceneError(f"{option} {path}: the folder {folder} is not writable", path)


def user_cache_dir(*parts: str) -> Path:
    """The package's folder in the user's cache directory, with ``parts`` below it: where the
    commands keep what they write unless told otherwise (``bench``'s tables, ``prove``'s
    hypothesis cache), never the current directory.

    ``$XDG_CACHE_HOME/quadric-contact`` (an absolute ``XDG_CACHE_HOME`` only, as the XDG
    specification asks), else ``~/.cache/quadric-contact`` on Linux and other Unix systems;
    ``~/Library/Caches/quadric-contact`` on macOS; ``%LOCALAPPDATA%\\quadric-contact\\Cache``
    on Windows.  The folder is not created here."""
    if sys.platform == "win32":
        local = os.environ.get("LOCALAPPDATA", "").strip()
        base = (Path(local) if local else Path.home() / "AppData" / "Local") / "quadric-contact" / "Cache"
    elif sys.platform == "darwin":
        base = Path.home() / "Library" / "Caches" / "quadric-contact"
    else:
        xdg = os.environ.get("XDG_CACHE_HOME", "").strip()
        root = Path(xdg) if xdg and Path(xdg).is_absolute() else Path.home() / ".cache"
        base = root / "quadric-contact"
    return base.joinpath(*parts)
