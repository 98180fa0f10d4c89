"""The drawings of ``gyroshell reproduce``: load-point and moving-head histories, wire
frames, waterfalls, periods against speed, stacked spectra and Bode plots, from arrays or
results."""

from __future__ import annotations

import numpy as np

from ..core.errors import ParameterError
from .figures import _axes, _mm, pyplot


def _vector(values, name: str) -> np.ndarray:
    arr = np.asarray(values, dtype=float)
    if arr.ndim != 1 or arr.size == 0:
        raise ParameterError(f"{name} must be a non-empty 1-D array")
    return arr


def load_point_history(times, w=None, *, steady: float | None = None, scale: float = 1.0,
                       ylabel: str = "load-point deflection w (m)", velocity=None,
                       label: str = "transient (Newmark, β=1/4)", ax=None):
    """The load-point displacement against time, with its steady state as a dot.

    Parameters
    ----------
    times : array_like or TransientResult
        Times, s (drawn in µs); or a :class:`~gyroshell.TransientResult`, whose
        ``times`` and ``load_point`` are used (then ``w`` is omitted).
    w : array_like, optional
        Load-point deflection at ``times``, m.
    steady : float, optional
        Steady-state deflection, m (e.g. :func:`~gyroshell.solve_static`'s
        ``load_point_deflection``): a dashed line and a dot at the last time.
    scale : float
        Factor applied to ``w`` and ``steady`` before drawing (e.g. k/P₀, m⁻¹, for the
        paper's nondimensional w k / P₀; then say so in ``ylabel``).
    ylabel : str
        Label of the vertical axis, with its unit.
    velocity : float, optional
        Tape speed, m/s, written in the corner.
    label : str
        Legend label of the history.
    ax : matplotlib.axes.Axes, optional
        Where to draw; a new figure if None.

    Returns
    -------
    matplotlib.axes.Axes
    """
    if w is None:
        if not hasattr(times, "load_point"):
            raise ParameterError("load_point_history needs times and w, or a TransientResult")
        result = times
        times, w = result.times, result.load_point
        velocity = getattr(result, "velocity", None) if velocity is None else velocity
    t = _vector(times, "times")
    w = _vector(w, "w")
    if w.shape != t.shape:
        raise ParameterError(f"w must have the shape of times {t.shape}, got {w.shape}")
    ax = _axes(ax)
    t_us = t * 1e6
    ax.plot(t_us, w * scale, lw=0.9, color="C0", label=label)
    if steady is not None:
        ax.axhline(steady * scale, color="C3", lw=0.8, ls="--")
        ax.plot([t_us[-1]], [steady * scale], "o", color="C3", ms=7,
                label="steady state (static solver)", clip_on=False)
    ax.set_ylabel(ylabel)
    ax.set_xlabel("time t (µs)")
    if velocity is not None:
        ax.text(0.01, 0.9, f"V = {velocity:g} m/s", transform=ax.transAxes, va="top",
                fontweight="bold")
    ax.grid(alpha=0.3)
    return ax


def _table_on(name: str, values, rows: tuple[str, np.ndarray], columns: tuple[str, np.ndarray]
              ) -> np.ndarray:
    """``values`` as a float array with one row per entry of ``rows`` and one column per
    entry of ``columns`` (each a (name, coordinates) pair); refused otherwise."""
    values = np.asarray(values, dtype=float)
    shape = (len(rows[1]), len(columns[1]))
    if values.shape != shape:
        raise ParameterError(f"{name} must have shape (len({rows[0]}), len({columns[0]})) = "
                             f"{shape}, got {values.shape}")
    return values


