"""``gyroshell study`` as review 46 found it wanting: the documented head study runs, a
point with both wraps 0 is refused naming it."""

from __future__ import annotations

import math
import shlex
from pathlib import Path

import pytest

from gyroshell.core.files import read_csv_exact

ROOT = Path(__file__).resolve().parents[2]


def documented_study(page: str) -> list[str]:
    """The ``gyroshell study --compute bearing`` command of ``page`` (continuation lines
    joined), without the program's name."""
    lines = (ROOT / page).read_text(encoding="utf-8").splitlines()
    start = next(i for i, line in enumerate(lines)
                 if line.startswith("gyroshell study") and "--compute bearing" in line)
    text = ""
    for line in lines[start:]:
        text += line.split("#")[0].rstrip().removesuffix("\\") + " "
        if not line.rstrip().endswith("\\"):
            break
    return shlex.split(text)[1:]


@pytest.mark.slow
@pytest.mark.parametrize("page", ["README.md", "docs/user_guide/bearing_studies.md"])
def test_the_documented_wrap_study_runs(cli, tmp_path, monkeypatch, page):
    argv = documented_study(page)
    assert "wrap_in=0.5:4:8" in argv and "wrap_out=1,2,4" in argv
    monkeypatch.chdir(tmp_path)
    run = cli(argv + ["--quiet"])
    assert run.code == 0, run.err
    table = read_csv_exact(tmp_path / "wraps.csv")
    assert len(table) == 24 and table.error.isna().all()
    expected = [math.radians(0.5 + 0.5 * i) for i in range(8)]
    assert table.wrap_in.unique().tolist() == pytest.approx(expected, rel=1e-15)
    assert table.wrap_out.unique().tolist() == [math.radians(w) for w in (1, 2, 4)]


def test_a_point_with_both_wraps_zero_is_refused_in_one_line(cli, tmp_path):
    out = tmp_path / "w.csv"
    run = cli(["study", "--compute", "bearing", "--head", "flat", "--land-length", "1e-3",
               "--transducers", "0", "--infinitely-wide", "--velocity", "4",
               "--vary", "wrap_in=1,0", "--vary", "wrap_out=2,0", "--workers", "1",
               "--out", out, "--quiet"])
    assert run.code == 2 and len(run.error_lines) == 1, run.err
    assert "point 3 {'wrap_in': 0.0, 'wrap_out': 0.0}: a flat head needs a wrap" in run.err
    assert not out.exists()


def test_the_printed_table_keeps_the_varied_values_and_six_digits(cli, tmp_path):
    """20.4um is printed as 2.04e-05 (it reads back exactly), not rounded to 0.000020; the
    critical speeds to 6 significant digits of those in --save's table."""
    saved = tmp_path / "t.csv"
    run = cli(["study", "--vary", "thickness=20um,20.4um,20.8um", "--compute", "critical",
               "--length-ratio", "1", "--spacing", "8e-4", "--workers", "1", "--quiet",
               "--save", saved])
    assert run.code == 0, run.err
    header, *rows = run.out.splitlines()[:4]
    assert header.split()[:2] == ["thickness", "critical_speed"]
    cells = [row.split() for row in rows]
    assert [float(c[0]) for c in cells] == [20e-6, 20.4e-6, 20.8e-6]
    assert [c[0] for c in cells] == ["2e-05", "2.04e-05", "2.08e-05"]
    table = read_csv_exact(saved)
    for c, speed in zip(cells, table.critical_speed, strict=True):
        assert c[1] == f"{speed:.6g}" and len(c[1].replace(".", "")) >= 6


@pytest.mark.parametrize("text, values", [
    ("true,false", [True, False]), ("TRUE,No", [True, False]), ("1,0,yes", [True, False, True]),
])
def test_vary_wrap_pressure_takes_true_and_false(cli, tmp_path, text, values):
    out = tmp_path / "w.csv"
    run = cli(["study", "--vary", f"wrap_pressure={text}", "--compute", "critical",
               "--length-ratio", "1", "--spacing", "8e-4", "--workers", "1", "--quiet",
               "--out", out])
    assert run.code == 0, run.err
    table = read_csv_exact(out)
    assert table.wrap_pressure.tolist() == values and table.error.isna().all()


@pytest.mark.parametrize("text", ["maybe", "0:1:2", "true,"])
def test_vary_wrap_pressure_refuses_other_words_in_one_line(cli, text):
    run = cli(["study", "--vary", f"wrap_pressure={text}", "--compute", "critical",
               "--workers", "1", "--quiet"])
    assert run.code == 2 and len(run.error_lines) == 1, run.err
    assert "--vary wrap_pressure: not true or false" in run.err


def test_one_boolean_parser():
    from gyroshell.cli.common import boolean

    assert [boolean(w) for w in ("yes", "YES", "Yes", "1", "true")] == [True] * 5
    assert [boolean(w) for w in ("no", "NO", "False", "0", " false ")] == [False] * 5


def test_sweep_refuses_an_empty_speed_in_one_line(cli, tmp_path):
    out = tmp_path / "s.csv"
    run = cli(["sweep", "--velocities", "1,,2", "--count", "2", "--quiet", "--out", out])
    assert run.code == 2 and len(run.error_lines) == 1, run.err
    assert "--velocities '1,,2': an empty entry" in run.err and not out.exists()


TINY = ["--length-ratio", "1", "--spacing", "8e-4", "--quiet"]
#: Commands the time limit covers, each with the file it would write.
TIMED = {
    "study": ["study", "--vary", "velocity=0:100:8", "--compute", "critical", "--workers",
              "1", *TINY],
    "study on processes": ["study", "--vary", "velocity=0:100:8", "--compute", "critical",
                           "--workers", "2", *TINY],
    "sweep": ["sweep", "--velocities", "0:100:11", "--count", "2", *TINY],
    "sweep on processes": ["sweep", "--velocities", "0:100:11", "--count", "2",
                           "--workers", "2", *TINY],
    "campbell": ["campbell", "--velocities", "0:100:11", "--count", "2", *TINY],
}


@pytest.mark.parametrize("name", TIMED)
def test_work_estimated_above_the_time_limit_is_refused_with_its_estimate(
        cli, cli_process, tmp_path, monkeypatch, name):
    out = tmp_path / "out.csv"
    limit = {"GYROSHELL_TIME_LIMIT": "1e-9"}
    if "processes" in name:   # a fork server started here would keep the limit for later
        run = cli_process([*TIMED[name], "--out", out], env=limit)
    else:
        monkeypatch.setenv(*limit.popitem())
        run = cli([*TIMED[name], "--out", out])
    assert run.code == 2 and len(run.error_lines) == 1, run.err
    assert "would take about" in run.err and "GYROSHELL_TIME_LIMIT" in run.err
    assert "measured on the first 2" in run.err
    assert list(tmp_path.iterdir()) == []


@pytest.mark.slow
@pytest.mark.parametrize("name", TIMED)
def test_the_default_time_limit_lets_the_commands_through(cli, tmp_path, monkeypatch, name):
    monkeypatch.delenv("GYROSHELL_TIME_LIMIT", raising=False)
    out = tmp_path / "out.csv"
    run = cli([*TIMED[name], "--out", out])
    assert run.code == 0, run.err
    assert out.is_file()
