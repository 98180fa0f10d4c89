"""Head contours (gyroshell.bearing.head): the contour, the dry string configuration over
it, its gap and curvature, corners and lands, the JSON round trip and the CSV profile."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from bearing_cases import FIRST_ORDER, HARD

from gyroshell import ParameterError
from gyroshell.bearing.head import (
    Cylinder,
    FlatHead,
    Module,
    ProfileHead,
    head_from_dict,
)
from gyroshell.core.errors import InputFileError

DEG = math.pi / 180.0
PHI = 20 * DEG          # the default flank angle


def _graded(lo, hi, n, rng):
    """Strictly increasing abscissae on [lo, hi] with random spacing (a graded grid)."""
    steps = rng.uniform(0.5, 1.5, n)
    return lo + (hi - lo) * np.concatenate([[0.0], np.cumsum(steps)]) / steps.sum()


def _control_widths(x):
    h = np.diff(x)
    return 0.5 * (h[:-1] + h[1:])


def test_flat_module_contour_and_dry_tape_are_the_string_over_two_sharp_corners():
    """One land of length L, sharp corners at ±L/2, spans at θ_in and θ_out: the string
    lies on the land and leaves each corner along a straight span; below the span the
    flank falls at φ, so the dry gap past a corner grows like (φ − θ) d."""
    L, t_in, t_out = 1e-3, 2 * DEG, 3 * DEG
    head = FlatHead((Module(L),), t_in, t_out)
    x = np.linspace(-2e-3, 2e-3, 801)
    d_left, d_right = np.clip(-L / 2 - x, 0, None), np.clip(x - L / 2, 0, None)
    assert np.array_equal(head.surface(x), -PHI * d_left - PHI * d_right)
    np.testing.assert_allclose(head.dry_tape(x), -t_in * d_left - t_out * d_right,
                               rtol=0, atol=1e-18)
    np.testing.assert_allclose(head.dry_gap(x), (PHI - t_in) * d_left + (PHI - t_out) * d_right,
                               rtol=1e-12, atol=1e-18)
    assert head.extent() == head.corners() == head.sharp_corners() == (-L / 2, L / 2)
    assert head.lands() == ((-L / 2, L / 2),)
    assert head.corner_turns() == pytest.approx((t_in, t_out), rel=1e-12)
    assert head.wrap == t_in + t_out and not head.symmetric


def test_sharp_corner_curvature_is_a_discrete_delta_carrying_the_turn():
    """κ = −δ²z₀ is zero on the land and spans and θ_c/w_i at a corner node, so that
    Σ W κ = θ_in + θ_out: the wrap load (T − ρV²) W κ is the corners' point loads."""
    L, t_in, t_out = 1e-3, 2 * DEG, 1 * DEG
    head = FlatHead((Module(L),), t_in, t_out)
    rng = np.random.default_rng(3)
    x = np.unique(np.concatenate([_graded(-2e-3, 2e-3, 300, rng), [-L / 2, L / 2]]))
    kappa = head.dry_curvature(x)
    w = _control_widths(x)
    inner = x[1:-1]
    at = [int(np.flatnonzero(inner == c)[0]) for c in (-L / 2, L / 2)]
    assert kappa[at] * w[at] == pytest.approx([t_in, t_out], rel=1e-9)
    rest = np.delete(kappa, at)
    assert np.max(np.abs(rest)) < 1e-9 * max(kappa[at])
    assert np.sum(w * kappa) == pytest.approx(t_in + t_out, rel=1e-12)


def test_rounded_corner_wraps_its_arc_at_curvature_one_over_r():
    """A corner of radius r: the tape lies on the arc over r θ (κ = 1/r there) and the
    total turn is still the wrap."""
    r, theta = 2e-3, 2 * DEG
    head = FlatHead((Module(1e-3, corner_radius=r),), theta, theta)
    x = np.linspace(-3e-3, 3e-3, 6001)
    kappa = head.dry_curvature(x)
    inner = x[1:-1]
    tangent = -0.5e-3 + 0.5 * r * PHI             # where the land meets the arc
    on_arc = (inner < tangent - 2e-6) & (inner > tangent - r * theta + 2e-6)
    assert on_arc.sum() > 50
    np.testing.assert_allclose(kappa[on_arc], 1.0 / r, rtol=1e-6)
    assert np.sum(_control_widths(x) * kappa) == pytest.approx(2 * theta, rel=1e-9)
    assert head.corner_turns() == pytest.approx((theta, theta), rel=1e-6)
    assert head.sharp_corners() == ()
    assert np.all(head.dry_gap(x) >= 0.0)


