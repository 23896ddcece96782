# %% [markdown]
# # 2. The smallness condition
#
# **Definition 1.** The ellipsoid $\mathcal E$ is *small* with respect to the quadric
# $\mathcal Q$ if the two surfaces cannot meet in two curves, whatever their relative
# position.
#
# Why care?  **Theorem 2**: if $\mathcal E$ is small, the surfaces cross (transversal
# contact) exactly when the characteristic polynomial $\mathfrak P(\lambda)=\det(\lambda E+Q)$
# has non-real roots.  Without smallness, four real roots prove nothing (Remark 9).
#
# The paper turns the definition into inequalities: **Table 1** for $\mathcal Q$ in
# standard form (Lemma 4) and **Table 2** for any position (Theorem 5).  With the
# ellipsoid's semi-axes $\alpha\ge\beta\ge\gamma$ there are two kinds of condition:
#
# * **size**: a length of $\mathcal Q$ is at least $\alpha$ (e.g. $b\ge\alpha$);
# * **curvature** (Lemma 3): the largest principal curvature of $\mathcal Q$ is at most
#   the smallest principal curvature of $\mathcal E$, which is $\gamma/\alpha^2$.
#
# This notebook shows both conditions bite, draws configurations like the paper's
# Fig. 1 and Fig. 3, and walks through the places where the printed tables are wrong.

# %%
from fractions import Fraction as F

import matplotlib.pyplot as plt
import numpy as np
import sympy as sp

import quadric_contact as qc
from quadric_contact.interfaces.plotting import plot_quadric, quadric_mesh
from quadric_contact.paper import ERRATA, PRINTED
from quadric_contact.paper.printed_tables import printed_table_2
from quadric_contact.theory.geometric import decide_geometrically
from quadric_contact.theory.smallness import smallness, table_1

# %% [markdown]
# A small drawing helper: the ellipsoid coloured by the sign of $X^TQX$ on it (red where
# it is inside $R_-=\{X^TQX\le0\}$, blue in $R_+$).  Where both colours appear the surfaces
# cross; **two separate red (or blue) patches mean two intersection curves**.

# %%
RED, BLUE = np.array([0.85, 0.15, 0.15, 1.0]), np.array([0.12, 0.47, 0.71, 1.0])


def values_on(E, Q, n=90):
    """Mesh of E and the value of X^T Q X at each vertex (floats: a picture)."""
    ((X, Y, Z),) = quadric_mesh(E, n=n)
    P = np.stack([X, Y, Z, np.ones_like(X)])
    return X, Y, Z, np.einsum("i...,ij,j...->...", P, Q.to_numpy(), P)


def show_pair(E, Q, box, title, n=90, method="parametric", view=(20, -60)):
    """Left: the pair in 3D.  Right: the ellipsoid unwrapped (longitude, latitude of
    its parametrisation), coloured by the sign of X^T Q X: count the red patches."""
    fig = plt.figure(figsize=(9.5, 4))
    ax = fig.add_subplot(1, 2, 1, projection="3d")
    plot_quadric(ax, Q, box, n=50, method=method, color="0.6", alpha=0.25)
    X, Y, Z, v = values_on(E, Q, n)
    colours = np.where(v[..., None] < 0, RED, BLUE)
    ax.plot_surface(X, Y, Z, facecolors=colours, linewidth=0, shade=False)
    ax.set(xlim=box[0], ylim=box[1], zlim=box[2], xlabel="x", ylabel="y", zlabel="z")
    ax.set_box_aspect([hi - lo for lo, hi in box])
    ax.view_init(*view)
    ax.set_title(title, fontsize=9)
    m = fig.add_subplot(1, 2, 2)
    m.imshow(colours, extent=(0, 360, 180, 0), aspect="auto", interpolation="nearest")
    m.set(xlabel="longitude on E (degrees)", ylabel="latitude from the pole", title="E unwrapped: red = inside R-, blue = R+")
    m.title.set_fontsize(9)
    fig.tight_layout()
    return fig


# %% [markdown]
# ## Table 1: standard forms
#
# `table_1` evaluates a row of Table 1 exactly.  The bee of Example 17 has semi-axes
# $\alpha=\beta=1/\sqrt{10}$, $\gamma=1/\sqrt{30}$; the trunk is the hyperboloid
# $x^2+y^2-(z-3)^2/4=1$ ($a=b=1$, $c=2$).  Semi-axes may be sympy expressions whose
# squares are rational; every comparison is exact.

