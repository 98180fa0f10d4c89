"""The head–tape air bearing: the tape flying over a cylindrical head on its own air film.

A film module (:mod:`.film`, finite-volume Reynolds with slip, compressible or not) and a
coupling engine (:mod:`.model`, :mod:`.steady`, :mod:`.transient`) over the tape's shell
operators (:mod:`gyroshell.tape.operators`): steady flying states by Newton's method with
contact, and strongly coupled transients by Newmark's method. The results
(:mod:`.results`) follow the result protocol of :mod:`gyroshell.results.base`; plots in
:mod:`.plots`.
"""

from __future__ import annotations

import importlib

#: public name -> submodule; imported on first use so that registering the ``bearing``
#: sub-command (which reads the air defaults) does not load scipy for ``gyroshell --help``.
_LAZY = {
    "AirParameters": "air", "check_wrap_angle": "geometry", "BearingModel": "model",
    "BearingSolution": "results", "NewtonInfo": "results", "solve_steady": "steady",
    "BearingTransient": "results", "march": "transient", "tension_harmonic": "transient",
    "tension_step": "transient", "Grading": "mesh", "save": "storage", "load": "storage",
    "Cylinder": "head", "FlatHead": "head", "Module": "head", "ProfileHead": "head",
    "head_from_dict": "head",
}

__all__ = sorted(_LAZY)


def __getattr__(name: str):
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(f".{module}", __name__), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))
