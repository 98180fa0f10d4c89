"""The CLI's table outputs: missing values read back by gyroshell.load as NaN floats."""

from __future__ import annotations

import numpy as np

import gyroshell

#: A flat head, infinitely wide tape, no tent on the span side: NaN cells in corners.csv and
#: an empty y in transducer_lines.csv.
FLAT_HEAD = ["bearing", "--head", "flat", "--land-length", "1e-3", "--wrap-in", "2",
             "--wrap-out", "2", "--transducers", "0", "--velocity", "4", "--infinitely-wide",
             "--quiet"]


def test_bearing_out_tables_read_back_missing_values_as_nan(cli, tmp_path):
    run = cli([*FLAT_HEAD, "--out", tmp_path / "bo"])
    assert run.code == 0, run.err
    corners = gyroshell.load(tmp_path / "bo" / "corners.csv")
    lines = gyroshell.load(tmp_path / "bo" / "transducer_lines.csv")
    fields = gyroshell.load(tmp_path / "bo" / "fields.csv")
    for table in (corners, lines, fields):
        floats = [c for c in table.columns if table[c].dtype != np.int64]
        assert all(table[c].dtype == np.float64 for c in floats), dict(table.dtypes)
    assert np.isnan(corners["span_tent_x_m"]).all()
    assert np.isnan(corners["span_tent_height_m"]).all()
    assert np.isnan(lines["y_m"]).all()              # infinitely wide: no y
    assert np.isfinite(corners["land_tent_x_m"]).all()
