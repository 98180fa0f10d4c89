"""
A Bode plot: the frequency response
===================================

The steady response of the tape to the paper's Gaussian load oscillating as
P₀ e^{iωt}: its amplitude and phase at the load point against the angular frequency ω.
:func:`gyroshell.frequency_response` computes it with a reduced (rational Krylov) model
whose error it estimates, falling back to direct solves wherever the estimate exceeds the
tolerance. The resonances sit on the eigen-solver's frequencies and move down as the
tape speed grows (the effective tension T − ρV² falls).
"""

# %%
# The tape and the frequencies
# ----------------------------
# Table 1 tape, L_x = 4 L_y, quick grid (12 intervals across), light viscous (air)
# damping c = 30 N·s/m³, 1000 frequencies up to 1.6e5 rad/s: the reduced model costs a
# few factorizations, not one per frequency. At 90 m/s the standing waves of the finite
# tape crowd above ω₁: the response is a dense comb of resonances.
import matplotlib.pyplot as plt
import numpy as np

import gyroshell
import gyroshell.plot
from gyroshell import TapeModel, TapeParameters

params = TapeParameters(length_ratio=4)
params = params.replace(spacing=params.width / 12)
model = TapeModel(params)
omega = np.linspace(0.0, 1.6e5, 1000)  # rad/s
DAMPING = 30.0  # N·s/m³

# %%
# The response at three speeds
# ----------------------------
# :func:`gyroshell.plot.bode` takes a :class:`gyroshell.FrequencyResponse` and the
# eigen-solver's frequencies (dotted).
axes = None
for i, v in enumerate((0.0, 50.0, 90.0)):  # m/s
    response = gyroshell.frequency_response(model, v, omega, damping=DAMPING)
    found = gyroshell.modes(model, v, count=6).omega  # rad/s
    axes = gyroshell.plot.bode(response, axes=axes, color=f"C{i}", label=f"V = {v:g} m/s",
                               mode_omegas=found)
    peak = omega[np.argmax(response.amplitude[:, 0])]
    print(f"V = {v:4.0f} m/s: tallest peak at {peak:9.0f} rad/s, ω₁ = {found[0]:9.0f} rad/s, "
          f"static |W| = {response.amplitude[0, 0] * 1e9:.2f} nm, "
          f"{response.info['factorizations']} factorizations, "
          f"largest error estimate {np.max(response.error_estimate):.0e}")
axes[0].legend(title="dotted: eigen-solver ω_j", fontsize=9)
axes[0].set_title("Load-point response, L_x/L_y = 4, c = 30 N·s/m³ (quick grid)")
plt.show()  # opens the figures in windows when run as a script

# %%
# The full-size case
# ------------------
# Full-size: ``gyroshell reproduce frf --out-dir results`` (the default grid),
# or for one speed ``gyroshell frf --velocity 50 --frequencies 0:1.6e5:1000 --damping 30
# --out frf.csv --plot frf.png``. From Python, drop the ``spacing`` override.
