"""The peak of a sampled time history between its samples.

A simulated record holds the response at the integration steps only; its greatest sample misses a sharp peak by up
to ½ |y''| (Δt/2)² and, as the peak slides across the time grid with the inputs, that error moves in a saw-tooth —
a search that aims the peak at a load factor then sees a response that is not monotone in its input. Near the stall
line the peak load factor is sharp (the lift curve's maximum) and nearly flat in the input, so that saw-tooth is
larger than the change it searches for.

The peak is read from the local cubic interpolant instead: on each side of the greatest sample, the cubic through the
four samples around that interval (Lagrange; the interpolant passes through every sample and is continuous), its
maximum found on a fine grid between the greatest sample's neighbours. Where the window leaves fewer samples, the
parabola through the greatest sample and its neighbours, or that sample itself at the window's edge.
"""

from __future__ import annotations

import numpy as np

_GRID = np.linspace(0.0, 1.0, 41)[1:]  # fractions of a step from the greatest sample (every 1/40 step)


def _lagrange(nodes: tuple[float, ...], s: np.ndarray) -> np.ndarray:
    """Lagrange basis weights (len(nodes), len(s)) of the polynomial through ``nodes`` (in steps) at ``s``."""
    w = []
    for i, a in enumerate(nodes):
        term = np.ones_like(s)
        for j, b in enumerate(nodes):
            if j != i:
                term = term * (s - b) / (a - b)
        w.append(term)
    return np.array(w)


_LEFT = _lagrange((-2.0, -1.0, 0.0, 1.0), -_GRID)  # s in [−1, 0): the cubic through samples k−2 … k+1
_RIGHT = _lagrange((-1.0, 0.0, 1.0, 2.0), _GRID)  # s in (0, 1]: the cubic through samples k−1 … k+2


def peak_between_samples(y: np.ndarray, valid: np.ndarray) -> np.ndarray:
    """Per column of ``y`` (T, n): the greatest value over the samples where ``valid`` (T, n), read between the
    samples (module docstring); −inf for a column with no valid sample."""
    masked = np.where(valid, y, -np.inf)
    k = masked.argmax(axis=0)
    cols = np.arange(y.shape[1])
    peak = masked[k, cols]
    T = y.shape[0]

    def sample(offset: int) -> tuple[np.ndarray, np.ndarray]:
        i = k + offset
        inside = (i >= 0) & (i < T)
        j = np.clip(i, 0, T - 1)
        return y[j, cols], inside & valid[j, cols]

    (y_m2, v_m2), (y_m1, v_m1), (y_p1, v_p1), (y_p2, v_p2) = (sample(o) for o in (-2, -1, 1, 2))
    y_0 = y[k, cols]
    three = v_m1 & v_p1 & np.isfinite(peak)
    five = three & v_m2 & v_p2
    curvature = y_m1 - 2.0 * y_0 + y_p1
    bowed = three & (curvature < 0.0)
    offset = 0.5 * (y_m1 - y_p1) / np.where(bowed, curvature, -1.0)  # within ±½ step for the greatest of three
    parabola = np.where(bowed, y_0 - 0.25 * (y_m1 - y_p1) * offset, peak)
    left = _LEFT.T @ np.array([y_m2, y_m1, y_0, y_p1])  # (grid, n)
    right = _RIGHT.T @ np.array([y_m1, y_0, y_p1, y_p2])
    cubic = np.maximum(y_0, np.maximum(left.max(axis=0), right.max(axis=0)))
    return np.where(five, cubic, parabola)
