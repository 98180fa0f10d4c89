"""Steady states under a smooth contact law (asperities or a measured compliance curve).

A smooth law p_c(h) acts on every tape node near the head (:meth:`.model.BearingModel.
asperity_force`): no contact set, no wall. Its stiffness −∂p_c/∂h grows like
exp(h²/2σ_s²) as the tape comes down onto its summits, and at a sharp corner the tape's
point load must spread over a zone a few σ_s/α wide (α the angle between tape and head):
from a start far from that state Newton's steps are cut to nothing by its line search.

The solve therefore starts from the hard wall's state on the same grid (the limit
σ_s → 0 of the law, with the wall at σ_s: the tape's shape away from the contact zones is
nearly right) and follows the law scaled by s, s p_c(h), from s = 100 (:data:`LAW_SCALE_STARTS`)
down to s = 1 (:func:`law_continuation`): at large s the law is a stiff wall a few σ_s
above the head, and each stage lowers it by about σ_s √(2 ln(factor)); a stage that fails
is retried with the factor's square root, down to :data:`LAW_MIN_FACTOR`.
"""

from __future__ import annotations

import copy
import math
import time

import numpy as np

from ..core.errors import ConvergenceError
from .model import BearingModel
from .results import BearingSolution, NewtonInfo

#: The law's scales at the first stage, tried in turn: at s the law is a stiff wall about
#: σ_s √(2 ln s) above where it carries the same load at s = 1. Measured (1 mm land,
#: 2°/2°, Table 1 tape, 1-D): from 100, 0.5-4 m/s reached s = 1 in 32-91 iterations; from
#: 1 (the law itself) Newton stagnated at the corners; from 1e8 it failed at 0.5-1 m/s.
LAW_SCALE_STARTS = (1e2, 1e4, 1e8)
#: The ratio between stages' scales ...
LAW_FACTOR = 10.0
#: ... cut to its square root after a failed stage, down to this ratio.
LAW_MIN_FACTOR = 1.05
#: Newton iterations per stage at most, and in all stages together.
STAGE_ITERATIONS = 40
TOTAL_ITERATIONS = 600


class _ScaledLaw:
    """The contact law times s (pressure and derivative)."""

    def __init__(self, law, scale: float) -> None:
        self.law, self.scale = law, scale

    def pressure(self, h):
        p, dp = self.law.pressure(h)
        return self.scale * p, self.scale * dp


def scaled_model(model: BearingModel, scale: float) -> BearingModel:
    """``model`` with its contact law multiplied by ``scale`` (a shallow copy sharing the
    grid, operators and film)."""
    if scale == 1.0:
        return model
    out = copy.copy(model)
    out.contact_law = _ScaledLaw(model.contact_law, scale)
    return out


def hard_wall_start(model: BearingModel, tension, progress, iteration_log) -> np.ndarray:
    """[u, p] of the hard wall at the roughness σ_s on ``model``'s grid (its rounded arcs
    all resolved, as the smooth law needs them): the start of :func:`law_continuation`."""
    from .contact import ContactParameters
    from .steady import interpolated_state, solve_steady

    hard = model.rebuilt(contact=ContactParameters(law="hard",
                                                   roughness=model.contact.roughness),
                         arc_contact="wrapped")
    if progress is not None:
        progress("start: the hard wall at the roughness on the same grid")
    sol = solve_steady(hard, tension=tension, progress=progress,
                       iteration_log=iteration_log)
    if np.array_equal(hard.x, model.x):
        return np.concatenate([sol.u, sol.p]), sol.info
    return interpolated_state(model, sol), sol.info


def law_continuation(model: BearingModel, z0: np.ndarray, *, tension=None,
                     info: NewtonInfo, progress=None, iteration_log=None,
                     scale: float | None = None):
    """Newton along the law's scale s from ``scale`` down to 1, each stage from the last
    state (see the module notes). Returns (z, contact forces, info); raises
    ConvergenceError naming the scale reached and what to try."""
    from .steady import newton

    scale = LAW_SCALE_STARTS[0] if scale is None else scale
    z, s, factor, budget = np.array(z0, dtype=float), scale, LAW_FACTOR, TOTAL_ITERATIONS
    lam = None
    while True:
        stage = scaled_model(model, s)
        if progress is not None:
            progress(f"contact law scaled by {s:.3g}")
        try:
            z1, lam, _, info = newton(stage, z, tension=tension, info=info,
                                      log=iteration_log,
                                      max_iterations=min(STAGE_ITERATIONS, budget))
        except ConvergenceError as exc:
            if s == scale or factor <= LAW_MIN_FACTOR or info.iterations >= budget:
                info.law_scales.clear()
                raise ConvergenceError(
                    f"the smooth contact law was not reached: stopped at the law scaled "
                    f"by {s:.3g} ({exc}); try a finer grid, or contact='hard'") from None
            s = min(s * factor, scale)            # back to the last scale reached
            factor = math.sqrt(factor)
            s = max(s / factor, 1.0)
            continue
        z = z1
        info.law_scales.append(s)
        if s == 1.0:
            return z, lam, info
        s = max(s / factor, 1.0)


def solve_smooth(model: BearingModel, z0, tension, progress, iteration_log
                 ) -> BearingSolution:
    """The steady state under the model's smooth contact law: Newton from ``z0`` if
    given; else (or if that fails) the hard wall's state on the same grid, then the
    continuation in the law's scale."""
    from .steady import check_cavitation, newton

    start = time.perf_counter()
    info = NewtonInfo()
    z = lam = None
    if z0 is not None:
        try:
            z, lam, _, info = newton(model, z0, tension=tension, info=info,
                                     log=iteration_log)
        except ConvergenceError as exc:
            if progress is not None:
                progress(f"{exc}: the hard wall's state, then the law's continuation")
    if z is None:
        z_hard, hard_info = hard_wall_start(model, tension, progress, iteration_log)
        info.iterations += hard_info.iterations
        info.step_norms += hard_info.step_norms
        info.residual_norms += hard_info.residual_norms
        info.contact_nodes += hard_info.contact_nodes
        info.continuation += hard_info.continuation
        info.pseudo_time += hard_info.pseudo_time
        for k, scale in enumerate(LAW_SCALE_STARTS):
            try:
                z, lam, info = law_continuation(model, z_hard, tension=tension, info=info,
                                                progress=progress,
                                                iteration_log=iteration_log, scale=scale)
                break
            except ConvergenceError as exc:
                if k == len(LAW_SCALE_STARTS) - 1 or info.iterations >= TOTAL_ITERATIONS:
                    raise
                if progress is not None:
                    progress(f"{exc}: starting the law's continuation from "
                             f"{LAW_SCALE_STARTS[k + 1]:.3g}")
    info.seconds = time.perf_counter() - start
    check_cavitation(model, z[model.n_u:])
    return BearingSolution(model, z[:model.n_u], z[model.n_u:], lam, info)
