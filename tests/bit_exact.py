"""Deep, bit-exact comparison of results: the yardstick of the round-trip tests."""

from __future__ import annotations

import dataclasses
import functools
import math

import numpy as np

#: Attributes that hold caches or live solver state, not data a result carries (values of
#: ``functools.cached_property`` are caches too: they are computed again on use).
TRANSIENT_ATTRIBUTES = ("_cache", "_factor", "_lu", "_solver", "_asperity_last")


def _arrays_equal(a: np.ndarray, b: np.ndarray, where: str) -> None:
    assert a.shape == b.shape, f"{where}: shape {a.shape} != {b.shape}"
    assert a.dtype == b.dtype, f"{where}: dtype {a.dtype} != {b.dtype}"
    if a.dtype.kind in "fc":
        assert np.array_equal(a, b, equal_nan=True), f"{where}: values differ"
    else:
        assert np.array_equal(a, b), f"{where}: values differ"


def _fields(obj) -> dict:
    if dataclasses.is_dataclass(obj):
        return {f.name: getattr(obj, f.name) for f in dataclasses.fields(obj)}
    state = dict(vars(obj)) if hasattr(obj, "__dict__") else {}
    for name in getattr(type(obj), "__slots__", ()):
        if hasattr(obj, name):
            state[name] = getattr(obj, name)
    cls = type(obj)
    return {k: v for k, v in state.items() if k not in TRANSIENT_ATTRIBUTES
            and not isinstance(getattr(cls, k, None), functools.cached_property)}


def assert_same(a, b, where: str = "result", _seen: set | None = None) -> None:
    """``a`` and ``b`` hold the same data to the last bit: arrays (values, dtype, shape),
    numbers, text, tables, dataclass fields and object attributes, recursively."""
    import pandas as pd
    import scipy.sparse as sp

    seen = set() if _seen is None else _seen
    if id(a) in seen:
        return
    seen.add(id(a))
    if isinstance(a, pd.DataFrame | pd.Series):
        assert type(a) is type(b), f"{where}: {type(a).__name__} != {type(b).__name__}"
        pd.testing.assert_frame_equal(a.to_frame() if isinstance(a, pd.Series) else a,
                                      b.to_frame() if isinstance(b, pd.Series) else b,
                                      check_exact=True, obj=where)
    elif sp.issparse(a):
        assert sp.issparse(b) and a.shape == b.shape, f"{where}: sparse shape differs"
        assert (a != b).nnz == 0, f"{where}: sparse values differ"
    elif isinstance(a, np.ndarray):
        assert isinstance(b, np.ndarray), f"{where}: {type(b).__name__} is not an array"
        _arrays_equal(a, b, where)
    elif isinstance(a, float | complex | np.floating | np.complexfloating):
        assert type(a) is type(b) or np.asarray(a).dtype == np.asarray(b).dtype, \
            f"{where}: {type(a).__name__} != {type(b).__name__}"
        same = a == b or (isinstance(a, float) and math.isnan(a) and math.isnan(b))
        assert same, f"{where}: {a!r} != {b!r}"
    elif isinstance(a, str | bytes | bool | int | np.integer | np.bool_ | type(None)):
        assert a == b, f"{where}: {a!r} != {b!r}"
    elif isinstance(a, dict):
        assert isinstance(b, dict), f"{where}: {type(b).__name__} is not a dict"
        assert sorted(map(str, a)) == sorted(map(str, b)), \
            f"{where}: keys {sorted(map(str, a))} != {sorted(map(str, b))}"
        for key in a:
            assert_same(a[key], b[key], f"{where}[{key!r}]", seen)
    elif isinstance(a, list | tuple):
        assert type(a) is type(b) and len(a) == len(b), f"{where}: sequences differ"
        for k, (x, y) in enumerate(zip(a, b, strict=True)):
            assert_same(x, y, f"{where}[{k}]", seen)
    elif callable(a) and not _fields(a):
        assert a == b or type(a) is type(b), f"{where}: callables differ"
    else:
        assert type(a) is type(b), f"{where}: {type(a).__name__} != {type(b).__name__}"
        fa, fb = _fields(a), _fields(b)
        assert sorted(fa) == sorted(fb), f"{where}: attributes {sorted(fa)} != {sorted(fb)}"
        for name in fa:
            assert_same(fa[name], fb[name], f"{where}.{name}", seen)
