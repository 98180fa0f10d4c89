"""Finite-volume Reynolds equation for the air film, with its exact sparse Jacobian.

The film pressure p(x, y, t) in the gap h between the head and the tape moving at V along
+x obeys

    ∇·(Γ ∇p) − 6μV ∂(φ_c)/∂x − 12μ ∂φ/∂t = 0,

compressible: φ = p h, Γ = p h³ Q(Kn) φ_x(h/σ), Kn = λ p_a / (p h), φ_c = p (h + σ Φ_s);
incompressible: φ = h, Γ = h³ Q(λ/h) φ_x(h/σ), φ_c = h + σ Φ_s. Q is the rarefaction
model's Poiseuille flow factor (:mod:`.rarefaction`, ``air.rarefaction``: first-order slip
Q = 1 + 6 Kn by default, so Γ = p h³ + 6 λ p_a h²); φ_x and Φ_s are Patir & Cheng's
pressure and shear flow factors of the roughness σ (:mod:`.flow_factors`,
``air.flow_factors``; φ_x = 1, Φ_s = 0 by default). The roughness is the tape's, the moving
surface's: its shear flow adds to the Couette flux. The squeeze term carries the nominal h.

Node-centred control volumes on the tape's grid; every face carries one flux
F = −Γ ∂p/∂n + 6μV φ_c n_x (12μ times the volume or mass flux per unit face length), added
to the node on one side and subtracted from the other, so the discrete fluxes balance
exactly (conservation to round-off). The compressible Couette term is exponentially fitted
(Scharfetter–Gummel): across each x-face the 1-D flux problem Γ p' − c p = const with
c = 6μV (h̄ + σ Φ_s(h̄/σ)) is solved exactly,

    F = (Γ/Δx) [B(−Pe) p_L − B(Pe) p_R],    Pe = c Δx / Γ,    B(z) = z / (eᶻ − 1),

which is central (second order) for small cell Péclet numbers and upwind for large ones,
so the scheme stays monotone at any bearing number. Incompressible Couette terms carry h
only (a source in p) and are taken at the face centre. Face values of p and h are nodal
averages (Q, φ_x and Φ_s are taken at the face's p̄ and h̄). p = p_a is imposed on every
film boundary (the ends of the domain and, in 2-D, the tape's lateral edges).

The grid may be graded (:mod:`.mesh`): each face's flux uses its own node distance, each
x-face has the length of its node's control width across (and each y-face the control
width along), and each control volume is the product of its node's widths; the fluxes
still balance exactly, whatever the spacing.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ..core import validation
from ..core.errors import ParameterError
from .air import ROUGHNESS_RANGE, AirParameters, flow_factors_for
from .flow_factors import pressure_flow_factor, shear_flow_factor
from .rarefaction import poiseuille_flow_factor

#: |z| below which B(z) and B'(z) come from their Taylor series (cancellation-free).
_SERIES_LIMIT = 0.05
#: |z| beyond which B(z) is taken as its limits, B(z) = −z for z < 0 and 0 for z > 0 (exact
#: to double precision: the neglected terms are below 600 e⁻⁶⁰⁰ ≈ 1e-258), without overflow.
_PECLET_CLIP = 600.0


def bernoulli(z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """B(z) = z / (eᶻ − 1) and its derivative B'(z), elementwise (dimensionless)."""
    z_in = np.asarray(z, dtype=float)
    z = np.clip(z_in, -_PECLET_CLIP, _PECLET_CLIP)
    small = np.abs(z) < _SERIES_LIMIT
    zs = np.where(small, 1.0, z)                   # keeps the direct formula finite
    b = zs / np.expm1(zs)
    db = b * (1.0 / zs + 1.0 / np.expm1(-zs))
    z2 = z * z
    b_series = 1 - z / 2 + z2 / 12 * (1 - z2 / 60 * (1 - z2 / 42 * (1 - z2 / 40)))
    db_series = -0.5 + z / 6 * (1 - z2 / 30 * (1 - z2 / 28 * (1 - z2 / 30)))
    b, db = np.where(small, b_series, b), np.where(small, db_series, db)
    low, high = z_in < -_PECLET_CLIP, z_in > _PECLET_CLIP
    return (np.where(low, -z_in, np.where(high, 0.0, b)),
            np.where(low, -1.0, np.where(high, 0.0, db)))


