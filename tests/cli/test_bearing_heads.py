"""`gyroshell bearing` over real heads: the JSON carries the readings, the files agree with
it, the TOML table and the options fly the same head, the cylinder through --head is
today's answer, and --error-estimate is the difference of the two grids' solves."""

from __future__ import annotations

import json
import math

import pytest
from bearing_cases import LEGACY_CLI

from gyroshell import TapeParameters
from gyroshell.bearing import AirParameters, BearingModel
from gyroshell.bearing.head import FlatHead, Module
from gyroshell.bearing.steady import initial_state, solve_steady
from gyroshell.core.files import read_csv_exact

#: The issue's command, infinitely wide (1-D: a few hundredths of a second).
FLAT_1D = ["bearing", "--head", "flat", "--land-length", "1e-3", "--wrap-in", "2",
           "--wrap-out", "2", "--transducers", "0", "--velocity", "4", "--infinitely-wide",
           "--quiet"]


def _json(cli, argv) -> dict:
    run = cli([*argv, "--json"])
    assert run.code == 0, run.err
    return json.loads(run.out)


def _direct(nx=None):
    head = FlatHead((Module(1e-3),), math.radians(2), math.radians(2), transducers=(0.0,))
    model = BearingModel(TapeParameters(), AirParameters(), velocity=4.0, head=head,
                         infinitely_wide=True, nx=nx)
    return solve_steady(model, z0=initial_state(model))


def test_the_flat_head_json_is_the_direct_solve(cli):
    out = _json(cli, FLAT_1D)
    sol = _direct()
    assert out["central_spacing"] == sol.central_spacing
    (line,) = out["transducer_lines"]
    assert line["x"] == 0.0 and line["minimum"] == sol.transducer_lines[0].minimum
    assert [c["force"] for c in out["corner_forces"]] == [c.force for c in sol.corner_forces]
    assert out["drag"] == sol.drag and out["tension_ratio"] == sol.tension_ratio
    assert "wrap_angle_degrees" not in out or out["wrap_angle_degrees"] == pytest.approx(4.0)


def test_the_cylinder_through_head_is_todays_answer(cli):
    today = _json(cli, ["bearing", "--velocity", "4", "--infinitely-wide", "--quiet"])
    named = _json(cli, ["bearing", "--head", "cylinder", "--wrap-angle", "15", "--velocity",
                        "4", "--infinitely-wide", "--quiet"])
    for key in ("central_spacing", "minimum_spacing", "air_force", "newton_iterations"):
        assert named[key] == today[key]
    assert named["wrap_angle_degrees"] == today["wrap_angle_degrees"] == 15.0


def test_the_toml_head_flies_as_the_options(cli, tmp_path):
    path = tmp_path / "head.toml"
    path.write_text('[tape]\nvelocity = "4 m/s"\n\n[head]\nkind = "flat"\n'
                    'land_length = "1 mm"\nwrap_in = "2 deg"\nwrap_out = "2 deg"\n'
                    'transducers = ["0 mm"]\nfriction = 0.2\n')
    from_file = _json(cli, ["bearing", "--config", path, "--infinitely-wide", "--quiet"])
    typed = _json(cli, [*FLAT_1D, "--friction", "0.2"])
    assert from_file["transducer_lines"] == typed["transducer_lines"]
    assert from_file["friction_drag"] == typed["friction_drag"] > 0.0
    # friction: the Coulomb drag is mu times the contact force
    assert typed["friction_drag"] == pytest.approx(0.2 * typed["contact_force"], rel=1e-12)


def test_out_tables_hold_the_readings_of_the_json(cli, tmp_path):
    out = _json(cli, [*FLAT_1D, "--transducers", "-2e-4,0", "--out-dir", tmp_path / "run"])
    lines = read_csv_exact(tmp_path / "run" / "transducer_lines.csv")
    corners = read_csv_exact(tmp_path / "run" / "corners.csv")
    assert lines.x_m.tolist() == [line["x"] for line in out["transducer_lines"]]
    assert lines.spacing_m.tolist() == [line["minimum"] for line in out["transducer_lines"]]
    assert corners.x_m.tolist() == [c["x"] for c in out["corner_forces"]]
    assert corners.contact_force_N_per_m.tolist() == [c["force"] for c in out["corner_forces"]]
    land = [t["height"] for t in out["tents"] if t["side"] == "land"]
    assert corners.land_tent_height_m.tolist() == land


