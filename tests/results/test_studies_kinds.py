"""The result kinds of gyroshell.studies round-trip through their files, field by field.

A SweepResult, a CampbellDiagram and a StudyResult saved as NetCDF and read back
(:func:`gyroshell.results.base.read`) hold the same arrays (values, dtypes, shapes), the same
settings and the same tape; tables also go to CSV / Parquet; old files still load.
"""

from __future__ import annotations

import dataclasses
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

sys.path.insert(0, str(Path(__file__).parent))
from examples_studies import EXAMPLES, TINY  # noqa: E402

import gyroshell  # noqa: E402
from gyroshell.results import base  # noqa: E402
from gyroshell.studies.campbell import (  # noqa: E402
    CampbellDiagram,
    _crossings_and_veerings,
)
from gyroshell.studies.sweep import SweepResult  # noqa: E402

pytest.importorskip("xarray")


def same_frame(a: pd.DataFrame, b: pd.DataFrame) -> None:
    """Equal columns in order, and each column equal bit for bit with its dtype."""
    assert list(a.columns) == list(b.columns) and a.shape == b.shape
    for column in a.columns:
        x, y = a[column].to_numpy(), b[column].to_numpy()
        assert x.dtype == y.dtype, column
        if x.dtype.kind == "f":
            assert np.array_equal(x, y, equal_nan=True), column
        else:
            assert np.array_equal(x, y), column


def same_fields(a, b) -> None:
    """Every dataclass field of two results equal (tables and arrays exactly)."""
    assert type(a) is type(b)
    for f in dataclasses.fields(a):
        x, y = getattr(a, f.name), getattr(b, f.name)
        if isinstance(x, pd.DataFrame):
            same_frame(x, y)
        elif isinstance(x, np.ndarray):
            assert x.dtype == y.dtype and x.shape == y.shape and np.array_equal(x, y), f.name
        else:
            assert x == y, f.name


@pytest.fixture(scope="module", params=sorted(EXAMPLES))
def example(request):
    return EXAMPLES[request.param]()


@pytest.mark.slow
def test_every_kind_round_trips_through_netcdf(example, tmp_path):
    path = example.save(tmp_path / f"{example.kind}.nc")
    back = base.read(path)
    same_fields(example, back)
    assert base.metadata(path)["gyroshell_type"] == example.kind
    assert back.summary() == example.summary()


@pytest.mark.slow
def test_every_kind_round_trips_through_a_dataset(example):
    same_fields(example, base.from_dataset(example.to_xarray()))


@pytest.mark.parametrize("suffix", [".csv", ".parquet"])
def test_tables_go_to_csv_and_parquet(example, tmp_path, suffix):
    path = example.save(tmp_path / f"t{suffix}")
    back = gyroshell.load(path)
    pd.testing.assert_frame_equal(back, example.to_frame(), check_exact=True)


def test_summaries_are_plain_json_values(example):
    import json

    summary = example.summary()
    assert json.loads(json.dumps(summary)) == summary


def test_sweep_stores_its_settings_and_the_tape():
    result = EXAMPLES["sweep"]()
    back = SweepResult.from_xarray(result.to_xarray())
    assert back.params == TINY and back.grid == result.grid
    assert back.velocities.tolist() == [0.0, 60.0, 110.0]
    assert (back.count, back.min_correlation, back.continuation) == (2, 0.5, True)
    ds = result.to_xarray()
    assert ds["velocities"].attrs["units"] == "m/s" and ds["omega"].attrs["units"] == "rad/s"


@pytest.mark.slow
def test_a_campbell_diagram_with_crossings_and_veerings_round_trips(tmp_path):
    # the closed-form pair of test_campbell: two crossing lines, then a veering pair
    s = np.linspace(0.0, 1.0, 21)
    crossing = pd.DataFrame({"velocity": np.concatenate([s, s]),
                             "branch": [0] * 21 + [1] * 21,
                             "rank": [0] * 21 + [1] * 21,
                             "omega": np.concatenate([1 + s, 2 - s]),
                             "growth_rate": 0.0,
                             "mac": np.tile(np.r_[np.nan, np.ones(20)], 2)})
    crossings, _ = _crossings_and_veerings(crossing, 0.02)
    half = np.sqrt((0.5 - s) ** 2 + 0.005**2)
    veering = crossing.assign(omega=np.concatenate([1.5 - half, 1.5 + half]))
    _, veerings = _crossings_and_veerings(veering, 0.02)
    assert len(crossings) == 1 and len(veerings) == 1
    d = CampbellDiagram(crossing, crossings, veerings, None, {"min_mac": 0.5}, TINY)
    back = base.read(d.save(tmp_path / "c.nc"))
    same_fields(d, back)
    assert back.critical_speed is None


@pytest.mark.slow
def test_old_sweep_and_campbell_tables_load_as_tables(tmp_path):
    """Before, a sweep and a Campbell diagram were saved as their table (kind "table")."""
    for result in (EXAMPLES["sweep"](), EXAMPLES["campbell"]()):
        path = gyroshell.save(result.to_frame(), tmp_path / "old.nc")
        pd.testing.assert_frame_equal(gyroshell.load(path), result.to_frame(),
                                      check_exact=True)
