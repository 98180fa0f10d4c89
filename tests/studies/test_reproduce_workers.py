"""`gyroshell reproduce` on several local workers writes what one process writes.

The studies' parts run on worker processes (one BLAS thread each, as the single process
holds itself to) and their files are moved in through the run's transaction, so the files
must be the same byte for byte, whatever the number of workers; a run that fails leaves no
file and no staging folder behind.
"""

from __future__ import annotations

import pytest

from gyroshell.cli import main
from gyroshell.reproduce import STUDIES, Settings, run_studies
from gyroshell.reproduce._runner import study_module

#: Cheap quick-settings studies: one with parts (fig2, one part per speed), one without.
STUDY_SET = ("fig2", "fig6")


def listing(folder):
    return sorted(p.name for p in folder.iterdir())


@pytest.mark.slow  # two worker pools and a serial run: 8-17 s
def test_two_workers_write_the_same_files_as_one(tmp_path):
    one, two = tmp_path / "one", tmp_path / "two"
    assert main(["reproduce", *STUDY_SET, "--quick", "--quiet", "--workers", "1",
                 "--out-dir", str(one)]) == 0
    lines = []
    written = run_studies(STUDY_SET, two, Settings(quick=True, progress=False), workers=2,
                          log=lines.append)
    assert listing(one) == listing(two)  # no hidden staging folder left either
    assert len(listing(one)) == 5
    for name in listing(one):
        assert (one / name).read_bytes() == (two / name).read_bytes(), name
    # each study logged once; the files returned per study, in the order asked for
    assert sorted(line.split(":")[0] for line in lines) == sorted(STUDY_SET)
    assert list(written) == list(STUDY_SET)
    assert [p.name for p in written["fig6"]] == ["fig6_centerline.csv", "fig6_waterfall.png"]
    assert all(p.parent == two for ps in written.values() for p in ps)


def test_parallel_run_that_fails_leaves_none_of_its_files(tmp_path, capsys):
    out = tmp_path / "out"
    out.mkdir()
    blocked = out / "fig6_waterfall.png"
    blocked.write_bytes(b"an earlier figure")
    blocked.chmod(0o444)
    assert main(["reproduce", "fig5", "fig6", "--quick", "--quiet", "--workers", "2",
                 "--out-dir", str(out)]) == 2
    err = capsys.readouterr().err
    assert "fig6_waterfall.png" in err and "read-only" in err
    assert listing(out) == ["fig6_waterfall.png"]  # fig5's files gone, no staging folder
    assert blocked.read_bytes() == b"an earlier figure"


def test_every_part_key_is_listed_once():
    for name in STUDIES:
        module = study_module(name)
        if hasattr(module, "parts"):
            keys = list(module.parts(Settings()))
            assert len(set(keys)) == len(keys) > 1, name
