"""What the paper prints, as data, and the discrepancies found so far.

Brozos-Vázquez, Pereira-Sáez, Rodríguez-Raposo, Souto-Salorio,
Tarrío-Tobar, *Contact detection between a small ellipsoid and another
quadric*, Computer Aided Geometric Design 98 (2022) 102139.

Nothing here is used to compute an answer: the code derives everything
itself.  These are the printed formulas and numbers that tests and
``proofs/`` compare the derivations with, and :data:`ERRATA`, the list of
places where the printed text differs from what is true.  Each erratum names
the test that demonstrates it; the test suite fails if a listed erratum
stops being reproducible or an unlisted difference appears.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["ERRATA", "PRINTED", "Erratum"]

PRINTED: dict[str, str] = {
    # Section 3.2, the two members of the discrimination system used by Corollary 10.
    "Delta3": (
        "16*c4**2*c0*c2 - 18*c4**2*c1**2 - 4*c4*c2**3 + 14*c4*c1*c3*c2"
        " - 6*c4*c0*c3**2 + c2**2*c3**2 - 3*c1*c3**3"
    ),
    "Delta4": (
        "256*c0**3*c4**3 - 192*c0**2*c1*c3*c4**2 - 128*c0**2*c2**2*c4**2 + 144*c0**2*c2*c3**2*c4"
        " - 27*c0**2*c4**4 + 144*c0*c1**2*c2*c4**2 - 6*c0*c1**2*c3**2*c4 - 4*c1**3*c3**3"
        " - 80*c0*c1*c2**2*c3*c4 + 18*c0*c1*c2*c3**3 + 16*c0*c2**4*c4 - 4*c0*c2**3*c3**2"
        " - 27*c1**4*c4**2 + 18*c1**3*c2*c3*c4 - 4*c1**2*c2**3*c4 + c1**2*c2**2*c3**2"
    ),
    # Example 11.
    "Example 11 E": "2*x**2 + 2*y**2 + 3*z**2 - 1",
    "Example 11 Q": "x**2 + y**2 + 8*z",
    "Example 11 P": "-(1 + 2*lambda)**2*(16 + 3*lambda**2)",
    "Example 11 Delta4": "0",
    "Example 11 Delta3": "-400",
    # Example 17 (the bee and the tree).
    "Example 17 E": "(x - 3)**2 + (y - 3)**2 + 3*(z - 5.5)**2 - 0.1",
    "Example 17 S1": "x**2 + y**2 + 3*(z - 8.36291)**2 - 20",
    "Example 17 S2": "x**2 + y**2 - 0.25*(z - 3)**2 - 1",
    "Example 17 plane": "z - 6",
    "Example 17 P0": "lambda**2*(-0.3*lambda**2 - 1.5*lambda - 0.25)",
    "Example 17 P0 Delta3": "0.121875",
    "Example 17 P2": "-0.3*lambda**4 + 45.7375*lambda**3 + 34.125*lambda**2 - 11.6625*lambda + 0.25",
    "Example 17 P2 Delta4": "6.90965e8",
    # Corollary 15 (1).
    "Corollary 15 (1)": "c3**2 < 4*c1*c2",
    # Remark 16.
    "Remark 16 c3": "(a*x_c + b*y_c + c*z_c - d)/(alpha**2*beta**2*gamma**2)",
    # Theorem 14, eq. (12).
    "eq. (12)": "-lambda**2*(r**2 + 4*lambda*(lambda - z_c))/(4*r**6)",
}


@dataclass(frozen=True)
class Erratum:
    """One place where the printed paper differs from what is true."""

    key: str
    location: str
    printed: str
    corrected: str
    evidence: str
    consequence: str


ERRATA: tuple[Erratum, ...] = (
    Erratum(
        key="delta4-term",
        location="Section 3.2, formula for Delta_4, fifth term",
        printed="-27*c0**2*c4**4",
        corrected="-27*c0**2*c3**4",
        evidence="Delta_4 derived as D_4/c4^2 from Yang's discrimination matrix (sympy) differs from the "
        "printed one in exactly this term; the printed term is not even isobaric (weight 16, "
        "all others 12). tests/test_discriminants.py::test_printed_delta4_term_by_term",
        consequence="any code that copies the printed Delta_4 misclassifies pencils",
    ),
    Erratum(
        key="example-11-delta3",
        location="Example 11",
        printed="Delta_3 = -400",
        corrected="Delta_3 = -13790208 (with the printed Delta_3 formula and P = -(1+2l)^2(16+3l^2))",
        evidence="no normalisation of P tried (monic, reversed, rescaled root) gives -400; the sign, "
        "which is all Corollary 10 uses, agrees. tests/test_paper_examples.py::test_example_11",
        consequence="none for the conclusion (transversal contact)",
    ),
    Erratum(
        key="corollary-15-c1",
        location="Corollary 15 (1) and its proof",
        printed="transversal contact iff c3^2 < 4 c1 c2 (proof: 0 < 4 c1 c2 - c3^2)",
        corrected="transversal contact iff c3^2 < 4 c4 c2",
        evidence="for a plane c1 = c0 = 0 (eq. (12)), so the printed condition never holds; "
        "Delta_3 with c0 = c1 = 0 is c2^2 (c3^2 - 4 c4 c2). tests/test_plane.py::test_corollary_15_misprint",
        consequence="the printed test would never detect contact with a plane",
    ),
)
