"""Average-flow factors of a rough film: Patir & Cheng's pressure and shear flow factors.

A film between rough surfaces, nominal gap h and combined RMS roughness σ (the film
parameter H = h/σ), carries on average the flux (per unit width)

    q = −φ_x h³/(12μ) ∂p/∂x + (V/2) (h + σ Φ_s)

when the rough surface moves at V over a smooth one (Patir & Cheng, "An average flow model
for determining effects of three-dimensional roughness on partial hydrodynamic
lubrication", J. Lubr. Technol. 100:12–17, 1978; "Application of average flow model to
lubrication between rough sliding surfaces", J. Lubr. Technol. 101:220–230, 1979). The
pressure flow factor φ_x corrects the Poiseuille flux, the shear flow factor Φ_s adds the
air the moving roughness drags along. Models (:data:`FLOW_FACTOR_MODELS`):

``patir-cheng``
    Isotropic roughness (Peklenik number γ = 1), the fits of the two papers:
    φ_x = 1 − 0.9 e^(−0.56 H) (1978, Table 1, fitted for H > 0.5) and
    Φ_s = 1.899 H^0.98 e^(−0.92 H + 0.05 H²) for H <= 5, 1.126 e^(−0.25 H) for H > 5
    (1979, Table 2, fitted for H > 0.5). The two shear pieces differ by 0.1 % in value
    and 12 % in slope at H = 5: they are blended by a C³ partition of unity over
    H = 5 ± :data:`SHEAR_BLEND_HALF_WIDTH`. Below the fits' range: φ_x keeps its formula
    down to H = 0, where it is 0.1 (it is analytic, positive and increasing there), and
    continues for H < 0 (a closed gap, reached only by Newton iterates) as
    0.1 e^(k H + m H²/2), matching its value and first two derivatives at 0 (C²,
    positive, increasing); Φ_s is, for H < 0.5, the cubic in H that vanishes at H = 0
    (no film, no drag) and matches the fit's value and first two derivatives at
    H = 0.5 (C²; increasing on [0, 0.5], within 4 % of the fit's own formula on [0.05, 0.5]).
    φ_x → 1 and Φ_s → 0 as H → ∞ (a smooth film).
``none``
    φ_x = 1, Φ_s = 0.
"""

from __future__ import annotations

import numpy as np

from ..core import validation
from ._blend import smooth_step

FLOW_FACTOR_MODELS = ("patir-cheng", "none")

#: Pressure flow factor φ_x = 1 − C e^(−r H), γ = 1: (C, r).
PRESSURE_FIT = (0.9, 0.56)
#: Shear flow factor for H <= 5: Φ_s = A₁ H^α₁ e^(−α₂ H + α₃ H²), γ = 1: (A₁, α₁, α₂, α₃).
SHEAR_FIT_LOW = (1.899, 0.98, 0.92, 0.05)
#: Shear flow factor for H > 5: Φ_s = A₂ e^(−0.25 H): (A₂, 0.25).
SHEAR_FIT_HIGH = (1.126, 0.25)
#: The break between the two shear pieces, and the half width of their blend (both in H).
SHEAR_BREAK, SHEAR_BLEND_HALF_WIDTH = 5.0, 0.5
#: Lower end of the fits' range in H = h/σ.
FIT_RANGE_LOW = 0.5


def _check(model: str) -> str:
    return validation.choice("flow_factors", model, FLOW_FACTOR_MODELS)


def _pressure_continuation() -> tuple[float, float, float]:
    """(φ₀, k, m) of φ_x = φ₀ e^(k H + m H²/2) for H < 0, C² with the fit at H = 0."""
    c, r = PRESSURE_FIT
    phi0 = 1.0 - c
    k = c * r / phi0                        # φ'(0)/φ(0)
    m = -c * r * r / phi0 - k * k           # φ''(0)/φ(0) − k²
    return phi0, k, m


def pressure_flow_factor(model: str, H) -> tuple[np.ndarray, np.ndarray]:
    """The pressure flow factor φ_x(H) and its derivative dφ_x/dH.

    Parameters
    ----------
    model : str
        One of :data:`FLOW_FACTOR_MODELS`.
    H : array_like
        Film parameter h/σ (dimensionless; any real, see the module notes below 0.5).

    Returns
    -------
    phi, dphi_dH : numpy.ndarray
        Dimensionless, shape of ``H``.
    """
    H = np.asarray(H, dtype=float)
    if _check(model) == "none":
        return np.ones_like(H), np.zeros_like(H)
    c, r = PRESSURE_FIT
    phi0, k, m = _pressure_continuation()
    above = c * np.exp(-r * np.maximum(H, 0.0))
    hb = np.minimum(H, 0.0)
    below = phi0 * np.exp(hb * (k + 0.5 * m * hb))
    positive = H >= 0.0
    return (np.where(positive, 1.0 - above, below),
            np.where(positive, r * above, (k + m * hb) * below))


def _shear_low(H):
    """Φ_s by the H <= 5 fit, its first and second derivatives (H > 0)."""
    a, alpha1, alpha2, alpha3 = SHEAR_FIT_LOW
    f = a * H**alpha1 * np.exp(H * (alpha3 * H - alpha2))
    g = alpha1 / H - alpha2 + 2.0 * alpha3 * H          # (ln f)'
    return f, f * g, f * (g * g - alpha1 / H**2 + 2.0 * alpha3)


def _shear_cubic() -> tuple[float, float, float, float]:
    """Coefficients (v, s, c, a) of Φ_s = v + s d + c d²/2 + a d³, d = H − 0.5, for
    H < 0.5: C² with the fit at 0.5 and zero at H = 0."""
    v, s, c = (float(q) for q in _shear_low(FIT_RANGE_LOW))
    d0 = -FIT_RANGE_LOW
    return v, s, c, -(v + s * d0 + 0.5 * c * d0 * d0) / d0**3


def shear_flow_factor(model: str, H) -> tuple[np.ndarray, np.ndarray]:
    """The shear flow factor Φ_s(H) and its derivative dΦ_s/dH.

    Parameters
    ----------
    model : str
        One of :data:`FLOW_FACTOR_MODELS`.
    H : array_like
        Film parameter h/σ (dimensionless; any real, see the module notes below 0.5).

    Returns
    -------
    Phi, dPhi_dH : numpy.ndarray
        Dimensionless, shape of ``H``; the Couette flux of a film whose rough surface moves
        is V (h + σ Φ_s) / 2.
    """
    H = np.asarray(H, dtype=float)
    if _check(model) == "none":
        return np.zeros_like(H), np.zeros_like(H)
    w = SHEAR_BLEND_HALF_WIDTH
    # each piece on its own support (its weight is 0 elsewhere): no overflow at large H
    f1, d1, _ = _shear_low(np.clip(H, FIT_RANGE_LOW, SHEAR_BREAK + w))
    a2, b2 = SHEAR_FIT_HIGH
    f2 = a2 * np.exp(-b2 * np.maximum(H, SHEAR_BREAK - w))
    d2 = -b2 * f2
    s, ds = smooth_step((H - SHEAR_BREAK) / w)
    ds = ds / w
    fit = (1.0 - s) * f1 + s * f2
    dfit = (1.0 - s) * d1 + s * d2 + ds * (f2 - f1)
    v, sl, c, a = _shear_cubic()
    d = np.minimum(H, FIT_RANGE_LOW) - FIT_RANGE_LOW
    low = v + d * (sl + d * (0.5 * c + d * a))
    dlow = sl + d * (c + 3.0 * a * d)
    below = H < FIT_RANGE_LOW
    return np.where(below, low, fit), np.where(below, dlow, dfit)
