"""plot.study_map and the units a study's plots show (degrees, lengths by their size), on
tables made here: each cell is the value of its row."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from gyroshell import ParameterError
from gyroshell import plot as gplot
from gyroshell.plot.study_maps import TRANSDUCER_MIN_SPACING, display_scale, plottable


def _table():
    wraps, thick = np.radians([1.0, 2.0, 4.0]), np.array([4e-6, 5e-6])
    rows = [{"point": i, "wrap": w, "thickness": c, "drag": w * c,
             "transducer_1_min_spacing": 1e-8 * (1 + w), "transducer_2_min_spacing": 3e-8 * c
             / 5e-6, "error": ""}
            for i, (w, c) in enumerate((w, c) for w in wraps for c in thick)]
    return pd.DataFrame(rows)


class Study:
    """What the plots read of a StudyResult."""

    def __init__(self, table, varied=("wrap", "thickness")):
        self.table, self.varied, self.compute, self.bearing = table, varied, ("bearing",), None


def test_the_map_puts_each_row_in_its_cell_with_units():
    study = Study(_table())
    ax = gplot.study_map(study, "drag")
    assert ax.get_xlabel() == "wrap (deg)" and ax.get_ylabel() == "thickness (µm)"
    assert ax.figure.axes[-1].get_ylabel() == "drag (N)"
    cells = np.asarray(ax.collections[0].get_array()).reshape(2, 3)  # (thickness, wrap)
    expected = np.outer([4e-6, 5e-6], np.radians([1.0, 2.0, 4.0]))
    np.testing.assert_allclose(cells, expected, rtol=1e-15)
    x_edges = ax.collections[0].get_coordinates()[0, :, 0]
    np.testing.assert_allclose(x_edges, [0.5, 1.5, 3.0, 5.0], rtol=1e-12)
    y_edges = ax.collections[0].get_coordinates()[:, 0, 1]
    np.testing.assert_allclose(y_edges, [3.5, 4.5, 5.5], rtol=1e-12)


def test_the_default_quantity_is_the_transducers_minimum_spacing():
    study = Study(_table())
    ax = gplot.study_map(study)
    assert ax.figure.axes[-1].get_ylabel() == "minimum spacing at the transducers (nm)"
    t = study.table
    smaller = np.minimum(t.transducer_1_min_spacing, t.transducer_2_min_spacing)
    cells = np.sort(np.ravel(ax.collections[0].get_array()))
    np.testing.assert_allclose(cells, np.sort(1e9 * smaller), rtol=1e-12)
    assert plottable(t.columns, study.varied)[0] == TRANSDUCER_MIN_SPACING


def test_an_unknown_quantity_is_refused_listing_the_study_s():
    with pytest.raises(ParameterError, match="no quantity 'lift' in the study: choose one of "
                                             "transducer_min_spacing, drag, transducer_1"):
        gplot.study_map(Study(_table()), "lift")


def test_a_failed_point_is_left_grey():
    table = _table()
    table.loc[2, "drag"] = math.nan
    ax = gplot.study_map(Study(table), "drag")
    assert np.ma.count_masked(ax.collections[0].get_array()) == 1
    assert "1 failed point grey" in ax.get_title()


@pytest.mark.parametrize("name, values, factor, label", [
    ("wrap_in", [0.01], 180 / math.pi, "wrap in (deg)"),
    ("central_spacing", [3e-7], 1e9, "central spacing (nm)"),
    ("central_spacing", [5e-5], 1e6, "central spacing (µm)"),
    ("land_length", [1e-3], 1e3, "land length (mm)"),
    ("tension", [80.0], 1.0, "tension (N/m)"),
])
def test_display_scale(name, values, factor, label):
    got = display_scale(Study(_table()), name, values)
    assert got[0] == pytest.approx(factor, rel=1e-15) and got[1] == label


def test_study_lines_shows_degrees_in_the_axis_and_legend():
    ax = gplot.study_lines(Study(_table()), quantity="drag")
    assert ax.get_xlabel() == "wrap (deg)" and ax.get_ylabel() == "drag (N)"
    np.testing.assert_allclose(ax.lines[0].get_xdata(), [1.0, 2.0, 4.0], rtol=1e-14)
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert labels == ["thickness = 4 µm", "thickness = 5 µm"]