@dataclass
class FaceFluxes:
    """Fluxes through one family of faces and their partial derivatives.

    ``flux`` is F (positive from the left/lower node to the right/upper one) per unit face
    length; ``d_pl``, ``d_pr``, ``d_h`` its derivatives by the two nodal pressures and by
    either nodal spacing (both enter only through the face average h̄).
    """

    flux: np.ndarray
    d_pl: np.ndarray
    d_pr: np.ndarray
    d_h: np.ndarray


def face_fluxes(pl, pr, hl, hr, spacing: float, velocity: float, air: AirParameters, *,
                roughness: float | None = None) -> FaceFluxes:
    """Fluxes F through faces between nodes (pl, hl) and (pr, hr) a distance ``spacing`` (m)
    apart, with the tape moving at ``velocity`` (m/s) along the face normal (0 across y).

    ``roughness`` is the σ (m) of the flow factors, needed when ``air.flow_factors`` is
    ``"patir-cheng"`` (ignored otherwise). Pressures (Pa) must be positive in the
    compressible film unless the model is first-order slip without flow factors.
    """
    air = flow_factors_for(air, roughness is not None)
    if air.rarefaction == "first-order" and air.flow_factors == "none":
        return _slip_fluxes(pl, pr, hl, hr, spacing, velocity, air)
    return _model_fluxes(pl, pr, hl, hr, spacing, velocity, air,
                         _flow_roughness(air, roughness))


def _flow_roughness(air: AirParameters, roughness: float | None) -> float | None:
    """The flow factors' σ, checked (m), or None when they are off."""
    if air.flow_factors == "none":
        return None
    low, high = ROUGHNESS_RANGE
    if roughness is None:
        raise ParameterError(f"roughness must be given (in [{low:g}, {high:g}] m) with "
                             f"flow_factors {air.flow_factors!r}, got None")
    return validation.real("roughness", roughness, low=low, high=high, unit="m")


def _slip_fluxes(pl, pr, hl, hr, spacing, velocity, air) -> FaceFluxes:
    """First-order slip, smooth surfaces: Γ = p h³ + 6 λ p_a h² (or h³ + 6 λ h²)."""
    mu, lam, pa = air.viscosity, air.mean_free_path, air.ambient_pressure
    h = 0.5 * (hl + hr)
    c = 6.0 * mu * velocity * h
    if not air.compressible:
        gamma = h**3 + 6.0 * lam * h**2
        dgamma_dh = 0.5 * (3.0 * h**2 + 12.0 * lam * h)
        grad = (pr - pl) / spacing
        flux = -gamma * grad + c
        d_h = -dgamma_dh * grad + 3.0 * mu * velocity
        g = gamma / spacing
        return FaceFluxes(flux, g, -g, d_h)
    p = 0.5 * (pl + pr)
    gamma = p * h**3 + 6.0 * lam * pa * h**2
    dgamma_dp = 0.5 * h**3
    dgamma_dh = 0.5 * (3.0 * p * h**2 + 12.0 * lam * pa * h)
    return _fitted_fluxes(pl, pr, spacing, gamma, c, dgamma_dp, dgamma_dh,
                          3.0 * mu * velocity)


def _fitted_fluxes(pl, pr, spacing, gamma, c, dgamma_dp, dgamma_dh, dc_dh) -> FaceFluxes:
    """The compressible film's Scharfetter–Gummel face flux (module notes) of the face
    coefficients Γ and c, and its derivatives from theirs by the face's mean p and h
    (∂Γ/∂p_L = ∂Γ/∂p_R = ``dgamma_dp``, by either nodal h ``dgamma_dh``; c's by either
    nodal h ``dc_dh``)."""
    peclet = c * spacing / gamma
    b_plus, db_plus = bernoulli(peclet)
    b_minus, db_minus = bernoulli(-peclet)
    g = gamma / spacing
    flux = g * (b_minus * pl - b_plus * pr)
    f_gamma = ((b_minus + peclet * db_minus) * pl - (b_plus - peclet * db_plus) * pr) / spacing
    f_c = -db_minus * pl - db_plus * pr
    d_pl = g * b_minus + f_gamma * dgamma_dp
    d_pr = -g * b_plus + f_gamma * dgamma_dp
    d_h = f_gamma * dgamma_dh + f_c * dc_dh
    return FaceFluxes(flux, d_pl, d_pr, d_h)


