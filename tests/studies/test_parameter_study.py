"""Parameter studies: the same numbers as one-by-one runs, on any executor, and resumable."""

from __future__ import annotations

import math

import pandas as pd
import pytest
from dense_reference import quadratic_eigenvalues

import gyroshell.studies.evaluation
import gyroshell.studies.executors
from gyroshell import (
    TapeModel,
    TapeParameters,
    classify_stability,
    critical_speeds,
    modes,
    run_study,
    solve_static,
)
from gyroshell.core.errors import ParameterError, SupercriticalError

BASE = TapeParameters(length_ratio=4, spacing=6.35e-3 / 8)
VARY = {"velocity": [0.0, 60.0, 104.0], "tension": [70.0, 90.0]}
COMPUTE = ("critical", "modes", "static", "period")


@pytest.fixture(scope="module")
def serial():
    return run_study(BASE, vary=VARY, compute=COMPUTE, count=3, workers=1)


@pytest.mark.slow
def test_grid_rows_and_columns(serial):
    t = serial.table
    assert len(t) == 6 and list(t["point"]) == list(range(6))
    assert list(t.columns[:3]) == ["point", "velocity", "tension"]
    assert list(zip(t["velocity"], t["tension"], strict=True)) == [
        (v, T) for v in VARY["velocity"] for T in VARY["tension"]]
    assert {"critical_speed", "divergence_speed", "omega_1", "omega_3", "growth_rate",
            "load_point_deflection", "max_deflection", "period", "stability", "error"
            } <= set(t.columns)


@pytest.mark.slow
def test_rows_equal_one_by_one_runs_exactly(serial):
    for row in serial.table.itertuples():
        model = TapeModel(BASE.replace(tension=row.tension))
        crit = critical_speeds(model)
        assert (row.critical_speed, row.divergence_speed) == (
            crit.critical_speed, crit.divergence_speed)
        res = modes(model, row.velocity, 3)
        got = [row.omega_1, row.omega_2, row.omega_3][:res.count]
        assert got == list(res.omega)
        assert row.period == res.period[0]  # the same eigen-solve serves both
        if row.velocity < crit.divergence_speed:
            sol = solve_static(model, row.velocity)
            assert row.load_point_deflection == sol.load_point_deflection
            assert row.error == ""
        else:  # a failing quantity is reported in its row, the others are kept
            with pytest.raises(SupercriticalError):
                solve_static(model, row.velocity)
            assert math.isnan(row.load_point_deflection)
            assert row.error.startswith("static: SupercriticalError: velocity 104")
        # the stability against the whole spectrum, dense (independent of modes)
        lam = quadratic_eigenvalues(model.M.toarray(), model.G(row.velocity).toarray(),
                                    model.K(row.velocity).toarray())
        assert row.stability == classify_stability(lam)
    assert set(serial.table["stability"]) == {"stable", "divergence"}


@pytest.mark.slow
def test_local_processes_give_identical_rows(serial):
    again = run_study(BASE, vary=VARY, compute=COMPUTE, count=3, workers=2)
    assert again.info["executor"] == "processes(2)"
    pd.testing.assert_frame_equal(again.table, serial.table, check_exact=True)


@pytest.mark.slow
def test_dask_local_cluster_gives_identical_rows(serial):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        again = run_study(BASE, vary=VARY, compute=COMPUTE, count=3,
                          scheduler=cluster.scheduler_address, chunk_size=1)
    assert again.info["executor"].startswith("dask(tcp://")
    pd.testing.assert_frame_equal(again.table, serial.table, check_exact=True)


@pytest.mark.slow
def test_point_list_and_unreachable_scheduler():
    pts = [{"tension": 80.0, "velocity": 10.0}, {"youngs-modulus": 3e9}]
    res = run_study(BASE, points=pts, compute="period", workers=1)
    assert list(res.table.columns) == ["point", "tension", "velocity", "youngs_modulus",
                                       "period", "stability", "error"]
    assert res.table.loc[0, "period"] == modes(
        TapeModel(BASE.replace(tension=80.0)), 10.0, 1).period[0]
    # a name a point does not set holds the value it ran with: the base's (review 46, 13)
    assert res.table.loc[1, "tension"] == BASE.tension
    assert res.table.loc[1, "velocity"] == 0.0
    assert res.table.loc[0, "youngs_modulus"] == BASE.youngs_modulus
    with pytest.raises(ParameterError, match="cannot reach the Dask scheduler"):
        run_study(BASE, points=pts, compute="period", scheduler="tcp://127.0.0.1:9",
                  connect_timeout=1.0)


QUICK = {"vary": VARY, "compute": ("modes", "static"), "count": 2, "workers": 1}


