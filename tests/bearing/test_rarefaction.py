"""Rarefaction models: Q(Kn) against the published formulas, limits, smoothness, range."""

from __future__ import annotations

import math

import numpy as np
import pytest

from gyroshell import ParameterError
from gyroshell.bearing.rarefaction import (
    RAREFACTION_MODELS,
    knudsen_range_warning,
    poiseuille_flow_factor,
)

SQRT_PI = math.sqrt(math.pi)
#: The breaks of Fukui & Kaneko's fit in D, and the blend half width in ln D.
BREAKS_D = (5.0, 0.15, 0.01)
BAND = 0.1


#: Fukui & Kaneko's fit, J. Tribol. 112:78 (1990): Q_P(D) piece by piece, largest D first.
PIECES = (lambda D: D / 6 + 1.0162 + 1.0653 / D - 2.1354 / D**2,            # D >= 5
          lambda D: 0.13852 * D + 1.25087 + 0.15653 / D - 0.00969 / D**2,    # 0.15 <= D < 5
          lambda D: -2.22919 * D + 2.10673 + 0.01653 / D - 0.0000694 / D**2)  # 0.01 <= D


def published_qp(D):
    """The three-piece Q_P(D), 0.01 <= D."""
    D = np.asarray(D, dtype=float)
    return np.where(D >= 5, PIECES[0](D), np.where(D >= 0.15, PIECES[1](D), PIECES[2](D)))


def kn_of(D):
    return SQRT_PI / (2 * np.asarray(D, dtype=float))


def outside_bands(D):
    return np.all([np.abs(np.log(D / b)) > BAND for b in BREAKS_D], axis=0)


def central_difference(model, kn, rel=1e-6):
    step = rel * np.maximum(kn, 1e-3)
    return (poiseuille_flow_factor(model, kn + step)[0]
            - poiseuille_flow_factor(model, kn - step)[0]) / (2 * step)


def test_polynomial_models_match_their_formulas():
    kn = np.array([0.0, 1e-3, 0.1, 0.5, 1.0, 3.0, 40.0])
    for model, q, dq in (("first-order", 1 + 6 * kn, 6 + 0 * kn),
                         ("second-order", 1 + 6 * kn + 6 * kn**2, 6 + 12 * kn),
                         ("none", 1 + 0 * kn, 0 * kn)):
        got, dgot = poiseuille_flow_factor(model, kn)
        assert np.allclose(got, q, rtol=1e-15) and np.allclose(dgot, dq, rtol=1e-15)


def test_fukui_kaneko_matches_the_published_fit_outside_the_blend_bands():
    D = np.geomspace(0.01, 1e4, 4001)
    keep = outside_bands(D)
    q, _ = poiseuille_flow_factor("fukui-kaneko", kn_of(D))
    exact = 6 * published_qp(D) / D
    assert np.allclose(q[keep], exact[keep], rtol=1e-12)
    # inside the bands: a convex combination of the two neighbouring pieces, which differ
    # by < 0.3 % at the break
    for k, b in enumerate(BREAKS_D[:2]):
        Db = b * np.exp(np.linspace(-BAND, BAND, 41))
        upper, lower = 6 * PIECES[k](Db) / Db, 6 * PIECES[k + 1](Db) / Db
        qb = poiseuille_flow_factor("fukui-kaneko", kn_of(Db))[0]
        assert abs(PIECES[k](b) / PIECES[k + 1](b) - 1) < 3e-3
        slack = 1e-13 * qb
        assert np.all(qb >= np.minimum(upper, lower) - slack)
        assert np.all(qb <= np.maximum(upper, lower) + slack)
        assert np.allclose(qb[:5], lower[:5], rtol=3e-3)


def test_fukui_kaneko_is_one_at_zero_knudsen_and_has_the_kinetic_slip_slope():
    """Large D: Q → 1 + 6 · 1.0162 · (2/√π) Kn ≈ 1 + 6.88 Kn (slip coefficient 1.147)."""
    q0, dq0 = poiseuille_flow_factor("fukui-kaneko", 0.0)
    slope = 6 * 1.0162 * 2 / SQRT_PI
    assert q0 == 1.0 and dq0 == pytest.approx(slope, rel=1e-14)
    assert slope == pytest.approx(6.88, abs=5e-3)
    kn = np.array([1e-6, 1e-4, 1e-3])
    q, _ = poiseuille_flow_factor("fukui-kaneko", kn)
    assert np.allclose((q - 1) / kn, slope, rtol=2 * kn.max())
    assert np.all(np.isfinite(q))


