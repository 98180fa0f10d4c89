"""Test harness: non-interactive plots, floating-point errors raise, `slow` and `docs`
markers, and the fixtures several test files share (a small tape model, a CLI runner)."""

from __future__ import annotations

import os
import subprocess
import sys
from dataclasses import dataclass

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")

#: Table 1 tape width L_y, m.
WIDTH = 6.35e-3


@pytest.fixture(scope="session")
def small():
    """L_x/L_y = 2, 16 x 8 intervals: 135 unknowns, dense-solvable."""
    from gyroshell import TapeModel, TapeParameters

    return TapeModel(TapeParameters(length_ratio=2, spacing=WIDTH / 8))


class WidthUniformModel:
    """The tape restricted to width-uniform fields w(x) ⊗ 1 (an exact invariant subspace for
    ν = 0 with free edges); duck-types what the eigen-solvers need from a TapeModel."""

    def __init__(self, model) -> None:
        import scipy.sparse as sp

        g = model.grid
        self.full, self.params, self.grid = model, model.params, g
        self.P = sp.kron(sp.identity(g.n_lines), np.ones((g.n_across, 1)), format="csr")
        self.unknowns = self.size = g.n_lines
        self.mass_diagonal = self.P.T @ model.mass_diagonal

    def K(self, v):
        return (self.P.T @ self.full.K(v) @ self.P).tocsr()

    def G(self, v):
        return (self.P.T @ self.full.G(v) @ self.P).tocsr()

    @property
    def M(self):
        import scipy.sparse as sp

        return sp.diags(self.mass_diagonal)


def moving_string(nx: int) -> WidthUniformModel:
    """An axially moving string (k = 0, D -> 0, ν = 0) of L_x = 2 L_y with nx intervals."""
    from gyroshell import Grid, TapeModel, TapeParameters

    p = TapeParameters(foundation_stiffness=0.0, bending_rigidity=1e-14, poisson=0.0,
                       length_ratio=2.0, spacing=WIDTH / 8)
    return WidthUniformModel(TapeModel(p, Grid(p.length, p.width, nx, 8, "free")))


@dataclass(frozen=True)
class CliRun:
    """What one command line did: exit code, stdout, stderr."""

    code: int
    out: str
    err: str

    @property
    def error_lines(self) -> list[str]:
        return self.err.strip().splitlines()


@pytest.fixture
def cli(capsys):
    """Run ``gyroshell.cli.main(argv)`` in-process; returns a :class:`CliRun` (argparse's
    SystemExit becomes the exit code)."""
    from gyroshell.cli import main

    def run(argv: list[str]) -> CliRun:
        capsys.readouterr()
        try:
            code = main([str(a) for a in argv])
        except SystemExit as exc:
            code = int(exc.code)
        captured = capsys.readouterr()
        return CliRun(code, captured.out, captured.err)

    return run


@pytest.fixture
def cli_process():
    """Run ``python -m gyroshell argv`` in a subprocess (cwd, env optional); returns CliRun."""

    def run(argv: list[str], *, cwd=None, env=None, timeout: float = 120) -> CliRun:
        proc = subprocess.run([sys.executable, "-m", "gyroshell", *map(str, argv)], cwd=cwd,
                              env={**os.environ, **(env or {})}, capture_output=True,
                              text=True, timeout=timeout)
        return CliRun(proc.returncode, proc.stdout, proc.stderr)

    return run


@pytest.fixture(autouse=True)
def _strict_floats_and_closed_figures():
    old = np.seterr(all="raise", under="ignore")
    yield
    np.seterr(**old)
    import matplotlib.pyplot as plt

    plt.close("all")


@pytest.fixture(params=["cholmod", "superlu"])
def every_factorization(request):
    """Run a test once per eigen-solver factorization back-end: "auto" means each in turn
    (CHOLMOD through cvxopt, in the test extra; SuperLU, pure scipy) for every solver,
    engine and inertia count, through the public ``use_factorization``."""
    from gyroshell.linalg import cholesky
    from gyroshell.linalg.factorization import use_factorization

    if request.param == "cholmod" and not cholesky.available():
        pytest.skip("cvxopt (CHOLMOD) is not installed")
    with use_factorization(request.param):
        yield request.param


@pytest.fixture
def rng() -> np.random.Generator:
    return np.random.default_rng(20261123)


def pytest_addoption(parser):
    parser.addoption("--runslow", action="store_true",
                     help="also run tests marked slow (full-size grids and studies)")
    parser.addoption("--rundocs", action="store_true",
                     help="also run tests marked docs (build the documentation site and "
                          "check it in headless Chromium)")


def pytest_collection_modifyitems(config, items):
    """Skip `slow` tests unless asked for with --runslow or a -m expression naming slow, and
    `docs` tests likewise (--rundocs or -m docs).

    A test is skipped for the marker it carries, never for a keyword: ``item.keywords`` also
    holds the names of the test's folders, so every test under ``tests/docs/`` would count as
    marked ``docs`` (and the gallery's and references' checks never ran).
    """
    for marker in ["slow", "docs"]:
        if config.getoption(f"--run{marker}") or marker in (config.getoption("-m") or ""):
            continue
        skip = pytest.mark.skip(reason=f"{marker}: run with --run{marker} or -m {marker}")
        for item in items:
            if item.get_closest_marker(marker) is not None:
                item.add_marker(skip)
