"""The head–tape interface at today's spacings: rarefaction, asperity contact and the
roughness flow factors in the coupled model, against closed forms and independent
quadratures, and the paths that must not move (the classical film, the hard wall)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

from gyroshell import TapeParameters
from gyroshell.bearing import AirParameters, BearingModel
from gyroshell.bearing.contact import ComplianceCurve, ContactParameters
from gyroshell.bearing.head import FlatHead, Module
from gyroshell.bearing.steady import initial_state, solve_steady
from gyroshell.bearing.transient import march

DEG = math.pi / 180.0
#: Table 1's tape without its hoop stiffness: dry on a cylinder of its own radius it is
#: pressed on with the wrap pressure T/R and nothing else
BARE = TapeParameters(foundation_stiffness=0.0)
ASPERITY = ContactParameters()
FLAT = FlatHead((Module(1e-3),), 2 * DEG, 2 * DEG, transducers=(0.0,), friction=0.3)


def gw_pressure(d: float, contact: ContactParameters) -> float:
    """Greenwood–Williamson's nominal pressure at the separation d (m), by quadrature of
    its defining integral over the Gaussian summit heights (Pa)."""
    s = contact.roughness
    scale = (4.0 / 3.0) * contact.contact_modulus * contact.asperity_density * math.sqrt(
        contact.asperity_radius)
    density = lambda z: math.exp(-0.5 * (z / s) ** 2) / (s * math.sqrt(2.0 * math.pi))  # noqa: E731
    return scale * quad(lambda z: (z - d) ** 1.5 * density(z), d, d + 40.0 * s,
                        epsabs=0.0, epsrel=1e-12, limit=200)[0]


def _dry_cylinder(contact, nx=None):
    return BearingModel(BARE, AirParameters(), velocity=0.0, dry=True,
                        wrap_angle=15 * DEG, infinitely_wide=True, contact=contact, nx=nx)


def test_dry_tape_on_its_own_radius_rests_where_the_asperities_carry_the_wrap_pressure():
    """V = 0, k = 0: the wrapped tape presses on its summits with T/R; in the middle of
    the wrap, far from the bending layers, p_GW(d) = T/R (quadrature, Brent)."""
    sol = solve_steady(_dry_cylinder(ASPERITY))
    target = BARE.tension / BARE.radius
    d = brentq(lambda x: gw_pressure(x, ASPERITY) - target, -10 * ASPERITY.roughness,
               20 * ASPERITY.roughness, xtol=1e-18, rtol=1e-14)
    assert sol.central_spacing == pytest.approx(d, rel=1e-6)
    wrap = np.abs(sol.x) < 0.25 * BARE.radius * 15 * DEG
    assert np.allclose(sol.spacing[wrap, 0], d, rtol=1e-5)
    # the asperities carry the whole wrap load, T θ in the shallow shell, N/m (to the
    # bending layers' share at the wrap's ends, well under 1 %)
    assert sol.contact_force == pytest.approx(BARE.tension * 15 * DEG, rel=1e-2)


def test_dry_tape_on_a_measured_compliance_curve_rests_at_the_wrap_pressure_point():
    """The same with a measured curve holding the point (10 nm, T/R): the middle of the
    wrap rests exactly there, whatever the interpolation does between the points."""
    target = BARE.tension / BARE.radius
    curve = ComplianceCurve([0.0, 4e-9, 10e-9, 16e-9, 30e-9],
                            [2e6, 1e5, target, 300.0, 0.0])
    sol = solve_steady(_dry_cylinder(ContactParameters(law="compliance", compliance=curve)))
    assert sol.central_spacing == pytest.approx(10e-9, rel=1e-6)


def test_a_vanishing_roughness_tends_to_the_hard_wall():
    """σ_s → 0 at a fixed pressure scale (4/3) E* η √β σ_s^{3/2}: the dry wrap's spacing
    d → 0 like σ_s (the summits become a wall at d = 0), its contact force unchanged."""
    spacings = []
    for sigma in (8e-9, 4e-9, 2e-9):
        scale = 6e6 / ((4 / 3) * 5e9 * math.sqrt(10e-6) * sigma**1.5)
        contact = ContactParameters(roughness=sigma, asperity_density=scale)
        sol = solve_steady(_dry_cylinder(contact))
        spacings.append(sol.central_spacing / sigma)
    # d/σ_s is the same t with p_s F_{3/2}(t) = T/R: d itself halves with σ_s
    assert spacings[0] == pytest.approx(spacings[1], rel=1e-4)
    assert spacings[1] == pytest.approx(spacings[2], rel=1e-4)


def test_first_order_slip_and_the_hard_wall_are_todays_bearing_bit_for_bit():
    """--rarefaction first-order --contact hard: the hard wall given by its gap and the
    legacy film (first-order slip; "auto" flow factors resolve to none under the wall) are
    the film of the explicit "none" to the last bit, over a flat head and a cylinder; the
    hard-wall tests (classical foil bearing, dry lands and wraps, contact sets) anchor it
    to closed forms."""
    auto = AirParameters(rarefaction="first-order")
    none = AirParameters(rarefaction="first-order", flow_factors="none")
    hard = ContactParameters(law="hard", roughness=20e-9)
    for kw in (dict(head=FLAT), dict(wrap_angle=15 * DEG)):
        a, b = (solve_steady(BearingModel(TapeParameters(), air, velocity=4.0,
                                          infinitely_wide=True, contact=hard, **kw))
                for air in (auto, none))
        assert a.model.air == b.model.air == none.replace(roughness=20e-9)
        assert np.array_equal(a.u, b.u) and np.array_equal(a.p, b.p)


def test_the_defaults_are_the_boltzmann_film_over_asperities():
    """No interface given: Fukui-Kaneko's flow rate, Patir-Cheng's flow factors on the
    summits' σ_s, Greenwood-Williamson asperities with the data-tape defaults; an air
    roughness given alone is the summits' σ_s."""
    model = BearingModel(TapeParameters(), velocity=4.0, head=FLAT, infinitely_wide=True)
    assert model.contact == ContactParameters(law="asperity")
    assert (model.air.rarefaction, model.air.flow_factors) == ("fukui-kaneko", "patir-cheng")
    assert model.air.roughness == ContactParameters(law="asperity").roughness
    rough = BearingModel(TapeParameters(), AirParameters(roughness=9e-9), velocity=4.0,
                         head=FLAT, infinitely_wide=True)
    assert rough.contact == ContactParameters(law="asperity", roughness=9e-9)


