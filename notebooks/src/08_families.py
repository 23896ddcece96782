# %% [markdown]
# # 8. Families: the pencil over Q(parameters), numeric lambdas and contact maps
#
# The other notebooks decide one pair at a time.  Here the pair depends on **parameters**:
# where may the bee's centre be so that it touches the trunk?  For which length does a
# capsule stop being small in a pipe?  `qc.family(E, Q, parameters)` builds the paper's
# quantities once, exactly, as rational functions of the parameters:
#
# * the coefficients $c_0,\dots,c_4$ of $\mathfrak P(\lambda)=\det(\lambda E+Q)$ (eq. (1)),
# * $\Delta_2,\Delta_3,\Delta_4$ (Section 3.2, with the corrected $\Delta_4$),
# * the sign rules of Table 4, Corollary 15 for planes, the smallness conditions of Tables 1-2
#   where they are rational,
#
# then evaluates them fast on arrays (`fam.lambdify`), and draws **contact maps**: the answer
# of the predicates on a grid of two parameters, with the exact curves where it can change.

# %%
import time

import matplotlib.pyplot as plt
import numpy as np
import sympy as sp

import quadric_contact as qc
from quadric_contact.families.family_maps import MapAnswer

# %% [markdown]
# ## The bee in the vertical plane through the tree
#
# Example 17's bee is $(x-3)^2+(y-3)^2+3(z-5.5)^2=0.1$.  We put its centre at $(u, 0, w)$:
# the plane $y=0$ contains the axis of the trunk $S_2$ and of the crown $S_1$.  The
# parameters are declared; the equation is read by the package's own parser, and any other
# name is refused.

# %%
bee = "(x - u)^2 + y^2 + 3*(z - w)^2 - 0.1"
trunk = "x^2 + y^2 - 0.25*(z - 3)^2 - 1"
crown = "x^2 + y^2 + 3*(z - 8.36291)^2 - 20"
fam = qc.family(bee, trunk, "u w")
print(fam.describe())

# %%
try:
    qc.family("(x - v)^2 + y^2 + 3*(z - w)^2 - 0.1", trunk, "u w")
except qc.EquationError as exc:
    print(exc)

# %% [markdown]
# The coefficients are polynomials of degree 2 in $(u, w)$: a translation only moves the last
# row and column of $E$.  $c_4=\det E$ and $c_0=\det Q$ do not move at all.

# %%
u, w = fam.symbols
for k, c in enumerate(fam.coefficients):
    print(f"c{k} =", sp.factor(c))

# %% [markdown]
# $\Delta_4$ has degree 12.  Its zero set is where $\mathfrak P$ has a multiple root; every
# tangency gives one (if the surfaces touch at $X$, then $(\lambda_0E+Q)X=0$ and
# $\mathfrak P'(\lambda_0)=\operatorname{tr}(\operatorname{adj}(\lambda_0E+Q)E)=kX^TEX=0$).  It
# factors over $\mathbb Q$: one factor is $u^4$ (the bee on the trunk's axis has a double
# root, by symmetry, and nothing happens there).

# %%
d4 = sp.factor(fam.deltas[2])
print(d4)
for b in fam.boundaries:
    print(b.name, "=0 :", [sp.factor(e) for e in b.exprs])

# %% [markdown]
# The bee only moves, so its smallness does not depend on $(u,w)$: the invariants of Section
# 2.4 are constant, and it is decided once (Theorem 5).  Table 4 (derived from Descartes'
# rule, not copied) names the region from the signs of the coefficients.

# %%
print(fam.smallness)
print(fam.smallness.report)
for rule in fam.table_4.values():
    print(rule)
# Corollary 10 as a sympy Boolean in u, w: Delta4 < 0, or Delta4 = 0 and Delta3 < 0
for point in [{u: 1, w: 3}, {u: 3, w: sp.Rational(11, 2)}]:
    print(point, "non-real roots:", fam.criterion.subs(point))

# %% [markdown]
# ## Numeric lambdas
#
# `fam.lambdify(name, backend)` compiles a quantity with the package's code generator
# (Horner form, shared subexpressions, the same generator as the kernels): `numpy`,
# `numba`, `mpmath`, `exact` and `certified`, which gives the *sign* with a rigorous
# error bound and `2` (uncertain) where it cannot be sure.