def test_cylinder_is_the_shallow_shell_wrap():
    """z_h = −x²/(2R); the dry gap (|x| − Rθ/2)₊²/(2R); κ = 1/R on the wrap and 0 on the
    spans; Σ W κ = θ on any grid."""
    R, theta = 20e-3, 15 * DEG
    head = Cylinder(theta)
    rng = np.random.default_rng(5)
    x = _graded(-6e-3, 6e-3, 400, rng)
    half = R * theta / 2
    np.testing.assert_allclose(head.dry_gap(x, radius=R),
                               np.clip(np.abs(x) - half, 0, None) ** 2 / (2 * R), rtol=1e-14)
    kappa = head.dry_curvature(x, radius=R)
    inner = x[1:-1]
    np.testing.assert_allclose(kappa[np.abs(inner) < 0.9 * half], 1 / R, rtol=1e-9)
    np.testing.assert_allclose(kappa[np.abs(inner) > 1.1 * half], 0, atol=1e-9 / R)
    assert np.sum(_control_widths(x) * kappa) == pytest.approx(theta, rel=1e-12)
    assert head.extent(R) == (-half, half) and head.wrap == theta and head.symmetric
    assert Cylinder(theta, radius=R).extent() == head.extent(R)


def test_modules_at_different_heights_are_bridged_by_the_concave_envelope():
    """Three modules, the middle one raised: the string is concave, on or above the head,
    touches it, and turns by the total wrap; each land's corners are corners."""
    mods = (Module(1e-3), Module(0.6e-3, height=2e-6), Module(1e-3, tilt=-0.2 * DEG))
    head = FlatHead(mods, 2 * DEG, 2.5 * DEG, gaps=(0.2e-3, 0.3e-3))
    x = np.linspace(-4e-3, 4e-3, 8001)
    z0, zh = head.dry_tape(x), head.surface(x)
    assert np.all(z0 >= zh - 1e-18)
    slopes = np.diff(z0) / np.diff(x)
    assert np.all(np.diff(slopes) <= 1e-9)                          # concave
    assert slopes[0] == pytest.approx(2 * DEG) and slopes[-1] == pytest.approx(-2.5 * DEG)
    assert np.min(z0 - zh) == 0.0
    assert sum(head.corner_turns()) == pytest.approx(4.5 * DEG, rel=1e-9)
    assert len(head.corners()) == 6 and len(head.lands()) == 3
    a, b = head.extent()
    assert a == pytest.approx(-b) and b - a == pytest.approx(2.6e-3 + 0.5e-3)


def test_rounded_modules_whose_flank_samples_overlap_the_next_module_keep_a_concave_string():
    """Two rounded modules 145 µm apart (the first's 20° flank reaches past the second's
    start): the string is still concave over both, on or above the head, and leaves at
    the second module's trailing corner, the corners' turns summing to the wrap."""
    mods = (Module(2.515e-3, corner_radius=1.322e-3), Module(2.679e-3, corner_radius=0.495e-3))
    head = FlatHead(mods, 4.207 * DEG, 0.595 * DEG, gaps=(0.145e-3,))
    x = np.linspace(-3.5e-3, 3.5e-3, 14001)
    z0, zh = head.dry_tape(x), head.surface(x)
    assert np.all(z0 >= zh - 1e-18)
    slopes = np.diff(z0) / np.diff(x)
    assert np.all(np.diff(slopes) <= 1e-9)                          # concave
    turns = head.corner_turns()
    assert sum(turns) == pytest.approx(4.802 * DEG, rel=1e-6)
    assert turns[3] == pytest.approx(0.595 * DEG, rel=1e-6) and turns[1] == 0.0


