"""`gyroshell study`, `--config` and `--save` through main([...])."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

import gyroshell
from gyroshell import TapeModel, TapeParameters, modes, run_study, solve_static
from gyroshell.cli import main
from gyroshell.core.files import read_csv_exact
from gyroshell.tape.config import write_config

COARSE = ["--length-ratio", "4", "--spacing", str(6.35e-3 / 8)]
BASE = TapeParameters(length_ratio=4, spacing=6.35e-3 / 8)


def exit_code(argv: list[str]) -> int:
    try:
        return main(argv)
    except SystemExit as exc:
        return int(exc.code)


@pytest.mark.slow
def test_study_csv_nc_png_and_the_same_rows_as_the_api(tmp_path, capsys):
    out, nc, png = tmp_path / "s.csv", tmp_path / "s.nc", tmp_path / "map.png"
    argv = ["study", *COARSE, "--vary", "velocity=0,60,104", "--vary", "tension=70:90:2",
            "--compute", "modes,critical", "--workers", "1", "--quiet",
            "--out", str(out), "--save", str(nc), "--plot", str(png)]
    assert main(argv) == 0
    table = read_csv_exact(out, keep_default_na=False, na_values=["NaN"])  # bit for bit
    api = run_study(BASE, vary={"velocity": [0.0, 60.0, 104.0], "tension": [70.0, 90.0]},
                    compute=["modes", "critical"], workers=1)
    pd.testing.assert_frame_equal(table, api.table, check_exact=True)
    assert list(table.columns[:3]) == ["point", "velocity", "tension"]
    assert "critical_speed" in table and set(table["stability"]) == {"stable", "divergence"}
    loaded = gyroshell.load(nc)
    pd.testing.assert_frame_equal(loaded.table, api.table, check_exact=True)
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "6 points (6 computed" in capsys.readouterr().out


def test_config_file_sets_the_tape_and_options_override_it(tmp_path, capsys):
    cfg = write_config(BASE.replace(tension=70.0), tmp_path / "tape.toml", velocity=30.0)
    assert main(["static", "--config", str(cfg), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    sol = solve_static(TapeModel(BASE.replace(tension=70.0)), 30.0)
    assert out["velocity"] == 30.0 and out["load_point_deflection"] == sol.load_point_deflection
    assert main(["static", "--config", str(cfg), "--velocity", "10", "--tension", "90",
                 "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["load_point_deflection"] == solve_static(TapeModel(BASE), 10.0
                                                        ).load_point_deflection


@pytest.mark.slow
@pytest.mark.parametrize("command", [["static"], ["modes", "--count", "3"],
                                     ["sweep", "--velocities", "0,50", "--count", "2"]])
def test_save_option_writes_a_loadable_result(tmp_path, command, capsys):
    path = tmp_path / "r.nc"
    speed = [] if command[0] == "sweep" else ["--velocity", "40"]  # sweep refuses --velocity
    assert main([*command, *COARSE, *speed, "--save", str(path)]) == 0
    back = gyroshell.load(path)
    model = TapeModel(BASE)
    if command[0] == "static":
        assert np.array_equal(back.w, solve_static(model, 40.0).w)
    elif command[0] == "modes":
        assert np.array_equal(back.eigenvalues, modes(model, 40.0, 3).eigenvalues)
    else:
        assert isinstance(back, gyroshell.SweepResult)  # the sweep, not its bare table
        assert list(back.table["velocity"].unique()) == [0.0, 50.0]
        assert back.velocities.tolist() == [0.0, 50.0] and back.params == BASE
    assert gyroshell.results.base.metadata(path)["parameters"] == BASE


@pytest.mark.slow
def test_transient_save(tmp_path, capsys):
    path = tmp_path / "t.nc"
    assert main(["transient", *COARSE, "--velocity", "40", "--steps", "20", "--dt", "2e-6",
                 "--quiet", "--save", str(path)]) == 0
    assert gyroshell.load(path).steps == 20


@pytest.mark.parametrize(("argv", "match"), [
    (["--vary", "colour=1,2", "--compute", "modes"], "cannot vary 'colour'"),
    (["--vary", "tension", "--compute", "modes"], "--vary needs NAME=VALUES"),
    (["--vary", "tension=1:2", "--compute", "modes"], "use START:STOP:NUM"),
    (["--vary", "tension=1,x", "--compute", "modes"], "not a number"),
    (["--vary", "tension=80", "--compute", "nothing"], "compute must be one or more"),
    (["--vary", "thickness=-1", "--compute", "modes"], "thickness must be > 0"),
    (["--vary", "tension=80", "--compute", "modes", "--out", "/nope/s.csv"],
     "--out /nope/s.csv: folder /nope does not exist"),
    (["--vary", "tension=80", "--compute", "modes", "--out", "s.txt"], "--out: use a .csv"),
    (["--vary", "tension=80", "--vary", "velocity=1", "--compute", "critical", "--plot",
      "m.png", "--quantity", "omega_1"],
     "--quantity omega_1: this study has no such column; choose one of critical_speed, "
     "divergence_speed"),
    (["--vary", "tension=80", "--compute", "modes", "--scheduler", "nowhere"],
     "tcp://HOST:PORT"),
    (["--vary", "tension=80", "--compute", "modes", "--config", "/nope.toml"],
     "no such config file"),
])
def test_user_errors_exit_2_with_one_line(tmp_path, monkeypatch, capsys, argv, match):
    monkeypatch.chdir(tmp_path)
    assert exit_code(["study", *COARSE, "--workers", "1", *argv]) == 2
    err = capsys.readouterr().err
    assert match in err and len(err.strip().splitlines()) == 1 and "Traceback" not in err
    assert not list(tmp_path.iterdir()), "nothing written on a user error"


def test_bad_config_exits_2_naming_the_key(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_text('tension = "90 N"\n')
    assert exit_code(["modes", "--config", str(bad)]) == 2
    err = capsys.readouterr().err
    assert "tension: unit 'N' is not a unit of N/m" in err and len(err.splitlines()) == 1


def test_vary_values_may_carry_units(tmp_path, capsys):
    out = tmp_path / "t.csv"
    assert main(["study", *COARSE, "--vary", "thickness=20um,30 um", "--vary",
                 "tension=0.09N/mm", "--compute", "static", "--workers", "1", "--quiet",
                 "--out", str(out)]) == 0
    table = pd.read_csv(out)
    assert list(table["thickness"]) == [20e-6, 30e-6] and set(table["tension"]) == {90.0}
    assert exit_code(["study", *COARSE, "--vary", "thickness=20N", "--compute", "static",
                      "--workers", "1"]) == 2
    assert "unit 'N' is not a unit of m" in capsys.readouterr().err


@pytest.mark.slow
def test_campbell_command(tmp_path, capsys):
    out, png = tmp_path / "c.csv", tmp_path / "c.png"
    assert main(["campbell", "--length-ratio", "1.5", "--spacing", str(6.35e-3 / 10),
                 "--edges", "simply-supported", "--foundation-stiffness", "0",
                 "--velocities", "0:75:16", "--count", "5", "--circumference", "0.01",
                 "--out", str(out), "--plot", str(png)]) == 0
    text = capsys.readouterr().out
    assert "crossing: branches" in text and "resonance: order 1" in text
    table = pd.read_csv(out)
    assert list(table.columns) == ["velocity", "branch", "rank", "omega", "growth_rate", "mac"]
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert exit_code(["campbell", *COARSE, "--circumference", "0.01", "--orders", "x"]) == 2
    assert "--orders must be integers" in capsys.readouterr().err


@pytest.mark.slow
def test_study_and_campbell_json_print_the_results_summary(tmp_path, capsys):
    from gyroshell.studies.campbell import campbell

    argv = ["study", *COARSE, "--vary", "velocity=0,104", "--compute", "modes,static",
            "--workers", "1", "--quiet", "--json"]
    assert main(argv) == 0
    out = json.loads(capsys.readouterr().out)
    api = run_study(BASE, vary={"velocity": [0.0, 104.0]}, compute=["modes", "static"],
                    workers=1)
    expected = api.summary()
    assert out.keys() == expected.keys() and out.pop("seconds") > 0
    assert out == {k: v for k, v in expected.items() if k != "seconds"}
    assert out["failed"] == 1  # static above critical
    assert main(["campbell", *COARSE, "--velocities", "0:10:3", "--count", "2", "--quiet",
                 "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out == campbell(TapeModel(BASE), [0.0, 5.0, 10.0], 2).summary()
    assert out["branches"] == 2 and out["speeds"] == 3 and out["critical_speed"] > 10.0


@pytest.mark.slow
def test_campbell_saves_the_whole_diagram_and_runs_on_workers(tmp_path, capsys):
    from gyroshell.results.base import read

    nc = tmp_path / "c.nc"
    base_argv = ["campbell", *COARSE, "--velocities", "0:30:4", "--count", "2", "--quiet"]
    assert main([*base_argv, "--out", str(nc)]) == 0
    one = read(nc)
    assert one.params == BASE and one.info["workers"] == 1
    assert main([*base_argv, "--workers", "2", "--out", str(nc)]) == 0
    two = read(nc)
    assert np.allclose(two.frame["omega"], one.frame["omega"], rtol=1e-10, atol=0)
    assert (two.frame["branch"] == one.frame["branch"]).all()
    assert "wrote" in capsys.readouterr().out
