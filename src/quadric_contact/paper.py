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
    ),
)
