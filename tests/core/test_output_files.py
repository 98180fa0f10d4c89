"""Output files: checked before computing, never half-written, nothing the user had damaged,
and every output of a run or none, including when the run is killed by a signal."""

from __future__ import annotations

import os
import signal
import stat
import subprocess
import sys
import textwrap

import numpy as np
import pytest
from conftest import WIDTH

from gyroshell import ParameterError
from gyroshell.core.files import (
    OutputPathError,
    atomic_path,
    check_output,
    check_outputs,
    transaction,
    write_atomic,
)

COARSE = ["--spacing", WIDTH / 8, "--length-ratio", 2]
SWEEP = ["sweep", *COARSE, "--velocities", "0,10", "--count", "2"]
TRANSIENT = ["transient", *COARSE, "--quiet", "--steps", "20", "--dt", "2e-6"]


def listing(folder) -> list[str]:
    """Every name in ``folder``, hidden temporary files included."""
    return sorted(os.listdir(folder))


# ----- refused before computing -----------------------------------------------------------
@pytest.fixture
def workdir(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "afile").write_text("x")
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o555)
    yield tmp_path
    ro.chmod(0o755)


BAD_OUTPUTS = [
    ("unsupported plot format", [*SWEEP, "--plot", "s.xyz"],
     "--plot s.xyz: unsupported plot format 'xyz'"),
    ("plot without a suffix", [*SWEEP, "--plot", "plot"], "unsupported plot format ''"),
    ("read-only folder", [*SWEEP, "--out", "ro/s.csv"], "--out ro/s.csv: folder ro is read-only"),
    ("parent is a file", [*SWEEP, "--out", "afile/s.csv"],
     "--out afile/s.csv: afile is a file, not a folder"),
    ("missing folder", [*SWEEP, "--out", "none/s.csv"], "folder none does not exist"),
    ("output is a folder", [*SWEEP, "--out", "ro"], "--out ro: is a folder"),
    ("same path twice", [*SWEEP, "--out", "s.csv", "--save", "s.csv"],
     "--out and --save name the same file s.csv"),
    ("same file through ./", [*TRANSIENT, "--out", "h.csv", "--save", "./h.csv"],
     "name the same file"),
    ("out not a table", [*SWEEP, "--out", "s.png"], "--out: use a .csv or .parquet file"),
    ("transient into a read-only folder", [*TRANSIENT, "--out", "ro/h.csv"], "read-only"),
    ("snapshots parent is a file", [*TRANSIENT, "--snapshot-every", "5", "--snapshots",
                                    "afile/s.npz"], "afile is a file"),
    ("frf plot into a read-only folder",
     ["frf", *COARSE, "--frequencies", "0:1e5:3", "--plot", "ro/f.png"], "read-only"),
    ("frf out not a table", ["frf", *COARSE, "--frequencies", "0:1e5:3", "--out", "f.png",
                             "--plot", "f.png"], "--out: use a .csv or .parquet file"),
    ("study out and save the same file",
     ["study", *COARSE, "--vary", "tension=80,90", "--compute", "modes", "--out", "s.csv",
      "--save", "./s.csv"], "name the same file"),
    ("study cache parent is a file",
     ["study", *COARSE, "--vary", "tension=80,90", "--compute", "modes", "--cache",
      "afile/c.jsonl"], "afile is a file"),
    ("reproduce into a file", ["reproduce", "fig2", "--quick", "--out-dir", "afile"],
     "--out-dir afile: is a file, not a folder"),
    ("reproduce into a read-only folder",
     ["reproduce", "fig2", "--quick", "--out-dir", "ro/r"], "read-only"),
]


