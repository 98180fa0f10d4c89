"""Campbell diagrams: frequencies against tape speed, branches tracked by MAC.

At each speed the lowest ``count`` modes are computed (:func:`gyroshell.eigen.modes`) and
matched to the previous speed's by the modal assurance criterion

    MAC(φ_a, φ_b) = |φ_aᴴ φ_b|² / ((φ_aᴴ φ_a)(φ_bᴴ φ_b))   (0: orthogonal, 1: the same shape)

with an optimal assignment (Hungarian method). A match below ``min_mac`` starts a new
branch. Each point reports the MAC of its match, so a user sees how sure each link is.

Two branches whose frequencies swap order between neighbouring speeds *cross* (modes of
different shape pass through each other; the MAC keeps each on its branch). Two branches
whose relative gap |ω_a − ω_b| / ω̄ has a local minimum below ``veering_gap`` without
swapping *veer* (the curves approach and turn away, exchanging shapes). Excitation lines
ω = n·2πV/ℓ are the n-th harmonics of a roller or capstan of circumference ℓ (m) turning
with the tape; where a branch meets one, that speed excites the mode.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ..core.errors import ParameterError

if TYPE_CHECKING:
    import pandas as pd

#: Default smallest MAC that continues a branch.
MIN_MAC = 0.5
#: Default largest relative gap |ω_a − ω_b| / ω̄ at a veering.
VEERING_GAP = 0.02


def mac(phi_a: np.ndarray, phi_b: np.ndarray) -> np.ndarray:
    """MAC matrix between the columns of ``phi_a`` (n, p) and ``phi_b`` (n, q): (p, q)."""
    a, b = np.atleast_2d(phi_a.T).T, np.atleast_2d(phi_b.T).T
    cross = np.abs(a.conj().T @ b) ** 2
    na = np.real(np.sum(a.conj() * a, axis=0))
    nb = np.real(np.sum(b.conj() * b, axis=0))
    return cross / np.outer(na, nb)


@dataclass(frozen=True, eq=False)
class CampbellDiagram:
    """Tracked frequency branches against speed.

    Attributes
    ----------
    frame : pandas.DataFrame
        ``velocity`` (m/s), ``branch``, ``rank`` (position in ascending ω at that speed),
        ``omega`` (rad/s), ``growth_rate`` (Re λ, 1/s), ``mac`` (with the branch's previous
        point; NaN at a branch's first point).
    crossings : pandas.DataFrame
        ``velocity`` (m/s, linear interpolation), ``branch_a``, ``branch_b``, ``omega``.
    veerings : pandas.DataFrame
        ``velocity`` (m/s), ``branch_a``, ``branch_b``, ``omega_a``, ``omega_b``, ``gap``
        (relative).
    critical_speed : float or None
        m/s, marked on the plot.
    """

    frame: pd.DataFrame
    crossings: pd.DataFrame
    veerings: pd.DataFrame
    critical_speed: float | None = None
    info: dict = field(default_factory=dict)

    @staticmethod
    def excitation(order: int, circumference: float, velocity):
        """ω = n·2πV/ℓ, rad/s, of the n-th harmonic of a roller of circumference ℓ (m)."""
        if not (math.isfinite(circumference) and circumference > 0):
            raise ParameterError(f"circumference must be > 0 m, got {circumference!r}")
        return order * 2 * np.pi * np.asarray(velocity, dtype=float) / circumference

    def resonances(self, circumference: float, orders=(1, 2, 3)) -> pd.DataFrame:
        """Where branches meet excitation lines: ``order``, ``branch``, ``velocity`` (m/s),
        ``omega`` (rad/s), by linear interpolation between the computed speeds."""
        import pandas as pd

        rows = []
        for branch, g in self.frame.groupby("branch"):
            g = g.sort_values("velocity")
            v, w = g["velocity"].to_numpy(), g["omega"].to_numpy()
            for n in orders:
                d = w - self.excitation(n, circumference, v)
                for k in np.flatnonzero(np.sign(d[:-1]) * np.sign(d[1:]) < 0):
                    t = d[k] / (d[k] - d[k + 1])
                    vv = v[k] + t * (v[k + 1] - v[k])
                    rows.append({"order": n, "branch": branch, "velocity": vv,
                                 "omega": float(self.excitation(n, circumference, vv))})
        return pd.DataFrame(rows, columns=["order", "branch", "velocity", "omega"])

    def plot(self, ax=None, **options):
        """See :func:`gyroshell.plot.campbell`."""
        from .. import plot

        return plot.campbell(self, ax=ax, **options)

    def save(self, path):
        """Write the tracked branches (NetCDF, CSV or Parquet)."""
        from ..results import storage

        return storage.save(self.frame, path)


def _track(results, min_mac: float) -> list[dict]:
    from scipy.optimize import linear_sum_assignment

    rows, prev, labels, nxt = [], None, [], 0
    for res in results:
        k = res.count
        new, macs = [-1] * k, np.full(k, np.nan)
        if prev is not None:
            m = mac(prev, res.vectors)
            for i, j in zip(*linear_sum_assignment(-m), strict=True):
                if m[i, j] >= min_mac:  # continues branch labels[i]
                    new[j], macs[j] = labels[i], m[i, j]
        for j in range(k):
            if new[j] < 0:  # a mode that entered the lowest-count window: a new branch
                new[j], nxt = nxt, nxt + 1
        for j in range(k):
            rows.append({"velocity": res.velocity, "branch": new[j], "rank": j,
                         "omega": float(res.omega[j]),
                         "growth_rate": float(max(res.eigenvalues[j].real, 0.0)),
                         "mac": float(macs[j])})
        prev, labels = res.vectors, new
    return rows


def _pairs(frame):
    """(branch a, branch b, velocities, ω_a, ω_b) over the speeds where both exist."""
    table = frame.pivot_table(index="velocity", columns="branch", values="omega")
    branches = list(table.columns)
    for i, a in enumerate(branches):
        for b in branches[i + 1:]:
            both = table[[a, b]].dropna()
            if len(both) >= 2:
                yield a, b, both.index.to_numpy(), both[a].to_numpy(), both[b].to_numpy()


def _crossings_and_veerings(frame, veering_gap: float):
    import pandas as pd

    cross, veer = [], []
    for a, b, v, wa, wb in _pairs(frame):
        d = wa - wb
        nz = np.flatnonzero(d != 0)  # a pair that touches exactly at a speed crosses there
        for i, j in zip(nz[:-1], nz[1:], strict=True):
            if np.sign(d[i]) != np.sign(d[j]):
                t = d[i] / (d[i] - d[j])
                cross.append({"velocity": v[i] + t * (v[j] - v[i]), "branch_a": a,
                              "branch_b": b, "omega": wa[i] + t * (wa[j] - wa[i])})
        gap = np.abs(d) / (0.5 * (wa + wb))
        for k in range(1, len(v) - 1):
            if (gap[k] < gap[k - 1] and gap[k] < gap[k + 1] and gap[k] < veering_gap
                    and np.sign(d[k - 1]) == np.sign(d[k]) == np.sign(d[k + 1])):
                veer.append({"velocity": v[k], "branch_a": a, "branch_b": b,
                             "omega_a": wa[k], "omega_b": wb[k], "gap": gap[k]})
    return (pd.DataFrame(cross, columns=["velocity", "branch_a", "branch_b", "omega"]),
            pd.DataFrame(veer, columns=["velocity", "branch_a", "branch_b", "omega_a",
                                        "omega_b", "gap"]))


def campbell(model, velocities, count: int = 6, *, min_mac: float = MIN_MAC,
             veering_gap: float = VEERING_GAP, critical_speed: float | bool | None = True,
             progress: bool | None = None, **options) -> CampbellDiagram:
    """Campbell diagram of the tape over ``velocities`` (m/s).

    Parameters
    ----------
    model : TapeModel
    velocities : sequence of float
        Speeds, m/s, ascending.
    count : int
        Modes per speed.
    min_mac : float
        Smallest MAC that continues a branch.
    veering_gap : float
        Largest relative gap at a veering.
    critical_speed : True, float or None
        True: compute it (:func:`gyroshell.critical.critical_speeds`); a number: use it;
        None/False: none.
    **options
        Passed to :func:`gyroshell.eigen.modes`.
    """
    import pandas as pd
    from tqdm import tqdm

    from ..engines.eigen import modes
    from .sweep import check_velocities

    velocities = check_velocities(velocities)
    if np.any(np.diff(velocities) <= 0):
        raise ParameterError("velocities must be strictly ascending (m/s)")
    if not 0.0 <= min_mac <= 1.0:
        raise ParameterError(f"min_mac must be in [0, 1], got {min_mac!r}")
    if not veering_gap > 0:
        raise ParameterError(f"veering_gap must be > 0, got {veering_gap!r}")
    if progress is None:
        import sys

        progress = bool(getattr(sys.stderr, "isatty", lambda: False)())
    results = [modes(model, v, count, **options)
               for v in tqdm(velocities, disable=not progress, desc="campbell", unit="speed")]
    frame = pd.DataFrame(_track(results, min_mac),
                         columns=["velocity", "branch", "rank", "omega", "growth_rate", "mac"])
    crossings, veerings = _crossings_and_veerings(frame, veering_gap)
    if critical_speed is True:
        from ..engines.critical import critical_speeds

        critical_speed = critical_speeds(model).critical_speed
    elif critical_speed is False:
        critical_speed = None
    return CampbellDiagram(frame, crossings, veerings,
                           None if critical_speed is None else float(critical_speed),
                           {"min_mac": min_mac, "veering_gap": veering_gap})
