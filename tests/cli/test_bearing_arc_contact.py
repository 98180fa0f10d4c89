"""`gyroshell bearing --arc-contact` and ``arc_contact`` in the ``[head]`` table: the rounded
corners' contact model reaches the BearingModel (the same numbers as the Python solve), the
JSON says which model met each corner, and bad values are refused in one line (exit 2).

The solves are 1-D at 8 m/s on 200-400 intervals (a few hundredths of a second each: at
4 m/s the 2.5 mm corners need pseudo-time, about 2 s)."""

from __future__ import annotations

import json
import math

import pytest
from bearing_cases import FIRST_ORDER, HARD, LEGACY_CLI

from gyroshell import TapeParameters
from gyroshell.bearing import BearingModel
from gyroshell.bearing.head import FlatHead, Module
from gyroshell.bearing.model import WRAPPED_ARC_BENDING_LENGTHS
from gyroshell.bearing.steady import solve_steady
from gyroshell.core.errors import ConvergenceError

VELOCITY, NX = 8.0, 200


def _argv(land=1e-3, radius=2.5e-3, wrap=2, nx=NX):
    return ["bearing", *LEGACY_CLI, "--head", "flat", "--land-length", land,
            "--corner-radius", radius,
            "--wrap-in", wrap, "--wrap-out", wrap, "--transducers", "0", "--velocity",
            VELOCITY, "--infinitely-wide", "--nx", nx, "--quiet"]


def _model(land=1e-3, radius=2.5e-3, wrap=2, nx=NX, **kw):
    head = FlatHead((Module(land, corner_radius=radius),), math.radians(wrap),
                    math.radians(wrap), transducers=(0.0,))
    return BearingModel(TapeParameters(), FIRST_ORDER,
                        velocity=VELOCITY, head=head,
                        infinitely_wide=True, nx=nx, **kw, contact=HARD)


def _json(cli, argv) -> dict:
    run = cli([*argv, "--json"])
    assert run.code == 0, run.err
    return json.loads(run.out)


def _one_error_line(run) -> str:
    assert run.code == 2, run.err
    assert "Traceback" not in run.err and len(run.error_lines) == 1, run.err
    assert run.error_lines[0].startswith("gyroshell: error: ")
    return run.error_lines[0]


def test_wrapped_on_the_cli_is_the_python_solve_with_wrapped_arcs(cli):
    """2.5 mm corners at 2°: r_c θ_c = 0.48 bending lengths, past the handover."""
    model = _model(arc_contact="wrapped")
    assert model.wrapped_corners == (0, 1)
    lam = model.bending_length
    assert 2.5e-3 * math.radians(2) > WRAPPED_ARC_BENDING_LENGTHS * lam
    out = _json(cli, [*_argv(), "--arc-contact", "wrapped"])
    sol = solve_steady(model)
    assert out["central_spacing"] == sol.central_spacing
    assert out["minimum_spacing"] == sol.minimum_spacing
    assert out["contact_force"] == sol.contact_force
    assert [c["force"] for c in out["corner_forces"]] == [c.force for c in sol.corner_forces]
    assert out["arc_contact"] == "wrapped"
    assert out["corner_arc_models"] == ["wrapped", "wrapped"]


def test_the_option_reaches_the_model_within_the_handover(cli):
    """1 mm corners at 2° (0.19 bending lengths): auto touches each at a point, wrapped
    puts the arcs in the contact set; both hold there, so on 800 intervals their central
    spacings agree within 3 % (measured 1.4 %; on 400, 5.6 %: the wrapped arcs' corner
    refinement takes most of so few nodes) but are not the same numbers."""
    auto = _json(cli, _argv(radius=1e-3, nx=800))
    wrapped = _json(cli, [*_argv(radius=1e-3, nx=800), "--arc-contact", "wrapped"])
    assert auto["arc_contact"] == "auto" and auto["corner_arc_models"] == ["point", "point"]
    assert wrapped["corner_arc_models"] == ["wrapped", "wrapped"]
    assert wrapped["central_spacing"] != auto["central_spacing"]
    assert wrapped["central_spacing"] == pytest.approx(auto["central_spacing"], rel=0.03)


def test_sharp_corners_and_the_cylinder_report_no_arc_model(cli):
    out = _json(cli, _argv(radius=0))
    assert out["corner_arc_models"] == ["sharp", "sharp"]
    cylinder = _json(cli, ["bearing", "--velocity", "4", "--infinitely-wide", "--quiet"])
    assert "corner_arc_models" not in cylinder and "arc_contact" not in cylinder


