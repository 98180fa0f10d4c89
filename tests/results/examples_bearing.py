"""Small instances of the bearing's result kinds, for the registry's round-trip test."""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable

from gyroshell import TapeParameters
from gyroshell.bearing import AirParameters, BearingModel
from gyroshell.bearing.head import FlatHead, Module
from gyroshell.bearing.model import BearingGridWarning
from gyroshell.bearing.steady import solve_steady
from gyroshell.bearing.transient import march, tension_step
from gyroshell.results.base import Result

#: A coarse infinitely wide tape: Newton in a few hundredths of a second.
INTERVALS = 60
#: A coarse free-edged tape (its default grid is graded).
INTERVALS_2D = (40, 8)
#: A coarse free-edged tape over a flat head.
INTERVALS_FLAT = (64, 8)
TIME_STEP = 1e-5
STEPS = 3


def _model(infinitely_wide: bool = True, **kw) -> BearingModel:
    nx, ny = (INTERVALS, None) if infinitely_wide else INTERVALS_2D
    with warnings.catch_warnings():  # coarse on purpose: the file, not the answer, is tested
        warnings.simplefilter("ignore", BearingGridWarning)
        return BearingModel(TapeParameters(width=3e-3), kw.pop("air", AirParameters()),
                            velocity=4.0, wrap_angle=math.radians(15.0),
                            infinitely_wide=infinitely_wide, nx=nx, ny=ny, **kw)


def steady() -> Result:
    """A steady flying state of the infinitely wide tape."""
    return solve_steady(_model())


def steady_legacy() -> Result:
    """:func:`steady` with the interface of the releases before contact laws: first-order
    slip and the hard wall at 20 nm (what their files hold)."""
    from gyroshell.bearing.contact import ContactParameters

    return solve_steady(_model(air=AirParameters(rarefaction="first-order"),
                               contact=ContactParameters(law="hard")))


def steady_2d() -> Result:
    """A steady flying state of a free-edged tape on a graded grid."""
    return solve_steady(_model(infinitely_wide=False))


def steady_flat_2d() -> Result:
    """A free-edged tape over a flat module with transducers and friction: its head and
    the designer's readings (summary, derived fields) go through the file too."""
    head = FlatHead((Module(1e-3),), math.radians(2.0), math.radians(2.0),
                    transducers=(0.0, 0.2345e-3), friction=0.2)
    with warnings.catch_warnings():  # coarse on purpose
        warnings.simplefilter("ignore", BearingGridWarning)
        model = BearingModel(TapeParameters(width=3e-3), AirParameters(), velocity=4.0,
                             head=head, nx=INTERVALS_FLAT[0], ny=INTERVALS_FLAT[1],
                             span=1e-3)
    return solve_steady(model)


def transient() -> Result:
    """A few steps after a tension step."""
    return march(solve_steady(_model()), dt=TIME_STEP, steps=STEPS,
                 tension=tension_step(90.0, 100.0), progress=False)


EXAMPLES: dict[str, Callable[[], Result]] = {
    # the 2-D state (graded y, mirror fold) over a flat head with transducers and friction;
    # the cylinder in 2-D and 1-D in test_bearing_kinds
    "bearing": steady_flat_2d,
    "bearing_transient": transient,
}
