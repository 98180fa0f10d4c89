"""The Python API of studies, Campbell diagrams and sweeps under hostile input (issue 18):
each refusal is a ParameterError naming the argument (or the file and line), raised before
any work."""

from __future__ import annotations

import io
import json
import math

import pytest
from conftest import WIDTH
from fake_servers import FakeServer, closed_port, dask_for

from gyroshell import ParameterError, TapeModel, TapeParameters, run_study
from gyroshell.core.parallel import check_process_count, max_processes, process_pool
from gyroshell.core.progress import StageLines, stage_progress
from gyroshell.studies.campbell import CampbellDiagram, campbell, check_orders
from gyroshell.studies.evaluation import MAX_COUNT, check_row, result_columns
from gyroshell.studies.scheduler import check_address
from gyroshell.studies.sweep import sweep

BASE = TapeParameters(length_ratio=2, spacing=WIDTH / 8)
ONE_POINT = {"vary": {"tension": [80.0]}, "compute": "modes", "count": 1}


@pytest.mark.parametrize(("scheduler", "match"), [
    ("http://127.0.0.1:8786", r"scheduler 'http://127.0.0.1:8786': unknown scheme 'http://'"),
    ("tcp://127.0.0.1:99999", r"port must be an integer in \[1, 65535\], got '99999'"),
    ("tcp://127.0.0.1:x", r"port must be an integer in \[1, 65535\], got 'x'"),
    ("tcp://:8786", "'' is not a host name"),
    ("tcp://-a.b:8786", "'-a.b' is not a host name"),
    ("tcp://[::1:8786", r"missing '\]'"),
    ("inproc://", "an inproc:// address names the in-process scheduler"),
    (8786, "scheduler must be an address like tcp://HOST:PORT"),
])
def test_scheduler_addresses_are_checked_without_the_network(scheduler, match):
    with pytest.raises(ParameterError, match=match):
        run_study(BASE, **ONE_POINT, scheduler=scheduler)


def test_good_addresses_are_read():
    assert check_address("tcp://127.0.0.1:8786").port == 8786
    assert check_address("TLS://sched.example.org:443/").host == "sched.example.org"
    assert check_address("tcp://[::1]:8786").host == "::1"


def test_a_closed_port_is_refused_without_waiting_for_the_timeout(tmp_path):
    cache = tmp_path / "c.jsonl"
    with pytest.raises(ParameterError, match="connection refused"):
        run_study(BASE, **ONE_POINT, scheduler=f"tcp://127.0.0.1:{closed_port()}",
                  connect_timeout=3600, cache=cache)
    assert not cache.exists()


@pytest.mark.parametrize("mode", list(FakeServer.REPLIES))
def test_a_server_that_is_not_dask_raises_a_parameter_error(mode):
    dask_for(mode)
    server = FakeServer(mode)
    try:
        with pytest.raises(ParameterError, match=f"tcp://127.0.0.1:{server.port}"):
            run_study(BASE, **ONE_POINT, scheduler=f"tcp://127.0.0.1:{server.port}",
                      connect_timeout=0.5)
    finally:
        server.stop()


def test_websocket_and_in_process_addresses_that_lead_nowhere(tmp_path):
    pytest.importorskip("distributed", exc_type=ImportError)  # Dask's own refusals
    with pytest.raises(ParameterError, match="no Dask scheduler of this process listens"):
        run_study(BASE, **ONE_POINT, scheduler="inproc://192.0.2.1/1/1", connect_timeout=1)
    server = FakeServer("http")
    try:
        with pytest.raises(ParameterError, match="wss:// needs Dask's TLS settings"):
            run_study(BASE, **ONE_POINT, scheduler=f"wss://127.0.0.1:{server.port}",
                      connect_timeout=1)
        with pytest.raises(ParameterError, match=f"ws://127.0.0.1:{server.port}"):
            run_study(BASE, **ONE_POINT, scheduler=f"ws://127.0.0.1:{server.port}",
                      connect_timeout=1)
    finally:
        server.stop()


@pytest.mark.parametrize("timeout", [0, -1, math.nan, math.inf, 1e300, "10"])
def test_connect_timeout_range(timeout):
    with pytest.raises(ParameterError, match="connect_timeout must be"):
        run_study(BASE, **ONE_POINT, scheduler="tcp://127.0.0.1:8786", connect_timeout=timeout)


def test_a_damaged_cache_names_the_file_and_line(tmp_path):
    cache = tmp_path / "c.jsonl"
    run_study(BASE, **ONE_POINT, workers=1, cache=cache, progress=False)
    entry = json.loads(cache.read_text())
    entry["row"]["omega_1"] = "fast"
    cache.write_text(json.dumps(entry) + "\n")
    with pytest.raises(ParameterError, match=f"cache {cache} line 1: omega_1 must be a number"):
        run_study(BASE, **ONE_POINT, workers=1, cache=cache, progress=False)
    cache.write_bytes(b"\x89PNG\r\n\x1a\n")
    with pytest.raises(ParameterError, match=f"cache {cache} is not a study cache"):
        run_study(BASE, **ONE_POINT, workers=1, cache=cache, progress=False)
    with pytest.raises(ParameterError, match="is not a file"):
        run_study(BASE, **ONE_POINT, workers=1, cache=tmp_path, progress=False)
    with pytest.raises(ParameterError, match="folder .* does not exist"):
        run_study(BASE, **ONE_POINT, workers=1, cache=tmp_path / "no" / "c.jsonl")