# %%
print(fam.lambdify("Delta4").source.split("\n\n")[0])

# %%
U, W = np.meshgrid(np.linspace(-4, 4, 400), np.linspace(-2, 12, 400), indexing="ij")
values = fam.lambdify("Delta4", "numba")(U, W)
signs = fam.lambdify("Delta4", "certified")(U, W)
peer = sp.lambdify((u, w), sp.expand(fam.deltas[2]), "numpy")
timings = {}
for name, fn in [
    ("sympy.lambdify", lambda: peer(U, W)),
    ("numba", lambda: fam.lambdify("Delta4", "numba")(U, W)),
    ("certified", lambda: fam.lambdify("Delta4", "certified")(U, W)),
]:
    t = time.perf_counter()
    fn()
    timings[name] = U.size / (time.perf_counter() - t)
print({k: f"{v:,.0f} evaluations/s" for k, v in timings.items()})
print("certified signs:", dict(zip(*np.unique(signs, return_counts=True), strict=True)))
exact = fam.lambdify("Delta4", "exact")(U[::40, ::40], W[::40, ::40])
assert all(s in (2, (e > 0) - (e < 0)) for s, e in zip(signs[::40, ::40].ravel(), exact.ravel(), strict=True))

# %% [markdown]
# A path: the bee flies along $x$ at the height $w=4$ (`fix` sets a parameter exactly).  The
# sign of $\Delta_4$ along the way, and where it changes: the certified signs only flip where
# the exact polynomial has a root.

# %%
path = fam.fix(w=4)
xs = np.linspace(-4, 4, 2001)
plt.figure(figsize=(7, 2.5))
plt.plot(xs, np.sign(path.lambdify("Delta4")(xs)), lw=1)
plt.axhline(0, color="0.7", lw=0.5)
roots = sp.Poly(sp.numer(sp.together(path.deltas[2])), path.symbols[0]).real_roots()
for r in roots:
    plt.axvline(float(r), color="tab:red", lw=0.8, ls="--")
plt.title("sign of Delta4 as the bee flies along x at z = 4; dashed: the exact roots", fontsize=9)
plt.xlabel("u")
print("exact roots of Delta4 on the path:", [sp.nsimplify(r) if r.is_Rational else float(r) for r in roots])

# %% [markdown]
# ## The contact map: the bee and the trunk
#
# `fam.contact_map(u=(a, b), w=(c, d), resolution=...)` decides every cell at its centre (a
# binary64 point) with the certified predicates (`relative_position`, and `contact_kind`
# where $\Delta_4$ may vanish) on the exact pair, so a cell's colour is never wrong for its
# centre; cells on a boundary are subdivided for the picture.  The curves on top are the
# zero sets of the exact polynomials, located exactly on vertical and horizontal lines.

# %%
m = fam.contact_map(u=(-4, 4), w=(-2, 12), resolution=160)
print(m.counts(), m.stats)
m.plot(title="the bee's centre (u, 0, w) and the trunk S2")

# %% [markdown]
# Each cell means what the scalar predicate means at its centre:

# %%
for i, j in [(10, 40), (60, 80), (80, 80), (150, 150)]:
    point, answer = m.cell(i, j)
    E, Q = fam.at(**point)
    print(point, answer.name, "|", qc.relative_position(E, Q).region, qc.contact_kind(E, Q).name)

# %% [markdown]
# ## The crown: $\Delta_4$ vanishes identically
#
# The crown $S_1$ has the bee's quadratic part ($x^2+y^2+3z^2$): the pencil has a double
# root for every position, and $\Delta_4\equiv0$.  The boundary is then the next minor of
# the discrimination system, $\Delta_3$.

# %%
fam1 = qc.family(bee, crown, "u w")
print("Delta4 =", fam1.deltas[2], "; boundaries:", [b.name for b in fam1.boundaries])
m1 = fam1.contact_map(u=(-6, 6), w=(3, 13), resolution=100)
print(m1.counts())
m1.plot(title="the bee's centre (u, 0, w) and the crown S1")

