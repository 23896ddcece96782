"""The errata registry: every place where the printed paper differs from what is true.

Each :class:`Erratum` names the test or proof that demonstrates it; the test suite fails if
a listed erratum stops being reproducible or an unlisted difference appears.  The
documentation's errata page and ``proofs/REPORT.md`` are rendered from :data:`ERRATA`.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["ERRATA", "Erratum"]


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
