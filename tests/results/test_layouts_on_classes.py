"""What each kind's file holds is declared once, on its class (issue 32): ``gyroshell.load``
reads every bearing file the bearing writes (rounded corners, any ``arc_contact``, steady
and transient), the Newton record keeps the rounded corners' contact passes, and a saved
head study's bearing setup is checked on load as when it is built."""

from __future__ import annotations

import dataclasses
import json
import math

import pytest

h5py = pytest.importorskip("h5py")
pytest.importorskip("xarray")

from bearing_cases import FIRST_ORDER, HARD  # noqa: E402

import gyroshell  # noqa: E402
import gyroshell.kinds  # noqa: E402
from gyroshell import TapeParameters  # noqa: E402
from gyroshell.bearing import BearingModel  # noqa: E402
from gyroshell.bearing.head import FlatHead, Module  # noqa: E402
from gyroshell.bearing.head_config import HeadDesign  # noqa: E402
from gyroshell.bearing.steady import solve_steady  # noqa: E402
from gyroshell.bearing.transient import march, tension_step  # noqa: E402
from gyroshell.core.errors import InputFileError  # noqa: E402
from gyroshell.results import base  # noqa: E402
from gyroshell.studies.head_study import BearingStudy  # noqa: E402

WRAP = math.radians(2.0)
#: A land with corners rounded to 100 um: the tape touches each arc at a point.
ROUNDED = FlatHead((Module(1e-3, corner_radius=100e-6),), WRAP, WRAP)


def test_every_kind_declares_its_file_on_its_class():
    gyroshell.kinds.import_kinds()
    assert [kind for kind, cls in base.kinds().items() if cls.file_layout is None] == []
    assert not hasattr(gyroshell.kinds, "FILE_LAYOUTS")


@pytest.fixture(scope="module", params=["auto", "point"])
def rounded(request):
    """A steady state over rounded corners (their contact points are model settings),
    with ``arc_contact`` as given."""
    model = BearingModel(TapeParameters(), FIRST_ORDER, velocity=4.0, head=ROUNDED,
                         infinitely_wide=True, nx=160, arc_contact=request.param, contact=HARD)
    return solve_steady(model)


def test_a_state_over_rounded_corners_loads_as_saved(rounded, tmp_path):
    assert rounded.model.corner_contacts, "the case has contact points to store"
    back = gyroshell.load(rounded.save(tmp_path / "s.nc"))
    assert back.model.corner_contacts == rounded.model.corner_contacts
    assert back.model.arc_contact == rounded.model.arc_contact
    assert (back.u == rounded.u).all() and back.summary() == rounded.summary()


def test_a_march_over_rounded_corners_loads_as_saved(rounded, tmp_path):
    run = march(rounded, dt=1e-5, steps=2, tension=tension_step(90.0, 100.0),
                progress=False)
    back = gyroshell.load(run.save(tmp_path / "t.nc"))
    assert back.final.model.corner_contacts == rounded.model.corner_contacts
    assert back.final.model.arc_contact == rounded.model.arc_contact
    assert (back.t == run.t).all() and (back.centreline == run.centreline).all()


def test_the_contact_passes_are_part_of_the_newton_record(rounded, tmp_path):
    info = dataclasses.asdict(rounded.info)
    assert info["contact_passes"] >= 1 and 0.0 <= info["contact_move"] <= 1.0
    back = gyroshell.load(rounded.save(tmp_path / "s.nc"))
    assert dataclasses.asdict(back.info) == info


def test_a_record_without_the_contact_passes_loads_with_none_counted(rounded, tmp_path):
    """Files written before the passes were recorded: 0 passes, 0 cells."""
    path = rounded.save(tmp_path / "s.nc")
    with h5py.File(path, "r+") as fh:
        info = json.loads(fh.attrs["info"])
        del info["contact_passes"], info["contact_move"]
        fh.attrs["info"] = json.dumps(info)
    back = gyroshell.load(path)
    assert (back.info.contact_passes, back.info.contact_move) == (0, 0.0)


# ----- a saved head study's bearing setup --------------------------------------------------
@pytest.fixture(scope="module")
def head_study(tmp_path_factory):
    setup = BearingStudy(head=HeadDesign(kind="flat", land_length=1e-3, wrap_in=WRAP,
                                         wrap_out=WRAP, modules=2, module_gap=3e-4),
                         infinitely_wide=True, nx=160)
    study = gyroshell.run_study(vary={"tension": [90.0]}, compute="bearing", velocity=4.0,
                                workers=1, bearing=setup, progress=False)
    return study.save(tmp_path_factory.mktemp("study") / "study.nc")


def _edited(source, tmp_path, change):
    path = tmp_path / "edited.nc"
    path.write_bytes(source.read_bytes())
    with h5py.File(path, "r+") as fh:
        data = json.loads(fh.attrs["bearing"])
        change(data)
        fh.attrs["bearing"] = json.dumps(data)
    return path


def test_a_saved_head_study_loads_with_its_setup(head_study):
    study = gyroshell.load(head_study)
    assert BearingStudy.from_spec(study.bearing).spec() == study.bearing
    assert study.bearing["head"]["modules"] == 2


@pytest.mark.parametrize(("change", "match"), [
    (lambda d: d["head"].update(modules=99), "bearing: modules must be an integer in"),
    (lambda d: d["head"].update(friction=-1.0), "bearing: friction must be"),
    (lambda d: d["head"].update(kind="banana"), "bearing: .*banana"),
    (lambda d: d["head"].update(wings=2), r"bearing: head: unknown key\(s\) wings"),
    (lambda d: d.pop("nx"), r"bearing: the setup: missing key\(s\) nx"),
    (lambda d: d.update(nx="many"), "bearing: nx must be None or an integer"),
    (lambda d: d.update(air={"viscosity": -1}), "bearing: .*viscosity"),
])
def test_a_garbage_bearing_setup_is_refused_naming_the_file(head_study, tmp_path, change,
                                                            match):
    path = _edited(head_study, tmp_path, change)
    with pytest.raises(InputFileError, match=match) as refused:
        gyroshell.load(path)
    message = str(refused.value)
    assert message.startswith(f"{path}: ") and "\n" not in message
