"""gyroshell: dynamics of a circumferentially moving magnetic tape.

The tape on a guide or head is a thin cylindrical shell transported at speed V (Müftü &
Benson's model): D ∇⁴w + (ρV² − T) w_xx + k w + 2ρV w_xt + ρ w_tt = P, simply supported at
x = 0, L_x and free along y = 0, L_y. Finite differences give M a + G v + K w = F.

Layers: parameters → grid and operators → engines (static, Newmark, eigen) → studies.
All quantities are SI.
"""

from __future__ import annotations

import importlib
import sys
import types
from importlib.metadata import PackageNotFoundError
from importlib.metadata import version as _package_version

from .errors import ConvergenceError, ParameterError, SupercriticalError  # noqa: F401
from .parameters import TapeParameters, bending_rigidity, shell_stiffness  # noqa: F401

try:
    __version__ = _package_version("gyroshell")
except PackageNotFoundError:  # pragma: no cover - run from a source tree without install
    __version__ = "0+unknown"

#: Public name -> submodule. Engines import scipy, so they load on first use: `import
#: gyroshell` and the CLI's refusals stay fast.
_LAZY: dict[str, str] = {
    # grid and operators
    "Grid": "grid", "TapeModel": "model",
    "bending_foundation": "operators", "gyroscopic": "operators", "mass": "operators",
    "membrane": "operators",
    "Harmonic": "loads", "Ramp": "loads", "gaussian_load": "loads", "pressure_load": "loads",
    "step": "loads",
    # static and divergence
    "StaticSolution": "static", "solve_static": "static",
    "Divergence": "divergence", "divergence": "divergence",
    "divergence_speed": "divergence",
    # time marching (Newmark, paper Eqs. 10-16) and its sparse LU back-ends
    "available_backends": "factorization", "factorize": "factorization",
    "Newmark": "newmark", "NewmarkStabilityWarning": "newmark", "march": "newmark",
    "Snapshots": "transient_result", "TransientResult": "transient_result",
    # quadratic eigen-solver, critical speeds and speed sweeps
    "CriticalSpeeds": "critical", "critical_speed_eigen": "critical",
    "critical_speeds": "critical",
    "Modes": "eigen", "frequencies": "eigen", "modes": "eigen",
    "InertiaFactor": "inertia", "factor_inertia": "inertia",
    "GyroscopicModes": "qep", "gyroscopic_modes": "qep",
    "plot_sweep": "sweep", "sweep": "sweep",
    # parameter studies and saved results (xarray, Dask and matplotlib load on use)
    "load": "persistence", "save": "persistence",
    "StudyResult": "study", "classify_stability": "qep", "run_study": "study",
    # damping, moving and intermittent loads, and the frequency response
    "Damping": "damping",
    "FrequencyResponse": "frf", "ReducedModel": "frf", "direct_response": "frf",
    "frequency_response": "frf",
    "ContactWindows": "moving_load", "GaussianShape": "moving_load",
    "MovingLoad": "moving_load", "StraightPath": "moving_load", "UniformShape": "moving_load",
    "UserShape": "moving_load", "drum_heads": "moving_load",
}

__all__ = sorted(["ConvergenceError", "ParameterError", "SupercriticalError",
                  "TapeParameters", "bending_rigidity", "shell_stiffness", *_LAZY])


def __getattr__(name: str):
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'gyroshell' has no attribute {name!r}")
    value = getattr(importlib.import_module(f".{module}", __name__), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))


class _Package(types.ModuleType):
    """``gyroshell.sweep`` and ``gyroshell.divergence`` name functions, like their
    submodules: importing a submodule must not replace the function of the same name."""

    def __setattr__(self, name: str, value: object) -> None:
        if isinstance(value, types.ModuleType) and _LAZY.get(name) == name:
            return
        super().__setattr__(name, value)


sys.modules[__name__].__class__ = _Package
