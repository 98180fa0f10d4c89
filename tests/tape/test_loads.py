"""The Gaussian load of Eq. 17 and the load-point interpolation."""

from __future__ import annotations

import math

import numpy as np
import pytest

from gyroshell import TapeModel, TapeParameters, gaussian_load
from gyroshell.tape.loads import Ramp, gaussian_exponent


def test_gaussian_decays_to_one_percent_at_five_percent_of_width():
    w = 6.35e-3
    alpha = gaussian_exponent(w)
    assert math.exp(-alpha * (0.05 * w) ** 2) == pytest.approx(0.01)


@pytest.mark.parametrize("ratio", [4, 19])
def test_nodal_forces_add_up_to_the_pressure_integral(ratio):
    """Cell-integrated forces: the total is P_0 π/α exactly on the paper's grid."""
    p = TapeParameters(length_ratio=ratio)
    m = TapeModel(p)
    total = gaussian_load(m.grid, p).sum()
    assert total == pytest.approx(p.load * math.pi / gaussian_exponent(p.width), rel=1e-12)


def test_off_centre_load_is_clipped_at_the_free_edge():
    p = TapeParameters(load_y=0.0)
    full = p.load * math.pi / gaussian_exponent(p.width)
    assert gaussian_load(TapeModel(p).grid, p).sum() == pytest.approx(full / 2, rel=1e-9)


def test_wrap_pressure_option_adds_uniform_minus_t_over_r():
    p0 = TapeParameters(spacing=6.35e-3 / 8)
    p1 = p0.replace(wrap_pressure=True)
    m = TapeModel(p0)
    diff = gaussian_load(m.grid, p1) - gaussian_load(m.grid, p0)
    np.testing.assert_allclose(diff, -p0.tension / p0.radius * m.grid.areas)


def test_load_point_between_nodes_is_interpolated():
    """y = L_y/2 lies between nodes j = 20, 21 on the 41-interval grid."""
    m = TapeModel(TapeParameters())
    g = m.grid
    field = g.Y * 1.0 + g.X * 2.0      # linear fields are interpolated exactly
    w = g.from_field(field)
    x0, y0 = m.params.load_centroid
    assert m.load_point_row @ w == pytest.approx(y0 + 2 * x0, rel=1e-12)


def test_ramp_profile():
    r = Ramp(1e-5)
    assert (r(-1.0), r(5e-6), r(1.0)) == (0.0, 0.5, 1.0)
