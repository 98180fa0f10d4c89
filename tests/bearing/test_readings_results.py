"""The designer's readings on solved bearing states (BearingSolution): they are plain JSON
in the summary, survive save -> load bit for bit, draw their figures, and the
transducer-line spacing converges at second order with the transducer off the nodes."""

from __future__ import annotations

import json
import math
import warnings

import numpy as np
import pytest
from bearing_cases import FIRST_ORDER, HARD

from gyroshell import TapeParameters
from gyroshell.bearing import BearingModel
from gyroshell.bearing.head import Cylinder, FlatHead, Module
from gyroshell.bearing.model import BearingGridWarning
from gyroshell.bearing.steady import solve_steady

READING_KEYS = ("transducer_lines", "tents", "corner_forces", "land_forces", "viscous_drag",
                "friction_drag", "drag", "tension_rise", "tension_ratio", "friction")


def _cylinder(nx=None, *, wide=True, velocity=4.0, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", BearingGridWarning)
        return BearingModel(TapeParameters(width=3e-3), FIRST_ORDER, velocity=velocity,
                            wrap_angle=math.radians(15), infinitely_wide=wide, nx=nx, **kw,
                            contact=HARD)


def _plain(value) -> bool:
    """Only dicts, lists, str, bool, int, finite float and None, recursively."""
    if isinstance(value, dict):
        return all(isinstance(k, str) and _plain(v) for k, v in value.items())
    if isinstance(value, list):
        return all(_plain(v) for v in value)
    if isinstance(value, float):
        return math.isfinite(value)
    return value is None or type(value) in (str, bool, int)


def test_readings_are_plain_json_in_the_summary():
    sol = solve_steady(_cylinder(60))
    summary = sol.summary()
    assert set(READING_KEYS) <= set(summary)
    assert _plain(summary)
    assert json.loads(json.dumps(summary, allow_nan=False)) == summary
    # the cylinder's tangent points are its corners, its arc its land; no contact here
    assert len(summary["corner_forces"]) == 2 and len(summary["land_forces"]) == 1
    assert summary["friction_drag"] == 0.0 and summary["viscous_drag"] > 0.0
    assert summary["drag"] == summary["viscous_drag"] == summary["tension_rise"]


def _line_orders(values) -> np.ndarray:
    """Observed orders from successive differences of values on grids halved each time."""
    d = np.abs(np.diff(np.asarray(values), axis=0))
    return np.log2(d[:-1] / d[1:])


def test_transducer_line_spacing_converges_at_second_order_off_the_nodes():
    x_t = 1.2345e-3                      # m: on the wrap, off every node of these grids
    head = Cylinder(math.radians(15), transducers=(x_t,))
    values = []
    for nx in (100, 200, 400, 800):
        sol = solve_steady(BearingModel(TapeParameters(), FIRST_ORDER, velocity=4.0,
                                        head=head, infinitely_wide=True, nx=nx, span=4e-3,
                                        contact=HARD))
        (line,) = sol.transducer_lines
        assert not np.any(np.isclose(sol.x, x_t, rtol=0, atol=1e-9))
        values.append(line.centre)
    assert _line_orders(values) == pytest.approx([2.0, 2.0], abs=0.1)


# ----- flat heads: corner forces, friction and the capstan law ----------------------------
DEG = math.pi / 180.0
TAPE = TapeParameters()


def _dry_flat(friction, *, span, t_in=2 * DEG, t_out=2 * DEG, nx=None):
    """Dry (no air, V = 0, k = 0) infinitely wide tape over one 1 mm flat land."""
    head = FlatHead((Module(1e-3),), t_in, t_out, friction=friction)
    return solve_steady(BearingModel(TAPE, FIRST_ORDER, velocity=0.0, head=head,
                                     infinitely_wide=True, dry=True, span=span, nx=nx,
                                     contact=HARD))


@pytest.mark.parametrize("t_in, t_out", [(2 * DEG, 2 * DEG), (1 * DEG, 3 * DEG)])
def test_dry_corner_forces_tend_to_t_theta_as_the_spans_grow(t_in, t_out):
    """Straight spans at the wraps and sharp corners: the corners carry T (θ_in + θ_out)
    per unit width together (the vertical balance of the spans' tension), each T θ when the
    wraps are equal; with spans S pinned at the dry string's ends, to within O(λ/S),
    λ = √(D/T). Unequal wraps share it otherwise: the tape over a land a few λ long
    carries shear from one corner to the other. The corners carry all the contact (none on
    the land), one node each, and corner plus land forces are the total to round-off."""
    lam = math.sqrt(TAPE.D / TAPE.tension)
    excess = []
    for span in (20 * lam, 40 * lam):
        sol = _dry_flat(0.0, span=span, t_in=t_in, t_out=t_out)
        lead, trail = sol.corner_forces
        (land,) = sol.land_forces
        assert land.force == 0.0 and land.nodes == 0 and lead.nodes == trail.nodes == 1
        assert lead.force + trail.force == pytest.approx(sol.contact_force, rel=1e-14)
        assert (lead.centroid, trail.centroid) == pytest.approx((-0.5e-3, 0.5e-3), rel=1e-12)
        excess.append((lead.force + trail.force) / (TAPE.tension * (t_in + t_out)) - 1)
        if t_in == t_out:
            assert lead.force == pytest.approx(trail.force, rel=1e-9)
    assert 0 < excess[1] < excess[0] < lam / (20 * lam)
    assert excess[0] / excess[1] == pytest.approx(2.0, rel=0.05)     # O(λ/S)


@pytest.mark.parametrize("t_in, t_out", [(2 * DEG, 2 * DEG), (1 * DEG, 3 * DEG)])
def test_friction_drag_of_dry_corners_is_mu_times_their_forces_capstan_to_first_order(
        t_in, t_out):
    """Coulomb friction μ_f at the corners: the drag is μ_f Σ F_c and, the model keeping
    the tension uniform (the contact does not depend on μ_f), the tension ratio is
    1 + μ_f Σ F_c / T = 1 + μ_f θ_t, θ_t = Σ F_c / T the angle the corners turn the tape
    by (θ_in + θ_out to O(λ/S)): the capstan law e^{μ_f θ_t} to first order. The difference
    is O((μ_f θ)²), about (μ_f θ)²/2: four times larger when μ_f doubles."""
    lam = math.sqrt(TAPE.D / TAPE.tension)
    gaps = []
    for mu_f in (0.3, 0.6):
        sol = _dry_flat(mu_f, span=40 * lam, t_in=t_in, t_out=t_out)
        turn = sum(c.force for c in sol.corner_forces) / TAPE.tension
        assert turn == pytest.approx(t_in + t_out, rel=lam / (20 * lam))
        assert sol.viscous_drag == 0.0                       # no air at rest
        assert sol.friction_drag == pytest.approx(mu_f * turn * TAPE.tension, rel=1e-14)
        assert sol.drag == sol.friction_drag == sol.tension_rise   # per unit width
        assert sol.tension_ratio == pytest.approx(1 + mu_f * turn, rel=1e-15)
        gaps.append(math.exp(mu_f * turn) - sol.tension_ratio)
        assert gaps[-1] == pytest.approx((mu_f * turn) ** 2 / 2, rel=0.05)
    assert gaps[1] / gaps[0] == pytest.approx(4.0, rel=0.05)


def test_flying_flat_head_readings_keep_their_books():
    """At speed over a flat land (1-D): the sub-ambient film pulls the tape onto the
    corners, which carry all the contact; corner plus land forces are the total; friction
    drag is μ_f times it; the tape tents next to both corners on the land side, above the
    transducer's spacing, with nothing on the span side (the flanks fall away)."""
    mu_f = 0.2
    head = FlatHead((Module(1e-3),), 2 * DEG, 2 * DEG, transducers=(0.0,), friction=mu_f)
    sol = solve_steady(BearingModel(TAPE, FIRST_ORDER, velocity=4.0, head=head,
                                    infinitely_wide=True, nx=320, span=1e-3, contact=HARD))
    shares = sol.corner_forces + sol.land_forces
    assert sum(s.force for s in shares) == pytest.approx(sol.contact_force, rel=1e-14)
    assert sol.contact_force > 0 and sol.land_forces[0].force == 0.0
    assert sol.friction_drag == pytest.approx(mu_f * sol.contact_force, rel=1e-15)
    assert sol.drag == pytest.approx(sol.viscous_drag + sol.friction_drag, rel=1e-15)
    assert sol.viscous_drag == pytest.approx(
        float(np.sum(sol.shear_stress * sol.model.film.cell_area)), rel=1e-15)
    (line,) = sol.transducer_lines
    land = {t.corner: t for t in sol.tents if t.side == "land"}
    for corner, tent in land.items():
        assert tent.height > line.centre and 0 < abs(tent.x - corner) < 0.5e-3
        assert tent.drop > 0
    assert all(t.height is None for t in sol.tents if t.side == "span")
    # the contact pressure is the corner force over the corner node's control width
    i = int(np.argmax(sol.contact_pressure[:, 0]))
    assert sol.contact_pressure[i, 0] * sol.model.film.cell_area[i, 0] == pytest.approx(
        max(s.force for s in sol.corner_forces), rel=1e-14)


def test_a_reversed_tape_reads_as_the_mirrored_head_run_forward():
    """V < 0 over wraps (1°, 3°) is the forward run over the mirrored head (3°, 1°): the
    same viscous and friction drag, both against the motion, and the same tension ratio
    above 1 (the outgoing tension is the higher one whichever way the tape runs). The
    reversed cylinder's ratio is its forward one. Friction alone (a dry reversed tape):
    the capstan law 1 + μ_f θ (T − ρV²)/T to first order."""
    def flat(t_in, t_out, velocity, **kw):
        head = FlatHead((Module(1e-3),), t_in, t_out, transducers=(0.0,), friction=0.3)
        return solve_steady(BearingModel(TAPE, FIRST_ORDER, velocity=velocity,
                                         head=head, infinitely_wide=True, **kw, contact=HARD))
    reversed_, mirrored = flat(1 * DEG, 3 * DEG, -4.0), flat(3 * DEG, 1 * DEG, 4.0)
    assert mirrored.viscous_drag > 0 and mirrored.friction_drag > 0
    for name in ("viscous_drag", "friction_drag", "drag", "tension_ratio"):
        assert getattr(reversed_, name) == pytest.approx(getattr(mirrored, name), rel=1e-6)
    assert reversed_.tension_ratio > 1
    backwards, forwards = solve_steady(_cylinder(velocity=-4.0)), solve_steady(_cylinder())
    assert backwards.viscous_drag == pytest.approx(forwards.viscous_drag, rel=1e-6)
    assert backwards.tension_ratio == pytest.approx(forwards.tension_ratio, rel=1e-12)
    assert backwards.tension_ratio > 1
    lam = math.sqrt(TAPE.D / TAPE.tension)
    dry = flat(1 * DEG, 3 * DEG, -4.0, dry=True, span=40 * lam)
    moving = TAPE.tension - TAPE.density * 16.0
    turn = dry.contact_force / moving
    assert turn == pytest.approx(4 * DEG, rel=1 / 20)
    assert dry.tension_ratio == pytest.approx(1 + 0.3 * turn * moving / TAPE.tension,
                                              rel=1e-15)


@pytest.mark.slow
def test_transducer_line_across_the_width_converges_at_second_order():
    """A 3 mm tape over the cylinder, both counts doubled (96 × 24 → 384 × 96), the
    transducer line off the nodes: its centre and minimum spacing at order 2; its mean
    (measured 1.68 on these grids: its differences are 4e-10 and 1.2e-10 m) above 1.5."""
    head = Cylinder(math.radians(15), transducers=(1.2345e-3,))
    values = []
    for nx, ny in ((96, 24), (192, 48), (384, 96)):
        sol = solve_steady(BearingModel(TapeParameters(width=3e-3), FIRST_ORDER,
                                        velocity=4.0, head=head, nx=nx, ny=ny, span=2e-3,
                                        contact=HARD))
        (line,) = sol.transducer_lines
        values.append((line.centre, line.minimum, line.mean))
    centre, minimum, mean = _line_orders(values)[0]
    assert centre == pytest.approx(2.0, abs=0.25) and minimum == pytest.approx(2.0, abs=0.25)
    assert mean > 1.5


def test_cylinder_below_its_smallest_valid_wrap_warns_where_the_model_stops_holding():
    """The cylinder keeps the hoop stiffness k on its straight spans. Their support, the
    air force less the wrap load (T − ρV²) θ (the tape's vertical balance), is about
    k R² ε at small wraps, bounded by HOOP_SPAN_SUPPORT k R² ε; the smallest valid wrap
    is where that bound is HOOP_SPAN_SHARE of the wrap load, 23 (ℓ_film/R)(ℓ_film/ℓ_k)²
    (6.2° here). Below it one warning line says so; at 15° none."""
    from gyroshell.bearing.model import (
        HOOP_SPAN_SHARE,
        HOOP_SPAN_SUPPORT,
        BearingModelWarning,
        foil_length_scales,
    )

    air = FIRST_ORDER
    t_eff = TAPE.tension - TAPE.density * 16.0
    _, l_film, _ = foil_length_scales(TAPE, air, 4.0)
    l_k = math.sqrt(t_eff / TAPE.k)
    limit = 23.0 * (l_film / TAPE.radius) * (l_film / l_k) ** 2
    support = HOOP_SPAN_SUPPORT * TAPE.k * TAPE.radius**2 * 6 * air.viscosity * 4.0 / t_eff
    assert limit == pytest.approx(support / (HOOP_SPAN_SHARE * t_eff), rel=1e-12)
    assert math.degrees(limit) == pytest.approx(6.24, abs=0.01)
    for deg in (0.01, 0.1):
        with pytest.warns(BearingModelWarning) as caught:
            model = BearingModel(TAPE, air, velocity=4.0, wrap_angle=deg * DEG,
                                 infinitely_wide=True, contact=HARD)
        (line,) = [str(w.message) for w in caught]
        assert f"a wrap of {deg:g} deg is below 6.24 deg, where this model stops" in line
        assert model.smallest_valid_wrap() == pytest.approx(limit, rel=1e-12)
        sol = solve_steady(model)
        spans = sol.air_force - t_eff * deg * DEG
        assert support / 3 < spans < support
    with warnings.catch_warnings():
        warnings.simplefilter("error", BearingModelWarning)
        BearingModel(TAPE, air, velocity=4.0, wrap_angle=15 * DEG, infinitely_wide=True,
                     contact=HARD)
