"""Orthotropic and layered tapes: the stiffnesses from engineering constants and from
classical lamination theory written out by hand, the operators against the energy written
out, the isotropic tape through the orthotropic path, JSON round trips and refusals."""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest

from gyroshell import BendingStiffness, Layer, ParameterError, TapeModel, TapeParameters
from gyroshell.bearing.tape import PlateOperators
from gyroshell.tape.material import laminate

WIDTH = 6.35e-3
#: Agreement expected of two assemblies of the same energy in a different order.
ROUND_OFF = 1e-14

#: A tensilized PEN-like tape: stiffer along (E_x) than across, G_xy independent.
ORTHO = dict(youngs_modulus=8.0e9, youngs_modulus_y=5.0e9, shear_modulus=1.8e9, poisson=0.35)

# Magnetic coat / PEN base / back coat (bottom up), SI: m, Pa, Pa, Pa, -, kg/m^3.
MAGNETIC = Layer(1.0e-6, 6.0e9, 6.0e9, 2.3e9, 0.30, 3000.0)
BASE = Layer(4.5e-6, 8.0e9, 5.5e9, 2.0e9, 0.35, 1360.0)
BACK = Layer(0.5e-6, 3.0e9, 3.0e9, 1.1e9, 0.35, 1500.0)


def _q(layer: Layer) -> np.ndarray:
    """(Q11, Q22, Q12, Q66), Pa, of a layer, written out: 1 − ν_xy ν_yx, ν_yx = ν_xy E_y/E_x."""
    ex, ey, g, nu = (layer.youngs_modulus_x, layer.youngs_modulus_y, layer.shear_modulus,
                     layer.poisson_xy)
    denominator = 1.0 - nu * nu * ey / ex
    return np.array([ex / denominator, ey / denominator, nu * ey / denominator, g])


def _rel(a, b) -> float:
    a, b = np.asarray(a, float), np.asarray(b, float)
    return float(np.abs(a - b).max() / np.abs(b).max())


# ----- material constants ---------------------------------------------------------------------
def test_isotropic_tape_has_the_isotropic_bending_matrix():
    p = TapeParameters()
    E, c, nu = p.youngs_modulus, p.thickness, p.poisson
    D = E * c**3 / (12 * (1 - nu**2))
    bend = p.bending_matrix
    assert p.isotropic
    assert (bend.D11, bend.D22) == pytest.approx((D, D), rel=1e-15)
    assert bend.D12 == pytest.approx(nu * D, rel=1e-15)
    assert bend.D66 == pytest.approx((1 - nu) * D / 2, rel=1e-15)
    # the factors of the isotropic energy, exactly: its operators are built from these
    assert bend.ratios == (1.0, nu, 2 * (1 - nu), 1 - nu**2)
    assert p.membrane_A11 == pytest.approx(E * c / (1 - nu**2), rel=1e-15)
    assert p.k == pytest.approx(p.membrane_A11 / p.radius**2, rel=1e-15)


def test_homogeneous_orthotropic_tape_from_engineering_constants():
    p = TapeParameters(**ORTHO)
    ex, ey, g, nu, c = 8.0e9, 5.0e9, 1.8e9, 0.35, p.thickness
    nu_yx = nu * ey / ex
    q11, q22, q12 = ex / (1 - nu * nu_yx), ey / (1 - nu * nu_yx), nu * ey / (1 - nu * nu_yx)
    expected = np.array([q11, q22, q12, g]) * c**3 / 12
    assert not p.isotropic
    assert _rel(p.bending_matrix.as_tuple(), expected) < 1e-15
    assert p.D == p.bending_matrix.D11
    assert p.membrane_A11 == pytest.approx(q11 * c, rel=1e-15)
    assert p.k == pytest.approx(q11 * c / p.radius**2, rel=1e-15)
    # the foundation override still wins, the membrane override sets k = A11/R²
    assert p.replace(foundation_stiffness=3e7).k == 3e7
    assert p.replace(membrane_stiffness=2e5).k == pytest.approx(2e5 / p.radius**2, rel=1e-15)


def test_bending_stiffness_override():
    p = TapeParameters(bending_stiffness=[3e-6, 1.5e-6, 0.4e-6, 0.9e-6])
    assert p.bending_stiffness == (3e-6, 1.5e-6, 0.4e-6, 0.9e-6)     # a list becomes a tuple
    assert p.bending_matrix == BendingStiffness(3e-6, 1.5e-6, 0.4e-6, 0.9e-6)
    assert p.D == 3e-6 and p.bending_matrix.edge == pytest.approx(3e-6 - 0.16e-12 / 1.5e-6)
    # k still comes from E, c, ν, as with bending_rigidity
    assert p.k == TapeParameters().k


