"""The steady harmonic response at a list of frequencies, as a saved result kind.

Kind ``"frequency_response"``. File layout: coordinate ``omega`` (rad/s); the complex
amplitude ``response`` (m, stored as ``response_real`` and ``response_imag``) on ``omega``
x ``point``; ``points`` (m) on ``point`` x ``axis`` (x, y); the text ``method`` and the
float ``error_estimate`` per frequency; the scalar ``velocity`` (m/s); and the solver's
statistics as ``info``.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..core.errors import ParameterError
from ..plot import bode, pyplot
from .base import Result, dataset, from_json, get, put, write_table
from .layout import INFO, Layout, Variable, nonnegative, speed

#: Millimetres per metre, for the probe labels of :meth:`FrequencyResponse.plot`.
MM_PER_M = 1e3
#: Size of a new Bode figure, inches.
FIGSIZE = (8, 6)


def _two_axes(ds) -> None:
    if ds.sizes.get("axis") != 2:
        raise ParameterError(f"points must have 2 columns (x, y), got {ds.sizes.get('axis')}")


@dataclass(frozen=True)
class FrequencyResponse(Result, kind="frequency_response"):
    """Steady harmonic response at a list of frequencies and points.

    Attributes
    ----------
    omega : numpy.ndarray
        Angular frequencies ω, rad/s, shape (k,).
    response : numpy.ndarray
        Complex displacement amplitude, m, shape (k, p): column 0 at the load centroid, then
        one per probe.
    points : numpy.ndarray
        (x, y) of the response points, m, shape (p, 2).
    velocity : float
        Tape speed V, m/s.
    method : numpy.ndarray
        "reduced" or "direct" per frequency, shape (k,).
    error_estimate : numpy.ndarray
        Estimated relative error per frequency (0 where solved directly), shape (k,).
    info : dict
        Statistics: ``factorizations``, ``interpolation_points`` (rad/s), ``basis_size``,
        ``direct_solves``, ``reduced_time``, ``direct_time`` (s), ``tol``, and the run's
        ``damping`` and ``unknowns``.
    """

    summary_units = {"amplitude": "m", "phase": "rad", "probes": "m", "probe_amplitude": "m",
                     "probe_phase": "rad", "damping": "N*s/m^3"}
    headline = ("velocity", "omega", "amplitude", "max_error_estimate", "unknowns")

    omega: np.ndarray
    response: np.ndarray
    points: np.ndarray
    velocity: float
    method: np.ndarray
    error_estimate: np.ndarray
    info: dict = field(default_factory=dict, compare=False)

    file_layout = Layout({
        "omega": Variable(("omega",), check=nonnegative("omega", "rad/s")),
        "response": Variable(("omega", "point"), "complex"),
        "points": Variable(("point", "axis")), "axis": Variable(("axis",), "text"),
        "method": Variable(("omega",), "text"),
        "error_estimate": Variable(("omega",), check=nonnegative("error_estimate")),
        "velocity": Variable((), check=speed())},
        {"info": INFO}, check=_two_axes)

    @property
    def amplitude(self) -> np.ndarray:
        """|W|, m, shape (k, p)."""
        return np.abs(self.response)

    @property
    def phase(self) -> np.ndarray:
        """arg W, rad in (−π, π], shape (k, p)."""
        return np.angle(self.response)

    def to_frame(self):
        """DataFrame: omega (rad/s), frequency (Hz), amplitude (m), phase (rad), method,
        error_estimate, then amplitude_<k>, phase_<k> for each probe k = 1, 2, ..."""
        import pandas as pd

        data = {"omega": self.omega, "frequency": self.omega / (2 * np.pi),
                "amplitude": self.amplitude[:, 0], "phase": self.phase[:, 0],
                "method": self.method, "error_estimate": self.error_estimate}
        for k in range(1, self.response.shape[1]):
            data[f"amplitude_{k}"] = self.amplitude[:, k]
            data[f"phase_{k}"] = self.phase[:, k]
        return pd.DataFrame(data)

    def to_csv(self, path: str | os.PathLike[str]) -> Path:
        """Write :meth:`to_frame` as CSV (Parquet for a ``.parquet`` path), whole or not at
        all (:func:`gyroshell.results.base.write_table`)."""
        return write_table(self.to_frame(), path)

    def to_xarray(self, *, params=None):
        """Dataset of the response (see the module docstring); ``params`` (a
        :class:`~gyroshell.TapeParameters`) is stored as metadata."""
        data_vars: dict = {}
        put(data_vars, "response", ("omega", "point"), self.response,
            {"units": "m", "long_name": "complex displacement amplitude"})
        data_vars["points"] = (("point", "axis"), self.points, {"units": "m"})
        data_vars["method"] = (("omega",), self.method.astype(object), {})
        data_vars["error_estimate"] = (("omega",), self.error_estimate, {"units": "1"})
        data_vars["velocity"] = ((), self.velocity, {"units": "m/s"})
        coords = {"omega": ("omega", self.omega, {"units": "rad/s"}),
                  "axis": ("axis", np.array(["x", "y"], dtype=object), {})}
        return dataset(data_vars, coords, self.kind, params=params, info=self.info)

    @classmethod
    def from_xarray(cls, ds) -> FrequencyResponse:
        """The response stored by :meth:`to_xarray`."""
        return cls(ds["omega"].values, get(ds, "response"), ds["points"].values,
                   float(ds["velocity"]), ds["method"].values.astype(str),
                   ds["error_estimate"].values, from_json(ds.attrs["info"]))

    def summary(self) -> dict:
        """Amplitudes (m) and phases (rad) at every frequency (rad/s) and point, the
        solver's statistics and the damping (SI units)."""
        info = self.info
        damping = info.get("damping", {})
        return {
            "velocity": float(self.velocity), "omega": self.omega.tolist(),
            "amplitude": self.amplitude[:, 0].tolist(), "phase": self.phase[:, 0].tolist(),
            "probes": [list(p) for p in self.points[1:].tolist()],
            "probe_amplitude": self.amplitude[:, 1:].T.tolist(),
            "probe_phase": self.phase[:, 1:].T.tolist(),
            "method": self.method.tolist(), "error_estimate": self.error_estimate.tolist(),
            "max_error_estimate": float(self.error_estimate.max()),
            "direct_solves": info.get("direct_solves"),
            "factorizations": info.get("factorizations"),
            "basis_size": info.get("basis_size"), "damping": damping.get("viscous", 0.0),
            "rayleigh": [damping.get("mass_coefficient", 0.0),
                         damping.get("stiffness_coefficient", 0.0)],
            "unknowns": info.get("unknowns"),
        }

    def _point_name(self, k: int) -> str:
        if k == 0:
            return "load point"
        x, y = self.points[k] * MM_PER_M
        return f"probe {k} ({x:.3g}, {y:.3g}) mm"

    def plot(self, ax=None, *, label: str | None = None, probes: bool = True):
        """Bode plot (amplitude, m, log scale; phase, rad) against ω (rad/s), one curve per
        point, drawn by :func:`gyroshell.plot.bode`.

        ``ax`` is a pair of Axes (amplitude, phase), one Axes (the amplitude alone) or None
        for a new figure; returns the Axes as an array.
        """
        if ax is None:
            _, ax = pyplot().subplots(2, 1, sharex=True, figsize=FIGSIZE)
        columns = range(self.response.shape[1]) if probes else range(1)
        for k in columns:
            name = self._point_name(k)
            text = name if label is None else f"{label}, {name}" if k else label
            ax = bode(self.omega, self.response[:, k], axes=ax, label=text, scale=1.0)
        ax[0].set_ylabel("amplitude |W| (m)")  # every point's, not only the load point's
        return ax
