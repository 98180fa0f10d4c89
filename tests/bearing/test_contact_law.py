"""The contact laws: Greenwood–Williamson asperity pressure against its defining integral
and its closed forms, a measured compliance curve's interpolation, the hard wall as the
limit σ_s → 0, and the parameters' checks and round trips."""

from __future__ import annotations

import json
import math
import pickle

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.interpolate import PchipInterpolator
from scipy.special import erfc, gamma, pbdv

from gyroshell.bearing.contact import (
    CONTACT_LAWS,
    ComplianceCurve,
    ContactParameters,
    GreenwoodWilliamson,
    HardWall,
    pchip_slopes,
    summit_integral,
)
from gyroshell.core.errors import InputFileError, MissingFileError, ParameterError

SIGMA, ETA, BETA, E_STAR = 6e-9, 6.7e11, 10e-6, 5e9


@pytest.fixture(scope="module")
def law() -> GreenwoodWilliamson:
    return GreenwoodWilliamson(SIGMA, ETA, BETA, E_STAR)


def gaussian(z, sigma=SIGMA):
    return math.exp(-0.5 * (z / sigma) ** 2) / (sigma * math.sqrt(2 * math.pi))


def gw_integral(d, power, sigma=SIGMA):
    """∫_d^∞ (z − d)^power φ(z) dz by QUADPACK's algebraic-weight rule (u = (z − d)/σ)."""
    top = max(-d / sigma, 0.0) + 40.0
    value, _ = quad(lambda u: gaussian(d + sigma * u, sigma) * sigma, 0.0, top,
                    weight="alg", wvar=(power, 0.0), epsabs=0.0, epsrel=1e-13, limit=200)
    return sigma ** power * value


def closed_form(n, t):
    """F_n(t) = Γ(n+1)/√(2π) e^{−t²/4} D_{−n−1}(t), scipy's parabolic cylinder function."""
    return gamma(n + 1) / math.sqrt(2 * math.pi) * np.exp(-t * t / 4) * pbdv(-n - 1, t)[0]


# ----- Greenwood–Williamson ---------------------------------------------------------------------
@pytest.mark.parametrize("t", np.linspace(-4.0, 8.0, 25))
def test_pressure_is_the_defining_integral(law, t):
    d = t * SIGMA
    p, dp = law.pressure(d)
    expected = 4 / 3 * E_STAR * ETA * math.sqrt(BETA) * gw_integral(d, 1.5)
    assert p == pytest.approx(expected, rel=1e-11)
    # dp/dd = −(4/3)(3/2) E* η √β ∫ (z − d)^{1/2} φ dz
    slope = -2.0 * E_STAR * ETA * math.sqrt(BETA) * gw_integral(d, 0.5)
    assert dp == pytest.approx(slope, rel=1e-11)


@pytest.mark.parametrize("t", [-3.0, -0.5, 0.0, 1.0, 2.0, 3.7, 6.0])
def test_slope_is_the_finite_difference_of_the_pressure(law, t):
    h = 1e-5 * SIGMA
    d = t * SIGMA
    (p_plus, _), (p_minus, _) = law.pressure(d + h), law.pressure(d - h)
    assert law.pressure(d)[1] == pytest.approx((p_plus - p_minus) / (2 * h), rel=1e-7)


def test_closed_forms_at_contact_with_the_mean_plane(law):
    """F_n(0) = 2^{(n−1)/2} Γ((n+1)/2)/√(2π): F_{3/2}(0) = 2^{1/4} Γ(5/4)/√(2π)."""
    p, dp = law.pressure(0.0)
    root = math.sqrt(2 * math.pi)
    assert p == pytest.approx(law.pressure_scale * 2 ** 0.25 * gamma(1.25) / root, rel=1e-13)
    assert dp == pytest.approx(-1.5 * law.pressure_scale / SIGMA
                               * 2 ** -0.25 * gamma(0.75) / root, rel=1e-13)


def test_agrees_with_the_parabolic_cylinder_closed_form_from_minus_8_to_40():
    t = np.linspace(-8.0, 40.0, 4801)
    for n in (0.5, 1.5):
        ours, exact = summit_integral(n, t), closed_form(n, t)
        normal = exact > 1e-300
        # pbdv itself is good to 3.4e-9 (near t = 5.8), so that bounds the comparison
        np.testing.assert_allclose(ours[normal], exact[normal], rtol=1e-8)
        assert np.all(ours[~normal] < 1e-290)