# %%
bee_axes = dict(alpha=sp.sqrt(10) / 10, beta=sp.sqrt(10) / 10, gamma=sp.sqrt(30) / 30)
print(table_1("hyperboloid of one sheet", a=1, b=1, c=2, **bee_axes))

# %% [markdown]
# Each condition keeps both sides exactly (`lhs`, `rhs` as sympy numbers) and says
# whether it is the printed one or a correction (the third line: see below).

# %%
row = table_1("hyperboloid of one sheet", a=1, b=1, c=2, **bee_axes)
[(c.name, c.lhs, c.rhs, c.holds, c.source) for c in row.conditions]

# %% [markdown]
# ## The size condition bites
#
# Between the parallel planes $x=\pm1$ (Table 1: $a=1$) an ellipsoid whose longest
# semi-axis is $\alpha=3/2$ can touch both planes at once: two circles.  Its
# characteristic polynomial has only real roots, with the sign pattern that Table 4
# assigns to "inside the slab".  Corollary 10 would answer *no contact*; the package
# refuses, because the ellipsoid is not small.

# %%
slab = qc.Quadric.parallel_planes(1)
long_one = qc.Quadric.ellipsoid(F(3, 2), F(1, 2), F(1, 2))
print(smallness(long_one, slab))
print(decide_geometrically(long_one, slab))
P = qc.characteristic_polynomial(long_one, slab)
print("P =", sp.factor(P.as_sympy()), "| roots:", P.structure.describe(), "| signs:", P.signs.pattern)
print(qc.transversal_contact(long_one, slab, method="theory"))

# %%
fig = show_pair(long_one, slab, [(-2, 2), (-1.5, 1.5), (-1.5, 1.5)], "size: α = 3/2 > a = 1")

# %% [markdown]
# ## The curvature condition bites (Fig. 1)
#
# The hyperboloid $x^2+y^2-z^2=1$ has $a=b=c=1$.  Seen from outside, its waist is a
# groove whose profile, the hyperbola $x=\sqrt{1+z^2}$, has curvature $a/c^2=1$ at the
# vertex.  A flat ellipsoid laid into the groove with its long axis along $z$ has
# smallest curvature $\gamma/\alpha^2<1$: the groove is tighter than the ellipsoid, so
# pushed in, the ellipsoid meets the surface above *and* below the waist.

# %%
waist = qc.Quadric.hyperboloid_one_sheet(1, 1, 1)
# semi-axes 3/10 (x, towards the waist), 1/2 (y), 9/10 (z): alpha = 9/10 <= b = 1
groove = qc.Quadric.ellipsoid(F(3, 10), F(1, 2), F(9, 10), center=(F(27, 20), 0, 0))
report = smallness(groove, waist)
print(report)

# %%
P = qc.characteristic_polynomial(groove, waist)
print("roots:", P.structure.describe(), "| signs:", P.signs.pattern, "| (Delta2, Delta3, Delta4) signs:", P.delta_signs())
print(decide_geometrically(groove, waist))
fig = show_pair(groove, waist, [(0, 2.2), (-1.1, 1.1), (-1.3, 1.3)], "Fig. 1: two curves, four real roots", view=(15, 200))

# %% [markdown]
# All four roots are real ($\Delta_4>0$), yet the two red patches are two intersection
# curves.  The last line is an independent, exact check that does not use the pencil:
# `decide_geometrically` finds the extremes of $X^TQX$ on the surface of $E$ from the
# Lagrange conditions (exact algebraic numbers) and counts the intersection curves by
# Morse theory.  It is what `transversal_contact` falls back on (`method="auto"`, the
# default) when the paper's results do not decide.
#
# ## Where the conditions bite: a map
#
# Take a flat spheroid, semi-axes $s, s, s/10$, against $x^2+y^2-z^2/c^2=1$.  The
# conditions of the hyperboloid row read
#
# * size $b\ge\alpha$: $s\le1$;
# * printed curvature $a/c^2\le\gamma/\alpha^2$: $s\le c^2/10$;
# * **corrected** curvature, the throat felt from inside, $a/b^2\le\gamma/\alpha^2$: $s\le 1/10$.
#
# The map below evaluates the corrected table and the printed one exactly on a grid.

