"""The CLI's outputs: tables whose missing values read back by gyroshell.load as NaN
floats; --out and --save formats refused before any work when they cannot hold the result;
sweep's speeds distinct, its outputs written together after everything that can fail, and
its --save the SweepResult itself."""

from __future__ import annotations

import dataclasses

import numpy as np
import pandas as pd
import pytest

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


# ----- sweep: distinct speeds, one transaction, --save keeps the SweepResult ---------------
#: A small tape (L_x/L_y = 2, 8 intervals across): a sweep of two modes at three speeds in
#: a fraction of a second.
SMALL = ["--length-ratio", "2", "--spacing", "7.9375e-4"]
SWEEP = ["sweep", *SMALL, "--count", "2", "--quiet"]


@pytest.fixture
def recorded_sweep(monkeypatch):
    """Record what ``gyroshell.studies.sweep.sweep`` returns to the CLI (and let a test
    change it: ``edit`` is applied to the result first)."""
    import gyroshell.studies.sweep as module

    calls: dict = {"results": [], "edit": None}
    real = module.sweep

    def recording(*args, **kwargs):
        result = real(*args, **kwargs)
        if calls["edit"] is not None:
            result = calls["edit"](result)
        calls["results"].append(result)
        return result

    monkeypatch.setattr(module, "sweep", recording)
    return calls


def _no_engine(monkeypatch, module_name: str, function: str) -> None:
    """Make ``module_name.function`` fail the test if the command calls it."""
    import importlib

    def called(*args, **kwargs):
        raise AssertionError(f"{function} was called: the refusal came after the work")

    monkeypatch.setattr(importlib.import_module(module_name), function, called)


def test_sweep_refuses_a_repeated_speed_before_any_work(cli, tmp_path, monkeypatch):
    _no_engine(monkeypatch, "gyroshell.studies.sweep", "sweep")
    _no_engine(monkeypatch, "gyroshell.studies.sweep", "solve_speeds")
    run = cli([*SWEEP, "--velocities", "0,10,10", "--save", tmp_path / "dup.nc",
               "--out", tmp_path / "dup.csv", "--plot", tmp_path / "dup.png"])
    assert run.code == 2
    assert run.err.count("\n") == 1 and "--velocities" in run.err and "10" in run.err
    assert list(tmp_path.iterdir()) == []


def test_check_velocities_refuses_repeats_and_keeps_any_order():
    from gyroshell.core.errors import ParameterError
    from gyroshell.studies.sweep import check_velocities

    assert check_velocities([30, 0.0, 10]) == [30.0, 0.0, 10.0]  # descending is tracked too
    with pytest.raises(ParameterError, match=r"^velocities must be distinct .*: 10 is given 2"):
        check_velocities([0, 10, 20, 10])


def test_sweep_in_descending_order_prints_every_speed(cli):
    run = cli([*SWEEP, "--velocities", "20,10,0"])
    assert run.code == 0, run.err
    rows = [line.split() for line in run.out.splitlines()[3:]]
    assert [float(r[0]) for r in rows] == [0.0, 10.0, 20.0]


def test_a_failed_sweep_leaves_none_of_its_outputs(cli, tmp_path, monkeypatch):
    """Everything that can fail after the sweep (here the printout) runs before any file
    is moved into place."""
    import gyroshell.cli.eigen as eigen

    def broken(frame):
        raise RuntimeError("the printout failed")

    monkeypatch.setattr(eigen, "_sweep_text", broken)
    with pytest.raises(RuntimeError, match="the printout failed"):
        cli([*SWEEP, "--velocities", "0,10", "--save", tmp_path / "s.nc",
             "--plot", tmp_path / "s.png"])
    assert list(tmp_path.iterdir()) == []


