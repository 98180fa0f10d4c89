"""Test harness: non-interactive plots, floating-point errors raise, a `slow` marker."""

from __future__ import annotations

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")


@pytest.fixture(autouse=True)
def _strict_floats_and_closed_figures():
    old = np.seterr(all="raise", under="ignore")
    yield
    np.seterr(**old)
    import matplotlib.pyplot as plt

    plt.close("all")


@pytest.fixture
def rng() -> np.random.Generator:
    return np.random.default_rng(20261123)
