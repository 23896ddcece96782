"""What the paper prints, as text: its formulas, tables and numbers, keyed by where they appear.

Nothing here is used to compute an answer: tests and ``proofs/`` compare the package's
derivations with these printed statements (where they differ, the erratum is in
:data:`~quadric_contact.paper.errata.ERRATA`).  Formulas are in sympy's syntax, tables one
row a line with ``|`` between the columns.
"""

from __future__ import annotations

__all__ = ["PRINTED"]

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
