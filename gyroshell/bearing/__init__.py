"""The head–tape air bearing: the tape flying over a cylindrical head on its own air film.

A film module (:mod:`.film`, finite-volume Reynolds with slip, compressible or not) and a
coupling engine (:mod:`.model`, :mod:`.steady`, :mod:`.transient`) over the tape's shell
operators (:mod:`gyroshell.operators`): steady flying states by Newton's method with
contact, and strongly coupled transients by Newmark's method.
"""

from __future__ import annotations

from .air import AirParameters
from .geometry import check_wrap_angle
from .model import BearingModel

__all__ = ["AirParameters", "BearingModel", "check_wrap_angle"]
