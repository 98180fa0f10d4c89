"""A smooth step for blending piecewise fits (a C³ partition of unity)."""

from __future__ import annotations

import numpy as np


def smooth_step(u) -> tuple[np.ndarray, np.ndarray]:
    """S(u) and S'(u), elementwise: 0 for u <= −1, 1 for u >= 1 and in between the septic
    smoothstep S = s⁴ (35 − 84 s + 70 s² − 20 s³), s = (u + 1)/2, whose first three
    derivatives vanish at both ends (so S is C³ everywhere). S(u) + S(−u) = 1."""
    s = np.clip(0.5 * (np.asarray(u, dtype=float) + 1.0), 0.0, 1.0)
    step = s**4 * (35.0 - 84.0 * s + 70.0 * s**2 - 20.0 * s**3)
    return step, 70.0 * s**3 * (1.0 - s) ** 3
