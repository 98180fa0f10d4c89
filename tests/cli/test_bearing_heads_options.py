"""The head options of `gyroshell bearing` and the `[head]` table of a TOML file: the design
they state (SI, angles in rad), the table and the options agreeing, and every mistake refused
in one line with exit code 2 before any numerical work."""

from __future__ import annotations

import math

import pytest

from gyroshell.bearing.head_config import HeadDesign, ModuleShape
from gyroshell.cli import build_parser
from gyroshell.cli.heads import head_design

FLAT = ["--head", "flat", "--land-length", "1e-3", "--wrap-in", "2", "--wrap-out", "3"]
THREE_MODULES = """
[tape]
tension = "90 N/m"
velocity = "4 m/s"

[head]
kind = "flat"
land_length = "1 mm"
corner_radius = ["5 um", "0 um"]
wrap_in = "2 deg"
wrap_out = "3 deg"
modules = 3
module_gap = "0.3 mm"
transducers = ["-1.3 mm", "0 mm", "1.3 mm"]
friction = 0.2
"""


def _design(argv, table=None, config=None) -> HeadDesign:
    args = build_parser().parse_args(["bearing", "--velocity", "4", *argv])
    return head_design(args, table, config)


def _one_error_line(run) -> str:
    assert run.code == 2, run.err
    assert "Traceback" not in run.err and len(run.error_lines) == 1, run.err
    assert run.error_lines[0].startswith("gyroshell: error: ")
    return run.error_lines[0]


def test_no_head_option_is_the_cylinder_of_the_tape():
    design = _design([])
    assert design.kind == "cylinder" and design.wrap_angle is None and design.radius is None


def test_flat_head_options_in_si_units():
    design = _design([*FLAT, "--corner-radius", "5e-6,0", "--modules", "3", "--module-gap",
                      "3e-4", "--transducers", "-1.3e-3,0,1.3e-3", "--friction", "0.2"])
    assert design.kind == "flat" and design.land_length == 1e-3
    assert design.wrap_in == math.radians(2) and design.wrap_out == math.radians(3)
    assert design.corner_radius == (5e-6, 0.0) and design.modules == 3
    assert design.module_gap == 3e-4 and design.friction == 0.2
    assert design.transducers == (-1.3e-3, 0.0, 1.3e-3)
    # three equal coplanar modules, the gap between each two
    assert design._gaps() == (3e-4, 3e-4) and design.module_count == 3


def test_the_toml_table_states_the_same_head_as_the_options(tmp_path):
    from gyroshell.tape.config import load_config

    path = tmp_path / "head.toml"
    path.write_text(THREE_MODULES)
    table = load_config(path, tables=("head",)).tables["head"]
    from_file = _design([], table, path)
    from_options = _design([*FLAT, "--corner-radius", "5e-6,0", "--modules", "3",
                            "--module-gap", "3e-4", "--transducers", "-1.3e-3,0,1.3e-3",
                            "--friction", "0.2"])
    assert from_file == from_options
    # an option typed beside the file wins over the file's value
    assert _design(["--wrap-in", "1"], table, path).wrap_in == math.radians(1)


def test_the_arc_contact_key_and_option_state_the_models_option(tmp_path):
    from gyroshell.bearing.head_config import design_from_table

    table = {"kind": "flat", "land_length": "1 mm", "corner_radius": "1 mm",
             "wrap_in": "2 deg", "arc_contact": "point"}
    design = design_from_table(table, where="head.toml: ")
    assert design.arc_contact == "point" and design.model_options() == {"arc_contact": "point"}
    assert _design([*FLAT, "--corner-radius", "1e-4", "--arc-contact", "wrapped"]
                   ).arc_contact == "wrapped"
    assert _design(["--arc-contact", "wrapped"], table, tmp_path / "head.toml"
                   ).model_options() == {"arc_contact": "wrapped"}
    assert _design(FLAT).model_options() == {}


