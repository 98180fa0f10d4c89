"""A study's cache key holds the content of every input file (issue 32): a measured head's
profile or a tape file edited in place computes its points again, so that the rows are those
of the files as they are now, never the old head's."""

from __future__ import annotations

import json
import math

import pytest

from gyroshell import ParameterError, TapeParameters, run_study
from gyroshell.bearing.head_config import HeadDesign
from gyroshell.studies.head_study import BearingStudy

WRAP = math.radians(2.0)
TENSIONS = [80.0, 90.0]


def _profile(path, land: float) -> None:
    """A measured flat land of half-length ``land`` (m) with flanks falling at 0.35."""
    path.write_text("x_m,z_m\n" + "".join(
        f"{x * 1e-4:.6e},{-max(abs(x * 1e-4) - land, 0.0) * 0.35:.6e}\n"
        for x in range(-30, 31)))


def _study(profile, cache):
    setup = BearingStudy(head=HeadDesign(kind="profile", profile=str(profile), wrap_in=WRAP,
                                         wrap_out=WRAP), infinitely_wide=True, nx=160)
    return run_study(TapeParameters(), vary={"tension": TENSIONS}, compute="bearing",
                     velocity=4.0, workers=1, bearing=setup, progress=False, cache=cache)


def test_a_profile_edited_in_place_computes_its_points_again(tmp_path):
    profile, cache = tmp_path / "p.csv", tmp_path / "c.jsonl"
    _profile(profile, 5e-4)
    first = _study(profile, cache)
    assert first.failed.empty and _study(profile, cache).info["cached"] == 2
    _profile(profile, 8e-4)                            # a longer land, the same path
    edited = _study(profile, cache)
    assert edited.info["computed"] == 2
    fresh = _study(profile, None)                      # the edited head, no cache
    assert edited.table["central_spacing"].tolist() == fresh.table["central_spacing"].tolist()
    assert edited.table["central_spacing"].tolist() != first.table["central_spacing"].tolist()


def test_input_files_are_keyed_by_content_and_checked(tmp_path):
    cfg, cache = tmp_path / "tape.toml", tmp_path / "c.jsonl"
    cfg.write_text('[tape]\ntension = "90 N/m"\n')
    study = {"vary": {"velocity": [10.0]}, "compute": "critical", "workers": 1,
             "progress": False, "cache": cache,
             "base": TapeParameters(length_ratio=2, spacing=6.35e-3 / 8)}
    assert run_study(**study, inputs=[cfg]).info["computed"] == 1
    assert run_study(**study, inputs=[cfg]).info["cached"] == 1
    cfg.write_text('[tape]\ntension = "90 N/m"   # edited\n')
    assert run_study(**study, inputs=[cfg]).info["computed"] == 1
    with pytest.raises(ParameterError, match="inputs must be a sequence of paths"):
        run_study(**study, inputs=cfg)
    with pytest.raises(ParameterError, match=f"inputs: {tmp_path} is not a file"):
        run_study(**study, inputs=[tmp_path])


def test_the_command_line_keys_the_head_file_and_the_tape_file(cli, tmp_path, monkeypatch):
    """``--head p.csv --cache c.jsonl`` (the issue's case) and ``--config``."""
    monkeypatch.chdir(tmp_path)
    _profile(tmp_path / "p.csv", 5e-4)
    (tmp_path / "tape.toml").write_text('[tape]\nvelocity = "4 m/s"\n')
    argv = ["study", "--config", "tape.toml", "--head", "p.csv", "--wrap-in", "2",
            "--wrap-out", "2", "--infinitely-wide", "--nx", "160", "--vary",
            "tension=80,90", "--compute", "bearing", "--workers", "1", "--quiet",
            "--cache", "c.jsonl", "--json"]

    def computed() -> int:
        run = cli(argv)
        assert run.code == 0, run.err
        summary = json.loads(run.out)
        assert summary["failed"] == 0
        return summary["computed"]

    assert computed() == 2 and computed() == 0
    _profile(tmp_path / "p.csv", 8e-4)
    assert computed() == 2 and computed() == 0
    (tmp_path / "tape.toml").write_text('# the same tape\n[tape]\nvelocity = "4 m/s"\n')
    assert computed() == 2
