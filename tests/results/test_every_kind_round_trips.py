"""Every registered result kind saves to NetCDF and loads back bit-exactly.

The kinds come from the registry (gyroshell.results.base), so a new kind is covered as soon
as it registers; its example instance comes from an ``EXAMPLES`` table in one of the
``examples_*.py`` files beside this test, and a kind without one fails here.
"""

from __future__ import annotations

import subprocess
import sys

import pytest
from bit_exact import assert_same
from kind_examples import every_example

import gyroshell
import gyroshell.kinds
from gyroshell.results import base

gyroshell.kinds.import_kinds()
KINDS = sorted(base.kinds())
EXAMPLES = every_example()


@pytest.mark.slow
def test_the_kinds_module_imports_every_kind_the_package_defines():
    code = ("import importlib, pkgutil, gyroshell\n"
            "from gyroshell.results import base\n"
            "for m in pkgutil.walk_packages(gyroshell.__path__, 'gyroshell.'):\n"
            "    if not m.name.endswith('__main__'): importlib.import_module(m.name)\n"
            "print(' '.join(sorted(base.kinds())))")
    every = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                           check=True, timeout=120).stdout.split()
    assert KINDS == every


@pytest.mark.parametrize("kind", KINDS)
def test_kind_has_an_example(kind):
    assert kind in EXAMPLES, f"result kind {kind!r} has no example in tests/results/examples_*.py"


@pytest.mark.slow
@pytest.mark.parametrize("kind", KINDS)
def test_save_and_load_give_the_same_object(kind, tmp_path):
    if kind not in EXAMPLES:
        pytest.fail(f"no example of {kind!r}")
    result = EXAMPLES[kind]()
    assert type(result).kind == kind
    path = result.save(tmp_path / f"{kind}.nc")
    assert_same(result, base.read(path), kind)
    loaded = gyroshell.load(path)  # the same, but a table is given back as its DataFrame
    assert_same(result.to_frame() if kind == "table" else result, loaded, kind)


@pytest.mark.slow
@pytest.mark.parametrize("kind", KINDS)
def test_summary_is_plain_json(kind):
    import json

    if kind not in EXAMPLES:
        pytest.fail(f"no example of {kind!r}")
    summary = EXAMPLES[kind]().summary()
    assert isinstance(summary, dict) and summary
    json.dumps(summary)  # plain numbers and text only: numpy integers or arrays raise here


@pytest.mark.parametrize("kind", KINDS)
def test_plot_draws_on_the_given_axes(kind):
    import matplotlib.pyplot as plt

    if kind not in EXAMPLES:
        pytest.fail(f"no example of {kind!r}")
    import numpy as np

    fig = plt.figure()
    drawn = np.atleast_1d(EXAMPLES[kind]().plot(ax=fig.add_subplot()))  # a Bode: the amplitude
    ax = drawn[0]
    assert ax.figure is fig and (ax.lines or ax.collections or ax.patches or ax.images)


@pytest.mark.slow
@pytest.mark.parametrize("kind", KINDS)
def test_is_table_says_whether_the_kind_gives_a_table(kind, tmp_path):
    """What ``--save x.csv`` is refused by before any work (Result.is_table, known from the
    class) is what the kind's result does: a table or 'not a table'."""
    import pandas as pd

    from gyroshell.core.errors import ParameterError

    if kind not in EXAMPLES:
        pytest.fail(f"no example of {kind!r}")
    result = EXAMPLES[kind]()
    if type(result).is_table():
        assert isinstance(result.to_frame(), pd.DataFrame)
        assert isinstance(gyroshell.load(result.save(tmp_path / "t.csv")), pd.DataFrame)
    else:
        with pytest.raises(ParameterError, match="is not a table"):
            result.save(tmp_path / "t.csv")
        assert not (tmp_path / "t.csv").exists()
