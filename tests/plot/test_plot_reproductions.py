"""The reproductions' drawings as public gyroshell.plot functions: each returns its Axes and
draws the lines, labels and units it says, from small synthetic data or real results."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.axes import Axes

from gyroshell import TapeModel, TapeParameters, march
from gyroshell import plot as gplot
from gyroshell.core.errors import ParameterError
from gyroshell.engines.frequency_response import frequency_response

T = np.linspace(0.0, 100e-6, 51)          # s
W = 1e-9 * (1 - np.cos(2 * np.pi * T / 50e-6))   # m


def test_load_point_history_draws_the_history_and_its_steady_state():
    fig, ax = plt.subplots()
    assert gplot.load_point_history(T, W, steady=1e-9, velocity=50.0, ax=ax) is ax
    history, steady_dot = ax.lines[0], ax.lines[-1]
    assert len(ax.lines) == 3      # history, dashed steady line, steady dot
    np.testing.assert_allclose(history.get_xdata(), T * 1e6)   # drawn in µs
    np.testing.assert_allclose(history.get_ydata(), W)
    np.testing.assert_allclose(steady_dot.get_xdata(), [100.0])
    assert ax.get_xlabel() == "time t (µs)" and "(m)" in ax.get_ylabel()
    assert any("V = 50 m/s" in t.get_text() for t in ax.texts)
    # scaled (nondimensional) and without a steady state: one line
    ax2 = gplot.load_point_history(T, W, scale=1e9, ylabel="w k / P₀")
    assert isinstance(ax2, Axes) and len(ax2.lines) == 1
    np.testing.assert_allclose(ax2.lines[0].get_ydata(), W * 1e9)
    with pytest.raises(ParameterError, match="shape of times"):
        gplot.load_point_history(T, W[:-1])


def test_load_point_history_of_a_transient_result():
    res = march(TapeModel(TapeParameters(length_ratio=2, spacing=6.35e-3 / 8)), 20.0,
                dt=2e-6, steps=10, progress=False)
    ax = gplot.load_point_history(res)
    np.testing.assert_allclose(ax.lines[0].get_ydata(), res.load_point)
    assert any("V = 20 m/s" in t.get_text() for t in ax.texts)


def test_wireframe_draws_the_field_in_mm_and_nm():
    x, y = np.linspace(0, 0.02, 21), np.linspace(0, 0.005, 6)       # m
    w = 1e-8 * np.outer(np.sin(np.pi * x / 0.02), np.ones_like(y))  # m
    fig = plt.figure()
    ax = fig.add_subplot(projection="3d")
    assert gplot.wireframe(x, y, w, ax=ax, title="t = 6 µs") is ax
    assert len(ax.collections) == 1                                 # one wire frame
    assert (ax.get_xlabel(), ax.get_ylabel(), ax.get_zlabel()) == ("x (mm)", "y (mm)",
                                                                    "w (nm)")
    np.testing.assert_allclose(ax.get_zlim(), (-6.0, 10.0))        # -0.6 max..max, nm
    assert ax.get_title() == "t = 6 µs"
    assert hasattr(gplot.wireframe(x, y, w, zmax=2e-8), "get_zlim")  # own 3-D figure
    with pytest.raises(ParameterError, match="shape"):
        gplot.wireframe(x, y, w.T)
    with pytest.raises(ParameterError, match="3-D Axes"):
        gplot.wireframe(x, y, w, ax=plt.subplots()[1])


def test_waterfall_raises_each_line_by_its_rank():
    times = np.arange(4) * 32e-6
    x = np.linspace(0, 0.1, 30)
    lines = 1e-9 * np.sin(np.outer(np.arange(1, 5), x / 0.1 * np.pi))
    fig, ax = plt.subplots()
    assert gplot.waterfall(times, x, lines, ax=ax, gap=2e-9, load_point=0.05) is ax
    curves = [line for line in ax.lines if line.get_linestyle() == "-"]
    assert len(curves) == 4 and len(ax.lines) == 5          # plus the load-point line
    for k, c in enumerate(curves):
        np.testing.assert_allclose(c.get_ydata(), lines[k] + 2e-9 * k)
        np.testing.assert_allclose(c.get_xdata(), x * 1e3)
    assert ax.get_xlabel().startswith("x (mm)")
    assert "2 nm per 32 µs" in ax.get_ylabel()
    assert [t.get_text() for t in ax.texts][:4] == ["0", "32", "64", "96"]
    with pytest.raises(ParameterError, match="shape"):
        gplot.waterfall(times, x, lines.T)


def test_period_vs_velocity_draws_each_measure_in_microseconds():
    v = np.array([0.0, 50.0, 90.0])
    p = np.array([50e-6, 62e-6, 180e-6])
    fig, ax = plt.subplots()
    out = gplot.period_vs_velocity(v, p, transient_edge=p * 1.01, transient=p * 0.9,
                                   critical_speed=100.0, ax=ax)
    assert out is ax and ax.get_yscale() == "log"
    labels = [line.get_label() for line in ax.lines]
    assert sum(lab.startswith("transient") for lab in labels) == 2
    assert any(lab.startswith("critical speed 100.00 m/s") for lab in labels)
    np.testing.assert_allclose(ax.lines[0].get_ydata(), p * 1e6)
    assert ax.get_xlabel() == "tape speed V (m/s)" and "(µs)" in ax.get_ylabel()
    only_eigen = gplot.period_vs_velocity(v, p)
    assert len([ln for ln in only_eigen.lines if not ln.get_label().startswith("_")]) == 1
    with pytest.raises(ParameterError, match="transient must have the shape"):
        gplot.period_vs_velocity(v, p, transient=p[:2])


def test_bode_of_a_single_mass_oscillator():
    """W = 1/(k - m ω² + i c ω): amplitude peaks at √(k/m), phase passes -π/2 there."""
    m, k, c = 1.0, 1e8, 200.0
    omega = np.linspace(0.0, 2e4, 401)
    response = 1 / (k - m * omega**2 + 1j * c * omega)
    axes = gplot.bode(omega, response, label="oscillator", mode_omegas=[1e4])
    assert len(axes) == 2 and all(isinstance(a, Axes) for a in axes)
    amp, ph = axes[0].lines[0], axes[1].lines[0]
    assert axes[0].get_yscale() == "log"
    assert amp.get_xdata()[np.argmax(amp.get_ydata())] == pytest.approx(10.0)   # 10³ rad/s
    assert ph.get_ydata()[200] == pytest.approx(-np.pi / 2)
    assert len(axes[0].lines) == 2                       # curve and the mode tick
    assert axes[0].get_ylabel() == "load-point amplitude |W| (m)"
    assert axes[1].get_ylabel() == "phase (rad)"
    assert axes[1].get_xlabel() == "angular frequency ω (10³ rad/s)"
    fig, pair = plt.subplots(2, 1)
    same = gplot.bode(omega, np.abs(response), np.angle(response), axes=pair, scale=1.0)
    assert same[0] is pair[0] and same[1].get_xlabel() == "angular frequency ω (rad/s)"
    with pytest.raises(ParameterError, match="phase"):
        gplot.bode(omega, np.abs(response))


def test_bode_of_a_frequency_response():
    model = TapeModel(TapeParameters(length_ratio=2, spacing=6.35e-3 / 8))
    res = frequency_response(model, 0.0, np.linspace(1e3, 5e4, 12), damping=30.0,
                             progress=False)
    axes = gplot.bode(res)
    np.testing.assert_allclose(axes[0].lines[0].get_ydata(), res.amplitude[:, 0])
    np.testing.assert_allclose(axes[1].lines[0].get_ydata(), res.phase[:, 0])


def test_spectra_are_normalized_stacked_and_scaled_by_their_reference():
    om = np.linspace(0.0, 3e4, 31)
    amps = [np.exp(-((om - 1e4) / 2e3) ** 2) * 5.0, np.exp(-((om - 2e4) / 2e3) ** 2)]
    fig, ax = plt.subplots()
    out = gplot.spectra([0.0, 50.0], [om, om], amps, omega_ref=[1e4, 2e4], ax=ax, xmax=3.0)
    assert out is ax
    curves = ax.lines[:2]
    for k, c in enumerate(curves):
        # each peak is at ω/ω_ref = 1 and at height 1 above its offset 1.1 k
        assert c.get_xdata()[np.argmax(c.get_ydata())] == pytest.approx(1.0)
        assert c.get_ydata().max() == pytest.approx(1.0 + 1.1 * k)
    assert len(ax.lines) == 3 and ax.get_xlabel() == "ω / ω₁(V)"
    assert [t.get_text() for t in ax.texts] == ["0 m/s", "50 m/s"]
    plain = gplot.spectra(["a"], [om], [amps[0]])
    assert plain.get_xlabel() == "angular frequency ω (rad/s)" and len(plain.lines) == 1
    with pytest.raises(ParameterError, match="one positive value"):
        gplot.spectra(["a"], [om], [amps[0]], omega_ref=[0.0])
    with pytest.raises(ParameterError, match="one entry per spectrum"):
        gplot.spectra(["a", "b"], [om], [amps[0]])


@pytest.mark.slow
def test_head_histories_draw_w_only_while_in_contact():
    t = np.linspace(0.0, 1e-3, 101)
    contact = np.column_stack([(t < 5e-4).astype(float), (t >= 5e-4).astype(float)])
    w = np.column_stack([1e-9 * np.ones_like(t), -2e-9 * np.ones_like(t)])
    axes = gplot.head_histories(t, w, contact)
    assert len(axes) == 3 and all(isinstance(a, Axes) for a in axes)
    assert len(axes[0].lines) == 2                          # one envelope per head
    for k in (0, 1):
        y = axes[k + 1].lines[0].get_ydata()
        np.testing.assert_array_equal(np.isnan(y), contact[:, k] == 0)
        np.testing.assert_allclose(y[contact[:, k] > 0], w[contact[:, k] > 0, k] * 1e9)
        assert axes[k + 1].get_ylabel() == "w under head (nm)"
    assert axes[-1].get_xlabel() == "time t (µs)"
    with pytest.raises(ParameterError, match="heads \\+ 1"):
        gplot.head_histories(t, w, contact, axes=plt.subplots(2, 1)[1])
    with pytest.raises(ParameterError, match="one column per head"):
        gplot.head_histories(t, w, contact[:, :1])


def test_edge_reflection_draws_both_histories_and_the_two_instants():
    fig, ax = plt.subplots()
    assert gplot.edge_reflection(T, W, 0.5 * W, t_edge=20e-6, t_reflection=45e-6, ax=ax) is ax
    tape, reference, edge, back = ax.lines
    np.testing.assert_allclose(tape.get_xdata(), T * 1e6)           # µs
    np.testing.assert_allclose(reference.get_ydata(), 0.5 * W * 1e9)  # nm
    assert list(edge.get_xdata()) == [20.0, 20.0] and list(back.get_xdata()) == [45.0, 45.0]
    assert ax.get_xlabel() == "time t (µs)" and ax.get_ylabel().endswith("(nm)")
    with pytest.raises(ParameterError, match="reference must have the shape of times"):
        gplot.edge_reflection(T, W, W[:-1], t_edge=1e-6, t_reflection=2e-6)


def test_wave_fronts_one_colour_per_speed_two_sides():
    import pandas as pd

    t = np.array([20e-6, 40e-6, 60e-6])
    table = pd.concat([pd.DataFrame({"velocity": v, "t": t, "downstream": (100 + v) * t,
                                     "upstream": (100 - v) * t}) for v in (0.0, 50.0)])
    ax = gplot.wave_fronts(table, speeds={(50.0, "downstream"): 150.0})
    assert len(ax.lines) == 4
    np.testing.assert_allclose(ax.lines[2].get_ydata(), 150 * t * 1e3)   # mm
    assert ax.lines[0].get_color() == ax.lines[1].get_color() != ax.lines[2].get_color()
    assert "(150 m/s)" in ax.lines[2].get_label()
    assert ax.get_ylabel() == "front distance from the load (mm)"
    with pytest.raises(ParameterError, match="table needs the columns"):
        gplot.wave_fronts(table.drop(columns="upstream"))