def test_error_estimate_is_the_difference_from_half_the_intervals(cli):
    out = _json(cli, [*FLAT_1D, "--error-estimate"])
    error = out["grid_error"]
    assert error["coarse_nx"] == out["nx"] // 2 and error["coarse_ny"] is None
    fine, coarse = _direct(out["nx"]), _direct(out["nx"] // 2)
    assert error["central_spacing"] == fine.central_spacing - coarse.central_spacing
    (line,) = error["transducer_lines"]
    assert line["minimum"] == (fine.transducer_lines[0].minimum
                               - coarse.transducer_lines[0].minimum)


def test_error_estimate_says_in_one_line_when_it_cannot_halve_the_width(cli):
    """ny = 8 is already the fewest intervals across: the coarse grid keeps it, and the
    one warning line says so, naming ny and the coarse grid; nx = 64 halves silently."""
    run = cli(["bearing", *LEGACY_CLI, "--velocity", "4", "--width", "3e-3", "--nx", "64",
               "--ny", "8",
               "--error-estimate", "--quiet", "--json"])
    assert run.code == 0, run.err
    error = json.loads(run.out)["grid_error"]
    assert (error["coarse_nx"], error["coarse_ny"]) == (32, 8)
    said = [line for line in run.error_lines if "--error-estimate" in line]
    assert len(said) == 1
    assert "cannot halve ny = 8 (the fewest is 8)" in said[0] and "nx = " not in said[0]
    assert "32 x 8 intervals" in said[0]
    quiet = cli([*FLAT_1D, "--error-estimate", "--json"])
    assert not any("--error-estimate" in line for line in quiet.error_lines)


def test_plot_draws_the_head_figure(cli, tmp_path):
    png = tmp_path / "head.png"
    run = cli([*FLAT_1D, "--plot", png])
    assert run.code == 0, run.err
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 20_000


def test_text_output_names_the_readings(cli):
    run = cli(FLAT_1D)
    assert run.code == 0, run.err
    assert run.out.count("corner:") == 2 and "transducer line:  x = 0.0000e+00 m" in run.out
    assert "tension rise" in run.out


@pytest.mark.slow
def test_two_dimensional_flat_head_reads_its_line_across_the_width(cli, tmp_path):
    argv = ["bearing", "--head", "flat", "--land-length", "1e-3", "--wrap-in", "2",
            "--wrap-out", "2", "--transducers", "0", "--velocity", "4", "--nx", "60", "--ny",
            "24", "--quiet", "--out-dir", tmp_path / "run"]
    out = _json(cli, argv)
    (line,) = out["transducer_lines"]
    across = read_csv_exact(tmp_path / "run" / "transducer_lines.csv")
    assert len(across) == out["ny"] + 1 and across.y_m.is_monotonic_increasing
    assert line["minimum"] == across.spacing_m.min() <= line["mean"]
    # the free edges let the suction out: the line is higher at the edges than mid-width
    assert across.spacing_m.iloc[0] > line["centre"] and across.spacing_m.iloc[-1] > line["centre"]


@pytest.mark.slow
def test_a_wrapped_corner_radius_answers_as_the_direct_solve(cli):
    """--corner-radius 2.5e-3 at 2° (r_c θ_c = 0.48 bending lengths: the tape wraps the
    arcs, once refused) answers with the direct solve's numbers (2.8 s: pseudo-time)."""
    out = _json(cli, [*FLAT_1D, "--corner-radius", "2.5e-3"])
    head = FlatHead((Module(1e-3, corner_radius=2.5e-3),), math.radians(2), math.radians(2),
                    transducers=(0.0,))
    model = BearingModel(TapeParameters(), AirParameters(), velocity=4.0, head=head,
                         infinitely_wide=True)
    assert model.wrapped_corners == (0, 1)
    direct = solve_steady(model)
    assert out["central_spacing"] == pytest.approx(direct.central_spacing, rel=1e-9)
    assert out["contact_force"] == pytest.approx(float(direct.contact.sum()), abs=1e-12)


def test_small_wrap_warns_in_one_line_through_the_whole_solve(cli_process):
    """A 1° cylinder (below its smallest valid wrap, 6.24° here) on a 2-D tape: the
    solve's start and continuation rebuild the model, and still one warning line, in the
    CLI's form, says where the model stops holding."""
    run = cli_process(["bearing", "--wrap-angle", "1", "--velocity", "4", "--width", "3e-3",
                       "--nx", "96", "--ny", "32", "--span", "2e-3", "--quiet", "--json"])
    assert run.code == 0, run.err
    said = [line for line in run.err.splitlines() if "stops holding" in line]
    assert len(said) == 1 and said[0].startswith("gyroshell: warning: a wrap of 1 deg is "
                                                 "below 6.24 deg")
    assert "Warning:" not in run.err