def test_per_module_tables_and_a_profile_relative_to_the_file(tmp_path):
    from gyroshell.bearing.head_config import design_from_table
    from gyroshell.tape.config import _tomllib

    table = _tomllib().loads("""
[head]
kind = "flat"
land_length = "1 mm"
wrap_in = "1 deg"
wrap_out = "1 deg"
module_gap = ["0.2 mm", "0.3 mm"]
[[head.module]]
tilt = "-0.5 deg"
[[head.module]]
height = "1 um"
land_length = "0.5 mm"
[[head.module]]
tilt = "0.5 deg"
""")["head"]
    design = design_from_table(table)
    assert design.module_count == 3 and design._gaps() == (2e-4, 3e-4)
    assert design.module_shapes[1] == ModuleShape(land_length=5e-4, height=1e-6)
    assert design.module_shapes[0].tilt == -math.radians(0.5)
    measured = design_from_table({"kind": "profile", "profile": "head.csv",
                                  "wrap_in": "2 deg", "wrap_out": 0.01}, folder=tmp_path)
    assert measured.profile == str(tmp_path / "head.csv") and measured.wrap_out == 0.01


@pytest.mark.parametrize("argv, message", [
    (["--head", "flat", "--land-length", "1e-3", "--wrap-in", "2", "--wrap-angle", "10"],
     "--wrap-angle is an option of a cylinder head, and this head is a flat (--head flat)"),
    (["--land-length", "1e-3"],
     "--land-length is an option of a flat head, and this head is a cylinder (the default "
     "cylinder)"),
    (["--head", "flat", "--land-length", "1e-3"], "a flat head needs a wrap: --wrap-in and "
                                                  "--wrap-out are both 0, so nothing presses "
                                                  "the tape onto the head"),
    (["--head", "flat", "--land-length", "1e-3", "--wrap-in", "0", "--wrap-out", "0"],
     "a flat head needs a wrap"),
    (["--head", "flat", "--wrap-in", "2"], "a flat head needs its land length: give "
                                           "--land-length"),
    ([*FLAT, "--modules", "3"], "3 modules need the gap between them: give --module-gap"),
    ([*FLAT, "--modules", "2", "--module-gap", "-1e-4"], "--module-gap must be > 0 m"),
    ([*FLAT, "--modules", "2", "--module-gap", "0"], "--module-gap must be > 0 m, got 0"),
    ([*FLAT, "--arc-contact", "point"],
     "--arc-contact point sets how the tape meets rounded corners, and this head's corners "
     "are all sharp (--corner-radius 0): drop --arc-contact or give --corner-radius > 0"),
    ([*FLAT[:4], "--wrap-in", "20", "--wrap-out", "20"],
     "--wrap-in must be below the flank angle 20 degrees (--flank-angle, its default), got "
     "20: beyond the outer corners the head falls away along the flanks"),
    ([*FLAT[:4], "--wrap-in", "2", "--wrap-out", "25", "--flank-angle", "25"],
     "--wrap-out must be below the flank angle 25 degrees (--flank-angle), got 25"),
    ([*FLAT, "--flank-angle", "90"], "--flank-angle must be in (0, 90) degrees, got 90"),
    ([*FLAT, "--module-gap", "1e-4"], "--module-gap is the gap between modules, and this "
                                      "head has one"),
    ([*FLAT, "--modules", "9", "--module-gap", "1e-4"], "--modules must be an integer in "
                                                        "[1, 8], got 9"),
    ([*FLAT, "--modules", "0"], "--modules must be an integer in [1, 8], got 0"),
    ([*FLAT[:6], "--wrap-out", "50"], "--wrap-out must be in [0, 45] degrees, got 50"),
    ([*FLAT, "--wrap-in", "-1"], "--wrap-in must be in [0, 45] degrees, got -1"),
    ([*FLAT, "--friction", "-0.1"], "--friction must be >= 0, got -0.1"),
    ([*FLAT, "--transducers", "0,,1e-4"], "--transducers: an empty item"),
    ([*FLAT, "--corner-radius", "1e-6,1e-6,1e-6"], "--corner-radius takes one radius or two"),
    (["--head", "wedge"], "--head must be cylinder, flat or a measured contour FILE.csv, got "
                          "'wedge'"),
    (["--head", "head.csv", "--land-length", "1e-3"],
     "--land-length is an option of a flat head, and this head is a profile (--head "
     "head.csv)"),
    (["--wrap-angle", "0"], "--wrap-angle must be in (0, 90] degrees, got 0"),
])
def test_bad_head_options_one_line_exit_2(cli, argv, message):
    line = _one_error_line(cli(["bearing", "--velocity", "4", "--infinitely-wide", *argv]))
    assert message in line


