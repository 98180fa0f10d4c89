"""Frequency response: the steady harmonic answer to F e^{iωt}, an engine beside static and Newmark.

At each angular frequency ω (rad/s) the displacement amplitude W (complex, m) solves

    Q(ω) W = F,        Q(ω) = K(V) − ω² M + iω (G(V) + C),

and the response at a point is r·W (bilinear interpolation row r): amplitude |r·W| (m) and
phase arg(r·W) (rad; negative = lagging the load). F is the model's force (the nodal forces
of the Gaussian pressure of Eq. 17, peak P₀), so the amplitude is the displacement under
that pressure.

Two methods, chosen per frequency:

* **direct**: one sparse complex LU of Q(ω) per frequency (exact to round-off);
* **reduced**: a rational Krylov (moment-matching) subspace. Q is factored at a few
  interpolation frequencies ω_k; the amplitude W(ω_k) and its first Taylor coefficients
  (Q W₁ = −Q′W₀, Q W_j = −(Q′W_{j−1} − M W_{j−2}), Q′ = −2ωM + i(G + C)) span, in real
  form, a basis V; M, G + C, K are projected on it (keeping M and K symmetric and G skew) and
  every frequency costs O(r) through the poles and residues of the small model (one dense
  eigen-decomposition). The reduced response matches W(ω) and its first derivatives at
  each ω_k.

The error of the reduced model is estimated at every frequency as twice the difference
between it and the nested model built without the highest moment at each point (the
nested model is the less accurate one), plus a round-off level of 1e-8. Interpolation
points are added greedily where the estimate is largest until it is below ``tol``
everywhere or the point budget is spent; frequencies still above ``tol`` are solved
directly.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import asdict

import numpy as np
import scipy.linalg as sl
import scipy.sparse as sp

from ..core import validation
from ..core.errors import ParameterError
from ..core.parallel import blas_threads as limit_blas_threads
from ..core.progress import LongWork
from ..linalg.factorization import splu
from ..plot import bode
from ..results import layout
from ..results.base import Result, dataset, from_json, get, put
from ..results.frequency_response import FrequencyResponse
from ..tape.damping import Damping, as_damping
from ..tape.model import TapeModel, check_model
from ..tape.parameters import check_velocity
from .divergence import DIVERGENCE_MEMBERS
from .frequency_options import (  # noqa: F401 - the checks are public here too
    DEFAULT_TOL,
    ESTIMATE_ROUNDOFF,
    MAX_POINTS,
    MAX_POINTS_LIMIT,
    MAX_TOL,
    METHODS,
    MIN_TOL,
    check_frequencies,
    check_options,
    max_frequency,
    parse_frequencies,
)

#: SuperLU's threshold for keeping a diagonal pivot. Q has a symmetric pattern; the default
#: partial pivoting (1.0) abandons the fill-reducing order when K − ω²M is indefinite and
#: took minutes per factorization at L_x/L_y = 19 instead of about a second.
PIVOT_THRESHOLD = 0.1
#: Taylor coefficients matched at each interpolation frequency (W₀ ... W_{m−1}).
DEFAULT_MOMENTS = 6
#: Interpolation frequencies placed before the greedy enrichment.
INITIAL_POINTS = 4
#: Responses below this fraction of the largest one count as this fraction (relative
#: errors at deep anti-resonances are not meaningful).
RESPONSE_FLOOR = 1e-6
#: The estimate is this multiple of the nested models' difference, plus the round-off level
#: ESTIMATE_ROUNDOFF (:mod:`gyroshell.engines.frequency_options`).
ESTIMATE_SAFETY = 2.0
#: A new (unit) vector whose part outside the basis is smaller than this adds no direction.
NEW_DIRECTION_TOL = 1e-8
#: Interpolation points added per greedy round (one rebuild of the reduced model each).
POINTS_PER_ROUND = 4
#: Frequencies per batch of small dense solves.
BATCH = 256
#: Frequencies of a reduced model's Bode plot ...
PLOT_FREQUENCIES = 400
#: ... and its span, rad/s, when the model has a single interpolation frequency.
SINGLE_POINT_SPAN = 1.0
#: Direct sweeps shorter than this show no progress bar (it would flash and vanish).
MIN_BAR_FREQUENCIES = 2


def response_rows(model: TapeModel, probes: Sequence[tuple[float, float]]
                  ) -> tuple[np.ndarray, sp.csr_matrix]:
    """Points (load centroid first, then probes), m, and their interpolation rows."""
    points = [tuple(map(float, model.params.load_centroid))]
    for probe in probes:
        try:
            x, y = probe
            points.append((float(x), float(y)))
        except (TypeError, ValueError):
            raise ParameterError(f"probe must be a point (x, y) in m, got {probe!r}") from None
    rows = sp.csr_matrix(np.array([model.grid.interpolation_row(x, y) for x, y in points]))
    return np.array(points), rows


# ----- the operator -----------------------------------------------------------------------
class _Operators:
    """M (diagonal), G + C, K and F of one model, speed and damping."""

    def __init__(self, model: TapeModel, velocity: float, damping: Damping,
                 force: np.ndarray | None):
        self.m = model.mass_diagonal
        self.M = sp.diags(self.m, format="csr")
        self.K = model.K(velocity).tocsr()
        G = model.G(velocity).tocsr()
        #: G + C, the velocity-proportional operator, kg/s.
        self.damped_gyroscopic = G if damping.is_zero else (
            G + damping.matrix(model, velocity)).tocsr()
        self.F = model.force if force is None else force
        #: The tape's areal density, kg/m^2 (it bounds the frequencies: check_frequencies).
        self.density = model.params.density

    def Q(self, omega: float) -> sp.csc_matrix:
        """K − ω²M + iω(G + C), N/m (complex unless ω = 0)."""
        if omega == 0.0:
            return self.K.tocsc()
        return (self.K - omega**2 * self.M + (1j * omega) * self.damped_gyroscopic).tocsc()

    def factor(self, omega: float):
        """A solver b -> Q(ω)⁻¹ b for complex b (one sparse LU)."""
        lu = splu(self.Q(omega), symmetric_mode=True, pivot_threshold=PIVOT_THRESHOLD)
        if omega != 0.0:
            return lu.solve
        return lambda b: lu.solve(np.ascontiguousarray(b.real)) + 1j * lu.solve(
            np.ascontiguousarray(b.imag))

    def moments(self, omega: float, count: int) -> list[np.ndarray]:
        """W₀ ... W_{count−1}: Taylor coefficients of W about ω (one factorization)."""
        solve = self.factor(omega)
        GC = self.damped_gyroscopic
        dQ = lambda x: -2.0 * omega * (self.m * x) + 1j * (GC @ x)  # noqa: E731
        out = [solve(self.F.astype(complex))]
        for j in range(1, count):
            rhs = -dQ(out[j - 1])
            if j >= 2:
                rhs += self.m * out[j - 2]
            out.append(solve(rhs))
        return out


#: What the frequency response reads from a model (the refusal above critical needs A, B).
RESPONSE_MEMBERS = (*DIVERGENCE_MEMBERS, "force")


def _check_model(model: object) -> TapeModel:
    return check_model(model, members=RESPONSE_MEMBERS)


def direct_response(model: TapeModel, velocity: float, omega, *,
                    damping: Damping | float | None = None, force: np.ndarray | None = None,
                    probes: Sequence[tuple[float, float]] = (), progress: bool | None = None
                    ) -> FrequencyResponse:
    """The response by one sparse LU of Q(ω) per frequency (exact to round-off).

    Parameters as in :func:`frequency_response`.
    """
    velocity = check_velocity(velocity)
    omega = check_frequencies(omega, density=_check_model(model).params.density)
    progress = validation.progress(progress)
    damping = as_damping(damping)
    ops = _Operators(model, velocity, damping, _force(model, force))
    points, rows = response_rows(model, probes)
    start = time.perf_counter()
    response = _direct(ops, rows, omega, progress)
    k = len(omega)
    info = {"factorizations": k, "direct_solves": k,
            "direct_time": time.perf_counter() - start, "reduced_time": 0.0,
            "basis_size": 0, "interpolation_points": [], **_run_info(model, damping)}
    return FrequencyResponse(omega, response, points, velocity, np.full(k, "direct"),
                             np.zeros(k), info)


def _run_info(model: TapeModel, damping: Damping) -> dict:
    """What a response records of its run: the damping's fields and the unknowns."""
    return {"damping": asdict(damping), "unknowns": model.unknowns}


