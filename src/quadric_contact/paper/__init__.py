"""What the paper prints, as data, and the discrepancies found so far.

Brozos-Vázquez, Pereira-Sáez, Rodríguez-Raposo, Souto-Salorio,
Tarrío-Tobar, *Contact detection between a small ellipsoid and another
quadric*, Computer Aided Geometric Design 98 (2022) 102139.

Nothing here is used to compute an answer: the code derives everything
itself.  These are the printed formulas and numbers that tests and
``proofs/`` compare the derivations with, and
:data:`~quadric_contact.paper.errata.ERRATA`, the list of
places where the printed text differs from what is true.  Each erratum names
the test that demonstrates it; the test suite fails if a listed erratum
stops being reproducible or an unlisted difference appears.

The data are in three modules: :mod:`~quadric_contact.paper.results` (the results that
``proofs/`` proves, in order), :mod:`~quadric_contact.paper.printed` (the printed formulas,
tables and numbers) and :mod:`~quadric_contact.paper.errata` (the errata registry); the
printed Table 2 is evaluated in :mod:`~quadric_contact.paper.printed_tables`, and
:mod:`~quadric_contact.paper.proving` runs the proofs.
"""

from __future__ import annotations

from quadric_contact.paper.errata import ERRATA, Erratum
from quadric_contact.paper.printed import PRINTED
from quadric_contact.paper.results import FURTHER_RESULTS, NUMBERED_RESULTS

__all__ = ["ERRATA", "FURTHER_RESULTS", "NUMBERED_RESULTS", "PRINTED", "Erratum"]
