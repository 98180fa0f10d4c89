"""The static, transient, frequency-response, reduced-model and table kinds: save -> read
gives back every field bit for bit; files of the previous release still load."""

from __future__ import annotations

import dataclasses
import warnings

import numpy as np
import pandas as pd
import pytest
from bit_exact import assert_same
from examples_timefreq import EXAMPLES, OMEGA, PARAMS, frequency, model

import gyroshell
from gyroshell.core.errors import ParameterError
from gyroshell.engines.frequency_response import ReducedModel, frequency_response
from gyroshell.engines.newmark import Newmark
from gyroshell.results.base import read
from gyroshell.results.frequency_response import FrequencyResponse
from gyroshell.results.static import StaticSolution
from gyroshell.results.tables import Table
from gyroshell.results.transient import TransientResult


def same_array(a, b) -> None:
    a, b = np.asarray(a), np.asarray(b)
    assert a.shape == b.shape and a.dtype == b.dtype, (a.shape, b.shape, a.dtype, b.dtype)
    assert np.array_equal(a, b, equal_nan=a.dtype.kind in "fc")


def same_fields(original, loaded) -> None:
    """Every dataclass field equal: arrays bit for bit (dtype and shape too)."""
    assert type(loaded) is type(original)
    for f in dataclasses.fields(original):
        a, b = getattr(original, f.name), getattr(loaded, f.name)
        if dataclasses.is_dataclass(a) and not isinstance(a, type) and hasattr(a, "fields"):
            same_fields(a, b)  # Snapshots
        elif isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
            same_array(a, b)
        else:
            assert a == b, f.name


def round_trip(result, tmp_path, name="result.nc"):
    return read(result.save(tmp_path / name))


@pytest.mark.slow
@pytest.mark.parametrize("kind", ["static", "transient", "frequency_response"])
def test_dataclass_kinds_round_trip_bit_exactly(kind, tmp_path):
    original = EXAMPLES[kind]()
    same_fields(original, round_trip(original, tmp_path))


@pytest.mark.slow
@pytest.mark.parametrize("kind", ["static", "transient", "frequency_response",
                                  "reduced_model"])
def test_loaded_results_hold_the_same_data_deeply(kind, tmp_path):
    original = EXAMPLES[kind]()
    assert_same(original, round_trip(original, tmp_path), kind)


def test_static_solution_carries_its_parameters(tmp_path):
    sol = EXAMPLES["static"]()
    assert sol.params == PARAMS
    loaded = round_trip(sol, tmp_path)
    assert loaded.params == PARAMS and loaded.grid == sol.grid
    same_array(loaded.field, sol.field)


@pytest.mark.slow
def test_transient_keeps_head_histories_energy_and_snapshots(tmp_path):
    run = EXAMPLES["transient"]()
    assert run.head_displacements.shape == (run.steps + 1, 2)
    assert run.energy is not None and len(run.snapshots) > 0
    assert run.snapshots.centerlines.shape[0] == 2
    loaded = round_trip(run, tmp_path)
    same_array(loaded.head_displacements, run.head_displacements)
    same_array(loaded.snapshots.fields, run.snapshots.fields)
    same_array(loaded.snapshots.centerlines, run.snapshots.centerlines)
    assert loaded.info == run.info and loaded.info["moving_load"] is True


@pytest.mark.slow
def test_frequency_response_with_direct_and_reduced_frequencies(tmp_path):
    mixed = frequency_response(model(), 10.0, OMEGA, damping=200.0, max_points=2,
                               progress=False)
    assert set(mixed.method) == {"direct", "reduced"}
    loaded = round_trip(mixed, tmp_path)
    same_fields(mixed, loaded)
    assert loaded.info == mixed.info


@pytest.mark.slow
def test_reduced_model_loaded_evaluates_identically(tmp_path):
    original = EXAMPLES["reduced_model"]()
    loaded = round_trip(original, tmp_path)
    assert isinstance(loaded, ReducedModel)
    for name in ("velocity", "moments", "interpolation_points", "basis_size", "unknowns",
                 "damping"):
        assert getattr(loaded, name) == getattr(original, name), name
    same_array(loaded.points, original.points)
    for a, b in zip(original.evaluate(OMEGA), loaded.evaluate(OMEGA), strict=True):
        same_array(a, b)
    assert loaded.summary() == original.summary()
    with pytest.raises(ParameterError, match="cannot add interpolation points"):
        loaded.add_points([5e4])


def test_reduced_model_without_points_refuses_to_save(tmp_path):
    with pytest.raises(ParameterError, match="no interpolation point"):
        ReducedModel(model(), 10.0, damping=200.0).save(tmp_path / "empty.nc")


def test_table_reads_back_as_the_dataframe(tmp_path):
    table = EXAMPLES["table"]()
    loaded = round_trip(table, tmp_path)
    assert isinstance(loaded, Table)
    pd.testing.assert_frame_equal(loaded.frame, table.frame, check_exact=True)
    plain = gyroshell.load(tmp_path / "result.nc")  # the previous release's reading of a table
    assert isinstance(plain, pd.DataFrame)
    pd.testing.assert_frame_equal(plain, table.frame, check_exact=True)
    assert table.summary() == {"rows": 3, "columns": ["velocity", "omega", "stability"]}
    csv = table.save(tmp_path / "table.csv")
    pd.testing.assert_frame_equal(pd.read_csv(csv), table.frame, check_exact=True)


@pytest.mark.slow
def test_summaries_are_plain_json_values():
    import json

    for build in EXAMPLES.values():
        json.dumps(build().summary())  # raises on numpy scalars or arrays
    assert frequency().summary()["unknowns"] == model().unknowns


@pytest.mark.slow
@pytest.mark.parametrize("kind", sorted(EXAMPLES))
def test_every_kind_plots(kind):
    import matplotlib.pyplot as plt

    ax = EXAMPLES[kind]().plot()
    assert ax is not None
    plt.close("all")


def test_frequency_response_plot_draws_one_bode_curve_per_point():
    import matplotlib.pyplot as plt

    result = frequency()
    amplitude, phase = result.plot()
    assert len(amplitude.lines) == len(phase.lines) == result.response.shape[1]
    assert amplitude.get_ylabel() == "amplitude |W| (m)"
    assert phase.get_xlabel() == "angular frequency ω (rad/s)"
    same_array(amplitude.lines[1].get_ydata(), result.amplitude[:, 1])
    plt.close("all")


def test_newmark_names_g_plus_c_damped_gyroscopic():
    stepper = Newmark(model(), 10.0, dt=1e-6, damping=200.0)
    gc = stepper.damped_gyroscopic
    with pytest.warns(DeprecationWarning, match="damped_gyroscopic"):
        assert stepper.D is gc
    with warnings.catch_warnings():
        warnings.simplefilter("error", DeprecationWarning)
        stepper.march(2, progress=False)


def test_public_names_point_to_the_new_homes():
    import gyroshell

    assert gyroshell.StaticSolution is StaticSolution
    assert gyroshell.FrequencyResponse is FrequencyResponse
    assert gyroshell.TransientResult is TransientResult
    assert Table.kind == "table"
