"""gyroshell.plot: every function takes ax=, returns it, and draws what it says."""

from __future__ import annotations

import subprocess
import sys

import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.axes import Axes

from gyroshell import TapeModel, TapeParameters, march, modes, run_study, solve_static
from gyroshell import plot as gplot
from gyroshell.core.errors import ParameterError
from gyroshell.studies.campbell import campbell

PARAMS = TapeParameters(length_ratio=4, spacing=6.35e-3 / 8)
PNG = b"\x89PNG\r\n\x1a\n"


@pytest.fixture(scope="module")
def model():
    return TapeModel(PARAMS)


def saved(ax, path) -> bytes:
    assert isinstance(ax, Axes)
    ax.figure.savefig(path, dpi=80)
    return path.read_bytes()[:8]


@pytest.mark.slow
def test_mode_shape_parts_are_the_real_and_imaginary_fields(model, tmp_path):
    res = modes(model, 60.0, 2)
    fig, (a, b) = plt.subplots(2, 1)
    assert gplot.mode_shape(res, 0, part="real", ax=a) is a
    assert gplot.mode_shape(res, 0, part="imag", ax=b) is b
    phi = res.field(0)
    assert "Re φ" in a.get_title() and "Im φ" in b.get_title()
    # the contour levels span the part they show
    top = max(level for level in a.collections[0].levels)
    assert top >= np.abs(phi.real).max() * 0.999
    axes = gplot.mode_shape_parts(res, 1)
    assert saved(axes[0], tmp_path / "m.png") == PNG
    with pytest.raises(ParameterError, match="part must be"):
        gplot.mode_shape(res, 0, part="abs")
    with pytest.raises(ParameterError, match="index must be in"):
        gplot.mode_shape(res, 5)


@pytest.mark.slow
def test_field_of_a_static_solution(model, tmp_path):
    sol = solve_static(model, 50.0)
    ax = gplot.field(sol, title="static")
    assert saved(ax, tmp_path / "f.png") == PNG
    assert ax.get_xlabel().startswith("x along")
    with pytest.raises(ParameterError, match="shape"):
        gplot.field(np.zeros((3, 3)), np.zeros(2), np.zeros(3))


@pytest.mark.slow
def test_stability_map_and_study_lines(tmp_path):
    study = run_study(PARAMS, vary={"velocity": [0.0, 104.0, 120.0], "tension": [70.0, 90.0]},
                      compute=["modes", "critical"], workers=1)
    _, ax = plt.subplots()
    assert study.plot(ax=ax) is ax  # two varied parameters: the stability map
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert set(labels) >= {"stable", "divergence", "critical speed"}
    assert saved(ax, tmp_path / "map.png") == PNG
    one = run_study(PARAMS, vary={"tension": [70.0, 90.0]}, compute="critical", workers=1)
    ax = one.plot()
    assert ax.get_ylabel() == "critical speed (m/s)"
    assert np.array_equal(ax.lines[0].get_ydata(), one.table["critical_speed"])
    with pytest.raises(ParameterError, match="stability"):
        gplot.stability_map(run_study(PARAMS, vary={"tension": [70.0], "velocity": [0.0]},
                                      compute="critical", workers=1))


@pytest.mark.slow
def test_campbell_plot_marks_what_it_found(tmp_path):
    p = TapeParameters(length_ratio=1.5, spacing=6.35e-3 / 10, edges="simply-supported",
                       foundation_stiffness=0.0)
    d = campbell(TapeModel(p), np.linspace(0.0, 75.0, 16), 5)
    _, ax = plt.subplots()
    assert d.plot(ax=ax, circumference=0.01) is ax
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert "crossing" in labels and any(s.startswith("critical speed") for s in labels)
    assert saved(ax, tmp_path / "campbell.png") == PNG