def _force(model: TapeModel, force) -> np.ndarray | None:
    if force is None:
        return None
    return validation.vector("force", force, model.unknowns, "N")


def _direct(ops: _Operators, rows: sp.csr_matrix, omega: np.ndarray,
            progress: bool | None) -> np.ndarray:
    with limit_blas_threads(1):  # SuperLU's dense kernels: one thread is fastest here
        return _direct_loop(ops, rows, omega, progress)


def _direct_loop(ops: _Operators, rows: sp.csr_matrix, omega: np.ndarray,
                 progress: bool | None) -> np.ndarray:
    out = np.empty((len(omega), rows.shape[0]), dtype=complex)
    shown = progress if len(omega) >= MIN_BAR_FREQUENCIES else False
    work = LongWork(len(omega), "frf direct", progress=shown, unit="solve",
                    size=f"{len(omega)} direct solves of {len(ops.m)} unknowns",
                    advice="use fewer frequencies, the reduced model (method auto) or a "
                           "larger spacing")
    with work as bar:
        for k, w in enumerate(omega):
            out[k] = rows @ ops.factor(float(w))(ops.F.astype(complex))
            bar.update(1)
    return out


# ----- the reduced model ----------------------------------------------------------------------
class _Projection:
    """An orthonormal real basis V, grown block by block, and M, G + C, K, F projected on it
    (``Mr``, ``GCr``, ``Kr``).

    Each block costs O(n r k) (two Gram–Schmidt passes and the new rows and columns of the
    projected matrices), not a re-orthogonalization of the whole basis.
    """

    def __init__(self, ops: _Operators, rows: sp.csr_matrix) -> None:
        self.ops, self.rows = ops, rows
        self.V = np.empty((len(ops.m), 0))
        self.Mr, self.Kr, self.GCr = (np.empty((0, 0)) for _ in range(3))

    @property
    def size(self) -> int:
        return self.V.shape[1]

    def extend(self, vectors: Sequence[np.ndarray]) -> None:
        """Add the real and imaginary parts of ``vectors`` (dependent ones are dropped)."""
        X = np.array([part for v in vectors for part in (v.real, v.imag)]).T
        norms = np.linalg.norm(X, axis=0)
        X = X[:, norms > 0] / norms[norms > 0]
        V = self.V
        for _ in range(2):  # twice is enough (Kahan-Parlett)
            X -= V @ (V.T @ X)
        U, sv, _ = sl.svd(X, full_matrices=False, check_finite=False)
        new = U[:, sv > NEW_DIRECTION_TOL]
        if new.shape[1] == 0:
            return
        for _ in range(2):
            new -= V @ (V.T @ new)
        new, _ = np.linalg.qr(new)
        ops = self.ops
        GC = ops.damped_gyroscopic
        MN, KN, GCN, GCtN = ops.m[:, None] * new, ops.K @ new, GC @ new, GC.T @ new
        self.Mr = _grow(self.Mr, V.T @ MN, MN.T @ V, new.T @ MN)
        self.Kr = _grow(self.Kr, V.T @ KN, KN.T @ V, new.T @ KN)
        self.GCr = _grow(self.GCr, V.T @ GCN, GCtN.T @ V, new.T @ GCN)
        self.V = np.hstack([V, new])

    def parts(self):
        """(M_r, K_r, GC_r, F_r, R_r) on the current basis (GC_r: G + C projected)."""
        V = self.V
        return (0.5 * (self.Mr + self.Mr.T), 0.5 * (self.Kr + self.Kr.T), self.GCr,
                V.T @ self.ops.F, np.asarray(self.rows @ V))


