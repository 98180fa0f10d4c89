"""The Newmark marcher against independent answers: energy, exact solutions, statics, symmetry.

Every exact answer here is for the same semi-discrete system M a + G v + K w = H(t) F, so
the error measured is the time stepper's alone: the modal solution (dense generalized eigh
of K, M) at V = 0, the matrix exponential of the first-order system at V > 0, and the
static solver for the damped run's steady state.
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg as sl
from convergence import observed_order

from gyroshell import TapeModel, TapeParameters, solve_static
from gyroshell.engines.newmark import Newmark, march

WIDTH = 6.35e-3
SPEED = 50.0  # m/s, well below the critical speed


def static_energy_scale(model: TapeModel, velocity: float) -> float:
    """|E| at the static equilibrium, ½|Fᵀw_s|, J: the natural energy scale."""
    return 0.5 * abs(model.force @ solve_static(model, velocity).w)


# ----- energy --------------------------------------------------------------------------
@pytest.mark.slow
@pytest.mark.parametrize("start", ["rest", "moving"])
def test_trapezoidal_rule_conserves_energy_with_gyroscopic_forces(small, start, rng):
    """β = 1/4, γ = 1/2, constant load, V > 0: E = ½vᵀMv + ½wᵀKw − Fᵀw is constant."""
    w0 = v0 = None
    if start == "moving":  # a state that makes G v large from the first step
        w0 = 1e-8 * rng.standard_normal(small.unknowns)
        v0 = 1e-3 * rng.standard_normal(small.unknowns)
    result = march(small, SPEED, dt=2e-6, steps=5000, w0=w0, v0=v0, record_energy=True)
    energy = result.energy
    scale = max(static_energy_scale(small, SPEED), np.abs(energy).max())
    drift = np.abs(energy - energy[0]).max() / scale
    assert drift < 1e-10
    # The recorded energy agrees with one computed here from the final state.
    K, m, F = small.K(SPEED), small.mass_diagonal, small.force
    w, v = result.w, result.v
    final = 0.5 * v @ (m * v) + 0.5 * w @ (K @ w) - F @ w
    assert final == pytest.approx(energy[-1], rel=1e-12, abs=1e-12 * scale)


def test_damped_scheme_loses_energy(small):
    """β = 1, γ = 3/2 dissipates: the energy ends at its static minimum, −½Fᵀw_s."""
    result = march(small, SPEED, dt=1e-5, steps=200, beta=1.0, gamma=1.5, record_energy=True)
    assert result.energy[-1] == pytest.approx(-static_energy_scale(small, SPEED), rel=1e-9)


# ----- exact solutions of the semi-discrete system ---------------------------------------
def modal_load_point(model: TapeModel):
    """Exact load-point history at V = 0 from rest under H(t) F, by modes (dense eigh)."""
    lam, phi = sl.eigh(model.K(0.0).toarray(), np.diag(model.mass_diagonal))
    assert lam.min() > 0.0
    omega = np.sqrt(lam)
    coeff = (model.load_point_row @ phi) * (phi.T @ model.force) / lam

    def exact(t: np.ndarray) -> np.ndarray:
        return (1.0 - np.cos(np.outer(t, omega))) @ coeff

    return exact


def state_space_field(model: TapeModel, velocity: float):
    """Exact w(t) at V > 0 from rest under H(t) F: matrix exponential of z' = A z + b."""
    n = model.unknowns
    K, G = model.K(velocity).toarray(), model.G(velocity).toarray()
    minv = 1.0 / model.mass_diagonal[:, None]
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-minv * K, -minv * G]])
    w_static = np.linalg.solve(K, model.force)
    z0 = -np.concatenate([w_static, np.zeros(n)])  # z − z_static at t = 0

    def exact(t: float) -> np.ndarray:
        return w_static + (sl.expm(A * t) @ z0)[:n]

    return exact


def test_matches_modal_solution_at_rest_with_order_two(small):
    """V = 0: load-point history against the modal solution; Δt halved twice."""
    exact = modal_load_point(small)
    duration = 60e-6  # about one dominant period, 2π (ρ/k)^½ ≈ 50 µs
    dts, errors = [], []
    for dt in (1e-6, 5e-7, 2.5e-7):
        result = march(small, 0.0, dt=dt, steps=round(duration / dt))
        ref = exact(result.times)
        errors.append(np.abs(result.load_point - ref).max() / np.abs(ref).max())
        dts.append(dt)
    assert errors[-1] < 1e-3
    assert observed_order(dts, errors) == pytest.approx(2.0, abs=0.1)


