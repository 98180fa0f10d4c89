"""Files saved by release 0.1.0 still load, as the objects of their kind, and hold the
numbers today's engines compute for the same problems (tests/results/data/make_0_1_0.py
wrote them)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import gyroshell as g
from gyroshell import bearing

DATA = Path(__file__).resolve().parent / "data" / "0.1.0"
WIDTH = 6.35e-3
#: Same code path, same machine arithmetic: the stored numbers agree to round-off.
RTOL = 1e-9


@pytest.fixture(scope="module")
def tape():
    params = g.TapeParameters(length_ratio=2, spacing=WIDTH / 8)
    return params, g.TapeModel(params)


def test_static_file(tape):
    params, model = tape
    old = g.load(DATA / "static.nc")
    assert isinstance(old, g.StaticSolution)
    new = g.solve_static(model, 10.0)
    np.testing.assert_allclose(old.w, new.w, rtol=RTOL, atol=0)
    assert old.grid == new.grid and old.velocity == 10.0


def test_modes_file(tape):
    params, model = tape
    old = g.load(DATA / "modes.nc")
    assert isinstance(old, g.Modes)
    np.testing.assert_allclose(old.omega, g.modes(model, 10.0, count=4).omega, rtol=RTOL)


@pytest.mark.slow
def test_critical_file(tape):
    params, model = tape
    old = g.load(DATA / "critical.nc")
    assert isinstance(old, g.CriticalSpeeds)
    new = g.critical_speeds(model)
    assert old.critical_speed == pytest.approx(new.critical_speed, rel=RTOL)
    assert old.divergence_speed == pytest.approx(new.divergence_speed, rel=RTOL)


@pytest.mark.slow
def test_transient_file(tape):
    params, model = tape
    old = g.load(DATA / "transient.nc")
    assert isinstance(old, g.TransientResult)
    new = g.march(model, 10.0, dt=2e-6, steps=40, snapshot_every=20, record_energy=True)
    np.testing.assert_allclose(old.load_point, new.load_point, rtol=RTOL,
                               atol=RTOL * np.abs(new.load_point).max())
    np.testing.assert_allclose(old.snapshots.fields, new.snapshots.fields, rtol=RTOL,
                               atol=RTOL * np.abs(new.snapshots.fields).max())
    assert old.head_displacements is None


@pytest.mark.slow
@pytest.mark.parametrize("name", ["sweep_table.nc", "sweep_table.csv"])
def test_sweep_table_files_are_tables(tape, name):
    params, model = tape
    old = g.load(DATA / name)
    assert isinstance(old, pd.DataFrame)
    new = g.sweep(model, [0.0, 10.0, 20.0], count=3).to_frame()
    assert list(old.columns) == list(new.columns)
    omega = [c for c in new.columns if c.startswith("omega")]
    np.testing.assert_allclose(old[omega].to_numpy(float), new[omega].to_numpy(float),
                               rtol=RTOL)


def test_study_file():
    old = g.load(DATA / "study.nc")
    assert isinstance(old, g.StudyResult)
    assert list(old.table["tension"]) == [80.0, 100.0]
    assert np.all(np.isfinite(old.table["critical_speed"]))


def test_campbell_table_file_is_a_table():
    old = g.load(DATA / "campbell_table.nc")
    assert isinstance(old, pd.DataFrame) and {"velocity", "omega"} <= set(old.columns)


@pytest.mark.slow
@pytest.mark.parametrize("name", ["bearing.nc", "bearing_2d.nc"])
def test_bearing_files(name):
    old = g.load(DATA / name)
    assert isinstance(old, bearing.BearingSolution)
    new = bearing.solve_steady(old.model)
    central = old.summary()["central_spacing"]
    assert central == pytest.approx(new.summary()["central_spacing"], rel=1e-8)
    np.testing.assert_allclose(old.spacing, new.spacing, rtol=1e-8)