@pytest.mark.parametrize(("case", "argv", "match"), BAD_OUTPUTS, ids=[b[0] for b in BAD_OUTPUTS])
def test_bad_output_refused_before_computing(cli, workdir, monkeypatch, case, argv, match):
    import gyroshell.engines.eigen
    import gyroshell.engines.newmark
    import gyroshell.studies.parameter_study  # noqa: F401 - bound to the real engines before the patch
    import gyroshell.studies.sweep  # noqa: F401

    def must_not_run(*args, **kwargs):
        raise AssertionError("computed before checking the outputs")

    monkeypatch.setattr(gyroshell.engines.eigen, "modes", must_not_run)
    monkeypatch.setattr(gyroshell.engines.newmark.Newmark, "__init__", must_not_run)
    before = listing(workdir)
    run = cli(argv)
    assert run.code == 2, run.err
    assert len(run.error_lines) == 1 and match in run.err and "Traceback" not in run.err
    assert listing(workdir) == before and listing(workdir / "ro") == []


def test_existing_read_only_file_is_not_replaced(cli, tmp_path):
    out = tmp_path / "s.csv"
    out.write_text("mine\n")
    out.chmod(0o444)
    run = cli([*SWEEP, "--out", out])
    assert run.code == 2 and f"--out {out}: exists and is read-only; not replaced" in run.err
    assert out.read_text() == "mine\n" and stat.S_IMODE(out.stat().st_mode) == 0o444


def test_device_file_is_not_replaced(tmp_path):
    with pytest.raises(OutputPathError, match="not a regular file"):
        check_output("/dev/null")


# ----- what a successful write does to what was there ----------------------------------
def test_write_through_symlink_updates_target_and_keeps_link(cli, tmp_path):
    real = tmp_path / "data" / "h.csv"
    real.parent.mkdir()
    real.write_text("old\n")
    link = tmp_path / "h.csv"
    link.symlink_to(real)
    run = cli([*TRANSIENT, "--out", link])
    assert run.code == 0, run.err
    assert link.is_symlink() and os.readlink(link) == str(real)
    assert real.read_text().startswith("t,w\n") and len(real.read_text().splitlines()) == 22
    assert listing(tmp_path) == ["data", "h.csv"] and listing(real.parent) == ["h.csv"]


def test_replaced_file_keeps_its_permissions(cli, tmp_path):
    out = tmp_path / "h.csv"
    out.write_text("old\n")
    out.chmod(0o640)
    assert cli([*TRANSIENT, "--out", out]).code == 0
    assert out.read_text().startswith("t,w\n")
    assert stat.S_IMODE(out.stat().st_mode) == 0o640


def test_new_file_gets_the_usual_permissions(tmp_path):
    umask = os.umask(0o022)
    try:
        write_atomic(tmp_path / "a.txt", lambda p: p.write_text("a"))
    finally:
        os.umask(umask)
    assert stat.S_IMODE((tmp_path / "a.txt").stat().st_mode) == 0o644


# ----- all outputs or none ----------------------------------------------------------------
@pytest.mark.slow
def test_sweep_whose_plot_fails_leaves_no_csv(cli, tmp_path, monkeypatch):
    import matplotlib.figure

    def disk_full(self, fname, *args, **kwargs):
        raise OSError(28, "No space left on device", os.fspath(fname))

    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", disk_full)
    csv, png = tmp_path / "s.csv", tmp_path / "s.png"
    run = cli([*SWEEP, "--out", csv, "--plot", png, "--quiet"])
    assert run.code == 2
    assert run.error_lines == [f"gyroshell: error: [Errno 28] cannot write {png}: "
                               "No space left on device"]
    assert listing(tmp_path) == []


@pytest.mark.slow
@pytest.mark.parametrize("argv", [
    ["frf", *COARSE, "--frequencies", "0:1e5:3"],
    ["study", *COARSE, "--vary", "tension=80,90", "--compute", "static"],
], ids=["frf", "study"])
def test_run_whose_plot_fails_leaves_no_table(cli, tmp_path, monkeypatch, argv):
    import matplotlib.figure

    def disk_full(self, fname, *args, **kwargs):
        raise OSError(28, "No space left on device", os.fspath(fname))

    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", disk_full)
    run = cli([*argv, "--out", tmp_path / "t.csv", "--plot", tmp_path / "t.png", "--quiet"])
    assert run.code == 2 and len(run.error_lines) == 1 and "cannot write" in run.err
    assert listing(tmp_path) == []


