"""Signal analysis of computed histories and profiles: dominant period, wavelength, fronts.

Plain functions on arrays (SI units in, SI units out), used by the studies to measure what
the paper reads off its figures.
"""

from __future__ import annotations

import numpy as np

from ..core import validation
from ..core.errors import ParameterError

#: Fewest samples for a spectral estimate.
MIN_SAMPLES = 8


def amplitude_spectrum(samples: np.ndarray, spacing: float, *, pad_factor: int = 16
                       ) -> tuple[np.ndarray, np.ndarray]:
    """Frequencies (1/unit of ``spacing``) and RMS amplitudes (unit of the samples) of the
    de-meaned, Hann-windowed record zero-padded to ``pad_factor`` times its length (rounded up
    to a power of two): the square root of :func:`scipy.signal.periodogram`'s spectrum.

    Examples
    --------
    >>> t = np.arange(256) * 1e-3
    >>> f, a = amplitude_spectrum(2.0 * np.sin(2 * np.pi * 125.0 * t), 1e-3)
    >>> float(f[np.argmax(a)]), round(float(a.max()), 3)     # Hz, RMS of the sine
    (125.0, 1.414)
    """
    from scipy.signal import periodogram

    samples = validation.vector("samples", samples, np.size(samples))
    if samples.size < MIN_SAMPLES:
        raise ParameterError(f"samples must hold at least {MIN_SAMPLES} values for a "
                             f"spectral estimate, got {samples.size}")
    spacing = validation.positive("sample spacing", spacing)
    pad_factor = validation.integer("pad_factor", pad_factor, low=1)
    n_fft = int(2 ** np.ceil(np.log2(samples.size * pad_factor)))
    freqs, power = periodogram(samples, fs=1.0 / spacing, window="hann", nfft=n_fft,
                               detrend="constant", scaling="spectrum")
    return freqs, np.sqrt(power)


def _refine(spectrum: np.ndarray, k: int) -> float:
    """Bin index of the peak at k refined by a parabola through log amplitudes."""
    if not 0 < k < spectrum.size - 1:
        return float(k)
    a, b, c = np.log(spectrum[k - 1:k + 2] + 1e-300)
    denom = a - 2 * b + c
    return k + (0.5 * (a - c) / denom if denom < 0 else 0.0)


def _spectral_peak(samples: np.ndarray, spacing: float, *, pad_factor: int,
                   min_frequency: float, lowest_fraction: float | None = None) -> float:
    """Frequency of the largest spectral peak above ``min_frequency`` or, with
    ``lowest_fraction``, of the lowest local peak reaching that fraction of the largest."""
    freqs, spectrum = amplitude_spectrum(samples, spacing, pad_factor=pad_factor)
    spectrum[freqs < min_frequency] = 0.0
    k = int(np.argmax(spectrum))
    if not spectrum[k] > 0:
        raise ParameterError("signal has no oscillating content")
    if lowest_fraction is not None:
        from scipy.signal import find_peaks

        peaks, _ = find_peaks(spectrum, height=lowest_fraction * spectrum[k])
        k = int(peaks[0]) if peaks.size else k
    return float(_refine(spectrum, k) * (freqs[1] - freqs[0]))


def _uniform_axis(name: str, axis, values) -> np.ndarray:
    """A finite sample axis with as many points as ``values`` (at least MIN_SAMPLES)."""
    axis = validation.vector(name, axis, np.size(axis))
    if axis.size != np.size(values) or axis.size < MIN_SAMPLES:
        raise ParameterError(f"{name} must hold as many samples as the values (at least "
                             f"{MIN_SAMPLES}), got {axis.size} and {np.size(values)}")
    return axis


def dominant_period(t: np.ndarray, w: np.ndarray, *, pad_factor: int = 16,
                    min_frequency: float | None = None,
                    lowest_fraction: float | None = None) -> float:
    """Dominant period of a uniformly sampled history w(t), s.

    The mean is removed, a Hann window applied, the record zero-padded ``pad_factor``
    times and the spectral peak refined by a parabola in log amplitude. Frequencies below
    ``min_frequency`` (Hz; default two cycles per record) are ignored, so a slow drift of the
    mean does not count as the period.

    With ``lowest_fraction`` (e.g. 0.25) the period of the *lowest-frequency* spectral peak
    that reaches that fraction of the largest is returned instead: the band edge of a
    response whose spectrum starts sharply at the lowest natural frequency.

    Parameters
    ----------
    t : numpy.ndarray
        Uniform sample times, s.
    w : numpy.ndarray
        Samples, any unit.
    """
    t = _uniform_axis("t", t, w)
    dt = float(t[1] - t[0])
    if not np.allclose(np.diff(t), dt, rtol=1e-6, atol=0):
        raise ParameterError("t must be uniformly spaced")
    duration = dt * (t.size - 1)
    fmin = 2.0 / duration if min_frequency is None else min_frequency
    return 1.0 / _spectral_peak(w, dt, pad_factor=pad_factor, min_frequency=fmin,
                                lowest_fraction=lowest_fraction)


def dominant_wavelength(x: np.ndarray, w: np.ndarray, *, pad_factor: int = 16) -> float:
    """Dominant wavelength of a uniformly sampled profile w(x), m (see dominant_period)."""
    x = _uniform_axis("x", x, w)
    dx = float(x[1] - x[0])
    return 1.0 / _spectral_peak(w, dx, pad_factor=pad_factor,
                                min_frequency=2.0 / (dx * (x.size - 1)))


def front_position(x: np.ndarray, w: np.ndarray, origin: float, threshold: float,
                   direction: int) -> float:
    """Farthest point from ``origin`` in ``direction`` (+1 downstream, −1 upstream) where
    |w| exceeds ``threshold``, m; ``origin`` itself if nowhere."""
    x = np.asarray(x, dtype=float)
    side = (x - origin) * direction >= 0
    hit = side & (np.abs(np.asarray(w)) > threshold)
    if not np.any(hit):
        return float(origin)
    return float(x[hit][np.argmax(np.abs(x[hit] - origin))])


def first_departure(t: np.ndarray, a: np.ndarray, b: np.ndarray, fraction: float) -> float:
    """First time at which |a − b| exceeds ``fraction`` × max|b|, s (NaN if never)."""
    a, b = np.asarray(a), np.asarray(b)
    over = np.abs(a - b) > fraction * np.abs(b).max()
    return float(np.asarray(t)[np.argmax(over)]) if np.any(over) else float("nan")