def test_rows_of_other_studies_in_the_same_cache_are_kept(tmp_path):
    cache = tmp_path / "c.jsonl"
    run_study(BASE, **ONE_POINT, workers=1, cache=cache, progress=False)
    other = run_study(BASE, vary=ONE_POINT["vary"], compute="critical", workers=1,
                      cache=cache, progress=False)
    assert other.info["computed"] == 1
    again = run_study(BASE, **ONE_POINT, workers=1, cache=cache, progress=False)
    assert again.info["cached"] == 1 and len(cache.read_text().splitlines()) == 2


ROW = {"omega_1": 100.0, "growth_rate": 0.0, "stability": "stable", "error": ""}


@pytest.mark.parametrize(("change", "match"), [
    ({"omega_1": "fast"}, "omega_1 must be a number >= 0 rad/s or NaN, got 'fast'"),
    ({"omega_1": math.inf}, "omega_1 must be a number >= 0 rad/s or NaN, got inf"),
    ({"omega_1": None}, "omega_1 must be a number"),
    ({"growth_rate": -1.0}, "growth_rate must be a number >= 0 1/s"),
    ({"stability": 3}, "stability must be one of"),
    ({"error": None}, "error must be text"),
])
def test_check_row_is_as_strict_as_the_computation(change, match):
    with pytest.raises(ParameterError, match=match):
        check_row({**ROW, **change}, ("modes",), 1)


def test_check_row_accepts_what_evaluation_writes():
    assert check_row({**ROW, "omega_1": 5}, ("modes",), 1)["omega_1"] == 5.0
    assert math.isnan(check_row({**ROW, "omega_1": math.nan, "error": "modes: x"},
                                ("modes",), 1)["omega_1"])
    row = dict.fromkeys(result_columns(("period",), 1), math.inf)
    row.update(stability="divergence", error="")
    assert check_row(row, ("period",), 1)["period"] == math.inf  # omega = 0: period inf
    with pytest.raises(ParameterError, match="row must have the columns"):
        check_row({"omega_1": 1.0}, ("modes",), 1)


def test_study_count_is_the_eigen_solvers_limit():
    from gyroshell.linalg.qep.problem import MAX_COUNT as SOLVER_LIMIT

    assert MAX_COUNT == SOLVER_LIMIT
    with pytest.raises(ParameterError, match=r"count must be an integer in \[1, 50\]"):
        run_study(BASE, vary={"tension": [80.0]}, compute="modes", count=10**9)


@pytest.mark.parametrize("orders", [[0], [-1], [1.5], ["2"], [10**6], [], 3, "1,2"])
def test_excitation_orders_are_positive_harmonics(orders):
    with pytest.raises(ParameterError, match="orders must"):
        check_orders(orders)


def test_campbell_refuses_bad_orders_circumference_and_critical_speed(small):
    d = campbell(small, [0.0, 10.0], 1, progress=False, critical_speed=None)
    assert isinstance(d, CampbellDiagram)
    with pytest.raises(ParameterError, match="orders must be integers in"):
        d.resonances(0.01, orders=(0, -1))
    with pytest.raises(ParameterError, match="orders must be integers in"):
        d.plot(circumference=0.01, orders=[-1])
    with pytest.raises(ParameterError, match="circumference must be > 0 m"):
        d.resonances(-0.01)
    with pytest.raises(ParameterError, match="orders must be integers in"):
        CampbellDiagram.excitation(0, 0.01, 1.0)
    with pytest.raises(ParameterError, match="critical_speed must be a real number"):
        campbell(small, [0.0], 1, critical_speed="fast")


def test_process_counts_are_bounded():
    assert check_process_count("workers", max_processes()) == max_processes()
    with pytest.raises(ParameterError, match=r"workers must be an integer in \[1, "):
        check_process_count("workers", max_processes() + 1)
    with pytest.raises(ParameterError, match="workers must be an integer"), \
            process_pool(10**6):
        pass
    model = TapeModel(BASE)
    with pytest.raises(ParameterError, match="workers must be an integer"):
        sweep(model, [0.0, 10.0], 1, workers=10**6)
    with pytest.raises(ParameterError, match="workers must be an integer"):
        run_study(BASE, **ONE_POINT, workers=10**6)


def test_stage_lines_only_where_no_bar_is_drawn(capsys):
    with stage_progress(2, "demo", progress=False, unit="point") as bar:
        bar.start("here")
        bar.update(2)
    assert capsys.readouterr().err == ""
    assert isinstance(stage_progress(2, "demo", progress=None, unit="point"), StageLines)
    out = io.StringIO()
    with StageLines(8, "study", "point", initial=2, stream=out) as lines:
        lines.start("on 2 processes")
        lines.update(2)
    text = out.getvalue().splitlines()  # interrupted at 4/8: no closing line
    assert text[0] == "gyroshell: study: 8 points (2 from the cache) on 2 processes"
    assert text[1].startswith("gyroshell: study: 4/8 points done (50 %) in ")
    assert len(text) == 2