@pytest.mark.parametrize("table, message", [
    ('kind = "wedge"', "[head] kind must be one of cylinder, flat, profile, got 'wedge'"),
    ('kind = "flat"\nland = "1 mm"', "[head] unknown key(s) land; allowed: kind,"),
    ('kind = "flat"\nland_length = "1 mm"\nwrap_in = "2 parsec"',
     "[head] wrap_in: unit 'parsec' is not a unit of rad (use one of: rad, mrad, deg, °)"),
    ('kind = "flat"\nland_length = "1 mm"\nwrap_in = 2',
     "[head] wrap_in must be in [0, 0.785398] rad, got 2"),
    ('wrap_angle = "15 deg"\nland_length = "1 mm"',
     "[head] land_length is an option of a flat head, and this head is a cylinder ([head] "
     "without a kind)"),
    ('kind = "flat"\nland_length = "1 mm"\nwrap_in = "1 deg"\nmodules = 2\n'
     'module_gap = "0.1 mm"\n[[head.module]]\ntilt = "1 deg"',
     "[head] modules = 2 but 1 [head] module tables are given"),
    ('kind = "flat"\nland_length = "1 mm"\nwrap_in = "1 deg"\n[[head.module]]\nangle = 1',
     "[head] module[0] unknown key(s) angle; allowed: land_length, corner_radius, height"),
    ('kind = "profile"\nwrap_in = "1 deg"', "a measured head needs its contour: give "
                                            "[head] profile"),
    ('kind = "flat"\nland_length = "1 mm"\nwrap_in = "1 deg"\ntransducers = ["0 m", true]',
     "[head] transducers[1] must be a number or '<number> <unit>', got True"),
    ('kind = "flat"\nland_length = "1 mm"\nwrap_in = "1 deg"\narc_contact = "tangent"',
     "[head] arc_contact must be one of auto, point, wrapped, got 'tangent'"),
    ('kind = "flat"\nland_length = "1 mm"\nwrap_in = "1 deg"\narc_contact = 1',
     "[head] arc_contact must be text, got 1"),
    ('arc_contact = "wrapped"',
     "[head] arc_contact is an option of a flat head, and this head is a cylinder"),
    ('kind = "flat"\nland_length = "1 mm"\nwrap_in = "1 deg"\narc_contact = "point"',
     "[head] arc_contact point sets how the tape meets rounded corners, and this head's "
     "corners are all sharp ([head] corner_radius 0)"),
    ('kind = "flat"\nland_length = "1 mm"\nwrap_in = "1 deg"\nflank_angle = "1 deg"',
     "[head] wrap_in must be below the flank angle 0.01745 rad ([head] flank_angle), got "
     "0.01745"),
    ('kind = "flat"\nland_length = "1 mm"\nwrap_in = "1 deg"\nmodules = 2\n'
     'module_gap = "0 mm"', "[head] module_gap must be > 0 m, got 0"),
])
def test_bad_head_tables_name_the_file_and_key(cli, tmp_path, table, message):
    path = tmp_path / "bad.toml"
    path.write_text(f'[tape]\nvelocity = "4 m/s"\n\n[head]\n{table}\n')
    line = _one_error_line(cli(["bearing", "--config", path, "--infinitely-wide"]))
    assert f"bad.toml: {message}" in line