def _grow(A: np.ndarray, right: np.ndarray, below: np.ndarray, corner: np.ndarray
          ) -> np.ndarray:
    return np.block([[A, right], [below, corner]])


class _Reduction:
    """The live state of a reduction: the full model's operators, the response rows and the
    full and nested bases (what a saved reduced model does not keep)."""

    def __init__(self, ops: _Operators, rows: sp.csr_matrix) -> None:
        self.ops, self.rows = ops, rows
        self.spaces = (_Projection(ops, rows), _Projection(ops, rows))


class ReducedModel(Result, kind="reduced_model"):
    """Rational Krylov (moment-matching) reduction of Q(ω) W = F on a real basis.

    Parameters
    ----------
    model : TapeModel
    velocity : float
        Tape speed V, m/s.
    damping : Damping, float or None
        Damping C (a number is viscous c, N·s/m³).
    force : numpy.ndarray, optional
        Nodal force amplitude F, N (default: the model's force).
    probes : sequence of (x, y)
        Extra response points, m.
    moments : int
        Taylor coefficients matched per interpolation frequency (>= 2).

    Notes
    -----
    Saved as kind ``"reduced_model"``: the poles (1/s) and residues (m·s⁻¹ per point) of the
    full and nested reduced models, the interpolation frequencies (rad/s), the response
    points (m), the speed, the moments and the basis size. A loaded model evaluates exactly
    as the saved one; it cannot :meth:`add_points` (that needs the tape's matrices).
    """

    #: The file: poles and residues of the full and nested models, the speed, the
    #: response and interpolation points, the moments and the basis size.
    file_layout = layout.Layout(
        {**{f"{p}_{what}": layout.Variable(dims, "complex") for p in ("full", "nested")
            for what, dims in (("poles", (f"{p}_pole",)),
                               ("residues", ("point", f"{p}_pole")))},
         "velocity": layout.Variable((), check=layout.speed()),
         "points": layout.Variable(("point", "axis")),
         "interpolation_points": layout.Variable(
             ("interpolation_point",), check=layout.nonnegative("interpolation_points"))},
        {"moments": layout.Attr(layout.count("moments", 2)),
         "basis_size": layout.Attr(layout.count("basis_size", 0)), "info": layout.INFO})
    summary_units = {"interpolation_points": "rad/s", "points": "m"}

    def __init__(self, model: TapeModel, velocity: float = 0.0, *,
                 damping: Damping | float | None = None, force: np.ndarray | None = None,
                 probes: Sequence[tuple[float, float]] = (), moments: int = DEFAULT_MOMENTS):
        moments = validation.integer("moments", moments, low=2)
        _check_model(model)
        self.velocity = check_velocity(velocity)
        self.damping = as_damping(damping)
        self.unknowns = model.unknowns
        ops = _Operators(model, self.velocity, self.damping, _force(model, force))
        self.points, rows = response_rows(model, probes)
        self._solver = _Reduction(ops, rows)
        self.moments = int(moments)
        self.interpolation_points: list[float] = []
        self._full = self._nested = None
        self._basis_size = 0

    def add_points(self, omegas: Sequence[float]) -> None:
        """Factor Q at each ω (rad/s), add W and its Taylor coefficients to the basis, and
        rebuild the reduced model."""
        if self._solver is None:
            raise ParameterError("a loaded reduced model cannot add interpolation points: "
                                 "build a new ReducedModel from the TapeModel")
        omegas = check_frequencies(omegas, density=self._solver.ops.density)
        full, nested = self._solver.spaces
        for omega in omegas:
            self.interpolation_points.append(float(omega))
            vectors = self.ops.moments(float(omega), self.moments)
            full.extend(vectors)
            nested.extend(vectors[:-1])
        self._full = self._poles(full.parts())
        self._nested = self._poles(nested.parts())
        self._basis_size = full.size

    @property
    def ops(self) -> _Operators | None:
        """The full model's operators (None for a loaded model)."""
        return None if self._solver is None else self._solver.ops

    @property
    def rows(self) -> sp.csr_matrix | None:
        """Interpolation rows of the response points (None for a loaded model)."""
        return None if self._solver is None else self._solver.rows

    @property
    def basis_size(self) -> int:
        """Columns of the reduced basis (twice the independent complex vectors)."""
        return self._basis_size

    def run_info(self) -> dict:
        """The damping's fields and the number of unknowns of the full model."""
        return {"damping": asdict(self.damping), "unknowns": self.unknowns}

    @staticmethod
    def _poles(parts) -> tuple[np.ndarray, np.ndarray]:
        """Poles λ_j (1/s) and residues (p, 2r) of the reduced transfer function.

        H(s) = R (s²M_r + sGC_r + K_r)⁻¹ F = Σ_j res_j / (s − λ_j), from the eigen-
        decomposition of the first-order form A z = λ B z, A = [[0, I], [−K_r, −GC_r]],
        B = diag(I, M_r): then every frequency costs O(r) instead of a dense solve.
        """
        Mr, Kr, GCr, Fr, Rr = parts
        r = len(Fr)
        Minv_K = np.linalg.solve(Mr, Kr)
        Minv_GC = np.linalg.solve(Mr, GCr)
        A = np.block([[np.zeros((r, r)), np.eye(r)], [-Minv_K, -Minv_GC]])
        lam, X = sl.eig(A, check_finite=False)
        b = np.concatenate([np.zeros(r), np.linalg.solve(Mr, Fr)])
        coeff = np.linalg.solve(X, b.astype(complex))
        return lam, (Rr @ X[:r]) * coeff[None, :]

    @staticmethod
    def _evaluate(poles, omega: np.ndarray) -> np.ndarray:
        lam, residues = poles
        out = np.empty((len(omega), residues.shape[0]), dtype=complex)
        for lo in range(0, len(omega), BATCH):
            s = 1j * omega[lo:lo + BATCH, None]
            out[lo:lo + BATCH] = (1.0 / (s - lam[None, :])) @ residues.T
        return out

    def evaluate(self, omega) -> tuple[np.ndarray, np.ndarray]:
        """Reduced response (complex, m, shape (k, p)) and its estimated relative error."""
        if self._full is None:
            raise ParameterError("the reduced model has no interpolation point yet")
        omega = check_frequencies(omega)
        full = self._evaluate(self._full, omega)
        nested = self._evaluate(self._nested, omega)
        return full, ESTIMATE_SAFETY * relative_error(full, nested) + ESTIMATE_ROUNDOFF

    # ----- the saved kind -------------------------------------------------------------
    def to_xarray(self, *, params=None):
        """Dataset of the poles and residues the model evaluates from (class Notes)."""
        if self._full is None:
            raise ParameterError("the reduced model has no interpolation point yet")
        data_vars: dict = {}
        for prefix, (lam, residues) in (("full", self._full), ("nested", self._nested)):
            put(data_vars, f"{prefix}_poles", (f"{prefix}_pole",), lam, {"units": "1/s"})
            put(data_vars, f"{prefix}_residues", ("point", f"{prefix}_pole"), residues,
                {"units": "m/s"})
        data_vars["points"] = (("point", "axis"), self.points, {"units": "m"})
        data_vars["interpolation_points"] = (("interpolation_point",),
                                             np.array(self.interpolation_points, dtype=float),
                                             {"units": "rad/s"})
        data_vars["velocity"] = ((), self.velocity, {"units": "m/s"})
        return dataset(data_vars, {}, self.kind, params=params, info=self.run_info(),
                       moments=self.moments, basis_size=self.basis_size)

    @classmethod
    def from_xarray(cls, ds) -> ReducedModel:
        """A reduced model that evaluates as the saved one (it cannot add points)."""
        self = cls.__new__(cls)
        info = from_json(ds.attrs["info"])
        self.velocity = float(ds["velocity"])
        self.damping, self.unknowns = Damping(**info["damping"]), info["unknowns"]
        self._solver = None
        self.points = ds["points"].values
        self.moments = int(from_json(ds.attrs["moments"]))
        self.interpolation_points = [float(w) for w in ds["interpolation_points"].values]
        self._full, self._nested = ((get(ds, f"{p}_poles"), get(ds, f"{p}_residues"))
                                    for p in ("full", "nested"))
        self._basis_size = int(from_json(ds.attrs["basis_size"]))
        return self

    def summary(self) -> dict:
        """Speed (m/s), interpolation frequencies (rad/s), sizes and response points (m)."""
        return {"velocity": self.velocity, "moments": self.moments,
                "interpolation_points": list(self.interpolation_points),
                "basis_size": self.basis_size,
                "poles": 0 if self._full is None else len(self._full[0]),
                "points": self.points.tolist(), **self.run_info()}

    def plot(self, ax=None):
        """Bode plot of the reduced load-point response between the lowest and highest
        interpolation frequencies (:func:`gyroshell.plot.bode`); returns the Axes."""
        if not self.interpolation_points:
            raise ParameterError("the reduced model has no interpolation point yet")
        lo, hi = min(self.interpolation_points), max(self.interpolation_points)
        omega = np.linspace(lo, hi if hi > lo else lo + SINGLE_POINT_SPAN, PLOT_FREQUENCIES)
        response, _ = self.evaluate(omega)
        return bode(omega, response[:, 0], axes=ax, label="reduced model", scale=1.0)


