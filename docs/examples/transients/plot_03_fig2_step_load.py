"""
Fig. 2: the load point after a step load, and a wire-frame
==========================================================

The paper's Fig. 2: the tape rests in its wrapped equilibrium, and at t = 0 the Gaussian
pressure of its Eq. 17 (P₀ = 200 Pa) is switched on. The load point oscillates about
the static deflection, which grows with the tape speed V as the effective tension
T − ρV² falls towards zero at the critical speed. Displacements are drawn as w k / P₀,
the deflection as a fraction of the Winkler value P₀/k of a uniformly loaded foundation.

The time march is Newmark's average-acceleration scheme (β = 1/4, γ = 1/2,
:func:`gyroshell.march`); the steady states come from the static solver
(:func:`gyroshell.solve_static`).
"""

# %%
# The tape
# --------
# Table 1 tape, L_x = 19 L_y as in the paper, on a quick grid (12 intervals across the
# width instead of 41), 400 steps of the paper's 2 µs.
import matplotlib.pyplot as plt

import gyroshell
import gyroshell.plot
from gyroshell import TapeModel, TapeParameters

params = TapeParameters(length_ratio=19)
params = params.replace(spacing=params.width / 12)
model = TapeModel(params)
scale = params.k / params.load_pressure  # 1/m: w k / P0 is dimensionless
DT, STEPS = 2e-6, 400  # s, steps

# %%
# The load-point histories
# ------------------------
velocities = (0.0, 50.0, 90.0, 100.0)  # m/s
fig, axes = plt.subplots(len(velocities), 1, figsize=(8, 8), sharex=True,
                         constrained_layout=True)
for ax, v in zip(axes, velocities, strict=True):
    run = gyroshell.march(model, v, dt=DT, steps=STEPS)
    static = gyroshell.solve_static(model, v).load_point_deflection  # m
    gyroshell.plot.load_point_history(run.times, run.load_point, steady=static, scale=scale,
                                      ylabel="w k / P₀", velocity=v, ax=ax)
    print(f"V = {v:5.1f} m/s: static w k/P0 = {static * scale:.4f}, "
          f"mean of the transient {run.load_point.mean() * scale:.4f}")
for ax in axes[:-1]:
    ax.set_xlabel("")
axes[0].legend(loc="lower right", fontsize=8)
fig.suptitle("Load-point displacement after a step load, L_x/L_y = 19 (quick grid)")

# %%
# A wire-frame of the whole tape
# ------------------------------
# As in the paper's Figs. 3 and 4, on a shorter tape (L_x = 4 L_y, 16 intervals across):
# the full field kept at chosen instants (``snapshot_times``), and the static solution
# as t = ∞. The disturbance spreads from the load, reaches the free edges near 28 µs and
# reflects; downstream (+x) its waves are longer than upstream.
short = TapeParameters(length_ratio=4)
short = TapeModel(short.replace(spacing=short.width / 16))
run = gyroshell.march(short, 50.0, dt=DT, steps=50, snapshot_times=[12e-6, 28e-6, 80e-6])
snaps = run.snapshots
fields = [*snaps.fields, gyroshell.solve_static(short, 50.0).field]
labels = [f"t = {t * 1e6:.0f} µs" for t in snaps.times] + ["t = ∞ (static)"]
top = max(abs(w).max() for w in fields)
fig = plt.figure(figsize=(10, 5.5))
for k, (label, w) in enumerate(zip(labels, fields, strict=True), start=1):
    gyroshell.plot.wireframe(snaps.x, snaps.y, w, ax=fig.add_subplot(2, 2, k, projection="3d"),
                             title=f"V = 50 m/s, {label}", zmax=top)
fig.subplots_adjust(left=0.0, right=1.0, bottom=0.02, top=0.95, wspace=0.0, hspace=0.1)
print(f"largest |w| of the panels: {top * 1e9:.2f} nm")
plt.show()  # opens the figures in windows when run as a script

# %%
# The full-size case
# ------------------
# Full-size: ``gyroshell reproduce fig2 --out-dir results`` (the default grid, 41 intervals
# across, 1000 steps; ``reproduce fig3`` and ``fig4`` draw the wire-frames at 0 and 50 m/s), or
# ``gyroshell transient --length-ratio 19 --velocity 50 --steps 1000 --dt 2e-6 --out h.csv``
# for one speed. From Python, drop the ``spacing`` override and use ``steps=1000``.