def test_mirrored_head_reflects_the_contour_and_swaps_the_wraps():
    mods = (Module(1e-3, (0.0, 1e-3)), Module(0.5e-3, height=1e-6, tilt=0.1 * DEG))
    head = FlatHead(mods, 1.5 * DEG, 3 * DEG, gaps=(0.25e-3,), transducers=(-0.3e-3,))
    mirror = head.mirrored()
    x = np.linspace(-3e-3, 3e-3, 1201)
    np.testing.assert_allclose(mirror.surface(-x), head.surface(x), rtol=0, atol=1e-15)
    np.testing.assert_allclose(mirror.dry_gap(-x), head.dry_gap(x), rtol=0, atol=1e-14)
    assert (mirror.wrap_in, mirror.wrap_out) == (head.wrap_out, head.wrap_in)
    assert mirror.transducers == (0.3e-3,)
    assert mirror.mirrored() == head and not head.symmetric
    sym = FlatHead((Module(1e-3), Module(1e-3)), 2 * DEG, 2 * DEG, gaps=(0.1e-3,))
    assert sym.symmetric and sym.mirrored() == sym


@pytest.mark.parametrize("head", [
    Cylinder(10 * DEG), Cylinder(10 * DEG, radius=5e-3, transducers=(0.0,), friction=0.2),
    FlatHead((Module(1e-3, (0.0, 0.5e-3), 1e-7, 0.01), Module(2e-3)), 0.5 * DEG, 4 * DEG,
             gaps=(1e-4,), flank_angle=0.3, transducers=(-1e-3, 0.0), friction=0.3),
], ids=["cylinder", "cylinder-radius", "flat"])
def test_as_dict_round_trips_through_json_exactly(head):
    back = head_from_dict(json.loads(json.dumps(head.as_dict())))
    assert back == head and back.as_dict() == head.as_dict()


def _sampled_flat(shift=1e-4):
    """A flat head's contour sampled with its corners among the samples."""
    head = FlatHead((Module(1e-3),), 2 * DEG, 2 * DEG)
    x = np.unique(np.concatenate([np.linspace(-2e-3, 2e-3, 401), [-0.5e-3, 0.5e-3]]))
    return head, x, head.surface(x), shift


def test_profile_of_a_sampled_flat_head_has_its_dry_tape_and_is_centred():
    """A profile measured off-centre is shifted so that the wrapped region's middle is
    x = 0; its envelope equals the flat head's (the samples include the corners)."""
    head, x, z, shift = _sampled_flat()
    profile = ProfileHead(x + shift, z, 2 * DEG, 2 * DEG)
    assert profile.shift == pytest.approx(-shift)
    assert profile.extent() == pytest.approx((-0.5e-3, 0.5e-3), abs=1e-15)
    xs = np.linspace(-2.5e-3, 2.5e-3, 777)
    np.testing.assert_allclose(profile.dry_tape(xs), head.dry_tape(xs), rtol=0, atol=1e-15)
    np.testing.assert_allclose(profile.dry_gap(xs[np.abs(xs) < 2e-3]),
                               head.dry_gap(xs[np.abs(xs) < 2e-3]), rtol=0, atol=1e-15)
    assert profile.sharp_corners() == pytest.approx((-0.5e-3, 0.5e-3), abs=1e-15)
    assert profile.symmetric
    back = head_from_dict(json.loads(json.dumps(profile.as_dict())))
    assert back == profile and np.array_equal(back.x, profile.x)


