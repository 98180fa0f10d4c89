"""The study cache under several writers and on a full disk (issue 32): two studies
resuming one cache keep every finished row of both, and a disk that fills while the cache
is written is one line naming the file, with the rows written before it kept whole."""

from __future__ import annotations

import errno
import hashlib
import json
import os
import subprocess
import sys
import time
from pathlib import Path

import pytest
from conftest import WIDTH

from gyroshell import TapeParameters, run_study
from gyroshell.studies.cache import PointCache

BASE = TapeParameters(length_ratio=2, spacing=WIDTH / 8)
COARSE = ["--spacing", WIDTH / 8, "--length-ratio", 2]
#: A process that reads the cache, says so, waits to be let go, then appends its rows one
#: by one (as a study does, a line per finished point).
WRITER = """
import hashlib, sys, time
from pathlib import Path
from gyroshell.studies.cache import PointCache
path, name, count, ready, go = sys.argv[1:]
cache = PointCache(path)
cache.done()
Path(ready).touch()
while not Path(go).exists():
    time.sleep(0.01)
with cache:
    for i in range(int(count)):
        key = hashlib.md5(f"{name} {i}".encode()).hexdigest()
        cache.add([(key, {"writer": name, "i": i})])
"""


def _key(name: str, i: int) -> str:
    return hashlib.md5(f"{name} {i}".encode()).hexdigest()


def _wait_for(path: Path, proc: subprocess.Popen, timeout: float = 60.0) -> None:
    end = time.monotonic() + timeout
    while not path.exists():
        assert proc.poll() is None, proc.communicate()
        assert time.monotonic() < end, f"{path} never appeared"
        time.sleep(0.01)


def test_two_writers_resuming_a_cache_with_a_cut_line_keep_every_row(tmp_path):
    """Both processes read the cache (its last line cut by an interruption) before either
    writes; the second to write must not drop what the first appended meanwhile."""
    cache = tmp_path / "c.jsonl"
    old = [json.dumps({"key": _key("old", i), "row": {"writer": "old", "i": i}})
           for i in range(3)]
    cache.write_text("\n".join(old) + "\n" + old[0][:25])      # a cut last line
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    procs = {}
    for name in ("a", "b"):
        procs[name] = subprocess.Popen(
            [sys.executable, "-c", WRITER, str(cache), name, "20", str(tmp_path / name),
             str(tmp_path / f"go_{name}")], env=env, stderr=subprocess.PIPE, text=True)
    for name, proc in procs.items():
        _wait_for(tmp_path / name, proc)
    for name, proc in procs.items():          # a writes all its rows, then b
        (tmp_path / f"go_{name}").touch()
        assert proc.wait(timeout=120) == 0, proc.stderr.read()
    rows = PointCache(cache).done()
    expected = {_key("old", i) for i in range(3)} | {
        _key(name, i) for name in ("a", "b") for i in range(20)}
    assert set(rows) == expected
    assert cache.read_text().endswith("\n") and len(cache.read_text().splitlines()) == 43


STUDY = """
import sys
from gyroshell import TapeParameters, run_study
base = TapeParameters(length_ratio=2, spacing=6.35e-3 / 8)
run_study(base, vary={"tension": [60.0 + i for i in range(24)]}, compute="critical",
          workers=1, cache=sys.argv[1], progress=False)
"""


def test_two_studies_at_once_on_one_cut_cache_resume_to_every_point(tmp_path):
    """The issue's case itself: two studies started together on a cache ending in a cut
    line; afterwards the cache holds every point and a third run computes nothing."""
    cache = tmp_path / "c.jsonl"
    vary = {"tension": [60.0 + i for i in range(24)]}
    run_study(BASE, vary={"tension": vary["tension"][:2]}, compute="critical", workers=1,
              cache=cache, progress=False)
    cache.write_text(cache.read_text() + cache.read_text()[:30])     # cut by a kill
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    procs = [subprocess.Popen([sys.executable, "-c", STUDY, str(cache)], env=env,
                              stderr=subprocess.PIPE, text=True) for _ in range(2)]
    for proc in procs:
        assert proc.wait(timeout=300) == 0, proc.stderr.read()
    again = run_study(BASE, vary=vary, compute="critical", workers=1, cache=cache,
                      progress=False)
    assert again.info["computed"] == 0 and again.info["cached"] == 24


