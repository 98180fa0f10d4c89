"""Python API: bad arguments raise ParameterError naming the parameter and the allowed range,
before any work; sizes are refused from estimates, fast and without allocating."""

from __future__ import annotations

import math
import tracemalloc

import numpy as np
import pytest
from conftest import WIDTH

from gyroshell import (
    Grid,
    ParameterError,
    TapeModel,
    TapeParameters,
    bending_rigidity,
    march,
    shell_stiffness,
    solve_static,
)
from gyroshell.core import budget, validation

NAN, INF = float("nan"), float("inf")


@pytest.mark.parametrize(("args", "match"), [
    ((-0.0254, WIDTH, 16, 8), "length must be > 0 m, got -0.0254"),
    ((NAN, WIDTH, 16, 8), "length must be finite m, got nan"),
    ((0.0254, INF, 16, 8), "width must be finite"),
    ((0.0254, WIDTH, 16.5, 8), "nx must be an integer, got 16.5"),
    ((0.0254, WIDTH, 16, "8"), "ny must be an integer, got '8'"),
    ((0.0254, WIDTH, True, 8), "nx must be an integer, got True"),
    ((0.0254, WIDTH, 2, 8), "nx must be an integer >= 8, got 2"),
    ((0.0254, WIDTH, 16, 4), "ny must be an integer >= 8, got 4"),
    ((0.0254, WIDTH, 16, 8, "clamped"), "edges must be one of free, simply-supported"),
    ((0.0254, WIDTH, 10**7, 10**4), "factor entries"),
])
def test_grid_refuses(args, match):
    with pytest.raises(ParameterError, match=match.replace("(", r"\(").replace(")", r"\)")):
        Grid(*args)


def test_grid_accepts_whole_floats_as_counts():
    assert Grid(0.0254, WIDTH, 16.0, 8).nx == 16


@pytest.mark.parametrize(("kwargs", "match"), [
    ({"wrap_pressure": "yes"}, "wrap_pressure must be True or False, got 'yes'"),
    ({"wrap_pressure": 1}, "wrap_pressure must be True or False, got 1"),
    ({"thickness": "thin"}, "thickness must be a real number m, got 'thin'"),
    ({"density": True}, "density must be a real number"),
    ({"load": NAN}, "load must be finite Pa"),
    ({"edges": None}, "edges must be one of"),
    ({"length_ratio": 1e-6}, "length_ratio must leave at least 8 intervals along the length"),
    ({"length_ratio": 1e308}, "gives an infinite number of intervals"),
    ({"width": 1e300, "spacing": 1e299, "length_ratio": 1e10}, "length .* overflows"),
    ({"youngs_modulus": 1e-300}, "bending_rigidity .* underflows"),
    ({"youngs_modulus": 1e308}, "overflows"),
    ({"density": 1e-300}, "density x spacing.* underflows"),
    ({"tension": 1e140, "radius": 1e-20}, "tension / radius .* overflows"),
    ({"foundation_stiffness": 1e200}, "foundation_stiffness x spacing.* overflows"),
    ({"radius": 1e-300}, "foundation_stiffness .* overflows"),
    ({"spacing": 1e-300}, "bending_rigidity / spacing.* overflows"),
    ({"bending_rigidity": 1e-320}, "underflows"),
    ({"load_x": 1.0}, r"load_x must be in \[0, 0.0254\] m, got 1"),
])
def test_parameters_refuse(kwargs, match):
    with pytest.raises(ParameterError, match=match):
        TapeParameters(**kwargs)


@pytest.mark.parametrize(("call", "match"), [
    (lambda: shell_stiffness(4e9, 20e-6, 0.0, 0.3), "radius must be > 0 m, got 0"),
    (lambda: shell_stiffness(4e9, 20e-6, NAN, 0.3), "radius must be finite"),
    (lambda: shell_stiffness(4e9, 20e-6, 0.02, 0.5), r"poisson must be in \(-1, 0.5\)"),
    (lambda: bending_rigidity(-4e9, 20e-6, 0.3), "youngs_modulus must be > 0 Pa"),
    (lambda: bending_rigidity(4e9, 1e200, 0.3), "bending_rigidity .* overflows"),
])
def test_derived_quantities_refuse(call, match):
    with pytest.raises(ParameterError, match=match):
        call()


def test_model_and_static_refuse_bad_forces_and_speeds(small):
    n = small.unknowns
    with pytest.raises(ParameterError, match=f"force must be a vector of length {n} N, got "
                                             r"shape \(3,\)"):
        TapeModel(small.params, force=np.ones(3))
    bad = np.ones(n)
    bad[7] = np.nan
    with pytest.raises(ParameterError, match="force must be finite N: it has 1 NaN"):
        solve_static(small, 0.0, force=bad)
    with pytest.raises(ParameterError, match="velocity must be <= "):
        solve_static(small, 1e200)
    with pytest.raises(ParameterError, match="velocity must be a real number"):
        small.K("fast")
    with pytest.raises(ParameterError, match="model must be a TapeModel"):
        solve_static(small.params, 0.0)
    with pytest.raises(ParameterError, match="params must be a TapeParameters"):
        TapeModel({"density": 1.0})


def test_deprecated_names_still_answer(small):
    with pytest.warns(DeprecationWarning, match="use unknowns"):
        assert small.size == small.unknowns
    with pytest.warns(DeprecationWarning, match="use force"):
        assert small.load is small.force
    assert small.params.load == small.params.load_pressure == 200.0  # Pa