def test_profile_csv_reads_x_z_and_x_y_z_with_a_header(tmp_path):
    head, x, z, _ = _sampled_flat(0.0)
    path = tmp_path / "p.csv"
    lines = [f"{a},{b}\n" for a, b in zip(x.tolist(), z.tolist(), strict=True)]
    path.write_text("x,z\n" + "".join(lines))
    profile = ProfileHead.from_csv(path, wrap_in=2 * DEG, wrap_out=2 * DEG)
    assert np.array_equal(profile.z, z) and profile.y is None
    y = np.array([0.0, 5e-3, 12e-3])
    rows = [f"{a} {b} {c + 1e-7 * j}\n" for a, c in zip(x.tolist(), z.tolist(), strict=True)
            for j, b in enumerate(y.tolist())]
    path.write_text("".join(rows))
    p2 = ProfileHead.from_csv(path, wrap_in=2 * DEG, wrap_out=2 * DEG)
    assert p2.z.shape == (len(x), 3)
    zh = p2.surface(np.array([0.0]), np.array([0.0, 2.5e-3, 20e-3]))
    np.testing.assert_allclose(zh[0], [0.0, 0.5e-7, 2e-7], rtol=1e-9, atol=1e-20)
    # the envelope is that of max_y z: the highest column, 2e-7 above the first
    np.testing.assert_allclose(p2.dry_tape(np.array([0.0])), [2e-7], rtol=1e-12)


@pytest.mark.parametrize("text, match", [
    ("", "empty"),
    ("x,z\n", "empty"),
    ("0,1\n1,a\n2,3\n3,4\n", "row 2 is not numbers"),
    ("0,0\n2e-3,0\n1e-3,0\n3e-3,0\n", "strictly increasing"),
    ("0,0,0,0\n1,0,0,0\n", "2 columns"),
])
def test_bad_profile_files_are_refused_naming_the_file(tmp_path, text, match):
    path = tmp_path / "bad.csv"
    path.write_text(text)
    with pytest.raises(InputFileError, match=match) as err:
        ProfileHead.from_csv(path, wrap_in=DEG, wrap_out=DEG)
    assert "bad.csv" in str(err.value) and "\n" not in str(err.value)


def test_profile_file_too_large_for_memory_is_refused_before_reading(tmp_path, monkeypatch):
    path = tmp_path / "big.csv"
    path.write_text("0,0\n" * 1000)
    monkeypatch.setenv("GYROSHELL_MEMORY_LIMIT", "1000")
    with pytest.raises(ParameterError, match="big.csv.*more than the limit"):
        ProfileHead.from_csv(path, wrap_in=DEG, wrap_out=DEG)


def test_profile_folder_and_short_profile_are_refused(tmp_path):
    with pytest.raises(InputFileError, match="folder"):
        ProfileHead.from_csv(tmp_path, wrap_in=DEG, wrap_out=DEG)
    x = np.linspace(-1e-3, 1e-3, 11)
    with pytest.raises(ParameterError, match="does not contain the wrapped region"):
        ProfileHead(x, np.zeros_like(x) - x, DEG, DEG)     # the tape meets its first point


@pytest.mark.parametrize("make, match", [
    (lambda: FlatHead((Module(1e-3),), 0.0, 0.0), "nothing presses the tape"),
    (lambda: FlatHead((Module(1e-3, 3e-3),), DEG, DEG), r"land_length .* shorter than its "
                                                        "corner radii"),
    (lambda: FlatHead((Module(1e-3), Module(1e-3)), DEG, DEG, gaps=(-1e-4,)),
     r"gaps\[0\] must be > 0"),
    (lambda: FlatHead((Module(1e-3), Module(1e-3)), DEG, DEG, gaps=(0.0,)),
     r"gaps\[0\] must be > 0 m, got 0"),
    (lambda: FlatHead((Module(1e-3), Module(1e-3)), DEG, DEG), "gaps must hold 1"),
    (lambda: Module(1e-3, -1e-6), "corner_radius must be >= 0"),
    (lambda: Module(0.0), "land_length must be > 0"),
    (lambda: FlatHead((Module(1e-3),), 15 * DEG, DEG, flank_angle=10 * DEG),
     "flank_angle 10 degrees is not steeper than the tape at the leading corner"),
    (lambda: FlatHead((Module(1e-3),), DEG, DEG, transducers=(0.6e-3,)),
     r"transducers\[0\] must lie on the head's wrapped region"),
    (lambda: FlatHead((Module(1e-3), Module(1e-3, height=1e-4)), DEG, DEG, gaps=(1e-4,)),
     r"modules\[1\] overlaps modules\[0\]"),
    (lambda: FlatHead((), DEG, DEG), "modules must hold 1 to 8"),
    (lambda: FlatHead((Module(1e-3),), -DEG, DEG), "wrap_in must be in"),
    (lambda: FlatHead((Module(1e-3),), DEG, DEG, friction=-0.1), "friction must be >= 0"),
    (lambda: Cylinder(0.0), "wrap_angle must be in"),
    (lambda: Cylinder(DEG, radius=1e-3, transducers=(1e-3,)), "transducers"),
    (lambda: ProfileHead([0, 1, 1, 2], [0, 0, 0, 0], DEG, DEG), "strictly increasing"),
    (lambda: ProfileHead([0, 1, 2, 3], ["a", 0, 0, 0], DEG, DEG), "array of numbers"),
    (lambda: ProfileHead([], [], DEG, DEG), "non-empty"),
    (lambda: head_from_dict({"kind": "oval"}), "kind one of"),
])
def test_invalid_heads_are_refused_in_one_line_naming_the_parameter(make, match):
    with pytest.raises(ParameterError, match=match) as err:
        make()
    assert "\n" not in str(err.value)


