"""Pareto fronts (non-dominated sets) of the objectives over the Monte Carlo cloud.

The non-dominated test is moocore's ``is_nondominated`` (López-Ibáñez et al., moocore; the O(n log n)
dimension sweep of Kung, Luccio & Preparata, J. ACM 22(4), 1975, for two and three objectives). A million
points are handled chunk by chunk: the non-dominated set of a union is the non-dominated set of the union of
the parts' non-dominated sets, so :class:`FrontAccumulator` keeps only the running front (bounded memory).
Objectives to maximise are negated; duplicates of a front point are kept once.
"""

from __future__ import annotations

from itertools import combinations

import moocore
import numpy as np


def nondominated(points: np.ndarray, maximise: tuple[bool, ...] | bool = False) -> np.ndarray:
    """Boolean mask of the rows of ``points`` that no other row dominates (minimisation unless ``maximise``)."""
    points = np.asarray(points, dtype=float)
    if len(points) == 0:
        return np.zeros(0, dtype=bool)
    return np.asarray(moocore.is_nondominated(points, maximise=maximise), dtype=bool)


class FrontAccumulator:
    """The running non-dominated set of objective vectors and their design points, fed chunk by chunk."""

    def __init__(self, n_inputs: int, columns: tuple[int, ...], maximise: tuple[bool, ...]):
        self.columns, self.maximise = columns, maximise
        self.f = np.empty((0, len(columns)))
        self.x = np.empty((0, n_inputs))

    def add(self, f_all: np.ndarray, x: np.ndarray) -> None:
        f = np.concatenate([self.f, f_all[:, self.columns]])
        x = np.concatenate([self.x, x])
        keep = nondominated(f, self.maximise)
        self.f, self.x = f[keep], x[keep]

    def front(self) -> tuple[np.ndarray, np.ndarray]:
        """(objective vectors, design points) of the front, sorted by the first objective."""
        order = np.lexsort(self.f.T[::-1])
        return self.f[order], self.x[order]


def objective_subsets(n_objectives: int) -> list[tuple[int, ...]]:
    """Every pair of objectives, then all of them together (when there are more than two)."""
    subsets: list[tuple[int, ...]] = list(combinations(range(n_objectives), 2))
    if n_objectives > 2:
        subsets.append(tuple(range(n_objectives)))
    return subsets
