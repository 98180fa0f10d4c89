"""Long work (core/progress.LongWork): a measured estimate, refused beyond the time limit,
and one line per stage when stderr is not a terminal."""

from __future__ import annotations

import pytest

from gyroshell.core.errors import ParameterError
from gyroshell.core.progress import LONG_WORK_SECONDS, LongWork, duration, time_limit


def work(total: int, progress=None) -> LongWork:
    return LongWork(total, "demo", progress=progress, unit="step", size=f"{total} steps",
                    advice="use fewer steps")


def test_long_work_off_a_terminal_writes_a_start_line_three_stages_and_an_end(capsys):
    with work(100) as w:
        w.assess(1.0, "8 trial steps")  # as measured: 1 s per step, 100 s in all
        for _ in range(100):
            w.update()
    lines = capsys.readouterr().err.strip().splitlines()
    assert lines[0] == ("gyroshell: demo: 100 steps: about 100 s (an estimate from 1 s per "
                        "step measured on 8 trial steps)")
    assert [line.split(": ")[2].split(" in ")[0] for line in lines[1:4]] == [
        "25/100 steps done (25 %)", "50/100 steps done (50 %)", "75/100 steps done (75 %)"]
    assert lines[1].endswith(" left")
    assert lines[4].startswith("gyroshell: demo: 100/100 steps done in ") and len(lines) == 5


def test_short_work_and_quiet_work_write_nothing(capsys):
    with work(100) as w:
        w.assess(LONG_WORK_SECONDS / 1000, "8 trial steps")
        for _ in range(100):
            w.update()
    with work(100, progress=False) as w:
        w.assess(1.0, "8 trial steps")
        for _ in range(100):
            w.update()
    assert capsys.readouterr().err == ""


def test_work_beyond_the_time_limit_is_refused_with_its_estimate(monkeypatch, capsys):
    monkeypatch.setenv("GYROSHELL_TIME_LIMIT", "50")
    with pytest.raises(ParameterError) as info, work(100) as w:
        w.assess(1.0, "8 trial steps")
    assert str(info.value) == (
        "100 steps would take about 100 s (an estimate from 1 s per step measured on 8 trial "
        "steps), more than the limit 50 s; use fewer steps (or set GYROSHELL_TIME_LIMIT, "
        "seconds)")
    assert capsys.readouterr().err == ""


def test_without_a_trial_the_first_steps_are_measured(monkeypatch):
    monkeypatch.setenv("GYROSHELL_TIME_LIMIT", "1e-9")
    with pytest.raises(ParameterError, match="measured on the first 16 steps"), \
            work(1000, progress=False) as w:
        for _ in range(1000):
            w.update()
    assert w.done == 16


@pytest.mark.parametrize("text", ["soon", "-1", "0", "nan", "inf"])
def test_time_limit_must_be_seconds(monkeypatch, text):
    monkeypatch.setenv("GYROSHELL_TIME_LIMIT", text)
    with pytest.raises(ParameterError, match="GYROSHELL_TIME_LIMIT must be a number of "
                                             "seconds > 0"):
        time_limit()


def test_durations_read_naturally():
    assert [duration(s) for s in (0.5, 59, 90, 7200, 3 * 86400)] == [
        "0.5 s", "59 s", "90 s", "2 h", "3 days"]