# ----- features narrower than the bearing's grid ------------------------------------------
def _asperity_profile(height=50e-9, base=2e-6, x0=0.1e-3):
    """The sampled 1 mm flat land (2°/2°) with a triangular asperity ``height`` high and
    ``base`` wide at ``x0`` (m), sampled every base/8 about it."""
    head, x, _, _ = _sampled_flat()
    x = np.unique(np.concatenate([x, x0 + np.linspace(-base, base, 17)]))
    bump = np.clip(height * (1 - np.abs(x - x0) / (base / 2)), 0.0, None)
    return ProfileHead(x, head.surface(x) + bump, 2 * DEG, 2 * DEG)


def test_unresolved_features_are_those_standing_above_the_contour_through_the_nodes():
    """Nodes 6.5 µm apart that step over a 50 nm × 2 µm asperity: the grid's contour is
    the flat land there, so the asperity stands its whole height above it, over its base;
    nodes on its foot and apex see it whole; a threshold above its height hides it."""
    profile = _asperity_profile()
    stepping = np.concatenate([np.linspace(-1e-3, 98e-6, 40), np.linspace(104.5e-6, 1e-3, 40),
                               [-0.5e-3, 0.5e-3]])      # a node on each corner, as the bearing's
    stepping.sort()
    ((missed, width, x),) = profile.unresolved_features(stepping, 20e-9)
    assert (missed, width, x) == pytest.approx((50e-9, 2e-6, 0.1e-3), rel=1e-9)
    assert profile.unresolved_features(stepping, 51e-9) == ()
    seeing = np.sort(np.concatenate([stepping, [99e-6, 100e-6, 101e-6]]))
    assert profile.unresolved_features(seeing, 1e-12) == ()


def test_bearing_grid_stepping_over_an_asperity_warns_with_its_size_and_place():
    """The issue's case: the default 1-D grid (nodes 6.5 µm apart at x = 0.1 mm) steps
    over a 50 nm × 2 µm asperity under a tape flying at ~31.5 nm; one warning line names
    its place, width and height and the nx that resolves it, and with that nx (or
    without the asperity) no warning."""
    import warnings

    from gyroshell import TapeParameters
    from gyroshell.bearing import BearingModel
    from gyroshell.bearing.model import BearingGridWarning

    def build(profile, nx=None):
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            BearingModel(TapeParameters(), FIRST_ORDER, velocity=4.0, head=profile,
                         infinitely_wide=True, nx=nx, contact=HARD)
        return [str(w.message) for w in caught if w.category is BearingGridWarning]

    (line,) = build(_asperity_profile())
    assert "x = 0.1 mm, 2 um wide, stands 50 nm above the contour the grid sees" in line
    assert "\n" not in line
    nx = int(line.split("use nx >= ")[1].split()[0])
    assert build(_asperity_profile(), nx) == []
    assert build(_asperity_profile(height=10e-9)) == []     # below the roughness, 20 nm
