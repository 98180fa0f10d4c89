"""Frequencies against tape speed: Campbell diagrams and sweeps, one way of drawing
the tracked branches."""

from __future__ import annotations

import numpy as np

from ..core.errors import ParameterError
from .figures import _axes, _table


def campbell(diagram, *, ax=None, circumference: float | None = None,
             orders=(1, 2, 3), title: str | None = None):
    """Campbell diagram: ω (rad/s) against V (m/s), one line per MAC-tracked branch.

    ``diagram`` is a :class:`gyroshell.CampbellDiagram`. Crossings are marked with
    circles, veerings with diamonds, growth rates above critical with crosses, the critical
    speed with a vertical line, and with ``circumference`` ℓ (m) of a roller or capstan the
    excitation lines ω = n·2πV/ℓ for n in ``orders``.
    """
    ax = _axes(ax, figsize=(8.0, 5.0))
    frame = diagram.frame
    _branch_lines(ax, frame, ms=2.5, colour_all=True)
    _growth_rates(ax, frame, "growth rate Re λ (1/s)")
    if len(diagram.crossings):
        ax.plot(diagram.crossings["velocity"], diagram.crossings["omega"], "o", ms=9,
                mfc="none", mec="k", label="crossing")
    if len(diagram.veerings):
        v = diagram.veerings
        ax.plot(v["velocity"], 0.5 * (v["omega_a"] + v["omega_b"]), "D", ms=8, mfc="none",
                mec="m", label="veering")
    vmax = float(frame["velocity"].max())
    crit = diagram.critical_speed
    if crit is not None and np.isfinite(crit) and crit <= 1.15 * vmax:
        vmax = max(vmax, crit * 1.01)  # show the critical speed just beyond the sweep
    top = float(np.nanmax(frame["omega"])) * 1.08 if len(frame) else 1.0
    if circumference is not None:
        speeds = np.linspace(0.0, vmax, 50)
        for n in orders:
            ax.plot(speeds, diagram.excitation(n, circumference, speeds), "--", color="0.4",
                    lw=0.9)
            v_end = min(vmax, top * circumference / (2 * np.pi * n))  # where it leaves
            ax.annotate(f"n = {n}", (v_end, float(diagram.excitation(n, circumference, v_end))),
                        fontsize=8, color="0.3", ha="right", va="top",
                        xytext=(-3, -3), textcoords="offset points")
    if crit is not None and np.isfinite(crit):
        ax.axvline(crit, color="k", ls=":", lw=1.2, label=f"critical speed {crit:.4g} m/s")
    ax.set_ylim(0, top)
    ax.set_xlim(float(frame["velocity"].min()), vmax)
    _speed_axes(ax, title or "Campbell diagram (branches tracked by MAC)")
    ax.legend(fontsize=8, loc="lower left")
    return ax


def sweep(result, *, ax=None, title: str | None = None):
    """Sweep: ω (rad/s) against V (m/s), one line per tracked branch; returns the Axes.

    ``result`` is a :class:`~gyroshell.SweepResult` (or its table, with columns
    ``velocity``, ``branch``, ``omega`` and optionally ``rank`` and ``growth_rate``). The
    k-th lowest frequencies are drawn in grey beneath (continuous where branches end), and
    growth rates above critical as crosses.
    """
    frame = _table(result)
    missing = {"velocity", "branch", "omega"} - set(frame.columns)
    if missing:
        raise ParameterError(f"frame lacks columns {sorted(missing)}")
    ax = _axes(ax)
    if "rank" in frame:  # the k-th lowest frequency: continuous even where branches end
        for rank, group in frame.groupby("rank"):
            group = group.sort_values("velocity")
            ax.plot(group["velocity"], group["omega"], color="0.75", lw=0.8, zorder=1,
                    label="k-th lowest ω" if rank == 0 else None)
    _branch_lines(ax, frame, ms=3, many_label="tracked branches (mode-shape correlation)")
    if "growth_rate" in frame:
        _growth_rates(ax, frame, "growth rate Re λ (1/s), divergence")
    _speed_axes(ax, title or "Lowest frequencies of the moving tape against speed")
    ax.set_ylim(bottom=0)
    ax.legend(fontsize=8, ncol=2)
    return ax


#: Most branches that each get a legend entry.
LEGEND_BRANCHES = 8


def _branch_lines(ax, frame, *, ms: float, colour_all: bool = False,
                  many_label: str | None = None) -> None:
    """One line with dots per tracked branch of ``frame``; up to :data:`LEGEND_BRANCHES`
    branches are labelled one by one, more share ``many_label`` (and take colours from
    their labels, as they do always with ``colour_all``)."""
    branches = frame.groupby("branch")
    few = branches.ngroups <= LEGEND_BRANCHES
    for k, (branch, group) in enumerate(branches):
        group = group.sort_values("velocity")
        label = f"branch {branch}" if few else (many_label if k == 0 else None)
        ax.plot(group["velocity"], group["omega"], marker="o", ms=ms, lw=1.2, zorder=2,
                color=f"C{int(branch) % 10}" if colour_all or not few else None,
                label=label)


def _growth_rates(ax, frame, label: str) -> None:
    """Crosses at the growth rates Re λ > 0 (1/s) of ``frame``, if any."""
    grow = frame[frame["growth_rate"] > 0]
    if len(grow):
        ax.plot(grow["velocity"], grow["growth_rate"], "kx", ls="none", label=label)


def _speed_axes(ax, title: str) -> None:
    ax.set_xlabel("tape speed V (m/s)")
    ax.set_ylabel("angular frequency ω (rad/s)")
    ax.set_title(title)
    ax.grid(True, alpha=0.3)
