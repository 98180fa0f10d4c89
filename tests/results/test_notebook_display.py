"""Every result kind shows itself in a notebook: a ``repr`` of at most 1,000 characters (the
kind, then the summary's numbers with their units) and an HTML table of its summary."""

from __future__ import annotations

import warnings
from html.parser import HTMLParser

import numpy as np
import pandas as pd
import pytest
from kind_examples import every_example

import gyroshell.kinds
from gyroshell.results import base
from gyroshell.results.tables import Table

gyroshell.kinds.import_kinds()
KINDS = sorted(base.kinds())
EXAMPLES = every_example()
#: Void elements need no end tag; every other tag must be closed, in order.
VOID = {"br", "hr", "img", "meta", "col", "wbr"}
#: "Small": far below the 32 kB a transient used to print.
HTML_LIMIT = 8000


class TableParser(HTMLParser):
    """The rows of the one table of a fragment (cell texts), checking that every tag is
    closed in order."""

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.open: list[str] = []
        self.tables = 0
        self.caption = ""
        self.rows: list[list[str]] = []
        self._cell: list[str] | None = None

    def handle_starttag(self, tag, attrs):
        if tag in VOID:
            return
        self.open.append(tag)
        self.tables += tag == "table"
        if tag == "tr":
            self.rows.append([])
        elif tag in ("td", "th"):
            self._cell = []

    def handle_endtag(self, tag):
        assert self.open and self.open[-1] == tag, (self.open, tag)
        self.open.pop()
        if tag in ("td", "th"):
            self.rows[-1].append("".join(self._cell))
            self._cell = None

    def handle_data(self, data):
        if self._cell is not None:
            self._cell.append(data)
        elif self.open and self.open[-1] == "caption":
            self.caption += data


def parse(fragment: str) -> TableParser:
    parser = TableParser()
    parser.feed(fragment)
    parser.close()
    assert parser.open == [] and parser.tables == 1
    return parser


@pytest.fixture(scope="module", params=KINDS)
def example(request):
    if request.param not in EXAMPLES:
        pytest.fail(f"no example of {request.param!r}")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return EXAMPLES[request.param]()


def test_repr_is_short_and_names_the_kind_and_the_units(example):
    text = repr(example)
    assert len(text) <= base.REPR_LIMIT and "\n" not in text
    assert text.startswith(f"{type(example).__name__}(kind={example.kind!r}")
    assert "array(" not in text  # not the dataclass's repr of every field
    summary = example.summary()
    shown = 0
    for name, value in summary.items():
        unit = example.summary_unit(name)
        if f" {name}=" not in text or unit in (None, "1"):
            continue
        if isinstance(value, int | float) and not isinstance(value, bool):
            entry = text.split(f" {name}=", 1)[1].split(", ")[0].rstrip(")")
            assert entry.endswith(f" {unit}"), (name, entry, unit)
            shown += 1
    with_units = [n for n, v in summary.items() if example.summary_unit(n) not in (None, "1")
                  and isinstance(v, int | float) and not isinstance(v, bool)]
    assert shown >= min(1, len(with_units)), (example.kind, with_units)


def test_repr_html_is_one_small_table_of_the_summary(example):
    fragment = example._repr_html_()
    assert len(fragment) < HTML_LIMIT
    table = parse(fragment)
    assert example.kind in table.caption
    header, *rows = table.rows
    assert header == ["entry", "value", "unit"] and all(len(r) == 3 for r in rows)
    summary = example.summary()
    assert [r[0] for r in rows] == list(summary)
    for name, value, unit in rows:
        assert unit == (example.summary_unit(name) or "")
        if isinstance(summary[name], float) and np.isfinite(summary[name]):
            assert float(value) == pytest.approx(summary[name], rel=1e-5)


def test_the_known_units_of_the_headline_quantities():
    # the units as the package documents them (SI), not looked up in its own table
    expected = {"modes": {"velocity": "m/s", "omega": "rad/s", "frequency": "Hz"},
                "critical": {"critical_speed": "m/s", "string_speed": "m/s"},
                "static": {"max_deflection": "m"},
                "transient": {"dt": "s", "final_time": "s"},
                "sweep": {"velocity_max": "m/s", "omega_min": "rad/s"},
                "bearing": {"minimum_spacing": "m", "central_pressure": "Pa",
                            "contact_force": "N", "tension_rise": "N/m"},
                "bearing_transient": {"end_time": "s"}}
    for kind, units in expected.items():
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            result = EXAMPLES[kind]()
        for name, unit in units.items():
            if kind == "bearing_transient" or (kind == "bearing" and name == "contact_force"):
                wide = (result.final if kind == "bearing_transient" else result).model
                unit = unit + "/m" if unit == "N" and wide.infinitely_wide else unit
            assert result.summary_unit(name) == unit, (kind, name)


def test_text_is_escaped_and_a_long_summary_is_cut():
    odd = Table(pd.DataFrame({"a<b&c": [1.0], "</table>": [2.0]}))
    table = parse(odd._repr_html_())
    assert "a<b&c" in table.rows[-1][1] and "</table>" in table.rows[-1][1]

    class Long(base.Result):  # no kind: not registered
        def summary(self):
            return {f"speed_{k}": float(k) for k in range(500)}

    text = repr(Long())
    assert len(text) <= base.REPR_LIMIT and text.endswith("more)")
    assert len(parse(Long()._repr_html_()).rows) == 501


def test_a_summary_that_fails_still_shows_the_kind():
    class Broken(base.Result):
        kind = "broken"

        def summary(self):
            raise RuntimeError("no data")

    assert repr(Broken()) == "Broken(kind='broken')"
    assert parse(Broken()._repr_html_()).rows == [["entry", "value", "unit"]]
