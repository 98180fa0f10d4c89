"""Exception types: user error apart from numerical failure.

``ParameterError`` is a ``ValueError``: the caller asked for something outside the model's
domain (a negative thickness, a spacing too coarse, a speed above critical for a static
solve). ``ConvergenceError`` is a ``RuntimeError``: the numerics failed (an eigen-solver that
did not converge, a time march that blew up).
"""

from __future__ import annotations

#: The public classes are shown as ``gyroshell.<Name>`` (their public home) in tracebacks and
#: doctests, as numpy does for its public names; pickling resolves them there too.
PUBLIC_MODULE = "gyroshell"


class ParameterError(ValueError):
    """A parameter is outside its allowed range; the message names it and the range."""


class SupercriticalError(ParameterError):
    """The tape speed is at or above the critical (divergence) speed.

    Attributes
    ----------
    velocity : float
        The requested tape speed, m/s.
    critical_speed : float
        The divergence speed of the discrete model, m/s.
    """

    def __init__(self, message: str, *, velocity: float, critical_speed: float) -> None:
        super().__init__(message)
        self.velocity = velocity
        self.critical_speed = critical_speed


class SingularError(ParameterError):
    """A matrix that must be inverted is exactly singular: the system is at a critical
    point (an eigenvalue λ = 0, or the shift is an eigenvalue)."""


class InputFileError(ParameterError):
    """An input file (a ``--config`` tape, a saved result) that is missing, is a folder, or
    is not what it should be (not UTF-8 text, not NetCDF, truncated, a field out of range);
    the message names the file and what is wrong."""


class MissingFileError(InputFileError, FileNotFoundError):
    """An input file that does not exist (also a ``FileNotFoundError``, as before)."""


class ConvergenceError(RuntimeError):
    """A numerical method failed to converge or a solution blew up."""


for _public in (ParameterError, SupercriticalError, ConvergenceError):
    _public.__module__ = PUBLIC_MODULE