def test_other_commands_refuse_a_head_table(cli, tmp_path):
    path = tmp_path / "head.toml"
    path.write_text(THREE_MODULES)
    line = _one_error_line(cli(["static", "--config", path]))
    assert "unknown key(s) head beside [tape]" in line


PROFILE_ROWS = "x_m,z_m\n" + "".join(f"{x * 1e-4:.6e},{-(x * 1e-4) ** 2 / 0.04:.6e}\n"
                                     for x in range(-10, 11))


@pytest.mark.parametrize("argv, contents, message", [
    ([*FLAT, "--transducers", "0,2e-3"], None,
     "transducers[1] must lie on the head's wrapped region [-0.0005, 0.0005] m"),
    ([*FLAT, "--corner-radius", "0.01"], None, "is shorter than its corner radii allow"),
    (["--head", "{csv}", "--wrap-in", "1"], "", "the profile file is empty"),
    (["--head", "{csv}", "--wrap-in", "1"], "x,z\n0,0\n1e-4,oops\n", "row 2 is not numbers"),
    (["--head", "{csv}", "--wrap-in", "1"], "0,0\n2e-4,0\n1e-4,0\n3e-4,0\n",
     "x must be strictly increasing"),
    (["--head", "{csv}", "--wrap-in", "1", "--wrap-out", "1", "--transducers", "1"],
     PROFILE_ROWS, "transducers[0] must lie on the head's wrapped region"),
])
def test_contour_refusals_before_the_solve(cli, tmp_path, argv, contents, message):
    """What needs the contour (its corners, its extent, its file) is refused in one line
    when the head is built, before the outputs are touched or anything is solved."""
    csv = tmp_path / "head.csv"
    if contents is not None:
        csv.write_text(contents)
    out = tmp_path / "never"
    argv = [a.replace("{csv}", str(csv)) for a in argv]
    line = _one_error_line(cli(["bearing", "--velocity", "4", "--infinitely-wide", *argv,
                                "--out-dir", out]))
    assert message in line
    assert not out.exists()


def test_a_profile_larger_than_memory_allows_is_refused(cli, tmp_path, monkeypatch):
    csv = tmp_path / "huge.csv"
    csv.write_text(PROFILE_ROWS * 20)
    monkeypatch.setenv("GYROSHELL_MEMORY_LIMIT", "1000")
    line = _one_error_line(cli(["bearing", "--velocity", "4", "--infinitely-wide",
                                "--head", csv, "--wrap-in", "1"]))
    assert "huge.csv" in line and "more than the limit 1 kB" in line


# ----- issue 32: the head options as the help states them, files named in every message ----
def test_what_the_help_states_is_what_is_accepted():
    """The wraps' help names the flank angle that bounds them, and the refusal's remedy
    is an option the parser has; a steeper flank lets 20 degree wraps through."""
    parser = build_parser()
    bearing = parser._subparsers._group_actions[0].choices["bearing"]
    helps = {a.option_strings[0]: a.help for a in bearing._actions if a.option_strings}
    for flag in ("--wrap-in", "--wrap-out"):
        assert "in [0, 45]" in helps[flag] and "below --flank-angle (default 20)" in helps[flag]
    assert "(0, 90)" in helps["--flank-angle"] and "> 0" in helps["--module-gap"]
    assert "refused on sharp ones" in helps["--arc-contact"]
    design = _design([*FLAT[:4], "--wrap-in", "20", "--wrap-out", "20", "--flank-angle", "30"])
    assert design.flank_angle == math.radians(30) and design.wrap_in == math.radians(20)
    design.head()   # the contour accepts it too