# %% [markdown]
# The tree of Example 17 is the crown above the plane $z=6$ and the trunk below it
# (Algorithm 1): the plane's own map (Corollary 15) is a band of width twice the bee's
# vertical semi-axis, and the plane's discriminant is exactly $c_3^2-4c_4c_2$.

# %%
plane = qc.family(bee, "z - 6", "u w")
print(plane.corollary_15)
m0 = plane.contact_map(u=(-4, 4), w=(5, 7), resolution=(40, 80))
print(m0.counts())

# %% [markdown]
# ## A capsule in a pipe: when does smallness stop?
#
# In the spirit of Fig. 1 and Fig. 3: a capsule with semi-axes $(1/4, s, 1/4)$ inside the
# pipe $x^2+y^2=1$, its long axis along the wall (the $y$ direction), its centre at
# $(u,0,0)$.  Now a semi-axis is a parameter: the smallness conditions of Table 1 are
# rational functions of $s$ (not all polynomials), valid where the eigenvalues keep the order
# they have at the reference point (here $s\ge 1/4$, where $s$ is the largest semi-axis).

# %%
capsule = qc.family("16*(x - u)^2 + y^2/s^2 + 16*z^2 - 1", "x^2 + y^2 - 1", "u s")
sm = capsule.smallness
print(sm)
for cond in sm.conditions:
    print(cond.name, ":", sp.factor(cond.expr), cond.relation, 0)

# %% [markdown]
# Small iff $s\le 1$ (the size condition) and $1\le \gamma/\alpha^2=\tfrac{1/4}{s^2}$ (the
# curvature condition, Lemma 3: the pipe's curvature 1 against the capsule's flattest
# curvature), so for $s\ge 1/4$: **small iff $s\le 1/2$**.  A longer capsule pushed against
# the wall touches it first with its two ends: two curves of intersection while all the roots
# of $\mathfrak P$ are real, where Corollary 10 alone would answer "no contact" (Remark 9).
# The map shows the predicates' answer; hatched: the cells where $\Delta_4>0$ (all roots
# real, certified) and yet the surfaces cross.

# %%
mc = capsule.contact_map(u=(-1.4, 1.4), s=(0.05, 1.2), resolution=(112, 92))
print(mc.counts(), mc.stats["seconds"], "s")
fig = mc.plot(
    extra_curves=["a/b^2 <= gamma/alpha^2", "b >= alpha"],
    title="capsule (1/4, s, 1/4) at (u, 0, 0) in the pipe x^2 + y^2 = 1",
)
Uc, Sc = np.meshgrid(mc.u, mc.w, indexing="ij")
all_real = capsule.lambdify("Delta4", "certified")(Uc, Sc) == 1
wrong = all_real & (mc.codes == MapAnswer.CONTACT)
fig.axes[0].contourf(Uc, Sc, wrong.astype(float), levels=[0.5, 1.5], hatches=["///"], colors="none")
print(f"cells where Corollary 10 alone would say 'no contact' but the surfaces cross: {wrong.sum()}")
print("smallest s among them:", Sc[wrong].min())

# %% [markdown]
# Every one of those cells lies above the line $s=1/2$ where smallness ends, as Theorem 2
# promises: for a small ellipsoid, all roots real means no transversal contact.  (Between
# $s=1/2$ and the first hatched cell the capsule is not small, but no placement on this line
# of centres shows it: Definition 1 quantifies over all positions.)

# %%
assert Sc[wrong].min() > 0.5
assert all(qc.smallness(*capsule.at(u=0, s=s)).small == (s <= 0.5) for s in (0.3, 0.5, 0.51, 0.9))

# %% [markdown]
# **Exercises.**  (1) Give the bee a third parameter $v$ (its $y$ coordinate) and draw the map
# over $(u, v)$ at $w=4$ with `contact_map(u=..., v=..., w=4)`.  (2) Make the capsule's
# radius a parameter $r$ too: where is the curvature condition now?  (3) Lay the capsule
# across the pipe (its long axis along $x$): which condition of Table 1 fails first?
