# %% [markdown]
# # 7. A gallery of scenes, many bodies, animations and sweeps
#
# The built-in scenes together cover **every quadric type of Table 1 and the plane**.
# This notebook runs each one, draws it, checks a few event times against closed forms,
# then scales up: a thousand-body scene with a certified broad phase (reduced here to a
# hundred bodies so that the notebook runs in seconds), per-object effects, an animation,
# and a sweep of perturbed flights.

# %%
from dataclasses import replace
from fractions import Fraction as F
from importlib import resources

import matplotlib.pyplot as plt
import sympy as sp
from IPython.display import Image, display

from quadric_contact.interfaces.animation import render_gif
from quadric_contact.interfaces.plotting import plot_result
from quadric_contact.model.classification import QuadricKind
from quadric_contact.scenes.manybody import many_body_scene
from quadric_contact.scenes.scene_toml import builtin_scene, builtin_scene_names
from quadric_contact.scenes.simulate import simulate
from quadric_contact.scenes.sweep import run_sweep

# %% [markdown]
# ## Which scene shows which quadric

# %%
covered = {}
for name in builtin_scene_names():
    for obj in builtin_scene(name, check_smallness=False).objects:
        for piece in obj.pieces:
            covered.setdefault(piece.quadric.kind.value, []).append(name)
for kind in [k for k in QuadricKind if k.in_table_1] + [QuadricKind.PLANE]:
    print(f"{kind.value:28s} {', '.join(sorted(set(covered.get(kind.value, ['MISSING']))))}")

# %% [markdown]
# ## A probe between the sheets of a two-sheet hyperboloid
#
# The sheets of $x^2+y^2-z^2+1=0$ are $z\ge 1$ and $z\le -1$.  A probe of radius $1/2$
# passes between them (no contact: its distance to them is at least
# $\sqrt{1+x^2/2}$), turns up the axis and enters the upper sheet.  On the axis the
# nearest point of the sheet is its vertex while $z\le 2$, so contact begins at
# $z = 1 - 1/2$ and the probe is inside from $z = 1 + 1/2$: with $z = t - 3$ on that leg,
# at $t = 7/2$ and $t = 9/2$ exactly.  It then drifts sideways out through the wall.

# %%
probe = simulate(builtin_scene("probe_two_sheets"))
pair = probe.pair("probe", "hyperboloid")
for ev in pair.events:
    print(ev.time.decimal(12), "|", "; ".join(ev.changes(pair.object)))
assert [ev.time.value for ev in pair.events[:2]] == [F(7, 2), F(9, 2)]
fig = plot_result(probe)

# %% [markdown]
# ## A ball between two parallel walls
#
# The walls are the parallel planes $x^2=1$ (Table 1), the floor the plane $z=0$.  The
# ball (radius $1/4$) rolls on the floor, touching it at one point all the time (a
# tangency, never a crossing: the contact kind says so), and crosses a wall exactly while
# $|x|>3/4$.  On each straight leg that is a linear equation in $t$; sympy solves them
# independently of the engine.

# %%
walls = simulate(builtin_scene("parallel_walls"))
pair = walls.pair("ball", "corridor")
t = sp.Symbol("t")
legs = [(0, 2, 0, sp.Rational(9, 10)), (2, 4, sp.Rational(9, 10), -sp.Rational(9, 10)), (4, 6, -sp.Rational(9, 10), sp.Rational(1, 2))]
closed = []
for ta, tb, xa, xb in legs:
    x = xa + (xb - xa) * (t - ta) / (tb - ta)
    for level in (sp.Rational(3, 4), -sp.Rational(3, 4)):
        closed += [s for s in sp.solve(sp.Eq(x, level), t) if ta < s < tb]
print("closed forms:", sorted(closed))
print("engine      :", [ev.time.value for ev in pair.events])
assert sorted(closed) == [ev.time.value for ev in pair.events]
fig = plot_result(walls)

# %% [markdown]
# ## Skimming a parabolic trough and a hyperbolic-cylinder channel
#
# The trough $x^2 = 4z$ (a parabolic cylinder) and the channel $x^2-(y-14)^2=1$ (a
# hyperbolic cylinder) are two objects, each cut by a plane.  On the trough's axis the
# distance to the bottom is $z$, so the body crosses it while $z<1/2$; at the throat of the
# channel the distance to the right branch is $1-x$, so it crosses the wall while $x>1/2$.