@pytest.mark.slow
def test_gif_animations(model, tmp_path):
    res = modes(model, 60.0, 1)
    ax = gplot.animate_mode(res, tmp_path / "mode.gif", frames=4)
    assert isinstance(ax, Axes)
    assert (tmp_path / "mode.gif").read_bytes()[:6] == b"GIF89a"
    run = march(model, 50.0, dt=2e-6, steps=20, snapshot_every=5, progress=False)
    gplot.animate_transient(run, tmp_path / "run.gif")
    assert (tmp_path / "run.gif").read_bytes()[:6] == b"GIF89a"
    with pytest.raises(ParameterError, match=".gif"):
        gplot.animate_mode(res, tmp_path / "x.png")
    assert not list(tmp_path.glob(".*")), "temporary files left behind"


@pytest.mark.slow
def test_import_gyroshell_does_not_import_matplotlib_xarray_or_dask():
    code = ("import sys, gyroshell, gyroshell.plot, gyroshell.studies.parameter_study, "
            "gyroshell.studies.campbell, gyroshell.studies.sweep; "
            "print([m for m in ('matplotlib', 'xarray', 'dask', 'distributed', 'pandas') "
            "if m in sys.modules])")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout
    assert out.strip() == "[]"


@pytest.mark.slow
def test_stability_map_over_a_word_parameter(tmp_path):
    study = run_study(PARAMS, vary={"edges": ["free", "simply-supported"],
                                    "velocity": [50.0, 120.0]},
                      compute="period", workers=1)
    ax = study.plot()
    assert [t.get_text() for t in ax.get_xticklabels()] == ["free", "simply-supported"]
    assert saved(ax, tmp_path / "edges.png") == PNG


@pytest.mark.slow
def test_sweep_plot_of_a_result_or_its_table_and_the_figure_saver(model, tmp_path):
    from gyroshell import sweep

    result = sweep(TapeModel(PARAMS.replace(length_ratio=2)), [0.0, 40.0, 80.0], 3)
    ax = result.plot(title="a sweep")
    assert isinstance(ax, Axes) and ax.get_title() == "a sweep"
    assert "m/s" in ax.get_xlabel() and "rad/s" in ax.get_ylabel()
    rank_lines = [line for line in ax.lines if line.get_zorder() == 1]
    assert len(rank_lines) == 3  # the k-th lowest ω, k = 1..3, in grey beneath
    _, other = plt.subplots()
    gplot.sweep(result.table, ax=other)
    for a, b in zip(ax.lines, other.lines, strict=True):  # a table draws the same lines
        assert np.array_equal(a.get_xydata(), b.get_xydata())
    with pytest.raises(ParameterError, match="lacks columns"):
        gplot.sweep(result.table.drop(columns="branch"))
    path = gplot.save_figure(ax.figure, tmp_path / "s.png", dpi=50, close=False)
    small = plt.imread(path).shape
    gplot.save_figure(ax.figure, tmp_path / "s.png", dpi=100)  # replaces the file whole
    assert plt.imread(path).shape[0] == pytest.approx(2 * small[0], abs=2)
    assert not plt.fignum_exists(ax.figure.number), "closed after writing"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.png"], "no temporary files"
    from gyroshell.core.files import OutputPathError

    with pytest.raises(OutputPathError, match="--plot .*does not exist"):
        gplot.save_figure(other.figure, tmp_path / "no" / "s.png", dpi=50, option="--plot")
    assert not plt.fignum_exists(other.figure.number), "closed also when writing failed"


@pytest.mark.slow
def test_study_lines_pick_the_first_computed_quantity_without_importing_studies():
    one = run_study(PARAMS, vary={"tension": [70.0, 90.0]}, compute=["modes", "critical"],
                    count=2, workers=1)
    ax = gplot.study_lines(one)
    assert ax.get_ylabel() == "critical speed (m/s)"  # critical comes first in the table
    with pytest.raises(ParameterError, match="quantity"):
        gplot.study_lines(one.table.drop(columns=["critical_speed"]), x="tension")
