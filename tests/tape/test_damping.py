"""Damping C = c W + a M + b K in the Newmark marcher: structure, dissipation, decay rate."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg as sl
from convergence import observed_order

from gyroshell import ParameterError, TapeModel, TapeParameters
from gyroshell.engines.newmark import Newmark, march
from gyroshell.tape.damping import Damping, as_damping, rayleigh, viscous
from gyroshell.tape.loads import Ramp, gaussian_load

WIDTH = 6.35e-3
SPEED = 50.0


@pytest.fixture(scope="module")
def small() -> TapeModel:
    return TapeModel(TapeParameters(length_ratio=2, spacing=WIDTH / 8))


def test_damping_matrix_structure(small):
    """Viscous C = (c/ρ) M, diagonal; Rayleigh a M + b K(V): symmetric, positive semi-definite."""
    c = viscous(700.0).matrix(small, SPEED)
    np.testing.assert_allclose(c.diagonal(), 700.0 / small.params.density
                               * small.mass_diagonal, rtol=1e-15)
    assert c.nnz == small.unknowns
    C = Damping(viscous=300.0, mass_coefficient=2e3, stiffness_coefficient=1e-7).matrix(
        small, SPEED).toarray()
    assert np.abs(C - C.T).max() == 0.0
    assert np.linalg.eigvalsh(C).min() > 0.0
    expected = (300.0 / small.params.density + 2e3) * small.M.toarray() \
        + 1e-7 * small.K(SPEED).toarray()
    np.testing.assert_allclose(C, expected, rtol=1e-14, atol=1e-14 * np.abs(C).max())


@pytest.mark.parametrize("damping", [viscous(500.0), rayleigh(1e3, 2e-7),
                                     Damping(300.0, 500.0, 1e-7)])
def test_trapezoidal_energy_decays_at_exactly_the_dissipation_rate(small, damping, rng):
    """β = 1/4, γ = 1/2, constant load: E_{n+1} − E_n = −Δt v̄ᵀC v̄, v̄ = (wⁿ⁺¹ − wⁿ)/Δt."""
    dt, steps = 1e-6, 400
    w0 = 1e-8 * rng.standard_normal(small.unknowns)
    v0 = 1e-3 * rng.standard_normal(small.unknowns)
    stepper = Newmark(small, SPEED, dt=dt, damping=damping)
    result = stepper.march(steps, w0=w0, v0=v0, record_energy=True, snapshot_every=1)
    W = np.array([small.grid.from_field(f) for f in result.snapshots.fields])
    dw = np.diff(W, axis=0)
    loss = np.einsum("ni,ni->n", dw, (stepper.C @ dw.T).T) / dt
    change = np.diff(result.energy)
    scale = np.abs(result.energy).max()
    assert np.all(change < 0.0)  # monotone decay
    assert np.abs(change + loss).max() < 1e-11 * scale
    assert result.energy[-1] < 0.5 * result.energy[0]


def test_mass_proportional_damping_decays_a_mode_at_c_over_2rho(small):
    """V = 0, C = (c/ρ) M: a mode φ with frequency ω released from rest moves as
    e^{−ζt}(cos ω_d t + ζ/ω_d sin ω_d t), ζ = c/2ρ, ω_d = √(ω² − ζ²); order 2 in Δt."""
    c = 2000.0
    zeta = c / (2 * small.params.density)
    lam, phi = sl.eigh(small.K(0.0).toarray(), np.diag(small.mass_diagonal))
    omega, mode = np.sqrt(lam[0]), phi[:, 0]
    wd = np.sqrt(omega**2 - zeta**2)
    duration = 100e-6
    errors, dts = [], []
    for dt in (1e-6, 5e-7, 2.5e-7):
        result = march(small, 0.0, dt=dt, steps=round(duration / dt), damping=c,
                       w0=1e-9 * mode, force=np.zeros(small.unknowns))
        t = result.times[-1]
        exact = 1e-9 * mode * np.exp(-zeta * t) * (np.cos(wd * t) + zeta / wd * np.sin(wd * t))
        errors.append(np.abs(result.w - exact).max() / (1e-9 * np.abs(mode).max()))
        dts.append(dt)
    assert errors[-1] < 1e-3
    assert observed_order(dts, errors) == pytest.approx(2.0, abs=0.1)


def test_damped_transient_settles_to_the_static_solution(small):
    """With damping the trapezoidal rule itself (no algorithmic damping) reaches statics."""
    from gyroshell import solve_static

    result = march(small, SPEED, dt=2e-6, steps=2000, damping=3000.0)
    static = solve_static(small, SPEED).w
    assert np.abs(result.w - static).max() < 1e-6 * np.abs(static).max()


@pytest.mark.parametrize(("make", "match"), [
    (lambda: Damping(viscous=-1.0), "damping must be >= 0 N\\*s/m\\^3, got -1"),
    (lambda: Damping(mass_coefficient=float("nan")), "mass_coefficient must be finite"),
    (lambda: rayleigh(0.0, -1e-7), "stiffness_coefficient must be >= 0 s, got -1e-07"),
    (lambda: as_damping("lots"), "damping must be a real number"),
    (lambda: Ramp("a"), "rise_time must be a real number s, got 'a'"),
    (lambda: Ramp(-1.0), "rise_time must be > 0 s, got -1"),
])
def test_bad_damping_and_profiles_raise_parameter_error(make, match):
    with pytest.raises(ParameterError, match=match):
        make()


def test_bad_force_exponent_and_blowup_factor(small):
    with pytest.raises(ParameterError, match="exponent must be > 0 1/m\\^2, got 0"):
        gaussian_load(small.grid, small.params, exponent=0)
    stepper = Newmark(small, 0.0, dt=1e-6)
    with pytest.raises(ParameterError,
                       match=r"force must be a vector of length 135 N, got shape \(3,\)"):
        stepper.march(2, force=np.zeros(3))
    with pytest.raises(ParameterError, match="force must be finite N: it has 135 NaN"):
        stepper.march(2, force=np.full(small.unknowns, np.nan))
    with pytest.raises(ParameterError, match="blowup_factor must be > 0"):
        stepper.march(2, blowup_factor=-1.0)


@pytest.mark.parametrize("name", ["gyroshell.tape.damping", "gyroshell.engines.frequency_options",
                                  "gyroshell.tape.moving_loads", "gyroshell.core.progress"])
def test_docstring_examples(name):
    import doctest
    import importlib

    result = doctest.testmod(importlib.import_module(name),
                             optionflags=doctest.NORMALIZE_WHITESPACE)
    assert result.attempted > 0 and result.failed == 0
