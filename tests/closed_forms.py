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
