"""Physical limits of the air film: compressibility, slip, finite width."""

from __future__ import annotations

import numpy as np
import pytest
from bearing_cases import FIRST_ORDER, flexible_model

from gyroshell import TapeParameters
from gyroshell.bearing import AirParameters
from gyroshell.bearing.steady import solve_steady

TAPE = TapeParameters()


def _spacing(air, **kw):
    return solve_steady(flexible_model(800, params=TAPE, air=air, **kw)).central_spacing


def test_compressible_tends_to_incompressible_as_ambient_pressure_grows():
    """The film's compressibility number falls like 1/p_a: the gap to the incompressible
    spacing shrinks by the same factor."""
    incompressible = _spacing(AirParameters(compressible=False, mean_free_path=0.0,
                                            rarefaction="first-order"))
    gaps = [abs(_spacing(AirParameters(ambient_pressure=pa, mean_free_path=0.0,
                                       rarefaction="first-order"))
                - incompressible) / incompressible for pa in (1e5, 1e6, 1e7)]
    assert gaps[0] > gaps[1] > gaps[2]
    assert gaps[2] < 1e-3
    slope = np.polyfit(np.log([1e5, 1e6, 1e7]), np.log(gaps), 1)[0]
    assert slope == pytest.approx(-1.0, abs=0.15)


@pytest.mark.parametrize("compressible", [True, False])
def test_slip_lowers_the_spacing(compressible):
    """Slip lets more Poiseuille flow escape the wedge at the same pressure gradient, so
    the film must be thinner to carry the wrap load; the effect vanishes as λ → 0."""
    spacings = [_spacing(AirParameters(compressible=compressible, mean_free_path=lam,
                                       rarefaction="first-order"))
                for lam in (0.0, 16e-9, 64e-9, 256e-9)]
    assert spacings[0] > spacings[1] > spacings[2] > spacings[3]
    drops = spacings[0] - np.array(spacings[1:])
    assert drops[1] / drops[0] == pytest.approx(4.0, rel=0.25)   # first order in λ


@pytest.mark.slow
def test_faster_tape_flies_higher_and_heavier_tension_lower():
    base = _spacing(FIRST_ORDER)
    assert _spacing(FIRST_ORDER, velocity=8.0) > base
    tense = solve_steady(flexible_model(800, params=TAPE.replace(tension=180.0),
                                        air=FIRST_ORDER)).central_spacing
    assert tense < base


def test_tape_at_rest_lies_on_the_head():
    """V → 0: no film; the wrap is in contact at h = σ and the head carries the tension's
    turn (T − ρV²) θ (per unit width), less what the pinned spans take."""
    model = flexible_model(400, params=TAPE, air=FIRST_ORDER, velocity=1e-6)
    sol = solve_steady(model)
    wrap = np.abs(sol.x) < 0.45 * model.params.radius * model.wrap_angle
    assert np.allclose(sol.spacing[wrap, 0], model.air.roughness)
    assert sol.contact_force == pytest.approx(model.effective_tension() * model.wrap_angle,
                                              rel=0.02)
    assert abs(sol.air_force) < 1e-6 * sol.contact_force
