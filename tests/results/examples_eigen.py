"""Small instances of the eigen-solver's result kinds, for the registry's round-trip test.

Each builds in well under a second on a 16 x 8 grid (L_x/L_y = 2).
"""

from __future__ import annotations

from collections.abc import Callable

from gyroshell import TapeModel, TapeParameters
from gyroshell.results.base import Result

#: The tiny tape of every example (279 unknowns: the sparse paths, not the dense one).
PARAMS = TapeParameters(length_ratio=2, spacing=6.35e-3 / 8)
#: Speed of the mode examples, m/s (below critical, about 101 m/s here).
VELOCITY = 10.0
#: Modes per example.
COUNT = 3


def _model() -> TapeModel:
    return TapeModel(PARAMS)


def modes_example():
    from gyroshell import modes

    return modes(_model(), VELOCITY, COUNT)


def damped_modes_example():
    from gyroshell import modes

    return modes(_model(), VELOCITY, COUNT, damping=(50.0, 0.0))


def gyroscopic_modes_example():
    from gyroshell import gyroscopic_modes

    model = _model()
    return gyroscopic_modes(model.M, model.G(VELOCITY), model.K(VELOCITY), COUNT)


def critical_example():
    from gyroshell import critical_speeds

    return critical_speeds(_model())


def divergence_example():
    from gyroshell import divergence

    return divergence(_model())


#: kind -> builder of a small instance of it.
EXAMPLES: dict[str, Callable[[], Result]] = {
    "modes": modes_example,
    "gyroscopic_modes": gyroscopic_modes_example,
    "critical": critical_example,
    "divergence": divergence_example,
}