# ----- classical lamination theory ----------------------------------------------------------
def test_symmetric_three_layer_stack_against_the_z_integrals_by_hand():
    """Coat / base / coat: D = Q_b t_b³/12 + 2 Q_c [(t_b/2 + t_c)³ − (t_b/2)³]/3 about the
    mid-plane, A11 = Q11_b t_b + 2 Q11_c t_c, ρ = ρ_b t_b + 2 ρ_c t_c, B = 0."""
    stack = [MAGNETIC, BASE, MAGNETIC]
    tb, tc = BASE.thickness, MAGNETIC.thickness
    qb, qc = _q(BASE), _q(MAGNETIC)
    D = qb * tb**3 / 12 + 2 * qc * ((tb / 2 + tc) ** 3 - (tb / 2) ** 3) / 3
    lam = laminate(stack)
    assert lam.B == (0.0, 0.0, 0.0, 0.0)
    assert _rel(lam.D, D) < 1e-14
    assert _rel(lam.bending.as_tuple(), D) < 1e-14
    assert lam.A[0] == pytest.approx(qb[0] * tb + 2 * qc[0] * tc, rel=1e-14)
    p = TapeParameters.from_layers(stack)
    assert p.thickness == pytest.approx(tb + 2 * tc, rel=1e-15)
    assert p.density == pytest.approx(BASE.density * tb + 2 * MAGNETIC.density * tc, rel=1e-15)
    assert _rel(p.bending_matrix.as_tuple(), D) < 1e-14
    assert p.k == pytest.approx((qb[0] * tb + 2 * qc[0] * tc) / p.radius**2, rel=1e-14)


def test_unsymmetric_stack_reduced_stiffness_by_matrices_about_the_bottom():
    """Magnetic coat / PEN / back coat: A, B, D about the bottom face (z = 0 … c) as 3×3
    matrices, D* = D − B A⁻¹ B, which does not depend on the reference plane."""
    stack = [MAGNETIC, BASE, BACK]
    z = np.concatenate([[0.0], np.cumsum([layer.thickness for layer in stack])])
    A, B, D = np.zeros((3, 3)), np.zeros((3, 3)), np.zeros((3, 3))
    for layer, lo, hi in zip(stack, z[:-1], z[1:], strict=True):
        q11, q22, q12, q66 = _q(layer)
        Q = np.array([[q11, q12, 0.0], [q12, q22, 0.0], [0.0, 0.0, q66]])
        A += Q * (hi - lo)
        B += Q * (hi**2 - lo**2) / 2
        D += Q * (hi**3 - lo**3) / 3
    reduced = D - B @ np.linalg.solve(A, B)
    expected = [reduced[0, 0], reduced[1, 1], reduced[0, 1], reduced[2, 2]]
    lam = laminate(stack)
    assert max(abs(b) for b in lam.B) > 0.0
    assert _rel(lam.bending.as_tuple(), expected) < 1e-12
    assert lam.A[0] == pytest.approx(A[0, 0], rel=1e-14)
    # the stack is stiffer about its mid-plane than the reduced D*
    assert lam.D[0] > lam.bending.D11


def test_unsymmetric_two_layer_stack_bends_about_its_neutral_plane():
    """Two layers with proportional Q (same ν_xy, E_y/E_x, G/E_x): a neutral plane
    z_n = Σ E t z̄ / Σ E t exists, and D* is D about it: Σ Q [(z − z_n)³]/3."""
    soft = Layer(3e-6, 4e9, 2e9, 1e9, 0.3, 1200.0)
    stiff = Layer(5e-6, 12e9, 6e9, 3e9, 0.3, 1400.0)
    z = np.array([0.0, 3e-6, 8e-6])
    e_t_z = 4e9 * 3e-6 * 1.5e-6 + 12e9 * 5e-6 * 5.5e-6
    zn = e_t_z / (4e9 * 3e-6 + 12e9 * 5e-6)
    D = sum(_q(layer) * ((hi - zn) ** 3 - (lo - zn) ** 3) / 3
            for layer, lo, hi in zip((soft, stiff), z[:-1], z[1:], strict=True))
    assert _rel(laminate([soft, stiff]).bending.as_tuple(), D) < 1e-12


