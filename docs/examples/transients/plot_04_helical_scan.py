"""
The helical scan: moving, intermittent heads
============================================

In a helical-scan recorder the heads sit on a rotating drum and cross the moving tape
obliquely, each touching it for part of a revolution. Here two heads, half a revolution
apart, sweep the same oblique track at 40 m/s, each pressing with the paper's Gaussian
(P₀ = 200 Pa) during its contact window (raised-cosine ramps of 20 µs), while the tape
moves at 10 m/s with light viscous (air) damping.

The heads are :class:`gyroshell.MovingLoad` objects, made here by
:func:`gyroshell.drum_heads`; :func:`gyroshell.march` takes them as ``load`` and records
the displacement under each head (``head_displacements``): the head-tape spacing
variation it sees.
"""

# %%
# The tape and the track
# ----------------------
# Table 1 tape, L_x = 4 L_y, quick grid (12 intervals across). The track runs from
# (0.15 L_x, 0.05 L_y) to (0.85 L_x, 0.95 L_y); the contact lasts the track's length over
# the head speed, and the heads are in contact for 80 % of the revolution.
import matplotlib.pyplot as plt
import numpy as np

import gyroshell
import gyroshell.plot
from gyroshell import TapeModel, TapeParameters

params = TapeParameters(length_ratio=4)
params = params.replace(spacing=params.width / 12)
model = TapeModel(params)

start = np.array([0.15 * params.length, 0.05 * params.width])  # m
end = np.array([0.85 * params.length, 0.95 * params.width])  # m
HEAD_SPEED, TAPE_SPEED, DAMPING = 40.0, 10.0, 100.0  # m/s, m/s, N·s/m³
duration = np.linalg.norm(end - start) / HEAD_SPEED  # s in contact per pass
revolution = 2 * duration / 0.8  # s
heads = gyroshell.drum_heads(2, tuple(start), tuple((end - start) / duration),
                             revolution_period=revolution, contact_duration=duration,
                             ramp=20e-6)
print(f"contact {duration * 1e6:.0f} µs per pass, revolution {revolution * 1e6:.0f} µs")

# %%
# One revolution of the drum
# --------------------------
# 2 µs steps, with the whole field kept at three instants for the wire-frames.
DT = 2e-6
steps = int(round(revolution / DT))
snap_times = revolution * np.array([0.1, 0.3, 0.7])
run = gyroshell.march(model, TAPE_SPEED, dt=DT, steps=steps, load=heads, damping=DAMPING,
                      snapshot_times=snap_times)
contact = np.column_stack([head.envelope(run.times) for head in heads])
for k in range(len(heads)):
    touching = contact[:, k] >= 1.0
    w = run.head_displacements[touching, k]
    print(f"head {k + 1}: in full contact for {touching.sum()} steps, w under it "
          f"{w.min() * 1e9:.2f} to {w.max() * 1e9:.2f} nm")

# %%
# The spacing variation under each head
# -------------------------------------
# :func:`gyroshell.plot.head_histories`: the contact envelopes, then w under each head
# while it touches (positive: away from the head).
axes = gyroshell.plot.head_histories(run.times, run.head_displacements, contact)
axes[0].figure.suptitle(f"Two-head drum at {HEAD_SPEED:g} m/s, tape at {TAPE_SPEED:g} m/s")

# %%
# The tape under the heads
# ------------------------
# Wire-frames at three instants; the dot marks a head in contact.
snaps = run.snapshots
top = abs(snaps.fields).max()
fig = plt.figure(figsize=(12, 3.8))
for i, (t, w) in enumerate(zip(snaps.times, snaps.fields, strict=True)):
    ax = gyroshell.plot.wireframe(snaps.x, snaps.y, w, zmax=top, zmin=-top,
                                  ax=fig.add_subplot(1, 3, i + 1, projection="3d"),
                                  title=f"t = {t * 1e6:.0f} µs", zoom=1.0)
    for k, head in enumerate(heads):
        if head.envelope(np.array([t]))[0] > 0:
            x, y = head.centres(np.array([t]))
            ax.scatter(x * 1e3, y * 1e3, [top * 1e9], color=f"C{k}", s=25)
fig.subplots_adjust(left=0.0, right=1.0, bottom=0.02, top=0.95, wspace=0.0)
plt.show()  # opens the figures in windows when run as a script

# %%
# The full-size case
# ------------------
# Full-size: ``gyroshell reproduce helical --out-dir results`` (the default grid, two
# revolutions). One head from the shell: ``gyroshell transient --velocity 10 --steps 500
# --dt 2e-6 --load-position 0.005,0.003 --load-velocity 40,5 --contact-period 200e-6
# --contact-duration 120e-6 --contact-ramp 10e-6 --damping 100 --out head.csv``.
