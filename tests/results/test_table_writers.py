"""Every table writer goes through results.base.write_table: missing values are written as
``NaN`` and read back by gyroshell.load as NaN floats (not text), every other float exact."""

from __future__ import annotations

import dataclasses

import examples_timefreq as ex
import numpy as np
import pandas as pd
import pytest

import gyroshell
from gyroshell.reproduce._common import save_csv


def _same_with_nan(read: pd.Series, written) -> None:
    """``read`` is float64 and equal to ``written`` bit for bit, NaN where it is NaN."""
    written = np.asarray(written, dtype=float)
    assert read.dtype == np.float64
    np.testing.assert_array_equal(read.to_numpy(), written)  # NaN == NaN here
    assert np.isnan(read.to_numpy()).sum() == np.isnan(written).sum() > 0


@pytest.mark.parametrize("suffix", [".csv", ".parquet"])
def test_transient_history_with_a_missing_value(tmp_path, suffix):
    res = ex.transient()
    w = res.load_point.copy()
    w[3] = np.nan  # a march that blew up
    res = dataclasses.replace(res, load_point=w)
    table = gyroshell.load(res.to_csv(tmp_path / f"h{suffix}"))
    assert list(table.columns) == ["t", "w"]
    _same_with_nan(table["w"], w)
    np.testing.assert_array_equal(table["t"].to_numpy(), res.times)


@pytest.mark.parametrize("suffix", [".csv", ".parquet"])
def test_frequency_response_with_a_missing_error_estimate(tmp_path, suffix):
    res = ex.frequency()
    error = res.error_estimate.copy()
    error[[0, 5]] = np.nan
    res = dataclasses.replace(res, error_estimate=error)
    table = gyroshell.load(res.to_csv(tmp_path / f"f{suffix}"))
    _same_with_nan(table["error_estimate"], error)
    np.testing.assert_array_equal(table["amplitude"].to_numpy(), res.amplitude[:, 0])


def test_reproduce_tables_with_missing_values(tmp_path):
    """As critical_speeds.csv: a speed column with NaN where a route gave none."""
    frame = pd.DataFrame({"edges": ["free", "simply-supported"],
                          "divergence_speed": [101.25, np.nan],
                          "note": ["", "x"]})
    table = gyroshell.load(save_csv(frame, tmp_path / "critical_speeds.csv"))
    _same_with_nan(table["divergence_speed"], frame["divergence_speed"])
    assert table["note"].tolist() == ["", "x"]  # empty text stays text
