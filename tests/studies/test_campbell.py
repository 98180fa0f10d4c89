"""Campbell diagrams: MAC tracking, crossings, veerings and excitation lines on known cases."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from conftest import WidthUniformModel

from gyroshell import Grid, TapeModel, TapeParameters
from gyroshell.core.errors import ParameterError
from gyroshell.studies.campbell import _crossings_and_veerings, campbell, mac

WIDTH = 6.35e-3


def test_mac_is_one_for_the_same_shape_and_zero_for_orthogonal(rng):
    a = rng.standard_normal(20) + 1j * rng.standard_normal(20)
    b = rng.standard_normal(20).astype(complex)
    b -= (a.conj() @ b) / (a.conj() @ a) * a  # orthogonal to a
    m = mac(np.column_stack([a, b]), np.column_stack([(2 - 3j) * a, b]))
    assert m[0, 0] == pytest.approx(1.0, abs=1e-14)   # invariant to complex scaling
    assert m[1, 1] == pytest.approx(1.0, abs=1e-14)
    assert m[0, 1] == pytest.approx(0.0, abs=1e-14) and m[1, 0] == pytest.approx(0.0, abs=1e-14)


def y_index(model: TapeModel, phi: np.ndarray) -> int:
    """The across-width sine sin(nπy/L_y) that φ is made of (simply supported edges)."""
    g = model.grid
    field = g.to_field(phi)[:, 1:-1]
    j = np.arange(1, g.ny)
    energy = [np.linalg.norm(field @ np.sin(n * np.pi * j / g.ny)) for n in range(1, g.ny)]
    return int(np.argmax(energy)) + 1


@pytest.mark.slow
def test_branches_keep_their_shape_and_cross_only_other_shapes():
    # All-sides simply supported: the across-width sine index n is exact for every V
    # (G acts along x only), so modes of different n are orthogonal and may cross.
    p = TapeParameters(length_ratio=1.5, spacing=WIDTH / 10, edges="simply-supported",
                       foundation_stiffness=0.0)
    model = TapeModel(p)
    speeds = np.linspace(0.0, 75.0, 16)
    d = campbell(model, speeds, 5, critical_speed=False)
    assert d.frame["branch"].nunique() == 5  # every branch tracked across all speeds
    from gyroshell import modes

    index = {}
    for v in speeds[::5]:
        res = modes(model, v, 5)
        rows = d.frame[d.frame["velocity"] == v].sort_values("rank")
        for branch, j in zip(rows["branch"], rows["rank"], strict=True):
            index.setdefault(branch, set()).add(y_index(model, res.vectors[:, j]))
    assert all(len(s) == 1 for s in index.values()), index  # one shape per branch
    continued = d.frame["mac"].dropna()
    assert len(continued) == 5 * 15 and continued.min() > 0.9
    assert len(d.crossings) >= 1
    for row in d.crossings.itertuples():
        assert index[row.branch_a] != index[row.branch_b]
        # at the crossing both interpolated branches have the same ω
        for b in (row.branch_a, row.branch_b):
            g = d.frame[d.frame["branch"] == b]
            assert np.interp(row.velocity, g["velocity"], g["omega"]) == pytest.approx(
                row.omega, rel=2e-3)
    assert d.critical_speed is None


@pytest.mark.slow
def test_string_branches_and_resonances_match_closed_forms():
    p = TapeParameters(foundation_stiffness=0.0, bending_rigidity=1e-14, poisson=0.0,
                       length_ratio=2.0, spacing=WIDTH / 8)
    model = WidthUniformModel(TapeModel(p, Grid(p.length, p.width, 200, 8, "free")))
    c, L = p.string_speed, p.length
    speeds = np.linspace(0.0, 0.9 * c, 91)
    d = campbell(model, speeds, 3, critical_speed=c)
    assert d.frame["branch"].nunique() == 3 and d.crossings.empty and d.veerings.empty
    for n in (1, 2, 3):  # Wickert & Mote: ω_n = nπc(1 − V²/c²)/L
        g = d.frame[d.frame["branch"] == n - 1]
        exact = n * np.pi * c * (1 - g["velocity"] ** 2 / c**2) / L
        assert np.max(np.abs(g["omega"] - exact) / exact) < 1e-3
    # a roller of circumference ℓ excites ω = k 2πV/ℓ; the string meets it where
    # nπc(1 − V²/c²)/L = 2πkV/ℓ, a quadratic in V
    ell = 2.0 * L
    res = d.resonances(ell, orders=(1, 2))
    for row in res.itertuples():
        n, k = row.branch + 1, row.order
        a, b, cc = n * np.pi / (c * L), 2 * np.pi * k / ell, -n * np.pi * c / L
        exact = (-b + np.sqrt(b * b - 4 * a * cc)) / (2 * a)
        assert row.velocity == pytest.approx(exact, rel=2e-3)
    assert len(res) == 6  # every branch meets both lines below 0.9 c


def test_veering_detector_on_a_closed_form_pair():
    # eigenvalues of [[1 + s, e], [e, 2 - s]]: the curves approach to 2e at s = 0.5
    e = 0.005
    s = np.linspace(0.0, 1.0, 21)
    mean, half = 1.5, np.sqrt((0.5 - s) ** 2 + e**2)  # (1+s) and (2-s) are 1 - 2s apart
    lo, hi = mean - half, mean + half
    frame = pd.DataFrame({"velocity": np.concatenate([s, s]), "branch": [0] * 21 + [1] * 21,
                          "omega": np.concatenate([lo, hi])})
    crossings, veerings = _crossings_and_veerings(frame, 0.02)
    assert crossings.empty and len(veerings) == 1
    assert veerings["velocity"].iloc[0] == pytest.approx(0.5)
    assert veerings["gap"].iloc[0] == pytest.approx(2 * e / mean)
    # the same lines without the coupling cross instead
    frame["omega"] = np.concatenate([1 + s, 2 - s])
    crossings, veerings = _crossings_and_veerings(frame, 0.02)
    assert veerings.empty and crossings["velocity"].iloc[0] == pytest.approx(0.5)


def test_refusals():
    model = TapeModel(TapeParameters(length_ratio=2, spacing=WIDTH / 8))
    with pytest.raises(ParameterError, match="ascending"):
        campbell(model, [10.0, 5.0], 2, critical_speed=False)
    with pytest.raises(ParameterError, match="min_mac"):
        campbell(model, [0.0, 5.0], 2, min_mac=2.0)
    from gyroshell.studies.campbell import CampbellDiagram

    with pytest.raises(ParameterError, match="circumference"):
        CampbellDiagram.excitation(1, -1.0, 3.0)


@pytest.mark.slow
def test_continued_and_two_process_diagrams_equal_the_independent_one():
    """Campbell shares the sweep's continuation and workers: the same branches, crossings
    and MAC, and the frequencies to the sweep tests' tolerance."""
    model = TapeModel(TapeParameters(length_ratio=4.0, spacing=WIDTH / 8))
    speeds = np.linspace(0.0, 95.0, 8)
    fresh = campbell(model, speeds, 4, critical_speed=False)
    for kwargs in ({"continuation": True}, {"workers": 2}, {"continuation": True,
                                                            "workers": 2}):
        other = campbell(TapeModel(model.params), speeds, 4, critical_speed=False, **kwargs)
        assert np.allclose(other.frame["omega"], fresh.frame["omega"], rtol=1e-10, atol=0)
        for column in ("velocity", "branch", "rank"):
            assert (other.frame[column] == fresh.frame[column]).all(), (kwargs, column)
        assert np.allclose(other.frame["mac"], fresh.frame["mac"], rtol=1e-8,
                           equal_nan=True)
        assert len(other.crossings) == len(fresh.crossings)
        assert len(other.veerings) == len(fresh.veerings)
        assert other.info["workers"] == kwargs.get("workers", 1)
    with pytest.raises(ParameterError, match=r"workers must be an integer in \[1, "):
        campbell(model, speeds, 2, critical_speed=False, workers=0)