def relative_error(value: np.ndarray, reference: np.ndarray) -> np.ndarray:
    """max over points of |value − reference| / max(|reference|, floor), per frequency.

    floor = RESPONSE_FLOOR × the largest |reference| of that point over all frequencies.
    """
    scale = np.maximum(np.abs(reference), RESPONSE_FLOOR * np.abs(reference).max(axis=0))
    scale = np.where(scale > 0, scale, 1.0)
    return (np.abs(value - reference) / scale).max(axis=1)


def frequency_response(model: TapeModel, velocity: float, omega, *,
                       damping: Damping | float | None = None,
                       force: np.ndarray | None = None,
                       probes: Sequence[tuple[float, float]] = (), method: str = "auto",
                       tol: float = DEFAULT_TOL, max_points: int = MAX_POINTS,
                       moments: int = DEFAULT_MOMENTS, progress: bool | None = None,
                       blas_threads: int | None = 1) -> FrequencyResponse:
    """Steady harmonic response to F e^{iωt} at the load centroid and probes.

    Parameters
    ----------
    model : TapeModel
    velocity : float
        Tape speed V, m/s (>= 0, below critical).
    omega : array_like
        Angular frequencies, rad/s (>= 0).
    damping : Damping, float or None
        Damping C (a number is viscous c, N·s/m³). Without damping the response is infinite
        at the natural frequencies; a frequency exactly on one gives a singular Q.
    force : numpy.ndarray, optional
        Nodal force amplitude F, N (default: the model's force, its Gaussian pressure of
        peak P₀, Pa).
    probes : sequence of (x, y)
        Extra response points, m.
    method : {"auto", "direct", "reduced"}
        "direct": one LU per frequency. "reduced": the rational Krylov model with greedy
        interpolation points (up to ``max_points``), reporting its estimated error.
        "auto": "direct" for a handful of frequencies, otherwise "reduced" with direct
        solves wherever the estimated error stays above ``tol``.
    tol : float
        Target relative error of the reduced model (> 0).
    max_points : int
        Budget of interpolation frequencies (factorizations) of the reduced model.
    moments : int
        Taylor coefficients matched per interpolation frequency.
    progress : bool or None
        Progress bar for direct solves; None: only on a terminal.
    blas_threads : int or None
        BLAS threads for the reduced model's dense algebra (None: leave them alone); one
        is fastest on a shared machine, where spinning BLAS workers compete for cores.
    """
    velocity = check_velocity(velocity)
    omega = check_frequencies(omega, density=_check_model(model).params.density)
    progress = validation.progress(progress)
    tol, max_points = check_options(method, tol, max_points)
    response_rows(model, probes), as_damping(damping), _force(model, force)  # checks first
    _check_subcritical(model, velocity)
    if method == "direct" or (method == "auto" and len(omega) <= INITIAL_POINTS * 2):
        return direct_response(model, velocity, omega, damping=damping, force=force,
                               probes=probes, progress=progress)
    reduced = ReducedModel(model, velocity, damping=damping, force=force, probes=probes,
                           moments=moments)
    return _reduced_response(reduced, omega, method=method, tol=tol, max_points=max_points,
                             progress=progress, blas_threads=blas_threads)