# %%
tc = simulate(builtin_scene("trough_and_channel"))
print(tc.format_text(8).split("work ledger")[0])
fig = plot_result(tc)

# %% [markdown]
# ## Every other scene
#
# The bee and the tree (ellipsoid, one-sheet hyperboloid), a ball over a saddle
# (hyperbolic paraboloid, plane), a drone past a cooling tower (one-sheet hyperboloid,
# plane), a capsule in a pipe (elliptic cylinder, elliptic paraboloid).  The test suite
# checks every event time of every scene against the static Algorithms 1-2 on both sides
# of the event and at dense sample times.

# %%
for name in ("ball_over_saddle", "drone_cooling_tower", "capsule_pipe"):
    fig = plot_result(simulate(builtin_scene(name)), samples=120)

# %% [markdown]
# ## Only what the scene asks for, per object
#
# In `bees_with_interests` the scout wants zones, contacts and its relative position, the
# worker only its first contact, the drone only contacts, and nobody wants the relative
# position on the crown.  The ledger compares the work done with every effect computed for
# every piece; the same scene without the per-object requests does more.

# %%
bees = builtin_scene("bees_with_interests")
asked = simulate(bees)
everything = simulate(replace(bees, ellipsoid_effects={}, piece_effects={}))
print("per-object effects:\n" + asked.ledger.format())
print("\nevery effect of the scene for every bee and piece:\n" + everything.ledger.format())

# %% [markdown]
# ## Many bodies and the broad phase
#
# `quadric-contact simulate many_bodies` runs a thousand small ellipsoids flying straight
# through and around a totem of 16 pieces (spheres and one-sheet hyperboloids separated by
# 15 planes).  The **broad phase** bounds, in exact rational interval arithmetic, the box
# each ellipsoid sweeps over a stretch of time, and tests it against each plane
# ($n\cdot x-d$ of one strict sign) and each piece ($X^TQX$ of one strict sign): where it
# certifies a side, no pencil in time is formed.  The timelines are the same as without it;
# here with a hundred bodies.

# %%
swarm = many_body_scene(100, 16, seed=0)
plain = simulate(swarm)
broad = simulate(swarm, broad_phase=True)
same = all(
    len(p.events) == len(q.events) and all(e.time.compare(f.time) == 0 for e, f in zip(p.events, q.events, strict=True))
    for p, q in zip(plain.pairs, broad.pairs, strict=True)
)
print(f"identical timelines: {same}; events: {sum(len(p.events) for p in broad.pairs)}")
print(f"pencils in time: {plain.ledger.done['characteristic_polynomials']} without, "
      f"{broad.ledger.done['characteristic_polynomials']} with the broad phase")
print(broad.ledger.format())

# %% [markdown]
# ## An animation
#
# `quadric-contact simulate SCENE --animate out.gif` writes the same as below: the bodies
# move, coloured by state, above the timeline with a cursor.

# %%
gif = render_gif(tc, frames=14, fps=6)
display(Image(data=gif, format="gif"))

# %% [markdown]
# ## A sweep: the bee's path under perturbations
#
# `quadric-contact sweep` moves every key of the bee's path by up to $1/20$ per
# coordinate (seeded, reproducible), runs each flight and keeps its exact first contact;
# on a `dask.distributed` cluster (`--scheduler ADDRESS`, a `LocalCluster` by default)
# the results are the same as here, run by run.  Forty runs, serially:

# %%
text = resources.files("quadric_contact").joinpath("scenes", "bee_and_tree.toml").read_text()
sweep = run_sweep(text, "bee_and_tree", 40, serial=True, progress=False)
print(sweep.format_text())
times = [float(t) for t in sweep.first_contacts("bee", "tree") if t is not None]
fig, ax = plt.subplots(figsize=(6, 2.5))
ax.hist(times, bins=12, color="tab:red")
ax.set(xlabel="first contact time", ylabel="runs", title="first contact of 40 perturbed flights")
