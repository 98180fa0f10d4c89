"""Orthotropic and layered tapes on the command line: the options reach the physics (the
orthotropic Navier frequency, derived here), override a --config file, and bad input is one
line with exit code 2; the PEN example file gives its critical speed, modes and flying
height in one command each."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from bearing_cases import LEGACY_CLI

import gyroshell as g
from gyroshell.cli import build_parser, main
from gyroshell.cli.common import parameters_from_args

ROOT = Path(__file__).resolve().parents[2]
PEN = str(ROOT / "studies" / "tapes" / "pen_tape.toml")
#: A coarse Table 1 grid: 16 intervals across, L_x/L_y = 2.
COARSE = ["--spacing", str(6.35e-3 / 16), "--length-ratio", "2"]
#: The PEN tape on 16 intervals across its 12.65 mm, L_x/L_y = 2.
PEN_COARSE = ["--config", PEN, "--spacing", str(12.65e-3 / 16), "--length-ratio", "2"]


def exit_code(argv: list[str]) -> int:
    try:
        return main(argv)
    except SystemExit as exc:
        return int(exc.code)


def parsed(argv: list[str]) -> g.TapeParameters:
    return parameters_from_args(build_parser().parse_args(["static", *argv]))


def test_engineering_constants_and_aliases_set_the_fields():
    p = parsed(["--youngs-modulus-x", "8e9", "--youngs-modulus-y", "5e9", "--shear-modulus",
                "2e9", "--poisson-xy", "0.35", "--membrane-stiffness", "4e4"])
    assert (p.youngs_modulus, p.youngs_modulus_y, p.shear_modulus, p.poisson,
            p.membrane_stiffness) == (8e9, 5e9, 2e9, 0.35, 4e4)
    # D = Q c^3 / 12 with the plane-stress Q of an orthotropic sheet, by hand
    c, det = 20e-6, 1 - 0.35**2 * 5e9 / 8e9
    assert p.bending_matrix.D11 == pytest.approx(8e9 / det * c**3 / 12, rel=1e-14)
    assert p.bending_matrix.D12 == pytest.approx(0.35 * 5e9 / det * c**3 / 12, rel=1e-14)
    assert p.k == 4e4 / p.radius**2


def test_bending_stiffness_takes_four_numbers():
    p = parsed(["--bending-stiffness", "2e-7,1e-7,3e-8,4e-8"])
    assert p.bending_stiffness == (2e-7, 1e-7, 3e-8, 4e-8) and p.D == 2e-7


def test_typed_options_override_the_config_file():
    p = parsed([*PEN_COARSE, "--tension", "70"])
    assert p.tension == 70.0 and len(p.layers) == 3
    assert parsed(PEN_COARSE).tension == 63.0


@pytest.mark.parametrize("argv, message", [
    (["--youngs-modulus", "4e9", "--youngs-modulus-x", "5e9"],
     "--youngs-modulus-x and --youngs-modulus are two names of youngs_modulus"),
    (["--poisson", "0.3", "--poisson-xy", "0.3"], "--poisson-xy and --poisson are two names"),
    (["--youngs-modulus-y", "1e9", "--shear-modulus", "1e9", "--poisson-xy", "2.1"],
     "poisson must be in (-2"),
    (["--youngs-modulus-y", "1e9"], "shear_modulus (G_xy, Pa, > 0) is required"),
    (["--bending-stiffness", "1e-7,1e-7,2e-7,1e-8"], "must be positive definite"),
    (["--bending-stiffness", "1e-7,1e-7,2e-7"], "give four numbers D11,D22,D12,D66"),
    (["--shear-modulus", "-1e9", "--youngs-modulus-y", "1e9"], "shear_modulus must be > 0"),
    ([*PEN_COARSE, "--thickness", "5e-6"], "thickness must be the layer stack's"),
])
def test_bad_material_input_is_one_line_and_exit_2(capsys, argv, message):
    assert exit_code(["static", *COARSE, *argv]) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1 and "Traceback" not in err


def test_lowest_frequency_is_the_orthotropic_navier_one(capsys):
    """All edges simply supported, V = 0: rho w^2 = D11 a^4 + 2 (D12 + 2 D66) a^2 b^2 +
    D22 b^4 + T a^2 + k, a = m pi/L_x, b = n pi/L_y, lowest at m = n = 1 here."""
    ex, ey, gxy, nu, c = 4e9, 16e9, 1e9, 0.3, 20e-6
    argv = ["modes", *COARSE, "--edges", "simply-supported", "--youngs-modulus-y", str(ey),
            "--shear-modulus", str(gxy), "--count", "1", "--json"]
    assert main(argv) == 0
    omega = json.loads(capsys.readouterr().out)["omega"][0]
    det = 1 - nu * nu * ey / ex
    d11, d22, d12, d66 = (q * c**3 / 12 for q in (ex / det, ey / det, nu * ey / det, gxy))
    k = ex / det * c / 0.02**2
    width, rho, tension = 6.35e-3, 0.014, 90.0
    a, b = math.pi / (2 * width), math.pi / width
    navier = math.sqrt((d11 * a**4 + 2 * (d12 + 2 * d66) * a**2 * b**2 + d22 * b**4
                        + tension * a**2 + k) / rho)
    # second order: 7.2e-5, 1.8e-5, 4.6e-6 low on 8, 16, 32 intervals across (measured);
    # the isotropic tape (E_y = E_x) is 16 % lower, so the options did reach the operators
    assert omega == pytest.approx(navier, rel=1e-4)


def run_json(capsys, argv):
    assert main([*argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_pen_tape_critical_speed_modes_and_flying_height_in_one_command_each(capsys):
    params = parsed(PEN_COARSE)
    crit = run_json(capsys, ["critical", *PEN_COARSE])
    assert crit["critical_speed"] == pytest.approx(
        g.critical_speeds(g.TapeModel(params)).critical_speed, rel=1e-9)
    assert crit["string_speed"] == pytest.approx(math.sqrt(63.0 / params.density), rel=1e-12)
    modes = run_json(capsys, ["modes", *PEN_COARSE, "--count", "2"])
    # above the cut-on frequency sqrt(k/rho) of the shell foundation, k = A11/R^2
    assert modes["omega"][0] > math.sqrt(params.lamination.A[0] / 0.02**2 / params.density)
    fly = run_json(capsys, ["bearing", *LEGACY_CLI, "--config", PEN, "--velocity", "4", "--nx",
                            "30",
                            "--ny", "12", "--quiet"])
    assert fly["width"] == 12.65e-3 and fly["tension"] == 63.0
    assert 1e-6 < fly["central_spacing"] < 1e-5  # microns, as the foil law says at 4 m/s


@pytest.mark.slow
@pytest.mark.parametrize("argv", [["critical"], ["modes"],
                                  ["bearing", "--velocity", "4", "--nx", "80", "--ny", "30"]])
def test_pen_tape_full_size(capsys, argv):
    """The file's own grid (40 intervals across); the bearing on a grid of a few seconds
    (its default 404 x 200 takes about a minute)."""
    out = run_json(capsys, [*argv, "--config", PEN, *(["--quiet"] if argv[0] == "bearing"
                                                       else [])])
    if argv[0] == "critical":
        assert abs(out["critical_speed"] - out["divergence_speed"]) < 1e-6 * out["critical_speed"]
        assert out["critical_speed"] <= out["strip_speed"]  # the edges' relief: a bound
    elif argv[0] == "modes":
        assert out["stability"] == "stable" and len(out["omega"]) >= 1
    else:
        assert out["minimum_spacing"] < out["central_spacing"]
