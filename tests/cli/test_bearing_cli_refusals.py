"""`gyroshell bearing` keeps the README's promise (issue 18, causes 2, 8, 9 and 11):
valid input is flown, options that mean nothing are refused in one line, every output
target is checked before the solve, and long work shows progress on stderr."""

from __future__ import annotations

import json
import os
import re
import stat

import pytest
from bearing_cases import LEGACY_CLI

from gyroshell.cli import bearing as bearing_cli

#: A 1-D bearing that solves in a few hundredths of a second.
TINY_1D = ["bearing", "--velocity", "4", "--infinitely-wide", "--nx", "40"]
#: A 2-D bearing that solves in a few tenths of a second.
TINY_2D = ["bearing", *LEGACY_CLI, "--velocity", "4", "--nx", "40", "--ny", "8"]


def _one_error_line(run) -> str:
    assert run.code == 2, run.err
    assert "Traceback" not in run.err
    assert len(run.error_lines) == 1, run.err
    line = run.error_lines[0]
    assert line.startswith("gyroshell: error: ")
    return line


def _spy_on_the_solve(monkeypatch) -> list:
    """Record every call of the steady solver (to show that a refusal comes before it)."""
    from gyroshell.bearing import steady

    calls: list = []
    real = steady.solve_steady

    def spy(*args, **kwargs):
        calls.append(args)
        return real(*args, **kwargs)

    monkeypatch.setattr(steady, "solve_steady", spy)
    return calls


# ----- cause 8: valid input is not refused ---------------------------------------------------
def test_velocity_from_the_config_file_is_used(cli, tmp_path):
    tape = tmp_path / "tape.toml"
    tape.write_text('[tape]\nvelocity = "4 m/s"\ntension = "90 N/m"\n')
    run = cli([*TINY_1D[:1], "--config", tape, *TINY_1D[3:], "--json", "--quiet"])
    assert run.code == 0, run.err
    assert json.loads(run.out)["velocity"] == 4.0


def test_velocity_typed_overrides_the_config_file(cli, tmp_path):
    tape = tmp_path / "tape.toml"
    tape.write_text('velocity = "4 m/s"\n')
    run = cli(["bearing", "--config", tape, "--velocity", "3", "--infinitely-wide",
               "--nx", "40", "--json", "--quiet"])
    assert run.code == 0, run.err
    assert json.loads(run.out)["velocity"] == 3.0


def test_config_file_without_velocity_names_both_ways_to_give_it(cli, tmp_path):
    tape = tmp_path / "tape.toml"
    tape.write_text('tension = "90 N/m"\n')
    line = _one_error_line(cli(["bearing", "--config", tape, "--infinitely-wide"]))
    assert "velocity must be nonzero" in line and "--velocity" in line and "--config" in line


def test_narrow_tape_is_not_refused_by_the_plate_grid(cli):
    """--width 1e-3 was refused by TapeParameters' check on --spacing, which the bearing
    does not use."""
    run = cli([*TINY_2D, "--width", "1e-3", "--json", "--quiet"])
    assert run.code == 0, run.err
    out = json.loads(run.out)
    assert out["width"] == 1e-3 and out["ny"] == 8


def test_plate_keys_of_a_config_file_do_not_apply(cli, tmp_path):
    """A tape file written for the plate commands (a coarse spacing, L_x/L_y = 19, a load
    off centre) flies: the bearing sizes its own grid and its load is the film."""
    tape = tmp_path / "tape.toml"
    tape.write_text('[tape]\nwidth = "6.35 mm"\nspacing = "0.5 mm"\nlength_ratio = 19\n'
                    'load = "900 Pa"\nload_x = "0.1 m"\nvelocity = "4 m/s"\n')
    run = cli(["bearing", *LEGACY_CLI, "--config", tape, "--nx", "40", "--ny", "8", "--json",
               "--quiet"])
    assert run.code == 0, run.err
    assert json.loads(run.out)["width"] == 6.35e-3


def test_narrow_tape_of_a_config_file_is_not_refused_by_the_plate_grid(cli, tmp_path):
    """A 1 mm tape in a file without a spacing key: the default plate spacing (0.155 mm)
    would leave fewer than 8 intervals across, but the bearing has no plate grid."""
    tape = tmp_path / "narrow.toml"
    tape.write_text('[tape]\nwidth = "1 mm"\nvelocity = "4 m/s"\n')
    run = cli(["bearing", "--config", tape, "--nx", "40", "--ny", "8", "--json", "--quiet"])
    assert run.code == 0, run.err
    assert json.loads(run.out)["width"] == 1e-3