def _reduced_response(reduced: ReducedModel, omega: np.ndarray, *, method: str, tol: float,
                      max_points: int, progress: bool | None, blas_threads: int | None
                      ) -> FrequencyResponse:
    """The response from the greedy reduced model; with method "auto", direct solves
    replace it wherever its estimated error stays above ``tol``."""
    start = time.perf_counter()
    with limit_blas_threads(blas_threads):
        response, estimate = _greedy(reduced, omega, tol, max_points)
    reduced_time = time.perf_counter() - start
    chosen = np.full(len(omega), "reduced", dtype=object)
    start = time.perf_counter()
    direct = 0
    if method == "auto":
        direct = _direct_where_inaccurate(reduced, omega, response, estimate, chosen, tol,
                                          progress)
    info = {"factorizations": len(reduced.interpolation_points) + direct,
            "interpolation_points": list(reduced.interpolation_points),
            "basis_size": reduced.basis_size, "direct_solves": direct,
            "reduced_time": reduced_time, "direct_time": time.perf_counter() - start,
            "tol": tol, "moments": reduced.moments, **reduced.run_info()}
    return FrequencyResponse(omega, response, reduced.points, reduced.velocity,
                             chosen.astype(str), estimate, info)


def _direct_where_inaccurate(reduced: ReducedModel, omega: np.ndarray, response: np.ndarray,
                             estimate: np.ndarray, chosen: np.ndarray, tol: float,
                             progress: bool | None) -> int:
    """Solve directly where ``estimate`` > ``tol``, in place (the estimate there becomes 0
    and ``chosen`` "direct"); returns how many frequencies that was."""
    bad = np.flatnonzero(estimate > tol)
    if bad.size:
        response[bad] = _direct(reduced.ops, reduced.rows, omega[bad], progress)
        estimate[bad] = 0.0
        chosen[bad] = "direct"
    return int(bad.size)