# %%
cs = np.linspace(0.2, 4, 39)
ss = np.linspace(0.02, 1.2, 60)
verdict = np.zeros((len(ss), len(cs)))
for j, c in enumerate(cs):
    for i, s in enumerate(ss):
        s_, c_ = F(s).limit_denominator(1000), F(c).limit_denominator(1000)
        r = table_1("hyperboloid of one sheet", a=1, b=1, c=c_, alpha=s_, beta=s_, gamma=s_ / 10)
        verdict[i, j] = 2 if r.small else (1 if r.paper_small else 0)
fig, ax = plt.subplots(figsize=(6, 3.6))
ax.pcolormesh(cs, ss, verdict, cmap=plt.matplotlib.colors.ListedColormap(["#dddddd", "#f4a261", "#2a9d8f"]), shading="nearest")
ax.plot(cs, np.minimum(1, cs**2 / 10), "k--", lw=1, label="printed boundary: min(1, c²/10)")
ax.axhline(0.1, color="k", lw=1, label="corrected boundary: s = 1/10")
ax.set(xlabel="c (hyperboloid)", ylabel="s (spheroid s, s, s/10)", title="green: small; orange: printed Table 1 says small, it is not")
ax.legend(fontsize=8, loc="upper left")

# %% [markdown]
# ## Erratum: the one-sheet hyperboloid needs both curvatures
#
# The orange region is real.  The paper's own counterexample in the package's
# errata list: $Q: x^2+y^2-z^2/100=1$, a disc of radius 1 and thickness $1/5$ inside the
# throat, pressed against the wall.  The printed conditions hold ($b=1\ge\alpha=1$,
# $a/c^2=1/100\le\gamma/\alpha^2=1/10$), but the throat circle, curvature $a/b^2=1$,
# wraps around the disc: two curves, four real roots.

# %%
erratum = {e.key: e for e in ERRATA}
print(erratum["table-1-h1-curvature"].corrected, "\n")
throat = qc.Quadric.from_equation("x**2 + y**2 - z**2/100 - 1")
disc = qc.Quadric.ellipsoid(F(1, 10), 1, 1, center=(F(17, 20), 0, 0))
r = smallness(disc, throat)
print(r, "\n")
P = qc.characteristic_polynomial(disc, throat)
print("roots:", P.structure.describe(), "| signs:", P.signs.pattern)
print(decide_geometrically(disc, throat))
fig = show_pair(disc, throat, [(-0.3, 1.3), (-1.2, 1.2), (-1.2, 1.2)], "the printed Table 1 calls this small", view=(20, 20))

# %% [markdown]
# ## Erratum: two ellipsoids, either can be the small one
#
# For two ellipsoids Definition 1 is symmetric: two spheres of any radii meet in at
# most one circle, so a sphere of radius 2 is small with respect to a sphere of radius
# 1, although the printed condition $c\ge\alpha$ fails.  The report shows the
# *enclosing* alternative.  Corollary 10 still works there, but Table 4 does not: the
# big sphere around the small one has the root signs of $R_-$ while its surface lies in
# $R_+$.  `table_4_applies` says so, and `relative_position` does not guess.

# %%
big, unit = qc.Quadric.sphere(2), qc.Quadric.sphere(1)
r = smallness(big, unit)
print(r)
print("table_4_applies:", r.table_4_applies)
P = qc.characteristic_polynomial(big, unit)
print("P =", sp.factor(P.as_sympy()), "| signs:", P.signs.pattern, "| Table 4 for R-:", qc.ROOT_SIGN_TABLE[qc.QuadricKind.ELLIPSOID][qc.Region.R_MINUS])
print(qc.relative_position(big, unit, method="theory"))
print(qc.relative_position(big, unit))  # method="auto": the geometric decision settles it

# %% [markdown]
# ## Table 2: any position
#
# Smallness depends only on the shapes, so `smallness` works from the Euclidean
# invariants of Section 2.4 (the eigenvalues of $Q_{00}$, $\det Q$, $J$, $K$, $J'$), exact
# real algebraic numbers.  Moving both surfaces by rational rigid motions changes nothing:

