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

#: Submodule -> the public names it defines. Engines import scipy, so they load on first use:
#: ``import gyroshell`` and the CLI's refusals stay fast.
_HOMES: dict[str, tuple[str, ...]] = {
    # the tape: grid, operators, loads, damping, moving heads
    "tape.grid": ("Grid",),
    "tape.material": ("BendingStiffness", "Layer", "laminate"),
    "tape.model": ("TapeModel",),
    "tape.operators": ("bending_foundation", "gyroscopic", "mass", "membrane"),
    "tape.loads": ("Harmonic", "Ramp", "gaussian_load", "pressure_load", "step"),
    "tape.damping": ("Damping",),
    "tape.moving_loads": ("ContactWindows", "GaussianShape", "MovingLoad", "StraightPath",
                          "UniformShape", "UserShape", "drum_heads"),
    # sparse factorizations
    "linalg.factorization": ("available_backends", "factorize"),
    "linalg.inertia": ("InertiaFactor", "factor_inertia"),
    # results
    "results.static": ("StaticSolution",),
    "results.transient": ("Snapshots", "TransientResult"),
    "results.modes": ("GyroscopicModes", "Modes"),
    "results.critical": ("CriticalSpeeds", "Divergence"),
    "results.frequency_response": ("FrequencyResponse",),
    # engines: static, Newmark (paper Eqs. 10-16), eigen-solvers, critical speeds, frf
    "engines.static": ("solve_static",),
    "engines.divergence": ("divergence", "divergence_speed"),
    "engines.newmark": ("Newmark", "NewmarkStabilityWarning", "march"),
    "engines.eigen": ("frequencies", "modes"),
    "engines.gyroscopic": ("gyroscopic_modes",),
    "engines.critical": ("critical_speed_eigen", "critical_speeds"),
    "engines.frequency_response": ("ReducedModel", "direct_response", "frequency_response"),
    # studies (xarray, Dask and matplotlib load on use) and saved results
    "studies.sweep": ("SweepResult", "plot_sweep", "sweep"),
    "studies.campbell": ("CampbellDiagram", "campbell"),
    "studies.parameter_study": ("StudyResult", "run_study"),
    "studies.stability": ("classify_stability",),
    "kinds": ("load", "save"),
}
_LAZY: dict[str, str] = {name: module for module, names in _HOMES.items() for name in names}

#: The subpackages, reachable as attributes after a plain ``import gyroshell`` (e.g.
#: ``gyroshell.plot.wireframe``, ``gyroshell.bearing.solve_steady``), loaded on first use.
_SUBPACKAGES = frozenset({"bearing", "core", "engines", "linalg", "plot", "reproduce",
                          "results", "studies", "tape"})

__all__ = sorted(["ConvergenceError", "ParameterError", "SupercriticalError",
                  "TapeParameters", "bending_rigidity", "shell_stiffness", *_LAZY])


def __getattr__(name: str):
    if name in _SUBPACKAGES:
        return _import_module(f".{name}", __name__)
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'gyroshell' has no attribute {name!r}")
    value = getattr(_import_module(f".{module}", __name__), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return list(__all__)