def test_a_config_file_of_a_negative_width_is_still_refused(cli, tmp_path):
    tape = tmp_path / "negative.toml"
    tape.write_text('[tape]\nwidth = "-1 mm"\nvelocity = "4 m/s"\n')
    line = _one_error_line(cli(["bearing", "--config", tape, "--quiet"]))
    assert "negative.toml: width must be > 0 m, got -0.001" in line


def test_bearing_parameters_through_the_python_api():
    """The bearing's tape: the typed fields, and plate-grid fields that always pass."""
    import argparse

    from gyroshell.cli import bearing

    args = argparse.Namespace(config=None, velocity=4.0, infinitely_wide=False,
                              **{field: None for _f, field, _t in bearing.TAPE_OPTIONS})
    args.width = 1e-3
    params, velocity, _head_table = bearing._tape(args)
    assert velocity == 4.0 and params.width == 1e-3
    assert params.edges == "free" and round(params.width / params.spacing) >= 8


# ----- cause 9: options that mean nothing are absent or refused -------------------------------
@pytest.mark.parametrize("option", ["--spacing", "--length-ratio", "--edges", "--load"])
def test_plate_options_are_not_offered(cli, option):
    help_run = cli(["bearing", "--help"])
    assert help_run.code == 0 and "--nx" in help_run.out
    assert not re.search(rf"^\s+{option}\b", help_run.out, re.MULTILINE)   # no entry
    value = "simply-supported" if option == "--edges" else "1e-3"
    line = _one_error_line(cli([*TINY_2D, option, value]))
    assert f"unrecognized arguments: {option} {value}" in line


#: (case, extra arguments, what the one error line must say)
UNUSED = [
    ("ny in 1-D", ["--infinitely-wide", "--ny", "10"],
     "--ny sets the intervals across the width, which the infinitely wide tape"),
    ("odd ny in 1-D", ["--infinitely-wide", "--ny", "9"], "drop --ny or --infinitely-wide"),
    ("uniform in 1-D", ["--infinitely-wide", "--uniform"],
     "--uniform switches off the 2-D grid's grading"),
    ("width in 1-D", ["--infinitely-wide", "--width", "3e-3"],
     "--width sets the tape width, which the infinitely wide tape"),
    ("E with D and k", ["--bending-rigidity", "3e-6", "--foundation-stiffness", "2e8",
                        "--youngs-modulus", "5e9"], "--youngs-modulus is not used when"),
    ("c with D and k", ["--bending-rigidity", "3e-6", "--foundation-stiffness", "2e8",
                        "--thickness", "1e-5"], "--thickness is not used when"),
    ("nu with D and k in 1-D", ["--infinitely-wide", "--bending-rigidity", "3e-6",
                                "--foundation-stiffness", "2e8", "--poisson", "0.2"],
     "--poisson is not used when"),
]


@pytest.mark.parametrize("case, extra, message", UNUSED, ids=[c[0] for c in UNUSED])
def test_option_unused_in_its_mode_is_refused_before_the_solve(cli, tmp_path, monkeypatch,
                                                               case, extra, message):
    calls = _spy_on_the_solve(monkeypatch)
    png = tmp_path / "never.png"
    line = _one_error_line(cli(["bearing", "--velocity", "4", "--nx", "40", *extra,
                                "--plot", png, "--out-dir", tmp_path / "run"]))
    assert message in line
    assert calls == [] and sorted(tmp_path.iterdir()) == []


def test_poisson_with_d_and_k_is_used_by_the_2d_plate(cli):
    """The 2-D plate's curvatures take ν itself: --poisson still applies there."""
    run = cli([*TINY_2D, "--bending-rigidity", "2.93e-6", "--foundation-stiffness",
               "2.198e8", "--poisson", "0.2", "--json", "--quiet"])
    assert run.code == 0, run.err


def test_simply_supported_edges_in_a_config_file_are_refused_in_2d(cli, tmp_path):
    tape = tmp_path / "tape.toml"
    tape.write_text('edges = "simply-supported"\nvelocity = "4 m/s"\n')
    line = _one_error_line(cli(["bearing", "--config", tape, "--nx", "40", "--ny", "8"]))
    assert "edges = 'simply-supported'" in line and "free edges" in line


