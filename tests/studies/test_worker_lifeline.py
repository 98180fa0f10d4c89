"""Worker processes die with the process that started them (issue 18, cause 12): a real
`kill -9` of `gyroshell study --workers 2` leaves no worker, fork server or resource
tracker behind, and the caller's pipes reach end-of-file."""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from conftest import WIDTH

#: Generous bounds for waiting on real processes (failure bounds, not timings under test).
START_BOUND, EXIT_BOUND = 120.0, 30.0

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"),
                                reason="reads the process tree from /proc")


def children_of(pid: int) -> set[int]:
    """Every living descendant of ``pid``, from /proc (no psutil needed)."""
    parents: dict[int, int] = {}
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                stat = (entry / "stat").read_bytes().rpartition(b")")[2].split()
            except OSError:
                continue
            if stat[0] not in (b"Z", b"X"):
                parents[int(entry.name)] = int(stat[1])
    found, frontier = set(), {pid}
    while frontier:
        frontier = {p for p, parent in parents.items() if parent in frontier} - found
        found |= frontier
    return found


def living(pids: set[int]) -> set[int]:
    """The pids of ``pids`` that still run (zombies count as gone)."""
    alive = set()
    for pid in pids:
        try:
            state = Path(f"/proc/{pid}/stat").read_bytes().rpartition(b")")[2].split()[0]
        except OSError:
            continue
        if state not in (b"Z", b"X"):
            alive.add(pid)
    return alive


def wait_for(condition, bound: float, what: str):
    deadline = time.monotonic() + bound
    while time.monotonic() < deadline:
        value = condition()
        if value:
            return value
        time.sleep(0.1)
    pytest.fail(f"{what} within {bound:g} s")


@contextlib.contextmanager
def running_study(argv: list[str], cwd, *, settle: float):
    """A study started in a subprocess, yielded with the set of its processes once its
    workers run (at least the fork server, two workers and the resource tracker) and
    ``settle`` s more; every one still alive is killed on the way out (a failing test
    cleans up after itself)."""
    env = {**os.environ, "PYTHONPATH": str(Path(__file__).resolve().parents[2])}
    proc = subprocess.Popen(argv, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            env=env)
    family: set[int] = set()
    try:
        family |= wait_for(lambda: (lambda c: c if len(c) >= 3 else None)(
            children_of(proc.pid)), START_BOUND, "the study did not start its workers")
        time.sleep(settle)
        family |= children_of(proc.pid)
        yield proc, family
    finally:
        for pid in living(family | {proc.pid}):
            os.kill(pid, signal.SIGKILL)


@pytest.mark.slow
def test_kill_9_of_a_study_with_workers_leaves_no_process_and_closes_the_pipes(tmp_path):
    argv = [sys.executable, "-m", "gyroshell", "study", "--spacing", str(WIDTH / 8),
            "--length-ratio", "4", "--vary", "velocity=0:100:30", "--vary",
            "tension=40:120:20", "--compute", "modes", "--workers", "2"]
    # the fork server, its two workers and the resource tracker: at least 3 processes
    with running_study(argv, tmp_path, settle=1.0) as (proc, family):  # workers computing
        os.kill(proc.pid, signal.SIGKILL)
        # the caller's pipes reach end-of-file: no survivor holds them
        _out, err = proc.communicate(timeout=EXIT_BOUND)
        assert proc.returncode == -signal.SIGKILL
        wait_for(lambda: not living(family), EXIT_BOUND, "processes survive")
        assert b"Traceback" not in err


@pytest.mark.slow
@pytest.mark.parametrize("when", ["before", "after"])
def test_a_worker_ends_when_its_starter_is_gone(when):
    """The lifeline itself, in a process whose parent is not the starter (as under a fork
    server): set up for a starter already gone, or one killed while the worker runs."""
    starter = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(600)"])
    if when == "before":
        starter.kill()
        starter.wait()
    code = ("import sys, time; from gyroshell.core.parallel import worker_setup; "
            f"worker_setup({starter.pid}); print('set up', flush=True); time.sleep(600); "
            "sys.exit(5)")
    worker = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE)
    try:
        if when == "after":
            assert worker.stdout.readline() == b"set up\n"
            starter.kill()  # not reaped yet: a zombie counts as gone
        assert worker.wait(timeout=EXIT_BOUND) == 1
    finally:
        for p in (starter, worker):
            if p.poll() is None:
                p.kill()
        starter.wait()


#: Ctrl-C or SIGTERM ends a study on workers within this, s, while each of its chunks takes
#: far longer (about 100 points of some 0.3 s each): the running chunks are not waited for.
STOP_BOUND = 10.0


@pytest.mark.slow
@pytest.mark.parametrize("sig, code", [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_a_signal_ends_a_study_on_workers_at_once_and_leaves_nothing(tmp_path, sig, code):
    out = tmp_path / "study.csv"
    argv = [sys.executable, "-m", "gyroshell", "study", "--vary", "velocity=0:100:800",
            "--compute", "critical,static", "--workers", "2", "--quiet", "--out", str(out)]
    with running_study(argv, tmp_path, settle=3.0) as (proc, family):  # in first chunks
        proc.send_signal(sig)
        _out, err = proc.communicate(timeout=STOP_BOUND)
        assert proc.returncode == code, err
        assert err.decode().strip().endswith("no output written"), err
        assert b"Traceback" not in err
        wait_for(lambda: not living(family), EXIT_BOUND, "processes survive")
        assert list(tmp_path.iterdir()) == []      # no output, no temporary file
