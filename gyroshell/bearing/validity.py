"""Where a steady state's models are used outside their range: one warning line each.

- **Rarefaction** (:func:`.rarefaction.knudsen_range_warning`): the film's Knudsen number
  Kn = λ p_a/(p h) at the smallest spacing over the head (the lands, corners and arcs,
  where the film's flow is metered), against the chosen model's range: first-order slip
  beyond Kn = 0.5, second-order beyond 1, no slip beyond 0.05.
- **The hard wall** at the gap σ: below 3 σ the tape's asperities carry load (data tapes
  run at h/σ >= 4, video tapes at h/σ <= 3: Bhushan & Tønder, J. Tribol. 111:228, 1989),
  which a wall does not model: the spacing there is a parameter, not physics.
- **Greenwood–Williamson asperities** pressed until their real contact area, π η β σ_s
  F_1(d/σ_s), exceeds half the nominal area (:data:`GW_REAL_AREA`): GW's summits deform
  independently, each as a Hertz contact, which holds while their contact spots are few
  and far apart (light contact, a real area of a few per cent); at half the area the spots
  merge, and the pressure there (and the spacing it sets) is the model's extrapolation. A
  sharp corner, an idealization of a corner rounded to microns, is where this happens: at
  30° wraps over 60° flanks the default tape reaches d = -14 σ_s (a real area of 1.8
  nominal) and the centre's spacing changes with the grid (34 nm on the default, 6.2 nm on
  half its intervals); across the random design set of benchmarks/bench_design_set.py the
  most pressed corner reaches d = -5.2 σ_s (0.66).
"""

from __future__ import annotations

import numpy as np

from .rarefaction import knudsen_range_warning

#: Spacings below this many wall gaps σ are outside the hard wall's range.
HARD_WALL_ROUGHNESSES = 3.0
#: Real contact areas above this fraction of the nominal are outside Greenwood–
#: Williamson's range (its independent summits' spots merge).
GW_REAL_AREA = 0.5


def head_nodes(sol) -> np.ndarray:
    """Boolean mask of the nodes over the head (its extent in x), shape (nx + 1, nc)."""
    m = sol.model
    first, last = m.head.extent(m.head_radius)
    over = (m.x_head >= first) & (m.x_head <= last)
    return np.broadcast_to(over[:, None], sol.spacing.shape)


def head_knudsen(sol) -> float:
    """The largest Knudsen number λ p_a/(p h) over the head, at spacings no smaller than
    the film sees (:attr:`.model.BearingModel.film_floor`); 0 without slip or film."""
    m = sol.model
    if m.dry or m.air.mean_free_path == 0.0:
        return 0.0
    over = head_nodes(sol)
    h = np.maximum(sol.spacing[over], m.film_floor)
    if m.air.compressible:
        p = np.maximum(sol.pressure[over], 1e-300)
        kn = m.air.mean_free_path * m.air.ambient_pressure / (p * h)
    else:
        kn = m.air.mean_free_path / h
    return float(kn.max())


def range_warnings(sol) -> list[str]:
    """The one-line warnings of a steady state ``sol`` (a BearingSolution or transient
    state) whose models are used outside their range (see the module notes)."""
    m = sol.model
    out = []
    if not m.dry:
        text = knudsen_range_warning(m.air.rarefaction, head_knudsen(sol))
        if text is not None:
            out.append(text)
    if not m.smooth_contact:
        sigma = m.air.roughness
        h_min = float(sol.spacing[head_nodes(sol)].min())
        if h_min < HARD_WALL_ROUGHNESSES * sigma:
            out.append(
                f"the hard wall at the gap {sigma:.3g} m holds the tape at {h_min:.3g} m, "
                f"below {HARD_WALL_ROUGHNESSES:g} times the gap, where asperities carry "
                "load and the spacing is set by the gap typed, not by physics: use "
                "--contact asperity (contact='asperity')")
    elif m.contact is not None and m.contact.law == "asperity":
        text = _asperity_range_warning(sol)
        if text is not None:
            out.append(text)
    return out


def _asperity_range_warning(sol) -> str | None:
    """The warning line of asperities pressed beyond :data:`GW_REAL_AREA`, or None."""
    m = sol.model
    spacing = np.where(head_nodes(sol), sol.spacing, np.inf)
    k = np.unravel_index(int(np.argmin(spacing)), spacing.shape)
    d = float(spacing[k])
    area = float(m.contact_law.real_area_fraction(d))
    if area <= GW_REAL_AREA:
        return None
    where = f" at x = {float(m.x_head[k[0]]):.4g} m"
    return (f"the asperities are pressed to d = {d / m.contact.roughness:.3g} sigma_s"
            f"{where}, where Greenwood-Williamson's real contact area would be "
            f"{area:.2g} of the nominal (its range: independent summits, a small fraction):"
            " the contact pressure and the spacing there are the model's extrapolation; "
            "give the corner its radius (corner_radius) or use a smaller wrap")