@pytest.fixture(scope="module")
def quick():
    return run_study(BASE, **QUICK)


@pytest.mark.slow
def test_resume_recomputes_nothing_done(tmp_path, monkeypatch, quick):
    calls: list[dict] = []
    interrupt = [True]
    real = gyroshell.studies.evaluation.evaluate

    def counting(*args):
        calls.append(args[2])
        if len(calls) == 4 and interrupt[0]:
            interrupt[0] = False
            raise KeyboardInterrupt  # the user stops the study after three points
        return real(*args)

    # the one patch left: an interruption in the middle of a study has no public trigger
    monkeypatch.setattr(gyroshell.studies.evaluation, "evaluate", counting)
    cache = tmp_path / "study.jsonl"
    with pytest.raises(KeyboardInterrupt):
        run_study(BASE, **QUICK, cache=cache)
    assert len(calls) == 4
    calls.clear()
    done = run_study(BASE, **QUICK, cache=cache)
    assert len(calls) == 3  # only the three missing points
    assert done.info["cached"] == 3 and done.info["computed"] == 3
    pd.testing.assert_frame_equal(done.table, quick.table, check_exact=True)
    calls.clear()
    again = run_study(BASE, **QUICK, cache=cache)
    assert calls == [] and again.info["cached"] == 6 and again.info["computed"] == 0
    pd.testing.assert_frame_equal(again.table, quick.table, check_exact=True)
    # a different study does not reuse those rows
    other = run_study(BASE, **{**QUICK, "count": 3}, cache=cache)
    assert len(calls) == 6 and other.info["computed"] == 6


@pytest.mark.slow
def test_cut_short_cache_line_is_recomputed(tmp_path, quick):
    cache = tmp_path / "c.jsonl"
    run_study(BASE, **QUICK, cache=cache)
    lines = cache.read_text().splitlines()
    cache.write_text("\n".join(lines[:-1]) + "\n" + lines[-1][:20])
    res = run_study(BASE, **QUICK, cache=cache)
    assert res.info["computed"] == 1
    pd.testing.assert_frame_equal(res.table, quick.table, check_exact=True)


@pytest.mark.parametrize("kwargs, match", [
    ({"vary": {"colour": [1]}}, "cannot vary 'colour'"),
    ({"vary": {"thickness": [-1.0]}}, r"point 0 .*thickness must be > 0"),
    ({"vary": {"velocity": [-5.0]}}, "velocity must be >= 0"),
    ({"vary": {"tension": []}}, "tension needs at least one value"),
    ({"vary": {"tension": [1.0]}, "compute": "everything"}, "compute must be one or more"),
    ({"vary": {"tension": [1.0]}, "workers": 0}, r"workers must be an integer in \[1, "),
    ({"vary": {"tension": [1.0]}, "compute": "modes", "count": 0},
     r"count must be an integer in \[1, 50\]"),
    ({"vary": {"tension": [1.0]}, "points": [{}]}, "either vary"),
    ({}, "either vary"),
    ({"vary": {"tension": [1.0]}, "scheduler": "localhost"}, "tcp://HOST:PORT"),
    ({"vary": {"tension": [1.0]}, "scheduler": "tcp://a:1", "workers": 2}, "not both"),
    ({"vary": {"tension": [1.0]}, "connect_timeout": 0}, "connect_timeout must be"),
    ({"vary": {"tension": [1.0]}, "chunk_size": 0}, "chunk_size must be None or an integer >= 1"),
])
def test_refusals_name_the_problem(kwargs, match):
    with pytest.raises(ParameterError, match=match):
        run_study(BASE, **kwargs)


def test_dask_workers_must_run_this_gyroshell(monkeypatch):
    distributed = pytest.importorskip("distributed")
    # a worker of another release is simulated by what the version check runs on it
    monkeypatch.setattr(gyroshell.studies.executors, "worker_version", lambda: "0.0-other")
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                                  dashboard_address=None) as cluster:
        with pytest.raises(ParameterError, match="runs gyroshell 0.0-other"):
            run_study(BASE, vary={"tension": [80.0]}, compute="modes",
                      scheduler=cluster.scheduler_address)


def test_importing_the_study_module_loads_neither_scipy_nor_pandas():
    """The CLI's parser imports it for its choices: the solvers load only with the work."""
    import subprocess
    import sys

    code = ("import sys, gyroshell.studies.parameter_study, gyroshell.studies.evaluation, "
            "gyroshell.studies.points; "
            "print([n for n in ('scipy', 'pandas', 'distributed') if n in sys.modules])")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.split()
    assert out == ["[]"]
