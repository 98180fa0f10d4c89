"""The 1-D flexible, incompressible limit against the classical foil-bearing theory
(Blok & van Rossum 1953; Eshel & Elrod 1965), with constants derived here from the scaled
third-order equation, and the observed order of convergence."""

from __future__ import annotations

import math

import numpy as np
import pytest
from bearing_cases import (
    CLASSICAL_AIR,
    FLEXIBLE,
    WRAP,
    classical_foil_constants,
    flexible_model,
    foil_scale,
)
from convergence import observed_order

from gyroshell.bearing import BearingModel, Grading
from gyroshell.bearing.steady import solve_steady

# Slow as a whole: the foil-bearing constants from refined strips (about 11 s of module fixtures).
pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def constants():
    return classical_foil_constants()


def test_classical_constants_are_the_known_ones(constants):
    C, h_min = constants
    # Sanity of the derivation itself (Eshel & Elrod quote 0.643 and 0.716).
    assert C == pytest.approx(0.643, abs=1e-3)
    assert h_min == pytest.approx(0.716, abs=1e-3)


@pytest.mark.slow
@pytest.mark.parametrize("velocity", [2.0, 8.0])
def test_central_spacing_follows_two_thirds_law(constants, velocity):
    C, _ = constants
    model = flexible_model(1600, velocity=velocity)
    sol = solve_steady(model)
    assert sol.central_spacing / foil_scale(model) == pytest.approx(C, rel=3e-3)


def test_exit_constriction_depth(constants):
    _, h_min = constants
    sol = solve_steady(flexible_model(3200))
    assert sol.minimum_spacing / sol.central_spacing == pytest.approx(h_min, rel=2e-3)
    x_min, _ = sol.minimum_location
    half_wrap = 0.5 * sol.model.params.radius * sol.model.wrap_angle
    assert 0.5 * half_wrap < x_min < 1.5 * half_wrap    # at the exit, downstream


@pytest.mark.slow
def test_spacing_scales_with_speed_to_the_two_thirds():
    """h₀ ∝ (6μV/(T − ρV²))^(2/3): the slope against ε on log-log axes."""
    models = [flexible_model(1600, velocity=v) for v in (2.0, 4.0, 8.0)]
    h = [solve_steady(m).central_spacing for m in models]
    eps = [m.velocity / m.effective_tension() for m in models]
    slope = np.polyfit(np.log(eps), np.log(h), 1)[0]
    assert slope == pytest.approx(2 / 3, abs=3e-3)


@pytest.mark.slow
def test_second_order_convergence_flexible():
    nxs = [400, 800, 1600, 3200]
    h = np.array([solve_steady(flexible_model(n)).central_spacing for n in nxs])
    order = observed_order(1.0 / np.array(nxs[:-1]), np.abs(np.diff(h)))
    assert order == pytest.approx(2.0, abs=0.2)


def test_second_order_convergence_real_tape_compressible():
    from gyroshell import TapeParameters
    from gyroshell.bearing import AirParameters, BearingModel

    def spacing(nx):
        m = BearingModel(TapeParameters(), AirParameters(), velocity=4.0,
                         wrap_angle=math.radians(15), infinitely_wide=True, nx=nx)
        return solve_steady(m).central_spacing

    nxs = [300, 600, 1200, 2400]
    h = np.array([spacing(n) for n in nxs])
    order = observed_order(1.0 / np.array(nxs[:-1]), np.abs(np.diff(h)))
    assert order == pytest.approx(2.0, abs=0.3)


def test_classical_constants_on_a_graded_strip(constants):
    """The strip's grid graded 4× towards the wrap corners (the film's entrance and exit
    constrictions): half the intervals of the uniform 3200 give both classical constants
    as closely."""
    C, h_min = constants
    model = BearingModel(FLEXIBLE, CLASSICAL_AIR, velocity=4.0, wrap_angle=WRAP,
                         infinitely_wide=True, nx=1600, grading=Grading(x_ratio=4.0))
    assert model.graded and np.ptp(np.diff(model.x)) > 0.5 * np.diff(model.x).max()
    sol = solve_steady(model)
    assert sol.central_spacing / foil_scale(model) == pytest.approx(C, rel=3e-3)
    assert sol.minimum_spacing / sol.central_spacing == pytest.approx(h_min, rel=2e-3)


def test_flexible_foil_converges_to_the_classical_spacing_as_bending_vanishes(constants):
    """D -> 0 on the default grid (no nx given; the bending length falls from 0.3 to 3e-4
    film lengths): h₀/(R ε^(2/3)) approaches Eshel & Elrod's 0.643 monotonically, each
    hundredfold drop of D bringing it closer, and ends within the finite-span offset
    (0.12 %) of the classical value."""
    C, _ = constants
    ratios = []
    for D in (1e-6, 1e-8, 1e-10, 1e-12):
        model = BearingModel(FLEXIBLE.replace(bending_rigidity=D), CLASSICAL_AIR,
                             velocity=4.0, wrap_angle=WRAP, infinitely_wide=True)
        ratios.append(solve_steady(model).central_spacing / foil_scale(model))
    steps = np.abs(np.diff(ratios))
    assert np.all(steps[1:] < 0.2 * steps[:-1])          # converging, each step 10x smaller
    assert ratios[-1] == pytest.approx(C, rel=3e-3)