def test_plot_and_out_with_json_are_all_written(cli, tmp_path):
    """--plot and --out are honoured with --json (stdout stays the one JSON object)."""
    png, out = tmp_path / "b.png", tmp_path / "run"
    run = cli([*TINY_1D, "--json", "--quiet", "--plot", png, "--out-dir", out])
    assert run.code == 0, run.err
    assert json.loads(run.out)["nx"] == 40
    assert png.stat().st_size > 0
    assert sorted(p.name for p in out.iterdir()) == sorted(bearing_cli.OUT_FILES)


# ----- cause 11: outputs checked before the work ----------------------------------------------
def _existing_run_folder(tmp_path):
    out = tmp_path / "run"
    out.mkdir()
    (out / "summary.json").write_text("my summary\n")
    (out / "fields.csv").write_text("my fields\n")
    return out


@pytest.mark.parametrize("name", ["summary.json", "fields.csv"])
def test_read_only_file_inside_out_is_refused_before_the_solve(cli, tmp_path, monkeypatch,
                                                               name):
    calls = _spy_on_the_solve(monkeypatch)
    out = _existing_run_folder(tmp_path)
    (out / name).chmod(0o444)
    before = {p.name: (p.read_text(), stat.S_IMODE(p.stat().st_mode)) for p in out.iterdir()}
    line = _one_error_line(cli([*TINY_1D, "--out-dir", out]))
    assert f"--out-dir {out / name}: exists and is read-only; not replaced" in line
    assert calls == []
    after = {p.name: (p.read_text(), stat.S_IMODE(p.stat().st_mode)) for p in out.iterdir()}
    assert after == before                     # no file touched, no temporary file left


def test_folder_in_place_of_an_out_file_is_refused(cli, tmp_path):
    out = tmp_path / "run"
    (out / "fields.csv").mkdir(parents=True)
    line = _one_error_line(cli([*TINY_1D, "--out-dir", out]))
    assert "fields.csv: is a folder, not a file" in line


def test_out_with_a_missing_parent_is_refused_and_nothing_created(cli, tmp_path,
                                                                  monkeypatch):
    calls = _spy_on_the_solve(monkeypatch)
    out = tmp_path / "missing" / "run"
    line = _one_error_line(cli([*TINY_1D, "--out-dir", out]))
    assert line == (f"gyroshell: error: --out-dir {out}: folder {tmp_path / 'missing'} "
                    "does not exist")
    assert calls == [] and sorted(tmp_path.iterdir()) == []


def test_out_folder_itself_is_created(cli, tmp_path):
    out = tmp_path / "run"
    run = cli([*TINY_1D, "--quiet", "--out-dir", out])
    assert run.code == 0, run.err
    saved = json.loads((out / "summary.json").read_text())
    assert saved["nx"] == 40 and (out / "fields.csv").stat().st_size > 0


def test_existing_out_files_are_replaced_whole(cli, tmp_path):
    out = _existing_run_folder(tmp_path)
    run = cli([*TINY_1D, "--quiet", "--out-dir", out])
    assert run.code == 0, run.err
    assert json.loads((out / "summary.json").read_text())["nx"] == 40
    assert sorted(p.name for p in out.iterdir()) == sorted(bearing_cli.OUT_FILES)


def test_output_folder_check_through_the_python_api(tmp_path):
    from gyroshell import ParameterError
    from gyroshell.core.files import OutputPathError, check_output_folder_with_files

    missing = tmp_path / "missing" / "run"
    with pytest.raises(OutputPathError, match="folder .*missing does not exist"):
        check_output_folder_with_files(missing, ("a.csv",), option="out")
    assert issubclass(OutputPathError, ParameterError)
    out = _existing_run_folder(tmp_path)
    os.chmod(out / "fields.csv", 0o444)
    with pytest.raises(OutputPathError, match=r"^out .*fields\.csv: exists and is read-only"):
        check_output_folder_with_files(out, ("summary.json", "fields.csv"), option="out")
    assert check_output_folder_with_files(tmp_path / "new", ("a.csv",)) == tmp_path / "new"
    assert not (tmp_path / "new").exists()


