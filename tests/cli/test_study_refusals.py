"""Hostile `study`, `campbell` and `sweep` command lines (issue 18): scheduler addresses that
are malformed, closed or not Dask's, cache files that are not this study's, options that
would be ignored or are nonsense. Each is refused in one line (exit 2, no traceback),
before any work, and leaves the folder (and the cache file) as it was."""

from __future__ import annotations

import json

import pytest
from conftest import WIDTH
from fake_servers import FakeServer, closed_port, dask_for

COARSE = ["--spacing", WIDTH / 8, "--length-ratio", 2]
LOUD_STUDY = ["study", *COARSE, "--vary", "tension=80,90", "--compute", "modes"]
STUDY = [*LOUD_STUDY, "--quiet"]


def refused(run, match: str) -> None:
    """Exit 2 with one `gyroshell: error:` line that says ``match``, nothing on stdout."""
    assert run.code == 2, run.err
    assert len(run.error_lines) == 1 and run.error_lines[0].startswith("gyroshell: error: ")
    assert match in run.err and "Traceback" not in run.err and run.out == ""


# ----- scheduler addresses -------------------------------------------------------------

ADDRESSES = [
    ("unknown scheme", "http://127.0.0.1:8786",
     "unknown scheme 'http://'; use tcp://, tls://, ws://, wss://, inproc://"),
    ("no such port", "tcp://127.0.0.1:99999", "port must be an integer in [1, 65535]"),
    ("port 0", "tcp://127.0.0.1:0", "port must be an integer in [1, 65535], got '0'"),
    ("no port", "tcp://127.0.0.1", "give the port, e.g. tcp://127.0.0.1:8786"),
    ("bad host", "tcp://bad_host:8786", "'bad_host' is not a host name"),
    ("bad IPv4", "tcp://999.1.1.1:8786", "'999.1.1.1' is not an IPv4 address"),
    ("bad IPv6", "tcp://[::g]:8786", "[::g] is not an IPv6 address"),
    ("no scheme", "127.0.0.1:8786", "scheduler must be an address like tcp://HOST:PORT"),
]


@pytest.mark.parametrize(("case", "address", "match"), ADDRESSES, ids=[a[0] for a in ADDRESSES])
def test_malformed_scheduler_addresses_are_refused_at_once(cli, tmp_path, monkeypatch, case,
                                                          address, match):
    monkeypatch.chdir(tmp_path)
    refused(cli([*STUDY, "--scheduler", address, "--cache", "c.jsonl", "--out", "s.csv"]),
            match)
    assert list(tmp_path.iterdir()) == []


def test_closed_port_is_refused_as_connection_refused(cli, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    port = closed_port()
    run = cli([*STUDY, "--scheduler", f"tcp://127.0.0.1:{port}", "--cache", "c.jsonl"])
    refused(run, f"connection refused (nothing listens on port {port} of 127.0.0.1)")
    assert list(tmp_path.iterdir()) == [], "no cache file created"


@pytest.fixture(params=list(FakeServer.REPLIES))
def fake_server(request):
    dask_for(request.param)
    server = FakeServer(request.param)
    yield server
    server.stop()


FAKE_MESSAGES = {"silent": "sent no Dask handshake within 0.5 s",
                 "close": "closed the connection without a Dask handshake",
                 "http": "is not a Dask scheduler: it answered b'HTTP/1.1 ",
                 "stall": "did not complete Dask's handshake within 0.5 s"}


def test_a_server_that_is_not_dask_is_refused_within_the_connect_timeout(
        cli, tmp_path, monkeypatch, fake_server):
    monkeypatch.chdir(tmp_path)
    run = cli([*STUDY, "--scheduler", f"tcp://127.0.0.1:{fake_server.port}",
               "--connect-timeout", "0.5", "--cache", "c.jsonl", "--out", "s.csv"])
    refused(run, FAKE_MESSAGES[fake_server.mode])
    assert list(tmp_path.iterdir()) == []


def test_a_real_dask_scheduler_passes_the_probes(cli, tmp_path):
    distributed = pytest.importorskip("distributed")
    out = tmp_path / "s.csv"
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                                  protocol="tcp://", dashboard_address=None) as cluster:
        address = cluster.scheduler_address
        assert address.startswith("tcp://127.0.0.1:")
        run = cli(["study", *COARSE, "--vary", "tension=80", "--compute", "modes",
                   "--count", "1", "--quiet", "--scheduler", address, "--connect-timeout",
                   "5", "--out", out])
    assert run.code == 0, run.err
    assert f"on dask({address})" in run.out and out.exists()


