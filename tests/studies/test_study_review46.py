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