def test_knudsen_minimum_of_the_flow_rate():
    """Q_P = Q D / 6 has its Knudsen minimum, about 1.54, near D ≈ 1."""
    D = np.geomspace(0.02, 50, 20001)
    qp = poiseuille_flow_factor("fukui-kaneko", kn_of(D))[0] * D / 6
    i = int(np.argmin(qp))
    assert qp[i] == pytest.approx(1.54, abs=0.01)
    assert 0.8 < D[i] < 1.2
    assert qp[0] > qp[i] and qp[-1] > qp[i]


def test_fukui_kaneko_is_smooth_across_the_breaks():
    """Value and derivative continuous at the breaks and their bands' ends; the derivative
    equals central differences everywhere, inside the bands too."""
    for b in BREAKS_D:
        for D in (b, b * math.exp(BAND), b * math.exp(-BAND)):
            kn = kn_of(D) * (1 + np.array([-1e-10, 1e-10]))
            q, dq = poiseuille_flow_factor("fukui-kaneko", kn)
            assert q[1] == pytest.approx(q[0], rel=1e-8)
            assert dq[1] == pytest.approx(dq[0], rel=1e-7)
    D = np.concatenate([np.geomspace(1e-4, 1e4, 3001)]
                       + [b * np.exp(np.linspace(-1.2 * BAND, 1.2 * BAND, 101))
                          for b in BREAKS_D])
    kn = kn_of(D)
    _, dq = poiseuille_flow_factor("fukui-kaneko", kn)
    assert np.allclose(dq, central_difference("fukui-kaneko", kn), rtol=1e-6)


def test_fukui_kaneko_below_the_fit_is_smooth_increasing_and_logarithmic():
    """Below D = 0.01: Q_P continues as its tangent in ln D (Q grows like Kn ln Kn)."""
    D = np.geomspace(1e-8, 1e4, 20001)
    q, dq = poiseuille_flow_factor("fukui-kaneko", kn_of(D))
    assert np.all(np.isfinite(q)) and np.all(dq > 0)
    assert np.all(np.diff(q[::-1]) > 0)            # increasing with Kn
    qp = q * D / 6
    low = D < 0.01 * math.exp(-BAND)
    # tangent: Q_P(D) = Q_P(0.01) + s ln(0.01/D), s = −D dQ_P/dD at 0.01 from the fit
    D0 = 0.01
    s = 2.22919 * D0 + 0.01653 / D0 - 2 * 0.0000694 / D0**2
    assert np.allclose(qp[low], published_qp(D0) + s * np.log(D0 / D[low]), rtol=1e-12)
    assert s > 0


@pytest.mark.parametrize("kn", np.linspace(0.5, 3.0, 26))
def test_boltzmann_lies_between_first_and_second_order_slip(kn):
    """Sakai et al. (J. Tribol. 118:800, 1996): for head–tape Knudsen numbers the
    Boltzmann flow factor lies between first- and second-order slip."""
    first, fk, second = (poiseuille_flow_factor(m, kn)[0]
                         for m in ("first-order", "fukui-kaneko", "second-order"))
    assert first < fk < second


def test_vectorized_shapes_and_refusal():
    kn = np.full((3, 4), 0.7)
    for model in RAREFACTION_MODELS:
        q, dq = poiseuille_flow_factor(model, kn)
        assert q.shape == dq.shape == (3, 4)
    with pytest.raises(ParameterError, match="rarefaction must be one of fukui-kaneko"):
        poiseuille_flow_factor("boltzmann", 1.0)


def test_knudsen_range_warning():
    assert knudsen_range_warning("first-order", 0.4) is None
    text = knudsen_range_warning("first-order", 2.0)
    assert "--rarefaction fukui-kaneko" in text and "0.5" in text and "\n" not in text
    assert knudsen_range_warning("second-order", 0.9) is None
    assert knudsen_range_warning("second-order", 1.5) is not None
    assert knudsen_range_warning("fukui-kaneko", 1e6) is None
    assert knudsen_range_warning("none", 0.2) is not None
    with pytest.raises(ParameterError, match="rarefaction"):
        knudsen_range_warning("slip", 1.0)


@pytest.mark.parametrize("model, limit, sign", [("first-order", 0.5, -1),
                                                ("second-order", 1.0, 1), ("none", 0.05, -1)])
def test_warning_limits_are_where_the_model_is_a_quarter_off_boltzmann(model, limit, sign):
    """Each limit is where Q is off the Boltzmann Q by about a quarter (by the published
    fit directly), and the error grows beyond it."""
    def error(kn):
        D = SQRT_PI / (2 * kn)
        return poiseuille_flow_factor(model, kn)[0] / (6 * published_qp(D) / D) - 1

    assert sign * error(limit) == pytest.approx(0.25, abs=0.02)
    assert sign * error(1.5 * limit) > sign * error(limit) > sign * error(limit / 1.5)
    assert knudsen_range_warning(model, 0.99 * limit) is None
    assert knudsen_range_warning(model, 1.01 * limit) is not None