# ----- cache files ---------------------------------------------------------------------

#: (case, the cache file's bytes, what the one error line says)
CACHES = [
    ("binary", bytes(range(256)), "is not a study cache: byte 128 is not UTF-8 text"),
    ("UTF-16", '{"key": 1}\n'.encode("utf-16"), "byte 0 is not UTF-8 text"),
    ("NUL bytes", b'{"key": "x"}\x00\n', "it holds NUL bytes"),
    ("a JSON list", b"[1, 2, 3]\n", "line 1 must be an object with the fields key and row, "
                                    "got list"),
    ("other fields", b'{"k": "0", "r": {}}\n', "got ['k', 'r']"),
    ("not JSON mid-file", b'{"key": \n{"key": "0", "row": {}}\n', "line 1 is not JSON"),
    ("bad key", b'{"key": "fast", "row": {}}\n', "key must be 32 hexadecimal digits"),
    ("row not an object", b'{"key": "' + b"0" * 32 + b'", "row": [1]}\n',
     "row must be an object"),
]


@pytest.mark.parametrize(("case", "content", "match"), CACHES, ids=[c[0] for c in CACHES])
def test_a_cache_that_is_not_a_study_cache_is_refused_and_kept(cli, tmp_path, monkeypatch,
                                                               case, content, match):
    monkeypatch.chdir(tmp_path)
    cache = tmp_path / "c.jsonl"
    cache.write_bytes(content)
    run = cli([*STUDY, "--workers", "1", "--cache", "c.jsonl", "--out", "s.csv"])
    refused(run, match)
    assert "cache c.jsonl" in run.err and "give another cache path" in run.err
    assert cache.read_bytes() == content, "the file is left as it was"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["c.jsonl"]


@pytest.fixture
def finished_cache(cli, tmp_path, monkeypatch):
    """A cache of the study STUDY (count 1 for speed), written by a real run."""
    monkeypatch.chdir(tmp_path)
    run = cli([*STUDY, "--count", "1", "--workers", "1", "--cache", "c.jsonl"])
    assert run.code == 0, run.err
    return tmp_path / "c.jsonl"


EDITS = [
    ("a word for a speed", {"omega_1": "fast"}, "omega_1 must be a number >= 0 rad/s or NaN, "
                                                "got 'fast'"),
    ("a negative frequency", {"omega_1": -5.0}, "omega_1 must be a number >= 0 rad/s"),
    ("infinite growth rate", {"growth_rate": float("inf")}, "growth_rate must be a number"),
    ("a boolean", {"growth_rate": True}, "growth_rate must be a number >= 0 1/s or NaN, got "
                                         "True"),
    ("unknown stability", {"stability": "wobbly"}, "stability must be one of 'stable'"),
    ("error not text", {"error": 0}, "error must be text, got 0"),
    ("a missing column", {"omega_1": None}, "row must have the columns omega_1, growth_rate, "
                                            "stability, error"),
    ("an extra column", {"colour": "red"}, "row must have the columns"),
    ("an emptied row", dict.fromkeys(["omega_1", "growth_rate", "stability", "error"]),
     "row must have the columns omega_1, growth_rate, stability, error, got []"),
]


