"""Head design studies (compute="bearing"): each row is the direct steady solve of its
point's tape and head, bit for bit, on every executor and through the cache; head variables
are checked as the head checks them."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from gyroshell import ParameterError, TapeParameters
from gyroshell.bearing import AirParameters, BearingModel
from gyroshell.bearing.head import FlatHead, Module
from gyroshell.bearing.head_config import HeadDesign
from gyroshell.bearing.steady import solve_steady
from gyroshell.core.files import read_csv_exact
from gyroshell.studies.head_study import BearingStudy
from gyroshell.studies.parameter_study import run_study

WRAP = math.radians(2.0)
NX = 160
DESIGN = HeadDesign(kind="flat", land_length=1e-3, wrap_in=WRAP, wrap_out=WRAP,
                    transducers=(-2e-4, 0.0), friction=0.2)
SETUP = BearingStudy(head=DESIGN, infinitely_wide=True, nx=NX)
WRAPS_IN = [math.radians(1.0), math.radians(3.0)]


@pytest.fixture(scope="module")
def study():
    return run_study(TapeParameters(), vary={"wrap_in": WRAPS_IN, "tension": [80.0, 100.0]},
                     compute="bearing", velocity=4.0, workers=1, bearing=SETUP,
                     progress=False)


def _direct(wrap_in: float, tension: float):
    """The point's state solved directly, its head built from the head's own classes."""
    head = FlatHead((Module(1e-3),), wrap_in, WRAP, transducers=(-2e-4, 0.0), friction=0.2)
    model = BearingModel(TapeParameters(tension=tension), AirParameters(), velocity=4.0,
                         head=head, infinitely_wide=True, nx=NX)
    return solve_steady(model)


def test_every_row_is_the_direct_solve_of_its_point(study):
    assert study.failed.empty, study.failed.error.tolist()
    assert len(study.table) == 4
    for row in study.table.itertuples():
        sol = _direct(row.wrap_in, row.tension)
        assert row.central_spacing == sol.central_spacing
        assert row.minimum_spacing == sol.minimum_spacing
        for k, line in enumerate(sol.transducer_lines, start=1):
            assert getattr(row, f"transducer_{k}_min_spacing") == line.minimum
            assert getattr(row, f"transducer_{k}_mean_spacing") == line.mean
        land = [t for t in sol.tents if t.side == "land"]
        for j, (tent, share) in enumerate(zip(land, sol.corner_forces, strict=True), start=1):
            assert getattr(row, f"corner_{j}_force") == share.force
            expected = math.nan if tent.height is None else tent.height
            assert np.array_equal(getattr(row, f"corner_{j}_tent_height"), expected,
                                  equal_nan=True)
        assert row.drag == sol.drag and row.tension_rise == sol.tension_rise
        assert row.tension_ratio == sol.tension_ratio
        assert row.newton_iterations == sol.info.iterations


def test_the_columns_follow_the_head(study):
    columns = list(study.table.columns)
    assert columns[:3] == ["point", "wrap_in", "tension"]
    assert "transducer_2_mean_spacing" in columns and "corner_2_force" in columns
    assert "transducer_3_min_spacing" not in columns and "corner_3_force" not in columns
    # the infinitely wide tape: a line's minimum and mean over its one column coincide
    assert (study.table.transducer_1_min_spacing == study.table.transducer_1_mean_spacing).all()


def test_more_wrap_at_the_leading_corner_loads_it_more_and_tents_higher(study):
    """The corner's point load (T − ρV²)θ grows with its wrap, and so does the tent the
    bending stiffness lifts beside it (height ~ θ √(D/T) before the suction holds it)."""
    for _tension, group in study.table.groupby("tension"):
        group = group.sort_values("wrap_in")
        assert group.corner_1_force.is_monotonic_increasing
        assert group.corner_1_tent_height.is_monotonic_increasing


def test_the_cache_gives_the_rows_back_and_the_file_keeps_the_setup(study, tmp_path):
    cache = tmp_path / "points.jsonl"
    vary = {"wrap_in": WRAPS_IN[:1]}
    first = run_study(TapeParameters(), vary=vary, compute="bearing", velocity=4.0,
                      workers=1, bearing=SETUP, cache=cache, progress=False)
    again = run_study(TapeParameters(), vary=vary, compute="bearing", velocity=4.0,
                      workers=1, bearing=SETUP, cache=cache, progress=False)
    assert again.info["computed"] == 0 and again.table.equals(first.table)
    path = tmp_path / "study.nc"
    first.save(path)
    from gyroshell import load

    back = load(path)
    assert back.table.equals(first.table) and back.bearing == SETUP.spec()
    assert json.loads(json.dumps(back.bearing))["head"]["land_length"] == 1e-3


@pytest.mark.parametrize("kwargs, message", [
    (dict(vary={"wrap_in": [0.01]}, compute="critical"),
     "wrap_in: a head's parameters vary in a bearing study: add compute='bearing'"),
    (dict(vary={"wrap_angle": [0.2]}, compute="bearing", bearing=SETUP),
     "point 0 {'wrap_angle': 0.2}: wrap_angle is not a parameter of a flat head"),
    (dict(vary={"wrap_in": [-0.01]}, compute="bearing", bearing=SETUP),
     "point 0 {'wrap_in': -0.01}: wrap_in must be in [0, 0.785398] rad, got -0.01"),
    (dict(vary={"land_length": [1e-3, 1e-5]}, compute="bearing",
          bearing=BearingStudy(head=DESIGN.replace(transducers=(4e-4,)))),
     "point 1 {'land_length': 1e-05}: transducers[0] must lie on the head's wrapped region"),
    (dict(vary={"tension": [90.0]}, compute="critical", bearing=SETUP),
     "bearing sets up compute='bearing': add it to compute or drop bearing"),
])
def test_bad_head_points_are_refused_before_any_work(kwargs, message):
    with pytest.raises(ParameterError) as info:
        run_study(TapeParameters(), velocity=4.0, workers=1, progress=False, **kwargs)
    assert message in str(info.value)


@pytest.mark.slow
def test_local_processes_give_the_same_rows(study):
    again = run_study(TapeParameters(), vary={"wrap_in": WRAPS_IN, "tension": [80.0, 100.0]},
                      compute="bearing", velocity=4.0, workers=2, bearing=SETUP,
                      progress=False)
    assert again.info["executor"] != study.info["executor"]
    assert again.table.equals(study.table)


@pytest.mark.slow
def test_a_dask_cluster_gives_the_same_rows(study):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        again = run_study(TapeParameters(),
                          vary={"wrap_in": WRAPS_IN, "tension": [80.0, 100.0]},
                          compute="bearing", velocity=4.0, bearing=SETUP, chunk_size=1,
                          scheduler=cluster.scheduler_address, progress=False)
    assert again.info["executor"].startswith("dask(tcp://")
    assert again.table.equals(study.table)


def test_the_study_command(cli, tmp_path):
    out = tmp_path / "wraps.csv"
    run = cli(["study", "--compute", "bearing", "--head", "flat", "--land-length", "1e-3",
               "--wrap-out", "2", "--transducers", "0", "--infinitely-wide", "--nx", NX,
               "--vary", "wrap_in=1,3deg", "--velocity", "4", "--workers", "1", "--out", out,
               "--quiet"])
    assert run.code == 0, run.err
    table = read_csv_exact(out)
    assert table.wrap_in.tolist() == [math.radians(1.0), math.radians(3.0)]
    assert table.error.isna().all()          # empty: every point succeeded
    assert (table.transducer_1_min_spacing > 0).all()


@pytest.mark.parametrize("argv, message", [
    (["--compute", "critical", "--vary", "tension=80,90", "--land-length", "1e-3"],
     "--land-length sets up --compute bearing: add it or drop --land-length"),
    (["--compute", "critical", "--vary", "tension=80,90", "--infinitely-wide"],
     "--infinitely-wide sets up --compute bearing"),
    (["--compute", "bearing", "--vary", "wrap_in=1,2", "--head", "flat", "--land-length",
      "1e-3", "--wrap-in", "2"], "--wrap-in and --vary wrap_in both set wrap_in"),
    (["--compute", "bearing", "--vary", "wrap_angle=10,20", "--head", "flat",
      "--land-length", "1e-3", "--wrap-in", "2"], "wrap_angle is not a parameter of a flat "
                                                  "head"),
])
def test_study_head_options_refused_in_one_line(cli, argv, message):
    run = cli(["study", *argv, "--workers", "1", "--quiet"])
    assert run.code == 2 and len(run.error_lines) == 1, run.err
    assert message in run.error_lines[0]


def test_wrap_varies_both_wraps_at_once():
    """``wrap`` is wrap_in = wrap_out: each row is the direct solve of the head built with
    both wraps at that angle."""
    setup = BearingStudy(head=HeadDesign(kind="flat", land_length=1e-3,
                                         transducers=(-2e-4, 0.0), friction=0.2),
                         infinitely_wide=True, nx=NX)
    wraps = [math.radians(1.5), math.radians(2.5)]
    study = run_study(TapeParameters(), vary={"wrap": wraps}, compute="bearing",
                      velocity=4.0, workers=1, bearing=setup, progress=False)
    assert study.failed.empty and study.table.wrap.tolist() == wraps
    for row in study.table.itertuples():
        head = FlatHead((Module(1e-3),), row.wrap, row.wrap, transducers=(-2e-4, 0.0),
                        friction=0.2)
        sol = solve_steady(BearingModel(TapeParameters(), AirParameters(), velocity=4.0,
                                        head=head, infinitely_wide=True, nx=NX))
        assert row.central_spacing == sol.central_spacing
        assert row.transducer_1_min_spacing == sol.transducer_lines[0].minimum


@pytest.mark.parametrize("kwargs, message", [
    ({"vary": {"wrap": [0.03], "wrap_in": [0.02]}},
     "wrap sets both wrap_in and wrap_out: vary wrap or wrap_in, not both"),
    ({"vary": {"wrap": [0.03]}, "bearing": BearingStudy()},
     "wrap (wrap_in and wrap_out) is not a parameter of a cylinder head"),
])
def test_wrap_is_refused_beside_a_wrap_or_on_a_cylinder(kwargs, message):
    kwargs = {"bearing": SETUP, **kwargs}
    with pytest.raises(ParameterError, match=message.replace("(", r"\(").replace(")", r"\)")):
        run_study(TapeParameters(), compute="bearing", velocity=4.0, workers=1,
                  progress=False, **kwargs)