def test_deep_penetration_is_every_summit_in_hertz_contact():
    """t ≪ 0: F_{3/2}(t) = E[(s + a)^{3/2}], a = −t: the binomial series with the Gaussian's
    moments, a^{3/2} (1 + 3/(8a²) + 9/(128a⁴) + 105/(1024a⁶) + O(a⁻⁸))."""
    a = np.array([12.0, 50.0, 1e3, 1e6])
    expected = a ** 1.5 * (1 + 3 / (8 * a * a) + 9 / (128 * a ** 4) + 105 / (1024 * a ** 6))
    np.testing.assert_allclose(summit_integral(1.5, -a), expected, rtol=1e-9)


def test_real_area_and_contact_count_are_greenwood_williamson(law):
    for t in (-1.0, 0.0, 1.5, 3.0):
        d = t * SIGMA
        area = math.pi * ETA * BETA * gw_integral(d, 1.0)
        assert law.real_area_fraction(d) == pytest.approx(area, rel=1e-11)
        # F_1(t) = φ(t) − t Q(t), F_0(t) = Q(t)
        q = 0.5 * erfc(t / math.sqrt(2))
        f1 = math.exp(-t * t / 2) / math.sqrt(2 * math.pi) - t * q
        assert law.real_area_fraction(d) == pytest.approx(math.pi * ETA * BETA * SIGMA * f1,
                                                          rel=1e-11)
        assert law.asperity_count(d) == pytest.approx(ETA * q, rel=1e-13)


def test_pressure_is_positive_and_falls_with_separation(law):
    d = np.linspace(-10.0, 30.0, 8001) * SIGMA
    p, dp = law.pressure(d)
    assert np.all(p > 0) and np.all(dp < 0)
    assert np.all(np.diff(p) < 0)
    far, slope_far = law.pressure(np.array([41.0, 1e6]) * SIGMA)
    assert np.all(far == 0.0) and np.all(slope_far == 0.0)


def test_pressure_scales_with_modulus_density_and_root_radius():
    base = GreenwoodWilliamson(SIGMA, ETA, BETA, E_STAR)
    d = np.array([-1.0, 0.5, 2.0, 3.5]) * SIGMA
    p0 = base.pressure(d)[0]
    for factor, law in ((2.0, GreenwoodWilliamson(SIGMA, ETA, BETA, 2 * E_STAR)),
                        (3.0, GreenwoodWilliamson(SIGMA, 3 * ETA, BETA, E_STAR)),
                        (2.0, GreenwoodWilliamson(SIGMA, ETA, 4 * BETA, E_STAR))):
        np.testing.assert_allclose(law.pressure(d)[0], factor * p0, rtol=1e-14)


def test_pressure_over_roughness_to_the_three_halves_depends_on_d_over_sigma_only():
    t = np.array([-2.0, 0.0, 1.0, 2.5, 4.0])
    curves = [GreenwoodWilliamson(s, ETA, BETA, E_STAR).pressure(t * s)[0] * s ** -1.5
              for s in (3e-9, 6e-9, 12e-9)]
    np.testing.assert_allclose(curves[0], curves[1], rtol=1e-13)
    np.testing.assert_allclose(curves[2], curves[1], rtol=1e-13)


def test_separation_inverts_the_pressure(law):
    loads = np.array([1e2, 1e4, 1e5, 1e7, 1e9])
    d = law.separation(loads)
    np.testing.assert_allclose(law.pressure(d)[0], loads, rtol=1e-12)
    assert d[-1] < 0 < d[0]          # above p(0) ≈ 0.43 p_s the summits' plane is passed
    with pytest.raises(ParameterError, match="pressure must be > 0 Pa"):
        law.separation(0.0)


