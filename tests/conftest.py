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


def pytest_addoption(parser):
    parser.addoption("--runslow", action="store_true",
                     help="also run tests marked slow (full-size grids and studies)")


def pytest_collection_modifyitems(config, items):
    """Skip `slow` tests unless asked for with --runslow or a -m expression naming slow."""
    if config.getoption("--runslow") or "slow" in (config.getoption("-m") or ""):
        return
    skip = pytest.mark.skip(reason="slow: run with --runslow or -m slow")
    for item in items:
        if "slow" in item.keywords:
            item.add_marker(skip)
