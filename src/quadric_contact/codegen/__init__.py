"""Derive the package's closed forms with sympy and emit them as straight-line code.

Nothing in :mod:`quadric_contact._generated.formulas` is typed in by hand: this
module derives every formula symbolically, checks it against an independent
sympy computation, and writes it out as plain Python that uses only ``+``,
``-``, ``*`` and integer literals.  Such code runs unchanged on every number
type the package uses (``int``, ``Fraction``, ``float``, numpy arrays, mpmath
numbers, flint ``arb`` balls), which is what "one formula, many number modes"
means in practice.

Derivations
-----------
``pencil_coefficients``
    The coefficients ``c0 .. c4`` of ``P(lambda) = det(lambda*E + Q)``
    (paper eq. (1)) for symmetric ``E`` and ``Q`` given by their ten upper
    entries.  Derived by the Laplace expansion of the 4x4 determinant along
    rows (0, 1) against rows (2, 3): each 2x2 minor of ``lambda*E + Q`` is a
    quadratic in lambda (an E-minor, a Q-minor and a mixed term), and the
    coefficients are sums of products of those.  Checked against sympy's
    determinant expanded in lambda.
``discrimination_sequence_n`` (n = 1 .. 4)
    The principal minors ``D_1 .. D_n`` of even order of the discrimination
    matrix of a degree-n polynomial and its derivative (Yang 1999, the
    subresultant-based "complete discrimination system").
``paper_deltas``
    The paper's normalisation (Section 3.2) of Yang's minors for the quartic:
    ``Delta_2 = D_2 / c4**2``, ``Delta_3 = D_3 / (2*c4**2)``,
    ``Delta_4 = D_4 / c4**2``; the divisions are exact polynomial divisions
    done by sympy, and the positive factors are what make the signs agree.

Companions for the number modes (``_generated/kernels.py``)
------------------------------------------------------------
``leading_minors_3``, ``quadric_invariants``
    The leading principal minors of a quadratic part (Sylvester's test that
    ``E`` is an ellipsoid) and the invariants that fix the affine type of
    ``Q`` (trace, ``J`` and determinant of the quadratic part; the sums of
    the principal minors of each order of the whole matrix), expanded by
    sympy and checked against its determinants.
``*_magnitude``
    For every straight-line function of either generated module, the same
    program with every ``-`` turned into ``+`` and every input read as its
    absolute value (an AST transformation of the emitted text, so the
    operations, their order and their association are those of the value
    program).  Its value bounds the sum of the absolute values of all the
    products the value program adds up: the quantity a rounding-error bound
    is proportional to.
``ROUNDING_COUNTS``
    For every output of every straight-line function, the largest number of
    rounded operations on any path from the inputs (an AST walk of the
    emitted text: a sum counts ``max + 1``, a product ``sum + 1``) and the
    degree.  :mod:`quadric_contact.modes.kernels.errorbounds` turns them into the
    error-bound constants.

Double-double programs (``_generated/dd_programs.py``)
-------------------------------------------------------
``quadric_invariants_dd``
    ``quadric_invariants`` evaluated in double-double arithmetic (the operations of
    :mod:`quadric_contact.modes.kernels.double_double`, passed as arguments): the same monomials,
    products by Dekker's exact product and DWTimesFP1, sums by AccurateDWPlusDW in balanced
    trees.  Checked by reading it exactly (it computes the invariants) and along its paths
    (its magnitude is the binary64 magnitude companion's); ``DD_COUNTS`` gives the rounding
    double-double operations on its paths, from which
    :data:`quadric_contact.modes.kernels.errorbounds.INVARIANTS_DD_ERRBOUND` is derived.

The reading of straight-line code (printer, magnitude companion, rounding counts)
is :mod:`quadric_contact.exact.straight_line` and the emitter of programs for polynomials
known at run time is :mod:`quadric_contact.families.family_emit`: run-time code uses them
without importing this module, which is development time only.

Modules
-------
Each generated file has the module of the same name here, which derives, checks and
writes it:

:mod:`~quadric_contact.codegen.formulas`
    ``_generated/formulas.py``: the pencil's coefficients, Yang's discrimination sequences,
    the paper's Deltas, and the symbolic building blocks the other files use too.
:mod:`~quadric_contact.codegen.kernels`
    ``_generated/kernels.py``: the leading minors, the invariants, the compact Deltas, the
    magnitude companions and ``ROUNDING_COUNTS``.
:mod:`~quadric_contact.codegen.blocks`
    ``_generated/blocks.py``: the unrolled block code of the binary64 kernels and the proofs
    of its row bounds.
:mod:`~quadric_contact.codegen.dd_programs`
    ``_generated/dd_programs.py``: the double-double programs and ``DD_COUNTS``.

:mod:`~quadric_contact.codegen.emission` prints sympy polynomials as straight-line Python
for all of them, :mod:`~quadric_contact.codegen.command` is the command that regenerates
(or checks) every file, and :mod:`~quadric_contact.codegen.native` builds the native kernels
at install (it is not imported here).

Regenerate with ``python -m quadric_contact.codegen`` (or
``quadric-contact codegen``); the test suite checks that regenerating
reproduces every committed file byte for byte.
"""

