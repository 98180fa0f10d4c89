"""Parameter studies as review 46 found them wanting: head variables checked per point,
mixed point keys, ``count`` without ``modes``."""

from __future__ import annotations

import math

import pytest

from gyroshell import ParameterError, TapeParameters
from gyroshell.bearing.head_config import HeadDesign
from gyroshell.studies.head_study import BearingStudy, head_of_point
from gyroshell.studies.parameter_study import run_study

#: A flat head with no wrap of its own: the study's points give both.
BARE = HeadDesign(kind="flat", land_length=1e-3, transducers=(0.0,))
COARSE = TapeParameters(length_ratio=1.0, spacing=6.35e-3 / 8)


def test_a_flat_head_without_wraps_may_leave_them_to_the_points():
    setup = BearingStudy(BARE, infinitely_wide=True)   # accepted: the points may set them
    design = head_of_point(setup, {"wrap_in": 0.01, "wrap_out": 0.02})
    assert (design.wrap_in, design.wrap_out) == (0.01, 0.02)
    with pytest.raises(ParameterError, match="a flat head needs a wrap"):
        head_of_point(setup, {"tension": 80.0})     # the point's head is checked whole


@pytest.mark.parametrize("vary, point", [
    ({"wrap_in": [0.0, 0.01], "wrap_out": [0.0, 0.02]}, "point 0 {'wrap_in': 0.0, "
                                                        "'wrap_out': 0.0}"),
    ({"wrap_in": [0.01, 0.0]}, "point 1 {'wrap_in': 0.0}"),
])
def test_a_point_with_both_wraps_zero_is_refused_naming_it(vary, point):
    with pytest.raises(ParameterError) as info:
        run_study(TapeParameters(), vary=vary, compute="bearing", velocity=4.0, workers=1,
                  progress=False, bearing=BearingStudy(BARE, infinitely_wide=True))
    assert str(info.value).startswith(f"{point}: a flat head needs a wrap")


def test_the_base_head_is_still_checked_for_what_the_points_do_not_vary():
    with pytest.raises(ParameterError, match="^a flat head needs a wrap"):
        run_study(TapeParameters(), vary={"tension": [80.0]}, compute="bearing",
                  velocity=4.0, workers=1, progress=False,
                  bearing=BearingStudy(BARE, infinitely_wide=True))
    with pytest.raises(ParameterError, match="needs its land length"):
        run_study(TapeParameters(), vary={"wrap_in": [0.01]}, compute="bearing",
                  velocity=4.0, workers=1, progress=False,
                  bearing=BearingStudy(HeadDesign(kind="flat", wrap_out=0.01),
                                       infinitely_wide=True))


def test_varying_both_wraps_runs_every_point_over_its_own_head():
    """Tiny grid: each row's wraps are those of its point, and its spacing differs from
    the other wrap's (the wrap presses the tape: more wrap, more contact force)."""
    wraps = [math.radians(1.0), math.radians(3.0)]
    study = run_study(TapeParameters(), vary={"wrap_in": wraps, "wrap_out": [wraps[0]]},
                      compute="bearing", velocity=4.0, workers=1, progress=False,
                      bearing=BearingStudy(BARE, infinitely_wide=True, nx=80))
    assert study.failed.empty, study.failed.error.tolist()
    assert study.table.wrap_in.tolist() == wraps
    assert study.table.wrap_out.tolist() == [wraps[0]] * 2
    assert study.table.contact_force[1] > study.table.contact_force[0]


def test_points_setting_different_names_show_the_values_they_ran_with():
    """Row 0 sets only the speed, row 1 only the tension: each row's other cell is the
    base's value, and its critical speed is that of the tape it ran with (the membrane's
    closed form c = sqrt(T/rho) bounds it from above, and only T moves it)."""
    base = COARSE.replace(tension=90.0)
    study = run_study(base, points=[{"velocity": 1.0}, {"tension": 80.0}], velocity=0.0,
                      workers=1, progress=False)
    table = study.table
    assert table.velocity.tolist() == [1.0, 0.0]
    assert table.tension.tolist() == [90.0, 80.0]
    alone = run_study(base, points=[{"tension": 90.0}, {"tension": 80.0}], workers=1,
                      progress=False).table
    assert table.critical_speed.tolist() == alone.critical_speed.tolist()
    for t, c in zip(table.tension, table.critical_speed, strict=True):
        assert c > math.sqrt(t / base.density)   # bending stiffens: above the string's


def test_a_head_variable_a_point_does_not_set_shows_the_base_heads_value():
    design = HeadDesign(kind="flat", land_length=1e-3, wrap_in=0.02, transducers=(0.0,))
    study = run_study(TapeParameters(), points=[{"wrap_in": 0.01, "wrap_out": 0.03},
                                                {"tension": 80.0}],
                      compute="bearing", velocity=4.0, workers=1, progress=False,
                      bearing=BearingStudy(design, infinitely_wide=True, nx=80))
    assert study.failed.empty, study.failed.error.tolist()
    assert study.table.wrap_in.tolist() == [0.01, 0.02]
    assert study.table.wrap_out.tolist() == [0.03, 0.0]     # None: the head's 0
    assert study.table.tension.tolist() == [90.0, 80.0]


def test_count_without_modes_is_refused_as_the_command_refuses_it():
    with pytest.raises(ParameterError, match="^count is the number of frequencies of "
                                             "compute='modes'"):
        run_study(COARSE, vary={"tension": [80.0]}, compute="critical", count=5, workers=1)
    study = run_study(COARSE, vary={"tension": [80.0]}, compute="modes", workers=1,
                      progress=False)
    assert study.count == 3 and "omega_3" in study.table


@pytest.mark.parametrize("text", ["1,,2", "1,2,", ",1", " , "])
def test_an_empty_speed_is_refused(text):
    from gyroshell.studies.sweep import parse_velocities

    with pytest.raises(ParameterError, match="an empty entry"):
        parse_velocities(text, option="--velocities")
    assert parse_velocities("1, 2") == [1.0, 2.0]


def test_a_study_estimated_above_the_time_limit_opens_no_file(tmp_path, monkeypatch):
    cache = tmp_path / "c.jsonl"
    kwargs = dict(vary={"tension": [70.0, 80.0, 90.0]}, compute="critical", workers=1,
                  progress=False, cache=cache)
    monkeypatch.setenv("GYROSHELL_TIME_LIMIT", "1e-9")
    with pytest.raises(ParameterError, match=r"^a study of 3 points \(critical\) would take "
                                             "about .* more than the limit"):
        run_study(COARSE, **kwargs)
    assert not cache.exists()
    monkeypatch.setenv("GYROSHELL_TIME_LIMIT", "3600")
    study = run_study(COARSE, **kwargs)
    assert study.failed.empty and len(cache.read_text().splitlines()) == 3
