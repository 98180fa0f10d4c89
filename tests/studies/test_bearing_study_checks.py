"""Bearing studies refuse up front what the single ``gyroshell bearing`` refuses (issue 32):
a speed of 0 (the default, or a varied speed through 0) and grids beyond the memory; they
accept the speeds of either sign that the bearing model accepts; and a point whose solve
fails carries the single command's hint in its row."""

from __future__ import annotations

import math

import pytest
from bearing_cases import FIRST_ORDER, HARD

from gyroshell import ParameterError, TapeParameters, run_study
from gyroshell.bearing import AirParameters, BearingModel
from gyroshell.bearing.head import FlatHead, Module
from gyroshell.bearing.head_config import HeadDesign
from gyroshell.bearing.steady import solve_steady
from gyroshell.core.budget import MEMORY_LIMIT_VARIABLE
from gyroshell.core.errors import ConvergenceError
from gyroshell.studies.head_study import BearingStudy

WRAP = math.radians(2.0)
FLAT = HeadDesign(kind="flat", land_length=1e-3, wrap_in=WRAP, wrap_out=WRAP)
ONE_D = BearingStudy(head=FLAT, infinitely_wide=True, nx=160)
STUDY = ["study", "--head", "flat", "--land-length", "1e-3", "--wrap-in", "2", "--wrap-out",
         "2", "--infinitely-wide", "--nx", "160", "--compute", "bearing", "--workers", "1",
         "--quiet"]


def _refused(run, match: str) -> None:
    assert run.code == 2, run.err
    assert len(run.error_lines) == 1 and run.error_lines[0].startswith("gyroshell: error: ")
    assert match in run.err and "Traceback" not in run.err and run.out == ""


# ----- a speed of 0 ------------------------------------------------------------------------
def test_the_default_speed_of_0_is_refused_before_any_work(tmp_path):
    cache = tmp_path / "c.jsonl"
    with pytest.raises(ParameterError, match="velocity must be nonzero for an air bearing"):
        run_study(vary={"tension": [80.0, 90.0]}, compute="bearing", bearing=ONE_D,
                  workers=1, cache=cache, progress=False)
    assert not cache.exists()


def test_a_speed_varied_through_0_is_refused_naming_the_point():
    with pytest.raises(ParameterError, match=r"point 1 \{'velocity': 0.0\}: velocity must "
                                             "be nonzero for an air bearing"):
        run_study(vary={"velocity": [-4.0, 0.0, 4.0]}, compute="bearing", bearing=ONE_D,
                  workers=1, progress=False)


def test_the_command_line_refuses_a_speed_of_0_in_one_line(cli, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    _refused(cli([*STUDY, "--vary", "tension=80,90", "--cache", "c.jsonl", "--out", "s.csv"]),
             "velocity must be nonzero for an air bearing (either sign: the tape running "
             "along +x or -x, e.g. 4 or -4 m/s), got 0: give it (--velocity), or vary it")
    _refused(cli([*STUDY, "--vary", "velocity=-4,0,4", "--cache", "c.jsonl"]),
             "point 1 {'velocity': 0.0}: velocity must be nonzero for an air bearing")
    assert list(tmp_path.iterdir()) == []


# ----- speeds of either sign ---------------------------------------------------------------
def test_negative_speeds_run_as_the_bearing_model_runs_them():
    study = run_study(vary={"velocity": [-4.0, 4.0]}, compute="bearing", bearing=ONE_D,
                      workers=1, progress=False)
    assert study.failed.empty, study.failed.error.tolist()
    head = FlatHead((Module(1e-3),), WRAP, WRAP)
    for row in study.table.itertuples():
        direct = solve_steady(BearingModel(TapeParameters(), AirParameters(),
                                           velocity=row.velocity, head=head,
                                           infinitely_wide=True, nx=160))
        assert row.central_spacing == direct.central_spacing
        assert row.minimum_spacing == direct.minimum_spacing
    backwards = run_study(vary={"tension": [90.0]}, velocity=-4.0, compute="bearing",
                          bearing=ONE_D, workers=1, progress=False)
    assert backwards.table["central_spacing"][0] == study.table["central_spacing"][0]


def test_negative_speeds_stay_refused_where_the_tape_alone_is_computed(cli):
    with pytest.raises(ParameterError, match="velocity must be >= 0 m/s, got -4"):
        run_study(vary={"tension": [90.0]}, velocity=-4.0, compute=["bearing", "critical"],
                  bearing=ONE_D, workers=1, progress=False)
    run = cli([*STUDY, "--vary", "tension=90", "--velocity", "-4", "--json"])
    assert run.code == 0, run.err
    assert '"failed": 0' in run.out


# ----- memory ------------------------------------------------------------------------------
def test_a_2d_study_beyond_the_memory_is_refused_before_any_work(tmp_path, monkeypatch):
    """The single command's check (gyroshell.bearing.budget), at every point, up front."""
    monkeypatch.setenv(MEMORY_LIMIT_VARIABLE, "2e8")
    cache = tmp_path / "c.jsonl"
    setup = BearingStudy(head=FLAT, nx=160)
    with pytest.raises(ParameterError, match=r"point 0 \{'width': 0.02\}: a bearing grid of "
                                             r"160 x \d+ intervals .* needs about"):
        run_study(vary={"width": [0.02, 0.04]}, velocity=4.0, compute="bearing",
                  bearing=setup, workers=1, cache=cache, progress=False)
    assert not cache.exists()


def test_the_command_line_refuses_a_study_beyond_the_memory(cli, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    run = cli(["study", "--vary", "tension=80,90", "--velocity", "4", "--compute", "bearing",
               "--nx", "3000", "--ny", "3000", "--workers", "1", "--quiet", "--out", "s.csv"])
    _refused(run, "point 0 {'tension': 80.0}: a bearing grid of 3000 x 3000 intervals")
    assert list(tmp_path.iterdir()) == []


# ----- a failed row's hint -----------------------------------------------------------------
def test_a_failed_row_carries_the_single_commands_hint(cli):
    """10 mm corners on a 4 mm land at 4 deg, 8 m/s, forced point contacts: the tape wraps
    the arcs, the solve fails as the Python solve fails, and the row says what to try."""
    head = FlatHead((Module(4e-3, corner_radius=10e-3),), math.radians(4), math.radians(4),
                    transducers=(0.0,))
    model = BearingModel(TapeParameters(), FIRST_ORDER, velocity=8.0, head=head,
                         infinitely_wide=True, nx=200, arc_contact="point", contact=HARD)
    with pytest.raises(ConvergenceError) as direct:
        solve_steady(model)
    design = HeadDesign(kind="flat", land_length=4e-3, corner_radius=10e-3,
                        wrap_in=math.radians(4), wrap_out=math.radians(4), transducers=(0.0,),
                        arc_contact="point")
    study = run_study(vary={"tension": [90.0]}, velocity=8.0, compute="bearing",
                      bearing=BearingStudy(head=design, infinitely_wide=True, nx=200,
                                           air=FIRST_ORDER, contact=HARD),
                      workers=1, progress=False)
    error = study.table["error"][0]
    assert error.startswith(f"bearing: ConvergenceError: {direct.value} (--arc-contact "
                            "point on a rounded corner")
    assert error.endswith("try --arc-contact wrapped or auto)")
