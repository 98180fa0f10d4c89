"""Parameters: Table 1 defaults, derived D and k, and the documented validation errors."""

from __future__ import annotations

import math

import numpy as np
import pytest

from gyroshell import Grid, ParameterError, TapeModel, TapeParameters, solve_static
from gyroshell.core.errors import SupercriticalError


def test_table1_defaults_and_derived_values():
    p = TapeParameters()
    assert p.D == pytest.approx(2.9e-6, rel=0.02)           # Table 1: 2.9e-6 N m
    assert p.k == pytest.approx(219.8e6, rel=1e-3)          # Table 1: 219.8e6 N/m^3
    assert p.wrap_pressure_value == pytest.approx(4500.0)   # T/R
    assert 2 * math.pi / p.foundation_frequency == pytest.approx(50e-6, rel=0.01)
    assert p.string_speed == pytest.approx(80.2, abs=0.1)   # Wickert & Mote's ~80 m/s


def test_overrides_allow_limit_cases():
    p = TapeParameters(foundation_stiffness=0.0, bending_rigidity=1e-15)
    assert p.k == 0.0 and p.D == 1e-15


def test_grid_takes_nearest_whole_intervals_and_reports_spacing():
    g = Grid.from_parameters(TapeParameters(length_ratio=19))
    assert (g.nx, g.ny) == (779, 41)
    assert g.hy == pytest.approx(6.35e-3 / 41)
    assert g.hx == pytest.approx(19 * 6.35e-3 / 779)


def test_field_vector_round_trip(rng):
    g = Grid.from_parameters(TapeParameters(spacing=6.35e-3 / 8, length_ratio=2))
    v = rng.standard_normal(g.unknowns)
    f = g.to_field(v)
    assert f.shape == g.shape
    assert np.all(f[0] == 0) and np.all(f[-1] == 0)
    np.testing.assert_array_equal(g.from_field(f), v)


@pytest.mark.parametrize(
    ("field", "value", "match"),
    [
        ("thickness", -1e-6, "thickness must be > 0"),
        ("thickness", 0.0, "thickness must be > 0"),
        ("width", 0.0, "width must be > 0"),
        ("radius", -1.0, "radius must be > 0"),
        ("density", 0.0, "density must be > 0"),
        ("youngs_modulus", -4e9, "youngs_modulus must be > 0"),
        ("poisson", 0.5, r"poisson must be in \(-1, 0.5\)"),
        ("poisson", -1.0, r"poisson must be in \(-1, 0.5\)"),
        ("youngs_modulus", float("nan"), "youngs_modulus must be finite"),
        ("tension", float("inf"), "tension must be finite"),
        ("tension", -1.0, "tension must be >= 0"),
        ("spacing", 1e-3, "spacing must leave at least 8 intervals across the width"),
        ("length_ratio", 0.0, "length_ratio must be > 0"),
        ("length_ratio", -4.0, "length_ratio must be > 0"),
        ("bending_rigidity", 0.0, "bending_rigidity must be > 0"),
        ("foundation_stiffness", -1.0, "foundation_stiffness must be >= 0"),
        ("load_y", 1.0, r"load_y must be in \[0, "),
        ("edges", "clamped", "edges must be one of free, simply-supported"),
    ],
)
def test_bad_input_gives_documented_error(field, value, match):
    with pytest.raises(ParameterError, match=match):
        TapeParameters(**{field: value})


def test_negative_velocity_is_refused():
    with pytest.raises(ParameterError, match="velocity must be >= 0"):
        solve_static(TapeModel(TapeParameters(spacing=6.35e-3 / 8)), -1.0)


def test_static_refuses_at_and_above_critical_speed_and_names_it():
    model = TapeModel(TapeParameters(spacing=6.35e-3 / 10, length_ratio=2))
    with pytest.raises(SupercriticalError, match=r"critical speed 10\d\.\d+ m/s") as info:
        solve_static(model, 110.0)
    assert 99.0 < info.value.critical_speed < 101.0
