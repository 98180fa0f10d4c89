"""Transients over flat heads' corners: sharp, rounded (touched at one tangent point) and
wrapped (rounded arcs the tape lies on), 1-D at 4 m/s (gyroshell.bearing.transient).

Exact consequences of the march: a steady state is a fixed point of the coupled Newmark /
backward-Euler step (so the march started there stays there, to the steady solve's
tolerance); a disturbance of the land decays back onto the same steady state (the film's
squeeze damps it); a tension step ends on the steady state at the new tension, solved on
the same grid with the same contact nodes (the march cannot move a tangent point's node);
and over a symmetric head the march at −V of the mirrored start is the mirror image of the
march at +V.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from bearing_cases import FIRST_ORDER, HARD

from gyroshell import TapeParameters
from gyroshell.bearing import BearingModel
from gyroshell.bearing.head import FlatHead, Module
from gyroshell.bearing.steady import BearingSolution, solve_steady
from gyroshell.bearing.transient import march, tension_step
from gyroshell.core.errors import ConvergenceError

DEG = math.pi / 180.0
AIR = FIRST_ORDER
#: Newmark with numerical damping of the grid-scale ringing (unconditionally stable).
DAMPED = {"beta": 0.3025, "gamma": 0.6}
HEADS = {
    "sharp": FlatHead((Module(1e-3),), 2 * DEG, 2 * DEG),
    "rounded": FlatHead((Module(1e-3, corner_radius=5e-6),), 2 * DEG, 2 * DEG),
    "wrapped": FlatHead((Module(4e-3, corner_radius=10e-3),), 4 * DEG, 4 * DEG,
                        flank_angle=8 * DEG),
}
#: The wrapped arcs' steady solve takes 1-2 s (pseudo-time from the foil start).
CASES = [pytest.param("sharp"), pytest.param("rounded"),
         pytest.param("wrapped", marks=pytest.mark.slow)]


def _model(kind, velocity=4.0, **kw):
    return BearingModel(TapeParameters(), AIR, velocity=velocity, head=HEADS[kind],
                        infinitely_wide=True, **kw, contact=HARD)


_STEADY: dict = {}


def _steady(kind, velocity=4.0) -> BearingSolution:
    key = (kind, velocity)
    if key not in _STEADY:
        _STEADY[key] = solve_steady(_model(kind, velocity))
    return _STEADY[key]


def _land_bump(sol, amplitude=0.3) -> np.ndarray:
    """A smooth lift of the tape in the land's middle, vanishing (to 1e-9 of itself) at
    the corners: it leaves their contacts alone."""
    x = sol.model.x_head[1:-1]
    half = 0.5 * (sol.model.head.extent()[1] - sol.model.head.extent()[0])
    return amplitude * sol.central_spacing * np.exp(-(x / (0.2 * half)) ** 2)


@pytest.mark.parametrize("kind", CASES)
def test_march_from_the_steady_state_over_corners_stays_there(kind):
    """20 steps of 10 µs from the steady state (constant tension): the spacing stays within
    1e-6 of the central spacing (the steady solve's tolerance; measured 4e-8 sharp and
    rounded, 2e-11 wrapped) and the contact set and forces do not change."""
    start = _steady(kind)
    run = march(start, dt=1e-5, steps=20, record_every=5)
    dev = np.max(np.abs(run.final.spacing - start.spacing)) / start.central_spacing
    assert dev < 1e-6
    assert np.array_equal(run.final.contact > 0, start.contact > 0)
    assert run.final.contact.sum() == pytest.approx(start.contact.sum(), rel=1e-6)


@pytest.mark.slow
@pytest.mark.parametrize("kind", ["sharp", "rounded"])
def test_a_lifted_land_settles_back_onto_the_steady_state(kind):
    """A lift of 0.3 h(0) over the land's middle decays (after 0.1 ms it still differs by
    more than 1 %) and 300 damped steps of 10 µs end on the steady state: spacing within 1e-4
    of h(0), pressure within 1e-5 of its peak, the corners' contact forces within 1e-5
    (measured 6e-8 and 2e-10 over the rounded corners)."""
    steady = _steady(kind)
    start = BearingSolution(steady.model, steady.u + _land_bump(steady), steady.p,
                            steady.contact, steady.info)
    run = march(start, dt=1e-5, steps=300, record_every=10, **DAMPED)
    assert abs(run.central_spacing[1] / steady.central_spacing - 1.0) > 1e-2
    dev = np.max(np.abs(run.final.spacing - steady.spacing)) / steady.central_spacing
    assert dev < 1e-4
    assert np.max(np.abs(run.final.p - steady.p)) < 1e-5 * steady.p.max()
    assert run.contact_force[-1] == pytest.approx(steady.contact.sum(), rel=1e-5)


@pytest.mark.slow
@pytest.mark.parametrize("kind", ["sharp", "rounded"])
def test_a_start_lifted_off_the_corners_settles_back(kind):
    """A lift of 0.3 h(0) reaching the corners (0.6 nm there: the corner nodes leave their
    contact) stalls the first step's Newton at 10 µs; the march retries it in halves
    (over the rounded corners down to 1e-8 s) and 150 damped steps end on the
    steady state within 1e-5 of h(0), its contact forces within 1e-5."""
    steady = _steady(kind)
    x = steady.model.x_head[1:-1]
    lift = 0.3 * steady.central_spacing * np.exp(-(x / 3e-4) ** 2)
    corners = steady.contact > 0
    assert np.all(lift[corners] > 0.02 * HARD.roughness)
    start = BearingSolution(steady.model, steady.u + lift, steady.p, steady.contact,
                            steady.info)
    run = march(start, dt=1e-5, steps=150, record_every=50, **DAMPED)
    dev = np.max(np.abs(run.final.spacing - steady.spacing)) / steady.central_spacing
    assert dev < 1e-5
    assert run.contact_force[-1] == pytest.approx(steady.contact.sum(), rel=1e-5)


@pytest.mark.slow
def test_a_lifted_tape_over_wrapped_arcs_settles_back():
    """Over the 10 mm wrapped arcs the tape flies 1.6 µm high and the squeeze film damps it
    slowly: the lift of 0.3 h(0) decays monotonically after the first 1.5 ms (the first
    steps overshoot) to below 2 % of h(0) in 3 ms (measured 0.12 %)."""
    steady = _steady("wrapped")
    start = BearingSolution(steady.model, steady.u + _land_bump(steady), steady.p,
                            steady.contact, steady.info)
    run = march(start, dt=1e-5, steps=300, record_every=10, **DAMPED)
    excess = np.abs(run.central_spacing / steady.central_spacing - 1.0)
    assert np.all(np.diff(excess[15:]) < 0.0)
    assert excess[-1] < 2e-2 and not run.final.contact.any()


@pytest.mark.slow
@pytest.mark.parametrize("kind", ["sharp", "rounded"])
def test_tension_step_over_corners_ends_on_the_new_steady_state(kind):
    """T: 90 → 100 N/m at t = 0; 400 damped steps of 10 µs end on the steady state at
    100 N/m on the same grid and contact nodes (adapt_contacts=False: the march keeps a
    rounded corner's tangent-point node), within 1e-4 of h(0) (the step moves h(0) by
    1.5 %: over a flat land a higher tension lifts the tape); the tape clears the
    rounded arcs (the contact does not need to move by a cell: r_c times the slope change
    is far below the cells next to it)."""
    before = _steady(kind)
    m = before.model
    after = solve_steady(m.rebuilt(adapt_contacts=False), tension=100.0)
    run = march(before, dt=1e-5, steps=400, record_every=100,
                tension=tension_step(90.0, 100.0), **DAMPED)
    dev = np.max(np.abs(run.final.spacing - after.spacing)) / after.central_spacing
    assert dev < 1e-4
    assert run.contact_force[-1] == pytest.approx(after.contact.sum(), rel=1e-4)
    assert abs(after.central_spacing / before.central_spacing - 1.0) > 1e-2
    if kind == "rounded":
        assert m.arc_clearance(run.final.u) >= 0.0


@pytest.mark.slow
@pytest.mark.parametrize("kind", ["sharp", "rounded", "wrapped"])
def test_reversed_march_over_a_symmetric_head_is_the_mirror_image(kind):
    """The mirrored start at −V (the rounded corners' contact nodes mirrored, kept fixed)
    marches as the mirror image of the start at +V: the centre-line spacing records
    agree within 1e-6 of h(0) after 50 steps (both marches from states equal to the
    solves' tolerance)."""
    plus = _steady(kind)
    m = plus.model
    mirrored = (tuple(-c for c in m.corner_contacts[::-1]) or None)
    minus_model = m.rebuilt(velocity=-4.0, corner_contacts=mirrored,
                            adapt_contacts=mirrored is None)
    assert np.allclose(minus_model.x_head, -m.x_head[::-1], rtol=0,
                       atol=1e-12 * m.length)
    minus = solve_steady(minus_model)
    bump = _land_bump(plus)
    runs = [march(BearingSolution(s.model, s.u + b, s.p, s.contact, s.info), dt=1e-5,
                  steps=50, record_every=10, **DAMPED)
            for s, b in ((plus, bump), (minus, bump[::-1]))]
    a, b = (r.centreline for r in runs)
    assert np.max(np.abs(b[:, ::-1] - a)) < 1e-6 * plus.central_spacing


def test_a_state_cutting_into_a_rounded_arc_is_refused_naming_when():
    """The march keeps each rounded corner's single contact node and checks every step's
    state with :func:`gyroshell.bearing.corners.check_point_contacts` (as the steady
    solve checks its last pass): a tape cutting 2σ into an arc node next to the contact
    is refused (it cuts 2σ below the arc's σ), naming the time and the wrapped model;
    the steady state passes."""
    from gyroshell.bearing.corners import check_point_contacts

    steady = _steady("rounded")
    m = steady.model
    check_point_contacts(m, steady.u, " at t = 0 s")
    free = np.flatnonzero(m.contact_floor < 0.0)
    u = steady.u.copy()
    u[free[np.argmin(np.abs(free - (m.contact_nodes[0] - 1)))]] -= 2.0 * HARD.roughness
    with pytest.raises(ConvergenceError, match=r"cuts 3\.99e-08 m into an arc .* at t = 1e-05 "
                       r"s, .*arc_contact='wrapped'") as info:
        check_point_contacts(m, u, " at t = 1e-05 s")
    assert "\n" not in str(info.value)
