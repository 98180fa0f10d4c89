r"""
A two-module flat head: where the modules sit, and the spacing over them
========================================================================

A write-read head of two flat modules, 1 mm lands 0.3 mm apart, the tape wrapped 2° at
each end, one transducer in the middle of each land. First the head alone, drawn before
any solve (modules, gap, corners, transducer lines and the dry tape over them), then the
tape flying over it at 4 m/s: the spacing and the film's pressure along the head, with
the tents beside the corners and the transducers' readings. The film and contact models are the
defaults; the spacing is to the mean plane of the tape's summits.
"""

# %%
# The head
# --------
# :class:`gyroshell.bearing.head_config.HeadDesign` states the head as a user does (SI
# units, angles in rad) and checks it whole; ``.head()`` builds the
# :class:`gyroshell.bearing.FlatHead`. A transducer off both lands (in the gap) would be
# refused here, in one line.
import math

import matplotlib.pyplot as plt

from gyroshell import TapeParameters
from gyroshell.bearing import BearingModel, plots, solve_steady
from gyroshell.bearing.head_config import HeadDesign

design = HeadDesign(kind="flat", land_length=1e-3, modules=2, module_gap=0.3e-3,
                    wrap_in=math.radians(2.0), wrap_out=math.radians(2.0),
                    transducers=(-0.65e-3, 0.65e-3))  # m: the lands' middles
head = design.head()
plots.head_sketch(head)

# %%
# The tape flying over it
# -----------------------
# Table 1's tape, 12.65 mm wide, at 4 m/s; the infinitely wide tape (1-D, the centre line
# of a wide tape) on its default grid, which is graded into the corners.
tape = TapeParameters(width=12.65e-3)  # m
solution = solve_steady(BearingModel(tape, velocity=4.0, head=head, infinitely_wide=True))
for line in solution.transducer_lines:
    print(f"transducer at x = {line.x * 1e3:+.2f} mm: spacing {line.minimum * 1e9:.2f} nm")
for corner in solution.summary()["corner_forces"]:
    print(f"corner at x = {corner['x'] * 1e3:+.2f} mm: contact force "
          f"{corner['force']:.3g} N/m")
print(f"central spacing {solution.central_spacing * 1e6:.1f} µm (x = 0 is in the gap: "
      "its depth, not a flying height)")

fig, ax = plt.subplots(figsize=(7, 4), constrained_layout=True)
plots.head_spacing(solution, ax)

# %%
# Full-size: this is the full case in 1-D; leave out ``infinitely_wide=True`` for the
# tape's real width and free edges (2-D, about a minute), and vary the wraps and the speed
# with ``gyroshell study --compute bearing --vary wrap=1:4:4 --vary velocity=2,4,6``
# (the tutorial "A two-module flat head").
plt.show()
