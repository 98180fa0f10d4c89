"""Patir & Cheng's flow factors: formulas, limits, smoothness and the range below the fit."""

from __future__ import annotations

import numpy as np
import pytest

from gyroshell import ParameterError
from gyroshell.bearing.flow_factors import pressure_flow_factor, shear_flow_factor

PC = "patir-cheng"


def phi_x(H):
    """Patir & Cheng (1978), isotropic roughness, H > 0.5."""
    return 1 - 0.9 * np.exp(-0.56 * H)


def shear_low(H):
    """Patir & Cheng (1979), isotropic roughness, 0.5 < H <= 5."""
    return 1.899 * H**0.98 * np.exp(-0.92 * H + 0.05 * H**2)


def shear_high(H):
    """Patir & Cheng (1979), H > 5."""
    return 1.126 * np.exp(-0.25 * H)


def central_difference(f, H, step=1e-6):
    return (f(PC, H + step)[0] - f(PC, H - step)[0]) / (2 * step)


def test_pressure_flow_factor_matches_the_fit_down_to_zero():
    H = np.linspace(0.0, 40.0, 801)
    phi, dphi = pressure_flow_factor(PC, H)
    assert np.allclose(phi, phi_x(H), rtol=1e-15)
    assert np.allclose(dphi, 0.9 * 0.56 * np.exp(-0.56 * H), rtol=1e-14)
    assert pressure_flow_factor(PC, 0.0)[0] == pytest.approx(0.1, rel=1e-14)


def test_shear_flow_factor_matches_the_fit_outside_the_blend():
    H = np.linspace(0.5, 30.0, 2951)
    low, high = (H >= 0.5) & (H <= 4.5), H >= 5.5
    Phi, _ = shear_flow_factor(PC, H)
    assert np.allclose(Phi[low], shear_low(H[low]), rtol=1e-14)
    assert np.allclose(Phi[high], shear_high(H[high]), rtol=1e-14)
    band = (H > 4.5) & (H < 5.5)
    a, b = shear_low(H[band]), shear_high(H[band])
    assert np.all(Phi[band] >= np.minimum(a, b) * (1 - 1e-14))
    assert np.all(Phi[band] <= np.maximum(a, b) * (1 + 1e-14))
    # the two published pieces nearly meet at H = 5
    assert shear_low(5.0) == pytest.approx(shear_high(5.0), rel=2e-3)


def test_limits_of_a_smooth_film_and_the_none_model():
    H = np.array([50.0, 200.0, 1e4, 1e300])
    phi, dphi = pressure_flow_factor(PC, H)
    Phi, dPhi = shear_flow_factor(PC, H)
    assert np.allclose(phi, 1.0, atol=1e-12) and np.allclose(dphi, 0.0, atol=1e-12)
    assert np.allclose(Phi, 0.0, atol=1e-5) and np.all(np.isfinite(dPhi))
    assert Phi[0] > Phi[1] > Phi[2] >= 0
    anyH = np.array([-1.0, 0.0, 0.7, 3.0, 1e6])
    assert np.array_equal(pressure_flow_factor("none", anyH)[0], np.ones(5))
    assert np.array_equal(shear_flow_factor("none", anyH)[0], np.zeros(5))
    assert np.array_equal(pressure_flow_factor("none", anyH)[1], np.zeros(5))
    assert np.array_equal(shear_flow_factor("none", anyH)[1], np.zeros(5))


@pytest.mark.parametrize("factor", [pressure_flow_factor, shear_flow_factor],
                         ids=["pressure", "shear"])
def test_derivatives_match_finite_differences_everywhere(factor):
    """Including below the fit (H < 0.5), across H = 0, the blend about H = 5, and far out."""
    H = np.concatenate([np.linspace(-1.5, 12.0, 2701), np.linspace(4.4, 5.6, 121),
                        [0.5, 0.0, 5.0, 100.0]])
    H = H[np.abs(H) > 2e-6]        # a central difference straddling H = 0 sees the join
    _, d = factor(PC, H)
    assert np.allclose(d, central_difference(factor, H), rtol=1e-7, atol=1e-9)


@pytest.mark.parametrize("factor, at", [(pressure_flow_factor, 0.0),
                                        (shear_flow_factor, 0.5),
                                        (shear_flow_factor, 4.5), (shear_flow_factor, 5.5)])
def test_joins_are_twice_continuously_differentiable(factor, at):
    """Value, slope and curvature agree from both sides of each join."""
    eps = 1e-7
    side = [factor(PC, at + s * np.array([eps, 2 * eps, 3 * eps])) for s in (-1, 1)]
    value = [f[0][0] for f in side]
    slope = [f[1][0] for f in side]
    curvature = [s * (f[1][1] - f[1][0]) / eps for s, f in zip((-1, 1), side, strict=True)]
    assert value[0] == pytest.approx(value[1], abs=1e-6)
    assert slope[0] == pytest.approx(slope[1], rel=1e-5, abs=1e-6)
    assert curvature[0] == pytest.approx(curvature[1], rel=1e-3, abs=1e-4)


def test_below_the_fit_range():
    """H < 0.5: φ_x stays positive and increasing (0.1 at H = 0); Φ_s rises from 0 at H = 0
    and follows the fit's own formula within a few per cent."""
    H = np.linspace(-3.0, 0.5, 3501)
    phi, dphi = pressure_flow_factor(PC, H)
    assert np.all(phi > 0) and np.all(dphi > 0) and np.all(np.diff(phi) > 0)
    Hs = np.linspace(0.0, 0.5, 501)
    Phi, dPhi = shear_flow_factor(PC, Hs)
    assert Phi[0] == 0.0 and np.all(dPhi > 0)
    assert np.allclose(Phi[50:], shear_low(Hs[50:]), rtol=0.04)


def test_refusal():
    with pytest.raises(ParameterError, match="flow_factors must be one of patir-cheng, none"):
        pressure_flow_factor("christensen", 1.0)
    with pytest.raises(ParameterError, match="flow_factors"):
        shear_flow_factor("christensen", 1.0)
