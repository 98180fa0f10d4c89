"""One march per (tape, V, Δt) for the reproductions' step-load runs (reproduce/_marches.py).

A Newmark march is deterministic and its step n does not depend on the steps after it, so
the first n steps of an N-step run are the n-step run bit for bit; what the shared runs
hand out must therefore equal a march made for the request exactly (assert_array_equal,
not a tolerance), whichever request came first.
"""

from __future__ import annotations

import numpy as np
import pytest

from gyroshell import TapeModel
from gyroshell.engines.newmark import march
from gyroshell.reproduce import Settings
from gyroshell.reproduce._marches import sharing_marches, step_response
from gyroshell.reproduce._runner import SHARED_RUNS, _units, study_module

QUICK = Settings(quick=True, progress=False)
DT = 2e-6  # s
SPEED = 50.0  # m/s


@pytest.mark.parametrize("symmetry", [True, False])
def test_the_first_steps_of_a_longer_march_are_the_shorter_march(symmetry):
    model = TapeModel(QUICK.params(length_ratio=19))
    times = [8e-6, 40e-6]
    short = march(model, SPEED, dt=DT, steps=20, centerline_times=times, progress=False,
                  symmetry=symmetry)
    long = march(model, SPEED, dt=DT, steps=45, centerline_times=DT * np.arange(46),
                 progress=False, symmetry=symmetry)
    assert short.info["symmetry"] == ("half" if symmetry else "full")
    np.testing.assert_array_equal(long.times[:21], short.times)
    np.testing.assert_array_equal(long.load_point[:21], short.load_point)
    np.testing.assert_array_equal(long.snapshots.centerlines[[4, 20]],
                                  short.snapshots.centerlines)


def assert_same(a, b):
    for name in ("times", "load_point", "x", "centerline_times", "centerlines"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name), err_msg=name)


def test_a_shorter_request_is_sliced_from_the_longest_run_and_equals_its_own_march():
    lines = [4e-6, 24e-6]
    alone = step_response(QUICK, SPEED, DT, 12, centerline_times=lines)  # outside: marched
    assert alone.centerlines.shape == (2, len(alone.x)) and len(alone.times) == 13
    with sharing_marches() as shared:
        step_response(QUICK, SPEED, DT, 30)
        sliced = step_response(QUICK, SPEED, DT, 12, centerline_times=lines)
        assert (shared.marches, shared.slices) == (1, 1)
        assert_same(sliced, alone)
        longer = step_response(QUICK, SPEED, DT, 40, centerline_times=lines)  # marches again
        other = step_response(QUICK, 0.0, DT, 12)                            # another V
        assert (shared.marches, shared.slices) == (3, 1)
        assert_same(step_response(QUICK, SPEED, DT, 40, centerline_times=lines), longer)
        assert shared.slices == 2 and other.centerlines.shape == (0, len(other.x))
        with sharing_marches() as inner:
            assert inner is shared
    with sharing_marches() as fresh:                                          # dropped
        step_response(QUICK, SPEED, DT, 12)
        assert fresh.marches == 1


def test_parts_sharing_a_run_go_to_one_worker_longest_first():
    class Study:
        def __init__(self, keys):
            self.keys = keys

    tasks = [("fig2", 0.0), ("fig2", 50.0), ("fig5", None), ("period", 0.0),
             ("period", 50.0), ("observations", "wavelengths"), ("critical", ("free", 4.0))]
    studies = {"fig2": Study([0.0, 50.0]), "fig5": Study(None), "period": Study([0.0, 50.0]),
               "observations": Study(["wavelengths"]), "critical": Study([("free", 4.0)])}
    units = _units(tasks, studies)
    assert [[m[:2] for m in u] for u in units] == [
        [("period", 50.0), ("fig2", 50.0), ("fig5", None), ("observations", "wavelengths")],
        [("period", 0.0), ("fig2", 0.0)], [("critical", ("free", 4.0))]]
    assert [m[2] for m in units[0]] == [False, False, True, False]  # fig5: a whole study


def test_every_shared_run_names_a_part_that_exists():
    for name, key in SHARED_RUNS:
        module = study_module(name)
        if key is None:
            assert not hasattr(module, "parts"), name
        else:
            assert key in module.parts(Settings()), (name, key)
