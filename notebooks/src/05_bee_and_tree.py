# %% [markdown]
# # 5. The bee and the tree: composite objects, Algorithms 1-2 and exact event times
#
# Section 5.2 of the paper models an object by pieces of quadrics separated by planes
# (Fig. 8).  In Example 17 a tree is a **crown** $S_1$ (an ellipsoid) above the plane
# $z=6$ and a **trunk** $S_2$ (a hyperboloid of one sheet) below it, and a bee is a small
# ellipsoid $\mathcal E$.  Two algorithms decide contact:
#
# * **Algorithm 1** (Corollary 15): on which side of the plane is the bee?  Zone 1
#   ($R_+$, the crown's side), Zone 2 ($R_-$, the trunk's side) or Zone 0 (crossing the
#   plane).  No smallness needed.
# * **Algorithm 2** (Corollary 10): contact with the piece(s) of that zone only; "the
#   other characteristic polynomials shall be computed only if needed".
#
# Then we let the bee fly, and the package computes the **exact times** at which its state
# changes.

# %%
from fractions import Fraction as F

import matplotlib.pyplot as plt
import numpy as np
import sympy as sp

import quadric_contact as qc
from quadric_contact.interfaces.plotting import plot_quadric, plot_result
from quadric_contact.paper import PRINTED
from quadric_contact.scenes.composite import algorithm_1, algorithm_2
from quadric_contact.scenes.ledger import Ledger
from quadric_contact.scenes.scene_toml import builtin_scene
from quadric_contact.scenes.simulate import simulate

# %% [markdown]
# ## The scene
#
# The scene ships with the package (`quadric-contact simulate` runs it); it is a TOML file
# that can be read with `load_scene` too.  Numbers in it are exact: `5.5` is $11/2$.

# %%
scene = builtin_scene("bee_and_tree")
print(scene.describe())
tree = scene.objects[0]
bee = scene.ellipsoids[0]
crown, trunk = (p.quadric for p in tree.pieces)
plane = tree.splits()[0].plane

# %%
fig = plt.figure(figsize=(6, 6))
ax = fig.add_subplot(projection="3d")
plot_quadric(ax, crown, [(-5, 5), (-5, 5), (6, 11)], color="tab:green", alpha=0.3, label="crown S1 (z > 6)")
plot_quadric(ax, trunk, [(-5, 5), (-5, 5), (0, 6)], color="tab:brown", alpha=0.4, label="trunk S2 (z < 6)")
plot_quadric(ax, plane, [(-5, 5), (-5, 5), (5.9, 6.1)], color="0.5", alpha=0.1)
plot_quadric(ax, bee.quadric, color="orange", alpha=1, label="bee E")
ax.set(xlim=(-5, 5), ylim=(-5, 5), zlim=(0, 11))
ax.set_box_aspect((10, 10, 11))
ax.legend(fontsize=8)
ax.set_title("Fig. 8: the tree cut by the plane z = 6, and the bee", fontsize=9)

# %% [markdown]
# The two pieces meet the plane in the same circle, $x^2+y^2=3.25$ (to the five digits
# printed for the crown's centre):

# %%
x, y = sp.symbols("x y")
for name, q in [("crown", crown), ("trunk", trunk)]:
    print(name, "at z = 6:", sp.expand(sp.sympify(q.equation()).subs("z", 6)), "= 0")

# %% [markdown]
# ## Example 17, step by step
#
# **Algorithm 1.** $\mathfrak P_0(\lambda)=\det(\lambda E+P)=\lambda^2(c_4\lambda^2+c_3\lambda+c_2)$.
# The paper prints $\mathfrak P_0=\lambda^2(-0.3\lambda^2-1.5\lambda-0.25)$ and
# $\Delta_3=0.121875>0$, $c_3=-1.5<0$: Zone 2.

# %%
E0 = bee.quadric
P0 = qc.characteristic_polynomial(E0, plane)
print("P0 =", sp.factor(P0.as_sympy()), "  printed:", PRINTED["Example 17 P0"])
print("Delta3 =", P0.deltas()[1], "=", float(P0.deltas()[1]), "  printed:", PRINTED["Example 17 P0 Delta3"])
zone = algorithm_1(E0, tree)
print("zones:", zone.zones, "-> pieces to check:", [p.name for p in zone.pieces])

# %% [markdown]
# **Algorithm 2.** Only the trunk is in Zone 2, so only $\mathfrak P_2$ is formed.
# Printed: $\Delta_4^2=6.90965\times10^8>0$, no contact; and $c_3>0$, $c_2>0$, $c_1<0$: the
# bee is outside the trunk (Table 4).  The ledger counts the work: the crown costs
# nothing.

# %%
ledger = Ledger()
result = algorithm_2(E0, tree, region=True, ledger=ledger)
P2 = result.contacts["trunk"].polynomial
print("P2 =", P2, "  printed:", PRINTED["Example 17 P2"])
print(f"Delta4 = {float(P2.deltas()[2]):.6g}   printed: {PRINTED['Example 17 P2 Delta4']}")
print("contact:", result.contact, "| trunk:", result.regions["trunk"])
print(ledger)
print("work on the crown:", ledger.cost("crown"))

# %% [markdown]
# ## Flying the bee
#
# The bee follows keyframes: it flies into the trunk's bark, backs off, climbs through
# the plane into Zone 1, enters the crown and leaves it on the far side, pitching as it
# climbs.  Between keyframes its centre moves linearly and its orientation is a rational
# rotation (a quaternion interpolated linearly), so its matrix is a matrix of
# polynomials in $t$, and so are the coefficients of every pencil and every discriminant.
# An event can only happen at a real root of one of those polynomials: the simulator
# isolates them exactly and decides the state between and at them.

