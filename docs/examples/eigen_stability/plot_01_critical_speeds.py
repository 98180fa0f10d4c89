r"""
Critical speeds of a few tapes
==============================

Above its critical speed a moving tape has no stable equilibrium: the lowest gyroscopic
frequency has fallen to zero and the tape diverges. gyroshell finds that speed by two
independent routes, and :func:`gyroshell.critical_speeds` returns both:

* where the lowest frequency of the gyroscopic eigenproblem crosses zero (eigen-solver and
  root search, ``critical_speed``);
* :math:`\sqrt{(T + \mu_{min})/\rho}` from one symmetric eigen-solve of the stiffness
  without the speed term (``divergence_speed``).

They must agree. Beside them stand two closed forms: the moving string
:math:`\sqrt{T/\rho}` (no bending, no foundation) and the infinitely wide strip on its
shell foundation :math:`\sqrt{(T + 2\sqrt{Dk})/\rho}`.

This example builds a table over the lateral edge conditions and the tension, on a coarse
grid so that it runs in a second.
"""

# %%
# The tapes
# ---------
# The paper's Table 1 tape (E = 4 GPa, c = 20 µm, R = 20 mm, T = 90 N/m, L_y = 6.35 mm)
# with L_x = 4 L_y, free or simply supported lateral edges, at three tensions. The quick
# grid has 12 intervals across the width (the default grid has 41).
import matplotlib.pyplot as plt
import pandas as pd

import gyroshell
from gyroshell import TapeModel, TapeParameters

QUICK_INTERVALS = 12  # intervals across the width; the default spacing gives 41

rows = []
for edges in ("free", "simply-supported"):
    for tension in (60.0, 90.0, 120.0):  # N/m
        params = TapeParameters(length_ratio=4, edges=edges, tension=tension)
        params = params.replace(spacing=params.width / QUICK_INTERVALS)
        speeds = gyroshell.critical_speeds(TapeModel(params))
        if (edges, tension) == ("free", 90.0):
            table_1_tape = speeds
        rows.append({"edges": edges, "T (N/m)": tension,
                     "critical (m/s)": speeds.critical_speed,
                     "divergence (m/s)": speeds.divergence_speed,
                     "string sqrt(T/rho) (m/s)": speeds.string_speed,
                     "strip (m/s)": speeds.strip_speed})

# %%
# The table
# ---------
# The two routes agree to round-off. Free edges give a critical speed a little below the
# infinite strip's (the edges' anticlastic relief), simply supported edges a little above
# it; all lie far above the string's, since bending and the shell's foundation stiffness
# k = E c / R² hold the tape up.
table = pd.DataFrame(rows)
pd.set_option("display.width", 120)
print(table.to_string(index=False, float_format=lambda v: f"{v:.3f}"))
print("largest relative difference of the two routes:",
      f"{(table['critical (m/s)'] / table['divergence (m/s)'] - 1).abs().max():.1e}")

# %%
# One tape's speeds as bars
# -------------------------
# Every result draws itself: :meth:`gyroshell.CriticalSpeeds.plot` shows both routes
# beside the reference values (the closed forms and the values quoted in the literature
# for this tape).
ax = table_1_tape.plot()
ax.set_title("Table 1 tape, free edges, T = 90 N/m (quick grid)")
plt.show()  # opens the figures in windows when run as a script

# %%
# The full-size case
# ------------------
# Full-size: drop the ``spacing`` override (the default grid, 41 intervals across) and
# use ``length_ratio=19``; from the shell, ``gyroshell critical --json`` (add
# ``--edges simply-supported``, ``--tension 120`` or ``--length-ratio 19``), or
# ``gyroshell reproduce critical --out-dir results`` for the paper's whole table.
