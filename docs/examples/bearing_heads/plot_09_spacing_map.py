"""
A 2-D spacing map (air bearing, 2-D)
====================================

The same head and tape as the 1-D example, now with the tape's real width and its free
lateral edges: the air leaks out at the edges, so the film pressure falls towards them
and the edges fly lowest, closest to the head near the exit corner. The 2-D model couples
the compressible Reynolds equation with slip on the tape's width to the shell's plate
operators; its grid is graded towards the free edges and the wrap corners.
"""

# %%
# The flying state
# ----------------
# Table 1 tape (6.35 mm wide) at 4 m/s over a 15° wrap, on a small grid: 120 intervals
# along the tape and 40 across.
import math

import matplotlib.pyplot as plt

from gyroshell import TapeParameters
from gyroshell.bearing import AirParameters, BearingModel, plots, solve_steady

model = BearingModel(TapeParameters(), AirParameters(), velocity=4.0,
                     wrap_angle=math.radians(15.0), nx=120, ny=40)
solution = solve_steady(model)
x_min, y_min = solution.minimum_location  # m
print(f"central spacing {solution.central_spacing * 1e6:.3f} µm, "
      f"minimum {solution.minimum_spacing * 1e6:.3f} µm at x = {x_min * 1e3:.2f} mm, "
      f"y = {y_min * 1e3:.2f} mm")
print(f"Newton iterations {solution.info.iterations}, unknowns {model.unknowns}")

# %%
# Spacing and pressure maps
# -------------------------
# ``gyroshell.bearing.plots.spacing_map`` draws the spacing (log colour scale, the
# minimum marked) or the film pressure over the tape; the dotted lines are the wrap
# corners.
fig, axes = plt.subplots(2, 1, figsize=(8, 7), constrained_layout=True)
plots.spacing_map(solution, axes[0])
plots.spacing_map(solution, axes[1], field="pressure")
axes[0].set_title(f"V = 4 m/s, 15° wrap, {model.nx} x {model.ny} grid")

# %%
# Across the width
# ----------------
# At the middle of the wrap the spacing is flat across the middle of the width, a little
# higher about a millimetre inside each edge, and falls steeply at the free edges.
fig, ax = plt.subplots(figsize=(6, 3.4), constrained_layout=True)
plots.cross_width(solution, ax)
plt.show()  # opens the figures in windows when run as a script

# %%
# The full-size case
# ------------------
# Full-size: drop ``nx`` and ``ny`` (the default graded grid, 388 x 148 intervals with an
# edge spacing near 12 µm, about 115,000 unknowns: some seconds per solve; its central
# spacing is within a few tenths of a per cent of this small grid's, its minimum spacing,
# at the edge by the exit corner, some per cent higher); from the shell,
# ``gyroshell bearing --velocity 4 --wrap-angle 15 --json`` or
# ``gyroshell reproduce bearing --out-dir results``.
