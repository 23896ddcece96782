"""Loading the optional dependencies, with one error that names the extra to install.

The core of the package needs numpy, sympy, python-flint, mpmath and numba; plots,
animations, the distributed sweeps and some benchmarks need packages declared as
extras in ``pyproject.toml`` (``plot``, ``dask``, ``bench``).  Every module that
needs one of them imports it through :func:`require` (or :func:`pyplot` for
matplotlib's drawing interface), so that a missing package is reported the same
way everywhere: a :class:`~quadric_contact.exact.errors.MissingDependencyError` (an
``ImportError``) whose message says which extra provides it.

This module imports only :mod:`~quadric_contact.exact.errors`, so any layer may use it.
"""

from __future__ import annotations

import importlib
import sys
from types import ModuleType

from quadric_contact.exact.errors import MissingDependencyError

__all__ = ["pyplot", "require"]


def require(module: str, *, extra: str, purpose: str, package: str | None = None) -> ModuleType:
    """Import an optional dependency, or say which extra installs it.

    Parameters
    ----------
    module : str
        The module to import (``"matplotlib.colors"``, ``"dask.array"``).
    extra : str
        The extra of ``pyproject.toml`` that declares it (``"plot"``, ``"dask"``).
    purpose : str
        What needs it, as the subject of "need": ``"plots"``, ``"animations"``.
    package : str, optional
        The name to ``pip install`` when it differs from the top-level module
        (``"python-fcl"`` for ``fcl``); default the top-level module's name.

    Returns
    -------
    module

    Raises
    ------
    MissingDependencyError
        If the module cannot be imported; ``value`` is the package's name.

    Examples
    --------
    >>> require("fractions", extra="plot", purpose="nothing").__name__
    'fractions'
    >>> require("no_such_module_here", extra="plot", purpose="examples")
    Traceback (most recent call last):
        ...
    quadric_contact.exact.errors.MissingDependencyError: examples need no_such_module_here: pip install ...
    """
    try:
        return importlib.import_module(module)
    except ImportError as exc:
        name = package or module.split(".")[0]
        raise MissingDependencyError(
            f'{purpose} need {name}: pip install ".[{extra}]" from a checkout'
            f" (pip install 'quadric-contact[{extra}]' from an index, or pip install {name})",
            name,
            module=module,
            extra=extra,
        ) from exc


def pyplot(purpose: str = "plots") -> ModuleType:
    """``matplotlib.pyplot``, drawing off-screen when nobody has chosen a backend.

    A session that already uses pyplot (a notebook) keeps its own backend; otherwise
    (the command line, a script) the ``Agg`` backend is selected before pyplot is
    imported, so no window system is needed.

    Raises
    ------
    MissingDependencyError
        If matplotlib is not installed (extra ``plot``).
    """
    matplotlib = require("matplotlib", extra="plot", purpose=purpose)
    if "matplotlib.pyplot" not in sys.modules:
        matplotlib.use("Agg")
    return require("matplotlib.pyplot", extra="plot", purpose=purpose)
