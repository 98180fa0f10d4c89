"""``gyroshell campbell`` reports how well its branches are tracked: the MAC of the matches
(min, median) in the text, the JSON and the saved file, and one warning line where branches
are still broken at the smallest step."""

from __future__ import annotations

import json

import pytest

from gyroshell.results.base import read

#: The defaults on a coarser grid: at steps of 10 m/s no mode keeps a MAC of 0.5.
SMALL = ["--spacing", str(6.35e-3 / 12), "--velocities", "0:90:10", "--count", "4"]


@pytest.mark.slow
def test_a_floor_at_the_given_step_leaves_branches_broken_with_one_warning_line(cli, tmp_path):
    nc = tmp_path / "c.nc"
    run = cli(["campbell", *SMALL, "--min-step", "10", "--quiet", "--save", nc])
    assert run.code == 0, run.err
    warnings = [line for line in run.err.splitlines() if line.strip()]
    assert len(warnings) == 1 and warnings[0].startswith(
        "gyroshell: warning: branches left unlinked between V = 0-10, 10-20")
    assert "--min-step" in warnings[0]
    first = run.out.splitlines()[0]
    assert first.startswith("40 branches over 10 speeds; MAC of the matches: min ")
    saved = read(nc)
    assert saved.info["mac_min"] == saved.mac_min < 0.5
    assert len(saved.info["unlinked"]) == 9


@pytest.mark.slow
def test_the_default_step_is_halved_where_the_mac_fell_and_json_says_so(cli, tmp_path):
    nc = tmp_path / "c.nc"
    run = cli(["campbell", *SMALL, "--quiet", "--json", "--save", nc])
    assert run.code == 0 and run.err == ""
    out = json.loads(run.out)
    assert out["branches"] <= 8 and out["unlinked"] == [] and out["inserted"] > 0
    assert 0.5 <= out["mac_min"] <= out["mac_median"] <= 1.0
    saved = read(nc)
    assert saved.summary() == out
    text = cli(["campbell", *SMALL, "--quiet"]).out.splitlines()[0]
    assert f"({out['inserted']} inserted where the MAC fell)" in text
    assert f"min {out['mac_min']:.3f}, median {out['mac_median']:.3f}" in text


def test_min_step_must_be_positive(cli):
    run = cli(["campbell", *SMALL, "--min-step", "-1"])
    assert run.code == 2 and run.err.count("\n") == 1
    assert "--min-step must be > 0 m/s" in run.err
