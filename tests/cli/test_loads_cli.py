"""`gyroshell transient` with moving loads and damping, and `gyroshell frf`, through main()."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from gyroshell import TapeModel, TapeParameters
from gyroshell.cli import main
from gyroshell.results.transient import Snapshots

WIDTH = 6.35e-3
COARSE = ["--spacing", str(WIDTH / 10), "--length-ratio", "3"]


def exit_code(argv: list[str]) -> int:
    try:
        return main(argv)
    except SystemExit as exc:
        return int(exc.code)


def test_moving_load_history_is_the_displacement_under_the_moving_centre(tmp_path, capsys):
    out, snaps = tmp_path / "h.csv", tmp_path / "s.npz"
    argv = ["transient", *COARSE, "--velocity", "30", "--steps", "60", "--dt", "1e-6",
            "--load-position", "0.004,0.002", "--load-velocity", "80,20", "--damping", "500",
            "--out", str(out), "--snapshot-every", "1", "--snapshots", str(snaps), "--quiet",
            "--json"]
    assert main(argv) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["moving_load"] is True and summary["damping"] == 500.0
    frame, fields = pd.read_csv(out), Snapshots.load(snaps)
    grid = TapeModel(TapeParameters(spacing=WIDTH / 10, length_ratio=3)).grid
    for n in (10, 35, 60):
        t = frame["t"].iloc[n]
        row = grid.interpolation_row(0.004 + 80 * t, 0.002 + 20 * t)
        w = row @ grid.from_field(fields.fields[n])
        assert frame["w"].iloc[n] == pytest.approx(w, rel=1e-12, abs=1e-25)
    assert frame["w"].abs().max() > 0


def test_intermittent_contact_from_the_command_line(tmp_path):
    out = tmp_path / "h.csv"
    argv = ["transient", *COARSE, "--steps", "80", "--dt", "1e-6", "--load-position",
            "0.003,0.003", "--load-velocity", "100,0", "--contact-period", "40e-6",
            "--contact-duration", "20e-6", "--contact-ramp", "2e-6", "--damping", "300",
            "--rayleigh", "100,1e-8", "--out", str(out), "--quiet"]
    assert main(argv) == 0
    assert len(pd.read_csv(out)) == 81


@pytest.mark.parametrize(("extra", "match"), [
    (["--load-position", "0.01,0.003", "--load-velocity", "0,500"], "load path leaves the tape"),
    (["--contact-period", "1e-5", "--contact-duration", "2e-5"], "contact duration must be <="),
    (["--contact-period", "1e-5"], "--contact-period and --contact-duration go together"),
    (["--damping", "-3"], "--damping must be >= 0 N*s/m^3, got -"),
    (["--rayleigh", "1,-1"], "--rayleigh B must be >= 0 s, got -1"),
    (["--load-velocity", "fast"], "expected two numbers"),
])
def test_transient_load_errors_exit_2_with_one_line(tmp_path, capsys, extra, match):
    out = tmp_path / "h.csv"
    argv = ["transient", *COARSE, "--steps", "50", "--dt", "1e-6", "--out", str(out), *extra]
    assert exit_code(argv) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and match in err
    assert "Traceback" not in err
    assert not out.exists()


@pytest.mark.slow
def test_frf_json_csv_and_plot(tmp_path, capsys):
    out, plot = tmp_path / "frf.csv", tmp_path / "frf.png"
    argv = ["frf", *COARSE, "--velocity", "50", "--frequencies", "0:2e5:60", "--damping",
            "200", "--probe", "0.01,0.001", "--json", "--out", str(out), "--plot", str(plot),
            "--quiet"]
    assert main(argv) == 0
    data = json.loads(capsys.readouterr().out)
    assert len(data["omega"]) == len(data["amplitude"]) == len(data["phase"]) == 60
    np.testing.assert_allclose(data["omega"], np.linspace(0, 2e5, 60))
    assert all(-np.pi <= p <= np.pi for p in data["phase"])
    assert data["max_error_estimate"] <= 1e-6
    frame = pd.read_csv(out)
    assert {"omega", "frequency", "amplitude", "phase", "amplitude_1", "phase_1"} \
        <= set(frame.columns)
    np.testing.assert_allclose(frame["amplitude"], data["amplitude"], rtol=1e-15)
    assert plot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize(("extra", "match"), [
    (["--frequencies", "0:1e5:0"], "NUM must be an integer >= 1"),
    (["--frequencies", "1e5:0:10"], "START <= STOP"),
    (["--frequencies", "0:1e5:10", "--damping", "-1"], "--damping must be >= 0 N*s/m^3, got -"),
    (["--frequencies", "0:1e5:10", "--probe", "5,5"], "must lie on the tape"),
    (["--frequencies", "0:1e5:10", "--velocity", "300"], "critical speed"),
    (["--frequencies", "0:1e5:10", "--plot", "x.svg"], "--plot must be a .png file"),
])
def test_frf_errors_exit_2_with_one_line(tmp_path, capsys, extra, match):
    out = tmp_path / "frf.csv"
    assert exit_code(["frf", *COARSE, "--out", str(out), *extra]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and match in err
    assert not out.exists()
