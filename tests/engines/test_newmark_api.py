"""Newmark's contract: validation, blow-up, recorders, the result and its files, back-ends."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp

from gyroshell import ConvergenceError, ParameterError, TapeModel, TapeParameters
from gyroshell.engines.newmark import Newmark, NewmarkStabilityWarning, march
from gyroshell.linalg.factorization import BACKENDS, available_backends, factorize, resolve_backend
from gyroshell.results.transient import Snapshots, TransientResult
from gyroshell.tape.loads import Harmonic

WIDTH = 6.35e-3


# ----- validation -------------------------------------------------------------------
class TestValidation:
    @pytest.mark.parametrize(("kwargs", "match"), [
        ({"dt": 0.0}, "dt must be > 0"),
        ({"dt": -1e-6}, "dt must be > 0"),
        ({"dt": float("nan")}, "dt must be finite s, got nan"),
        ({"steps": 0}, "steps must be an integer >= 1"),
        ({"steps": 2.5}, "steps must be an integer, got 2.5"),
        ({"beta": 0.0}, "beta must be > 0"),
        ({"gamma": float("inf")}, "gamma must be finite"),
        ({"backend": "magic"}, "backend must be one of auto, superlu"),
        # beta dt^2 underflows (the corrector divides by it) or overflows K_eq
        ({"dt": 1e-170}, "dt 1e-170 s is too small"),
        ({"dt": 1e160}, "dt 1e[+]160 s is too large"),
    ])
    def test_bad_arguments_raise_parameter_error(self, small, kwargs, match):
        args = {"dt": 1e-6, "steps": 3} | kwargs
        with pytest.raises(ParameterError, match=match):
            march(small, 10.0, **args)

    def test_negative_speed_is_refused(self, small):
        with pytest.raises(ParameterError, match="velocity must be >= 0"):
            march(small, -1.0, dt=1e-6, steps=1)

    @pytest.mark.parametrize(("beta", "gamma"), [(0.2, 0.5), (0.25, 0.4), (0.3, 0.7)])
    def test_outside_unconditional_stability_warns(self, small, beta, gamma):
        with pytest.warns(NewmarkStabilityWarning, match="2\\*beta >= gamma >= 1/2"):
            Newmark(small, 0.0, dt=1e-7, beta=beta, gamma=gamma)

    @pytest.mark.parametrize(("beta", "gamma"), [(0.25, 0.5), (1.0, 1.5), (0.3025, 0.6)])
    def test_inside_does_not_warn(self, small, beta, gamma, recwarn):
        Newmark(small, 0.0, dt=1e-6, beta=beta, gamma=gamma)
        assert not [w for w in recwarn if issubclass(w.category, NewmarkStabilityWarning)]

    def test_bad_initial_state_and_times(self, small):
        stepper = Newmark(small, 0.0, dt=1e-6)
        with pytest.raises(ParameterError, match="w0 must be a vector of length 135 m, got shape"):
            stepper.march(2, w0=np.zeros(3))
        with pytest.raises(ParameterError, match="v0 must be finite m/s: it has 135 NaN"):
            stepper.march(2, v0=np.full(small.unknowns, np.nan))
        with pytest.raises(ParameterError, match="snapshot_times must lie in"):
            stepper.march(2, snapshot_times=[5e-6])
        with pytest.raises(ParameterError, match="snapshot_every must be an integer >= 1"):
            stepper.march(2, snapshot_every=0)


# ----- blow-up --------------------------------------------------------------------------
def test_unstable_march_stops_with_a_clear_error(small):
    """β = 0.05, γ = 1/2 with ω_max Δt ≈ 6 > 2.2 is unstable: stop, do not return garbage."""
    with pytest.warns(NewmarkStabilityWarning):
        stepper = Newmark(small, 0.0, dt=2e-5, beta=0.05, gamma=0.5)
    with pytest.raises(ConvergenceError, match=r"blew up: the displacement .* at step \d+"):
        stepper.march(2000)


def test_supercritical_speed_blows_up_clearly():
    model = TapeModel(TapeParameters(length_ratio=2, spacing=WIDTH / 8))
    with pytest.raises(ConvergenceError, match="critical speed"):
        march(model, 400.0, dt=2e-6, steps=5000)


# ----- recorders and result ------------------------------------------------------------
def test_recorders_keep_only_what_is_asked(small):
    plain = march(small, 20.0, dt=2e-6, steps=50)
    assert plain.times.shape == plain.load_point.shape == (51,)
    assert plain.times[0] == 0.0 and plain.times[-1] == pytest.approx(1e-4)
    assert plain.load_point[0] == 0.0
    assert len(plain.snapshots) == 0 and plain.snapshots.centerlines.shape == (0, 17)
    assert plain.energy is None
    assert {"backend", "factor_time", "solve_time", "loop_time", "steps"} <= set(plain.info)

    rich = march(small, 20.0, dt=2e-6, steps=50, snapshot_every=20,
                 snapshot_times=[3.1e-5], centerline_times=[1e-4, 0.0])
    snaps = rich.snapshots
    np.testing.assert_allclose(snaps.times, [0.0, 3.2e-5, 4e-5, 8e-5])
    assert snaps.fields.shape == (4, 17, 9)
    np.testing.assert_allclose(snaps.centerline_times, [0.0, 1e-4])
    # ny = 8 is even: y = L_y/2 is grid column 4 exactly.
    last = small.grid.to_field(rich.w)
    np.testing.assert_allclose(snaps.centerlines[-1], last[:, 4], rtol=1e-14)
    np.testing.assert_array_equal(rich.load_point, plain.load_point)
    np.testing.assert_allclose(snaps.x, small.grid.x)


def test_centerline_interpolates_between_columns_on_an_odd_grid():
    model = TapeModel(TapeParameters(length_ratio=2, spacing=WIDTH / 9))
    result = march(model, 0.0, dt=2e-6, steps=5, centerline_times=[1e-5])
    field = model.grid.to_field(result.w)
    np.testing.assert_allclose(result.snapshots.centerlines[0],
                               0.5 * (field[:, 4] + field[:, 5]), rtol=1e-14)


def test_time_profiles_from_the_core(small):
    """A harmonic load starts from f(0) = 0: rest stays rest at t = 0, then moves."""
    result = march(small, 0.0, dt=1e-6, steps=20, profile=Harmonic(2e4))
    assert result.load_point[0] == 0.0 and np.abs(result.load_point[1:]).max() > 0.0


def test_frame_csv_and_npz_round_trip(small, tmp_path):
    result = march(small, 20.0, dt=2e-6, steps=30, snapshot_every=10,
                   centerline_times=[2e-5], record_energy=True)
    frame = result.to_frame()
    assert list(frame.columns) == ["t", "w", "energy"]
    csv = result.to_csv(tmp_path / "h.csv")
    back = TransientResult.read_csv(csv)
    assert list(back.columns) == ["t", "w"] and len(back) == 31
    np.testing.assert_array_equal(back["w"].to_numpy(), result.load_point)  # %.17g: exact
    path = result.save_snapshots(tmp_path / "s.npz")
    snaps = Snapshots.load(path)
    assert isinstance(snaps, Snapshots)
    for name in ("x", "y", "times", "fields", "centerline_times", "centerlines"):
        np.testing.assert_array_equal(getattr(snaps, name), getattr(result.snapshots, name))


def test_writing_is_whole_or_nothing(small, tmp_path):
    result = march(small, 0.0, dt=2e-6, steps=3)
    with pytest.raises(ParameterError, match="does not exist"):
        result.to_csv(tmp_path / "missing" / "h.csv")
    result.save_snapshots(tmp_path / "odd.name")  # no ".npz" appended behind our back
    assert sorted(p.name for p in tmp_path.iterdir()) == ["odd.name"]


# ----- factorization back-ends ---------------------------------------------------------
@pytest.mark.parametrize("backend", available_backends())
def test_every_installed_backend_solves_and_marches_alike(small, backend, rng):
    A = (sp.random(60, 60, density=0.1, random_state=3) + 4 * sp.eye(60)).tocsc()
    b = rng.standard_normal(60)
    x = factorize(A, backend).solve(b)
    assert np.abs(A @ x - b).max() < 1e-12
    ref = march(small, 30.0, dt=2e-6, steps=40, backend="superlu")
    got = march(small, 30.0, dt=2e-6, steps=40, backend=backend)
    assert got.info["backend"] == backend
    np.testing.assert_allclose(got.load_point, ref.load_point, rtol=1e-9,
                               atol=1e-12 * np.abs(ref.load_point).max())


def test_backend_table_and_auto():
    assert {"superlu", "banded"} <= set(available_backends()) <= set(BACKENDS)
    assert resolve_backend("auto") == "superlu"
    with pytest.raises(ParameterError, match="backend must be one of auto, superlu, umfpack"):
        resolve_backend("lu")
    with pytest.raises(ParameterError, match="must be square"):
        factorize(sp.eye(3, 4).tocsc())