def test_one_layer_stack_is_the_homogeneous_orthotropic_tape():
    layer = Layer(20e-6, 8.0e9, 5.0e9, 1.8e9, 0.35, 700.0)
    stacked = TapeParameters.from_layers([layer], spacing=WIDTH / 8, length_ratio=2.0)
    plain = TapeParameters(**ORTHO, density=0.014, spacing=WIDTH / 8, length_ratio=2.0)
    assert stacked.thickness == plain.thickness and stacked.density == pytest.approx(0.014)
    assert stacked.youngs_modulus == pytest.approx(8e9, rel=1e-14)
    assert stacked.poisson == pytest.approx(0.35, rel=1e-14)
    assert _rel(stacked.bending_matrix.as_tuple(), plain.bending_matrix.as_tuple()) < 1e-14
    assert stacked.k == pytest.approx(plain.k, rel=1e-14)
    a, b = TapeModel(stacked), TapeModel(plain)
    assert _rel(a.K(30.0).toarray(), b.K(30.0).toarray()) < 1e-13
    assert _rel(a.M.diagonal(), b.M.diagonal()) < 1e-14


def test_layers_survive_a_json_round_trip_and_with_layers_follows_the_stack():
    p = TapeParameters.from_layers([MAGNETIC, BASE, BACK], tension=60.0)
    text = json.dumps({f.name: p.as_dict()[f.name] for f in dataclasses.fields(p)})
    back = TapeParameters(**json.loads(text))
    assert back == p and back.layers == p.layers
    thicker = p.with_layers([MAGNETIC, BASE.__class__(**{**BASE.as_dict(),
                                                          "thickness": 6e-6}), BACK])
    assert thicker.thickness == pytest.approx(7.5e-6) and thicker.tension == 60.0
    assert thicker.D > p.D
    assert p.replace(tension=50.0).layers == p.layers


# ----- operators ------------------------------------------------------------------------------
def _energy_written_out(p: TapeParameters, model: TapeModel, w: np.ndarray) -> float:
    """½ Σ W [D11 w_xx² + 2 D12 w_xx w_yy + D22 w_yy²] (edges: (D11 − D12²/D22) w_xx²)
    + ½ Σ h_x h_y 4 D66 w_xy² + ½ k Σ W w², J, with the differences written out on the
    uniform grid (the stiffnesses computed here from E_x, E_y, G_xy, ν_xy, c)."""
    g = model.grid
    ex, ey, gxy, nu, c = (p.youngs_modulus, p.youngs_modulus_y, p.shear_modulus, p.poisson,
                          p.thickness)
    det = 1 - nu * nu * ey / ex
    d11, d22, d12, d66 = np.array([ex, ey, nu * ey, gxy * det]) / det * c**3 / 12
    f = g.to_field(w)
    hx, hy = g.hx, g.hy
    wxx = (f[2:] - 2 * f[1:-1] + f[:-2]) / hx**2                       # interior x, every y
    wyy = (f[1:-1, 2:] - 2 * f[1:-1, 1:-1] + f[1:-1, :-2]) / hy**2     # interior x and y
    wxy = (f[1:, 1:] - f[1:, :-1] - f[:-1, 1:] + f[:-1, :-1]) / (hx * hy)
    xx = wxx[:, 1:-1]
    e = 0.5 * hx * hy * np.sum(d11 * xx**2 + 2 * d12 * xx * wyy + d22 * wyy**2)
    e += 0.5 * hx * hy / 2 * (d11 - d12**2 / d22) * np.sum(wxx[:, [0, -1]] ** 2)
    e += 0.5 * hx * hy * 4 * d66 * np.sum(wxy**2)
    weights = np.full(f.shape[1], hy)
    weights[[0, -1]] = hy / 2
    return e + 0.5 * p.k * hx * np.sum(weights * f[1:-1] ** 2)


@pytest.mark.parametrize("ratio", [0.5, 2.0])
@pytest.mark.parametrize("edges", ["free", "simply-supported"])
def test_stiffness_is_the_orthotropic_energy_written_out(edges, ratio, rng):
    p = TapeParameters(youngs_modulus=4e9, youngs_modulus_y=ratio * 4e9, shear_modulus=1e9,
                       poisson=0.3, edges=edges, spacing=WIDTH / 8, length_ratio=1.5)
    model = TapeModel(p)
    A = model.A
    assert abs(A - A.T).max() == 0.0
    for _ in range(3):
        w = rng.standard_normal(model.unknowns)
        assert 0.5 * w @ (A @ w) == pytest.approx(_energy_written_out(p, model, w), rel=1e-13)


