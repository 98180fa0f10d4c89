"""Damping: the operator piece C of M a + (G + C) v + K w = F, accepted by every engine.

Two kinds, which add:

* viscous (air or material) damping c ∂w/∂t per unit area, c in N·s/m³: C = c W with W the
  nodal control areas, diagonal and positive like M (C = (c/ρ) M);
* Rayleigh damping C = a M + b K(V), a in 1/s and b in s, symmetric.

The damping force is written in the lab frame (the frame of the supports and of the air),
so C acts on ∂w/∂t, not on the material derivative. C is symmetric positive semi-definite:
the dissipated power vᵀCv is never negative.
"""

from __future__ import annotations

from dataclasses import dataclass

import scipy.sparse as sp

from ..core import validation
from .model import TapeModel


@dataclass(frozen=True)
class Damping:
    """Viscous plus Rayleigh damping: C = c W + a M + b K(V).

    Parameters
    ----------
    viscous : float
        c, N·s/m³ (>= 0): damping pressure c ∂w/∂t.
    mass_coefficient : float
        Rayleigh a, 1/s (>= 0).
    stiffness_coefficient : float
        Rayleigh b, s (>= 0).

    Examples
    --------
    >>> Damping(viscous=700.0)
    Damping(viscous=700.0, mass_coefficient=0.0, stiffness_coefficient=0.0)
    >>> Damping(viscous=-1.0)
    Traceback (most recent call last):
    ...
    gyroshell.ParameterError: damping must be >= 0 N*s/m^3, got -1
    """

    viscous: float = 0.0
    mass_coefficient: float = 0.0
    stiffness_coefficient: float = 0.0

    def __post_init__(self) -> None:
        put = object.__setattr__
        put(self, "viscous", validation.nonnegative("damping", self.viscous, "N*s/m^3"))
        put(self, "mass_coefficient",
            validation.nonnegative("mass_coefficient", self.mass_coefficient, "1/s"))
        put(self, "stiffness_coefficient",
            validation.nonnegative("stiffness_coefficient", self.stiffness_coefficient, "s"))

    @property
    def is_zero(self) -> bool:
        """True if C = 0."""
        return self.viscous == 0.0 and self.mass_coefficient == 0.0 \
            and self.stiffness_coefficient == 0.0

    def matrix(self, model: TapeModel, velocity: float) -> sp.csr_matrix:
        """C, kg/s (N·s/m per node): symmetric positive semi-definite, shape (n, n).

        Parameters
        ----------
        model : TapeModel
        velocity : float
            Tape speed V, m/s (the Rayleigh part uses K(V)).
        """
        diag = (self.viscous + self.mass_coefficient * model.params.density) * model.grid.areas
        C = sp.diags(diag, format="csr")
        if self.stiffness_coefficient:
            C = (C + self.stiffness_coefficient * model.K(velocity)).tocsr()
        return C


def viscous(c: float) -> Damping:
    """Viscous damping c ∂w/∂t, c in N·s/m³: C = c W (diagonal)."""
    return Damping(viscous=c)


def rayleigh(a: float, b: float) -> Damping:
    """Rayleigh damping C = a M + b K(V), a in 1/s, b in s."""
    return Damping(mass_coefficient=a, stiffness_coefficient=b)


def as_damping(damping: Damping | float | None) -> Damping:
    """A Damping from ``None`` (none), a number (viscous c, N·s/m³) or a Damping."""
    if damping is None:
        return Damping()
    if isinstance(damping, Damping):
        return damping
    return Damping(viscous=damping)


def damping_matrix(model: TapeModel, velocity: float,
                   damping: Damping | float | None) -> sp.csr_matrix | None:
    """C for ``damping`` (see :func:`as_damping`), or None if there is none."""
    damping = as_damping(damping)
    return None if damping.is_zero else damping.matrix(model, velocity)
