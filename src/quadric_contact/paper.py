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

__all__ = ["ERRATA", "NUMBERED_RESULTS", "PRINTED", "Erratum"]

NUMBERED_RESULTS: tuple[str, ...] = (
    "eq. (1)",
    "Theorem 2",
    "Lemma 3",
    "Lemma 4",
    "Theorem 5",
    "Example 6",
    "Lemma 7",
    "Lemma 8",
    "Remark 9",
    "Section 3.2",
    "Corollary 10",
    "Example 11",
    "Lemma 12",
    "Theorem 13",
    "Theorem 14",
    "Corollary 15",
    "Remark 16",
    "Example 17",
)
"""The paper's numbered results in the paper's order (Definition 1 is a
definition; the formulas of Section 3.2 are unnumbered but proved too).
Tables 1-4 and the numbered equations belong to the results that state them."""

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
    # Table 4, read row by row (the extraction shifts the quadric names; the rows are grouped as the
    # mathematics forces: see proofs/theorem_13_table_4.py).  One entry per row:
    # "group | region | root signs | coefficients".
    "Table 4 rows": (
        "ellipsoid, hyperboloid of two sheets, elliptic paraboloid | R- | ---- | c4, c0 < 0; No sign changes;"
        " c_i <= 0 for i = 1, 2, 3\n"
        "ellipsoid, hyperboloid of two sheets, elliptic paraboloid | R+ | --++ | c4, c0 < 0; 2 sign changes;"
        " c_i > 0 for some i = 1, 2, 3\n"
        "hyperboloid of one sheet, hyperbolic paraboloid | R- | ---+ | c4 < 0, c0 > 0; No sign changes;"
        " c_i > 0 => c_j >= 0 for all j > i\n"
        "hyperboloid of one sheet, hyperbolic paraboloid | R+ | -+++ | c4 < 0, c0 > 0; 3 sign changes;"
        " c_i <= 0, c_j > 0 for some i < j\n"
        "elliptic cylinder, parabolic cylinder | R- | ---0 | c4 < 0, c0 = 0; No sign changes;"
        " c_i <= 0 for all i = 1, 2, 3\n"
        "elliptic cylinder, parabolic cylinder | R+ | -0++ | c4 < 0, c0 = 0; 1 sign change;"
        " c_i > 0 for some i = 1, 2, 3\n"
        "hyperbolic cylinder | R- | --0+ | c4 < 0, c0 = 0; 1 sign change; c_i < 0 => c_j <= 0 for all j > i\n"
        "hyperbolic cylinder | R+ | 0+++ | c4 < 0, c0 = 0; No sign changes;"
        " (-1)^i c_i <= 0 for all i = 1, 2, 3\n"
        "parallel planes | R- | --00 | c_i < 0 for i = 2, 3, 4; c0 = c1 = 0\n"
        "parallel planes | R+ | 00++ | (-1)^i c_i <= 0 for i = 2, 3, 4; c0 = c1 = 0"
    ),
    # Corollary 15 (1).
    "Corollary 15 (1)": "c3**2 < 4*c1*c2",
    # Remark 16.
    "Remark 16 c3": "(a*x_c + b*y_c + c*z_c - d)/(alpha**2*beta**2*gamma**2)",
    # Lemma 3 (proof): the conic computations.
    "eq. (3) E": "(x - a + beta)**2/beta**2 + y**2/alpha**2 - 1",
    "eq. (3) C1": "x**2/a**2 + y**2/b**2 - 1",
    "Lemma 3 second x": "a*(a**2*alpha**2 - 2*a*alpha**2*beta + b**2*beta**2)/(a**2*alpha**2 - b**2*beta**2)",
    "eq. (4)": (
        "-4*a*alpha**2*b**2*beta*(a - beta)*(b**2*beta - a*alpha**2)"
        "/((b*beta - a*alpha)**2*(a*alpha + b*beta)**2)"
    ),
    "Lemma 3 sign step": (
        "if y^2 < 0, since beta < a, all factors in (4) have to be positive, so we conclude that "
        "b^2 beta - a alpha^2 < 0"
    ),
    "Lemma 3 relation": "b**2*beta - a*alpha**2 >= 0",
    "Lemma 3 ellipse curvature": "a*b/sqrt(a**2*sin(t)**2 + b**2*cos(t)**2)",
    "Lemma 3 ellipse-ellipse": "a/b**2 <= beta/alpha**2",
    "eq. (5) E": "(x - a - beta)**2/beta**2 + y**2/alpha**2 - 1",
    "eq. (5) C2": "x**2/a**2 - y**2/b**2 - 1",
    "Lemma 3 ellipse-hyperbola": "a/b**2 <= beta/alpha**2",
    "Lemma 3 parabola E": "x**2/alpha**2 + (y - beta)**2/beta**2 - 1",
    "Lemma 3 parabola C3": "x**2/a**2 - y",
    "Lemma 3 ellipse-parabola": "2/a**2 <= beta/alpha**2",
    # Table 1 (Lemma 4): "type | standard equation | order of the parameters | conditions".
    "Table 1": (
        "ellipsoid | x**2/a**2 + y**2/b**2 + z**2/c**2 - 1 | a >= b >= c | c >= alpha; a/c**2 <= gamma/alpha**2\n"
        "hyperboloid of one sheet | x**2/a**2 + y**2/b**2 - z**2/c**2 - 1 | a >= b | b >= alpha;"
        " a/c**2 <= gamma/alpha**2\n"
        "hyperboloid of two sheets | x**2/a**2 + y**2/b**2 - z**2/c**2 + 1 | a >= b | c >= alpha;"
        " c/b**2 <= gamma/alpha**2\n"
        "elliptic paraboloid | x**2/a**2 + y**2/b**2 - z | a >= b | 2/b**2 <= gamma/alpha**2\n"
        "hyperbolic paraboloid | x**2/a**2 - y**2/b**2 - z | a >= b | 2/b**2 <= gamma/alpha**2\n"
        "elliptic cylinder | x**2/a**2 + y**2/b**2 - 1 | a >= b | b >= alpha; a/b**2 <= gamma/alpha**2\n"
        "hyperbolic cylinder | x**2/a**2 - y**2/b**2 - 1 |  | a >= alpha; a/b**2 <= gamma/alpha**2\n"
        "parabolic cylinder | x**2/a**2 - z |  | 2/a**2 <= gamma/alpha**2\n"
        "parallel planes | x**2/a**2 - 1 |  | a >= alpha"
    ),
    # Lemma 12: the two-sheet hyperboloid H = diag(1/a^2, 1/b^2, -1/c^2, 1) and the unit sphere (10)
    # centred at (x_c, y_c, z_c).
    "eq. (11)": (
        "-lambda**4 + ((x_c**2 - 1)/a**2 + (y_c**2 - 1)/b**2 + (1 - z_c**2)/c**2 + 1)*lambda**3"
        " + ((c**2*(a**2 + b**2 - 1) + a**2 + b**2 - a**2*b**2 - (a**2 + b**2)*z_c**2 + (c**2 - a**2)*y_c**2"
        " + (c**2 - b**2)*x_c**2)/(a**2*b**2*c**2))*lambda**2"
        " - (a**2 + b**2 - c**2 + x_c**2 + y_c**2 + z_c**2 - 1)/(a**2*b**2*c**2)*lambda - 1/(a**2*b**2*c**2)"
    ),
    "Lemma 12 at (0, 0, 0)": "-(lambda - 1)*(a**2*lambda + 1)*(b**2*lambda + 1)*(c**2*lambda - 1)",
    "Lemma 12 at (0, 0, c + 1)": "-(a**2*lambda + 1)*(b**2*lambda + 1)*(c*lambda + 1)**2",
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
    Erratum(
        key="table-4-one-sheet-r-minus",
        location="Table 4, row 'hyperboloid of one sheet / hyperbolic paraboloid, X^T Q X <= 0' "
        "(root signs ---+)",
        printed="c4 < 0, c0 > 0; No sign changes; c_i > 0 => c_j >= 0 for all j > i",
        corrected="c4 < 0, c0 > 0; 1 sign change; c_i < 0 => c_j <= 0 for all j > i "
        "(equivalently c_i > 0 => c_j >= 0 for all j < i)",
        evidence="with c4 < 0 < c0 there is at least one sign change, and the printed rule applied to i = 0 "
        "forces c4 >= 0, so it never holds; exhaustive case analysis over the 49 realisable sign vectors of "
        "real-rooted quartics: every vector of root pattern ---+ has exactly 1 sign change and the corrected "
        "rule holds exactly for them among the patterns ---+ and -+++ "
        "(proofs/theorem_13_table_4.py::row_03). The extraction garbles Table 4, so this may be a layout "
        "artefact; the cell as it reads is wrong",
        consequence="a classifier coded from the printed row never reports R- for one-sheet hyperboloids "
        "and hyperbolic paraboloids",
    ),
    Erratum(
        key="table-4-sign-change-counts",
        location="Table 4, rows 'elliptic / parabolic cylinder, X^T Q X >= 0' (-0++) and "
        "'hyperbolic cylinder, X^T Q X >= 0' (0+++)",
        printed="-0++: '1 sign change'; 0+++: 'No sign changes'",
        corrected="-0++: 2 sign changes; 0+++: 3 sign changes (Descartes: one per positive root)",
        evidence="exhaustive case analysis over the realisable sign vectors of real-rooted quartics: every "
        "vector of pattern -0++ has 2 sign changes and every vector of pattern 0+++ has 3; the rules printed "
        "beside them (c_i > 0 for some i; (-1)^i c_i <= 0) are right "
        "(proofs/theorem_13_table_4.py::row_06, row_08)",
        consequence="none if the rules are used; the counts as printed contradict the root signs in "
        "the same row",
    ),
    Erratum(
        key="lemma-3-sign-step",
        location="Lemma 3, proof, ellipse-ellipse case, after eq. (4)",
        printed="if y^2 < 0, since beta < a, all factors in (4) have to be positive, so we conclude that "
        "b^2 beta - a alpha^2 < 0",
        corrected="y^2 < 0 iff b^2 beta - a alpha^2 > 0: (4) is -K (b^2 beta - a alpha^2) with K > 0",
        evidence="symbolic identity (4) = -K (b^2 beta - a alpha^2), K = 4 a alpha^2 b^2 beta (a - beta) / "
        "((b beta - a alpha)^2 (a alpha + b beta)^2); a = 3, b = 2, alpha = beta = 1 gives y^2 < 0 with "
        "b^2 beta - a alpha^2 = 1 > 0 (proofs/lemma_03_curvature.py::sign_step)",
        consequence="none: the lemma's conclusion b^2 beta - a alpha^2 >= 0 is right",
    ),
    Erratum(
        key="lemma-3-curvature-exponent",
        location="Lemma 3, proof, curvature of the ellipse (a cos t, b sin t)",
        printed="kappa_1(t) = a b / sqrt(a^2 sin^2 t + b^2 cos^2 t)",
        corrected="kappa_1(t) = a b / (a^2 sin^2 t + b^2 cos^2 t)^(3/2)",
        evidence="the curvature |x'y'' - y'x''| / (x'^2 + y'^2)^(3/2) of (a cos t, b sin t), by sympy; "
        "the printed formula gives kappa_1(0) = a, not the maximum a/b^2 the proof uses next "
        "(proofs/lemma_03_curvature.py::ellipse_curvature_formula). Possibly an exponent lost in typesetting",
        consequence="none: the extreme values a/b^2 and beta/alpha^2 the proof uses are right",
    ),
    Erratum(
        key="table-1-one-sheet-curvature",
        location="Table 1 (and Table 2), hyperboloid of one sheet x^2/a^2 + y^2/b^2 - z^2/c^2 = 1, a >= b",
        printed="b >= alpha; a/c^2 <= gamma/alpha^2",
        corrected="b >= alpha; a/c^2 <= gamma/alpha^2 and a/b^2 <= gamma/alpha^2 (kappa_max = max(a/b^2, a/c^2); "
        "in Table 2 also a'/(d' b'^2) <= gamma'/(delta' alpha'^2))",
        evidence="the principal curvatures at (a, 0, 0) are a/b^2 (along the waist ellipse) and a/c^2, and "
        "|A p| >= 1/a everywhere, so kappa_max = max(a/b^2, a/c^2) (proofs/lemma_04_table_1.py::"
        "curvature_one_sheet); counterexample: Q = x^2/100 + y^2/4 - z^2/10000 - 1 and the sphere of radius 1/2 "
        "centred at (949/100, 0, 0) satisfy the printed conditions, yet P has four distinct real roots and the "
        "sphere has rational points on both sides of Q (two intersection curves), contradicting Theorem 2 "
        "(proofs/lemma_04_table_1.py::one_sheet_counterexample)",
        consequence="a smallness test coded from Table 1/2 accepts pairs for which Corollary 10 misses a "
        "transversal contact",
    ),
)
