"""Signal-analysis helpers on signals whose answer is known."""

from __future__ import annotations

import numpy as np
import pytest

from gyroshell.studies.signal import (
    dominant_period,
    dominant_wavelength,
    first_departure,
    front_position,
)


@pytest.mark.slow
def test_dominant_period_of_a_decaying_mixture_with_drift():
    t = np.arange(2000) * 2e-6
    w = (1.0 + 0.3 * np.exp(-t / 3e-3) * np.cos(2 * np.pi * t / 50e-6)
         + 0.1 * np.cos(2 * np.pi * t / 23e-6) + 0.5 * t / t[-1])
    assert dominant_period(t, w) == pytest.approx(50e-6, rel=2e-3)


@pytest.mark.slow
def test_lowest_peak_period_picks_the_band_edge():
    t = np.arange(4000) * 2e-6
    w = 0.5 * np.cos(2 * np.pi * t / 200e-6) + 1.0 * np.cos(2 * np.pi * t / 150e-6)
    assert dominant_period(t, w) == pytest.approx(150e-6, rel=2e-3)
    assert dominant_period(t, w, lowest_fraction=0.25) == pytest.approx(200e-6, rel=2e-3)


def test_dominant_wavelength():
    x = np.linspace(0, 0.1, 800)
    assert dominant_wavelength(x, np.sin(2 * np.pi * x / 2.1e-3)) == pytest.approx(2.1e-3,
                                                                                   rel=1e-3)


def test_front_position_and_departure():
    x = np.linspace(-1, 1, 201)
    w = np.where(np.abs(x) < 0.295, 1.0, 0.0)
    assert front_position(x, w, 0.0, 0.5, +1) == pytest.approx(0.29)
    assert front_position(x, w, 0.0, 0.5, -1) == pytest.approx(-0.29)
    t = np.linspace(0, 1, 101)
    assert first_departure(t, np.where(t > 0.42, 1.1, 1.0), np.ones_like(t), 0.05) == \
        pytest.approx(0.43)


def test_amplitude_spectrum_is_the_rms_of_a_sine_in_its_units():
    from gyroshell.studies.signal import amplitude_spectrum

    t = np.arange(1000) * 1e-5
    f, a = amplitude_spectrum(3e-7 * np.cos(2 * np.pi * 2000.0 * t) + 1.0, 1e-5)
    assert f[np.argmax(a)] == pytest.approx(2000.0, rel=1e-3)
    assert a.max() == pytest.approx(3e-7 / np.sqrt(2), rel=2e-2)  # window scalloping < 2 %


@pytest.mark.parametrize(("call", "match"), [
    (lambda: dominant_period(np.arange(5.0), np.ones(5)), "at least 8"),
    (lambda: dominant_period(np.arange(10.0), np.ones(9)), "as many samples"),
    (lambda: dominant_period(np.arange(10.0), np.full(10, np.nan)), "samples must be finite"),
])
def test_analysis_refuses_bad_records(call, match):
    from gyroshell import ParameterError

    with pytest.raises(ParameterError, match=match):
        call()
