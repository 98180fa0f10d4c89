"""Rounded corners: the tape's contact point on each arc, found by regridding.

A tape of bending length ℓ = √(D/(T − ρV²)) cannot follow an arc of radius r_c much
shorter than ℓ: it touches it at one point x_c (a point load, w''' jumping there; w, w', w''
continuous), where its slope equals the arc's (tangency), or, flying over it, comes
nearest there. The contact is a node of the grid (:class:`~.model.BearingModel`'s
``corner_contacts``, put on the grid as a break, like a sharp corner, and made the centre
of the corner's geometric refinement: the film's constriction about it). x_c depends on the
solution, so :func:`solve_adapting_contacts` solves with the contacts fixed, moves each to
the point of its arc whose slope is the tape's at its node (:meth:`~.model.BearingModel.
updated_contacts`), regrids there and solves again from the default start (the previous
state interpolated onto the moved nodes, whose 25 nm cells put a fourth difference ∝ Δ⁻⁴
on the interpolation error, led Newton astray: measured, in 1-D, interpolating u), until no
contact moves by more than :data:`CONTACT_TOLERANCE` of the smallest cell next to it.
A large 2-D tape (``coarse_start``) instead solves the grid twice as coarse first, its
contacts adapted there (recursively), starts the passes from those contacts and each pass
from that solution interpolated (as the tape's height w = z₀ + u:
:func:`~.steady.interpolated_state`), and a pass whose contacts stay on their nodes from
the previous pass's state, node for node: on the 12.65 mm tape's default grid 4 + 2
Newton iterations in 2 passes, where the extruded strip's start took over 5 minutes.
Only a rounded arc's contact node may touch it (:attr:`~.model.BearingModel.
contact_floor`); a state cutting into the rest of the arc is refused
(:func:`check_point_contacts`).
The map is a strong contraction: a contact moves by r_c times the change of the tape's
slope, and the tape's curvature w'' near a corner is far below 1/r_c (r_c w'' ~ 1e-3 for
r_c = 5 µm), so two or three passes suffice.
"""

from __future__ import annotations

import numpy as np

from ..core.errors import ConvergenceError

#: A contact has settled when it moves by less than this fraction of the smallest cell
#: next to its node.
CONTACT_TOLERANCE = 1e-2
#: A tape cutting into an arc (away from its contact) by more than this fraction of the
#: roughness σ wraps it: refused.
ARC_TOLERANCE = 0.05
#: Most solve-and-regrid passes.
MAX_CONTACT_PASSES = 8


def arc_contact_hint(model) -> str:
    """The hint that ends the message of a failed solve of ``model``: point contacts
    forced (``arc_contact="point"``) on rounded corners whose arcs ``"auto"`` would have
    wrapped, with what to try; "" otherwise. Spelled as the command line's option, the
    same for ``gyroshell bearing`` and a study's row."""
    from .model import WRAPPED_ARC_BENDING_LENGTHS, wrapped_corners

    if model.arc_contact != "point" or not wrapped_corners(model.head, model.bending_length):
        return ""
    return (f" (--arc-contact point on a rounded corner whose arc r_c theta_c exceeds "
            f"{WRAPPED_ARC_BENDING_LENGTHS:g} bending lengths: the tape may wrap it; try "
            "--arc-contact wrapped or auto)")


def _moved(model, new: tuple[float, ...]) -> float:
    """The largest move of a contact, in units of the smallest cell next to its node."""
    i = model.contact_nodes
    cell = np.minimum(model.x[i] - model.x[i - 1], model.x[i + 1] - model.x[i])
    return float(np.max(np.abs(np.array(new) - np.array(model.corner_contacts)) / cell))


def check_point_contacts(model, u, where: str = "") -> None:
    """Refuse a state u (m) whose tape cuts into an arc away from its contact node by more
    than :data:`ARC_TOLERANCE` σ (the arc's other nodes are free of contact): the tape then
    wraps the arc, which this point-contact model does not solve (``arc_contact="wrapped"``
    does). ``where`` ends the message (e.g. " at t = 1e-05 s")."""
    clearance = model.arc_clearance(u)
    sigma = model.air.roughness
    if clearance < -ARC_TOLERANCE * sigma:
        raise ConvergenceError(
            f"the tape does not touch the rounded corners at one point: it cuts "
            f"{-clearance:.3g} m into an arc (more than {ARC_TOLERANCE:g} of the roughness "
            f"{sigma:g} m){where}, i.e. it wraps the arc, which the tangent-point model "
            "does not solve; use arc_contact='wrapped' (the arc nodes in the contact set) "
            "or a smaller corner_radius")


def solve_adapting_contacts(model, solve, *, z0=None, progress=None, coarse_start=None,
                            **kw):
    """The steady state of ``model`` with its rounded corners' contacts adapted (module
    notes): ``solve(fixed_model, z0=..., progress=..., **kw)`` (``solve_steady``) on each
    pass. The solution's model is the last pass's, its contacts converged; its info counts
    every pass's Newton iterations and records ``contact_passes`` and the last
    ``contact_move`` (in cells).

    ``coarse_start`` (optional, used when ``z0`` is None): a callable taking the model and
    returning None or (contacts, start): the contacts adapted on a coarser grid and a
    callable giving that grid's solution interpolated onto a model's grid
    (``steady.coarse_solution``, ``steady.interpolated_state``). The contacts start the
    passes and the interpolated state each pass's Newton: the coarse grid's
    contacts lie within a fraction of a fine cell of the fine grid's, and Newton from the
    coarse state needs a few iterations where the infinitely wide tape's start (the
    free edges still to come down) needs tens, each a full 2-D factorization.

    Raises
    ------
    ConvergenceError
        If the contacts still move after :data:`MAX_CONTACT_PASSES` passes.
    """
    coarse = coarse_start(model) if coarse_start is not None and z0 is None else None
    current = model.rebuilt(adapt_contacts=False, **(
        {} if coarse is None else {"corner_contacts": coarse[0]}))
    iterations, moves = 0, []
    for passes in range(1, MAX_CONTACT_PASSES + 1):
        if coarse is not None and z0 is None:
            z0 = coarse[1](current)
        sol = solve(current, z0=z0, progress=progress, **kw)
        iterations += sol.info.iterations
        new = current.updated_contacts(sol.u)
        moves.append(_moved(current, new))
        if progress is not None:
            progress(f"rounded corners, pass {passes}: {sol.info.iterations} Newton "
                     f"iterations, contacts move {moves[-1]:.3g} cells")
        if moves[-1] <= CONTACT_TOLERANCE:
            check_point_contacts(current, sol.u)
            sol.info.iterations = iterations
            sol.info.contact_passes = passes
            sol.info.contact_move = moves[-1]
            current.adapt_contacts = model.adapt_contacts
            return sol
        moved = current.rebuilt(corner_contacts=new)
        # a coarse-started pass whose contacts stay on their nodes restarts from its own
        # state node for node (the nodes move by a fraction of a cell; the point loads
        # stay on their nodes); else from the coarse state again, or the default start
        z0 = (np.concatenate([sol.u, sol.p]) if coarse is not None
              and np.array_equal(moved.contact_nodes, current.contact_nodes) else None)
        current = moved
    raise ConvergenceError(
        f"the tape's contact on the rounded corners did not settle in "
        f"{MAX_CONTACT_PASSES} passes (moves {', '.join(f'{m:.3g}' for m in moves)} "
        "cells)")