def test_boltzmann_flow_moves_the_cylinder_at_micrometres_by_under_a_percent():
    """At h ≈ 3 µm (Kn ≈ 0.02) the linearized Boltzmann flow factor is first-order slip
    with a kinetic slip coefficient (1 + 6.88 Kn): the spacing changes by far less than
    1 %."""
    out = {}
    for model in ("first-order", "fukui-kaneko"):
        m = BearingModel(TapeParameters(), AirParameters(rarefaction=model), velocity=4.0,
                         wrap_angle=15 * DEG, infinitely_wide=True)
        out[model] = solve_steady(m).central_spacing
    change = out["fukui-kaneko"] / out["first-order"] - 1.0
    assert 0.0 < abs(change) < 0.01


def _flying_flat(**kw):
    return BearingModel(TapeParameters(), AirParameters(rarefaction="fukui-kaneko",
                                                        flow_factors="patir-cheng"),
                        velocity=4.0, head=FLAT, infinitely_wide=True, contact=ASPERITY,
                        **kw)


def test_a_flat_land_rests_on_its_asperities_under_the_sub_ambient_film():
    """Contact recording: the land's film is sub-ambient and the summits carry it (d a
    few σ_s); the sharp corners are pressed below the summits' mean plane; the head's
    friction acts on the asperity force, wherever it is."""
    sol = solve_steady(_flying_flat())
    land = np.abs(sol.x) < 0.3e-3
    assert np.all(sol.pressure[land, 0] < AirParameters().ambient_pressure)
    d = sol.transducer_lines[0].centre / ASPERITY.roughness
    assert 1.0 < d < 4.0
    assert sol.minimum_spacing < 0.0            # the corners: summits compressed past d = 0
    assert sol.contact_force > 0.0
    assert sol.friction_drag == pytest.approx(0.3 * sol.contact_force, rel=1e-12)
    assert sol.range_warnings == []


