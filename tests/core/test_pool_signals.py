"""A signal that stops a run on worker processes (issue 32): a worker being started when the
signal comes is stopped with the others (it was left to start after the run was gone and
printed a 14-line FileNotFoundError traceback), and stopped workers leave no semaphore for
Python's resource tracker to report as leaked. Real processes and real signals."""

from __future__ import annotations

import subprocess
import sys
import textwrap

import pytest

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"),
                                reason="SIGTERM and the fork server are POSIX")

#: Bound on each script's run, s (a failure bound, not a timing under test).
BOUND = 120.0

#: The run stopped by SIGTERM as its first worker starts: the signal is sent just after the
#: fork server has started the worker and before the pool has taken its pid, the moment
#: where ``kill -TERM`` of ``gyroshell sweep --workers 2`` found it. Prints whether that
#: worker still runs once the pool has stopped.
DURING_START = """
    import os, signal, sys, time
    from multiprocessing import forkserver

    from gyroshell.core.files import Terminated, termination_signals
    from gyroshell.core.parallel import _alive, process_pool

    started = []
    real_read = forkserver.read_signed

    def read_signed(fd):  # the pool reads the new worker's pid here
        forkserver.read_signed = real_read
        pid = real_read(fd)
        started.append(pid)
        os.kill(os.getpid(), signal.SIGTERM)
        return pid

    if __name__ == "__main__":
        try:
            with termination_signals(), process_pool(2) as pool:
                forkserver.read_signed = read_signed
                pool.submit(time.sleep, 30).result()
        except Terminated:
            print("worker left running:", _alive(started[0]), flush=True)
            sys.exit(143)
"""

#: The run stopped by SIGTERM while its worker waits for work, after the worker made a
#: (disabled) progress bar, as every engine does.
AFTER_A_BAR = """
    import os, signal, sys

    from gyroshell.core.files import Terminated, termination_signals
    from gyroshell.core.parallel import process_pool
    from gyroshell.core.progress import progress_bar

    def bar():
        with progress_bar(3, "work", progress=False) as shown:
            shown.update(3)
        return os.getpid()

    if __name__ == "__main__":
        try:
            with termination_signals(), process_pool(1) as pool:
                print("worker", pool.submit(bar).result(), flush=True)
                os.kill(os.getpid(), signal.SIGTERM)
                pool.submit(bar).result()
        except Terminated:
            sys.exit(143)
"""


def run_script(tmp_path, text: str) -> subprocess.CompletedProcess:
    """Run ``text`` as a script file (the workers import their main module from it); the
    pipes reach end-of-file only when the fork server and resource tracker are gone too."""
    script = tmp_path / "run.py"
    script.write_text(textwrap.dedent(text))
    return subprocess.run([sys.executable, str(script)], cwd=tmp_path, capture_output=True,
                          text=True, timeout=BOUND)


def test_a_worker_starting_when_sigterm_comes_is_stopped_with_the_pool(tmp_path):
    run = run_script(tmp_path, DURING_START)
    assert run.returncode == 143, run.stderr
    assert run.stdout == "worker left running: False\n"
    assert run.stderr == ""   # neither a traceback from the worker nor a tracker warning


def test_workers_stopped_by_sigterm_leave_no_semaphore_behind(tmp_path):
    run = run_script(tmp_path, AFTER_A_BAR)
    assert run.returncode == 143, run.stderr
    assert run.stdout.startswith("worker ")
    assert "leaked semaphore" not in run.stderr and run.stderr == ""