def test_no_lapack_noise_on_stderr(small, capfd):
    bad = np.full(small.unknowns, np.nan)
    with pytest.raises(ParameterError):
        solve_static(small, 0.0, force=bad)
    with pytest.raises(ParameterError):
        TapeModel(small.params, force=bad)
    assert capfd.readouterr().err == ""


# ----- size before work: estimates, refusal time and memory ---------------------------------
@pytest.mark.parametrize("make", [
    lambda: TapeModel(TapeParameters(spacing=1e-9)),
    lambda: TapeModel(TapeParameters(length_ratio=1e12)),
    lambda: TapeModel(TapeParameters(spacing=5e-6)),
])
def test_oversized_grids_are_refused_without_allocating(make, monkeypatch):
    monkeypatch.setenv(budget.MEMORY_LIMIT_VARIABLE, "8e9")
    tracemalloc.start()
    try:
        with pytest.raises(ParameterError, match="use a larger spacing or a smaller length_ratio"):
            make()
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert peak < 1e6  # bytes: the estimate, not the grid


def test_transient_steps_beyond_memory_refused_before_allocating(small, monkeypatch):
    monkeypatch.setenv(budget.MEMORY_LIMIT_VARIABLE, "1e9")
    with pytest.raises(ParameterError, match="a transient of 1000000000000 steps needs about"):
        march(small, 0.0, dt=2e-6, steps=10**12)
    with pytest.raises(ParameterError, match="1000001 full fields of 153 nodes"):
        march(small, 0.0, dt=2e-6, steps=10**6, snapshot_every=1)


def test_factor_estimate_bounds_the_measured_fill():
    """The estimate must not be below what SuperLU actually stores, or refusals come late."""
    import scipy.sparse.linalg as spla

    for ratio, ny in ((4, 10), (2, 40), (1, 60)):
        model = TapeModel(TapeParameters(length_ratio=ratio, spacing=WIDTH / ny))
        lu = spla.splu(model.K(0.0).tocsc(), permc_spec="MMD_AT_PLUS_A",
                       diag_pivot_thresh=0.0, options={"SymmetricMode": True})
        g = model.grid
        measured = lu.L.nnz + lu.U.nnz
        estimate = budget.factor_entries(g.nx, g.ny, g.edges)
        assert measured <= estimate <= 3 * measured


def test_memory_limit_setting_is_validated(monkeypatch):
    monkeypatch.setenv(budget.MEMORY_LIMIT_VARIABLE, "lots")
    with pytest.raises(ParameterError, match="GYROSHELL_MEMORY_LIMIT must be a number"):
        budget.memory_limit()


def test_sweep_length_guard_is_a_count_not_a_list():
    with pytest.raises(ParameterError, match="more than the limit 10000"):
        budget.check_sweep_length(math.inf)
    assert budget.check_sweep_length(10_000) == 10_000


# ----- the shared checks themselves -----------------------------------------------------------
@pytest.mark.parametrize(("call", "match"), [
    (lambda: validation.integer("count", None, low=1), "count must be an integer, got None"),
    (lambda: validation.integer("maxiter", 0, low=1), "maxiter must be an integer >= 1, got 0"),
    (lambda: validation.positive("xtol", 0.0), "xtol must be > 0, got 0"),
    (lambda: validation.positive("xtol", -1e-9), "xtol must be > 0, got -1e-09"),
    (lambda: validation.real("gamma", 2j), "gamma must be a real number"),
    (lambda: validation.boolean("record_energy", None), "must be True or False"),
    (lambda: validation.vector("w0", [[1.0]], 1), r"got shape \(1, 1\)"),
    (lambda: validation.time_step(2e-6, 0.0), "beta must be > 0"),
    (lambda: validation.integer("ncv", 0, low=1, optional=True),
     "ncv must be None or an integer >= 1, got 0"),
    (lambda: validation.instance("model", {}, TapeModel), "model must be a TapeModel, got dict"),
    (lambda: validation.instance("label", 1.0, (int, str), optional=True),
     "label must be a int or str or None, got float"),
])
def test_shared_checks_name_parameter_and_range(call, match):
    with pytest.raises(ParameterError, match=match):
        call()


def test_shared_checks_pass_good_values_through(small):
    assert validation.integer("maxiter", None, low=1, optional=True) is None
    assert validation.integer("maxiter", 4.0, low=1, optional=True) == 4
    assert validation.instance("model", small, TapeModel) is small
    assert validation.instance("grid", None, Grid, optional=True) is None


def test_eigen_budget_counts_the_krylov_basis(monkeypatch):
    monkeypatch.setenv(budget.MEMORY_LIMIT_VARIABLE, "1e9")
    assert budget.check_eigen(779, 41, "free", 40) < 1e9  # the paper's long tape, 40 vectors
    with pytest.raises(ParameterError, match="an eigen-solve with 100000 Krylov vectors"):
        budget.check_eigen(779, 41, "free", 100_000)


def test_run_study_refuses_a_file_as_folder(tmp_path):
    from gyroshell.reproduce import run_study

    (tmp_path / "f").write_text("x")
    with pytest.raises(ParameterError, match="is a file, not a folder"):
        run_study("critical", tmp_path / "f")


def test_progress_bars_only_on_a_terminal(monkeypatch):
    import io as stdio
    import sys

    from gyroshell.core.progress import progress_wanted

    monkeypatch.setattr(sys, "stderr", stdio.StringIO())
    assert progress_wanted(None) is False and progress_wanted(True) is True

    class Terminal(stdio.StringIO):
        def isatty(self) -> bool:
            return True

    monkeypatch.setattr(sys, "stderr", Terminal())
    assert progress_wanted(None) is True and progress_wanted(False) is False
