"""gyroshell: dynamics of a circumferentially moving magnetic tape.

The tape on a guide or head is a thin cylindrical shell transported at speed V (Müftü &
Benson's model): D ∇⁴w + (ρV² − T) w_xx + k w + 2ρV w_xt + ρ w_tt = P, simply supported at
x = 0, L_x and free along y = 0, L_y. Finite differences give M a + G v + K w = F.

Layers: parameters → grid and operators → engines (static, Newmark, eigen) → studies.
All quantities are SI.
"""

from __future__ import annotations

from .divergence import Divergence, divergence, divergence_speed
from .errors import ConvergenceError, ParameterError, SupercriticalError
from .grid import Grid
from .loads import Harmonic, Ramp, gaussian_load, pressure_load, step
from .model import TapeModel
from .operators import bending_foundation, gyroscopic, mass, membrane, stiffness
from .parameters import TapeParameters, bending_rigidity, shell_stiffness
from .static import StaticSolution, solve_static

__version__ = "0.1.0"

__all__ = [
    "ConvergenceError", "Divergence", "Grid", "Harmonic", "ParameterError", "Ramp",
    "StaticSolution", "SupercriticalError", "TapeModel", "TapeParameters",
    "bending_foundation", "bending_rigidity", "divergence", "divergence_speed",
    "gaussian_load", "gyroscopic", "mass", "membrane", "pressure_load", "shell_stiffness",
    "solve_static", "step", "stiffness",
]

# Time marching (Newmark, paper Eqs. 10-16) and its sparse LU back-ends.
from .factorization import available_backends, factorize  # noqa: E402
from .newmark import Newmark, NewmarkStabilityWarning, march  # noqa: E402
from .transient_result import Snapshots, TransientResult  # noqa: E402

__all__ += ["Newmark", "NewmarkStabilityWarning", "Snapshots", "TransientResult",
            "available_backends", "factorize", "march"]

# Quadratic eigen-solver, critical speeds and speed sweeps (issue #4).
from .critical import CriticalSpeeds, critical_speed_eigen, critical_speeds  # noqa: E402
from .eigen import Modes, frequencies, modes  # noqa: E402
from .inertia import InertiaFactor, factor_inertia  # noqa: E402
from .qep import GyroscopicModes, gyroscopic_modes  # noqa: E402
from .sweep import plot_sweep, sweep  # noqa: E402

__all__ += ["CriticalSpeeds", "GyroscopicModes", "InertiaFactor", "Modes",
            "critical_speed_eigen", "critical_speeds", "factor_inertia", "frequencies",
            "gyroscopic_modes", "modes", "plot_sweep", "sweep"]

# Parameter studies, saved results (issue #11); xarray, Dask and matplotlib load lazily.
from .persistence import load, save  # noqa: E402
from .study import StudyResult, classify_stability, run_study  # noqa: E402

__all__ += ["StudyResult", "classify_stability", "load", "run_study", "save"]

# Damping, moving and intermittent loads, and the frequency response (issue #10).
from .damping import Damping  # noqa: E402
from .frf import FrequencyResponse, ReducedModel, direct_response, frequency_response  # noqa: E402
from .moving_load import (  # noqa: E402
    ContactWindows,
    GaussianShape,
    MovingLoad,
    StraightPath,
    UniformShape,
    UserShape,
    drum_heads,
)

__all__ += ["ContactWindows", "Damping", "FrequencyResponse", "GaussianShape", "MovingLoad",
            "ReducedModel", "StraightPath", "UniformShape", "UserShape", "direct_response",
            "drum_heads", "frequency_response"]
