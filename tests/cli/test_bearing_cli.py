"""`gyroshell bearing`: JSON keys, files, refusals with one line and exit code 2."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest
from bearing_cases import LEGACY_CLI

from gyroshell.cli import main


def _json(capsys, argv):
    assert main(argv) == 0
    return json.loads(capsys.readouterr().out)


def test_infinitely_wide_json(capsys):
    out = _json(capsys, ["bearing", "--velocity", "4", "--wrap-angle", "15",
                         "--infinitely-wide", "--json"])
    assert 1e-6 < out["minimum_spacing"] < out["central_spacing"] < 5e-6
    assert out["contact_force"] == 0.0 and out["newton_iterations"] >= 2
    assert out["minimum_x"] > 0                              # at the exit
    assert out["central_pressure"] > out["wrap_pressure"] > 0


@pytest.mark.slow
def test_touch_down_reported_in_json(capsys):
    """A slow 3 mm tape touches down: the JSON reports the contact force and nodes, the
    minimum at the roughness height, and that Newton reached it directly."""
    out = _json(capsys, ["bearing", *LEGACY_CLI, "--velocity", "0.2", "--wrap-angle", "15",
                         "--width",
                         "3e-3", "--nx", "160", "--ny", "48", "--json"])
    assert out["contact_force"] > 0.0 and out["contact_nodes"] > 0
    assert out["minimum_spacing"] == pytest.approx(out["roughness"], rel=1e-9)
    assert out["pseudo_time_steps"] == [] and out["continuation_speeds"] == []
    assert out["air_force"] > 0.0


@pytest.mark.slow
def test_two_dimensional_json_files_and_plot(capsys, tmp_path):
    png = tmp_path / "b.png"
    out = _json(capsys, ["bearing", "--velocity", "4", "--wrap-angle", "15", "--nx", "80",
                         "--ny", "10", "--json", "--out-dir", str(tmp_path / "run"),
                         "--plot", str(png)])
    assert out["ny"] == 10 and out["minimum_y"] is not None
    assert out["minimum_spacing"] < out["central_spacing"]
    assert png.stat().st_size > 10_000
    saved = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert saved["central_spacing"] == out["central_spacing"]
    assert (tmp_path / "run" / "fields.csv").stat().st_size > 0
    # the default 2-D grid is graded: finer at the free edges than in the middle
    assert out["graded"] and out["finest_y_spacing"] < 0.5 * 6.35e-3 / 10
    ys = np.unique(pd.read_csv(tmp_path / "run" / "fields.csv")["y_m"].to_numpy())
    assert len(ys) == 11 and np.diff(ys)[0] < 0.5 * np.diff(ys)[4]


def test_uniform_grid_option(capsys):
    out = _json(capsys, ["bearing", *LEGACY_CLI, "--velocity", "4", "--nx", "80", "--ny", "10",
                         "--uniform", "--json"])
    assert not out["graded"]
    assert out["finest_y_spacing"] == pytest.approx(6.35e-3 / 10, rel=1e-12)
    assert out["finest_x_spacing"] == pytest.approx(out["length"] / 80, rel=1e-12)


def test_incompressible_flies_a_little_higher_than_compressible(capsys):
    base = ["bearing", "--velocity", "4", "--infinitely-wide", "--json",
            "--mean-free-path", "0"]
    comp = _json(capsys, base)["central_spacing"]
    incomp = _json(capsys, base + ["--incompressible"])["central_spacing"]
    assert incomp > comp
    assert incomp == pytest.approx(comp, rel=0.1)


def test_bearing_does_not_change_other_commands_defaults(capsys):
    """The sub-commands share the tape options: 'static' still defaults to V = 0."""
    out = _json(capsys, ["static", "--json"])
    assert out["velocity"] == 0.0


def test_velocity_is_required(capsys):
    assert main(["bearing", "--infinitely-wide"]) == 2
    assert "velocity must be nonzero" in capsys.readouterr().err


def test_a_negative_velocity_runs_the_tape_backwards_and_mirrors_the_state(capsys):
    """Over the symmetric cylinder the state at -V is the mirror image of the one at +V:
    the same central and minimum spacings, the minimum at -x."""
    forward = _json(capsys, ["bearing", "--infinitely-wide", "--velocity", "4", "--json"])
    backward = _json(capsys, ["bearing", "--infinitely-wide", "--velocity", "-4", "--json"])
    assert backward["velocity"] == -4.0
    for key in ("central_spacing", "minimum_spacing"):
        assert backward[key] == pytest.approx(forward[key], rel=1e-9)
    assert backward["minimum_x"] == pytest.approx(-forward["minimum_x"], rel=1e-12)
    assert forward["minimum_x"] > 0.0          # the exit corner: downstream of the middle


@pytest.mark.slow
@pytest.mark.parametrize("argv, message", [
    (["--velocity", "0"], "velocity must be nonzero"),
    (["--velocity", "-90"], "string speed"),
    (["--velocity", "90"], "string speed"),
    (["--wrap-angle", "0"], "--wrap-angle must be in (0, 90] degrees"),
    (["--wrap-angle", "120"], "--wrap-angle must be in (0, 90] degrees"),
    (["--viscosity", "-1"], "viscosity must be in [1e-07, 1000] Pa*s"),
    (["--mean-free-path=-1e-9"], "mean_free_path must be in [0, 0.001] m"),
    (["--ambient-pressure", "1e-300"], "ambient_pressure must be in [100, 1e+09] Pa"),
    (["--velocity", "1e-9", "--infinitely-wide"], "needs 498480 intervals, more than the limit"),
    (["--ny", "9"], "ny must be an even integer"),
])
def test_bad_input_one_line_exit_2(capsys, tmp_path, argv, message):
    png = tmp_path / "never.png"
    assert main(["bearing", "--velocity", "4",
                 "--infinitely-wide" if "--ny" not in argv else "--nx=40",
                 *argv, "--plot", str(png)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("gyroshell: error:") and message in err[0]
    assert not png.exists()


def test_unreachable_state_is_a_user_error(capsys, monkeypatch):
    """When neither Newton nor the continuation converges: one line, exit 2."""
    from gyroshell.bearing import smooth
    from gyroshell.core.errors import ConvergenceError

    def failing(*args, **kwargs):
        raise ConvergenceError("Newton did not converge in 60 iterations")

    monkeypatch.setattr(smooth, "newton", failing)
    assert main(["bearing", *LEGACY_CLI, "--velocity", "4", "--infinitely-wide", "--nx", "40",
                 "--quiet"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "no steady flying state" in err[0]


def test_unreachable_state_reports_each_stage_before_the_error(capsys, monkeypatch):
    """Without --quiet every path tried (the pseudo-time march, the speed from the dry
    tape) gets a progress line on stderr (not a terminal here) before the one error
    line."""
    from gyroshell.bearing import smooth
    from gyroshell.core.errors import ConvergenceError

    def failing(*args, **kwargs):
        raise ConvergenceError("Newton did not converge in 60 iterations")

    monkeypatch.setattr(smooth, "newton", failing)
    assert main(["bearing", *LEGACY_CLI, "--velocity", "4", "--infinitely-wide", "--nx", "40"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert all(line.startswith("gyroshell bearing: ") for line in err[:-1])
    assert "unknowns; estimated" in err[0]
    assert any("pseudo-time from the start did not reach" in line for line in err)
    assert any("the speed from the dry tape did not reach" in line for line in err)
    assert err[-1].startswith("gyroshell: error: no steady flying state")


def test_out_that_is_a_file_is_refused_before_solving(capsys, tmp_path):
    afile = tmp_path / "afile"
    afile.write_text("mine")
    assert main(["bearing", "--velocity", "4", "--infinitely-wide", "--out-dir", str(afile)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "is a file, not a folder" in err[0]
    assert afile.read_text() == "mine"


def test_failing_plot_leaves_no_out_folder(capsys, tmp_path, monkeypatch):
    import matplotlib.figure

    def disk_full(self, fname, *args, **kwargs):
        raise OSError(28, "No space left on device", str(fname))

    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", disk_full)
    out, png = tmp_path / "run", tmp_path / "b.png"
    assert main(["bearing", "--velocity", "4", "--infinitely-wide", "--out-dir", str(out),
                 "--plot", str(png)]) == 2
    assert "cannot write" in capsys.readouterr().err
    assert sorted(p.name for p in tmp_path.iterdir()) == []
