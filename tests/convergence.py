"""Shared helper for convergence tests: the observed order from a log-log fit."""

from __future__ import annotations

import numpy as np


def observed_order(steps, errors) -> float:
    """Least-squares slope of log(error) against log(step): the observed order."""
    slope, _ = np.polyfit(np.log(np.asarray(steps, float)), np.log(np.asarray(errors, float)), 1)
    return float(slope)
