"""Small instances of the result kinds of the static, transient and frequency-response
engines (and of tables), for the round-trip tests: each builds in well under a second."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pandas as pd

from gyroshell import TapeModel, TapeParameters
from gyroshell.engines.frequency_response import ReducedModel, frequency_response
from gyroshell.engines.newmark import march
from gyroshell.engines.static import solve_static
from gyroshell.results.base import Result
from gyroshell.results.tables import Table
from gyroshell.tape.moving_loads import drum_heads

#: Tape width L_y, m (Table 1).
WIDTH = 6.35e-3
#: L_x/L_y = 2, 16 x 8 intervals: 135 unknowns.
PARAMS = TapeParameters(length_ratio=2, spacing=WIDTH / 8)
#: Tape speed, m/s; viscous damping, N·s/m³ (keeps Q(ω) regular at the resonances).
SPEED, DAMPING = 10.0, 200.0
#: Angular frequencies of the responses, rad/s (more than the direct method's handful).
OMEGA = np.linspace(0.0, 2.0e5, 24)
#: An extra response point, m.
PROBE = (0.3 * PARAMS.length, 0.25 * PARAMS.width)


def model() -> TapeModel:
    return TapeModel(PARAMS)


def static() -> Result:
    return solve_static(model(), SPEED)


def transient() -> Result:
    """Two moving heads (so head histories), energy, snapshots and centre lines."""
    p = PARAMS
    heads = drum_heads(2, (0.2 * p.length, 0.2 * p.width), (200.0, 30.0),
                       revolution_period=12e-6, contact_duration=6e-6, ramp=1e-6)
    return march(model(), SPEED, dt=1e-6, steps=12, load=heads, damping=DAMPING,
                 record_energy=True, snapshot_every=4, centerline_times=[3e-6, 9e-6],
                 progress=False)


def frequency() -> Result:
    return frequency_response(model(), SPEED, OMEGA, damping=DAMPING, probes=[PROBE],
                              progress=False)


def reduced() -> Result:
    out = ReducedModel(model(), SPEED, damping=DAMPING, probes=[PROBE])
    out.add_points([2.0e4, 1.2e5])
    return out


def table() -> Result:
    """A table; note that reading a "table" file gives back the plain DataFrame."""
    frame = pd.DataFrame({"velocity": [0.0, 10.0, 20.0], "omega": [1.5e4, 1.4e4, 1.2e4],
                          "stability": ["stable", "stable", "divergence"]})
    return Table(frame, PARAMS)


EXAMPLES: dict[str, Callable[[], Result]] = {
    "static": static, "transient": transient, "frequency_response": frequency,
    "reduced_model": reduced, "table": table,
}
