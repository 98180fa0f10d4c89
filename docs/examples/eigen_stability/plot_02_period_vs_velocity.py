r"""
The period against the tape speed
=================================

After a step load the load point of a moving tape rings at a dominant period that grows
with the tape speed V. Two independent routes give it:

* the eigen-solver: :math:`2\pi/\omega_1`, the lowest frequency of the gyroscopic
  eigenproblem (:func:`gyroshell.modes`);
* the transient: the lowest strong peak of the load point's spectrum after a step load
  (Newmark, :func:`gyroshell.march`, then
  :func:`gyroshell.studies.signal.dominant_period`).

A long tape's lowest frequency is the minimum over wavenumbers α of the moving-frame
dispersion :math:`|V\alpha - \sqrt{(D\alpha^4 + T\alpha^2 + k)/\rho}|`; it falls from
:math:`\sqrt{k/\rho}` at rest to zero at the critical speed, so the period grows without
bound as V approaches it.
"""

# %%
# The tape and the speeds
# -----------------------
# Table 1 tape, L_x = 8 L_y, on a quick grid (12 intervals across the width).
import math

import matplotlib.pyplot as plt
import numpy as np

import gyroshell
import gyroshell.plot
from gyroshell import TapeModel, TapeParameters
from gyroshell.studies.signal import dominant_period

params = TapeParameters(length_ratio=8)
params = params.replace(spacing=params.width / 12)
model = TapeModel(params)
velocities = np.array([0.0, 50.0, 75.0, 90.0, 95.0])  # m/s

# %%
# Both routes at each speed
# -------------------------
# The time step resolves the eigen-period with 40 steps (at least the paper's 2 µs) and
# the record holds 20 periods (at least 1 ms); the spectral peak taken is the lowest one
# reaching a quarter of the tallest (the band edge at ω₁).
eigen, transient = [], []
for v in velocities:
    period = float(gyroshell.modes(model, v, count=1).period[0])  # s
    dt = max(2e-6, period / 40)
    steps = math.ceil(max(1e-3, 20 * period) / dt)
    run = gyroshell.march(model, v, dt=dt, steps=steps)  # step load P0 at t = 0
    eigen.append(period)
    transient.append(dominant_period(run.times, run.load_point, lowest_fraction=0.25))
    print(f"V = {v:5.1f} m/s: 2π/ω₁ = {period * 1e6:7.2f} µs, "
          f"transient {transient[-1] * 1e6:7.2f} µs ({steps} steps of {dt * 1e6:.2f} µs)")

# %%
# The figure
# ----------
# :func:`gyroshell.plot.period_vs_velocity` draws both, with the critical speed.
critical = gyroshell.divergence_speed(model)
ax = gyroshell.plot.period_vs_velocity(velocities, np.array(eigen),
                                       transient_edge=np.array(transient),
                                       critical_speed=critical,
                                       title="Period of the load-point displacement, L_x/L_y = 8")
print(f"critical speed {critical:.2f} m/s")
plt.show()  # opens the figures in windows when run as a script

# %%
# The full-size case
# ------------------
# Full-size: ``gyroshell reproduce period --out-dir results`` (L_x/L_y = 19 on the default
# grid, 60 periods per record, speeds up to 100 m/s; about a minute). From Python, drop the
# ``spacing`` override and use ``length_ratio=19``.
