"""The finite-difference grid against the tape it discretizes."""

import pytest

from gyroshell import TapeModel, TapeParameters
from gyroshell.core.errors import ParameterError
from gyroshell.tape.grid import Grid


def test_a_model_grid_must_span_its_tape():
    """A grid may refine the tape's spacing (the refinement studies do), not change the
    tape's size or its lateral edges: those would make the model's geometry disagree with
    its parameters (and with the saved file's)."""
    p = TapeParameters(length_ratio=2, spacing=6.35e-3 / 8)
    finer = Grid(p.length, p.width, 32, 16, p.edges)
    assert TapeModel(p, finer).grid is finer
    for grid, message in ((Grid(2 * p.length, p.width, 32, 8), "grid length"),
                          (Grid(p.length, 0.9 * p.width, 16, 8), "grid width"),
                          (Grid(p.length, p.width, 16, 8, "simply-supported"), "grid edges")):
        with pytest.raises(ParameterError, match=message):
            TapeModel(p, grid)