def test_transient_whose_snapshots_fail_leaves_old_history_untouched(cli, tmp_path,
                                                                     monkeypatch):
    history = tmp_path / "h.csv"
    history.write_text("previous run\n")
    monkeypatch.setattr(np, "savez", lambda *a, **k: (_ for _ in ()).throw(
        OSError(28, "No space left on device")))
    run = cli([*TRANSIENT, "--out", history, "--snapshot-every", "5",
               "--snapshots", tmp_path / "s.npz"])
    assert run.code == 2 and "cannot write" in run.err and str(tmp_path / "s.npz") in run.err
    assert ".s.npz" not in run.err  # the user's path, not the hidden temporary file
    assert history.read_text() == "previous run\n"
    assert listing(tmp_path) == ["h.csv"]


def test_transaction_commits_all_or_restores_everything(tmp_path):
    a, b = tmp_path / "a.txt", tmp_path / "b.txt"
    a.write_text("old a")
    with pytest.raises(RuntimeError), transaction():
        write_atomic(a, lambda p: p.write_text("new a"))
        write_atomic(b, lambda p: p.write_text("new b"))
        raise RuntimeError("the last step failed")
    assert a.read_text() == "old a" and listing(tmp_path) == ["a.txt"]
    with transaction():
        write_atomic(a, lambda p: p.write_text("new a"))
        with atomic_path(b) as tmp:
            tmp.write_text("new b")
        assert a.read_text() == "old a" and not b.exists()  # staged until the end
    assert a.read_text() == "new a" and b.read_text() == "new b"
    assert listing(tmp_path) == ["a.txt", "b.txt"]


def test_commit_that_fails_half_way_puts_back_the_first_file(tmp_path, monkeypatch):
    a, b = tmp_path / "a.txt", tmp_path / "b.txt"
    a.write_text("old a")
    real_replace = os.replace

    def replace(src, dst):
        if os.fspath(dst) == os.fspath(b):
            raise OSError(5, "Input/output error")
        return real_replace(src, dst)

    with pytest.raises(OSError, match=f"cannot write {b}"), transaction():
        write_atomic(a, lambda p: p.write_text("new a"))
        write_atomic(b, lambda p: p.write_text("new b"))
        monkeypatch.setattr(os, "replace", replace)
    monkeypatch.undo()
    assert a.read_text() == "old a" and listing(tmp_path) == ["a.txt"]


def test_python_api_refuses_bad_paths_with_parameter_error(small, tmp_path):
    from gyroshell import march

    result = march(small, 0.0, dt=2e-6, steps=3)
    with pytest.raises(ParameterError, match="is a folder"):
        result.to_csv(tmp_path)
    with pytest.raises(ParameterError, match="does not exist"):
        result.save_snapshots(tmp_path / "no" / "s.npz")
    with pytest.raises(OutputPathError, match="name the same file"):
        check_outputs({"a": (tmp_path / "x", None), "b": (tmp_path / "." / "x", None)})


# ----- signals: a real process, real signals ---------------------------------------------
SLOW_WRITE = textwrap.dedent("""
    import sys, time
    import pandas
    from gyroshell.cli import main

    original = pandas.DataFrame.to_csv

    def slow_to_csv(self, path, *args, **kwargs):
        original(self, path, *args, **kwargs)   # the temporary file is written...
        print("writing", flush=True)
        time.sleep(60)                          # ...and the signal arrives meanwhile

    pandas.DataFrame.to_csv = slow_to_csv
    sys.exit(main(sys.argv[1:]))
""")


