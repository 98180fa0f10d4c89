"""The tape's material: bending stiffnesses of an isotropic, orthotropic or layered tape.

A thin orthotropic plate with its axes along (x) and across (y) the tape stores the bending
energy density

    ½ [D11 w_xx² + 2 D12 w_xx w_yy + D22 w_yy² + 4 D66 w_xy²]       (N·m × 1/m² = J/m²),

positive definite when D11 > 0, D22 > 0, D66 > 0 and D12² < D11 D22. An isotropic plate
has D11 = D22 = D, D12 = νD, D66 = (1 − ν)D/2.

Homogeneous orthotropic tape (engineering constants E_x, E_y, G_xy, ν_xy, thickness c): the
plane-stress reduced stiffnesses, Pa,

    Q11 = E_x / (1 − ν_xy ν_yx),  Q22 = E_y / (1 − ν_xy ν_yx),  Q12 = ν_xy E_y / (1 − ν_xy ν_yx),
    Q66 = G_xy,                    ν_yx = ν_xy E_y / E_x,

positive definite when the moduli are positive and ν_xy² < E_x / E_y; then D = Q c³/12 and
the membrane stiffness along the tape A11 = Q11 c.

Layered tape (classical lamination theory, layers bottom up, each orthotropic with its axes
along and across the tape): with z measured from the mid-plane and layer i on
z_{i−1} < z < z_i,

    A = Σ Q_i (z_i − z_{i−1}),  B = ½ Σ Q_i (z_i² − z_{i−1}²),  D = ⅓ Σ Q_i (z_i³ − z_{i−1}³).

A symmetric stack has B = 0 and D about the mid-plane. An unsymmetric one couples bending
and stretching (B ≠ 0); it is modelled by the reduced bending stiffness

    D* = D − B A⁻¹ B

(separately for the (11, 12, 22) block and for 66), the stiffness of a plate whose in-plane
resultants stay zero, i.e. free to stretch in its plane: with N = A ε + B κ = 0,
M = B ε + D κ = D* κ. D* does not depend on the reference plane; where a neutral plane
exists (B = 0 about it, e.g. layers of one material ratio) D* is D about that plane. The
tape's in-plane forces are the prescribed tension T only, so this is the stiffness its
bending sees; the coupling of the wrap's hoop strain w/R to the curvature (a B term in the
shell stiffness) is left out, as the shell model's k = A11/R² already simplifies the
membrane.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import asdict, dataclass, field

from ..core import validation
from ..core.errors import ParameterError

__all__ = ["BendingStiffness", "Lamination", "Layer", "laminate", "layers_from",
           "orthotropic_bending", "reduced_stiffness"]


def _check_poisson_xy(name: str, poisson_xy: object, ex: float, ey: float) -> float:
    """ν_xy with ν_xy² < E_x/E_y (a positive-definite plane-stress compliance)."""
    bound = math.sqrt(ex / ey) if ey > 0 else math.inf
    try:
        return validation.real(name, poisson_xy, low=-bound, high=bound, low_open=True,
                               high_open=True)
    except ParameterError as exc:
        raise ParameterError(f"{exc} (nu_xy^2 < E_x/E_y = {ex / ey:.4g}: a positive-definite "
                             "compliance)") from None


#: Names of E_x, E_y, G_xy, ν_xy in the messages of a homogeneous tape's parameters.
TAPE_NAMES = ("youngs_modulus", "youngs_modulus_y", "shear_modulus", "poisson")
#: ... and of a layer's fields.
LAYER_NAMES = ("youngs_modulus_x", "youngs_modulus_y", "shear_modulus", "poisson_xy")


def reduced_stiffness(youngs_modulus_x: float, youngs_modulus_y: float, shear_modulus: float,
                      poisson_xy: float, *, names: tuple[str, ...] = TAPE_NAMES
                      ) -> tuple[float, float, float, float]:
    """Plane-stress reduced stiffnesses (Q11, Q22, Q12, Q66), Pa, of an orthotropic sheet.

    ``names`` are the parameter names of E_x, E_y, G_xy, ν_xy in the messages.

    Examples
    --------
    >>> [f"{q:.4g}" for q in reduced_stiffness(8e9, 4e9, 2e9, 0.4)]
    ['8.7e+09', '4.348e+09', '1.739e+09', '2e+09']
    """
    ex = validation.positive(names[0], youngs_modulus_x, "Pa")
    ey = validation.positive(names[1], youngs_modulus_y, "Pa")
    g = validation.positive(names[2], shear_modulus, "Pa")
    nu = _check_poisson_xy(names[3], poisson_xy, ex, ey)
    det = 1.0 - nu * (nu * ey / ex)
    q = (ex / det, ey / det, nu * ey / det, g)
    for label, value in zip(("Q11", "Q22", "Q66"), (q[0], q[1], q[3]), strict=True):
        validation.finite_scale(label, value, "Pa", what=", ".join(names))
    return q


@dataclass(frozen=True)
class BendingStiffness:
    """The plate's bending stiffnesses (D11, D22, D12, D66), N·m, axes along and across.

    Validated: all finite, D11, D22, D66 > 0 and D12² < D11 D22 (positive definite).
    ``poisson`` is set (by :meth:`isotropic`) for an isotropic plate, so that the operators
    assemble its energy in the factored form D [...] of the isotropic plate, bit for bit; it
    does not take part in comparisons.

    Examples
    --------
    >>> BendingStiffness.isotropic(2.0, 0.25)
    BendingStiffness(D11=2.0, D22=2.0, D12=0.5, D66=0.75)
    >>> BendingStiffness(1.0, 1.0, 2.0, 0.5)
    Traceback (most recent call last):
    ...
    gyroshell.ParameterError: bending_stiffness must be positive definite: D12^2 < D11 D22 ...
    """

    D11: float
    D22: float
    D12: float
    D66: float
    poisson: float | None = field(default=None, compare=False, repr=False)

    def __post_init__(self) -> None:
        put = object.__setattr__
        for name in ("D11", "D22", "D66"):
            value = validation.positive(f"bending_stiffness {name}", getattr(self, name), "N*m")
            put(self, name, validation.finite_scale(f"bending_stiffness {name}", value, "N*m"))
        d12 = validation.real("bending_stiffness D12", self.D12, unit="N*m")
        put(self, "D12", d12)
        if not d12 * d12 < self.D11 * self.D22:
            raise ParameterError(
                "bending_stiffness must be positive definite: D12^2 < D11 D22 "
                f"(|D12| < {math.sqrt(self.D11 * self.D22):.6g} N*m), got D12 = {d12:g} N*m")

    @classmethod
    def isotropic(cls, rigidity: float, poisson: float) -> BendingStiffness:
        """D11 = D22 = D, D12 = νD, D66 = (1 − ν)D/2 for the rigidity D (N·m) and ratio ν."""
        return cls(rigidity, rigidity, poisson * rigidity, (1.0 - poisson) * rigidity / 2.0,
                   poisson=poisson)

    def as_tuple(self) -> tuple[float, float, float, float]:
        """(D11, D22, D12, D66), N·m."""
        return self.D11, self.D22, self.D12, self.D66

    @property
    def edge(self) -> float:
        """D11 − D12²/D22, N·m: the rigidity along a free edge (M_y = 0), also that of a
        narrow strip free to curve anticlastically."""
        if self.poisson is not None:
            return (1.0 - self.poisson**2) * self.D11
        return self.D11 - self.D12 * self.D12 / self.D22

    @property
    def ratios(self) -> tuple[float, float, float, float]:
        """(D22, D12, 4 D66, D11 − D12²/D22) / D11: the energy's terms relative to D11.

        For an isotropic plate exactly (1, ν, 2(1 − ν), 1 − ν²), the factors of the
        isotropic energy, so that D11 × (...) reproduces its operators bit for bit.
        """
        nu = self.poisson
        if nu is not None:
            return 1.0, nu, 2 * (1 - nu), 1 - nu**2
        d = self.D11
        return self.D22 / d, self.D12 / d, 4.0 * self.D66 / d, self.edge / d


def orthotropic_bending(youngs_modulus_x: float, youngs_modulus_y: float,
                        shear_modulus: float, poisson_xy: float, thickness: float
                        ) -> BendingStiffness:
    """D = Q c³/12 of a homogeneous orthotropic sheet of thickness c (m), N·m."""
    c = validation.positive("thickness", thickness, "m")
    q11, q22, q12, q66 = reduced_stiffness(youngs_modulus_x, youngs_modulus_y, shear_modulus,
                                           poisson_xy)
    c3 = c**3 / 12.0
    return BendingStiffness(q11 * c3, q22 * c3, q12 * c3, q66 * c3)


@dataclass(frozen=True)
class Layer:
    """One orthotropic layer of the tape (its axes along x and across y the tape).

    Parameters
    ----------
    thickness : float
        Layer thickness, m (> 0).
    youngs_modulus_x, youngs_modulus_y : float
        Young's moduli along and across the tape, Pa (> 0).
    shear_modulus : float
        In-plane shear modulus G_xy, Pa (> 0).
    poisson_xy : float
        Major Poisson ratio ν_xy (ν_yx = ν_xy E_y/E_x), with ν_xy² < E_x/E_y.
    density : float
        Volume density, kg/m³ (> 0).

    Examples
    --------
    >>> base = Layer(6e-6, 8e9, 5e9, 2e9, 0.35, 1360.0)
    >>> Layer(**base.as_dict()) == base
    True
    >>> Layer(6e-6, 8e9, 5e9, 2e9, 1.5, 1360.0)
    Traceback (most recent call last):
    ...
    gyroshell.ParameterError: poisson_xy must be in (-1.26491, 1.26491), got 1.5 (nu_xy^2 < ...
    """

    thickness: float
    youngs_modulus_x: float
    youngs_modulus_y: float
    shear_modulus: float
    poisson_xy: float
    density: float

    def __post_init__(self) -> None:
        self._validate("")

    def _validate(self, prefix: str) -> None:
        put = object.__setattr__
        put(self, "thickness",
            validation.positive(f"{prefix}thickness", self.thickness, "m"))
        for name in ("youngs_modulus_x", "youngs_modulus_y", "shear_modulus"):
            put(self, name, validation.positive(f"{prefix}{name}", getattr(self, name), "Pa"))
        put(self, "poisson_xy", _check_poisson_xy(f"{prefix}poisson_xy", self.poisson_xy,
                                                  self.youngs_modulus_x, self.youngs_modulus_y))
        put(self, "density", validation.positive(f"{prefix}density", self.density, "kg/m^3"))
        self.stiffness(prefix)

    def stiffness(self, prefix: str = "") -> tuple[float, float, float, float]:
        """(Q11, Q22, Q12, Q66), Pa (see :func:`reduced_stiffness`)."""
        return reduced_stiffness(self.youngs_modulus_x, self.youngs_modulus_y,
                                 self.shear_modulus, self.poisson_xy,
                                 names=tuple(prefix + n for n in LAYER_NAMES))

    def as_dict(self) -> dict[str, float]:
        """The fields as plain floats (JSON-ready; ``Layer(**d)`` rebuilds the layer)."""
        return asdict(self)


def layers_from(value: object) -> tuple[Layer, ...]:
    """A validated, non-empty stack (bottom up) from Layers or mappings of their fields."""
    if isinstance(value, (str, bytes, Mapping)) or not isinstance(value, Sequence):
        raise ParameterError("layers must be a non-empty sequence of Layer (bottom up), "
                             f"got {type(value).__name__}")
    if len(value) == 0:
        raise ParameterError("layers must hold at least one layer, got an empty stack")
    out = []
    for i, item in enumerate(value):
        if isinstance(item, Mapping):
            try:
                item = Layer(**item)
            except TypeError:
                raise ParameterError(
                    f"layers[{i}] must have exactly the fields thickness, youngs_modulus_x, "
                    f"youngs_modulus_y, shear_modulus, poisson_xy, density; got "
                    f"{sorted(item)}") from None
            except ParameterError as exc:
                raise ParameterError(f"layers[{i}].{exc}") from None
        elif not isinstance(item, Layer):
            raise ParameterError(f"layers[{i}] must be a Layer or a mapping of its fields, "
                                 f"got {type(item).__name__}")
        out.append(item)
    return tuple(out)


@dataclass(frozen=True)
class Lamination:
    """Classical lamination theory of a stack (z from the mid-plane), SI.

    Attributes
    ----------
    A : tuple
        (A11, A22, A12, A66), N/m.
    B : tuple
        (B11, B22, B12, B66), N (zero for a symmetric stack).
    D : tuple
        (D11, D22, D12, D66) about the mid-plane, N·m.
    thickness : float
        Σ t_i, m.
    areal_density : float
        Σ ρ_i t_i, kg/m².
    """

    A: tuple[float, float, float, float]
    B: tuple[float, float, float, float]
    D: tuple[float, float, float, float]
    thickness: float
    areal_density: float

    @property
    def bending(self) -> BendingStiffness:
        """D* = D − B A⁻¹ B (the (11, 12, 22) block and 66 apart), N·m: D for B = 0."""
        (a11, a22, a12, a66), (b11, b22, b12, b66) = self.A, self.B
        d11, d22, d12, d66 = self.D
        if not any(self.B):
            return BendingStiffness(d11, d22, d12, d66)
        det = a11 * a22 - a12 * a12
        # A⁻¹ of the block [[a11, a12], [a12, a22]]; then B A⁻¹ B, B = [[b11, b12], [b12, b22]]
        i11, i22, i12 = a22 / det, a11 / det, -a12 / det
        c11, c12 = b11 * i11 + b12 * i12, b11 * i12 + b12 * i22
        c21, c22 = b12 * i11 + b22 * i12, b12 * i12 + b22 * i22
        return BendingStiffness(d11 - (c11 * b11 + c12 * b12), d22 - (c21 * b12 + c22 * b22),
                                d12 - (c11 * b12 + c12 * b22), d66 - b66 * b66 / a66)

    @property
    def effective_modulus(self) -> float:
        """In-plane E_x of the stack, (A11 − A12²/A22)/c, Pa."""
        a11, a22, a12, _ = self.A
        return (a11 - a12 * a12 / a22) / self.thickness

    @property
    def effective_poisson(self) -> float:
        """In-plane ν_xy of the stack, A12/A22."""
        return self.A[2] / self.A[1]


def laminate(layers: Sequence[Layer]) -> Lamination:
    """A, B, D, thickness and areal density of a stack, bottom up (see module notes).

    Examples
    --------
    >>> one = laminate([Layer(10e-6, 6e9, 6e9, 2.5e9, 0.2, 1400.0)])
    >>> [f"{d:.4g}" for d in one.D], one.B
    (['5.208e-07', '5.208e-07', '1.042e-07', '2.083e-07'], (0.0, 0.0, 0.0, 0.0))
    """
    stack = layers_from(layers)
    total = sum(layer.thickness for layer in stack)
    z = [-0.5 * total]
    for layer in stack:
        z.append(z[-1] + layer.thickness)
    z[-1] = 0.5 * total
    A, B, D = [0.0] * 4, [0.0] * 4, [0.0] * 4
    for i, layer in enumerate(stack):
        q = layer.stiffness(f"layers[{i}].")
        lo, hi = z[i], z[i + 1]
        for j in range(4):
            A[j] += q[j] * (hi - lo)
            B[j] += q[j] * (hi * hi - lo * lo) / 2.0
            D[j] += q[j] * (hi**3 - lo**3) / 3.0
    if _symmetric(stack):
        B = [0.0] * 4
    density = sum(layer.density * layer.thickness for layer in stack)
    lam = Lamination(tuple(A), tuple(B), tuple(D), total, density)
    for name, value, unit in (("stack D11", D[0], "N*m"), ("stack A11", A[0], "N/m"),
                              ("stack areal density", density, "kg/m^2")):
        validation.finite_scale(name, value, unit, what="the layers")
    return lam


def _symmetric(stack: tuple[Layer, ...]) -> bool:
    """True if the stack reads the same top down (B = 0 exactly, not to round-off)."""
    return all(a == b for a, b in zip(stack, reversed(stack), strict=True))
