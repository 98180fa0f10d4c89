"""The eigen benchmark's SLEPc column: skipped cleanly without SLEPc, in agreement with it."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import numpy as np
import pytest

from gyroshell import TapeModel, TapeParameters
from gyroshell.engines.eigen import modes

BENCH = Path(__file__).resolve().parents[1] / "benchmarks" / "bench_eigen.py"


def _bench():
    spec = importlib.util.spec_from_file_location("bench_eigen", BENCH)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_slepc_column_skips_without_its_interpreter(tmp_path, monkeypatch):
    bench = _bench()
    monkeypatch.setattr(bench, "SLEPC_PYTHON", str(tmp_path / "no-such-python"))
    assert bench.slepc_round(tmp_path / "m.npz", 3) is None


def test_slepc_agrees_with_gyroshell(tmp_path):
    bench = _bench()
    if not Path(bench.SLEPC_PYTHON).exists():
        pytest.skip(f"no SLEPc interpreter at {bench.SLEPC_PYTHON}")
    model = TapeModel(TapeParameters(length_ratio=3.0, spacing=TapeParameters().width / 8))
    ours = modes(model, 50.0, 4)
    path = tmp_path / "m.npz"
    bench.export(model, 50.0, abs(ours.info["shift"]), path)
    theirs = bench.slepc_round(path, 4)
    assert theirs is not None
    assert np.allclose(theirs["omega"], ours.omega, rtol=1e-7)
