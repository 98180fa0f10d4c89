"""gyroshell: dynamics of a circumferentially moving magnetic tape.

The tape on a guide or head is a thin cylindrical shell transported at speed V (Müftü &
Benson's model): D ∇⁴w + (ρV² − T) w_xx + k w + 2ρV w_xt + ρ w_tt = P, simply supported at
x = 0, L_x and free along y = 0, L_y. Finite differences give M a + G v + K w = F.

Layers: parameters → grid and operators → engines (static, Newmark, eigen) → studies.
All quantities are SI.
"""

from __future__ import annotations

from importlib import import_module as _import_module

from .core.errors import ConvergenceError, ParameterError, SupercriticalError  # noqa: F401
from .core.version import __version__  # noqa: F401
from .tape.parameters import TapeParameters, bending_rigidity, shell_stiffness  # noqa: F401

#: Public name -> submodule. Engines import scipy, so they load on first use: `import
#: gyroshell` and the CLI's refusals stay fast.
_LAZY: dict[str, str] = {
    # grid and operators
    "Grid": "tape.grid", "TapeModel": "tape.model",
    "bending_foundation": "tape.operators", "gyroscopic": "tape.operators", "mass": "tape.operators",
    "membrane": "tape.operators",
    "Harmonic": "tape.loads", "Ramp": "tape.loads", "gaussian_load": "tape.loads", "pressure_load": "tape.loads",
    "step": "tape.loads",
    # static and divergence
    "StaticSolution": "engines.static", "solve_static": "engines.static",
    "Divergence": "results.critical", "divergence": "engines.divergence",
    "divergence_speed": "engines.divergence",
    # time marching (Newmark, paper Eqs. 10-16) and its sparse LU back-ends
    "available_backends": "linalg.factorization", "factorize": "linalg.factorization",
    "Newmark": "engines.newmark", "NewmarkStabilityWarning": "engines.newmark", "march": "engines.newmark",
    "Snapshots": "results.transient", "TransientResult": "results.transient",
    # quadratic eigen-solver, critical speeds and speed sweeps
    "CriticalSpeeds": "results.critical", "critical_speed_eigen": "engines.critical",
    "critical_speeds": "engines.critical",
    "Modes": "results.modes", "frequencies": "engines.eigen", "modes": "engines.eigen",
    "InertiaFactor": "linalg.inertia", "factor_inertia": "linalg.inertia",
    "GyroscopicModes": "results.modes", "gyroscopic_modes": "engines.gyroscopic",
    "plot_sweep": "studies.sweep", "sweep": "studies.sweep",
    # parameter studies and saved results (xarray, Dask and matplotlib load on use)
    "load": "kinds", "save": "kinds",
    "StudyResult": "studies.parameter_study", "classify_stability": "studies.stability", "run_study": "studies.parameter_study",
    # damping, moving and intermittent loads, and the frequency response
    "Damping": "tape.damping",
    "FrequencyResponse": "engines.frequency_response", "ReducedModel": "engines.frequency_response", "direct_response": "engines.frequency_response",
    "frequency_response": "engines.frequency_response",
    "ContactWindows": "tape.moving_loads", "GaussianShape": "tape.moving_loads",
    "MovingLoad": "tape.moving_loads", "StraightPath": "tape.moving_loads", "UniformShape": "tape.moving_loads",
    "UserShape": "tape.moving_loads", "drum_heads": "tape.moving_loads",
}

__all__ = sorted(["ConvergenceError", "ParameterError", "SupercriticalError",
                  "TapeParameters", "bending_rigidity", "shell_stiffness", *_LAZY])


def __getattr__(name: str):
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'gyroshell' has no attribute {name!r}")
    value = getattr(_import_module(f".{module}", __name__), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return list(__all__)
