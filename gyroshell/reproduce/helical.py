"""Helical scan: a two-head drum crossing the tape obliquely with intermittent contact.

The seed paper's motivation: "a read-write head travels relative to the tape with high
velocity and causes intermittent loading". Two heads, half a revolution apart, each sweep
the same oblique track across the tape (L_x/L_y = 4, Table 1) at the head speed, pressing
with the Gaussian of Eq. 17 (P₀ = 200 Pa) during their contact windows (raised-cosine
ramps), while the tape moves at V. Light viscous (air) damping. Outputs: the displacement
under each head (the head–tape spacing variation it sees, positive = away from the head),
wire-frames of the whole tape, and a per-contact table (mean, range).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from ..engines.newmark import march
from ..plot import head_histories, wireframe
from ..tape.model import TapeModel
from ..tape.moving_loads import drum_heads
from ._common import PAPER_DT, Settings, pyplot, save_csv, save_figure
from ._wireframes import snapshot_axes

#: Tape speed V, m/s.
TAPE_SPEED = 10.0
#: Head speed along its track, m/s.
HEAD_SPEED = 40.0
#: Track from (x, y) / (L_x, L_y) = START to END: oblique, 0.7 L_x along, 0.9 L_y across.
START, END = (0.15, 0.05), (0.85, 0.95)
#: Fraction of each half revolution a head is in contact (wrap angle below 180°).
WRAP_FRACTION = 0.8
#: Rise and fall of each contact, s.
RAMP = 20e-6
#: Viscous (air) damping, N·s/m³.
DAMPING = 100.0
HEADS = 2


def geometry(model: TapeModel) -> dict:
    """Track start (m), head velocity (m/s), contact duration and revolution period (s)."""
    p = model.params
    start = np.array([START[0] * p.length, START[1] * p.width])
    end = np.array([END[0] * p.length, END[1] * p.width])
    track = end - start
    duration = float(np.linalg.norm(track)) / HEAD_SPEED
    return {"start": tuple(start), "velocity": tuple(track / duration),
            "duration": duration, "period": HEADS * duration / WRAP_FRACTION}


def compute(settings: Settings) -> tuple[pd.DataFrame, pd.DataFrame, pd.DataFrame]:
    """Histories under each head, per-contact statistics, and wire-frame snapshots."""
    model = TapeModel(settings.params(length_ratio=4))
    geo = geometry(model)
    heads = drum_heads(HEADS, geo["start"], geo["velocity"], revolution_period=geo["period"],
                       contact_duration=geo["duration"], ramp=RAMP)
    revolutions = settings.pick(2.0, 1.0)
    steps = int(round(revolutions * geo["period"] / PAPER_DT))
    snap_times = geo["period"] * np.array([0.1, 0.25, 0.4, 0.6, 0.75, 0.9]) \
        + (revolutions - 1) * geo["period"]
    result = march(model, TAPE_SPEED, dt=PAPER_DT, steps=steps, load=heads, damping=DAMPING,
                   snapshot_times=snap_times, progress=settings.progress)
    t = result.times
    history = {"t": t}
    for k, head in enumerate(heads):
        x, y = head.centres(t)
        history.update({f"x_head{k}": x, f"y_head{k}": y,
                        f"contact_head{k}": head.envelope(t),
                        f"w_head{k}": result.head_displacements[:, k]})
    history = pd.DataFrame(history)
    contacts = _per_contact(history, geo)
    g = model.grid
    X, Y = np.asarray(g.X), np.asarray(g.Y)
    snaps = pd.concat([pd.DataFrame({"t": s, "x": X.ravel(), "y": Y.ravel(), "w": f.ravel()})
                       for s, f in zip(result.snapshots.times, result.snapshots.fields,
                                       strict=True)], ignore_index=True)
    return history, contacts, snaps


def _per_contact(history: pd.DataFrame, geo: dict) -> pd.DataFrame:
    """Mean, min, max and range (m) of w under each head while fully in contact."""
    rows = []
    for k in range(HEADS):
        full = history[f"contact_head{k}"].to_numpy() >= 1.0
        index = np.cumsum(np.diff(np.concatenate([[0], full.astype(int)])) == 1)
        for contact in np.unique(index[full]):
            w = history[f"w_head{k}"].to_numpy()[full & (index == contact)]
            rows.append({"head": k, "contact": int(contact), "mean_w": w.mean(),
                         "min_w": w.min(), "max_w": w.max(), "range_w": np.ptp(w),
                         "samples": len(w)})
    return pd.DataFrame(rows)


def plot_histories(history: pd.DataFrame, contacts: pd.DataFrame, path: Path) -> Path:
    plt = pyplot()
    fig, axes = plt.subplots(HEADS + 1, 1, figsize=(9, 7.5), sharex=True,
                             gridspec_kw={"height_ratios": [1] + [2] * HEADS})
    head_histories(history["t"],
                   history[[f"w_head{k}" for k in range(HEADS)]].to_numpy(),
                   history[[f"contact_head{k}" for k in range(HEADS)]].to_numpy(), axes=axes)
    for k in range(HEADS):
        stats = contacts[contacts["head"] == k]
        if len(stats):
            last = stats.iloc[-1]
            axes[k + 1].text(0.01, 0.95, f"head {k + 1}, last full contact: mean "
                             f"{last.mean_w * 1e9:.3g} nm, range {last.range_w * 1e9:.3g} nm",
                             transform=axes[k + 1].transAxes, va="top", fontsize=9)
    fig.suptitle(f"Helical scan: two-head drum, head speed {HEAD_SPEED:g} m/s on an oblique "
                 f"track, tape V = {TAPE_SPEED:g} m/s, c = {DAMPING:g} N·s/m³", fontsize=11)
    fig.tight_layout()
    return save_figure(fig, path)


def plot_wireframes(snaps: pd.DataFrame, history: pd.DataFrame, path: Path) -> Path:
    plt = pyplot()
    times = list(dict.fromkeys(snaps["t"]))
    x, y = snapshot_axes(snaps)
    zmax = snaps["w"].abs().max()
    fig = plt.figure(figsize=(12, 6.5))
    t_all = history["t"].to_numpy()
    for i, t in enumerate(times):
        W = snaps[snaps["t"] == t]["w"].to_numpy().reshape(len(x), len(y))
        ax = wireframe(x, y, W, ax=fig.add_subplot(2, 3, i + 1, projection="3d"),
                       title=f"t = {t * 1e6:.0f} µs", zmax=zmax, zmin=-zmax,
                       cstride=max(1, len(y) // 20), elev=30, zoom=1.25)
        n = int(np.argmin(np.abs(t_all - t)))
        for k in range(HEADS):
            if history[f"contact_head{k}"].iloc[n] > 0:
                ax.scatter([history[f"x_head{k}"].iloc[n] * 1e3],
                           [history[f"y_head{k}"].iloc[n] * 1e3], [zmax * 1e9],
                           color=f"C{k}", s=25, label=f"head {k + 1}")
    fig.suptitle("Helical scan: the tape under a two-head drum (dots: heads in contact; "
                 "tape moves toward +x)", fontsize=12)
    fig.subplots_adjust(left=0.0, right=1.0, bottom=0.02, top=0.92, wspace=0.0, hspace=0.05)
    return save_figure(fig, path)


def run(out: Path, settings: Settings) -> list[Path]:
    history, contacts, snaps = compute(settings)
    return [save_csv(history, out / "helical_heads.csv"),
            save_csv(contacts, out / "helical_contacts.csv"),
            save_csv(snaps, out / "helical_snapshots.csv"),
            plot_histories(history, contacts, out / "helical_heads.png"),
            plot_wireframes(snaps, history, out / "helical_wireframes.png")]
