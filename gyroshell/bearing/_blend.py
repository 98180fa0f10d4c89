"""A smooth step for blending piecewise fits (a C³ partition of unity)."""

from __future__ import annotations

import numpy as np


def smooth_step(u) -> tuple[np.ndarray, np.ndarray]:
    """S(u) and S'(u), elementwise: 0 for u <= −1, 1 for u >= 1 and in between the septic
    smoothstep S = s⁴ (35 − 84 s + 70 s² − 20 s³), s = (u + 1)/2, whose first three
    derivatives vanish at both ends (so S is C³ everywhere). S(u) + S(−u) = 1."""
    s = np.clip(0.5 * (np.asarray(u, dtype=float) + 1.0), 0.0, 1.0)
    # products and Horner's rule, not s**k: NumPy's float powers cost 4x as much on the
    # film's arrays (the blend is evaluated on every face at every residual)
    s2 = s * s
    t = s * (1.0 - s)
    return s2 * s2 * (35.0 + s * (-84.0 + s * (70.0 - 20.0 * s))), 70.0 * (t * t * t)
