"""Eigenvalues in the complex plane and the critical speeds of a tape."""

from __future__ import annotations

import numpy as np

from ..core.errors import ParameterError
from .figures import _axes

#: What each critical-speed entry means, in the order drawn (all m/s).
SPEED_LABELS: dict[str, str] = {
    "critical_speed": "lowest frequency reaches 0",
    "divergence_speed": "K(V) loses definiteness",
    "string_speed": "moving string √(T/ρ)",
    "strip_speed": "strip on the foundation",
    "sundaram_benson_speed": "Sundaram & Benson",
    "paper_speed": "the seed paper",
}


def eigenvalues(values, *, ax=None, title: str | None = None):
    """The eigenvalues λ (1/s) of a gyroscopic system in the complex plane: Im λ = ±ω
    (rad/s) against Re λ, the growth (> 0) or decay (< 0) rate, 1/s.

    ``values`` is an array of λ or an object with ``eigenvalues`` (e.g.
    :class:`~gyroshell.GyroscopicModes`). Returns the Axes.
    """
    lam = np.asarray(getattr(values, "eigenvalues", values))
    if lam.ndim != 1 or lam.size == 0:
        raise ParameterError("eigenvalues needs a non-empty 1-D array of eigenvalues")
    ax = _axes(ax)
    ax.axvline(0.0, color="0.6", lw=0.8)
    ax.plot(lam.real, lam.imag, "o", ms=5, label="λ")
    ax.set_xlabel("Re λ, growth rate (1/s)")
    ax.set_ylabel("Im λ, angular frequency (rad/s)")
    ax.grid(True, alpha=0.3)
    if title:
        ax.set_title(title)
    return ax


def critical_speeds(speeds, *, ax=None, title: str | None = None):
    """The critical speed by both routes beside its reference values, m/s, as bars.

    ``speeds`` is a mapping name -> m/s (keys of :data:`SPEED_LABELS`) or an object with
    ``as_dict()`` (e.g. :class:`~gyroshell.CriticalSpeeds`). Returns the Axes.
    """
    table = speeds.as_dict() if hasattr(speeds, "as_dict") else dict(speeds)
    names = [n for n in SPEED_LABELS if n in table]
    if not names:
        raise ParameterError(f"critical_speeds needs some of {', '.join(SPEED_LABELS)}")
    ax = _axes(ax)
    values = [float(table[n]) for n in names]
    ax.barh(range(len(names)), values, color=["C3", "C0"] + ["0.6"] * (len(names) - 2))
    ax.set_yticks(range(len(names)), [SPEED_LABELS[n] for n in names])
    ax.invert_yaxis()
    for k, v in enumerate(values):
        ax.text(v, k, f" {v:.2f}", va="center", fontsize=8)
    ax.set_xlabel("tape speed V (m/s)")
    ax.grid(True, axis="x", alpha=0.3)
    if title:
        ax.set_title(title)
    return ax
