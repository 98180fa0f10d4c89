"""Rarefaction: the Poiseuille flow factor Q(Kn) of a thin gas film.

The pressure-driven flux of a film of gap h is Q(Kn) h³ ∇p / (12μ) (no-slip: Q = 1); the
Couette flux is unchanged. The local Knudsen number is Kn = λ p_a / (p h) (λ the mean free
path at the ambient pressure p_a; λ/h in the incompressible film), and the inverse
Knudsen number of Fukui & Kaneko is D = √π / (2 Kn). Models (:data:`RAREFACTION_MODELS`):

``first-order``
    Q = 1 + 6 Kn, first-order slip (Burgdorfer, J. Basic Eng. 81:94, 1959).
``second-order``
    Q = 1 + 6 Kn + 6 Kn², second-order slip (Hsia & Domoto, J. Lubr. Technol. 105:120,
    1983).
``fukui-kaneko``
    Q = 6 Q_P(D) / D, the Poiseuille flow rate Q_P of the linearized Boltzmann equation
    (BGK, diffuse walls) by the three-piece fit of Fukui & Kaneko, J. Tribol. 112:78–83
    (1990):

    =================  =====================================================
    D >= 5             Q_P = D/6 + 1.0162 + 1.0653/D − 2.1354/D²
    0.15 <= D < 5      Q_P = 0.13852 D + 1.25087 + 0.15653/D − 0.00969/D²
    0.01 <= D < 0.15   Q_P = −2.22919 D + 2.10673 + 0.01653/D − 0.0000694/D²
    =================  =====================================================

    Each piece is written as a cubic in x = 1/D = 2 Kn/√π, Q = 6 Σ c_k x^(k+1) (so Kn = 0
    gives Q = 1 exactly, no 1/D), and the pieces, which differ by < 0.3 % at their breaks,
    are blended by a C³ partition of unity in ln D over ±:data:`BLEND_HALF_WIDTH` about
    each break (D·e^(±0.1), ±10 %): Q is smooth and increasing with an exact derivative.
    Below the fit's range (D < 0.01, Kn > 88.6, reached only transiently in Newton
    iterations or in a film that has closed), Q_P continues as its tangent in ln D,
    Q_P = Q_P(0.01) + s ln(0.01/D) with the fit's own slope s ≈ 0.287 there (blended in
    the same way): the logarithmic growth of the free-molecular Poiseuille flow rate
    (Cercignani), smooth and increasing without bound, so Q grows like Kn ln Kn.
    Limits: for large D, Q = 1 + 6 · 1.0162 · (2/√π) Kn + O(Kn²) ≈ 1 + 6.88 Kn (slip with
    the kinetic slip coefficient 1.147); Q_P has its Knudsen minimum ≈ 1.536 at D ≈ 0.99.
``none``
    Q = 1, no slip.
"""

from __future__ import annotations

import math

import numpy as np

from ..core import validation
from ._blend import smooth_step

RAREFACTION_MODELS = ("fukui-kaneko", "first-order", "second-order", "none")

#: Fukui & Kaneko's fit, (lowest D of the piece, (c₋₁, c₀, c₁, c₂)) with
#: Q_P = c₋₁ D + c₀ + c₁/D + c₂/D², largest D first.
FUKUI_KANEKO_FIT = ((5.0, (1.0 / 6.0, 1.0162, 1.0653, -2.1354)),
                    (0.15, (0.13852, 1.25087, 0.15653, -0.00969)),
                    (0.01, (-2.22919, 2.10673, 0.01653, -0.0000694)))
#: Half width, in ln D, of the bands over which neighbouring pieces are blended.
BLEND_HALF_WIDTH = 0.1
#: Largest Kn at which each model's Q stays within about a quarter of the linearized
#: Boltzmann Q (Fukui & Kaneko): first-order slip is 25 % low at Kn = 0.5 (the limit the
#: design note and Sakai et al., J. Tribol. 118:800, 1996, put on it); second-order slip is
#: 25 % high at Kn = 1.0 and no slip 25 % low at Kn = 0.05 (both by the same measure).
KNUDSEN_LIMITS = {"first-order": 0.5, "second-order": 1.0, "none": 0.05}

_SQRT_PI = math.sqrt(math.pi)
#: The velocity-slip length of each model at the walls, in (local) mean free paths: ζ of
#: the small-Kn limit Q ≈ 1 + 6 ζ Kn, the slip u_s = ζ λ ∂u/∂z whose Poiseuille flow that
#: term is. The readings' Couette shear μV/(h + 2ζλ) uses it (:func:`.readings.
#: shear_stress`): Maxwell's ζ = 1 for the slip models, the kinetic slip coefficient
#: 1.0162 · 2/√π = 1.147 for the Boltzmann flow rate (its large-D limit), 0 without slip.
SLIP_COEFFICIENTS = {"first-order": 1.0, "second-order": 1.0,
                     "fukui-kaneko": FUKUI_KANEKO_FIT[0][1][1] * 2.0 / _SQRT_PI, "none": 0.0}
#: Breaks of the fit in x = 1/D, increasing.
_BREAKS = tuple(1.0 / low for low, _ in FUKUI_KANEKO_FIT)