def test_a_fifo_as_the_profile_is_refused_instead_of_blocking(cli_process, tmp_path):
    import os

    fifo = tmp_path / "p.csv"
    os.mkfifo(fifo)
    run = cli_process(["bearing", "--velocity", "4", "--infinitely-wide", "--head", fifo,
                       "--wrap-in", "1"], timeout=60)
    assert run.code == 2 and run.err.strip() == (f"gyroshell: error: {fifo} is not a regular "
                                                 "file, so not a profile CSV file")


def _profile(tmp_path, text, name="head.csv", encoding="utf-8"):
    path = tmp_path / name
    path.write_text(text, encoding=encoding)
    return path


def test_a_row_of_another_width_names_the_file_and_line(cli, tmp_path):
    rows = PROFILE_ROWS.splitlines(keepends=True)
    rows[5] = rows[5].rstrip("\n") + ",0\n"     # line 6: a third column
    csv = _profile(tmp_path, "".join(rows))
    line = _one_error_line(cli(["bearing", "--velocity", "4", "--infinitely-wide", "--head",
                                csv, "--wrap-in", "1"]))
    assert line == (f"gyroshell: error: {csv}: line 6: row 5 has 3 values, but the rows "
                    "before have 2: every row must be (x, z) or every row (x, y, z), m")


def test_a_byte_order_mark_is_not_a_header(tmp_path):
    from gyroshell.bearing.head import ProfileHead

    rows = PROFILE_ROWS.split("\n", 1)[1]         # no header line
    plain = ProfileHead.from_csv(_profile(tmp_path, rows), wrap_in=0.02, wrap_out=0.02)
    marked = ProfileHead.from_csv(_profile(tmp_path, rows, "bom.csv", "utf-8-sig"),
                                  wrap_in=0.02, wrap_out=0.02)
    assert (tmp_path / "bom.csv").read_bytes()[:3] == b"\xef\xbb\xbf"
    assert len(marked.x) == len(plain.x) == 21 and marked == plain


def test_a_profile_too_short_for_the_wrap_names_the_file(cli, tmp_path):
    short = "".join(f"{x * 1e-5:.6e},{-(x * 1e-5) ** 2 / 0.04:.6e}\n" for x in range(-3, 4))
    csv = _profile(tmp_path, short)
    line = _one_error_line(cli(["bearing", "--velocity", "4", "--infinitely-wide", "--head",
                                csv, "--wrap-in", "1", "--wrap-out", "1"]))
    assert line.startswith(f"gyroshell: error: {csv}: the profile does not contain the "
                           "wrapped region")


def test_a_profile_in_mm_names_the_file_and_the_unit_not_the_velocity(cli, tmp_path):
    in_mm = "x_mm,z_mm\n" + "".join(f"{x * 1e-1:.6e},{-(x * 1e-1) ** 2 / 40:.6e}\n"
                                     for x in range(-10, 11))   # 2 mm long, written in mm
    csv = _profile(tmp_path, in_mm)
    line = _one_error_line(cli(["bearing", "--velocity", "4", "--infinitely-wide", "--head",
                                csv, "--wrap-in", "1", "--wrap-out", "1"]))
    assert line == (f"gyroshell: error: {csv}: x spans 2 m, longer than any head (0.1 m): a "
                    "profile is in m; are its numbers in mm or um?")
    assert "velocity" not in line


def test_overlapping_modules_of_a_head_table_name_the_file_and_tables(cli, tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text('[tape]\nvelocity = "4 m/s"\n\n[head]\nkind = "flat"\n'
                    'land_length = "1 mm"\nwrap_in = "1 deg"\nwrap_out = "1 deg"\n'
                    'modules = 2\nmodule_gap = "0.1 mm"\n[[head.module]]\nheight = "0 um"\n'
                    '[[head.module]]\nheight = "100 um"\n')
    line = _one_error_line(cli(["bearing", "--config", path, "--infinitely-wide"]))
    assert line.startswith(f"gyroshell: error: {path}: [head] module[1] overlaps [head] "
                           "module[0]: with these heights, tilts and gaps")