def test_hard_wall_is_the_limit_of_vanishing_roughness():
    """At a fixed pressure scale p_s the separation carrying a load falls as σ_s: the law
    becomes a wall at d = 0; at fixed η, β instead it tends to the Hertz penetration of
    every summit, −(P / ((4/3) E* η √β))^{2/3}."""
    load, scale = 5e4, 6.5e6
    separations = []
    for sigma in (8e-9, 2e-9, 5e-10, 1.25e-10):
        eta = scale / (4 / 3 * E_STAR * math.sqrt(BETA) * sigma ** 1.5)
        separations.append(GreenwoodWilliamson(sigma, eta, BETA, E_STAR).separation(load))
    assert separations[0] > 0
    np.testing.assert_allclose(np.diff(np.log(separations)), math.log(0.25), rtol=1e-10)
    assert separations[-1] < 0.5e-9
    hertz = -(load / (4 / 3 * E_STAR * ETA * math.sqrt(BETA))) ** (2 / 3)
    fixed = [GreenwoodWilliamson(s, ETA, BETA, E_STAR).separation(load)
             for s in (1e-9, 1e-10, 1e-11)]
    errors = np.abs(np.array(fixed) - hertz)
    assert errors[2] < errors[1] < errors[0] and errors[2] < 1e-3 * abs(hertz)


@pytest.mark.parametrize("name, value, message", [
    ("roughness", 0.0, r"roughness must be in \[1e-12, 0.0001\] m, got 0"),
    ("asperity_density", -1.0, r"asperity_density must be in \[1, 1e\+20\] 1/m\^2"),
    ("asperity_radius", math.nan, "asperity_radius must be finite"),
    ("contact_modulus", 1e20, r"contact_modulus must be in \[1000, 1e\+13\] Pa"),
])
def test_law_refuses_parameters_out_of_range(name, value, message):
    kw = {"roughness": SIGMA, "asperity_density": ETA, "asperity_radius": BETA,
          "contact_modulus": E_STAR, name: value}
    with pytest.raises(ParameterError, match=message):
        GreenwoodWilliamson(**kw)


# ----- the compliance curve ----------------------------------------------------------------------
D_TABLE = np.array([2.0, 4.0, 6.0, 9.0, 12.0, 16.0]) * 1e-9
P_TABLE = np.array([4e5, 1.2e5, 3e4, 5e3, 4e2, 0.0])


@pytest.fixture(scope="module")
def curve() -> ComplianceCurve:
    return ComplianceCurve(D_TABLE, P_TABLE)


def test_curve_passes_through_its_points(curve):
    np.testing.assert_array_equal(curve.pressure(D_TABLE)[0], P_TABLE)


def test_curve_slopes_are_scipys_pchip(rng):
    x = np.cumsum(rng.uniform(0.1, 2.0, 12))
    y = np.cumsum(rng.uniform(-3.0, 0.0, 12))[::-1].copy() * -1.0   # non-increasing
    y[4] = y[5]                                                     # a flat step
    for n in (2, 3, 12):
        expected = PchipInterpolator(x[:n], y[:n]).derivative()(x[:n])
        np.testing.assert_allclose(pchip_slopes(x[:n], y[:n]), expected, rtol=1e-12,
                                   atol=1e-12)


def test_curve_is_monotone_and_c1_with_its_finite_differences(curve):
    d = np.linspace(-5e-9, 25e-9, 30001)
    p, dp = curve.pressure(d)
    assert np.all(np.diff(p) <= 0) and np.all(dp <= 0) and np.all(p >= 0)
    h = 1e-15                                          # m: 1e-6 of the table's spacing
    for knot in np.concatenate([D_TABLE, [1.3e-9, 7.7e-9, 20e-9]]):
        left, right = curve.pressure(knot - 1e-18)[1], curve.pressure(knot + 1e-18)[1]
        scale = np.max(np.abs(np.diff(P_TABLE) / np.diff(D_TABLE)))   # Pa/m
        assert abs(left - right) < 1e-6 * scale        # one slope on both sides
        (pp, _), (pm, _) = curve.pressure(knot + h), curve.pressure(knot - h)
        assert curve.pressure(knot)[1] == pytest.approx((pp - pm) / (2 * h), rel=1e-5,
                                                        abs=1e-6 * scale)


