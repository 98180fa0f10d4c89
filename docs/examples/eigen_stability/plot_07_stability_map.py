"""
A stability map from a parameter study
======================================

:func:`gyroshell.run_study` evaluates a grid of parameter points (every combination of
the varied values) and returns a :class:`gyroshell.StudyResult`: one table row per
point. With ``compute=["modes", "critical"]`` each row holds the lowest frequencies at
the point's speed, their stability class (stable, divergence or flutter, from the
gyroscopic eigenvalues) and the tape's critical speed.

Here the tape speed and the tension vary: a tape is stable below its critical speed,
which grows with the tension as √((T + μ_min)/ρ).
"""

# %%
# The study
# ---------
# Table 1 tape, L_x = 2 L_y, on a quick grid (8 intervals across the width), speeds from 0
# to 140 m/s, three tensions; ``workers=1`` runs the points in this process.
import matplotlib.pyplot as plt

import gyroshell
from gyroshell import TapeParameters

base = TapeParameters(length_ratio=2)
base = base.replace(spacing=base.width / 8)
study = gyroshell.run_study(base,
                            vary={"velocity": range(0, 141, 20),  # m/s
                                  "tension": [40.0, 80.0, 120.0]},  # N/m
                            compute=["modes", "critical"], workers=1, progress=False)
table = study.to_frame()
print(table.groupby(["tension", "stability"]).size().unstack(fill_value=0))
print(table.groupby("tension")["critical_speed"].first().round(2))

# %%
# The map
# -------
# :meth:`gyroshell.StudyResult.plot` draws the stability classes over the two varied
# parameters, with the critical speed as a line.
ax = study.plot()
plt.show()  # opens the figures in windows when run as a script

# %%
# Saving and loading
# ------------------
# A study saves to NetCDF (or CSV/Parquet for its table) and loads back equal, so a map
# can be redrawn later without recomputing: ``study.save("map.nc")`` then
# ``gyroshell.load("map.nc").plot()``.
#
# The full-size case
# ------------------
# Full-size: drop the ``spacing`` override, refine the speeds (``range(0, 131, 10)``), and
# use the machine's cores
# with ``workers=2`` (in a script, under ``if __name__ == "__main__":``, since workers are
# fresh processes) or a Dask cluster with ``scheduler="tcp://HOST:PORT"``. From the shell:
# ``gyroshell study --vary velocity=0:130:14 --vary tension=40,80,120 --compute modes
# --compute critical --workers 2 --out map.csv --save map.nc --plot map.png``.