# ----- cause 2: long work shows progress --------------------------------------------------------
def _progress_lines(err: str) -> list[str]:
    """The progress lines of stderr (warning lines set aside: a coarse grid's, and the
    models' range warnings of a tape resting on the hard wall)."""
    lines = [line for line in err.strip().splitlines()
             if not line.startswith("gyroshell: warning: ")]
    assert lines and all(line.startswith("gyroshell bearing: ") for line in lines), err
    return lines


def test_progress_lines_when_stderr_is_not_a_terminal(cli):
    """In-process, stderr is captured (not a terminal): the size and estimate first, then
    one line per Newton iteration with the elapsed time, and stdout is the JSON alone."""
    run = cli([*TINY_1D, "--json"])
    assert run.code == 0, run.err
    out = json.loads(run.out)
    lines = _progress_lines(run.err)
    assert "infinitely wide tape, 40 intervals along x, 78 unknowns; estimated" in lines[0]
    newton = [line for line in lines if ": Newton " in line]
    assert len(newton) == out["newton_iterations"]
    assert " s: Newton 1: step " in newton[0]
    assert lines[-1].endswith(f"done: {out['newton_iterations']} Newton iterations")


def _without_range_warnings(err: str) -> list[str]:
    """stderr's lines less the models' range warnings (the default hard wall holds this
    tape's free edges at its gap, with first-order slip at Kn = 3: both warned, each one
    line, and listed in the JSON's ``warnings``)."""
    return [line for line in err.strip().splitlines()
            if "beyond its validity" not in line and "the hard wall at the gap" not in line]


def test_progress_of_the_2d_starting_state(cli):
    run = cli([*TINY_2D, "--json"])
    assert run.code == 0, run.err
    lines = _progress_lines(run.err)
    assert "40 x 8 intervals (graded), 624 unknowns; estimated" in lines[0]
    assert ": start: a first solve" in lines[1] and lines[2].endswith("start: ready")


def test_quiet_means_no_progress_lines(cli):
    run = cli([*TINY_2D, "--json", "--quiet"])
    assert run.code == 0
    lines = _without_range_warnings(run.err)
    assert [line[:30] for line in lines] == ["gyroshell: warning: ny = 8 lea"]
    assert json.loads(run.out)["nx"] == 40


def test_progress_lines_from_a_real_process(cli_process):
    """A fresh process with stderr a pipe: one line per stage; stdout exactly one JSON
    object; with --quiet stderr stays empty."""
    run = cli_process([*TINY_1D, "--json"])
    assert run.code == 0, run.err
    out = json.loads(run.out)
    lines = _progress_lines(run.err)
    assert "unknowns; estimated" in lines[0]
    assert sum(": Newton " in line for line in lines) == out["newton_iterations"]
    quiet = cli_process([*TINY_1D, "--json", "--quiet"])
    assert quiet.code == 0 and quiet.err == "" and json.loads(quiet.out)["nx"] == 40


def test_time_estimate_grows_with_the_model():
    """The estimate is arithmetic on the grid's counts: no model is built here."""
    from types import SimpleNamespace

    from gyroshell.cli.bearing import iteration_seconds

    def model(nx, ny):
        unknowns = 2 * (nx - 1) if ny is None else 2 * (nx - 1) * (ny + 1)
        return SimpleNamespace(infinitely_wide=ny is None, nx=nx, ny=ny, unknowns=unknowns)

    assert iteration_seconds(model(800, None)) < iteration_seconds(model(45_000, None))
    assert iteration_seconds(model(200, 20)) < iteration_seconds(model(200, 80))
    assert iteration_seconds(model(388, 148)) < iteration_seconds(model(1016, 148))


def test_coarse_free_edges_are_one_warning_line_and_the_run_goes_on(cli):
    """ny = 8 on the 6.35 mm tape leaves 0.8 mm at the edges: flown, with the estimated
    error in one `gyroshell: warning:` line (no Python warning text)."""
    run = cli(["bearing", *LEGACY_CLI, "--velocity", "4", "--nx", "40", "--ny", "8", "--json",
               "--quiet"])
    assert run.code == 0, run.err
    lines = _without_range_warnings(run.err)
    assert len(lines) == 1 and lines[0].startswith("gyroshell: warning: ny = 8 leaves")
    assert "off by" in lines[0] and "BearingGridWarning" not in run.err
    assert json.loads(run.out)["ny"] == 8