def _model_fluxes(pl, pr, hl, hr, spacing, velocity, air, sigma) -> FaceFluxes:
    """Any rarefaction model and flow factors: Γ = p h³ Q(Kn) φ_x (or h³ Q(λ/h) φ_x) and
    the Couette flux 6μV (h̄ + σ Φ_s) (times p in the compressible film)."""
    mu, lam, pa = air.viscosity, air.mean_free_path, air.ambient_pressure
    h = 0.5 * (hl + hr)
    if sigma is None:
        phi, dphi, h_c, dhc = 1.0, 0.0, h, 1.0
    else:
        phi, dphi = pressure_flow_factor(air.flow_factors, h / sigma)
        dphi = dphi / sigma
        shear, dshear = shear_flow_factor(air.flow_factors, h / sigma)
        h_c, dhc = h + sigma * shear, 1.0 + dshear
    c = 6.0 * mu * velocity * h_c
    dc_dh = 3.0 * mu * velocity * dhc                 # by either nodal spacing
    if not air.compressible:
        kn = lam / h if air.rarefaction != "none" else np.zeros_like(h)
        q, dq = poiseuille_flow_factor(air.rarefaction, kn)
        gamma = h**3 * q * phi
        # dKn/dh̄ = −Kn/h̄
        dgamma_dh = 0.5 * (h**2 * (3.0 * q - dq * kn) * phi + h**3 * q * dphi)
        grad = (pr - pl) / spacing
        flux = -gamma * grad + c
        d_h = -dgamma_dh * grad + dc_dh
        g = gamma / spacing
        return FaceFluxes(flux, g, -g, d_h)
    p = 0.5 * (pl + pr)
    kn = lam * pa / (p * h) if air.rarefaction != "none" else np.zeros_like(p * h)
    q, dq = poiseuille_flow_factor(air.rarefaction, kn)
    gamma = p * h**3 * q * phi
    # dKn/dp̄ = −Kn/p̄, dKn/dh̄ = −Kn/h̄; each nodal p or h moves p̄ or h̄ by one half
    dgamma_dp = 0.5 * h**3 * (q - dq * kn) * phi
    dgamma_dh = 0.5 * (p * h**2 * (3.0 * q - dq * kn) * phi + p * h**3 * q * dphi)
    return _fitted_fluxes(pl, pr, spacing, gamma, c, dgamma_dp, dgamma_dh, dc_dh)


def scatter_map(rows: np.ndarray, cols: np.ndarray, shape: tuple[int, int]
                ) -> tuple[sp.csr_matrix, np.ndarray]:
    """The CSR pattern of entries (rows, cols) (duplicates summed, indices sorted) and
    where each entry lands in its data array: ``np.bincount(map, weights=values,
    minlength=nnz)`` assembles values given per entry."""
    m = sp.coo_matrix((np.ones(len(rows)), (rows, cols)), shape=shape).tocsr()
    m.sum_duplicates()
    m.sort_indices()
    lin = rows.astype(np.int64) * shape[1] + cols
    key = np.repeat(np.arange(shape[0]), np.diff(m.indptr)).astype(np.int64) \
        * shape[1] + m.indices
    return m, np.searchsorted(key, lin)


def _dual(h: np.ndarray) -> np.ndarray:
    """Control widths of the nodes between intervals h (half intervals at the ends)."""
    w = np.empty(len(h) + 1)
    w[0], w[-1] = 0.5 * h[0], 0.5 * h[-1]
    w[1:-1] = 0.5 * (h[:-1] + h[1:])
    return w


