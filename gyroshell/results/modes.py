"""Eigenpairs as results: :class:`GyroscopicModes` (any matrices) and :class:`Modes` (the tape).

Kinds ``"gyroscopic_modes"`` and ``"modes"``. Files of kind ``"modes"`` keep the variable and
attribute names of the previous release (``eigenvalue``, ``mode_shape`` on ``x``, ``y``,
``mode``, ``omega``, ``residual``, ``velocity``; attributes ``supercritical``, ``damped``),
so its files load here.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..linalg.qep import spectrum
from ..tape.grid import Grid
from .base import Result, dataset, from_json, get, grid_from, put, xy_coords
from .layout import INFO, Attr, Layout, Variable, X, Y, flag, nonnegative, speed

__all__ = ["GyroscopicModes", "Modes"]

#: What both kinds' files hold about the spectrum.
_SPECTRUM = {"eigenvalue": Variable(("mode",), "complex"),
             "residual": Variable(("mode",), check=nonnegative("residual")),
             "mode": Variable(("mode",), "int")}
_FLAGS = {"supercritical": Attr(flag("supercritical")), "info": INFO}

_EIGENVALUE_ATTRS = {"units": "1/s", "long_name": "lambda (omega = |Im lambda|)"}
_SHAPE_ATTRS = {"units": "1", "long_name": "complex mode shape, largest entry 1"}


class _EigenvalueProperties:
    """Derived quantities of ``eigenvalues`` λ (1/s) shared by both kinds."""

    eigenvalues: np.ndarray

    @property
    def count(self) -> int:
        return len(self.eigenvalues)

    @property
    def omega(self) -> np.ndarray:
        """Angular frequencies ω = |Im λ| (damped frequencies with damping), rad/s."""
        return spectrum.omega(self.eigenvalues)

    @property
    def frequency(self) -> np.ndarray:
        """Frequencies ω / 2π, Hz."""
        return self.omega / (2 * np.pi)

    @property
    def period(self) -> np.ndarray:
        """Periods 2π / ω, s (inf for a non-oscillating eigenvalue)."""
        return spectrum.period(self.eigenvalues)

    @property
    def growth_rate(self) -> np.ndarray:
        """max(Re λ, 0), 1/s: zero for stable modes, the divergence/flutter growth rate."""
        return spectrum.growth_rate(self.eigenvalues)

    @property
    def decay_rate(self) -> np.ndarray:
        """−Re λ, 1/s: positive for damped modes, zero undamped, negative if growing."""
        return spectrum.decay_rate(self.eigenvalues)

    @property
    def damping_ratio(self) -> np.ndarray:
        """ζ = −Re λ / |λ| (dimensionless; 0 undamped, 1 critically damped)."""
        return spectrum.damping_ratio(self.eigenvalues)

    @property
    def stability(self) -> str:
        """``"stable"``, ``"divergence"`` or ``"flutter"`` (see
        :func:`gyroshell.classify_stability`)."""
        return spectrum.stability_label(spectrum.check_eigenvalues(self.eigenvalues))

    def _spectrum_summary(self) -> dict:
        """The per-mode numbers of :meth:`summary` (plain lists; an infinite period: None)."""
        return {
            "omega": self.omega.tolist(),
            "frequency": self.frequency.tolist(),
            "period": [p if math.isfinite(p) else None for p in self.period.tolist()],
            "growth_rate": self.growth_rate.tolist(),
            "decay_rate": self.decay_rate.tolist(),
            "damping_ratio": self.damping_ratio.tolist(),
        }

    def to_frame(self):
        """One row per mode: eigenvalue parts (1/s), omega (rad/s), frequency (Hz), period
        (s), growth and decay rates (1/s), damping ratio and residual."""
        import pandas as pd

        lam = np.asarray(self.eigenvalues)
        return pd.DataFrame({
            "mode": np.arange(self.count), "eigenvalue_real": lam.real,
            "eigenvalue_imag": lam.imag, "omega": self.omega, "frequency": self.frequency,
            "period": self.period, "growth_rate": self.growth_rate,
            "decay_rate": self.decay_rate, "damping_ratio": self.damping_ratio,
            "residual": np.asarray(self.residuals)})


@dataclass(frozen=True)
class GyroscopicModes(_EigenvalueProperties, Result, kind="gyroscopic_modes"):
    """Eigenpairs of (λ²M + λ(G + C) + K) φ = 0 nearest the shift.

    Attributes
    ----------
    eigenvalues : numpy.ndarray
        λ, 1/s, one representative per conjugate pair (Im λ >= 0). Undamped below critical:
        +iω, ascending ω. Undamped above critical: the eigenvalues nearest zero with
        Re λ >= 0, ascending |λ| (a real, divergent λ and an oscillating one are ordered by
        their distance from zero, so ``omega`` need not ascend). Damped: ascending damped
        frequency Im λ.
    vectors : numpy.ndarray
        Mode shapes φ, complex, shape (n, count), largest entry 1.
    residuals : numpy.ndarray
        ‖Q(λ)φ‖₂ / ((|λ|²‖M‖₁ + |λ|‖G + C‖₁ + ‖K‖₁) ‖φ‖₂) (backward errors).
    supercritical : bool
        True if K is not positive definite (for the tape: V at or above critical).
    damped : bool
        True if a damping matrix C was given (the count certificate does not apply).
    info : dict
        Diagnostics: ``method`` ("lanczos", "arpack" or "dense"), ``shift`` σ (1/s),
        ``below_shift`` (certified number of frequencies below the shift, None without
        certificate), ``factor_time``, ``solve_time`` (s), ``operator_applications``,
        ``pair_defect``, ``max_residual`` and method details.
    """

    summary_units = {"decay_rate": "1/s"}

    eigenvalues: np.ndarray
    vectors: np.ndarray
    residuals: np.ndarray
    supercritical: bool = False
    damped: bool = False
    info: dict = field(default_factory=dict, compare=False)

    file_layout = Layout({**_SPECTRUM, "vector": Variable(("unknown", "mode"), "complex")},
                         {**_FLAGS, "damped": Attr(flag("damped"))})

    def to_xarray(self, *, params=None):
        """Dataset on dimensions ``mode`` and ``unknown``: ``eigenvalue`` (1/s) and
        ``vector`` (complex, as real/imag pairs), ``residual``; flags and info as attributes."""
        dv: dict = {}
        coords = {"mode": ("mode", np.arange(self.count))}
        put(dv, "eigenvalue", ("mode",), self.eigenvalues, _EIGENVALUE_ATTRS)
        put(dv, "vector", ("unknown", "mode"), self.vectors, _SHAPE_ATTRS)
        dv["residual"] = (("mode",), self.residuals, {"units": "1"})
        return dataset(dv, coords, self.kind, params=params, info=self.info,
                       supercritical=int(self.supercritical), damped=int(self.damped))

    @classmethod
    def from_xarray(cls, ds) -> GyroscopicModes:
        return cls(get(ds, "eigenvalue"), get(ds, "vector"), ds["residual"].values,
                   bool(int(ds.attrs["supercritical"])), bool(int(ds.attrs["damped"])),
                   from_json(ds.attrs["info"]))

    def summary(self) -> dict:
        """ω, f, periods, rates (SI), flags, stability and residuals as plain values."""
        return {**self._spectrum_summary(), "supercritical": bool(self.supercritical),
                "damped": bool(self.damped), "stability": self.stability,
                "residual": np.asarray(self.residuals).tolist(),
                "unknowns": int(self.vectors.shape[0])}

    def plot(self, ax=None):
        """The eigenvalues in the complex plane (:func:`gyroshell.plot.eigenvalues`)."""
        from ..plot import eigenvalues

        return eigenvalues(self, ax=ax, title=f"{self.stability}, {self.count} eigenvalues")


@dataclass(frozen=True)
class Modes(_EigenvalueProperties, Result, kind="modes"):
    """Lowest eigenpairs of the gyroscopic tape at one speed.

    Attributes
    ----------
    grid : Grid
    velocity : float
        Tape speed V, m/s.
    eigenvalues : numpy.ndarray
        λ (complex, 1/s), one per conjugate pair: +iω below critical (ascending ω); above
        critical the eigenvalues nearest zero with Re λ >= 0 (ascending |λ|); damped:
        −δ + iω_d (ascending ω_d).
    vectors : numpy.ndarray
        Mode shapes φ, complex, shape (n, count), largest entry 1.
    residuals : numpy.ndarray
        Relative residuals ‖Q(λ)φ‖ / ((|λ|²‖M‖ + |λ|‖G + C‖ + ‖K‖) ‖φ‖) (backward errors).
    supercritical : bool
        True if K(V) is not positive definite (V at or above the critical speed).
    info : dict
        Diagnostics of :func:`gyroshell.gyroscopic_modes`: ``method``, ``shift`` (σ, 1/s),
        ``below_shift`` (certified number of frequencies below the shift), ``factor_time``
        and ``solve_time`` (s), ``operator_applications``, ``pair_defect``, ...
    damped : bool
        True if computed with damping (``decay_rate``, ``damping_ratio`` then mean something).

    Notes
    -----
    Derived: ``omega`` (rad/s), ``frequency`` (Hz), ``period`` (s), ``growth_rate``,
    ``decay_rate`` (1/s), ``damping_ratio``, ``stability`` ("stable", "divergence",
    "flutter").
    """

    summary_units = {"decay_rate": "1/s"}
    headline = ("velocity", "omega", "frequency", "growth_rate", "stability", "nx", "ny",
                "unknowns")

    grid: Grid
    velocity: float
    eigenvalues: np.ndarray
    vectors: np.ndarray
    residuals: np.ndarray
    supercritical: bool = False
    info: dict = field(default_factory=dict, compare=False)
    damped: bool = False

    file_layout = Layout({**_SPECTRUM, "x": X, "y": Y,
                          "mode_shape": Variable(("x", "y", "mode"), "complex"),
                          "omega": Variable(("mode",), optional=True),
                          "velocity": Variable((), check=speed())},
                         {**_FLAGS, "damped": Attr(flag("damped"), optional=True)},
                         needs=("grid",))

    @property
    def fields(self) -> np.ndarray:
        """Complex mode shapes on all nodes, shape (nx + 1, ny + 1, count)."""
        return self.grid.to_field(self.vectors)

    def field(self, index: int) -> np.ndarray:
        """Complex mode shape ``index`` on all nodes, shape (nx + 1, ny + 1)."""
        return self.grid.to_field(self.vectors[:, index])

    def to_xarray(self, *, params=None):
        """Dataset on ``x``, ``y`` (m) and ``mode``: ``eigenvalue`` (1/s), ``mode_shape``,
        ``omega`` (rad/s), ``residual``, ``velocity`` (m/s); grid, info and flags as
        attributes."""
        dv: dict = {}
        coords = {**xy_coords(self.grid), "mode": ("mode", np.arange(self.count))}
        put(dv, "eigenvalue", ("mode",), self.eigenvalues, _EIGENVALUE_ATTRS)
        put(dv, "mode_shape", ("x", "y", "mode"), self.fields, _SHAPE_ATTRS)
        dv["omega"] = (("mode",), self.omega, {"units": "rad/s"})
        dv["residual"] = (("mode",), self.residuals, {"units": "1"})
        dv["velocity"] = ((), self.velocity, {"units": "m/s"})
        return dataset(dv, coords, self.kind, params=params, grid=self.grid, info=self.info,
                       supercritical=int(self.supercritical), damped=int(self.damped))

    @classmethod
    def from_xarray(cls, ds) -> Modes:
        grid = grid_from(ds.attrs)
        return cls(grid, float(ds["velocity"]), get(ds, "eigenvalue"),
                   grid.from_field(get(ds, "mode_shape")), ds["residual"].values,
                   bool(int(ds.attrs["supercritical"])), from_json(ds.attrs["info"]),
                   bool(int(ds.attrs.get("damped", 0))))

    def summary(self) -> dict:
        """What ``gyroshell modes --json`` prints of the result (SI units)."""
        g = self.grid
        return {"velocity": float(self.velocity), **self._spectrum_summary(),
                "supercritical": bool(self.supercritical), "stability": self.stability,
                "residual": np.asarray(self.residuals).tolist(),
                "nx": g.nx, "ny": g.ny, "unknowns": g.unknowns, "edges": g.edges}

    def plot(self, ax=None, *, index: int = 0, part: str = "real"):
        """The real (or imaginary) part of mode ``index`` on the tape; returns the Axes."""
        from .. import plot

        return plot.mode_shape(self, index, part=part, ax=ax)
