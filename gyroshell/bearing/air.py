"""Properties of the lubricating air film (SI), validated.

Defaults are dry air at 20 °C and one standard atmosphere: dynamic viscosity
μ = 1.81e-5 Pa·s and mean free path λ = 64 nm at p_a = 101325 Pa (e.g. White, *Viscous
Fluid Flow*, Table A.1 for μ; λ = μ/p_a · √(π R_air T/2) ≈ 65 nm, the value 64 nm used in
tape and slider bearing work since Fukui & Kaneko).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from ..errors import ParameterError
from ..parameters import _check_nonnegative, _check_positive

#: Dynamic viscosity of air at 20 °C, Pa·s.
AIR_VISCOSITY = 1.81e-5
#: Standard atmosphere, Pa.
AMBIENT_PRESSURE = 101325.0
#: Mean free path of air molecules at 20 °C and one atmosphere, m.
MEAN_FREE_PATH = 64.0e-9
#: Combined surface roughness below which tape and head touch, m.
ROUGHNESS = 20.0e-9


@dataclass(frozen=True)
class AirParameters:
    """The air film between tape and head.

    Parameters
    ----------
    viscosity : float
        Dynamic viscosity μ, Pa·s (> 0).
    ambient_pressure : float
        Ambient pressure p_a, Pa (> 0); the film pressure on every film boundary.
    mean_free_path : float
        Mean free path λ at p_a, m (>= 0); the slip flow factor is
        Q = 1 + 6 λ p_a / (p h). ``0`` turns slip off.
    compressible : bool
        Compressible (isothermal ideal gas, p h transported) or incompressible Reynolds
        equation (p h → h in the flux and the sources; slip then uses Q = 1 + 6 λ / h).
    roughness : float
        Combined surface roughness σ, m (> 0): the spacing never drops below it; where it
        would, the tape touches the head and a contact force holds it at h = σ.
    """

    viscosity: float = AIR_VISCOSITY
    ambient_pressure: float = AMBIENT_PRESSURE
    mean_free_path: float = MEAN_FREE_PATH
    compressible: bool = True
    roughness: float = ROUGHNESS

    def __post_init__(self) -> None:
        put = object.__setattr__
        put(self, "viscosity", _check_positive("viscosity", self.viscosity, "Pa*s"))
        put(self, "ambient_pressure",
            _check_positive("ambient_pressure", self.ambient_pressure, "Pa"))
        put(self, "mean_free_path",
            _check_nonnegative("mean_free_path", self.mean_free_path, "m"))
        put(self, "roughness", _check_positive("roughness", self.roughness, "m"))
        if not isinstance(self.compressible, bool):
            raise ParameterError(f"compressible must be True or False, got {self.compressible!r}")

    def replace(self, **changes: object) -> AirParameters:
        """A copy with some fields changed (validated again)."""
        return replace(self, **changes)