def test_point_beyond_the_handover_gives_the_models_error_in_one_line(cli):
    """10 mm corners on a 4 mm land at 4° (r_c θ_c = 3.9 bending lengths: the tape wraps
    them); forced point contacts fail as the Python solve fails, plus a hint."""
    geometry = {"land": 4e-3, "radius": 10e-3, "wrap": 4}
    model = _model(**geometry, arc_contact="point")
    assert model.wrapped_corners == () and len(model.corner_contacts) == 2
    with pytest.raises(ConvergenceError) as info:
        solve_steady(model)
    line = _one_error_line(cli([*_argv(**geometry), "--arc-contact", "point"]))
    assert f"no steady flying state reached for this input: {info.value}" in line
    assert line.endswith("try --arc-contact wrapped or auto)")


@pytest.mark.parametrize("argv, message", [
    ([*_argv(), "--arc-contact", "tangent"],
     "--arc-contact must be one of auto, point, wrapped, got 'tangent'"),
    (["bearing", "--velocity", "4", "--infinitely-wide", "--arc-contact", "point"],
     "--arc-contact is an option of a flat head, and this head is a cylinder"),
    (["study", "--vary", "tension=80,90", "--compute", "bearing", "--head", "flat",
      "--land-length", "1e-3", "--wrap-in", "2", "--velocity", "4", "--arc-contact", "x"],
     "--arc-contact must be one of auto, point, wrapped, got 'x'"),
    (["study", "--vary", "tension=80,90", "--compute", "modes", "--arc-contact", "wrapped"],
     "--arc-contact sets up --compute bearing"),
])
def test_bad_arc_contact_is_one_line_exit_2(cli, argv, message):
    assert message in _one_error_line(cli(argv))


def test_the_toml_key_flies_as_the_option(cli, tmp_path):
    path = tmp_path / "head.toml"
    path.write_text(f'[tape]\nvelocity = "{VELOCITY} m/s"\n\n[head]\nkind = "flat"\n'
                    'land_length = "1 mm"\ncorner_radius = "1 mm"\nwrap_in = "2 deg"\n'
                    'wrap_out = "2 deg"\ntransducers = ["0 mm"]\narc_contact = "wrapped"\n')
    from_file = _json(cli, ["bearing", *LEGACY_CLI, "--config", path, "--infinitely-wide",
                            "--nx", NX,
                            "--quiet"])
    from_options = _json(cli, [*_argv(radius=1e-3), "--arc-contact", "wrapped"])
    assert from_file["corner_arc_models"] == ["wrapped", "wrapped"]
    assert from_file["central_spacing"] == from_options["central_spacing"]
    # the option typed beside the file wins
    point = _json(cli, ["bearing", *LEGACY_CLI, "--config", path, "--infinitely-wide", "--nx", NX,
                        "--quiet", "--arc-contact", "point"])
    assert point["corner_arc_models"] == ["point", "point"]


def test_a_head_study_solves_with_the_designs_arc_model():
    """compute="bearing" with arc_contact="wrapped" in the head design: the row is the
    Python solve of that model (the study's default would touch the 1 mm corners at a
    point)."""
    from gyroshell.bearing.head_config import HeadDesign
    from gyroshell.studies.head_study import BearingStudy
    from gyroshell.studies.parameter_study import run_study

    wrap = math.radians(2)
    design = HeadDesign(kind="flat", land_length=1e-3, corner_radius=1e-3, wrap_in=wrap,
                        wrap_out=wrap, transducers=(0.0,), arc_contact="wrapped")
    setup = BearingStudy(head=design, infinitely_wide=True, nx=NX, air=FIRST_ORDER, contact=HARD)
    study = run_study(TapeParameters(), vary={"tension": [90.0]}, compute="bearing",
                      velocity=VELOCITY, workers=1, bearing=setup, progress=False)
    assert study.failed.empty, study.failed.error.tolist()
    model = _model(radius=1e-3, arc_contact="wrapped")
    assert model.wrapped_corners == (0, 1)
    (row,) = study.table.itertuples()
    assert row.central_spacing == solve_steady(model).central_spacing


def test_the_help_states_the_models_handover():
    from gyroshell.cli import build_parser

    sub = build_parser()._subparsers._group_actions[0].choices["bearing"]
    (action,) = [a for a in sub._actions if "--arc-contact" in a.option_strings]
    assert f"exceeds {WRAPPED_ARC_BENDING_LENGTHS:g} bending lengths" in action.help
