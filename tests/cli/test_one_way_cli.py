"""One way to do a thing across sub-commands: --json, --quiet, --plot and --save where they
fit; --out a file (a table) and --out-dir a folder, the old ``--out DIR`` read with a
notice; ``START:STOP:NUM`` the same in every range option."""

from __future__ import annotations

import argparse
import json

import numpy as np
import pytest

from gyroshell.cli import build_parser

COARSE = ["--length-ratio", "4", "--spacing", str(6.35e-3 / 8)]
PNG = b"\x89PNG\r\n\x1a\n"
HDF5 = b"\x89HDF\r\n\x1a\n"   # NetCDF-4

#: Which of the shared options each sub-command offers: every one that computes a result
#: saves it (--save) and draws it (--plot) and prints its summary (--json); --quiet where
#: a run reports progress. reproduce writes figures and tables by definition.
OFFERED = {
    "static": {"--json", "--plot", "--save"},
    "modes": {"--json", "--plot", "--save"},
    "critical": {"--json", "--plot", "--save"},
    "sweep": {"--json", "--plot", "--save", "--quiet"},
    "transient": {"--json", "--plot", "--save", "--quiet"},
    "frf": {"--json", "--plot", "--save", "--quiet"},
    "study": {"--json", "--plot", "--save", "--quiet"},
    "campbell": {"--json", "--plot", "--save", "--quiet"},
    "bearing": {"--json", "--plot", "--save", "--quiet"},
    "reproduce": {"--json", "--quiet"},
}


def _options(name: str) -> set[str]:
    parser = build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return {o for a in sub.choices[name]._actions for o in a.option_strings}


@pytest.mark.parametrize("name", sorted(OFFERED))
def test_each_sub_command_offers_the_shared_options_that_fit(name):
    options = _options(name)
    assert options & {"--json", "--plot", "--save", "--quiet"} == OFFERED[name]
    # a folder is --out-dir (bearing, reproduce); --out elsewhere is a file
    assert ("--out-dir" in options) == (name in ("bearing", "reproduce"))


@pytest.mark.parametrize("name", ["bearing", "reproduce"])
def test_out_names_a_folder_only_as_the_old_spelling_of_out_dir(name):
    parser = build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    helps = {o: a.help for a in sub.choices[name]._actions for o in a.option_strings}
    assert "the old spelling of --out-dir" in helps["--out"]


def test_bearing_out_still_writes_the_folder_with_one_notice(cli, tmp_path):
    old, new = tmp_path / "old", tmp_path / "new"
    base = ["bearing", "--velocity", "4", "--infinitely-wide", "--nx", "200", "--quiet"]
    run = cli([*base, "--out", old])
    assert run.code == 0, run.err
    assert run.error_lines == ["gyroshell: notice: gyroshell bearing --out DIR is now "
                               "--out-dir DIR (the folder of the files); --out goes in "
                               "release 0.3"]
    run = cli([*base, "--out-dir", new])
    assert run.code == 0 and run.err == ""
    assert sorted(p.name for p in old.iterdir()) == sorted(p.name for p in new.iterdir()) \
        == ["corners.csv", "fields.csv", "summary.json", "transducer_lines.csv"]
    assert (old / "fields.csv").read_text() == (new / "fields.csv").read_text()
    run = cli([*base, "--out-dir", new, "--out", old])
    assert run.code == 2
    assert "--out-dir and --out both name the output folder: give --out-dir alone" in run.err


def test_reproduce_out_is_read_as_out_dir(cli, tmp_path):
    afile = tmp_path / "afile"
    afile.write_text("")
    run = cli(["reproduce", "fig2", "--quick", "--quiet", "--out", afile])
    assert run.code == 2
    assert run.error_lines[0].startswith("gyroshell: notice: gyroshell reproduce --out DIR "
                                         "is now --out-dir DIR")
    assert f"--out-dir {afile}: is a file, not a folder" in run.error_lines[1]
    run = cli(["reproduce", "fig2", "--quick", "--quiet"])
    assert run.code == 2 and "reproduce needs --out-dir DIR" in run.err


def _sweep_speeds(cli, velocities: str) -> tuple[list[float], str]:
    run = cli(["sweep", *COARSE, "--velocities", velocities, "--count", "1", "--quiet",
               "--json"])
    assert run.code == 0, run.err
    summary = json.loads(run.out)
    return summary, run.err


@pytest.mark.parametrize("text, count, low, high", [
    ("0:100:11", 11, 0.0, 100.0), ("0:90:10", 10, 0.0, 90.0), ("20:40:3", 3, 20.0, 40.0),
    ("40:20:3", 3, 20.0, 40.0),
])
def test_velocities_start_stop_num(cli, text, count, low, high):
    summary, err = _sweep_speeds(cli, text)
    assert (summary["speeds"], summary["velocity_min"], summary["velocity_max"]) == \
        (count, low, high)
    assert err == ""


