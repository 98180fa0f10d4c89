"""Orthotropic and layered tapes in TOML files: the new keys with their units, the
``[[layer]]`` array bottom up, and refusals that name the file, the layer and the key."""

from __future__ import annotations

from pathlib import Path

import pytest

from gyroshell import TapeParameters
from gyroshell.core.errors import ParameterError
from gyroshell.tape.config import config_text, load_config

ROOT = Path(__file__).resolve().parents[2]
PEN = ROOT / "studies" / "tapes" / "pen_tape.toml"

LAYER = """
[[layer]]
thickness = "{t}"
youngs_modulus_x = "{ex}"
youngs_modulus_y = "{ey}"
shear_modulus = "{g}"
poisson_xy = {nu}
density = "{rho}"
"""
#: Two layers, bottom up: (thickness, E_x, E_y, G_xy, nu_xy, density) as typed and in SI.
TYPED = (("0.5 um", "3 GPa", "2 GPa", "1 GPa", 0.3, "1.5 g/cm^3"),
         ("4.5 um", "8 GPa", "5.5 GPa", "2000 MPa", 0.35, "1360 kg/m^3"))
SI = ((0.5e-6, 3e9, 2e9, 1e9, 0.3, 1500.0), (4.5e-6, 8e9, 5.5e9, 2e9, 0.35, 1360.0))
LAYER_KEYS = ("thickness", "youngs_modulus_x", "youngs_modulus_y", "shear_modulus",
              "poisson_xy", "density")


def stack_text(layers=TYPED) -> str:
    return "".join(LAYER.format(t=t, ex=ex, ey=ey, g=g, nu=nu, rho=rho)
                   for t, ex, ey, g, nu, rho in layers)


def write(tmp_path, text: str) -> Path:
    path = tmp_path / "tape.toml"
    path.write_text(text, encoding="utf-8")
    return path


def test_layers_are_read_bottom_up_in_si(tmp_path):
    path = write(tmp_path, '[tape]\ntension = "60 N/m"\n' + stack_text())
    params = load_config(path).params
    assert [tuple(layer.as_dict().values()) for layer in params.layers] == list(SI)
    # the stack's thickness and areal density, summed by hand
    assert params.thickness == pytest.approx(5e-6, rel=1e-15)
    assert params.density == pytest.approx(0.5e-6 * 1500 + 4.5e-6 * 1360, rel=1e-15)
    assert params.tension == 60.0


def test_homogeneous_orthotropic_keys_with_units(tmp_path):
    path = write(tmp_path, """
[tape]
youngs_modulus_x = "8 GPa"
youngs_modulus_y = "5.5 GPa"
shear_modulus = "2 GPa"
poisson_xy = 0.3
membrane_stiffness = "40 kN/m"
""".replace("kN/m", "N/mm"))
    p = load_config(path).params
    assert (p.youngs_modulus, p.youngs_modulus_y, p.shear_modulus, p.poisson) == \
        (8e9, 5.5e9, 2e9, 0.3)
    assert p.membrane_stiffness == 4e4
    assert p.k == 4e4 / p.radius**2


def test_bending_stiffness_is_a_list_of_four(tmp_path):
    path = write(tmp_path, '[tape]\nbending_stiffness = ["2e-7 N*m", 1e-7, "30 nN*m", 4e-8]\n'
                 .replace('"30 nN*m"', '"3e-8 N m"'))
    assert load_config(path).params.bending_stiffness == (2e-7, 1e-7, 3e-8, 4e-8)


@pytest.mark.parametrize("text, message", [
    ('[tape]\nthickness = "5 um"\n' + stack_text(),
     "thickness: the [[layer]] stack gives the tape's thickness"),
    ('[tape]\ndensity = "0.01 kg/m^2"\npoisson_xy = 0.3\n' + stack_text(),
     "density, poisson_xy: the [[layer]] stack gives"),
    ('[tape]\n' + stack_text().replace('thickness = "4.5 um"', 'thickness = "-4.5 um"'),
     "[[layer]] 2: thickness must be > 0 m, got -4.5e-06"),
    ('[tape]\n' + stack_text().replace('density = "1360 kg/m^3"', 'density = "1360 kg/m^2"'),
     "[[layer]] 2: density: unit 'kg/m^2' is not a unit of kg/m^3"),
    ('[tape]\n' + stack_text().replace("poisson_xy = 0.3", "poisson_xy = 0.3\ncolour = 1"),
     "[[layer]] 1: unknown key(s) colour"),
    ('[tape]\n' + stack_text().replace('shear_modulus = "1 GPa"\n', ''),
     "[[layer]] 1: missing key(s) shear_modulus"),
    ('[tape]\n' + stack_text().replace("poisson_xy = 0.35", "poisson_xy = 1.3"),
     "[[layer]] 2: poisson_xy must be in ("),
    ("layer = 3\n", "layer must be an array of tables"),
    ("layer = []\n", "[[layer]]: the stack has no layer"),
    ('[tape]\nyoungs_modulus = "4 GPa"\nyoungs_modulus_x = "4 GPa"\n',
     "youngs_modulus_x and youngs_modulus are two names of youngs_modulus"),
    ('[tape]\nbending_stiffness = [1e-7, 1e-7]\n',
     "bending_stiffness must be a list of 4 values"),
    ('[tape]\nbending_stiffness = [1e-7, 1e-7, 2e-7, 1e-8]\n',
     "bending_stiffness must be positive definite"),
    ('[tape]\nyoungs_modulus_y = "2 GPa"\n', "shear_modulus (G_xy, Pa, > 0) is required"),
])
def test_refusals_name_the_file_the_layer_and_the_key(tmp_path, text, message):
    path = write(tmp_path, text)
    with pytest.raises(ParameterError) as info:
        load_config(path)
    assert str(info.value).startswith(f"{path}: ")
    assert message in str(info.value)
    assert "\n" not in str(info.value)


@pytest.mark.parametrize("params", [
    TapeParameters.from_layers([dict(zip(LAYER_KEYS, si, strict=True)) for si in SI],
                               width=12.65e-3, tension=63.0),
    TapeParameters(youngs_modulus_y=1.0 / 3.0 * 1e10, shear_modulus=1.7e9),
    TapeParameters(bending_stiffness=(2e-7, 1.0 / 7.0 * 1e-6, 3e-8, 4e-8),
                   membrane_stiffness=3.3e4),
], ids=["layers", "moduli", "stiffnesses"])
def test_written_files_read_back_equal(tmp_path, params):
    back = load_config(write(tmp_path, config_text(params, velocity=4.0))).params
    assert back == params
    assert back.bending_matrix == params.bending_matrix


def test_the_pen_example_is_a_three_layer_unsymmetric_tape():
    cfg = load_config(PEN)
    p = cfg.params
    assert len(p.layers) == 3 and p.width == 12.65e-3
    base = p.layers[1]
    assert base.youngs_modulus_x > base.youngs_modulus_y  # tensilized along the tape
    assert any(p.lamination.B)  # coat on top, back coat below: B != 0
    # thickness and areal density summed by hand over the file's layers
    assert p.thickness == pytest.approx(0.5e-6 + 4.5e-6 + 0.8e-6, rel=1e-14)
    assert p.density == pytest.approx(0.5e-6 * 1500 + 4.5e-6 * 1360 + 0.8e-6 * 4000,
                                      rel=1e-14)
    assert 50.0 <= p.tension <= 80.0
