"""The designer's readings on solved bearing states (BearingSolution): they are plain JSON
in the summary, survive save -> load bit for bit, draw their figures, and the
transducer-line spacing converges at second order with the transducer off the nodes."""

from __future__ import annotations

import json
import math
import warnings

import numpy as np
import pytest
from convergence import observed_order

from gyroshell import TapeParameters
from gyroshell.bearing import AirParameters, BearingModel
from gyroshell.bearing.model import BearingGridWarning
from gyroshell.bearing.steady import solve_steady

READING_KEYS = ("transducer_lines", "tents", "corner_forces", "land_forces", "viscous_drag",
                "friction_drag", "drag", "tension_rise", "tension_ratio", "friction")


def _cylinder(nx=None, *, wide=True, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", BearingGridWarning)
        return BearingModel(TapeParameters(width=3e-3), AirParameters(), velocity=4.0,
                            wrap_angle=math.radians(15), infinitely_wide=wide, nx=nx, **kw)


def _plain(value) -> bool:
    """Only dicts, lists, str, bool, int, finite float and None, recursively."""
    if isinstance(value, dict):
        return all(isinstance(k, str) and _plain(v) for k, v in value.items())
    if isinstance(value, list):
        return all(_plain(v) for v in value)
    if isinstance(value, float):
        return math.isfinite(value)
    return value is None or type(value) in (str, bool, int)


def test_readings_are_plain_json_in_the_summary():
    sol = solve_steady(_cylinder(60))
    summary = sol.summary()
    assert set(READING_KEYS) <= set(summary)
    assert _plain(summary)
    assert json.loads(json.dumps(summary, allow_nan=False)) == summary
    # the cylinder's tangent points are its corners, its arc its land; no contact here
    assert len(summary["corner_forces"]) == 2 and len(summary["land_forces"]) == 1
    assert summary["friction_drag"] == 0.0 and summary["viscous_drag"] > 0.0
    assert summary["drag"] == summary["viscous_drag"] == summary["tension_rise"]


def _line_orders(values) -> np.ndarray:
    """Observed orders from successive differences of values on grids halved each time."""
    d = np.abs(np.diff(np.asarray(values)))
    return np.log2(d[:-1] / d[1:])


def test_transducer_line_spacing_converges_at_second_order_off_the_nodes():
    from gyroshell.bearing.head import Cylinder

    x_t = 1.2345e-3                      # m: on the wrap, off every node of these grids
    head = Cylinder(math.radians(15), transducers=(x_t,))
    values = []
    for nx in (100, 200, 400, 800):
        sol = solve_steady(BearingModel(TapeParameters(), AirParameters(), velocity=4.0,
                                        head=head, infinitely_wide=True, nx=nx, span=4e-3))
        (line,) = sol.transducer_lines
        assert not np.any(np.isclose(sol.x, x_t, rtol=0, atol=1e-9))
        values.append(line.centre)
    assert _line_orders(values) == pytest.approx([2.0, 2.0], abs=0.1)
