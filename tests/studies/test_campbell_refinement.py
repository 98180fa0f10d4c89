"""Campbell diagrams that track: the speed step is halved where the MAC of neighbouring
speeds falls, and what still breaks at the floor is named in one warning.

The free-edged tape of the defaults has clustered frequencies whose complex gyroscopic
shapes turn fast with the speed: at steps of 10 m/s no mode's MAC with itself reaches 0.5.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from scipy.optimize import linear_sum_assignment

from gyroshell import TapeModel, TapeParameters, modes
from gyroshell.studies.campbell import MIN_MAC, CampbellTrackingWarning, campbell

SPEEDS = np.arange(0.0, 91.0, 10.0)  # 0:90:10, m/s
COUNT = 4
#: The defaults on a coarser grid (611 unknowns): the same clustered, crossing modes.
SMALL = TapeParameters(spacing=6.35e-3 / 12)


def diagram(params, **options):
    with warnings.catch_warnings():
        warnings.simplefilter("error", CampbellTrackingWarning)  # none may be raised
        return campbell(TapeModel(params), SPEEDS, COUNT, critical_speed=False,
                        progress=False, **options)


def shape_mac(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """|aᴴb|² / (aᴴa bᴴb) between the columns, written here from its definition."""
    cross = np.abs(np.einsum("ip,iq->pq", a.conj(), b)) ** 2
    return cross / np.outer(np.linalg.norm(a, axis=0) ** 2, np.linalg.norm(b, axis=0) ** 2)


@pytest.mark.slow
def test_the_default_tape_at_0_90_10_with_4_modes_gives_at_most_8_branches():
    d = diagram(TapeParameters())
    summary = d.summary()
    assert summary["branches"] <= 8, summary
    assert summary["unlinked"] == [] and d.info["unlinked"] == []
    assert MIN_MAC <= d.mac_min <= d.mac_median <= 1.0
    assert summary["mac_min"] == d.mac_min and summary["mac_median"] == d.mac_median
    assert summary["inserted"] == summary["speeds"] - len(SPEEDS) > 0
    # every given speed is kept, each with the lowest COUNT modes
    assert set(SPEEDS) <= set(d.frame["velocity"])
    assert (d.frame.groupby("velocity")["rank"].count() == COUNT).all()


@pytest.mark.slow
def test_speeds_are_inserted_only_in_the_steps_where_the_mac_fell():
    given = np.arange(0.0, 91.0, 5.0)  # at 5 m/s the slow steps link, the fast do not
    d = campbell(TapeModel(SMALL), given, COUNT, critical_speed=False, progress=False)
    assert d.info["unlinked"] == []
    model = TapeModel(SMALL)
    ends = {v: modes(model, v, COUNT + 1).vectors for v in given}
    inserted = np.setdiff1d(d.frame["velocity"].unique(), given)
    assert len(inserted) == d.info["inserted"]
    fell = []
    for a, b in zip(given[:-1], given[1:], strict=True):
        c = shape_mac(ends[a], ends[b])
        rows, cols = linear_sum_assignment(c, maximize=True)
        low = [c[i, j] for i, j in zip(rows, cols, strict=True) if min(i, j) < COUNT]
        fell.append(min(low) < MIN_MAC)
        inside = inserted[(inserted > a) & (inserted < b)]
        assert (len(inside) > 0) == fell[-1], (a, b, min(low))
        if len(inside):  # halvings of the step: (a + b)/2, then quarters, ...
            level = np.log2((b - a) / np.diff(np.concatenate([[a], inside, [b]])))
            assert np.allclose(level, np.round(level)) and (level >= 1).all()
    assert any(fell) and not all(fell)  # a case where the rule decides both ways


def follow(grid, omega, order, seed):
    """Frequencies followed over ``grid[order]`` from the ``seed`` {index: ω} (two points),
    each the one nearest the quadratic in V² through the last three: frequency alone."""
    path, done = dict(seed), list(seed)
    for k in order:
        if k not in path:
            last = done[-3:]
            fit = np.polyfit(grid[last] ** 2, [path[i] for i in last], len(last) - 1)
            path[k] = omega[k][np.argmin(np.abs(omega[k] - np.polyval(fit, grid[k] ** 2)))]
            done.append(k)
    return path


@pytest.mark.slow
def test_frequencies_along_each_branch_follow_a_fine_uniform_sweep():
    """An independent fine sweep (every 0.625 m/s and at the diagram's speeds), followed by
    frequency alone from each branch's first two points up and from its last two down:
    both land on the branch's frequency at every one of its speeds, through crossings."""
    d = diagram(SMALL)
    model = TapeModel(SMALL)
    grid = np.union1d(np.arange(0.0, 90.001, 0.625), d.frame["velocity"].unique())
    omega = [modes(model, v, COUNT + 2).omega for v in grid]
    rank_changes = 0
    for _, g in d.frame.groupby("branch"):
        g = g.sort_values("velocity")
        ks = [int(np.flatnonzero(grid == v)[0]) for v in g["velocity"]]
        w = g["omega"].to_numpy()
        span = range(ks[0], ks[-1] + 1)
        up = follow(grid, omega, span, dict(zip(ks[:2], w[:2], strict=True)))
        down = follow(grid, omega, span[::-1], dict(zip(ks[-2:][::-1], w[-2:][::-1],
                                                        strict=True)))
        for path in (up, down):
            assert np.allclose([path[k] for k in ks], w, rtol=1e-8, atol=0)
        rank_changes += int(np.count_nonzero(np.diff(g["rank"])))
    assert rank_changes >= 2 and len(d.crossings) >= 2  # the branches do cross


@pytest.mark.slow
def test_one_warning_names_the_steps_still_broken_at_the_floor():
    # a floor of the given step itself: no halving, every step of the default tape breaks
    with pytest.warns(CampbellTrackingWarning) as caught:
        d = campbell(TapeModel(SMALL), SPEEDS, COUNT, critical_speed=False, progress=False,
                     min_step=10.0)
    assert len(caught) == 1
    text = str(caught[0].message)
    assert "\n" not in text and "V = 0-10, 10-20" in text and "--min-step" in text
    assert d.info["inserted"] == 0 and len(d.info["unlinked"]) == len(SPEEDS) - 1
    assert d.mac_min < MIN_MAC and d.summary()["branches"] > 8


@pytest.mark.slow
def test_a_min_mac_that_a_crossing_never_reaches_warns_once_where_modes_meet():
    # through a crossing the MAC of the pair stays below 0.9 down to the floor: the
    # warning names that step alone, where two frequencies all but coincide
    with pytest.warns(CampbellTrackingWarning) as caught:
        d = campbell(TapeModel(SMALL), SPEEDS, COUNT, critical_speed=False, progress=False,
                     min_mac=0.9, min_step=0.625)
    assert len(caught) == 1
    steps = d.info["unlinked"]
    assert steps and all(b - a < 2 * 0.625 for a, b in steps)
    assert all(f"{a:.4g}-{b:.4g}" in str(caught[0].message) for a, b in steps[:5])
    model = TapeModel(SMALL)
    for a, b in steps:
        omega = [modes(model, v, COUNT + 1).omega for v in (a, b)]
        gaps = [np.min(np.diff(w) / w[1:]) for w in omega]  # relative
        assert min(gaps) < 2e-4, (a, b, gaps)
    assert d.mac_min < 0.9 <= d.mac_median


def test_min_step_is_refused_unless_positive():
    from gyroshell.core.errors import ParameterError

    with pytest.raises(ParameterError, match="min_step must be > 0"):
        campbell(TapeModel(SMALL), [0.0, 10.0], 1, critical_speed=False, progress=False,
                 min_step=0.0)


def test_the_time_limit_covers_the_speeds_refinement_inserts(monkeypatch):
    from gyroshell.core.errors import ParameterError
    from gyroshell.core.progress import TIME_LIMIT_VARIABLE

    # two given speeds (the sweep's own check needs a third), 90 m/s apart: the MAC falls,
    # and the halving is refused on the time per speed measured so far
    monkeypatch.setenv(TIME_LIMIT_VARIABLE, "1e-6")
    with pytest.raises(ParameterError, match=r"a Campbell diagram of 3 speeds \(1 inserted "
                                             r"where the MAC fell\) would take about .* "
                                             r"raise min_step \(--min-step\)"):
        campbell(TapeModel(SMALL), [0.0, 90.0], COUNT, critical_speed=False, progress=False)