def test_curve_is_zero_beyond_a_table_ending_at_zero_and_stiffens_below(curve):
    p, dp = curve.pressure(np.array([16e-9, 17e-9, 1e-3]))
    assert np.all(p == 0) and np.all(dp == 0)
    # a straight last stretch down to 0 still meets p = 0 with zero slope: C¹ there
    straight = ComplianceCurve([1e-9, 2e-9, 3e-9], [2e3, 1e3, 0.0])
    inside = np.linspace(1e-9, 3e-9, 2001)
    p, dp = straight.pressure(inside)
    assert np.all(np.diff(p) <= 0) and np.all(p >= 0)
    assert abs(straight.pressure(3e-9 - 1e-18)[1]) < 1e-6 * 1e3 / 1e-9
    d = np.array([2e-9, 1e-9, 0.0, -1e-8, -1e-6])
    p, dp = curve.pressure(d)
    assert np.all(np.diff(p) > 0) and np.all(np.diff(dp) < 0)     # steeper and steeper


def test_curve_ending_above_zero_decays_smoothly():
    c = ComplianceCurve(D_TABLE[:-1], P_TABLE[:-1])
    end = D_TABLE[-2]
    p, dp = c.pressure(np.array([end, end + 1e-9, end + 5e-9, end + 1e-7]))
    assert p[0] == P_TABLE[-2] and np.all(np.diff(p) < 0) and p[-1] < 1e-100
    scale = abs(P_TABLE[-2] - P_TABLE[-3]) / (D_TABLE[-2] - D_TABLE[-3])    # Pa/m
    assert abs(c.pressure(end + 1e-16)[1] - c.pressure(end - 1e-16)[1]) < 1e-6 * scale


def test_curve_tabulated_from_the_asperity_law_reproduces_it(law):
    d = np.linspace(-1.0, 4.0, 51) * SIGMA
    c = ComplianceCurve(d, law.pressure(d)[0])
    between = 0.5 * (d[1:] + d[:-1])
    np.testing.assert_allclose(c.pressure(between)[0], law.pressure(between)[0], rtol=3e-3)


