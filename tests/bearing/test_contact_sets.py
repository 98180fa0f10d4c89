"""Contact sets that move many nodes per Newton iteration (issue #19): a 2-D tape over
two modules, the second raised by 0.3 µm, touches down on that land over a zone of the
plate. The generic Newton with the wall as bounds (its reduced-space active set,
:func:`gyroshell.linalg.newton.newton`) reaches it in a few iterations.

The state must satisfy the contact conditions exactly: h >= σ on every node, λ >= 0 and
λ = 0 wherever h > σ (complementarity), with λ the contact forces."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from bearing_cases import FIRST_ORDER, HARD

from gyroshell import TapeParameters
from gyroshell.bearing import BearingModel, steady
from gyroshell.bearing.head import FlatHead, Module
from gyroshell.bearing.model import BearingGridWarning

DEG = math.pi / 180.0
AIR = FIRST_ORDER
#: Two modules, the second raised: a 2 mm tape touches down on the second land.
TWO = FlatHead((Module(0.8e-3), Module(0.5e-3, height=0.3e-6)), 1.5 * DEG, 3 * DEG,
               gaps=(0.2e-3,))
#: Newton iterations allowed for the 2-D solve (the issue's bound; measured 8).
MAX_NEWTON = 30


def _model(nx=96, ny=16):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", BearingGridWarning)
        return BearingModel(TapeParameters(width=2e-3), AIR, velocity=4.0, head=TWO,
                            nx=nx, ny=ny, contact=HARD)


@pytest.fixture(scope="module")
def solved():
    model = _model()
    return model, steady.solve_steady(model)


def test_land_touchdown_converges_in_few_newton_iterations(solved):
    model, sol = solved
    assert sol.info.iterations <= MAX_NEWTON
    assert not sol.info.pseudo_time and not sol.info.continuation
    # the land zone: many more nodes than the corner lines of the two modules
    assert sol.contact_nodes > 2 * model.nc


def test_contact_conditions_hold_exactly(solved):
    """h − σ >= 0 to round-off, λ >= 0, λ = 0 where h > σ (beyond round-off)."""
    model, sol = solved
    sigma = HARD.roughness
    h = sol.spacing[1:-1, :].ravel()
    lam = sol.contact
    floor = 1e-12 * sigma
    assert h.min() >= sigma - floor
    assert lam.min() >= 0.0
    assert np.all(lam[h > sigma + floor] == 0.0)
    assert np.all(np.abs(h[lam > 0.0] - sigma) <= floor)