def _greedy(reduced: ReducedModel, omega: np.ndarray, tol: float, max_points: int
            ) -> tuple[np.ndarray, np.ndarray]:
    """Add interpolation points where the estimate peaks until it is below ``tol``.

    Each round adds up to POINTS_PER_ROUND of the largest local maxima of the estimate
    (one rebuild of the reduced model per round).
    """
    lo, hi = float(omega.min()), float(omega.max())
    reduced.add_points(np.linspace(lo, hi, min(INITIAL_POINTS, max_points)))
    response, estimate = reduced.evaluate(omega)
    while estimate.max() > tol and len(reduced.interpolation_points) < max_points:
        budget = min(POINTS_PER_ROUND, max_points - len(reduced.interpolation_points))
        chosen = _peaks(estimate, tol, budget, omega, reduced.interpolation_points)
        if not chosen:
            break
        reduced.add_points(chosen)
        response, estimate = reduced.evaluate(omega)
    return response, estimate


def _peaks(estimate: np.ndarray, tol: float, count: int, omega: np.ndarray,
           taken: list[float]) -> list[float]:
    """Frequencies of the ``count`` largest local maxima of ``estimate`` above ``tol``."""
    padded = np.concatenate([[-np.inf], estimate, [-np.inf]])
    peak = (estimate >= padded[:-2]) & (estimate >= padded[2:]) & (estimate > tol)
    order = np.flatnonzero(peak)[np.argsort(-estimate[peak])]
    return [float(omega[i]) for i in order if float(omega[i]) not in taken][:count]


def _check_subcritical(model: TapeModel, velocity: float) -> None:
    """Refuse at or above the critical speed: there is no steady harmonic state there."""
    from .static import factor_definite

    factor_definite(model, velocity)
