r"""
Contact recording: a flat head's spacing against the measured trends
=====================================================================

Over a flat, lapped module the tape runs tens of nanometres from the head. The sharp
leading corner skives the air, the land's film is sub-ambient and the tape rests on its
asperities there (contact recording). Magnetic spacing measured at IBM Research over such
heads **falls** as the leading wrap grows, does **not depend** on the trailing wrap,
**falls** as the tension grows and **rises** with speed.

:func:`gyroshell.bearing.trends.spacing_trends` sweeps each parameter about a thin data
tape over a 1 mm module (2°/2°, 60 N/m, 4 m/s) and reads the spacing at a mid-land
transducer, to the mean plane of the tape's summits. With the linearized Boltzmann flow
factor, Patir–Cheng's flow factors and Greenwood–Williamson asperities (the film's gap the
mean gap between the head and the rough tape) the four signs come out: the air reaches the
land through the valleys of the corners pressed into their summits, less the harder they
are pressed (a larger leading wrap, a higher tension), while the roughness the tape carries
along brings more in at speed. The hard wall at a gap with first-order slip gets three of
them wrong.
"""

# %%
# The four sweeps, under both models
# ----------------------------------
# Each sweep solves four designs of the infinitely wide tape on their default grids (about
# 0.1 s each under the asperities).
# Full-size: these sweeps are the full case (every point on its default grid).
import matplotlib.pyplot as plt

from gyroshell.bearing import AirParameters
from gyroshell.bearing.contact import ContactParameters
from gyroshell.bearing.trends import spacing_trends

legacy = (AirParameters(rarefaction="first-order"), ContactParameters(law="hard"))
models = {"Boltzmann film, asperities (the defaults)": spacing_trends(),
          "first-order slip, hard wall at 20 nm": spacing_trends(*legacy)}
units = {"wrap_in": "leading wrap (deg)", "wrap_out": "trailing wrap (deg)",
         "tension": "tension (N/m)", "velocity": "speed (m/s)"}
words = {-1: "falls", 0: "does not depend", 1: "rises"}

fig, axes = plt.subplots(2, 4, figsize=(13, 5.5), sharex="col", sharey="row")
for row, (name, trends) in enumerate(models.items()):
    for ax, trend in zip(axes[row], trends, strict=True):
        ax.plot(trend.values, [h * 1e9 for h in trend.spacings], "o-",
                color="C0" if trend.agrees else "C3")
        ax.set_title(f"{words[trend.sign]} (measured: {words[trend.measured]})",
                     fontsize=9, color="k" if trend.agrees else "C3")
        ax.set_xlabel(units[trend.parameter])
    axes[row][0].set_ylabel(f"{name}\nspacing at the transducer (nm)", fontsize=9)
fig.tight_layout()
plt.show()

# %%
# The table
# ---------
for name, trends in models.items():
    agree = sum(t.agrees for t in trends)
    print(f"{name}: {agree} of 4 measured signs")
    for t in trends:
        print(f"  {t.parameter:9s} {t.spacings[0] * 1e9:7.3f} -> {t.spacings[-1] * 1e9:7.3f} nm "
              f"({t.change:+.2%}): {words[t.sign]}, measured {words[t.measured]}")
