"""`gyroshell static` through main([...]) and through the installed entry points."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from gyroshell.cli import main

COARSE = ["--spacing", str(6.35e-3 / 10)]


def exit_code(argv: list[str]) -> int:
    """main()'s return value, or the code of the SystemExit that argparse raises."""
    try:
        return main(argv)
    except SystemExit as exc:
        return int(exc.code)


def test_static_json_has_load_point_deflection(capsys):
    assert main(["static", *COARSE, "--velocity", "50", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["load_point_deflection"] > 0.0
    assert out["velocity"] == 50.0
    assert out["ny"] == 10


def test_static_text_output_names_units(capsys):
    assert main(["static", *COARSE]) == 0
    out = capsys.readouterr().out
    assert "load-point deflection" in out and " m" in out


@pytest.mark.parametrize(
    ("argv", "match"),
    [
        (["--poisson", "0.7"], "poisson must be in (-1, 0.5)"),
        (["--thickness", "-1"], "thickness must be > 0"),
        (["--length-ratio", "0"], "length_ratio must be > 0"),
        (["--spacing", "0.01"], "spacing must leave at least 8 intervals"),
        (["--velocity", "150"], "at or above the critical speed"),
        (["--velocity", "-3"], "velocity must be >= 0"),
        (["--tension", "nan"], "must be finite"),
        (["--edges", "clamped"], "invalid choice"),
    ],
)
def test_user_errors_exit_2_with_one_line(capsys, argv, match):
    assert exit_code(["static", *COARSE, *argv]) == 2
    err = capsys.readouterr().err
    assert match in err
    assert len(err.strip().splitlines()) == 1
    assert "Traceback" not in err


@pytest.mark.slow
def test_python_dash_m_entry_point_runs():
    proc = subprocess.run([sys.executable, "-m", "gyroshell", "static", *COARSE, "--json"],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout)["load_point_deflection"] > 0


@pytest.mark.slow
def test_user_error_from_subprocess_has_no_traceback():
    proc = subprocess.run([sys.executable, "-m", "gyroshell", "static", "--density", "0"],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 2
    assert proc.stderr.strip() == "gyroshell: error: density must be > 0 kg/m^2, got 0"