# %%
run = simulate(scene)
print(run.format_text())

# %%
fig = plot_result(run)

# %% [markdown]
# ## Event times are exact algebraic numbers
#
# Each event time is a real root of an integer polynomial, held with an isolating
# interval that can be refined to any number of digits.  The first contact:

# %%
pair = run.pair("bee", "tree")
t_first, pieces = pair.first_contact
print("first contact with", pieces, "at t =", t_first.decimal(30))
print("t is the root of", t_first.poly_str("t", integer=True))
print(f"isolated in [lo, hi] with rational ends, width {float(t_first.hi - t_first.lo):.1e}")

# %% [markdown]
# Check it from outside the simulator: place the bee just before and just after that
# time (exact rational times $10^{-9}$ away) and ask `transversal_contact`.

# %%
t0, t1 = scene.span
traj = bee.trajectory
t_mid = t_first.rational_near(15)
for dt in (F(-1, 10**9), F(1, 10**9)):
    placed = traj.placed(E0, t_mid + dt, t0, t1)
    print(f"t = {float(t_mid + dt):.10f}: contact with the trunk: {bool(qc.transversal_contact(placed, trunk))}")

# %% [markdown]
# ## $\Delta_4$ along the path
#
# The same story told by the discriminants.  At many times along the flight, place the
# bee exactly and compute $\Delta_4$ of its pencil with each piece, and the plane's
# $c_3^2-4c_4c_2$ (negative while the bee crosses the plane: Zone 0).  Event times are
# marked.  A piece's $\Delta_4$ is only *used* while the bee is in that piece's zone:
# there its sign is the contact (Corollary 10).

# %%
def slog(v):
    v = np.asarray(v, dtype=float)
    return np.sign(v) * np.log10(1 + np.abs(v))


ts = [F(k, 40) for k in range(0, 401)]
d4 = {"crown": [], "trunk": []}
plane_disc = []
for t in ts:
    E = traj.placed(E0, t, t0, t1)
    for name, q in [("crown", crown), ("trunk", trunk)]:
        d4[name].append(qc.characteristic_polynomial(E, q).deltas()[2])
    plane_disc.append(qc.plane_side(E, plane).discriminant)
tf = [float(t) for t in ts]

fig, ax = plt.subplots(3, 1, figsize=(9, 7), sharex=True)
ax[0].plot(tf, slog(plane_disc), color="0.3")
ax[0].set_ylabel("plane: c3² - 4 c4 c2")
ax[1].plot(tf, slog(d4["trunk"]), color="tab:brown")
ax[1].set_ylabel("trunk: Δ4")
ax[2].plot(tf, slog(d4["crown"]), color="tab:green")
ax[2].set_ylabel("crown: Δ4")
for a in ax:
    a.axhline(0, color="k", lw=0.5)
    for ev in pair.events:
        a.axvline(float(ev.time), color="r", lw=0.6, ls=":")
ax[2].set_xlabel("t   (dotted: exact event times;  all curves: sign · log10(1 + |value|))")
fig.suptitle("discriminants along the bee's flight", fontsize=10)
plt.tight_layout()

# %% [markdown]
# Read it with the timeline above: the trunk's $\Delta_4$ is negative exactly while the
# bee is in the bark (events 1-2); the plane's discriminant is negative while the bee
# crosses $z=6$ (events 3-5); the crown's $\Delta_4$ is negative while the bee enters and
# leaves the crown (events 4-6 and 7-8).
#
# Two more things show up.  The trunk's $\Delta_4$ is also negative twice while the bee
# flies *inside the crown* (around $t=5$ and $t=8.5$): the bee then crosses the
# hyperboloid's continuation above $z=6$, which is not part of the tree.  Algorithm 1 is
# what keeps this from being reported: in Zone 1 the trunk is not looked at.  And the
# crown's $\Delta_4$ is exactly 0 while the bee is not rotated ($t\le3$ and $t=10$): the
# bee's quadratic part is then proportional to the crown's, $\lambda=-1$ is a double
# root (notebook 3), and $\Delta_3$ decides.
#
# ## Only what is asked is computed
#
# The effects a run asks for decide the plan.  Asking only for the zone never forms a
# piece's pencil; a full evaluation of everything on every segment is there to compare.

# %%
zone_only = simulate(scene, effects=["zone"])
full = simulate(scene, full=True)
print("zone only: work on crown, trunk:", zone_only.ledger.cost("tree/crown"), zone_only.ledger.cost("tree/trunk"))
print("\nfull evaluation:\n" + full.ledger.format())
print("\nthe scene's own plan:\n" + run.ledger.format())
same = all(a.time == b.time for a, b in zip(full.pair("bee", "tree").events, pair.events, strict=True))
print("\nthe same exact event times either way:", same)

# %% [markdown]
# ## Exercise
#
# Where is the bee at $t=6$?  Place it with `traj.placed(E0, 6, t0, t1)`, run Algorithm 2
# on it with `region=True`, and store its region with respect to the crown (a `Region`:
# `R-` is inside the crown's ellipsoid) in `answer`.

# %%
at6 = algorithm_2(traj.placed(E0, 6, t0, t1), tree, region=True)
answer = at6.regions["crown"].region

# %%
# Check against the exact timeline of the simulation.
state = pair.state_at(6)
assert dict(state.pieces)["crown"].region == answer == qc.Region.R_MINUS
print("correct! at t = 6:", state.summary(tree))