@pytest.mark.slow
@pytest.mark.parametrize(("signum", "code", "message"), [
    (signal.SIGTERM, 143, "gyroshell: error: terminated by SIGTERM; no output written"),
    (signal.SIGHUP, 129, "gyroshell: error: terminated by SIGHUP; no output written"),
    (signal.SIGINT, 130, "gyroshell: error: interrupted; no output written"),
])
def test_signal_during_write_leaves_no_file(tmp_path, signum, code, message):
    old = tmp_path / "s.npz"
    old.write_bytes(b"an earlier run")
    argv = [str(a) for a in (*TRANSIENT, "--out", "h.csv", "--snapshot-every", "5",
                                "--snapshots", "s.npz")]
    proc = subprocess.Popen([sys.executable, "-c", SLOW_WRITE, *argv], cwd=tmp_path,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert proc.stdout.readline() == "writing\n"
        assert any(name.startswith(".h.csv.") for name in listing(tmp_path))  # mid-write
        proc.send_signal(signum)
        out, err = proc.communicate(timeout=60)
    finally:
        proc.kill()
    assert proc.returncode == code
    assert err.strip().splitlines() == [message]
    assert listing(tmp_path) == ["s.npz"] and old.read_bytes() == b"an earlier run"


#: A sweep that says when its first eigen-solve starts, i.e. once the CLI's signal handlers
#: are in place (a fixed sleep raced with a cold start: imports can take longer than it).
ANNOUNCED_SWEEP = textwrap.dedent("""
    import importlib
    import sys
    from gyroshell.cli import main

    sweep = importlib.import_module("gyroshell.studies.sweep")   # the module, not the function

    original, started = sweep.modes, []

    def announced(*args, **kwargs):
        if not started:
            started.append(True)
            print("computing", flush=True)
        return original(*args, **kwargs)

    sweep.modes = announced
    sys.exit(main(sys.argv[1:]))
""")


@pytest.mark.slow
def test_sigterm_during_computation_exits_cleanly(tmp_path):
    argv = ["sweep", *map(str, COARSE), "--velocities", "0:100:5001", "--out", "s.csv",
            "--quiet"]
    proc = subprocess.Popen([sys.executable, "-c", ANNOUNCED_SWEEP, *argv], cwd=tmp_path,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert proc.stdout.readline() == "computing\n"
        proc.send_signal(signal.SIGTERM)
        _, err = proc.communicate(timeout=60)
    finally:
        proc.kill()
    assert proc.returncode == 143, err
    assert err.strip().splitlines() == ["gyroshell: error: terminated by SIGTERM; "
                                        "no output written"]
    assert listing(tmp_path) == []


@pytest.mark.slow
def test_plot_formats_are_ones_matplotlib_writes(tmp_path):
    import matplotlib.pyplot as plt
    from matplotlib.backend_bases import FigureCanvasBase

    from gyroshell.core.files import PLOT_FORMATS

    assert set(PLOT_FORMATS) <= set(FigureCanvasBase.get_supported_filetypes())
    fig = plt.figure()
    for fmt in ("png", "pdf", "svg"):
        write_atomic(tmp_path / f"f.{fmt}", lambda p, fmt=fmt: fig.savefig(p, format=fmt),
                     kind="plot")
    assert listing(tmp_path) == ["f.pdf", "f.png", "f.svg"]


@pytest.mark.slow
def test_reproduce_run_whose_last_study_fails_leaves_none_of_its_files(cli, tmp_path,
                                                                        monkeypatch):
    import gyroshell.reproduce.fig3 as fig3

    def disk_full(out, settings):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(fig3, "run", disk_full)
    out = tmp_path / "today"  # its parent must exist (as for bearing --out-dir)
    run = cli(["reproduce", "critical", "fig3", "--quick", "--quiet", "--workers", "1",
               "--out-dir", out])
    assert run.code == 2 and "No space left on device" in run.err
    assert len(run.error_lines) == 1
    assert listing(tmp_path) == []  # critical's files and the folder made for them are gone


@pytest.mark.parametrize("command", [["static"], ["modes", "--count", "2"]])
def test_save_into_a_read_only_file_is_refused(cli, tmp_path, command):
    saved = tmp_path / "r.nc"
    saved.write_bytes(b"an earlier result")
    saved.chmod(0o444)
    run = cli([*command, *COARSE, "--save", saved])
    assert run.code == 2 and f"--save {saved}: exists and is read-only" in run.err
    assert saved.read_bytes() == b"an earlier result"
