"""Exit statuses of the ``quadric-contact`` command (shared by its subcommands)."""

from __future__ import annotations

__all__ = ["EXIT_BAD_INPUT", "EXIT_FAILED", "EXIT_OK", "EXIT_UNDECIDED"]

EXIT_OK = 0
"""The command did what was asked (a decision was reached, the checks passed)."""
EXIT_FAILED = 1
"""A check failed (``prove``)."""
EXIT_BAD_INPUT = 2
"""The input was refused (a bad equation, an unknown scene, a bad option)."""
EXIT_UNDECIDED = 3
"""The theory does not decide the case (``check``)."""
