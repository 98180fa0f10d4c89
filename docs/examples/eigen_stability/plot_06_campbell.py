"""
A Campbell diagram
==================

The natural frequencies of the moving tape against its speed, one line per mode branch.
:func:`gyroshell.campbell` solves the gyroscopic eigenproblem at each speed and links the
modes of neighbouring speeds by their mass-weighted modal assurance criterion (MAC), so a
branch keeps its identity through crossings and veerings. The frequencies fall with the
speed and the lowest reaches zero at the critical speed.

Against the branches stand the excitation lines ω = n·2πV/ℓ of a roller or capstan of
circumference ℓ turning with the tape: where a branch meets a line, the n-th harmonic of
the roller's run-out excites that mode.
"""

# %%
# The tape and the speeds
# -----------------------
# A short tape (L_x = 1.5 L_y) with all sides simply supported, so that its modes are well
# separated; quick grid (12 intervals across), five modes at every 5 m/s up to 80 m/s.
import matplotlib.pyplot as plt
import numpy as np

import gyroshell
from gyroshell import TapeModel, TapeParameters

params = TapeParameters(length_ratio=1.5, edges="simply-supported")
params = params.replace(spacing=params.width / 12)
model = TapeModel(params)
diagram = gyroshell.campbell(model, np.arange(0.0, 85.0, 5.0), count=5, progress=False)
print(diagram.summary())

# %%
# The diagram
# -----------
# :meth:`gyroshell.CampbellDiagram.plot` with a roller of 10 mm circumference: the
# crossings are circled, veerings marked with diamonds (none here); the critical speed,
# just above 100 m/s, lies beyond the sweep (its value is in the legend). Between 80 m/s
# and it the five frequencies crowd together, and a grid this coarse no longer tells their
# branches apart.
ax = diagram.plot(circumference=0.01)  # m

# %%
# Where the roller excites the tape
# ---------------------------------
# :meth:`~gyroshell.CampbellDiagram.resonances`: the speeds (m/s) at which each branch
# meets each excitation line.
print(diagram.resonances(0.01).round(2).to_string(index=False))
plt.show()  # opens the figures in windows when run as a script

# %%
# The full-size case
# ------------------
# Full-size: drop the ``spacing`` override; from the shell, ``gyroshell campbell
# --length-ratio 1.5 --edges simply-supported --velocities 0:80:17 --count 5
# --circumference 0.01 --plot campbell.png`` (``--workers 2`` solves the speeds on two
# processes).
