"""The one branch tracker of sweeps and Campbell diagrams: modes matched across speeds.

At each speed the modes are matched to the previous speed's by a similarity of their shapes
(the sweep's mass-weighted correlation, the Campbell diagram's MAC), with the assignment
that maximizes the total similarity (Hungarian algorithm). A match at least as similar as
the threshold continues the branch; a mode left unmatched or matched more weakly (it
entered the lowest-``count`` window) starts a new branch.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Match:
    """The branches of one speed's modes.

    Attributes
    ----------
    labels : list of int
        Branch label of each mode (column of the speed's vectors).
    similarity : numpy.ndarray
        Similarity with the previous speed's mode it was assigned to; NaN where none was.
    assigned : numpy.ndarray of bool
        Whether the mode was assigned a previous mode (at any similarity).
    continued : numpy.ndarray of bool
        Whether that assignment continues a branch (similarity >= the threshold).
    """

    labels: list[int]
    similarity: np.ndarray
    assigned: np.ndarray
    continued: np.ndarray


class BranchTracker:
    """Labels each speed's modes by their similarity with the previous speed's.

    Parameters
    ----------
    similarity : callable
        ``similarity(previous, vectors)``: the (p, q) matrix between the columns of the
        previous speed's vectors (n, p) and this speed's (n, q), in [0, 1].
    threshold : float
        Smallest similarity that continues a branch.
    """

    def __init__(self, similarity: Callable[[np.ndarray, np.ndarray], np.ndarray],
                 threshold: float) -> None:
        self.similarity, self.threshold = similarity, threshold
        self.previous: np.ndarray | None = None
        self.labels: list[int] = []
        self.next_label = 0

    def match(self, vectors: np.ndarray) -> Match:
        """The branches of the modes ``vectors`` (n, k), the next speed after the last."""
        k = vectors.shape[1]
        labels = [-1] * k
        similarity = np.full(k, np.nan)
        assigned, continued = np.zeros(k, dtype=bool), np.zeros(k, dtype=bool)
        if self.previous is not None:
            c = self.similarity(self.previous, vectors)
            for i, j in zip(*_assignment(-c), strict=True):
                similarity[j], assigned[j] = c[i, j], True
                if c[i, j] >= self.threshold:
                    labels[j], continued[j] = self.labels[i], True
        for j in range(k):
            if labels[j] < 0:  # a mode that entered the window: a new branch
                labels[j], self.next_label = self.next_label, self.next_label + 1
        self.previous, self.labels = vectors, labels
        return Match(labels, similarity, assigned, continued)


def track(results, tracker: BranchTracker) -> list[Match]:
    """The matches of consecutive speeds' :class:`~gyroshell.Modes`, in order."""
    return [tracker.match(res.vectors) for res in results]


def _assignment(cost: np.ndarray):
    """The optimal assignment (Hungarian method) of a cost matrix: scipy is imported here,
    not with the module, so that the CLI refuses bad options before loading it."""
    from scipy.optimize import linear_sum_assignment

    return linear_sum_assignment(cost)
