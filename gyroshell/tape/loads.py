"""Loads: the Gaussian "concentrated" load of Eq. 17, pressure fields, time profiles.

A load is a pressure P (Pa) on the tape. The functions here turn it into the nodal force
vector F the engines take (N, one entry per unknown; rows scaled by control areas like the
operators), and a time profile f(t) (dimensionless) switches it: F(t) = f(t) F.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy.special import erf

from ..core import validation
from .grid import Grid
from .parameters import TapeParameters

#: Eq. 17 decays to 1 % of its peak ...
DECAY_LEVEL = 0.01
#: ... at 5 % of the width from the load point.
DECAY_FRACTION = 0.05


def gaussian_exponent(width: float) -> float:
    """α of Eq. 17, 1/m²: exp(−α r²) = 1 % at r = 5 % of the width, α = ln 100 / (0.05 L_y)²."""
    return math.log(1.0 / DECAY_LEVEL) / (DECAY_FRACTION * width) ** 2


def check_exponent(exponent: float) -> float:
    """Validate a Gaussian exponent α, 1/m² (finite, > 0)."""
    return validation.positive("exponent", exponent, "1/m^2")


def _cell_integrals(nodes: np.ndarray, h: float, centre: float, alpha: float,
                    lo: float, hi: float) -> np.ndarray:
    """∫ exp(−α (s − centre)²) ds over each node's control interval, clipped to [lo, hi]."""
    a = np.clip(nodes - h / 2, lo, hi)
    b = np.clip(nodes + h / 2, lo, hi)
    s = math.sqrt(alpha)
    return 0.5 * math.sqrt(math.pi / alpha) * (erf(s * (b - centre)) - erf(s * (a - centre)))


def gaussian_load(grid: Grid, params: TapeParameters, *, exponent: float | None = None
                  ) -> np.ndarray:
    """Nodal forces (N) of P = P_0 exp(−α(x−x_0)²) exp(−α(y−y_0)²) (Eq. 17).

    Each node receives the exact integral of the pressure over its control cell (erf), so
    the total force equals ∫∫ P dA on the tape however coarse the grid: the load spans only
    a few spacings on the Table 1 grid, where point sampling would misstate it. If
    ``params.wrap_pressure`` is set, the uniform belt-wrap pressure −T/R is added.
    ``exponent`` overrides α (1/m²), e.g. to put the same load on a wider reference tape.
    """
    alpha = gaussian_exponent(params.width) if exponent is None else check_exponent(exponent)
    x0, y0 = params.load_centroid
    fx = _cell_integrals(grid.x[grid.x_unknowns], grid.hx, x0, alpha, 0.0, grid.length)
    fy = _cell_integrals(grid.y[grid.y_unknowns], grid.hy, y0, alpha, 0.0, grid.width)
    force = params.load * np.kron(fx, fy)
    if params.wrap_pressure:
        force -= params.wrap_pressure_value * grid.areas
    return force


def pressure_load(grid: Grid, pressure: Callable[[np.ndarray, np.ndarray], np.ndarray]
                  ) -> np.ndarray:
    """Nodal forces (N) of a pressure field ``pressure(X, Y)`` (Pa): trapezoid rule."""
    return grid.areas * grid.sample(pressure)


# ----- time profiles -------------------------------------------------------------------
TimeProfile = Callable[[float], float]


def step(t: float) -> float:
    """Heaviside step H(t): 1 for t >= 0 (the load is on from the first instant)."""
    return 1.0 if t >= 0.0 else 0.0


@dataclass(frozen=True)
class Ramp:
    """Linear rise from 0 at t = 0 to 1 at ``rise_time`` (s), then constant."""

    rise_time: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "rise_time", validation.positive("rise_time", self.rise_time, "s"))

    def __call__(self, t: float) -> float:
        return min(max(t / self.rise_time, 0.0), 1.0)


@dataclass(frozen=True)
class Harmonic:
    """sin(2π f t) with frequency f (Hz) switched on at t = 0."""

    frequency: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "frequency",
                           validation.positive("frequency", self.frequency, "Hz"))

    def __call__(self, t: float) -> float:
        return math.sin(2 * math.pi * self.frequency * t) if t >= 0 else 0.0