def test_warnings_name_the_models_used_out_of_their_range(cli):
    """The hard wall with first-order slip over a flat land: both models out of range,
    each one warning line and in the JSON's ``warnings``."""
    run = cli(["bearing", "--rarefaction", "first-order", "--contact", "hard", "--head", "flat",
               "--land-length", "1e-3", "--wrap-in", "2",
               "--wrap-out", "2", "--transducers", "0", "--velocity", "4",
               "--infinitely-wide", "--json", "--quiet", "--recession", "1.5e-8"])
    assert run.code == 0, run.err
    out = json.loads(run.out)
    assert len(out["warnings"]) == 2
    assert "first-order slip" in out["warnings"][0] and "hard wall" in out["warnings"][1]
    assert sum(line.startswith("gyroshell: warning:") for line in run.err.splitlines()) == 2
    line = out["magnetic_spacings"][0]
    assert line["magnetic_spacing"] == pytest.approx(
        out["transducer_lines"][0]["centre"] + 1.5e-8, rel=1e-12)


def _gw_real_area(d: float, contact: ContactParameters) -> float:
    """Greenwood–Williamson's real contact area over the nominal at the separation d (m),
    π η β σ_s ∫_d^∞ (z − d) φ(z) dz / σ_s by quadrature of its defining integral."""
    s = contact.roughness

    def integrand(z):
        return (z - d) * math.exp(-0.5 * (z / s) ** 2) / (s * math.sqrt(2.0 * math.pi))

    mean = quad(integrand, d, max(d, 0.0) + 40.0 * s, epsabs=0.0, epsrel=1e-12,
                limit=200)[0]
    return math.pi * contact.asperity_density * contact.asperity_radius * mean


@pytest.mark.slow
def test_asperities_pressed_past_greenwood_williamsons_range_are_named():
    """30° wraps over 60° flanks press the sharp corners' summits to d = -14 σ_s, where
    GW's real contact area (quadrature) exceeds the nominal: one warning line names the
    depth and the place; over 2°/2° (d = -1.3 σ_s, a real area of 0.3) there is none."""
    head = FlatHead((Module(1e-3),), 30 * DEG, 30 * DEG, transducers=(0.0,),
                    flank_angle=60 * DEG)
    model = BearingModel(TapeParameters(), AirParameters(), velocity=4.0, head=head,
                         infinitely_wide=True, contact=ASPERITY)
    sol = solve_steady(model, z0=initial_state(model))     # the CLI's start
    assert _gw_real_area(sol.minimum_spacing, ASPERITY) > 0.5
    (line,) = sol.range_warnings
    assert "Greenwood-Williamson" in line and "corner_radius" in line
    assert f"d = {sol.minimum_spacing / ASPERITY.roughness:.3g} sigma_s" in line
    mild = solve_steady(_flying_flat())
    assert _gw_real_area(mild.minimum_spacing, ASPERITY) < 0.5
    assert mild.range_warnings == []


def test_a_march_from_a_steady_state_on_asperities_stays_there():
    """The transient runs on the same physics: its steady state is the steady solver's."""
    sol = solve_steady(_flying_flat())
    record = march(sol, dt=1e-6, steps=3, progress=False)
    assert np.allclose(record.final.spacing, sol.spacing, rtol=1e-6,
                       atol=1e-4 * ASPERITY.roughness)
    assert np.allclose(record.contact_force, sol.contact_force, rtol=1e-6)