class Film:
    """The discrete Reynolds equation on an (nx + 1) × nc node array.

    Parameters
    ----------
    nx : int
        Intervals along x (the ends i = 0, nx are film boundaries).
    nc : int
        Node columns across the width: 1 for an infinitely wide tape, ny + 1 in 2-D (the
        columns j = 0, ny are the tape's free edges, film boundaries).
    hx : float or numpy.ndarray
        Node spacing along x, m: one value, or the nx intervals of a graded grid.
    hy : float, numpy.ndarray or None
        Node spacing across y, m (one value or the ny intervals); ``None`` for the
        infinitely wide tape (per unit width).
    air : AirParameters
    velocity : float
        Tape speed V, m/s.
    roughness : float or None
        RMS roughness σ of the tape's surface seen by the flow factors, m (in
        [1e-12, 1e-4]); required when ``air.flow_factors`` is ``"patir-cheng"``, ignored
        otherwise.

    Notes
    -----
    The pressure unknowns are the film-interior nodes (:attr:`pressure_index` >= 0);
    spacings h are given on every node. ``residual`` rows are the node balances
    Σ_faces F·(face length) + 12μ A (φ − φ_old)/Δt, in Pa·m³ (1-D: per unit width Pa·m²).
    """

    def __init__(self, nx: int, nc: int, hx: float, hy: float | None, air: AirParameters,
                 velocity: float, *, roughness: float | None = None) -> None:
        self.nx, self.nc = nx, nc
        air = flow_factors_for(air, roughness is not None)
        self.roughness = _flow_roughness(air, roughness)
        self.hx = np.broadcast_to(np.asarray(hx, dtype=float), (nx,)).copy()
        self.hy = (None if hy is None
                   else np.broadcast_to(np.asarray(hy, dtype=float), (nc - 1,)).copy())
        self.air, self.velocity = air, velocity
        shape = (nx + 1, nc)
        interior = np.zeros(shape, dtype=bool)
        if nc == 1:
            interior[1:-1, :] = True
        else:
            interior[1:-1, 1:-1] = True
        self.interior = interior
        pid = np.full(shape, -1)
        pid[interior] = np.arange(int(interior.sum()))
        self.pressure_index = pid
        self.size = int(interior.sum())
        #: Control widths of the nodes along x and (2-D) across y, m
        self.x_widths = _dual(self.hx)
        self.y_widths = np.ones(1) if hy is None else _dual(self.hy)
        #: Length of the x-faces of each node column (m; 1 per unit width in 1-D) and the
        #: control area of every node (m², m per unit width in 1-D), shape (nx + 1, nc)
        self.x_face_length = self.y_widths
        self.cell_area = np.outer(self.x_widths, self.y_widths)
        self._pattern = self._build_pattern()

    # ----- sparsity pattern, computed once --------------------------------------------
    def _face_pairs(self):
        pid = self.pressure_index
        pairs = [(pid[:-1, :].ravel(), pid[1:, :].ravel(), "x")]
        if self.nc > 1:
            pairs.append((pid[:, :-1].ravel(), pid[:, 1:].ravel(), "y"))
        return pairs

    def _build_pattern(self):
        """Row/column indices of every Jacobian contribution, and their CSR positions."""
        rows_p, cols_p, rows_h, cols_h = [], [], [], []
        nid = np.arange((self.nx + 1) * self.nc).reshape(self.nx + 1, self.nc)
        node_pairs = [(nid[:-1, :].ravel(), nid[1:, :].ravel())]
        if self.nc > 1:
            node_pairs.append((nid[:, :-1].ravel(), nid[:, 1:].ravel()))
        for (left, right, _), (nl, nr) in zip(self._face_pairs(), node_pairs, strict=True):
            # d/dpL, d/dpR on rows L (+) and R (−); d/dh on node columns (global node ids).
            rows_p += [left, left, right, right]
            cols_p += [left, right, left, right]
            rows_h += [left, left, right, right]
            cols_h += [nl, nr, nl, nr]
        rows_p, cols_p = np.concatenate(rows_p), np.concatenate(cols_p)
        rows_h, cols_h = np.concatenate(rows_h), np.concatenate(cols_h)
        keep_p = (rows_p >= 0) & (cols_p >= 0)
        keep_h = rows_h >= 0
        n_nodes = (self.nx + 1) * self.nc
        diag = np.arange(self.size)
        node_of_p = nid[self.interior]

        jp, map_p = scatter_map(np.concatenate([rows_p[keep_p], diag]),
                                np.concatenate([cols_p[keep_p], diag]), (self.size, self.size))
        jh, map_h = scatter_map(np.concatenate([rows_h[keep_h], diag]),
                                np.concatenate([cols_h[keep_h], node_of_p]),
                                (self.size, n_nodes))
        return dict(keep_p=keep_p, keep_h=keep_h, jp=jp, jh=jh, map_p=map_p, map_h=map_h,
                    node_of_p=node_of_p)

    # ----- evaluation -------------------------------------------------------------------
    def fluxes(self, P: np.ndarray, H: np.ndarray) -> list[FaceFluxes]:
        """Face fluxes of nodal fields P (Pa) and H (m), shape (nx + 1, nc): x-faces first,
        then (2-D) y-faces; each per unit face length."""
        out = [face_fluxes(P[:-1], P[1:], H[:-1], H[1:], self.hx[:, None], self.velocity,
                           self.air, roughness=self.roughness)]
        if self.nc > 1:
            out.append(face_fluxes(P[:, :-1], P[:, 1:], H[:, :-1], H[:, 1:],
                                   self.hy[None, :], 0.0, self.air, roughness=self.roughness))
        return out

    def transported(self, P: np.ndarray, H: np.ndarray) -> np.ndarray:
        """φ: p h (compressible, Pa·m) or h (incompressible, m) on every node."""
        return P * H if self.air.compressible else H

    def residual(self, P: np.ndarray, H: np.ndarray, *, phi_old: np.ndarray | None = None,
                 dt: float | None = None, jacobian: bool = True):
        """Node balances at the pressure unknowns, and optionally their Jacobian.

        Returns
        -------
        r : numpy.ndarray, shape (size,)
        J_p : scipy.sparse.csr_matrix, (size, size), or None
            ∂r/∂p over the pressure unknowns.
        J_h : scipy.sparse.csr_matrix, (size, (nx + 1) nc), or None
            ∂r/∂h over every node (row-major node numbering).
        """
        lengths = [self.y_widths[None, :], self.x_widths[:, None]]
        R = np.zeros((self.nx + 1, self.nc))
        fl = self.fluxes(P, H)
        vals_p, vals_h = [], []
        for k, f in enumerate(fl):
            F = f.flux * lengths[k]
            if k == 0:
                R[:-1] += F
                R[1:] -= F
            else:
                R[:, :-1] += F
                R[:, 1:] -= F
            if jacobian:
                a, b, c = (f.d_pl * lengths[k]).ravel(), (f.d_pr * lengths[k]).ravel(), \
                    (f.d_h * lengths[k]).ravel()
                vals_p += [a, b, -a, -b]
                vals_h += [c, c, -c, -c]
        r = R[self.interior]
        sq_p = np.zeros(self.size)
        sq_h = np.zeros(self.size)
        if dt is not None:
            s = 12.0 * self.air.viscosity * self.cell_area[self.interior] / dt
            phi = self.transported(P, H)
            r = r + s * (phi - phi_old)[self.interior]
            if self.air.compressible:
                sq_p, sq_h = s * H[self.interior], s * P[self.interior]
            else:
                sq_h = s
        if not jacobian:
            return r, None, None
        pat = self._pattern
        dp = np.concatenate([np.concatenate(vals_p)[pat["keep_p"]], sq_p])
        dh = np.concatenate([np.concatenate(vals_h)[pat["keep_h"]], sq_h])
        J_p = pat["jp"].copy()
        J_p.data = np.bincount(pat["map_p"], weights=dp, minlength=J_p.nnz)
        J_h = pat["jh"].copy()
        J_h.data = np.bincount(pat["map_h"], weights=dh, minlength=J_h.nnz)
        return r, J_p, J_h


class DryFilm(Film):
    """No air film (a dry contact): the pressure is p_a at every node. Its rows are the
    equations p − p_a = 0 (Pa), so the coupled model keeps its [u, p] unknowns and the
    tape carries only its contact with the head."""

    def residual(self, P: np.ndarray, H: np.ndarray, *, phi_old: np.ndarray | None = None,
                 dt: float | None = None, jacobian: bool = True):
        """p − p_a at the pressure unknowns (Pa); ∂/∂p the identity, ∂/∂h zero."""
        r = (P - self.air.ambient_pressure)[self.interior]
        if not jacobian:
            return r, None, None
        n_nodes = (self.nx + 1) * self.nc
        return (r, sp.identity(self.size, format="csr"),
                sp.csr_matrix((self.size, n_nodes)))