# ----- a full disk ---------------------------------------------------------------------
PAGE = 4096


@pytest.fixture
def small_disk(tmp_path):
    """A 64 kB tmpfs (root on Linux only; skipped elsewhere), unmounted afterwards."""
    if not sys.platform.startswith("linux") or os.geteuid() != 0:
        pytest.skip("mounting a small tmpfs needs root on Linux")
    disk = tmp_path / "disk"
    disk.mkdir()
    mounted = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=64k", "tmpfs", str(disk)],
                             capture_output=True, text=True)
    if mounted.returncode != 0:
        pytest.skip(f"cannot mount a tmpfs here: {mounted.stderr.strip()}")
    try:
        yield disk
    finally:
        subprocess.run(["umount", "-l", str(disk)], check=False)


def _fill(disk: Path, leave: int = 0) -> None:
    """Fill ``disk`` with a file, then free ``leave`` bytes (whole pages) of it."""
    filler = disk / "filler"
    fd = os.open(filler, os.O_WRONLY | os.O_CREAT)
    try:
        while True:
            os.write(fd, b"\0" * PAGE)
    except OSError as exc:
        assert exc.errno == errno.ENOSPC
    finally:
        os.close(fd)
    size = filler.stat().st_size // PAGE * PAGE
    os.truncate(filler, size - leave)


def test_a_full_disk_while_writing_the_cache_is_one_line_naming_it(cli, small_disk):
    _fill(small_disk)
    cache = small_disk / "c.jsonl"
    run = cli(["study", *COARSE, "--vary", "tension=80,90", "--compute", "critical",
               "--workers", "1", "--quiet", "--cache", cache])
    assert run.code == 2, run.err
    assert run.error_lines == [f"gyroshell: error: [Errno 28] cannot write the study cache "
                               f"{cache}: No space left on device; the points it holds are "
                               "kept: free some space and run the study again to resume"]
    assert run.out == "" and "Traceback" not in run.err
    assert not cache.exists() or cache.read_bytes() == b""


def test_rows_written_before_the_disk_filled_are_whole_and_resume(small_disk):
    _fill(small_disk, leave=PAGE)        # room for a page of rows, then the disk is full
    cache = small_disk / "c.jsonl"
    vary = {"tension": [60.0 + i for i in range(60)]}
    with pytest.raises(OSError, match=f"cannot write the study cache {cache}: No space"):
        run_study(BASE, vary=vary, compute="critical", workers=1, cache=cache,
                  progress=False)
    text = cache.read_text()
    assert 0 < len(text) <= PAGE and text.endswith("\n"), "no cut line is left behind"
    kept = PointCache(cache).done()
    os.remove(small_disk / "filler")
    again = run_study(BASE, vary=vary, compute="critical", workers=1, cache=cache,
                      progress=False)
    assert again.info["cached"] == len(kept) > 0
    assert again.info["computed"] == 60 - len(kept)


def test_a_cache_on_a_read_only_disk_is_one_line_naming_it(small_disk):
    """The rows the cache holds are served; the first new one cannot be kept (the command
    line refuses the folder before any work)."""
    cache = small_disk / "c.jsonl"
    run_study(BASE, vary={"tension": [80.0]}, compute="critical", workers=1, cache=cache,
              progress=False)
    kept = cache.read_bytes()
    remounted = subprocess.run(["mount", "-o", "remount,ro", str(small_disk)],
                               capture_output=True, text=True)
    if remounted.returncode != 0:
        pytest.skip(f"cannot remount the tmpfs read-only: {remounted.stderr.strip()}")
    with pytest.raises(OSError) as refused:
        run_study(BASE, vary={"tension": [80.0, 90.0]}, compute="critical", workers=1,
                  cache=cache, progress=False)
    assert str(refused.value) == (f"[Errno 30] cannot write the study cache {cache}: "
                                  "Read-only file system; the points it holds are kept: run "
                                  "the study again to resume")
    assert cache.read_bytes() == kept
