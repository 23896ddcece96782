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

__all__ = ["ERRATA", "FURTHER_RESULTS", "NUMBERED_RESULTS", "PRINTED", "Erratum"]

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

FURTHER_RESULTS: tuple[str, ...] = (
    "Wang-Wang-Kim 2001",
    "Tu-Wang-Mourrain-Wang 2009",
    "Pieces as cut",
    "First-contact scale",
    "Mutual contact events",
    "Distance along a path",
    "Depth of crossing ellipsoids",
    "Distance of separated ellipsoids",
)
"""Results from outside the paper that the package relies on and proves in ``proofs/``
alongside the paper's (after them, in this order): the separation condition of two
ellipsoids of Wang, Wang and Kim (CAGD 18, 2001), on which
:func:`quadric_contact.overlap` decides two ellipsoids; the decision of contact,
region and overlap of an ellipsoid and any quadric from the signature sequence of the pencil
(after Tu, Wang, Mourrain and Wang, CAGD 26, 2009), which needs no smallness: beyond the
paper; the package's own reduction of contact with a piece as cut by a plane to the plane
section's pencil (:mod:`quadric_contact.theory.sections`), on which the geometric reading of
scenes rests; the choice of the root that :func:`quadric_contact.contact_scale` returns; the
reduction of the contacts of two moving ellipsoids with each other to the real roots of a
discriminant in time (:mod:`quadric_contact.scenes.mutual`); the bound on the displacement of
a rigidly moving ellipsoid's points by which the least distance along a path is enclosed
(:mod:`quadric_contact.scenes.path_distance`); the certificate by which the depth of two
crossing ellipsoids is enclosed on stacks (:mod:`quadric_contact.modes.distance.depth_kernel`); and the
isolated root by which the distance of two separated ellipsoids and its witnesses are enclosed
in the ``certified`` mode (:mod:`quadric_contact.modes.distance.certified`)."""

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
    # Example 17, the smallness checks (Table 2), in the order printed:
    # d1 c1, delta alpha, a1/(d1 c1^2), gamma/(delta alpha^2) for S1, then the same for S2.
    "Example 17 smallness S1": "2.58199 0.316228 0.67082 1.82574",
    "Example 17 smallness S2": "1 0.316228 0.25 1.82574",
    # Example 6 (the decimal matrices as printed, rows separated by ';').
    "Example 6 Q": (
        "-0.426777 -0.800103 0.176777 -6.57593; -0.800103 0.5 0.331414 -1.16043;"
        " 0.176777 0.331414 -0.0732233 1.64145; -6.57593 -1.16043 1.64145 -42.4962"
    ),
    "Example 6 E": (
        "1.82853 0.58657 0.000852152 13.6556; 0.58657 1.09505 -0.242965 8.48796;"
        " 0.000852152 -0.242965 1.83023 3.48535; 13.6556 8.48796 3.48535 131.077"
    ),
    "Example 6 EV": "1.7484959871992433e-7 0.9999999062901268 -1.0000003811397258",
    "Example 6 det Q": "1.0000019781303608",
    "Example 6 paraboloid b": "0.9999998094301916",
    "Example 6 paraboloid L": "2.00000169069926",
    "Example 6 paraboloid curvature": "0.9999995357904882",
    "Example 6 hyperboloid 1/a^2": "1.7484959871992433e-7",
    "Example 6 hyperboloid -1/c^2": "-1.0000003811397258",
    "Example 6 hyperboloid d": "2391.4871252673324",
    "Example 6 hyperboloid curvature": "0.9999995357904464",
    "Example 6 alpha": "1.1716212752992812",
    "Example 6 beta": "0.7391034270329864",
    "Example 6 gamma": "0.6750083318272421",
    "Example 6 delta": "1.181065224418655",
    "Example 6 E curvature": "0.41635209331503953",
    # Table 3: Segre types listed for each kind of contact (text of the proof of Theorem 2 agrees,
    # except that the text gives only [(111)1]_2 for a curve of tangency).
    "Table 3 none": "[1111]_4 [(111)1]_2 [(11)11]_3 [(11)(11)]_2",
    "Table 3 tangent_point": "[211]_3 [2(11)]_2 [(21)1]_3 [(211)]_1",
    "Table 3 two_tangent_points": "[(11)11]_3 [2(11)]_2",
    "Table 3 transversal": "[1111]_2 [(11)11]_1",
    "Table 3 tangent_curve": "[(111)1]_2 [(11)11]_3",
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
        "ellipsoid | x**2/a**2 + y**2/b**2 + z**2/c**2 - 1 | a >= b >= c | c >= alpha; a/c**2 <= "
        "gamma/alpha**2\n"
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
    # Table 2 (Theorem 5): "type | invariant formula | reduced equation | conditions", primed names
    # written a_, b_, ...; detQ, J, K, Jp are det(Q), J, K, J' of Section 2.4.
    "Table 2 E": "al_**-2, be_**-2, ga_**-2 | de_**2 = -al_**2*be_**2*ga_**2*detE"
    " | x**2/al_**2 + y**2/be_**2 + z**2/ga_**2 - de_**2",
    "Table 2": (
        "ellipsoid | d_**2 = -a_**2*b_**2*c_**2*detQ | x**2/a_**2 + y**2/b_**2 + z**2/c_**2 - d_**2"
        " | d_*c_ >= de_*al_; a_/(d_*c_**2) <= ga_/(de_*al_**2)\n"
        "hyperboloid of one sheet | d_**2 = a_**2*b_**2*c_**2*detQ"
        " | x**2/a_**2 + y**2/b_**2 - z**2/c_**2 - d_**2"
        " | b_*d_ >= de_*al_; a_/(d_*c_**2) <= ga_/(de_*al_**2)\n"
        "hyperboloid of two sheets | d_**2 = -a_**2*b_**2*c_**2*detQ"
        " | x**2/a_**2 + y**2/b_**2 - z**2/c_**2 + d_**2"
        " | c_*d_ >= de_*al_; c_/(d_*b_**2) <= ga_/(de_*al_**2)\n"
        "elliptic paraboloid | L**2 = -4*detQ/J | x**2/a_**2 + y**2/b_**2 - L*z"
        " | 2/(L*b_**2) <= ga_/(de_*al_**2)\n"
        "hyperbolic paraboloid | L**2 = -4*detQ/J | x**2/a_**2 - y**2/b_**2 - L*z"
        " | 2/(L*b_**2) <= ga_/(de_*al_**2)\n"
        "elliptic cylinder | M**2 = -K/J | x**2/a_**2 + y**2/b_**2 - M**2"
        " | M*b_ >= de_*al_; a_/(M*b_**2) <= ga_/(de_*al_**2)\n"
        "hyperbolic cylinder | M**2 = -K/J | x**2/a_**2 - y**2/b_**2 - M**2"
        " | M*b_ >= de_*al_; a_/(M*b_**2) <= ga_/(de_*al_**2)\n"
        "parabolic cylinder | d_**2 = 4*K*a_**2 | x**2/a_**2 - d_*z | 2/(d_*a_**2) <= ga_/(de_*al_**2)\n"
        "parallel planes | d_**2 = -a_**2*Jp | x**2/a_**2 - d_**2 | a_*d_ >= al_*de_"
    ),
    # Table 3 (Theorem 2): "type of contact | Segre types | roots | Delta conditions" (the proof of
    # Theorem 2 lists the same Segre types, except that it gives only [(111)1]_2 for the curve of tangency).
    "Table 3": (
        "no contact | [1111]_4, [(111)1]_2, [(11)11]_3, [(11)(11)]_2 | R | D4 > 0 or D4 = 0 and D3 >= 0\n"
        "1 isolated tangent point | [211]_3, [2(11)]_2, [(21)1]_3, [(211)]_1 | R | D4 = 0 and D3 >= 0\n"
        "2 isolated tangent points | [(11)11]_3, [2(11)]_2 | R | D4 = 0 and D3 >= 0\n"
        "curve with no tangent points | [1111]_2, [(11)11]_1 | C | D4 < 0 or D4 = 0 and D3 < 0\n"
        "curve of tangency | [(111)1]_2, [(11)11]_3 | R | D4 = 0 and D3 >= 0"
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
    """One place where the printed paper differs from what is true.

    ``printed`` is what the text of the paper used here reads (an extraction
    from the PDF, which garbles some matrices and the layout of Tables 3 and 4).
    ``confidence`` says, where the extraction may be at fault, how sure we are
    that the printed paper itself, and not only its extraction, is wrong, and
    why; the mathematics of ``corrected`` is certain either way.
    """

    key: str
    location: str
    printed: str
    corrected: str
    evidence: str
    consequence: str
    confidence: str = ""


ERRATA: tuple[Erratum, ...] = (
    Erratum(
        key="section-2-4-semi-invariants",
        location="Section 2.4, the list of invariants (K and J')",
        printed="K and J' are listed as invariants of the quadric, without a condition",
        corrected="K is invariant under rigid motions only where det Q = det Q00 = 0, and J' only where "
        "moreover J = K = 0 (the cases where Table 2 uses them: cylinders, parallel planes)",
        evidence="case analysis on the rank of Q00 after a rotation (which keeps K and J', coefficients "
        "of det(Q - l diag(1, 1, 1, 0))): under a symbolic translation K moves unless det Q = det Q00 = 0, "
        "J' unless moreover J = K = 0 (proofs/theorem_05_table_2.py::k_and_j_prime_invariance); "
        "translating x^2 + y^2 - z changes K, translating x^2 - y changes J' "
        "(tests/test_invariants.py::test_k_and_j_prime_are_not_invariant_in_general)",
        consequence="none for Table 2, which reads K and J' only where they are invariant; code that "
        "used K or J' of other quadrics as invariants would depend on the placement",
        confidence="high: the statement is the paper's own text, not a layout artefact",
    ),
    Erratum(
        key="delta4-term",
        location="Section 3.2, formula for Delta_4, fifth term",
        printed="-27*c0**2*c4**4",
        corrected="-27*c0**2*c3**4",
        evidence="Delta_4 derived as D_4/c4^2 from Yang's discrimination matrix (sympy) differs from the "
        "printed one in exactly this term; the printed term is not even isobaric (weight 16, "
        "all others 12). tests/test_discriminants.py::test_printed_delta4_term_by_term",
        consequence="any code that copies the printed Delta_4 misclassifies pencils",
        confidence="moderate that the printed paper is wrong: the extracted term certainly is, but it "
        "differs from the true one in a single subscript (c4 for c3), which an extraction can misread",
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
        confidence="high that the printed paper is wrong: the same '4 c1 c2' is extracted twice, in the "
        "statement and in its proof, so a misreading would have had to repeat",
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
        "(proofs/theorem_13_table_4.py::row_03)",
        consequence="a classifier coded from the printed row never reports R- for one-sheet hyperboloids "
        "and hyperbolic paraboloids",
        confidence="low that the printed paper is wrong: the cell as extracted certainly cannot hold, but "
        "the extraction garbles the layout of Table 4 (the quadric names are shifted against the rows "
        "and each row's rule runs on into the next line), so the count and the rule read here may be a "
        "layout artefact of the extraction rather than what the paper prints",
    ),
    Erratum(
        key="table-4-sign-change-counts",
        location="Table 4, rows 'elliptic / parabolic cylinder, X^T Q X >= 0' (-0++) and "
        "'hyperbolic cylinder, X^T Q X >= 0' (0+++)",
        printed="-0++: '1 sign change'; 0+++: 'No sign changes'",
        corrected="-0++: 2 sign changes; 0+++: 3 sign changes (Descartes: one per positive root)",
        evidence="exhaustive case analysis over the realisable sign vectors of real-rooted quartics: every "
        "vector of pattern -0++ has 2 sign changes and every vector of pattern 0+++ has 3; the rules printed "
        "beside them (c_i > 0 for some i; (-1)^i c_i <= 0) are right; the printed counts 1 and 0 are the "
        "sign changes of (-1)^i c_i, i.e. of P(-l) (the numbers of negative roots), on every vector of "
        "these patterns (proofs/theorem_13_table_4.py::row_06, row_08)",
        consequence="none if the rules are used; the counts as printed contradict the root signs in "
        "the same row",
        confidence="low that the printed paper is wrong: the counts as extracted are certainly not the sign "
        "changes of (c0, .., c4), but the extraction shifts the cells of Table 4 between rows, and both "
        "printed counts equal the sign changes of P(-l), which the rule printed beside 0+++ uses, so they "
        "may be a layout artefact or counts of P(-l) written in these two rows (the other rows, except the "
        "one-sheet R- row, count the changes of P(l))",
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
        "(proofs/lemma_03_curvature.py::ellipse_curvature_formula)",
        consequence="none: the extreme values a/b^2 and beta/alpha^2 the proof uses are right",
        confidence="low that the printed paper is wrong: the extraction reads "
        "\\frac{ab}{\\sqrt{a^2 \\sin^2 t + b^2 \\cos^2 t}}, where an exponent 3 on the root is easily "
        "lost, and the next sentence of the proof uses the maximum a/b^2 of the correct formula; the "
        "exponent is probably printed and lost in the extraction or typesetting",
    ),
    Erratum(
        key="table-1-h1-curvature",
        location="Table 1 and Table 2, hyperboloid of one sheet (curvature condition)",
        printed="b >= alpha and a/c^2 <= gamma/alpha^2 (Table 2: a'/(d'c'^2) <= gamma'/(delta' alpha'^2))",
        corrected="b >= alpha and max(a/b^2, a/c^2) <= gamma/alpha^2: the largest principal curvature of "
        "x^2/a^2 + y^2/b^2 - z^2/c^2 = 1 (a >= b) is a/b^2 (throat ellipse, felt from inside) or a/c^2 "
        "(hyperbola, felt from outside), as Lemma 3 itself requires",
        evidence="Q = x^2 + y^2 - z^2/100 - 1, E with semi-axes 1/10, 1, 1 centred at (17/20, 0, 0) (short "
        "axis along x): the printed conditions hold (1 >= 1, 1/100 <= 1/10), but E meets Q in two "
        "curves and P has four real roots (Delta_4 > 0), so Corollary 10 answers 'no contact'. "
        "tests/test_smallness.py::test_h1_counterexample",
        consequence="Corollary 10 and Table 4 fail for pairs the printed table calls small; Example 17 is "
        "unaffected (a/b^2 = 1 <= 1.82574)",
    ),
    Erratum(
        key="table-1-ellipsoid-enclosing",
        location="Section 2.1, Lemma 4 and Table 1, ellipsoid; Theorem 13",
        printed="E small w.r.t. an ellipsoid Q iff c >= alpha and a/c^2 <= gamma/alpha^2 ('it is immediate "
        "that the largest axis of E must be smaller than or equal to the smallest axis of Q')",
        corrected="for two ellipsoids Definition 1 is symmetric: E is also small when Q is small w.r.t. E "
        "(gamma >= a and alpha/gamma^2 <= c/a^2). In that enclosing case Theorem 2 and Corollary 10 "
        "hold, but Theorem 13 / Table 4 do not, so Theorem 13 needs the printed (non-enclosing) condition",
        evidence="two spheres meet in a circle, a point or nothing, never in two curves, so a sphere of "
        "radius 2 is small w.r.t. a sphere of radius 1 although c = 1 < 2 = alpha; with the two concentric, "
        "P = -(l+1)^3 (4l+1) has root signs ---- (R- in Table 4) while E lies in R+. "
        "tests/test_smallness.py::test_enclosing_spheres_are_small_but_table_4_fails",
        consequence="the printed conditions are sufficient but not necessary for ellipsoids; the package "
        "reports both and uses Table 4 only in the non-enclosing case (SmallnessReport.table_4_applies)",
    ),
    Erratum(
        key="table-2-hyperbolic-cylinder-size",
        location="Table 2, hyperbolic cylinder (size condition and eigenvalue ordering)",
        printed="EV 1/a'^2, -1/b'^2, 0 with a' >= b'; x^2/a'^2 - y^2/b'^2 = M^2; M b' >= delta' alpha'",
        corrected="M a' >= delta' alpha' (the transverse semi-axis is M a', Table 1: a >= alpha); M^2 = -K/J "
        "fixes the sign of Q, and then no ordering a' >= b' can be imposed",
        evidence="x^2 - y^2/100 = 1 and a sphere of radius 3/2: the printed row holds (M b' = 10 >= 3/2) but "
        "the sphere centred between the branches crosses both (two curves). "
        "tests/test_smallness.py::test_hyperbolic_cylinder_printed_size_condition; symbolic reduction "
        "tests/test_table_2_symbolic.py::test_table_2_reduces_to_table_1",
        consequence="the printed Table 2 calls pairs small that are not",
    ),
    Erratum(
        key="table-2-parabolic-cylinder-d",
        location="Table 2, parabolic cylinder",
        printed="d'^2 = 4 K a'^2",
        corrected="d'^2 = -4 K a'^2 (for x^2/a'^2 - d' z = 0, K = -d'^2/(4 a'^2))",
        evidence="the printed value is negative for every parabolic cylinder. "
        "tests/test_smallness.py::test_parabolic_cylinder_printed_d_is_imaginary; "
        "tests/test_table_2_symbolic.py::test_table_2_reduces_to_table_1",
        consequence="the printed row cannot be evaluated (d' would be imaginary)",
        confidence="moderate that the printed paper is wrong: the extracted formula certainly is, but it "
        "differs from the true one by a minus sign, which an extraction can drop",
    ),
    Erratum(
        key="table-3-2-11-two-points",
        location="Table 3, row '2 isolated tangent points'; proof of Theorem 2, item (2b)",
        printed="2 isolated tangent points: [(11)11]_3, [2(11)]_2",
        corrected="[2(11)]_2 never gives exactly two isolated tangent points (it gives one, as in row '1 "
        "isolated tangent point'); the row is [(11)11]_3 and [(11)(11)]_2 (see table-3-two-double-roots)",
        evidence="the eigenvector p of the size-2 Jordan block is E-isotropic (A = -E^-1 Q is "
        "E-self-adjoint), so p is a real tangent point on E and Q. If the rank-2 member is a pair of "
        "conjugate planes, E and Q meet only on its real line, which misses p (kernels of distinct "
        "eigenvalues): impossible. So it is a pair of real planes and E, Q meet in (E cap Pi1) cup (E cap "
        "Pi2); with only isolated points both planes are tangent to E, their common line misses E, and a "
        "second point would lie in no kernel, so it would not be a tangent point. Construction: a sphere "
        "touching a spheroid's vertex from outside (small) is [2(11)]_2 with one tangent point "
        "(proofs/theorem_02_table_3.py::two_points_2_11)",
        consequence="none for Theorem 2 (real roots either way)",
        confidence="high that the printed paper is wrong: the text of the proof of Theorem 2, item (2b), "
        "lists [2(11)]_2 under two isolated tangent points too, so the table cell is not an artefact",
    ),
    Erratum(
        key="example-17-s2-label",
        location="Example 17, smallness of E with respect to S2",
        printed="E - S2: d2 c2 = 1 >= 0.316228 = delta alpha",
        corrected="b2 d2 = 1 >= 0.316228 = delta alpha (Table 2, one sheet: b'd' >= delta' alpha'); d2 c2 = "
        "2",
        evidence="for S2: x^2 + y^2 - (z - 3)^2/4 = 1, a2 = b2 = 1, c2 = 2, d2 = 1 (as the example itself "
        "states), so d2 c2 = 2 and the printed value 1 is b2 d2 "
        "(proofs/example_17_bee_and_tree.py::smallness_s2)",
        consequence="none: the condition holds either way",
    ),
    Erratum(
        key="table-3-two-double-roots",
        location="Table 3 and proof of Theorem 2, item (1): Segre type [(11)(11)]_2 under 'no contact'",
        printed="[(11)(11)]_2: no contact",
        corrected="[(11)(11)]_2: two isolated tangent points, always. With two real double roots of rank 2, "
        "E = S1 - S2 for the two singular members (pairs of planes); E has signature (3,1), so one "
        "member is a pair of conjugate planes with a real line L, and E restricted to L is indefinite: "
        "L meets E in two real points, singular points of a member lying on E, i.e. tangent points",
        evidence="a sphere between two parallel planes touching both (the pair is small: a = alpha) has "
        "Segre [(11)(11)]_2 and touches at 2 points; every pair built as above does. "
        "tests/test_contact_kind.py::test_two_double_roots_always_touch_twice",
        consequence="none for Theorem 2 or Corollary 10 (both kinds are 'no transversal contact')",
        confidence="high that the printed paper is wrong: the text of the proof of Theorem 2, item (1), "
        "lists [(11)(11)]_2 under no contact too",
    ),
    Erratum(
        key="table-3-subscript",
        location="Table 3 and proof of Theorem 2, item (2)(a): Segre type [(21)1]_3",
        printed="[(21)1]_3",
        corrected="[(21)1]_2: the symbol has two groups, a triple root and a simple one, so at most two "
        "distinct real roots",
        evidence="a sphere osculating the throat of a one-sheet hyperboloid from inside has Segre [(21)1]_2 "
        "and one tangent point. tests/test_contact_kind.py::test_the_subscript_of_21_1",
        consequence="none",
        confidence="high that the printed paper is wrong: the text of the proof of Theorem 2, item (2)(a), "
        "prints [(21)1]_3 too",
    ),
    Erratum(
        key="table-3-tangent-curve-segre",
        location="Table 3, row 'Curve of tangency'",
        printed="[(111)1]_2 and [(11)11]_3",
        corrected="[(111)1]_2 only (as the text of the proof of Theorem 2, item (3)(b), says). A rank-2 "
        "member (Segre group (11)) has a line of singular points, which meets E in at most two points; "
        "a curve of tangency needs a member of rank 1 (a double plane), i.e. a group of three blocks",
        evidence="tests/test_contact_kind.py::test_tangent_curves_need_a_rank_one_member",
        consequence="none for the contact tests (both are 'no transversal contact')",
        confidence="low that the printed paper is wrong: the text of the proof, item (3)(b), gives "
        "[(111)1]_2 alone, and the extra [(11)11]_3 duplicates a symbol of the rows 'no contact' and "
        "'2 isolated tangent points' in the second column of symbols, where the extraction may have "
        "displaced a cell; the table as extracted is certainly wrong",
    ),
)