@pytest.mark.parametrize("text, count, rewrite", [
    ("0:100:10", 11, "0:100:11"), ("0:1:0.25", 5, "0:1:5"),
])
def test_the_old_step_form_still_works_with_a_notice(cli, text, count, rewrite):
    summary, err = _sweep_speeds(cli, text)
    assert summary["speeds"] == count
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"gyroshell: notice: --velocities {text} "
                                                   "is read as START:STOP:STEP")
    assert lines[0].endswith(f"write {rewrite}")
    again, err = _sweep_speeds(cli, rewrite)
    assert again == {**summary} and err == ""


def test_every_range_option_reads_start_stop_num_alike(cli, tmp_path):
    """The same START:STOP:NUM gives numpy.linspace's values in sweep, frf and study."""
    expected = np.linspace(0.0, 45.0, 4)
    csv = tmp_path / "s.csv"
    assert cli(["sweep", *COARSE, "--velocities", "0:45:4", "--count", "1", "--quiet",
                "--out", csv]).code == 0
    import pandas as pd

    np.testing.assert_array_equal(np.unique(pd.read_csv(csv)["velocity"]), expected)
    run = cli(["frf", *COARSE, "--frequencies", "0:45:4", "--quiet", "--out", csv])
    assert run.code == 0, run.err
    np.testing.assert_array_equal(pd.read_csv(csv)["omega"], expected)
    run = cli(["study", *COARSE, "--vary", "velocity=0:45:4", "--compute", "critical",
               "--workers", "1", "--quiet", "--out", csv])
    assert run.code == 0, run.err
    np.testing.assert_array_equal(pd.read_csv(csv)["velocity"], expected)


@pytest.mark.parametrize("argv, message", [
    (["sweep", "--velocities", "0:100"], "--velocities '0:100': use START:STOP:NUM"),
    (["frf", "--frequencies", "0:1e5"], "frequencies '0:1e5': use START:STOP:NUM"),
    (["study", "--vary", "tension=80:90", "--compute", "critical"],
     "--vary tension '80:90': use START:STOP:NUM"),
    (["study", "--vary", "tension=80:90:1", "--compute", "critical"],
     "--vary tension: NUM = 1 gives START alone; use START = STOP or NUM >= 2"),
    (["frf", "--frequencies", "0:1e5:1"],
     "frequencies: NUM = 1 gives START alone; use START = STOP or NUM >= 2"),
    (["sweep", "--velocities", "0:100:0"], "--velocities: NUM must be an integer >= 1"),
    (["frf", "--frequencies", "0:1e5:0"], "frequencies: NUM must be an integer >= 1"),
])
def test_a_bad_range_is_refused_alike_in_one_line(cli, argv, message):
    run = cli([*argv, *COARSE])
    assert run.code == 2 and len(run.error_lines) == 1, run.err
    assert message in run.err


def test_the_range_options_say_so_in_their_help():
    parser = build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    for name, option in (("sweep", "--velocities"), ("campbell", "--velocities"),
                         ("frf", "--frequencies"), ("study", "--vary")):
        action = next(a for a in sub.choices[name]._actions if option in a.option_strings)
        assert "START:STOP:NUM" in action.help and "both included" in action.help, name


@pytest.mark.parametrize("command", [
    ["static", *COARSE], ["modes", *COARSE, "--count", "2"], ["critical", *COARSE],
    ["transient", *COARSE, "--steps", "5", "--dt", "2e-6", "--quiet"],
])
def test_plot_draws_the_result(cli, tmp_path, command):
    png = tmp_path / "r.png"
    run = cli([*command, "--plot", png])
    assert run.code == 0, run.err
    assert png.read_bytes()[:8] == PNG


@pytest.mark.parametrize("command", [
    ["critical", *COARSE],
    ["frf", *COARSE, "--frequencies", "0:1e5:3", "--quiet"],
    ["campbell", *COARSE, "--velocities", "0:20:3", "--count", "2", "--quiet"],
    ["bearing", "--velocity", "4", "--infinitely-wide", "--nx", "200", "--quiet"],
])
def test_save_writes_the_result(cli, tmp_path, command):
    nc = tmp_path / "r.nc"
    run = cli([*command, "--save", nc])
    assert run.code == 0, run.err
    assert nc.read_bytes()[:8] == HDF5
    run = cli([*command, "--save", tmp_path / "r.txt"])
    assert run.code == 2 and "--save" in run.err


def test_campbell_out_nc_is_the_old_spelling_of_save(cli, tmp_path):
    nc = tmp_path / "c.nc"
    run = cli(["campbell", *COARSE, "--velocities", "0:20:3", "--count", "2", "--quiet",
               "--out", nc])
    assert run.code == 0 and nc.read_bytes()[:8] == HDF5
    assert run.error_lines == ["gyroshell: notice: campbell --out FILE.nc is now --save "
                               "FILE.nc (--out is the table, CSV or Parquet, in every "
                               "sub-command); --out FILE.nc goes in release 0.3"]
