"""`gyroshell transient` through main([...]): files, summaries, one-line errors."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from gyroshell.cli import main
from gyroshell.results.transient import Snapshots

COARSE = ["--spacing", str(6.35e-3 / 10), "--length-ratio", "3"]


def exit_code(argv: list[str]) -> int:
    try:
        return main(argv)
    except SystemExit as exc:
        return int(exc.code)


def test_history_csv_has_t_and_w_one_row_per_step(tmp_path, capsys):
    out = tmp_path / "h.csv"
    argv = ["transient", *COARSE, "--velocity", "50", "--steps", "40", "--dt", "2e-6",
            "--out", str(out), "--quiet"]
    assert main(argv) == 0
    frame = pd.read_csv(out)
    assert list(frame.columns) == ["t", "w"]
    assert len(frame) == 41 and frame["t"].iloc[0] == 0.0
    np.testing.assert_allclose(frame["t"], 2e-6 * np.arange(41), rtol=1e-12)
    assert frame["w"].iloc[0] == 0.0 and frame["w"].abs().max() > 0.0
    text = capsys.readouterr()
    assert "load-point displacement" in text.out and " m" in text.out
    assert text.err == ""  # --quiet: no progress bar


def test_snapshots_and_json_summary(tmp_path, capsys):
    snaps = tmp_path / "s.npz"
    argv = ["transient", *COARSE, "--steps", "20", "--dt", "2e-6", "--beta", "1",
            "--gamma", "1.5", "--snapshot-every", "10", "--snapshots", str(snaps), "--json",
            "--quiet"]
    assert main(argv) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["steps"] == 20 and out["beta"] == 1.0 and out["gamma"] == 1.5
    assert out["backend"] == "band"  # "auto" on the symmetric half's narrow band
    loaded = Snapshots.load(snaps)
    np.testing.assert_allclose(loaded.times, [0.0, 2e-5, 4e-5])
    assert loaded.fields.shape == (3, 31, 11)


@pytest.mark.parametrize(("extra", "match"), [
    (["--dt", "0"], "dt must be > 0"),
    (["--dt=-2e-6"], "dt must be > 0"),
    (["--dt", "2e-6", "--steps", "0"], "must be >= 1"),
    (["--dt", "2e-6", "--snapshot-every", "5"], "--snapshot-every and --snapshots go together"),
    (["--dt", "2e-6", "--backend", "fastest"], "invalid choice: 'fastest'"),
    (["--dt", "2e-6", "--velocity", "-1"], "velocity must be >= 0"),
    (["--dt", "2e-6", "--out", "/no/such/folder/h.csv"], "does not exist"),
])
def test_user_errors_exit_2_with_one_line(capsys, extra, match):
    argv = ["transient", *COARSE, "--quiet", *extra]
    if "--steps" not in extra:
        argv += ["--steps", "5"]
    assert exit_code(argv) == 2
    err = capsys.readouterr().err
    assert match in err and len(err.strip().splitlines()) == 1 and "Traceback" not in err


def test_blow_up_exits_1_and_writes_nothing(tmp_path, capsys):
    out = tmp_path / "h.csv"
    argv = ["transient", *COARSE, "--velocity", "400", "--steps", "4000", "--dt", "2e-6",
            "--out", str(out), "--quiet"]
    assert exit_code(argv) == 1
    err = capsys.readouterr().err
    warning, error = err.strip().splitlines()  # above critical: warned first, then refused
    assert warning.startswith("gyroshell: warning: V = 400 m/s is above the critical")
    assert "numerical failure" in error and "blew up" in error
    assert list(tmp_path.iterdir()) == []
