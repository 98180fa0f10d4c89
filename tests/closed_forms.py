"""Independent exact solutions the discrete model is checked against (continuous PDE).

* Navier: a plate simply supported on all four sides under p sin(αx) sin(βy).
* Beam on an elastic foundation with tension: width-uniform solution for ν = 0 and a load
  uniform across the width.
* Lévy: simply supported ends, free lateral edges, any ν, a load p sin(αx) uniform across
  the width: w = Y(y) sin(αx), Y from a 4th-order ODE with the free-edge conditions.
"""

from __future__ import annotations

import numpy as np

from gyroshell import TapeParameters


def navier_static(p: TapeParameters, velocity: float, m: int, n: int) -> float:
    """Amplitude of w = W sin(mπx/L_x) sin(nπy/L_y) under a unit-amplitude pressure, m/Pa."""
    a, b = m * np.pi / p.length, n * np.pi / p.width
    S = p.tension - p.density * velocity**2
    return 1.0 / (p.D * (a**2 + b**2) ** 2 + S * a**2 + p.k)


def navier_frequency(p: TapeParameters, m: int, n: int) -> float:
    """V = 0 natural frequency of the all-sides simply supported shell, rad/s."""
    a, b = m * np.pi / p.length, n * np.pi / p.width
    return float(np.sqrt((p.D * (a**2 + b**2) ** 2 + p.tension * a**2 + p.k) / p.density))


def beam_on_foundation(p: TapeParameters, velocity: float, m: int) -> float:
    """Amplitude of the width-uniform w = W sin(αx) under unit pressure sin(αx), m/Pa."""
    a = m * np.pi / p.length
    return 1.0 / (p.D * a**4 + (p.tension - p.density * velocity**2) * a**2 + p.k)


def levy_profile(p: TapeParameters, velocity: float, m: int, y: np.ndarray) -> np.ndarray:
    """Y(y) of w = Y(y) sin(mπx/L_x) under unit pressure sin(mπx/L_x), free edges, m/Pa.

    D(Y'''' − 2α²Y'' + α⁴Y) + (T − ρV²)α²Y + kY = 1 on 0 < y < L_y with zero moment
    Y'' − να²Y = 0 and zero Kirchhoff shear Y''' − (2 − ν)α²Y' = 0 at y = 0, L_y.
    """
    a, D, nu = m * np.pi / p.length, p.D, p.poisson
    S = p.tension - p.density * velocity**2
    Yp = 1.0 / (D * a**4 + S * a**2 + p.k)
    beta = np.sqrt(complex((S * a**2 + p.k) / D))
    r = np.sqrt(np.array([a**2 + 1j * beta, a**2 - 1j * beta]))
    roots = np.concatenate([r, -r])
    rows, rhs = [], []
    for edge in (-p.width / 2, p.width / 2):
        e = np.exp(roots * edge)
        rows.append(e * (roots**2 - nu * a**2))
        rhs.append(nu * a**2 * Yp)
        rows.append(e * (roots**3 - (2 - nu) * a**2 * roots))
        rhs.append(0.0)
    c = np.linalg.solve(np.array(rows), np.array(rhs, dtype=complex))
    return (Yp + np.exp(np.outer(np.asarray(y) - p.width / 2, roots)) @ c).real


def moving_line_load(p: TapeParameters, velocity: float, load_speed: float, damping: float,
                     exponent: float, xi: np.ndarray, *, points: int = 200_001) -> np.ndarray:
    """Steady deflection W(ξ), ξ = x − U t, m, of the infinite beam on the shell foundation
    under a line load P_0 exp(−α ξ²) (uniform across the width, ν = 0) moving at U, tape at V.

    In the load's frame D W'''' + (ρ(V − U)² − T) W'' − c U W' + k W = p(ξ) (lab-frame
    viscous damping c), so by Fourier transform (Frýba's moving-load solution)

        W(ξ) = (1/π) ∫₀^∞ Re[ p̂(κ) e^{iκξ} / (Dκ⁴ − (ρ(V−U)² − T)κ² − i c U κ + k) ] dκ,

    p̂(κ) = P_0 √(π/α) exp(−κ²/4α); evaluated by the trapezoid rule on [0, 13√α] (the
    integrand is smooth and p̂ is below 1e-18 of its peak beyond).
    """
    kappa = np.linspace(0.0, 13.0 * np.sqrt(exponent), points)
    s = p.density * (velocity - load_speed) ** 2 - p.tension
    den = p.D * kappa**4 - s * kappa**2 + p.k - 1j * damping * load_speed * kappa
    p_hat = p.load * np.sqrt(np.pi / exponent) * np.exp(-kappa**2 / (4 * exponent))
    g = p_hat / den
    dk = kappa[1] - kappa[0]
    out = np.empty(len(np.atleast_1d(xi)))
    for i, x in enumerate(np.atleast_1d(xi)):
        f = (g * np.exp(1j * kappa * x)).real
        out[i] = dk * (f.sum() - 0.5 * (f[0] + f[-1])) / np.pi
    return out