from __future__ import annotations

from quadric_contact.codegen.blocks import (
    BLOCKS_PATH,
    FLAT_LOWER,
    FLAT_UPPER,
    ROW_SYMBOLS,
    derive_row_bound,
    emit_blocks,
    regenerate_blocks,
    verify_member_minor_row_bounds,
    verify_minor_row_bounds,
    verify_plane_zeros,
    verify_row_bound,
)
from quadric_contact.codegen.command import main
from quadric_contact.codegen.dd_programs import (
    COFACTOR_INDICES,
    COFACTOR_OUTPUTS,
    DD_OPERATIONS,
    DD_PATH,
    dd_rounding_counts,
    derive_adjugate_3,
    derive_cofactor_forms,
    emit_dd_programs,
    regenerate_dd,
    verify_cofactor_forms,
    verify_dd_programs,
)
from quadric_contact.codegen.emission import (
    emit_expression,
    emit_function,
    emit_polynomial,
    format_counts,
    power_temps,
)
from quadric_contact.codegen.formulas import (
    GENERATED_PATH,
    charpoly_by_determinant,
    coefficient_symbols,
    derive_discrimination_sequence,
    derive_paper_deltas,
    derive_pencil,
    derive_quartic_invariants,
    discrimination_matrix,
    emit_formulas,
    regenerate,
    substitute_program,
    symmetric_matrix,
    verify_pencil,
)
from quadric_contact.codegen.kernels import (
    FILTERED_FUNCTIONS,
    KERNELS_PATH,
    QUADRATIC_PART_INDICES,
    derive_compact_deltas,
    derive_leading_minors_3,
    derive_leading_minors_4,
    derive_quadric_invariants,
    emit_kernels,
    leading_minors_expanded,
    regenerate_kernels,
    verify_compact_deltas,
    verify_invariants,
    verify_leading_minors_4,
)

__all__ = [
    "BLOCKS_PATH",
    "COFACTOR_INDICES",
    "COFACTOR_OUTPUTS",
    "DD_OPERATIONS",
    "DD_PATH",
    "FILTERED_FUNCTIONS",
    "FLAT_LOWER",
    "FLAT_UPPER",
    "GENERATED_PATH",
    "KERNELS_PATH",
    "QUADRATIC_PART_INDICES",
    "ROW_SYMBOLS",
    "charpoly_by_determinant",
    "coefficient_symbols",
    "dd_rounding_counts",
    "derive_adjugate_3",
    "derive_cofactor_forms",
    "derive_compact_deltas",
    "derive_discrimination_sequence",
    "derive_leading_minors_3",
    "derive_leading_minors_4",
    "derive_paper_deltas",
    "derive_pencil",
    "derive_quadric_invariants",
    "derive_quartic_invariants",
    "derive_row_bound",
    "discrimination_matrix",
    "emit_blocks",
    "emit_dd_programs",
    "emit_expression",
    "emit_formulas",
    "emit_function",
    "emit_kernels",
    "emit_polynomial",
    "format_counts",
    "leading_minors_expanded",
    "main",
    "power_temps",
    "regenerate",
    "regenerate_blocks",
    "regenerate_dd",
    "regenerate_kernels",
    "substitute_program",
    "symmetric_matrix",
    "verify_cofactor_forms",
    "verify_compact_deltas",
    "verify_dd_programs",
    "verify_invariants",
    "verify_leading_minors_4",
    "verify_member_minor_row_bounds",
    "verify_minor_row_bounds",
    "verify_pencil",
    "verify_plane_zeros",
    "verify_row_bound",
]