# %%
trunk = qc.Quadric.from_equation("x**2 + y**2 - 0.25*(z-3)**2 - 1")
bee = qc.Quadric.from_equation("(x-3)**2 + (y-3)**2 + 3*(z-5.5)**2 - 0.1")
moved = [(bee.rotated((1, 2, 3, 4)).translated((5, -1, 2)), trunk.rotated((3, 0, 1, 1)).translated((0, 7, 1)))]
for e, q in [(bee, trunk), *moved]:
    r = smallness(e, q)
    print(r.small, [f"{c.name}: {c.decimal('lhs', 6)} vs {c.decimal('rhs', 6)}" for c in r.conditions])

# %% [markdown]
# The numbers printed in Example 17 (Table 2 notation: $d_1c_1$, $\delta\alpha$,
# $a_1/(d_1c_1^2)$, $\gamma/(\delta\alpha^2)$ for the crown, then the trunk) come out of the
# corrected table to the digits printed:

# %%
crown = qc.Quadric.from_equation("x**2 + y**2 + 3*(z - 8.36291)**2 - 20")
for name, q in [("S1", crown), ("S2", trunk)]:
    r = smallness(bee, q)
    ours = [r.conditions[0].decimal("lhs", 6), r.conditions[0].decimal("rhs", 6), r.conditions[1].decimal("lhs", 6), r.conditions[1].decimal("rhs", 6)]
    print(name, "printed:", PRINTED[f"Example 17 smallness {name}"], "| computed:", " ".join(ours))

# %% [markdown]
# ## Example 6 and Fig. 3: a quadric that is almost another type
#
# Example 6 gives two matrices in decimals.  The quadric's $Q_{00}$ has an eigenvalue
# $1.7\times10^{-7}$: with exact arithmetic it is a hyperboloid of one sheet, but it is
# obviously meant as a hyperbolic paraboloid.  The paper reads it both ways with Table 2
# and finds the same maximal curvature, about 1, larger than the ellipsoid's smallest
# curvature, about 0.416: **not small**.

# %%
def printed_matrix(name):
    return qc.Quadric([[F(x) for x in row.split()] for row in PRINTED[name].split(";")])


Q6, E6 = printed_matrix("Example 6 Q"), printed_matrix("Example 6 E")
print("exact type of Q:", Q6.kind, "| E:", E6.kind)
for reading in ("hyperbolic paraboloid", "hyperboloid of one sheet"):
    t2 = printed_table_2(E6, Q6, reading=reading)
    for c in t2.conditions:
        print(f"  read as {reading}: {c.name}: {c.decimal('lhs', 10)} vs {c.decimal('rhs', 10)} -> {'holds' if c.holds else 'FAILS'}")
print("printed: maximal curvature", PRINTED["Example 6 paraboloid curvature"], "/", PRINTED["Example 6 hyperboloid curvature"], "; minimal curvature of E", PRINTED["Example 6 E curvature"])
print("exact verdict:", smallness(E6, Q6).small)

# %% [markdown]
# The quadric's numbers agree with the printed ones to about nine digits (the tiny
# eigenvalue limits the rest).  The ellipsoid's do not beyond the fourth digit: the
# printed $E$ has six significant digits, which fix $\delta$ to only two or three, and
# the paper computed from its unrounded matrix.  The conclusion holds for every matrix
# that rounds to the printed one (`tests/test_example_6.py` checks it with ball
# arithmetic over the whole rounding box).
#
# Fig. 3(ii) shows the pair "after an appropriate rigid motion".  Here is one, found by
# looking at the geometry: the ellipsoid's axes are aligned with the principal
# directions of $Q$, and its *longest* axis lies along the direction in which the
# saddle curves *away* from it.  A quarter turn about the nearly null direction of
# $Q_{00}$ puts the long axis where the saddle wraps around the ellipsoid.  The rotation
# is exact (a rational quaternion), so the rotated pair is still exact.

