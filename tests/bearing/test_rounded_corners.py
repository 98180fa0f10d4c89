"""Rounded corners of a flat head: the tape touches each arc at one point, found by
regridding (gyroshell.bearing.corners).

Dry closed form (no air, V = 0, k = 0, small slopes): the tensioned plate D w'''' − T w'' = 0
on three pieces, touching the two arcs z_h = −d²/(2 r_c) (d the distance past the land's
tangent point) at unknown points x₁, x₂, where w = z_h + σ, w, w', w'' are continuous (a
point force: w''' jumps) and the tape is tangent to the arc, w'(x_k) = z_h'(x_k). This
holds while the tape is less curved than the arc, |w''| < 1/r_c (its curvature near a
corner is about θ/(2λ), λ = √(D/T) ≈ 0.1 mm: 175 1/m at 2°, against 1/r_c = 1e4 1/m
for r_c = 100 µm): the regime of a point contact, which these tests take.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from convergence import observed_order

from gyroshell import TapeParameters
from gyroshell.bearing import AirParameters, BearingModel
from gyroshell.bearing.head import FlatHead, Module
from gyroshell.bearing.steady import solve_steady

DEG = math.pi / 180.0
TAPE = TapeParameters(foundation_stiffness=0.0)
AIR = AirParameters()
LAND = 1e-3
SPAN = 1e-3
RADIUS = 100e-6
FLANK = 20 * DEG


def plate_over_rounded_land(L, S, t_in, t_out, lam, sigma, r, phi=FLANK):
    """The exact tape (w, corner forces D[w'''] in N/m, contact points x₁, x₂ in m) over a
    land [−L/2, L/2] at height 0 whose corners are arcs of radius r (parabolas, small
    slopes) reaching r φ/2 either side of the corner points, spans pinned at
    x = −L/2 − S and L/2 + S on the dry string (the arcs' tangent lines of slopes
    +t_in, −t_out) with w'' = 0 there.

    For given contacts the 12 constants of c₁ + c₂(x − x₀) + c₃e^{(x − x₁)/λ} + c₄e^{−(x −
    x₀)/λ} per piece follow from a linear system; the contacts from the tangency, by the
    fixed point x_k ← the arc's point of slope w'(x_k) (a contraction: r |w''| ≪ 1)."""
    a, b = -L / 2, L / 2
    lead, trail = a + 0.5 * r * phi, b - 0.5 * r * phi      # the land's tangent points

    def arc(x, k):           # (z_h, z_h') on the arc of corner k (0 leading, 1 trailing)
        d = lead - x if k == 0 else x - trail
        return -d * d / (2 * r), (d / r if k == 0 else -d / r)

    # the dry string's end heights: the tangent line of slope t at d = r t on each arc
    z_left = -r * t_in**2 / 2 + t_in * ((a - S) - (lead - r * t_in))
    z_right = -r * t_out**2 / 2 - t_out * ((b + S) - (trail + r * t_out))

    def solve(x1, x2):
        pieces = [(a - S, x1), (x1, x2), (x2, b + S)]

        def basis(x, k, d):
            x0, xe = pieces[k]
            x = np.asarray(x, dtype=float)
            one, zero = np.ones_like(x), np.zeros_like(x)
            grow, decay = np.exp((x - xe) / lam), np.exp(-(x - x0) / lam)
            lin = [one, x - x0] if d == 0 else ([zero, one] if d == 1 else [zero, zero])
            return np.array(lin + [grow / lam**d, (-1) ** d * decay / lam**d])

        rows, rhs = [], []

        def condition(x, k, d, value, other=None):
            row = np.zeros(12)
            row[4 * k:4 * k + 4] = basis(x, k, d)
            if other is not None:
                row[4 * other:4 * other + 4] -= basis(x, other, d)
            rows.append(row)
            rhs.append(value)

        condition(a - S, 0, 0, z_left)
        condition(a - S, 0, 2, 0.0)
        condition(b + S, 2, 0, z_right)
        condition(b + S, 2, 2, 0.0)
        for k, (x, left, right) in enumerate(((x1, 0, 1), (x2, 1, 2))):
            condition(x, left, 0, arc(x, k)[0] + sigma)
            condition(x, right, 0, arc(x, k)[0] + sigma)
            condition(x, left, 1, 0.0, right)
            condition(x, left, 2, 0.0, right)
        c = np.linalg.solve(np.array(rows), np.array(rhs)).reshape(3, 4)

        def evaluate(x, d):
            x = np.asarray(x, dtype=float)
            k = np.where(x < x1, 0, np.where(x <= x2, 1, 2))
            out = np.zeros_like(x)
            for j in range(3):
                on = k == j
                if on.any():
                    out[on] = (c[j][:, None] * basis(x[on], j, d)).sum(axis=0)
            return out

        D = lam * lam * TAPE.tension
        forces = tuple(D * float(np.sum(c[rt] * basis(x, rt, 3)) - np.sum(c[lf] * basis(x, lf, 3)))
                       for x, lf, rt in ((x1, 0, 1), (x2, 1, 2)))
        return evaluate, forces

    x1, x2 = lead - r * t_in / 2, trail + r * t_out / 2
    for _ in range(50):
        evaluate, forces = solve(x1, x2)
        s1, s2 = evaluate(np.array([x1, x2]), 1)
        new = (lead - r * s1, trail - r * s2)       # slope s at d = r s (lead), −r s (trail)
        moved = max(abs(new[0] - x1), abs(new[1] - x2))
        x1, x2 = new
        if moved < 1e-16:
            break
    evaluate, forces = solve(x1, x2)
    return (lambda x: evaluate(x, 0)), forces, (x1, x2)


def _dry(nx, t_in=2 * DEG, t_out=2 * DEG, r=RADIUS, **kw):
    head = FlatHead((Module(LAND, corner_radius=r),), t_in, t_out, flank_angle=FLANK)
    return BearingModel(TAPE, AIR, velocity=0.0, head=head, span=SPAN, nx=nx, dry=True,
                        grading="uniform", infinitely_wide=True, **kw)


def test_closed_form_touches_each_arc_tangentially_inside_its_wrapped_part():
    """The derivation's own checks: the contacts lie on the wrapped part of each arc
    (0 < d < r θ), the tape clears the head everywhere else, and r → 0 gives back the
    sharp corners' contacts at the corner points."""
    lam = math.sqrt(TAPE.D / TAPE.tension)
    t = 2 * DEG
    w, forces, (x1, x2) = plate_over_rounded_land(LAND, SPAN, t, t, lam, 0.0, RADIUS)
    lead = -LAND / 2 + 0.5 * RADIUS * FLANK
    assert 0.0 < lead - x1 < RADIUS * t
    x = np.linspace(-LAND / 2 - 0.5 * RADIUS * FLANK, LAND / 2 + 0.5 * RADIUS * FLANK, 4001)
    head = FlatHead((Module(LAND, corner_radius=RADIUS),), t, t, flank_angle=FLANK)
    clearance = w(x) - head.surface(x)
    assert clearance.min() > -1e-15
    assert forces == pytest.approx((TAPE.tension * t,) * 2, rel=0.15)
    _, _, tiny = plate_over_rounded_land(LAND, SPAN, t, t, lam, 0.0, 1e-12)
    assert tiny == pytest.approx((-LAND / 2, LAND / 2), abs=1e-12)


@pytest.mark.parametrize("t_in, t_out", [(2 * DEG, 2 * DEG), (1 * DEG, 3 * DEG)],
                         ids=["equal", "unequal"])
def test_dry_tape_over_rounded_corners_matches_the_plate_and_converges(t_in, t_out):
    """Height along the tape and both corner forces against the closed form, one contact
    node per corner (at the adapted contact point), second order."""
    lam = math.sqrt(TAPE.D / TAPE.tension)
    w, forces, contacts = plate_over_rounded_land(LAND, SPAN, t_in, t_out, lam,
                                                  AIR.roughness, RADIUS)
    steps, errs, ferrs, xerrs = [], [], [], []
    for nx in (96, 192, 384):
        sol = solve_steady(_dry(nx, t_in, t_out))
        m = sol.model
        height = sol.spacing[:, 0] + m.head.surface(m.x_head)
        errs.append(np.max(np.abs(height - w(m.x_head))) / (max(t_in, t_out) * lam))
        line = sol.contact
        at = m.contact_nodes - 1
        assert set(np.flatnonzero(line)) == set(at)
        ferrs.append(max(abs(line[i] / f - 1.0) for i, f in zip(at, forces, strict=True)))
        xerrs.append(max(abs(c - e) for c, e in zip(m.corner_contacts, contacts, strict=True)))
        assert m.arc_clearance(sol.u) > 0.0
        assert sol.info.contact_passes <= 4
        steps.append(m.hx)
    assert errs[-1] < 1e-3 and ferrs[-1] < 2e-3
    assert observed_order(steps, errs) == pytest.approx(2.0, abs=0.25)
    assert observed_order(steps, ferrs) == pytest.approx(2.0, abs=0.3)
    assert xerrs[-1] < 0.05 * RADIUS * max(t_in, t_out)