@pytest.mark.parametrize("edges", ["free", "simply-supported"])
def test_isotropic_tape_through_the_orthotropic_path_gives_the_same_operators(edges):
    p = TapeParameters(edges=edges, spacing=WIDTH / 8, length_ratio=2.0)
    E, nu, c = p.youngs_modulus, p.poisson, p.thickness
    D = E * c**3 / (12 * (1 - nu**2))
    general = [
        p.replace(bending_stiffness=(D, D, nu * D, (1 - nu) * D / 2)),
        p.replace(youngs_modulus_y=E, shear_modulus=E / (2 * (1 + nu))),
    ]
    iso = TapeModel(p)
    for q in general:
        model = TapeModel(q)
        assert not q.isotropic
        assert _rel(model.K(40.0).toarray(), iso.K(40.0).toarray()) < ROUND_OFF
        assert _rel(model.G(40.0).toarray(), iso.G(40.0).toarray()) == 0.0
        assert _rel(model.M.diagonal(), iso.M.diagonal()) == 0.0


def _graded(length: float, n: int) -> np.ndarray:
    s = np.linspace(0.0, 1.0, n + 1)
    return length * (s - 0.6 * np.sin(2 * np.pi * s) / (2 * np.pi))


def test_bearing_plate_isotropic_through_the_orthotropic_path_on_a_graded_grid():
    p = TapeParameters()
    E, nu, c = p.youngs_modulus, p.poisson, p.thickness
    D = E * c**3 / (12 * (1 - nu**2))
    q = p.replace(bending_stiffness=(D, D, nu * D, (1 - nu) * D / 2))
    x, y = _graded(0.02, 40), _graded(p.width, 16)
    iso, general = PlateOperators(p, x, y), PlateOperators(q, x, y)
    kappa = 1.0 / 0.02 * np.cos(np.pi * x[1:-1] / 0.02)
    assert _rel(general.A.toarray(), iso.A.toarray()) < ROUND_OFF
    assert _rel(general.curvature_load(kappa), iso.curvature_load(kappa)) < ROUND_OFF


def test_bearing_curvature_load_is_the_gradient_of_the_orthotropic_energy(rng):
    """f_κ·u = E(0; κ) + ½uᵀAu − E(u; κ) with E the energy of w_xx − κ written out."""
    p = TapeParameters(**ORTHO, foundation_stiffness=0.0)
    x, y = np.linspace(0.0, 0.01, 21), np.linspace(0.0, p.width, 9)
    plate = PlateOperators(p, x, y)
    kappa = 40.0 + 10.0 * np.sin(np.pi * x[1:-1] / 0.01)
    d11, d22, d12, d66 = p.bending_matrix.as_tuple()
    hx, hy = x[1] - x[0], y[1] - y[0]

    def energy(u):
        f = np.zeros((len(x), len(y)))
        f[1:-1] = u.reshape(len(x) - 2, len(y))
        wxx = (f[2:] - 2 * f[1:-1] + f[:-2]) / hx**2 - kappa[:, None]
        wyy = (f[1:-1, 2:] - 2 * f[1:-1, 1:-1] + f[1:-1, :-2]) / hy**2
        wxy = (f[1:, 1:] - f[1:, :-1] - f[:-1, 1:] + f[:-1, :-1]) / (hx * hy)
        xx = wxx[:, 1:-1]
        return (0.5 * hx * hy * np.sum(d11 * xx**2 + 2 * d12 * xx * wyy + d22 * wyy**2)
                + 0.25 * hx * hy * (d11 - d12**2 / d22) * np.sum(wxx[:, [0, -1]] ** 2)
                + 2 * hx * hy * d66 * np.sum(wxy**2))

    u = 1e-6 * rng.standard_normal(plate.n)
    expected = energy(np.zeros(plate.n)) + 0.5 * u @ (plate.A @ u) - energy(u)
    assert plate.curvature_load(kappa) @ u == pytest.approx(expected, rel=1e-9)


