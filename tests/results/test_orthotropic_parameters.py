"""Saved results keep an orthotropic or layered tape exactly: the ``parameters`` attribute
holds the new fields (``layers`` as a list of objects), every float comes back bit for bit,
files without the new fields (release 0.1.0) still load, and an edited stack is refused as
when typed."""

from __future__ import annotations

import json
import math
import re

import pytest
from bit_exact import assert_same
from kind_examples import every_example

import gyroshell
from gyroshell import Layer, TapeModel, TapeParameters
from gyroshell.core.errors import InputFileError
from gyroshell.results import base

WIDTH = 6.35e-3
GRID = dict(length_ratio=2, spacing=WIDTH / 8)
#: An unsymmetric three-layer stack (B != 0) with moduli that are not short decimals.
STACK = (Layer(0.4e-6, 3.1e9, 2.9e9, 1.1e9, 0.31, 1500.0),
         Layer(4.7e-6, 8.3e9, 5.3e9, 2.1e9, 0.29, 1360.0),
         Layer(0.7e-6, 7.1e9, 6.9e9, 2.7e9, 0.3, 4100.0))
#: The three ways of giving an orthotropic tape.
TAPES = {
    "layered": TapeParameters.from_layers(STACK, **GRID),
    "moduli": TapeParameters(youngs_modulus_y=1.0 / 3.0 * 1e10, shear_modulus=math.pi * 1e8,
                             membrane_stiffness=7.7e4, **GRID),
    "stiffnesses": TapeParameters(bending_stiffness=(2e-7, 1.0 / 7.0 * 1e-6, 3e-8, 4e-8),
                                  foundation_stiffness=1.5e8, **GRID),
}


def stored_parameters(path) -> dict:
    import xarray as xr

    with xr.open_dataset(path) as ds:
        return json.loads(ds.attrs["parameters"])


@pytest.mark.parametrize("name", TAPES)
def test_parameters_json_rebuilds_the_same_tape(name):
    tape = TAPES[name]
    back = base.params_from({"parameters": base.params_json(tape)})
    assert back == tape
    assert_same(tape, back, name)  # bit for bit, layer by layer


@pytest.mark.parametrize("name", TAPES)
def test_static_file_keeps_the_tape(name, tmp_path):
    tape = TAPES[name]
    sol = gyroshell.solve_static(TapeModel(tape), 0.0)
    back = gyroshell.load(sol.save(tmp_path / "static.nc"))
    assert_same(sol, back, name)
    assert back.params.bending_matrix == tape.bending_matrix


def test_layers_are_stored_as_objects_of_their_fields(tmp_path):
    tape = TAPES["layered"]
    path = gyroshell.solve_static(TapeModel(tape), 0.0).save(tmp_path / "static.nc")
    stored = stored_parameters(path)
    assert stored["layers"] == [layer.as_dict() for layer in STACK]
    assert stored["thickness"] == sum(layer.thickness for layer in STACK)


@pytest.mark.parametrize("kind", ["study", "sweep", "bearing"])
def test_kinds_that_carry_their_tape_keep_a_layered_one(kind, tmp_path):
    tape = TAPES["layered"]
    if kind == "study":
        result = gyroshell.run_study(tape, vary={"layer2.thickness": [4e-6, 5e-6]},
                                     compute="modes", count=1, workers=1)
        assert result.table["layer2.thickness"].tolist() == [4e-6, 5e-6]
    elif kind == "sweep":
        result = gyroshell.sweep(TapeModel(tape), [0.0, 5.0], 1)
    else:
        from examples_bearing import _model

        from gyroshell.bearing import BearingModel, solve_steady

        one_d = _model()
        layered = TapeParameters.from_layers(STACK, width=3e-3)
        result = solve_steady(BearingModel(layered, one_d.air, velocity=4.0,
                                           wrap_angle=one_d.wrap_angle, infinitely_wide=True,
                                           nx=one_d.nx))
    path = result.save(tmp_path / f"{kind}.nc", params=tape)
    assert_same(result, base.read(path), kind)
    assert stored_parameters(path)["layers"] == [layer.as_dict() for layer in STACK]


def own_tape(kind: str, result):
    """The tape a result knows itself (a study's base, a bearing's model), which it stores
    instead of one given to save; None if it knows none."""
    if kind == "study":
        return result.base
    if kind == "bearing":
        return result.model.params
    if kind == "bearing_transient":
        return result.final.model.params
    return vars(result).get("params")


@pytest.mark.slow
def test_every_kind_stores_a_layered_tape_given_to_save(tmp_path):
    tape = TAPES["layered"]
    for kind, example in every_example().items():
        result = example()
        path = result.save(tmp_path / f"{kind}.nc", params=tape)
        back = TapeParameters(**stored_parameters(path))
        own = own_tape(kind, result)
        assert back == tape or (own is not None and back == own), kind
        base.read(path)  # and the file passes the layout's checks


def edited(path, change) -> None:
    """Rewrite a file's ``parameters`` through ``change(dict)``."""
    import xarray as xr

    with xr.open_dataset(path) as ds:
        ds.load()
    data = json.loads(ds.attrs["parameters"])
    change(data)
    ds.attrs["parameters"] = json.dumps(data)
    path.unlink()
    ds.to_netcdf(path)


@pytest.mark.parametrize("change, message", [
    (lambda d: d["layers"][1].update(thickness=-1e-6),
     "parameters: layers[1].thickness must be > 0 m"),
    (lambda d: d.update(thickness=d["thickness"] * 1.01),
     "parameters: thickness must be the layer stack's"),
    (lambda d: d["layers"][0].update(colour="red"), "parameters: layers[0] must have"),
    (lambda d: d.update(layers=[]), "parameters: layers must hold at least one layer"),
])
def test_an_edited_stack_is_refused_naming_the_file_and_field(tmp_path, change, message):
    path = gyroshell.solve_static(TapeModel(TAPES["layered"]), 0.0).save(tmp_path / "s.nc")
    edited(path, change)
    with pytest.raises(InputFileError, match=re.escape(f"s.nc: {message}")):
        gyroshell.load(path)


def test_a_file_without_the_orthotropic_fields_reads_as_the_isotropic_tape(tmp_path):
    tape = TapeParameters(**GRID)
    path = gyroshell.solve_static(TapeModel(tape), 0.0).save(tmp_path / "old.nc")
    edited(path, lambda d: [d.pop(name) for name in ("youngs_modulus_y", "shear_modulus",
                                                     "bending_stiffness",
                                                     "membrane_stiffness", "layers")])
    assert gyroshell.load(path).params == tape
