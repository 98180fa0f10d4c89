"""A sweep split over local processes gives the one-process sweep: same frequencies (each
run restarts its continuation: equal to round-off), same tracked branches, same table from
the CLI; bad worker counts are refused."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from gyroshell import ParameterError, TapeModel, TapeParameters
from gyroshell.studies.sweep import sweep

WIDTH = TapeParameters().width


@pytest.mark.slow
def test_two_processes_give_the_one_process_sweep():
    model = TapeModel(TapeParameters(length_ratio=4.0, spacing=WIDTH / 8))
    speeds = np.linspace(0, 95, 7)
    one = sweep(model, speeds, 4).table
    two = sweep(TapeModel(model.params), speeds, 4, workers=2).table
    assert list(two.velocity) == list(one.velocity)
    assert np.allclose(two.omega, one.omega, rtol=1e-10, atol=0)
    assert (two.branch == one.branch).all() and (two["rank"] == one["rank"]).all()


@pytest.mark.slow
def test_cli_sweep_workers(cli, tmp_path):
    out1, out2 = tmp_path / "one.csv", tmp_path / "two.csv"
    base = ["sweep", "--length-ratio", "2", "--velocities", "0,20,40,60", "--count", "3"]
    assert cli(base + ["--out", str(out1)]).code == 0
    assert cli(base + ["--out", str(out2), "--workers", "2"]).code == 0
    a, b = pd.read_csv(out1), pd.read_csv(out2)
    assert np.allclose(a.omega, b.omega, rtol=1e-10, atol=0)
    run = cli(base + ["--workers", "0"])
    assert run.code == 2 and "--workers" in run.err


@pytest.mark.parametrize("workers", [0, -1, 1.5, True, "2"])
def test_worker_count_refusals(workers):
    model = TapeModel(TapeParameters(length_ratio=2.0, spacing=WIDTH / 8))
    with pytest.raises(ParameterError, match="workers must be an integer"):
        sweep(model, [0.0, 10.0], 2, workers=workers)


def test_a_sweep_result_still_behaves_like_its_table_with_a_warning():
    model = TapeModel(TapeParameters(length_ratio=2.0, spacing=WIDTH / 8))
    result = sweep(model, [0.0, 10.0], 2)
    table = result.table
    for use in (lambda r: r["omega"], lambda r: r.omega, lambda r: len(r),
                lambda r: r.columns, lambda r: "rank" in r, lambda r: list(r)):
        with pytest.warns(DeprecationWarning, match="use .table"):
            got = use(result)
        expected = use(table)
        if isinstance(expected, pd.Series):
            pd.testing.assert_series_equal(got, expected)
        elif isinstance(expected, pd.Index):
            assert list(got) == list(expected)
        else:
            assert got == expected
    with pytest.raises(AttributeError):
        _ = result._not_a_field  # private probes are not sent to the table


@pytest.mark.slow
def test_process_pool_cancels_the_queue_when_the_block_fails():
    from gyroshell.core.parallel import process_pool

    with pytest.raises(ZeroDivisionError), process_pool(1) as pool:
        futures = [pool.submit(pow, 2, k) for k in range(50)]
        raise ZeroDivisionError
    assert any(f.cancelled() for f in futures)
    with process_pool(2) as pool:
        assert list(pool.map(pow, [2, 3], [3, 2])) == [8, 9]
