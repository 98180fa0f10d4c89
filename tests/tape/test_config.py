"""Tape definitions in TOML: units converted to SI, exact round trips, clear refusals."""

from __future__ import annotations

import pytest

from gyroshell import TapeParameters
from gyroshell.core.errors import ParameterError
from gyroshell.tape.config import config_text, load_config, write_config

TABLE1 = """
[tape]
name = "Table 1"
youngs_modulus = "4 GPa"
poisson = 0.3
thickness = "20 um"
radius = "20 mm"
density = "14 g/m^2"
tension = "0.09 N/mm"
width = "6.35 mm"
length_ratio = 4
spacing = "0.1549 mm"
edges = "free"
load = "0.2 kPa"
velocity = "180 km/h"
"""


def write(tmp_path, text: str):
    path = tmp_path / "tape.toml"
    path.write_text(text, encoding="utf-8")
    return path


def test_units_are_converted_to_si(tmp_path):
    cfg = load_config(write(tmp_path, TABLE1))
    assert cfg.name == "Table 1"
    assert cfg.velocity == pytest.approx(50.0, rel=1e-15)  # km/h: not a decimal prefix
    p = cfg.params
    # decimal prefixes are exact: the same floats as typing the SI numbers
    assert (p.youngs_modulus, p.thickness, p.radius, p.density) == (4e9, 20e-6, 20e-3, 0.014)
    assert (p.tension, p.load, p.spacing, p.width) == (90.0, 200.0, 1.549e-4, 6.35e-3)
    assert p == TapeParameters(**{k: getattr(p, k) for k in ("youngs_modulus", "thickness",
                                                               "density", "tension", "load",
                                                               "spacing")})


def test_plain_numbers_are_si_and_top_level_keys_work(tmp_path):
    cfg = load_config(write(tmp_path, "tension = 75\nthickness = 1.2e-5\n"))
    assert cfg.params == TapeParameters(tension=75.0, thickness=1.2e-5)
    assert cfg.velocity is None and cfg.name is None


@pytest.mark.parametrize("params, velocity", [
    (TapeParameters(), None),
    (TapeParameters(tension=77.123456789, thickness=1.3e-5, length_ratio=19,
                    edges="simply-supported", bending_rigidity=3.3e-6, load_x=0.01,
                    wrap_pressure=True), 12.345678901234567),
])
def test_round_trip_is_exact(tmp_path, params, velocity):
    path = write_config(params, tmp_path / "t.toml", velocity=velocity, name='my "tape"')
    cfg = load_config(path)
    assert cfg.params == params and cfg.velocity == velocity and cfg.name == 'my "tape"'
    assert 'tension = "' in config_text(params)  # units written out


@pytest.mark.parametrize("text, match", [
    ("colour = 3", r"tape.toml: unknown key\(s\) colour; allowed: youngs_modulus"),
    ('[tape]\ntension = 3\n[head]\nx = 1', r"unknown key\(s\) head beside \[tape\]"),
    ('tension = "90 N"', r"tension: unit 'N' is not a unit of N/m \(use one of: N/m"),
    ('thickness = "20 furlongs"', "thickness: unit 'furlongs'"),
    ('thickness = "thin"', r"thickness must look like '<number> <unit>'"),
    ("thickness = -2e-5", r"thickness must be > 0 m"),
    ('velocity = "-3 m/s"', "velocity must be >= 0"),
    ("tension = true", "tension must be a number"),
    ('edges = "clamped"', "edges must be one of free, simply-supported"),
    ("wrap_pressure = 1", "wrap_pressure must be true or false"),
    ("tension = ", "not valid TOML"),
    ("tension = nan", "tension must be finite"),
])
def test_bad_files_are_refused_naming_file_and_key(tmp_path, text, match):
    with pytest.raises(ParameterError, match=match):
        load_config(write(tmp_path, text))


def test_missing_file(tmp_path):
    with pytest.raises(FileNotFoundError, match="no such config file"):
        load_config(tmp_path / "nope.toml")