def _piece(coeffs, x):
    """Q = 6 x Q_P(1/x) of one fitted piece, and dQ/dx (x = 1/D)."""
    a, b, c, d = coeffs
    return (6.0 * (a + x * (b + x * (c + x * d))),
            6.0 * (b + x * (2.0 * c + x * 3.0 * d)))


def _extension():
    """(q0, s): Q_P and its slope in ln x at the fit's end x = 100 (D = 0.01)."""
    a, b, c, d = FUKUI_KANEKO_FIT[-1][1]
    x = _BREAKS[-1]
    return a / x + b + c * x + d * x * x, -a / x + c * x + 2.0 * d * x * x


_Q0, _SLOPE = _extension()


def _fukui_kaneko(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Q and dQ/dx of the blended fit and its extension, x = 1/D >= 0."""
    band = math.exp(BLEND_HALF_WIDTH)
    x1, x2, x3 = _BREAKS
    fits = [c for _, c in FUKUI_KANEKO_FIT]
    # Each piece is evaluated on its own support (its weight is 0 elsewhere), so that no
    # piece is ever taken where it overflows.
    qa, dqa = _piece(fits[0], np.minimum(x, x1 * band))
    qb, dqb = _piece(fits[1], np.clip(x, x1 / band, x2 * band))
    qc, dqc = _piece(fits[2], np.clip(x, x2 / band, x3 * band))
    xe = np.maximum(x, x3 / band)
    qp_e = _Q0 + _SLOPE * np.log(xe / x3)
    qe, dqe = 6.0 * xe * qp_e, 6.0 * (qp_e + _SLOPE)
    xs = np.maximum(x, x1 / band**2)
    t = np.log(xs)
    s1, d1 = smooth_step((t - math.log(x1)) / BLEND_HALF_WIDTH)
    s2, d2 = smooth_step((t - math.log(x2)) / BLEND_HALF_WIDTH)
    s3, d3 = smooth_step((t - math.log(x3)) / BLEND_HALF_WIDTH)
    to_x = 1.0 / (BLEND_HALF_WIDTH * xs)
    d1, d2, d3 = d1 * to_x, d2 * to_x, d3 * to_x
    wa, wb, wc, we = 1.0 - s1, s1 * (1.0 - s2), s2 * (1.0 - s3), s3
    q = wa * qa + wb * qb + wc * qc + we * qe
    dq = (wa * dqa + wb * dqb + wc * dqc + we * dqe
          - d1 * qa + (d1 * (1.0 - s2) - s1 * d2) * qb + (d2 * (1.0 - s3) - s2 * d3) * qc
          + d3 * qe)
    return q, dq


def poiseuille_flow_factor(model: str, kn) -> tuple[np.ndarray, np.ndarray]:
    """The Poiseuille flow factor Q(Kn) of a rarefaction model and its exact derivative.

    Parameters
    ----------
    model : str
        One of :data:`RAREFACTION_MODELS` (see the module notes for the formulas).
    kn : array_like
        Local Knudsen number Kn = λ p_a / (p h) (dimensionless, >= 0 for physical states;
        the polynomial models and the fit's first piece also accept Kn < 0).

    Returns
    -------
    Q, dQ_dKn : numpy.ndarray
        Both dimensionless, with the shape of ``kn``.

    Examples
    --------
    >>> q, dq = poiseuille_flow_factor("second-order", [0.0, 1.0])
    >>> q.tolist(), dq.tolist()
    ([1.0, 13.0], [6.0, 18.0])
    """
    model = validation.choice("rarefaction", model, RAREFACTION_MODELS)
    kn = np.asarray(kn, dtype=float)
    if model == "first-order":
        return 1.0 + 6.0 * kn, np.full_like(kn, 6.0)
    if model == "second-order":
        return 1.0 + 6.0 * kn * (1.0 + kn), 6.0 + 12.0 * kn
    if model == "none":
        return np.ones_like(kn), np.zeros_like(kn)
    to_x = 2.0 / _SQRT_PI
    q, dq_dx = _fukui_kaneko(to_x * kn)
    return q, to_x * dq_dx


def knudsen_range_warning(model: str, kn_max: float) -> str | None:
    """A one-line warning when a model is used beyond its range of Knudsen numbers, else
    ``None``.

    Parameters
    ----------
    model : str
        One of :data:`RAREFACTION_MODELS`.
    kn_max : float
        Largest local Knudsen number λ p_a / (p h) of the film (dimensionless).

    Notes
    -----
    The limits are :data:`KNUDSEN_LIMITS`: where the model's Q is off the linearized
    Boltzmann Q (``fukui-kaneko``) by about a quarter. ``fukui-kaneko`` never warns.
    """
    model = validation.choice("rarefaction", model, RAREFACTION_MODELS)
    kn_max = validation.real("kn_max", kn_max)
    limit = KNUDSEN_LIMITS.get(model)
    if limit is None or kn_max <= limit:
        return None
    name = {"first-order": "first-order slip (Q = 1 + 6 Kn)",
            "second-order": "second-order slip (Q = 1 + 6 Kn + 6 Kn²)",
            "none": "no slip (Q = 1)"}[model]
    return (f"{name} is used up to Kn = {kn_max:.3g}, beyond its validity (Kn <= {limit:g}): "
            "use --rarefaction fukui-kaneko (linearized Boltzmann flow factor)")