def write(tmp_path, text, name="curve.csv"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def test_curve_from_csv(tmp_path, curve):
    rows = "\n".join(f"{d!r},{p!r}" for d, p in zip(D_TABLE.tolist(), P_TABLE.tolist(),
                                                    strict=True))
    path = write(tmp_path, f"separation_m,pressure_Pa\n{rows}\n\n")
    read = ComplianceCurve.from_csv(path)
    assert read == curve and read.source == str(path)
    np.testing.assert_array_equal(read.pressure(np.linspace(0, 2e-8, 7))[0],
                                  curve.pressure(np.linspace(0, 2e-8, 7))[0])


@pytest.mark.parametrize("text, message", [
    ("", "the compliance table is empty"),
    ("separation_m,pressure_Pa\n", "the compliance table is empty"),
    ("separation_m,pressure_Pa\n1e-9,1e5\n", "needs at least 2 points, got 1"),
    ("separation_m,pressure_Pa\n1e-9,nan\n2e-9,0\n", "point 1 is not finite"),
    ("separation_m,pressure_Pa\n1e-9,1e5\n2e-9,inf\n", "point 2 is not finite"),
    ("1e-9,1e5\n2e-9,0\n", "no header: the first line must be separation_m,pressure_Pa"),
    ("d,p\n1e-9,1e5\n2e-9,0\n", "the header must be separation_m,pressure_Pa, got d,p"),
    ("separation_m,pressure_Pa\n2e-9,1e5\n1e-9,0\n", "separation_m must increase strictly"),
    ("separation_m,pressure_Pa\n1e-9,1e5\n1e-9,0\n", "separation_m must increase strictly"),
    ("separation_m,pressure_Pa\n1e-9,1e4\n2e-9,2e4\n3e-9,0\n",
     "pressure_Pa must not increase with separation"),
    ("separation_m,pressure_Pa\n1e-9,1e5\n2e-9,-1\n", "pressure_Pa must be >= 0, point 2"),
    ("separation_m,pressure_Pa\n1e-9,0\n2e-9,0\n", "pressure_Pa is 0 at every point"),
    ("separation_m,pressure_Pa\n1e-9,1e5,3\n2e-9,0\n", "line 2 must be 2 numbers"),
    ("separation_m,pressure_Pa\n1e-9,lots\n2e-9,0\n", "line 2 must be 2 numbers"),
])
def test_curve_file_refusals_name_the_file(tmp_path, text, message):
    path = write(tmp_path, text)
    with pytest.raises(InputFileError, match=message) as info:
        ComplianceCurve.from_csv(path)
    assert str(info.value).startswith(f"{path}: ") and "\n" not in str(info.value)


def test_curve_file_that_is_missing_a_folder_or_not_text(tmp_path):
    with pytest.raises(MissingFileError, match="no such compliance CSV file"):
        ComplianceCurve.from_csv(tmp_path / "absent.csv")
    with pytest.raises(InputFileError, match="is a directory"):
        ComplianceCurve.from_csv(tmp_path)
    path = tmp_path / "binary.csv"
    path.write_bytes(b"\xff\xfe\x00bad")
    with pytest.raises(InputFileError, match="cannot be read as UTF-8 text"):
        ComplianceCurve.from_csv(path)


def test_curve_from_arrays_refuses_with_a_parameter_error():
    with pytest.raises(ParameterError, match="compliance curve: pressure_Pa must not increase"):
        ComplianceCurve([1e-9, 2e-9], [1.0, 2.0])
    with pytest.raises(ParameterError, match="one value per point, got 3 and 2"):
        ComplianceCurve([1e-9, 2e-9, 3e-9], [1.0, 0.0])


def test_curve_dict_round_trip(curve, tmp_path):
    again = ComplianceCurve.from_dict(json.loads(json.dumps(curve.to_dict())))
    assert again == curve and hash(again) == hash(curve)
    d = np.linspace(-3e-9, 2e-8, 11)
    np.testing.assert_array_equal(again.pressure(d)[0], curve.pressure(d)[0])
    assert pickle.loads(pickle.dumps(curve)) == curve
    with pytest.raises(ParameterError, match="unknown key.*points; allowed: separation_m"):
        ComplianceCurve.from_dict({**curve.to_dict(), "points": 3})


# ----- the parameters ---------------------------------------------------------------------------
def test_defaults_are_the_asperity_law_of_a_modern_data_tape():
    params = ContactParameters()
    assert params.law == "asperity" == CONTACT_LAWS[0]
    law = params.law_object
    assert isinstance(law, GreenwoodWilliamson) and law.kind == "asperity"
    assert 5e-9 <= law.roughness <= 10e-9
    assert 0.03 <= law.asperity_density * law.asperity_radius * law.roughness <= 0.05
    # a land load of 10–100 kPa rests at d/σ_s between 1.5 and 3 (the docstring's claim)
    t = law.separation(np.array([1e5, 1e4])) / law.roughness
    assert 1.5 < t[0] < t[1] < 3.0


def test_hard_wall_and_compliance_laws():
    hard = ContactParameters(law="hard")
    assert isinstance(hard.law_object, HardWall) and hard.law_object.gap == 20e-9
    assert ContactParameters(law="hard", roughness=5e-9).law_object == HardWall(5e-9)
    assert not hard.smooth
    with pytest.raises(ParameterError, match="not a pressure function"):
        hard.pressure(1e-9)
    curve = ComplianceCurve(D_TABLE, P_TABLE)
    measured = ContactParameters(law="compliance", compliance=curve)
    assert measured.law_object is curve and measured.smooth
    np.testing.assert_array_equal(measured.pressure(D_TABLE)[0], P_TABLE)


@pytest.mark.parametrize("kw, message", [
    ({"law": "hard", "asperity_density": 1e12},
     "asperity_density applies to contact='asperity' only, and this contact is 'hard'"),
    ({"law": "hard", "contact_modulus": 1e9}, "contact_modulus applies to contact='asperity'"),
    ({"law": "compliance", "roughness": 5e-9,
      "compliance": ComplianceCurve(D_TABLE, P_TABLE)},
     "roughness applies to contact='asperity' or 'hard' only, and this contact is "
     "'compliance'"),
    ({"compliance": ComplianceCurve(D_TABLE, P_TABLE)},
     "compliance applies to contact='compliance' only"),
    ({"law": "compliance"}, "contact='compliance' needs its curve"),
    ({"law": "wall"}, "contact must be one of asperity, hard, compliance, got 'wall'"),
    ({"roughness": -1e-9}, r"roughness must be in \[1e-12, 0.0001\] m"),
    ({"law": "hard", "roughness": 1.0}, r"roughness must be in \[1e-12, 0.0001\] m"),
    ({"asperity_radius": 0.0}, r"asperity_radius must be in \[1e-10, 0.1\] m"),
    ({"law": "compliance", "compliance": [1, 2]}, "compliance must be a ComplianceCurve"),
])
def test_parameters_refuse_what_would_not_act_or_is_out_of_range(kw, message):
    with pytest.raises(ParameterError, match=message) as info:
        ContactParameters(**kw)
    assert "\n" not in str(info.value)


def test_parameters_dict_round_trips():
    for params in (ContactParameters(), ContactParameters(roughness=8e-9, asperity_radius=2e-5),
                   ContactParameters(law="hard", roughness=15e-9),
                   ContactParameters(law="compliance",
                                     compliance=ComplianceCurve(D_TABLE, P_TABLE))):
        data = json.loads(json.dumps(params.to_dict()))
        again = ContactParameters.from_dict(data)
        assert again == params and hash(again) == hash(params)
        assert set(data) == {"law", *{"asperity": ["roughness", "asperity_density",
                                                   "asperity_radius", "contact_modulus"],
                                      "hard": ["roughness"],
                                      "compliance": ["compliance"]}[params.law]}
    with pytest.raises(ParameterError, match=r"unknown key\(s\) dry, sigma; allowed: law, "
                                             "roughness, asperity_density"):
        ContactParameters.from_dict({"law": "hard", "sigma": 1e-9, "dry": True})


def test_replace_keeps_or_restarts_from_the_law_defaults():
    params = ContactParameters(roughness=8e-9)
    assert params.replace(contact_modulus=2e9).roughness == 8e-9
    hard = params.replace(law="hard")
    assert hard.roughness == 20e-9 and hard.asperity_density is None
    with pytest.raises(ParameterError, match="have no sigma"):
        params.replace(sigma=1e-9)


def test_toml_table_with_units_and_a_curve_beside_the_file(tmp_path):
    from gyroshell.tape.config import _tomllib

    tomllib = _tomllib()      # the standard library's, or tomli on Python 3.10

    rows = "\n".join(f"{d!r},{p!r}" for d, p in zip(D_TABLE.tolist(), P_TABLE.tolist(),
                                                    strict=True))
    (tmp_path / "tape.csv").write_text(f"separation_m,pressure_Pa\n{rows}\n")
    asperity = tomllib.loads('[contact]\nroughness = "8 nm"\nasperity_density = "0.5 1/um^2"\n'
                             'asperity_radius = "20 um"\ncontact_modulus = "3 GPa"\n')
    params = ContactParameters.from_table(asperity["contact"], tmp_path)
    assert params == ContactParameters(roughness=8e-9, asperity_density=5e11,
                                       asperity_radius=2e-5, contact_modulus=3e9)
    measured = ContactParameters.from_table({"law": "compliance", "compliance": "tape.csv"},
                                            tmp_path)
    assert measured.compliance == ComplianceCurve(D_TABLE, P_TABLE)
    assert measured.compliance.source == str(tmp_path / "tape.csv")


@pytest.mark.parametrize("table, message", [
    ({"law": "hard", "gap": 1e-9}, r"run.toml: \[contact\] unknown key\(s\) gap; allowed: "
                                   "law, roughness"),
    ({"law": "hard", "asperity_radius": "1 um"},
     r"run.toml: \[contact\] asperity_radius applies to contact='asperity' only"),
    ({"roughness": "5 nN"}, r"run.toml: \[contact\] roughness: unit 'nN' is not a unit of m"),
    ({"asperity_density": "3 per um2"}, r"\[contact\] asperity_density must look like"),
    ({"law": 3}, r"\[contact\] law must be text"),
    ({"law": "compliance", "compliance": "absent.csv"}, "no such compliance CSV file"),
])
def test_toml_table_refusals_name_the_file_and_key(tmp_path, table, message):
    with pytest.raises(ParameterError, match=message):
        ContactParameters.from_table(table, tmp_path, where="run.toml: ")


def test_docstring_examples():
    import doctest

    import gyroshell.bearing.contact as module

    result = doctest.testmod(module, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert result.attempted > 0 and result.failed == 0