def wireframe(x, y, w, *, ax=None, title: str | None = None, zmax: float | None = None,
              zmin: float | None = None, rstride: int | None = None, cstride: int = 2,
              elev: float = 28.0, azim: float = -62.0, zoom: float = 1.3):
    """A 3-D wire frame of a field w(x, y) on the tape (x, y in mm, w in nm).

    Parameters
    ----------
    x, y : array_like
        Node coordinates along and across the tape, m, lengths nx + 1 and ny + 1.
    w : array_like
        Deflection, m, shape (nx + 1, ny + 1) (a snapshot, ``solve_static(...).field``).
    ax : mpl_toolkits.mplot3d.axes3d.Axes3D, optional
        A 3-D Axes (``projection="3d"``); a new figure if None.
    title : str, optional
        Panel title.
    zmax, zmin : float, optional
        Vertical limits, m; default ``zmax = max|w|`` and ``zmin = -0.6 zmax``, so that
        panels of one history share their scale when given the history's maximum.
    rstride, cstride : int, optional
        Row (along x) and column strides of the wire frame; ``rstride`` defaults to about
        80 lines along the tape.
    elev, azim : float
        Viewing angles, degrees.
    zoom : float
        Zoom of the box (matplotlib ``set_box_aspect``).

    Returns
    -------
    mpl_toolkits.mplot3d.axes3d.Axes3D
    """
    x, y = _vector(x, "x"), _vector(y, "y")
    w = _table_on("w", w, ("x", x), ("y", y))
    if ax is None:
        plt = pyplot()
        ax = plt.figure(figsize=(7.0, 4.0)).add_subplot(projection="3d")
    elif not hasattr(ax, "plot_wireframe"):
        raise ParameterError("wireframe needs a 3-D Axes (add_subplot(projection='3d'))")
    X, Y = np.meshgrid(_mm(x), _mm(y), indexing="ij")
    top = float(np.max(np.abs(w))) if zmax is None else float(zmax)
    top = top or 1e-12
    bottom = -0.6 * top if zmin is None else float(zmin)
    stride = max(1, len(x) // 80) if rstride is None else int(rstride)
    ax.plot_wireframe(X, Y, w * 1e9, rstride=stride, cstride=int(cstride), lw=0.4, color="k")
    ax.set_zlim(bottom * 1e9, top * 1e9)
    ax.set_box_aspect((4, 1.3, 1.2), zoom=zoom)
    ax.view_init(elev=elev, azim=azim)
    if title:
        ax.set_title(title, fontsize=10, pad=-2)
    ax.set_xlabel("x (mm)", fontsize=7, labelpad=-4)
    ax.set_ylabel("y (mm)", fontsize=7, labelpad=-6)
    ax.set_zlabel("w (nm)", fontsize=7, labelpad=-6)
    ax.tick_params(labelsize=6, pad=-2)
    return ax


def edge_reflection(times, tape, reference, *, t_edge: float, t_reflection: float,
                    ax=None):
    """Load-point histories of a tape and of a wider reference tape, with the instants the
    front reaches the free edge and its reflection returns to the load (seed paper, §4).

    Parameters
    ----------
    times : array_like
        Times, s (drawn in µs).
    tape, reference : array_like
        Load-point displacement of the tape and of the wider reference, m (drawn in nm),
        same length as ``times``.
    t_edge, t_reflection : float
        Arrival of the front at the free edge and of its reflection at the load point, s.
    ax : matplotlib.axes.Axes, optional
        Where to draw; a new figure if None.

    Returns
    -------
    matplotlib.axes.Axes
    """
    t = _vector(times, "times")
    series = {}
    for name, values in (("tape", tape), ("reference", reference)):
        series[name] = _vector(values, name)
        if series[name].shape != t.shape:
            raise ParameterError(f"{name} must have the shape of times {t.shape}, "
                                 f"got {series[name].shape}")
    ax = _axes(ax)
    ax.plot(t * 1e6, series["tape"] * 1e9, label="tape, width L_y (free edges)")
    ax.plot(t * 1e6, series["reference"] * 1e9, "--", label="reference, wider tape")
    ax.axvline(t_edge * 1e6, color="C2", lw=0.8, ls=":",
               label=f"front reaches the free edge: {t_edge * 1e6:.1f} µs")
    ax.axvline(t_reflection * 1e6, color="C3", lw=0.8,
               label=f"edge reflection back at the load: {t_reflection * 1e6:.1f} µs")
    ax.set_xlabel("time t (µs)")
    ax.set_ylabel("load-point displacement w (nm)")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return ax


def wave_fronts(table, *, speeds: dict | None = None, ax=None):
    """Distance of the apparent wave fronts from the load against time, downstream (solid)
    and upstream (dashed), one colour per tape speed.

    Parameters
    ----------
    table : pandas.DataFrame
        Columns ``velocity`` (m/s), ``t`` (s, drawn in µs), ``downstream`` and
        ``upstream`` (m, drawn in mm).
    speeds : dict, optional
        {(velocity, "downstream" or "upstream"): apparent front speed, m/s} for the legend.
    ax : matplotlib.axes.Axes, optional
        Where to draw; a new figure if None.

    Returns
    -------
    matplotlib.axes.Axes
    """
    missing = {"velocity", "t", "downstream", "upstream"} - set(getattr(table, "columns", ()))
    if missing:
        raise ParameterError(f"table needs the columns {sorted(missing)}")
    ax = _axes(ax)
    for k, (v, ft) in enumerate(table.groupby("velocity")):
        for side, ls in (("downstream", "-"), ("upstream", "--")):
            speed = None if speeds is None else speeds.get((v, side))
            extra = "" if speed is None else f" ({speed:.0f} m/s)"
            ax.plot(ft["t"] * 1e6, ft[side] * 1e3, ls, color=f"C{k}", marker=".",
                    label=f"V = {v:g} m/s, {side}{extra}")
    ax.set_xlabel("time t (µs)")
    ax.set_ylabel("front distance from the load (mm)")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return ax


def waterfall(times, x, lines, *, ax=None, gap: float | None = None,
              load_point: float | None = None, title: str | None = None):
    """Centre-line displacements at a series of times, each raised by its rank (waterfall).

    Parameters
    ----------
    times : array_like
        Times of the lines, s (written at the right end in µs), length m.
    x : array_like
        Positions along the tape, m (drawn in mm), length n.
    lines : array_like
        Displacements, m, shape (m, n) (``TransientResult.snapshots.centerlines``).
    ax : matplotlib.axes.Axes, optional
        Where to draw; a new figure if None.
    gap : float, optional
        Offset between successive lines, m; default 0.55 max|w|.
    load_point : float, optional
        x of the load centroid, m: a dotted vertical line.
    title : str, optional
        Axes title.

    Returns
    -------
    matplotlib.axes.Axes
    """
    t, x = _vector(times, "times"), _vector(x, "x")
    lines = _table_on("lines", lines, ("times", t), ("x", x))
    if gap is None:
        gap = 0.55 * float(np.max(np.abs(lines)))
    ax = _axes(ax, figsize=(9.0, 10.0))
    x_mm = _mm(x)
    for k, (tk, line) in enumerate(zip(t, lines, strict=True)):
        ax.plot(x_mm, line + k * gap, color="k", lw=0.7)
        ax.text(x_mm.max() * 1.01, k * gap, f"{tk * 1e6:.0f}", fontsize=7, va="center")
    if load_point is not None:
        ax.axvline(load_point * 1e3, color="C3", lw=0.6, ls=":", label="load point")
        ax.legend(loc="upper left", fontsize=8)
    step = f" per {np.median(np.diff(t)) * 1e6:.3g} µs" if len(t) > 1 else ""
    ax.set_xlabel("x (mm)   (tape moves left → right)")
    ax.set_ylabel(f"w + offset (each curve raised {gap * 1e9:.3g} nm{step})")
    ax.set_yticks([])
    ax.text(1.0, 1.0, "t (µs)", transform=ax.transAxes, fontsize=8, ha="left", va="bottom")
    for side in ("top", "right", "left"):
        ax.spines[side].set_visible(False)
    if title:
        ax.set_title(title, fontsize=11)
    return ax


def head_histories(times, w_heads, contact, *, axes=None):
    """Contact envelopes and the displacement under each moving head while in contact.

    Parameters
    ----------
    times : array_like
        Times, s (drawn in µs), length n.
    w_heads : array_like
        Displacement under each head, m (drawn in nm), shape (n, heads)
        (``TransientResult.head_displacements``).
    contact : array_like
        Contact envelope of each head, 0..1, shape (n, heads) (``head.envelope(times)``);
        w is drawn only where it is positive.
    axes : sequence of matplotlib.axes.Axes, optional
        heads + 1 Axes: the envelopes, then one per head; a new figure if None.

    Returns
    -------
    numpy.ndarray of matplotlib.axes.Axes
    """
    t = _vector(times, "times")
    w = np.asarray(w_heads, dtype=float).reshape(len(t), -1)
    env = np.asarray(contact, dtype=float).reshape(len(t), -1)
    if w.shape != env.shape:
        raise ParameterError(f"w_heads and contact must have one column per head, shapes "
                             f"{w.shape} and {env.shape}")
    heads = w.shape[1]
    if axes is None:
        plt = pyplot()
        _, axes = plt.subplots(heads + 1, 1, figsize=(9.0, 7.5), sharex=True,
                               gridspec_kw={"height_ratios": [1] + [2] * heads})
    axes = np.asarray(axes).ravel()
    if axes.size != heads + 1:
        raise ParameterError(f"axes must hold heads + 1 = {heads + 1} Axes, got {axes.size}")
    t_us = t * 1e6
    for k in range(heads):
        axes[0].plot(t_us, env[:, k], lw=1.2, label=f"head {k + 1}")
        ax = axes[k + 1]
        ax.plot(t_us, np.where(env[:, k] > 0, w[:, k] * 1e9, np.nan), lw=1.1,
                color=f"C{k}", label="w under the head while in contact (spacing variation)")
        ax.axhline(0, color="k", lw=0.5)
        ax.set_ylabel("w under head (nm)")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("contact")
    axes[0].legend(fontsize=8, loc="upper right", ncol=2)
    axes[1].legend(fontsize=8, loc="lower right")
    axes[0].set_title("contact envelopes", fontsize=9)
    axes[-1].set_xlabel("time t (µs)")
    return axes


def period_vs_velocity(velocity, period_eigen, *, transient_edge=None, transient=None,
                       critical_speed: float | None = None, ax=None,
                       title: str | None = None):
    """Dominant period of the load-point displacement against tape speed (log scale, µs).

    Parameters
    ----------
    velocity : array_like
        Tape speeds, m/s.
    period_eigen : array_like
        2π/ω₁ from the gyroscopic eigen-solver at each speed, s.
    transient_edge, transient : array_like, optional
        Periods from the load-point spectrum of a transient, s: the lowest peak (band
        edge) and the tallest peak.
    critical_speed : float, optional
        Critical (divergence) speed, m/s: a dashed vertical line.
    ax : matplotlib.axes.Axes, optional
        Where to draw; a new figure if None.
    title : str, optional
        Axes title.

    Returns
    -------
    matplotlib.axes.Axes
    """
    v = _vector(velocity, "velocity")
    series = {"period_eigen": period_eigen, "transient_edge": transient_edge,
              "transient": transient}
    series = {k: _vector(s, k) for k, s in series.items() if s is not None}
    for name, s in series.items():
        if s.shape != v.shape:
            raise ParameterError(f"{name} must have the shape of velocity {v.shape}")
    ax = _axes(ax)
    p0 = series["period_eigen"] * 1e6
    ax.semilogy(v, p0, "-", color="C0", lw=1.2, marker="s", ms=5,
                label="2π/ω₁ (gyroscopic eigen-solver)")
    if "transient_edge" in series:
        ax.semilogy(v, series["transient_edge"] * 1e6, "o", color="C2", mfc="none", ms=10,
                    mew=1.5, label="transient: lowest spectral peak (band edge)")
    if "transient" in series:
        ax.semilogy(v, series["transient"] * 1e6, "x", color="C3", ms=8, mew=1.5,
                    label="transient: tallest spectral peak")
    first = p0[int(np.argmin(np.abs(v)))]
    ax.axhline(first, color="0.6", lw=0.7, ls=":")
    ax.text(1, first * 1.08, f"at V = {v[int(np.argmin(np.abs(v)))]:g} m/s: {first:.3g} µs",
            color="0.4", fontsize=8)
    if critical_speed is not None:
        ax.axvline(critical_speed, color="k", lw=0.7, ls="--",
                   label=f"critical speed {critical_speed:.2f} m/s")
    ax.set_xlabel("tape speed V (m/s)")
    ax.set_ylabel("period of the load-point displacement (µs)")
    if title:
        ax.set_title(title, fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8, loc="upper left")
    return ax


def spectra(labels, omegas, amplitudes, *, omega_ref=None, ax=None, xmax: float | None = None,
            spacing: float = 1.1, title: str | None = None):
    """Amplitude spectra stacked one above the other, each normalized to its peak.

    Parameters
    ----------
    labels : sequence of str or float
        One label per spectrum (a number is written as a speed, ``"50 m/s"``).
    omegas : sequence of array_like
        Angular frequencies of each spectrum, rad/s (lengths may differ).
    amplitudes : sequence of array_like
        Amplitudes at ``omegas`` (any unit: each curve is divided by its maximum).
    omega_ref : array_like, optional
        One reference angular frequency per spectrum, rad/s (e.g. ω₁(V) from the
        eigen-solver): the curves are drawn against ω/ω_ref with a dashed line at 1.
        Without it they are drawn against ω in rad/s.
    ax : matplotlib.axes.Axes, optional
        Where to draw; a new figure if None.
    xmax : float, optional
        Right end of the horizontal axis (in ω/ω_ref or rad/s); labels are written there.
    spacing : float
        Vertical offset between successive spectra (normalized units).
    title : str, optional
        Axes title.

    Returns
    -------
    matplotlib.axes.Axes
    """
    labels, omegas, amplitudes = list(labels), list(omegas), list(amplitudes)
    if not (len(labels) == len(omegas) == len(amplitudes)) or not labels:
        raise ParameterError("labels, omegas and amplitudes need one entry per spectrum")
    ref = None if omega_ref is None else _vector(omega_ref, "omega_ref")
    if ref is not None and (ref.shape != (len(labels),) or np.any(ref <= 0)):
        raise ParameterError("omega_ref needs one positive value (rad/s) per spectrum")
    ax = _axes(ax)
    right = xmax
    for k, (lab, om, amp) in enumerate(zip(labels, omegas, amplitudes, strict=True)):
        om, amp = _vector(om, "omegas"), np.abs(_vector(amp, "amplitudes"))
        if om.shape != amp.shape:
            raise ParameterError(f"spectrum {k}: omegas and amplitudes differ in length")
        xs = om / ref[k] if ref is not None else om
        top = float(amp.max()) or 1.0
        ax.plot(xs, amp / top + spacing * k, color=f"C{k % 10}", lw=0.8)
        text = f"{lab:g} m/s" if isinstance(lab, (int, float, np.number)) else str(lab)
        at = right if right is not None else float(xs.max())
        ax.text(at * (1 + 1 / 60), spacing * k + 0.1, text, fontsize=8)
    if ref is not None:
        ax.axvline(1.0, color="k", lw=0.7, ls="--", label="ω₁ from the eigen-solver")
        ax.set_xlabel("ω / ω₁(V)")
        ax.legend(fontsize=8, loc="upper left")
    else:
        ax.set_xlabel("angular frequency ω (rad/s)")
    if right is not None:
        ax.set_xlim(0, right)
    ax.set_ylabel("amplitude spectrum (normalized, offset)")
    ax.set_yticks([])
    if title:
        ax.set_title(title, fontsize=10)
    return ax


def _bode_curve(omega, response, phase) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(ω in rad/s, |W| in m, phase in rad) from the arguments :func:`bode` accepts."""
    if response is None:
        if not hasattr(omega, "amplitude"):
            raise ParameterError("bode needs omega and response, or a FrequencyResponse")
        omega, response, phase = omega.omega, omega.amplitude[:, 0], omega.phase[:, 0]
    om = _vector(omega, "omega")
    response = np.asarray(response)
    if np.iscomplexobj(response):
        amplitude, phase = np.abs(response), np.angle(response)
    else:
        if phase is None:
            raise ParameterError("bode needs phase (rad) when response is real (|W|, m)")
        amplitude, phase = response.astype(float), np.asarray(phase, dtype=float)
    if amplitude.shape != om.shape or phase.shape != om.shape:
        raise ParameterError(f"response and phase must have the shape of omega {om.shape}")
    return om, amplitude, phase


def bode(omega, response=None, phase=None, *, axes=None, label: str | None = None,
         color=None, mode_omegas=None, scale: float = 1e-3):
    """Bode plot: amplitude (m, log scale) and phase (rad) against angular frequency.

    Parameters
    ----------
    omega : array_like or FrequencyResponse
        Angular frequencies, rad/s; or a :class:`~gyroshell.FrequencyResponse`
        (its load-point column is drawn; omit ``response``).
    response : array_like, optional
        Complex displacement amplitude, m, or its modulus |W| (then give ``phase``).
    phase : array_like, optional
        Phase, rad, when ``response`` is the modulus.
    axes : matplotlib.axes.Axes or a pair of them, optional
        (amplitude, phase), or one Axes for the amplitude; None: a new two-row figure.
    label : str, optional
        Legend label of the curve.
    color : optional
        matplotlib colour of the curve and its mode ticks.
    mode_omegas : array_like, optional
        Eigenfrequencies, rad/s, drawn as dotted vertical lines on the amplitude.
    scale : float
        ω is drawn as ω·scale; the default 1e-3 gives 10³ rad/s, 1 gives rad/s.

    Returns
    -------
    numpy.ndarray of matplotlib.axes.Axes
        The (amplitude, phase) Axes.
    """
    om, amplitude, phase = _bode_curve(omega, response, phase)
    if axes is None:
        plt = pyplot()
        _, axes = plt.subplots(2, 1, sharex=True, figsize=(9.0, 7.0))
    axes = np.asarray(axes).ravel()
    if axes.size not in (1, 2):
        raise ParameterError("axes must be one Axes (amplitude) or a pair (amplitude, phase)")
    line, = axes[0].semilogy(om * scale, amplitude, lw=1.0, color=color, label=label)
    if axes.size == 2:
        axes[1].plot(om * scale, phase, lw=1.0, color=line.get_color())
        axes[1].set_ylabel("phase (rad)")
    for w in ([] if mode_omegas is None else np.asarray(mode_omegas, dtype=float)):
        axes[0].axvline(w * scale, color=line.get_color(), lw=0.6, ls=":", alpha=0.8)
    unit = "rad/s" if scale == 1 else f"{1 / scale:.0e} rad/s".replace("1e+03", "10³")
    axes[0].set_ylabel("load-point amplitude |W| (m)")
    axes[-1].set_xlabel(f"angular frequency ω ({unit})")
    for a in axes:
        a.grid(alpha=0.3)
    return axes