@pytest.mark.parametrize(("case", "edit", "match"), EDITS, ids=[e[0] for e in EDITS])
def test_an_edited_cache_row_is_refused_naming_file_and_line(cli, finished_cache, case, edit,
                                                             match):
    lines = finished_cache.read_text().splitlines()
    entry = json.loads(lines[1])
    for column, value in edit.items():
        if value is None:
            entry["row"].pop(column)
        else:
            entry["row"][column] = value
    lines[1] = json.dumps(entry)
    edited = "\n".join(lines) + "\n"
    finished_cache.write_text(edited)
    run = cli([*STUDY, "--count", "1", "--workers", "1", "--cache", "c.jsonl", "--out",
               "s.csv"])
    refused(run, match)
    assert "cache c.jsonl line 2: " in run.err
    assert finished_cache.read_text() == edited
    assert not (finished_cache.parent / "s.csv").exists(), "nothing wrong written to the CSV"


def test_an_emptied_cache_file_is_a_cache_with_nothing_done(cli, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    cache = tmp_path / "c.jsonl"
    cache.write_bytes(b"")
    run = cli([*STUDY, "--count", "1", "--workers", "1", "--cache", "c.jsonl", "--json"])
    assert run.code == 0, run.err
    assert json.loads(run.out)["computed"] == 2 and len(cache.read_text().splitlines()) == 2


def test_a_last_line_cut_short_is_recomputed_and_dropped(cli, finished_cache):
    text = finished_cache.read_text()
    finished_cache.write_text(text[:-25])  # an interruption in the middle of the last line
    run = cli([*STUDY, "--count", "1", "--workers", "1", "--cache", "c.jsonl", "--json"])
    assert run.code == 0, run.err
    assert json.loads(run.out)["cached"] == 1 and json.loads(run.out)["computed"] == 1
    assert finished_cache.read_text() == text, "the cut line replaced by the whole row"


def test_a_cache_without_its_last_newline_is_appended_to_cleanly(cli, finished_cache):
    lines = finished_cache.read_text().splitlines()
    finished_cache.write_text(lines[0])  # one whole row, no newline (an editor's save)
    run = cli([*STUDY, "--count", "1", "--workers", "1", "--cache", "c.jsonl", "--json"])
    assert run.code == 0, run.err
    assert finished_cache.read_text().splitlines() == lines


# ----- options ignored or nonsense -------------------------------------------------------

OPTIONS = [
    ("campbell --velocity", ["campbell", *COARSE, "--velocity", "5"],
     "unrecognized arguments: --velocity 5"),
    ("campbell --orders 0,-1", ["campbell", *COARSE, "--circumference", "0.01",
                                "--orders=0,-1"], "--orders must be integers in [1, 1000]"),
    ("campbell --orders 2.5", ["campbell", *COARSE, "--circumference", "0.01", "--orders",
                               "1,2.5"], "got 2.5"),
    ("campbell --orders without --circumference", ["campbell", *COARSE, "--orders", "1,2"],
     "add --circumference or drop --orders"),
    ("campbell --circumference 0", ["campbell", *COARSE, "--circumference", "0"],
     "--circumference must be > 0 m, got 0"),
    ("campbell --min-mac 2", ["campbell", *COARSE, "--min-mac", "2"],
     "--min-mac must be in [0, 1], got 2"),
    ("campbell --workers 10000", ["campbell", *COARSE, "--workers", "10000"],
     "--workers must be an integer in [1, "),
    ("sweep --workers 10000", ["sweep", *COARSE, "--workers", "10000"],
     "--workers must be an integer in [1, "),
    ("sweep --count 1000", ["sweep", *COARSE, "--count", "1000"],
     "count must be in [1, 50] for 135 unknowns, got 1000"),
    ("campbell --count 1000", ["campbell", *COARSE, "--count", "1000"],
     "count must be in [1, 50] for 135 unknowns, got 1000"),
    ("study --workers 10000", [*STUDY, "--workers", "10000"], "workers must be an integer in"),
    ("study --tension with --vary tension", [*STUDY, "--tension", "50"],
     "--tension and --vary tension both set tension"),
    ("study --velocity with --vary velocity", ["study", *COARSE, "--vary", "velocity=0,10",
                                               "--velocity", "5", "--compute", "critical"],
     "--velocity and --vary velocity both set velocity"),
    ("study --count without modes", ["study", *COARSE, "--vary", "tension=80", "--compute",
                                     "critical", "--count", "4"],
     "--count is the number of frequencies of --compute modes"),
    ("study --count 51", [*STUDY, "--count", "51"], "count must be an integer in [1, 50]"),
    ("study --connect-timeout without --scheduler", [*STUDY, "--connect-timeout", "1"],
     "--connect-timeout applies to --scheduler only"),
    ("study --connect-timeout 0", [*STUDY, "--scheduler", "tcp://127.0.0.1:8786",
                                   "--connect-timeout", "0"],
     "connect_timeout must be in (0, 3600] s, got 0"),
    ("study --workers and --scheduler", [*STUDY, "--workers", "2", "--scheduler",
                                         "tcp://127.0.0.1:8786"], "not both"),
]


@pytest.mark.parametrize(("case", "argv", "match"), OPTIONS, ids=[o[0] for o in OPTIONS])
def test_ignored_or_nonsense_options_are_refused(cli, tmp_path, monkeypatch, case, argv,
                                                 match):
    monkeypatch.chdir(tmp_path)
    refused(cli(argv), match)
    assert list(tmp_path.iterdir()) == []


def test_campbell_json_with_a_circumference_lists_the_resonances(cli):
    run = cli(["campbell", *COARSE, "--velocities", "0:80:3", "--count", "2", "--quiet",
               "--circumference", "1e-3", "--orders", "1", "--json"])
    assert run.code == 0, run.err
    out = json.loads(run.out)
    assert isinstance(out["resonances"], list)
    for row in out["resonances"]:
        assert set(row) == {"order", "branch", "velocity", "omega"} and row["order"] == 1


# ----- progress on a non-terminal stderr ----------------------------------------------

PROGRESS = [
    ("study", [*LOUD_STUDY, "--count", "1", "--workers", "1"],
     ["gyroshell: study: 2 points in this process",
      "gyroshell: study: 1/2 points done (50 %) in ",
      "gyroshell: study: 2/2 points done in "]),
    ("sweep", ["sweep", *COARSE, "--velocities", "0,10,20,30", "--count", "1"],
     ["gyroshell: sweep: 4 speeds of 1 modes each, 135 unknowns, in this process",
      "gyroshell: sweep: 1/4 speeds done (25 %) in ",
      "gyroshell: sweep: 2/4 speeds done (50 %) in ",
      "gyroshell: sweep: 3/4 speeds done (75 %) in ",
      "gyroshell: sweep: 4/4 speeds done in "]),
    ("campbell", ["campbell", *COARSE, "--velocities", "0,10", "--count", "1"],
     ["gyroshell: campbell: 2 speeds of 1 modes each (and 1 above, tracked), 135 unknowns, "
      "in this process",
      "gyroshell: campbell: 1/2 speeds done (50 %) in ",
      "gyroshell: campbell: 2/2 speeds done in ",
      "gyroshell: campbell: the critical speed (a few more eigen-solves)"]),
]


@pytest.mark.parametrize(("command", "argv", "lines"), PROGRESS, ids=[p[0] for p in PROGRESS])
def test_long_work_writes_one_line_per_stage_when_stderr_is_not_a_terminal(cli, command,
                                                                           argv, lines):
    run = cli(argv)  # the cli fixture's stderr is captured: not a terminal
    assert run.code == 0, run.err
    assert len(run.error_lines) == len(lines)
    for got, start in zip(run.error_lines, lines, strict=True):
        assert got.startswith(start)
    quiet = cli([*argv, "--quiet"])
    assert quiet.code == 0 and quiet.err == ""