def test_matches_state_space_solution_when_moving_with_order_two(small):
    """V > 0 (G ≠ 0): the whole field at t = 40 µs against expm; Δt halved twice."""
    duration = 40e-6
    w_exact = state_space_field(small, SPEED)(duration)
    dts, errors = [], []
    for dt in (1e-6, 5e-7, 2.5e-7):
        result = march(small, SPEED, dt=dt, steps=round(duration / dt))
        errors.append(np.abs(result.w - w_exact).max() / np.abs(w_exact).max())
        dts.append(dt)
    assert errors[-1] < 1e-3
    assert observed_order(dts, errors) == pytest.approx(2.0, abs=0.1)


# ----- the damped steady state ------------------------------------------------------------
@pytest.mark.parametrize("velocity", [0.0, SPEED])
def test_damped_run_converges_to_static_solution(small, velocity):
    """β = 1, γ = 3/2 with a large Δt brings the transient to the static answer."""
    result = march(small, velocity, dt=1e-4, steps=50, beta=1.0, gamma=1.5)
    static = solve_static(small, velocity)
    assert np.abs(result.w - static.w).max() < 1e-10 * np.abs(static.w).max()
    assert result.load_point[-1] == pytest.approx(static.load_point_deflection, rel=1e-10)


# ----- symmetry ------------------------------------------------------------------------
def _symmetry_defects(field: np.ndarray) -> tuple[float, float]:
    """Relative defects of symmetry about x = L_x/2 and y = L_y/2."""
    scale = np.abs(field).max()
    return (np.abs(field - field[::-1, :]).max() / scale,
            np.abs(field - field[:, ::-1]).max() / scale)


def test_centred_load_is_symmetric_at_rest_and_not_when_moving():
    model = TapeModel(TapeParameters(length_ratio=3, spacing=WIDTH / 10))
    times = [10e-6, 30e-6, 60e-6]
    at_rest = march(model, 0.0, dt=2e-6, steps=30, snapshot_times=times)
    moving = march(model, SPEED, dt=2e-6, steps=30, snapshot_times=times)
    for field in at_rest.snapshots.fields:
        sx, sy = _symmetry_defects(field)
        assert sx < 1e-10 and sy < 1e-10
    for field in moving.snapshots.fields:
        sx, sy = _symmetry_defects(field)
        assert sx > 1e-3  # transport breaks the fore-aft symmetry ...
        assert sy < 1e-10  # ... but not the symmetry across the width


# ----- reuse and continuation ----------------------------------------------------------
def test_one_factorization_serves_many_runs_and_runs_continue(small):
    stepper = Newmark(small, SPEED, dt=2e-6)
    whole = stepper.march(100)
    first = stepper.march(60)
    rest = stepper.march(40, w0=first.w, v0=first.v, t0=first.times[-1])
    assert stepper.info["factorizations"] == 1
    np.testing.assert_allclose(rest.times, whole.times[60:], rtol=1e-14)
    np.testing.assert_allclose(rest.load_point, whole.load_point[60:], rtol=1e-10,
                               atol=1e-12 * np.abs(whole.load_point).max())


# ----- the paper's grid ----------------------------------------------------------------
@pytest.mark.slow
def test_energy_and_steady_state_on_the_table_1_grid():
    """L_x/L_y = 4, 164 x 41 intervals: 3000 trapezoidal steps conserve E; β = 1 settles."""
    model = TapeModel(TapeParameters(length_ratio=4))
    result = march(model, SPEED, dt=2e-6, steps=3000, record_energy=True)
    scale = static_energy_scale(model, SPEED)
    assert np.abs(result.energy - result.energy[0]).max() < 1e-10 * scale
    damped = march(model, SPEED, dt=1e-4, steps=50, beta=1.0, gamma=1.5)
    static = solve_static(model, SPEED)
    assert np.abs(damped.w - static.w).max() < 1e-10 * np.abs(static.w).max()