def test_a_flat_heads_spacing_follows_the_four_measured_trends():
    """IBM's measurements over a flat module: the spacing falls with the leading wrap and
    with the tension, does not depend on the trailing wrap, rises with speed. The
    Boltzmann film over asperities, its gap the mean gap of the rough tape, gives all four
    signs; the hard wall with first-order slip gets the leading wrap, the tension and the
    speed wrong (what the mean gap's leak through the pressed corners changes)."""
    from gyroshell.bearing.trends import spacing_trends

    trends = spacing_trends()
    assert [t.sign for t in trends] == [t.measured for t in trends] == [-1, 0, -1, 1]
    hard = spacing_trends(AirParameters(rarefaction="first-order"),
                          ContactParameters(law="hard", roughness=20e-9))
    assert [t.sign for t in hard] == [1, 0, 1, -1]


def test_the_one_newton_with_the_wall_as_bounds_finds_the_hard_walls_state():
    """The hard wall as lower bounds h >= σ on the generic Newton (reduced-space active
    set) reaches the state of the hard wall's own solver: the same complementarity
    solution, on the same grid, to Newton's tolerance."""
    from gyroshell.bearing.problem import SteadyProblem
    from gyroshell.bearing.smooth import flying_start
    from gyroshell.linalg.newton import NewtonOptions, newton

    model = BearingModel(TapeParameters(), AirParameters(rarefaction="first-order"),
                         velocity=4.0, head=FLAT, infinitely_wide=True,
                         contact=ContactParameters(law="hard", roughness=20e-9))
    legacy = solve_steady(model)
    problem = SteadyProblem(model)
    z, report = newton(problem, problem.unknowns(flying_start(model)),
                       NewtonOptions(max_iterations=40, round_off_step=1e-2))
    spacing = model.spacing_field(z[:model.n_u])
    assert report.active_counts[-1] == 2            # the two corners at the wall
    assert np.allclose(spacing, legacy.spacing, rtol=1e-6, atol=1e-6 * model.air.roughness)
    assert np.allclose(z[model.n_u:], legacy.p, rtol=0.0,
                       atol=1e-6 * model.air.ambient_pressure)


def test_contact_recording_readings_converge_as_the_grid_is_refined():
    """The transducer's spacing and the land's pressure on 1, 2 and 4 times the default
    intervals: the changes shrink (first order: the pressed corners' leak is metered over
    a few tens of nm, which the corner grading resolves) and are small on the default."""
    base = _flying_flat()
    readings = []
    for factor in (1, 2, 4):
        sol = solve_steady(base if factor == 1 else base.rebuilt(nx=base.nx * factor))
        land = np.abs(sol.x) < 0.3e-3
        readings.append((sol.transducer_lines[0].centre, sol.pressure[land, 0].mean()))
    h, p = np.array(readings).T
    assert abs(h[1] - h[2]) < 0.7 * abs(h[0] - h[1])
    assert abs(h[0] / h[2] - 1.0) < 2e-3 and abs(p[0] / p[2] - 1.0) < 3e-2


def test_a_graded_grid_on_few_intervals_keeps_its_nodes_in_order():
    """0.01° wraps over a 1 mm land, the 2-D grading (corners refined to 30 nm over
    0.1 m spans) on 764 intervals: the mapping's few Newton steps overshot there and the
    nodes went backwards along x (refused before, naming nx); found within their
    brackets, they increase and every corner is a node. Too few intervals between the
    corners are still refused in one line naming nx."""
    from gyroshell import ParameterError
    from gyroshell.bearing.model import DEFAULT_GRADING

    head = FlatHead((Module(1e-3),), 0.01 * DEG, 0.01 * DEG)
    model = BearingModel(TapeParameters(), AirParameters(), velocity=4.0, head=head,
                         infinitely_wide=True, grading=DEFAULT_GRADING, nx=764)
    dx = np.diff(model.x)
    assert np.all(dx > 0.0)
    for corner in head.corners():
        assert np.min(np.abs(model.x_head - corner)) < 1e-12
    with pytest.raises(ParameterError, match=r"nx = 100 is too small for the head"):
        BearingModel(TapeParameters(), AirParameters(), velocity=4.0, head=head,
                     infinitely_wide=True, grading=DEFAULT_GRADING, nx=100)
