"""Head geometry: a cylinder of the tape's radius R, wrapped over an angle θ.

Without air the tape lies on the head over the arc R θ, centred in the domain, and leaves
along straight spans tangent to it. Its displacement w is measured from the cylinder, so
in that dry configuration

    w₀(x) = (|x − x_c| − R θ / 2)₊² / (2R),

the gap between a tangent span and the cylinder in the small-slope (shallow shell)
approximation the shell equations already make. The flying tape is w = w₀ + u, the gap
h = w₀ + u: h = u on the wrap and h grows with the spans outside.

The tape's curvature in the dry configuration, measured from flat, is
κ = 1/R − w₀'' (1/R on the wrap, 0 on the spans): it sets both the belt-wrap load
(T − ρV²) κ and the bending moment that a tape of finite D cannot jump at the wrap corners.
"""

from __future__ import annotations

import math

import numpy as np

from ..core import validation
from ..core.errors import ParameterError

#: Largest wrap angle, rad: beyond it the shallow-shell gap w₀ is no longer a fair model.
MAX_WRAP_ANGLE = math.radians(90.0)


def check_wrap_angle(angle: float) -> float:
    """Validate a wrap angle θ in rad: 0 < θ <= π/2."""
    # The range is stated in degrees, which users read more easily than π/2 rad.
    angle = validation.real("wrap_angle", angle, unit="rad")
    if not 0.0 < angle <= MAX_WRAP_ANGLE:
        raise ParameterError(
            f"wrap_angle must be in (0, {math.degrees(MAX_WRAP_ANGLE):g}] degrees, "
            f"got {math.degrees(angle):g} degrees")
    return angle


def dry_gap(x: np.ndarray, length: float, radius: float, wrap_angle: float) -> np.ndarray:
    """w₀(x), m: distance from the cylinder to the dry tape (0 on the wrap)."""
    half = 0.5 * radius * wrap_angle
    s = np.maximum(np.abs(np.asarray(x, dtype=float) - 0.5 * length) - half, 0.0)
    return s * s / (2.0 * radius)


def dry_curvature(x: np.ndarray, length: float, radius: float, wrap_angle: float
                  ) -> np.ndarray:
    """κ at the interior nodes of the abscissae ``x`` (uniform or graded), 1/m: 1/R − δ²w₀.

    The discrete second difference (the one of the tape's operators,
    δ²w_i = [(w_{i+1} − w_i)/h_i − (w_i − w_{i−1})/h_{i−1}] / ((h_{i−1} + h_i)/2)) makes
    the wrap load and the bending reference exactly consistent with the nodal w₀ (a node
    straddling a corner gets the right fraction).
    """
    x = np.asarray(x, dtype=float)
    w0 = dry_gap(x, length, radius, wrap_angle)
    h = np.diff(x)
    slope = np.diff(w0) / h
    return 1.0 / radius - np.diff(slope) / (0.5 * (h[:-1] + h[1:]))
