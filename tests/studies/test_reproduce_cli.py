"""`gyroshell reproduce`: a study named twice runs once; --out's parent must exist (as for
`bearing --out`), the folder itself is created."""

from __future__ import annotations

import pytest

import gyroshell.reproduce as reproduce
from gyroshell import ParameterError
from gyroshell.reproduce import Settings, run_studies


@pytest.fixture
def ran(monkeypatch):
    """The studies run_studies would run, in order (none computed): [(name, folder)]."""
    calls: list = []

    def run_here(name, out, settings):
        calls.append((name, out))
        return []

    def run_parallel(names, out, settings, workers, log=None):
        calls.extend((name, out) for name in names)
        return {name: [] for name in names}

    monkeypatch.setattr(reproduce, "run_here", run_here)
    monkeypatch.setattr(reproduce, "run_parallel", run_parallel)
    return calls


@pytest.mark.parametrize("workers", [1, 2])
def test_a_study_named_twice_runs_once_in_the_order_first_named(tmp_path, ran, workers):
    written = run_studies(["fig2", "critical", "fig2", "critical", "fig6"], tmp_path,
                          Settings(quick=True, progress=False), log=None, workers=workers)
    assert [name for name, _out in ran] == ["fig2", "critical", "fig6"]
    assert list(written) == ["fig2", "critical", "fig6"]


def test_the_cli_runs_a_repeated_study_once(cli, tmp_path, ran):
    run = cli(["reproduce", "fig2", "fig2", "--quick", "--quiet", "--workers", "1",
               "--out-dir", tmp_path / "r2"])
    assert run.code == 0, run.err
    assert [name for name, _out in ran] == ["fig2"]


def test_out_with_a_missing_parent_is_refused_like_bearing_out(cli, tmp_path, ran):
    deep = tmp_path / "missing" / "deep" / "x"
    run = cli(["reproduce", "fig2", "--quick", "--quiet", "--out-dir", deep])
    assert run.code == 2
    assert run.err.count("\n") == 1, run.err
    assert "--out-dir" in run.err and "does not exist" in run.err
    assert ran == [] and list(tmp_path.iterdir()) == []
    bearing = cli(["bearing", "--velocity", "4", "--infinitely-wide", "--quiet", "--out-dir", deep])
    assert bearing.code == 2 and bearing.err.split(": ", 2)[2] == run.err.split(": ", 2)[2]


def test_out_itself_is_created_when_its_parent_exists(cli, tmp_path, ran):
    run = cli(["reproduce", "fig2", "--quick", "--quiet", "--workers", "1",
               "--out-dir", tmp_path / "new"])
    assert run.code == 0, run.err
    assert (tmp_path / "new").is_dir() and ran == [("fig2", tmp_path / "new")]


@pytest.mark.parametrize("workers", ["1", "2"])
@pytest.mark.parametrize("blocker", ["folder", "read-only file"])
def test_out_that_cannot_take_a_study_file_is_refused_before_any_work(cli, tmp_path, ran,
                                                                        workers, blocker):
    out = tmp_path / "r"
    out.mkdir()
    blocked = out / "heads_wraps.png"   # the last file of the last study of 'all'
    if blocker == "folder":
        blocked.mkdir()
    else:
        blocked.write_bytes(b"an earlier figure")
        blocked.chmod(0o444)
    run = cli(["reproduce", "all", "--quick", "--quiet", "--workers", workers, "--out-dir", out])
    assert run.code == 2 and len(run.error_lines) == 1, run.err
    assert run.error_lines[0].startswith(f"gyroshell: error: --out-dir {blocked}: ")
    assert ran == []                    # no study started
    assert sorted(p.name for p in out.iterdir()) == ["heads_wraps.png"]


def test_run_studies_refuses_the_same_before_any_work(tmp_path, ran):
    (tmp_path / "fig6_waterfall.png").mkdir()
    with pytest.raises(ParameterError, match="fig6_waterfall.png: is a folder, not a file"):
        run_studies(["fig5", "fig6"], tmp_path, Settings(quick=True, progress=False),
                    log=None)
    assert ran == []


def test_every_study_lists_its_files():
    assert list(reproduce.FILES) == list(reproduce.STUDIES)
    assert reproduce.output_files(["fig6", "critical", "fig6"]) == (
        "fig6_centerline.csv", "fig6_waterfall.png", "critical_speeds.csv",
        "critical_speeds.md")
    every = reproduce.output_files(["all"])
    assert len(every) == len(set(every)) == sum(map(len, reproduce.FILES.values()))


def test_a_study_writing_other_files_than_it_lists_is_a_bug_not_a_silent_change(tmp_path):
    from gyroshell.reproduce._files import check_written

    assert check_written("fig5", [tmp_path / "fig5_centerline.csv",
                                  tmp_path / "fig5_waterfall.png"])
    with pytest.raises(RuntimeError, match="study fig5 wrote"):
        check_written("fig5", [tmp_path / "fig5_centerline.csv"])
