"""The head–tape air bearing: the tape flying over a cylindrical head on its own air film.

A film module (:mod:`.film`, finite-volume Reynolds with slip, compressible or not) and a
coupling engine (:mod:`.model`, :mod:`.steady`, :mod:`.transient`) over the tape's shell
operators (:mod:`gyroshell.operators`): steady flying states by Newton's method with
contact, and strongly coupled transients by Newmark's method. Plots in :mod:`.plots`.
"""

from __future__ import annotations

from .air import AirParameters
from .geometry import check_wrap_angle
from .model import BearingModel
from .steady import BearingSolution, NewtonInfo, solve_steady
from .transient import BearingTransient, march, tension_harmonic, tension_step

__all__ = ["AirParameters", "BearingModel", "BearingSolution", "BearingTransient",
           "NewtonInfo", "check_wrap_angle", "march", "solve_steady", "tension_harmonic",
           "tension_step"]
