"""The package's exception hierarchy.

Every error raised at the public boundary is a :class:`QuadricContactError`
and also a :class:`ValueError` or :class:`TypeError`, so callers can catch
either the package's own classes or the built-in ones.  Each error names the
violated condition in its message and carries the offending object in
``.value`` (and, where it helps, more context in ``.details``).
"""

from __future__ import annotations

from typing import Any


class QuadricContactError(Exception):
    """Base class of every error the package raises on purpose."""

    def __init__(self, message: str, value: Any = None, **details: Any) -> None:
        super().__init__(message)
        self.value = value
        self.details = details


# -- bad numbers and bad shapes -------------------------------------------------


class NotANumberError(QuadricContactError, TypeError):
    """An entry is not a real number (a string the number parser refuses, a
    complex, a bool, an arbitrary object).  For a string, as for
    :class:`EquationError`, the message quotes the offending part under a
    caret and ``.details`` holds its ``position``."""


class NonFiniteError(QuadricContactError, ValueError):
    """An entry is NaN or an infinity."""


class NotRationalError(QuadricContactError, ValueError):
    """An entry is a real number that is not rational (``sqrt(2)``, ``pi``)."""


class ShapeError(QuadricContactError, ValueError):
    """A matrix does not have the required shape (4x4, or a stack (..., 4, 4))."""


SYMMETRIZE_HINT = (
    "to use the symmetric part (M + M^T)/2, which has the same quadratic form, say so: "
    "Quadric.from_matrix(M, symmetrize=True) for one matrix, quadric_contact.symmetrize(M) "
    "for a stack (numpy's R @ D @ R.T is often asymmetric in the last bit)"
)
"""How to symmetrise, appended to every :class:`NotSymmetricError` about an input matrix."""


class NotSymmetricError(QuadricContactError, ValueError):
    """A matrix that must be symmetric is not; ``.details['entry']`` is the
    first ``(i, j)`` with ``M[i, j] != M[j, i]``.  The message says how to
    symmetrise explicitly (:data:`SYMMETRIZE_HINT`); nothing is symmetrised
    unless asked."""


class EquationError(QuadricContactError, ValueError):
    """An equation or expression cannot be read: the package's parser
    (:mod:`quadric_contact.exact.reading`) refuses the text, or it is not a
    polynomial of the degree required (<= 2 in x, y, z for a quadric).

    For text, the message names the offending part and its position and
    quotes it under a caret; ``.value`` is the text and ``.details`` has
    ``position`` (1-based, as printed), ``offset`` and ``end`` (0-based, a
    slice of the text)."""


# -- wrong kinds of quadric -----------------------------------------------------


class NotAnEllipsoidError(QuadricContactError, ValueError):
    """An argument that must be a real (non-empty, non-degenerate) ellipsoid is
    not; ``.details['kind']`` is what it is."""


class NotAPlaneError(QuadricContactError, ValueError):
    """An argument that must be a plane is not."""


class ExcludedQuadricError(QuadricContactError, ValueError):
    """The quadric type is excluded by the theory for this question (cones,
    intersecting planes, coincident planes, imaginary quadrics, or a plane
    where Theorem 14 rather than Theorem 2 applies)."""


class DegeneratePencilError(QuadricContactError, ValueError):
    """The pencil lambda*E + Q is degenerate (its characteristic polynomial
    vanishes identically), so no root-based statement is possible."""


# -- undecided answers ----------------------------------------------------------


class UndecidedError(QuadricContactError, ValueError):
    """A result was used as a definite answer (for instance with ``bool()``)
    although the theory it relies on did not decide it."""


class SceneError(QuadricContactError, ValueError):
    """A scene file is malformed; the message names the file, the key and what
    was expected."""


class MissingDependencyError(QuadricContactError, ImportError):
    """An optional dependency needed for the requested feature is not installed
    (for instance matplotlib for plots: ``pip install ".[plot]"`` from a checkout)."""


class ProofsNotFoundError(QuadricContactError, FileNotFoundError):
    """The ``proofs/`` directory of a checkout could not be found (``quadric-contact
    prove`` runs from a checkout, or with ``--proofs DIR``)."""


class WorkLimitError(QuadricContactError, ValueError):
    """An input is within the bounds of what is read, but the work it asks for
    exceeds a bound of the package's budget (:mod:`quadric_contact.exact.bounds`):
    the terms of a family's discriminant, the size of a pair for the exact
    engine.  Raised before that work starts; the message names the input and the
    bound, ``.details['limit']`` is the bound and ``.details['needed']`` what the
    input would need (an upper estimate where the work was not done)."""


class ChoiceError(QuadricContactError, ValueError):
    """A name chosen from a fixed set is not one of them (a ``mode=``, a
    ``backend=``, a quantity of a family); the message lists the valid ones,
    ``.details['choices']`` holds them."""


class SchedulerError(QuadricContactError, ConnectionError):
    """A dask scheduler address is malformed (not ``tcp://host:port`` or a kind
    dask speaks), or the scheduler cannot be reached within the connection
    timeout (:data:`~quadric_contact.exact.bounds.SCHEDULER_TIMEOUT`)."""