# %%
M = Q6.to_numpy()
w_, V_ = np.linalg.eigh(M[:3, :3])
null = V_[:, np.argmin(abs(w_))]
axis = [F(float(t)).limit_denominator(100) for t in null]
print("nearly null direction of Q00:", np.round(null, 4), "-> rational axis", axis)
E6_turned = E6.rotated((1, *axis), about=E6.center())
P = qc.characteristic_polynomial(E6_turned, Q6)
print("after the quarter turn: roots", P.structure.describe(), "| signs", P.signs.pattern, "| Delta signs", P.delta_signs())
print(qc.transversal_contact(E6_turned, Q6, method="theory"))

# %%
c6 = [float(t) for t in E6.center()]
box6 = [(c6[0] - 2, c6[0] + 2), (c6[1] - 2, c6[1] + 2), (c6[2] - 2, c6[2] + 2)]
show_pair(E6, Q6, box6, "Fig. 3(i): as printed (no contact)", method="graph")
show_pair(E6_turned, Q6, box6, "Fig. 3(ii): a quarter turn: two curves", method="graph")
print("before:", decide_geometrically(E6, Q6))
print("after: ", decide_geometrically(E6_turned, Q6))

# %% [markdown]
# The quadric is drawn with `method="graph"` (solved along its nearly null direction):
# its exact parametrisation as a hyperboloid lives at the scale $a\approx2391$ and is
# useless for a picture.  After the quarter turn all four roots are real and have the
# pattern of "outside", and the surfaces cross in two curves: exactly the failure that
# smallness excludes.
#
# ## Errata in Table 2
#
# Table 2 restates Table 1 through invariants; two rows are misprinted.
#
# **Hyperbolic cylinder.** Printed: $x^2/a'^2-y^2/b'^2=M^2$ and $Mb'\ge\delta'\alpha'$.  The
# transverse semi-axis is $Ma'$, so the size condition is $Ma'\ge\delta'\alpha'$.  With
# $x^2-y^2/100=1$ and a sphere of radius $3/2$ between the branches the printed row
# holds ($Mb'=10$), yet the sphere crosses both branches.

# %%
print(erratum["table-2-hyperbolic-cylinder-size"].corrected, "\n")
hc = qc.Quadric.from_equation("x**2 - y**2/100 - 1")
ball = qc.Quadric.sphere(F(3, 2))
printed = printed_table_2(ball, hc)
print("printed row:", [(c.name, c.holds) for c in printed.conditions], "-> small:", printed.small)
print(smallness(ball, hc))
print(decide_geometrically(ball, hc))
fig = show_pair(ball, hc, [(-2, 2), (-2, 2), (-2, 2)], "printed Table 2: 'small'")

# %% [markdown]
# **Parabolic cylinder.** Printed: $d'^2=4Ka'^2$.  For $x^2/a'^2-d'z=0$ the invariant $K$ is
# $-d'^2/(4a'^2)$, negative, so the printed $d'^2$ is negative for every parabolic
# cylinder and the row cannot be evaluated.  The corrected $d'^2=-4Ka'^2$ is used.

# %%
pc = qc.Quadric.parabolic_cylinder(1)
print("printed row:", printed_table_2(qc.Quadric.sphere(F(1, 10)), pc).undefined)
print(smallness(qc.Quadric.sphere(F(1, 10)), pc))

# %% [markdown]
# All the errata the package records, with the test that demonstrates each one:

# %%
for e in ERRATA:
    print(f"[{e.key}] {e.location}\n    printed:   {e.printed}\n    corrected: {e.corrected}\n")

# %% [markdown]
# ## Exercise
#
# A sphere of radius $r$ rolls inside the elliptic paraboloid $x^2+y^2/4=z$ (Table 1:
# $a=2$, $b=1$ after ordering $a\ge b$).  Only the curvature condition applies:
# $2/b^2\le\gamma/\alpha^2=1/r$.  What is the largest $r$ for which the sphere is small?
# Store it as a `Fraction` in `answer`.

# %%
answer = F(1, 2)  # 2/b^2 <= 1/r  <=>  r <= b^2/2 = 1/2

# %%
# Check: smallness holds at `answer` (equality allowed) and fails just above it.
bowl = qc.Quadric.from_equation("x**2 + y**2/4 - z")
assert smallness(qc.Quadric.sphere(answer, center=(0, 0, 3)), bowl).small
assert not smallness(qc.Quadric.sphere(answer * F(1001, 1000), center=(0, 0, 3)), bowl).small
print("correct!")
