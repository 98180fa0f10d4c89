"""Shared set-ups for the air-bearing tests: the classical flexible-foil limit."""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from gyroshell import TapeParameters
from gyroshell.bearing import AirParameters, BearingModel
from gyroshell.bearing.contact import ContactParameters

#: The head–tape interface the solver had before the contact-recording models (and the
#: tests of its mechanisms: contact sets, point contacts on rounded corners, the foil
#: bearing's closed forms): first-order slip (flow factors "auto" resolve to none under
#: the hard wall) and a hard wall at a 20 nm gap.
FIRST_ORDER = AirParameters(rarefaction="first-order")
HARD = ContactParameters(law="hard")
#: The same on the command line.
LEGACY_CLI = ["--rarefaction", "first-order", "--contact", "hard"]

#: A perfectly flexible tape: D so small that the bending length √(D/T) is 0.1 µm.
FLEXIBLE = TapeParameters(bending_rigidity=1e-12, foundation_stiffness=0.0)
#: Incompressible film without slip: the classical foil-bearing film.
CLASSICAL_AIR = AirParameters(compressible=False, mean_free_path=0.0, rarefaction="first-order")
WRAP = math.radians(15.0)


def flexible_model(nx: int = 1600, *, velocity: float = 4.0, air=CLASSICAL_AIR,
                   params=FLEXIBLE, wrap_angle: float = WRAP) -> BearingModel:
    return BearingModel(params, air, velocity=velocity, wrap_angle=wrap_angle,
                        infinitely_wide=True, nx=nx, contact=HARD)


def foil_scale(model: BearingModel) -> float:
    """R ε^(2/3), ε = 6μV/(T − ρV²), m."""
    eps = 6 * model.air.viscosity * model.velocity / model.effective_tension()
    return model.params.radius * eps ** (2 / 3)


def _rhs(_x, y):
    """The scaled foil-bearing equation H''' = −(H − 1)/H³ (x along the tape's motion)."""
    return [y[1], y[2], -(y[0] - 1.0) / y[0] ** 3]


def classical_foil_constants(delta: float = 1e-7) -> tuple[float, float]:
    """(C, H_min): h₀ = C R ε^(2/3) and h_min/h₀ of Blok & van Rossum / Eshel & Elrod.

    Scaling h = h₀ H, x = h₀ ε^(−1/3) X turns the flexible tape −T h''' = p' and Reynolds'
    p' = 6μV (h − h₀)/h³ into H''' = −(H − 1)/H³, and the far spans (h'' = 1/R) into
    H'' → h₀ ε^(−2/3)/R = C. Entrance: from the plateau the only decaying mode is e^(−X);
    integrated backwards it gives C. Exit: the growing modes e^(X/2) cos(√3 X/2 + φ); the
    phase φ is shot so that H'' → C downstream, and H_min is the constriction's depth.
    """
    entrance = solve_ivp(_rhs, [0.0, -400.0], [1 + delta, -delta, delta],
                         rtol=1e-12, atol=1e-14)
    C = entrance.y[2, -1]
    r = complex(0.5, math.sqrt(3) / 2)

    def exit_run(phi, dense=False):
        y0 = [1 + delta * math.cos(phi), delta * (r * np.exp(1j * phi)).real,
              delta * (r * r * np.exp(1j * phi)).real]
        low = lambda _x, y: y[0] - 0.05  # noqa: E731 - a collapsed film ends the run
        low.terminal = True
        return solve_ivp(_rhs, [0.0, 400.0], y0, rtol=1e-12, atol=1e-14, events=low,
                         dense_output=dense)

    def mismatch(phi):
        run = exit_run(phi)
        return (run.y[2, -1] if run.status == 0 else -1.0) - C

    phis = np.linspace(0.0, 2 * math.pi, 37)
    values = [mismatch(phi) for phi in phis]
    k = next(i for i in range(len(phis) - 1)
             if values[i] > 0 > values[i + 1] and values[i + 1] > -0.9)
    phi = brentq(mismatch, phis[k], phis[k + 1], xtol=1e-13)
    run = exit_run(phi, dense=True)
    xs = np.linspace(0.0, min(run.t[-1], 60.0), 600001)
    return float(C), float(run.sol(xs)[0].min())


def flux_spread_1d(sol) -> tuple[float, float, float]:
    """(max |F − F₀|, the largest pressure-driven term (p h³ + 6 λ p_a h²) p/Δx, |F₀|) of
    a 1-D steady film's face fluxes F: one constant in = out to the round-off of those
    terms (large where the spans' gap is wide)."""
    m, air = sol.model, sol.model.air
    flux = m.film.fluxes(sol.pressure, sol.spacing)[0].flux[:, 0]
    H, P = sol.spacing[:, 0], sol.pressure[:, 0]
    h, p = 0.5 * (H[1:] + H[:-1]), 0.5 * (P[1:] + P[:-1])
    terms = (p * h**3 + 6 * air.mean_free_path * air.ambient_pressure * h**2) * p / np.diff(m.x)
    return float(np.max(np.abs(flux - flux[0]))), float(terms.max()), float(abs(flux[0]))