# ----- refusals ---------------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("changes", "match"),
    [
        (dict(youngs_modulus_y=4e9), "shear_modulus .* is required with youngs_modulus_y"),
        (dict(shear_modulus=1e9), "youngs_modulus_y .* is required with shear_modulus"),
        (dict(youngs_modulus_y=-1.0, shear_modulus=1e9), "youngs_modulus_y must be > 0"),
        (dict(youngs_modulus_y=4e9, shear_modulus=0.0), "shear_modulus must be > 0"),
        (dict(youngs_modulus_y=16e9, shear_modulus=1e9, poisson=0.5),
         r"poisson must be in \(-0.5, 0.5\).*nu_xy\^2 < E_x/E_y"),
        (dict(youngs_modulus_y=1e9, shear_modulus=1e9, poisson=float("nan")),
         "poisson must be finite"),
        (dict(youngs_modulus_y=4e9, shear_modulus=1e9, bending_rigidity=1e-6),
         "bending_rigidity cannot be combined with youngs_modulus_y"),
        (dict(youngs_modulus_y=4e9, shear_modulus=1e9, bending_stiffness=(1, 1, 0, 1)),
         "bending_stiffness cannot be combined with youngs_modulus_y"),
        (dict(bending_stiffness=(1e-6, 1e-6, 0.0, 1e-6), bending_rigidity=1e-6),
         "bending_stiffness cannot be combined with bending_rigidity"),
        (dict(bending_stiffness=(1e-6, 1e-6, 2e-6, 1e-6)),
         r"bending_stiffness must be positive definite: D12\^2 < D11 D22"),
        (dict(bending_stiffness=(-1e-6, 1e-6, 0.0, 1e-6)), "bending_stiffness D11 must be > 0"),
        (dict(bending_stiffness=(1e-6, 0.0, 0.0, 1e-6)), "bending_stiffness D22 must be > 0"),
        (dict(bending_stiffness=(1e-6, 1e-6, 0.0, 0.0)), "bending_stiffness D66 must be > 0"),
        (dict(bending_stiffness=(1e-6, 1e-6, 0.0)), "bending_stiffness must be 4 numbers"),
        (dict(bending_stiffness=(1e300, 1e-6, 0.0, 1e-6)), "overflows the solvers' range"),
        (dict(membrane_stiffness=0.0), "membrane_stiffness must be > 0"),
        (dict(membrane_stiffness=float("inf")), "membrane_stiffness must be finite"),
        (dict(layers=[]), "layers must hold at least one layer"),
        (dict(layers=MAGNETIC), "layers must be a non-empty sequence"),
        (dict(layers=[MAGNETIC]), "thickness must be the layer stack's 1e-06 m"),
        (dict(layers=[{"thickness": 1e-6}]), r"layers\[0\] must have exactly the fields"),
        (dict(layers=[{**MAGNETIC.as_dict(), "density": 0.0}]),
         r"layers\[0\].density must be > 0 kg/m\^3"),
        (dict(layers=[MAGNETIC, "PEN"]), r"layers\[1\] must be a Layer"),
    ],
)
def test_invalid_orthotropic_input_is_refused_in_one_line(changes, match):
    with pytest.raises(ParameterError, match=match) as info:
        TapeParameters(**changes)
    assert "\n" not in str(info.value)


@pytest.mark.parametrize(
    ("fields", "match"),
    [
        (dict(thickness=0.0), "thickness must be > 0 m"),
        (dict(thickness=-1e-6), "thickness must be > 0 m"),
        (dict(youngs_modulus_x=0.0), "youngs_modulus_x must be > 0 Pa"),
        (dict(youngs_modulus_y=float("nan")), "youngs_modulus_y must be finite"),
        (dict(shear_modulus=-1.0), "shear_modulus must be > 0 Pa"),
        (dict(poisson_xy=1.3), r"poisson_xy must be in .*nu_xy\^2 < E_x/E_y"),
        (dict(density=-1.0), "density must be > 0 kg/m"),
        (dict(youngs_modulus_x=1e308, youngs_modulus_y=1e308, poisson_xy=1 - 1e-10), "overflows"),
    ],
)
def test_invalid_layer_is_refused_naming_the_field(fields, match):
    with pytest.raises(ParameterError, match=match) as info:
        Layer(**{**MAGNETIC.as_dict(), **fields})
    assert "\n" not in str(info.value)


@pytest.mark.parametrize(
    ("changes", "match"),
    [
        (dict(bending_rigidity=1e-6), "layers cannot be combined with bending_rigidity"),
        (dict(youngs_modulus_y=4e9, shear_modulus=1e9),
         "layers cannot be combined with shear_modulus, youngs_modulus_y"),
        (dict(membrane_stiffness=1e5), "layers cannot be combined with membrane_stiffness"),
        (dict(bending_stiffness=(1e-6, 1e-6, 0, 1e-6)),
         "layers cannot be combined with bending_stiffness"),
        (dict(density=0.02), "density must be the layer stack's"),
        (dict(poisson=0.3), "poisson must be the layer stack's"),
        (dict(youngs_modulus=4e9), "youngs_modulus must be the layer stack's"),
    ],
)
def test_layers_refuse_other_stiffnesses_and_inconsistent_fields(changes, match):
    p = TapeParameters.from_layers([MAGNETIC, BASE, BACK])
    with pytest.raises(ParameterError, match=match):
        p.replace(**changes)


def test_from_layers_refuses_the_fields_it_sets():
    with pytest.raises(ParameterError, match="from_layers sets thickness from the stack"):
        TapeParameters.from_layers([BASE], thickness=1e-5)