def test_sweep_save_keeps_the_sweep_result_exactly(cli, tmp_path, recorded_sweep):
    from bit_exact import assert_same

    from gyroshell.studies.sweep import SweepResult

    run = cli([*SWEEP, "--velocities", "0,20,10", "--save", tmp_path / "s.nc"])
    assert run.code == 0, run.err
    (result,) = recorded_sweep["results"]
    loaded = gyroshell.load(tmp_path / "s.nc")
    assert isinstance(loaded, SweepResult)
    assert_same(result, loaded, "sweep")
    assert loaded.velocities.tolist() == [0.0, 20.0, 10.0] and loaded.count == 2
    assert loaded.params is not None and loaded.grid is not None
    assert loaded.params.length_ratio == 2.0 and loaded.info == {"workers": 1}


@pytest.mark.parametrize("suffix", [".csv", ".parquet"])
def test_sweep_out_reads_back_missing_values_as_nan(cli, tmp_path, recorded_sweep, suffix):
    def with_a_missing_residual(result):
        table = result.table.copy()
        table.loc[1, "residual"] = np.nan
        return dataclasses.replace(result, table=table)

    recorded_sweep["edit"] = with_a_missing_residual
    run = cli([*SWEEP, "--velocities", "0,10", "--out", tmp_path / f"s{suffix}"])
    assert run.code == 0, run.err
    table = gyroshell.load(tmp_path / f"s{suffix}")
    written = recorded_sweep["results"][0].table
    assert table["residual"].dtype == np.float64
    np.testing.assert_array_equal(table["residual"], written["residual"])  # NaN in place
    assert np.isnan(table["residual"]).sum() == 1


# ----- --out of transient, frf and sweep: a table, .csv or .parquet --------------------------
COMMANDS = {
    "transient": (["transient", *SMALL, "--steps", "3", "--dt", "2e-6", "--quiet"],
                  "gyroshell.engines.newmark", "march"),
    "frf": (["frf", *SMALL, "--frequencies", "0:1000:3", "--quiet"],
            "gyroshell.engines.frequency_response", "frequency_response"),
    "sweep": ([*SWEEP, "--velocities", "0,10"], "gyroshell.studies.sweep", "sweep"),
}


@pytest.mark.parametrize("name", sorted(COMMANDS))
@pytest.mark.parametrize("suffix", [".nc", ".parquet2", ".txt", ""])
def test_out_of_another_format_is_refused_before_the_work(cli, tmp_path, monkeypatch, name,
                                                          suffix):
    argv, module, function = COMMANDS[name]
    _no_engine(monkeypatch, module, function)
    run = cli([*argv, "--out", tmp_path / f"o{suffix}"])
    assert run.code == 2
    assert run.err.count("\n") == 1, run.err
    assert "--out: use a .csv or .parquet file" in run.err
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("name", sorted(COMMANDS))
def test_out_parquet_is_written_as_parquet(cli, tmp_path, name):
    argv, _module, _function = COMMANDS[name]
    assert cli([*argv, "--out", tmp_path / "o.csv"]).code == 0
    assert cli([*argv, "--out", tmp_path / "o.parquet"]).code == 0
    assert (tmp_path / "o.parquet").read_bytes()[:4] == b"PAR1"
    pd.testing.assert_frame_equal(gyroshell.load(tmp_path / "o.parquet"),
                                  gyroshell.load(tmp_path / "o.csv"))


# ----- --save of a kind that is not a table ------------------------------------------------
@pytest.mark.parametrize("suffix", [".csv", ".parquet"])
def test_static_save_as_a_table_is_refused_before_the_solve(cli, tmp_path, monkeypatch,
                                                            suffix):
    _no_engine(monkeypatch, "gyroshell.engines.static", "solve_static")
    run = cli(["static", *SMALL, "--save", tmp_path / f"x{suffix}"])
    assert run.code == 2
    assert run.err.count("\n") == 1, run.err
    assert "--save: a StaticSolution is not a table: use a .nc file" in run.err
    assert list(tmp_path.iterdir()) == []


def test_modes_save_as_a_table_is_accepted(cli, tmp_path):
    """Modes are a table (one row per mode): .csv stays allowed."""
    run = cli(["modes", *SMALL, "--count", "2", "--save", tmp_path / "m.csv"])
    assert run.code == 0, run.err
    assert len(gyroshell.load(tmp_path / "m.csv")) == 2
