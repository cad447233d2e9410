"""Interpolating cubic spline with not-a-knot ends, in numpy (the camber-line slopes of the lattice).

The spline scipy's ``CubicSpline`` builds by default (de Boor, *A Practical Guide to Splines*, 1978, ch. IV: the
third derivative continuous at the second and last-but-one knots), written out so that the lattice needs no
scipy.interpolate (its import costs more than a short ``certkit derivatives`` run): the knot slopes s solve the
tridiagonal system of C² continuity
    Δx_i s_{i−1} + 2 (Δx_{i−1} + Δx_i) s_i + Δx_{i−1} s_{i+1} = 3 (Δx_i m_{i−1} + Δx_{i−1} m_i),   m_i = Δy_i/Δx_i,
closed by the not-a-knot rows, and each interval is the cubic Hermite polynomial of its end values and slopes.
Agrees with scipy's to round-off (tests/aero/test_cubic_spline.py).
"""

from __future__ import annotations

import numpy as np


class NotAKnotSpline:
    """Cubic spline through (x, y), x increasing; fewer than four points: the polynomial through them."""

    def __init__(self, x, y):
        x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
        n = x.size
        if n < 2 or np.any(np.diff(x) <= 0):
            raise ValueError("spline knots must increase (at least two)")
        dx, slope = np.diff(x), np.diff(y) / np.diff(x)
        if n == 2:
            s = np.array([slope[0], slope[0]])
        elif n == 3:  # not-a-knot on three points: the parabola
            a = (slope[1] - slope[0]) / (x[2] - x[0])
            s = np.array([slope[0] - a * dx[0], slope[0] + a * dx[0], slope[1] + a * dx[1]])
        else:
            lower, diag, upper, b = np.zeros(n), np.empty(n), np.zeros(n), np.empty(n)
            lower[1:-1], diag[1:-1], upper[1:-1] = dx[1:], 2.0 * (dx[:-1] + dx[1:]), dx[:-1]
            b[1:-1] = 3.0 * (dx[1:] * slope[:-1] + dx[:-1] * slope[1:])
            d = x[2] - x[0]
            diag[0], upper[0] = dx[1], d
            b[0] = ((dx[0] + 2.0 * d) * dx[1] * slope[0] + dx[0] ** 2 * slope[1]) / d
            d = x[-1] - x[-3]
            diag[-1], lower[-1] = dx[-2], d
            b[-1] = (dx[-1] ** 2 * slope[-2] + (2.0 * d + dx[-1]) * dx[-2] * slope[-1]) / d
            s = _tridiagonal(lower, diag, upper, b)
        t = (s[:-1] + s[1:] - 2.0 * slope) / dx
        self.x = x
        self.c = np.stack([t / dx, (slope - s[:-1]) / dx - t, s[:-1], y[:-1]])  # power form per interval

    def _interval(self, xq):
        xq = np.asarray(xq, dtype=float)
        i = np.clip(np.searchsorted(self.x, xq, side="right") - 1, 0, self.x.size - 2)
        return i, xq - self.x[i]

    def __call__(self, xq):
        i, h = self._interval(xq)
        c = self.c[:, i]
        return ((c[0] * h + c[1]) * h + c[2]) * h + c[3]

    def derivative(self, xq):
        """dy/dx at ``xq`` (the end intervals' polynomials beyond the knots), summed in the order scipy's piecewise
        polynomials use: c2 + 2 c1 h + 3 c0 h²."""
        i, h = self._interval(xq)
        c = self.c[:, i]
        return (c[2] + c[1] * h * 2.0) + c[0] * (h * h) * 3.0


def _tridiagonal(lower, diag, upper, rhs) -> np.ndarray:
    """Solve the tridiagonal system (row i: lower_i x_{i−1} + diag_i x_i + upper_i x_{i+1} = rhs_i) by Gaussian
    elimination with partial pivoting, step for step as LAPACK's dgtsv (the routine scipy's banded solver calls for
    such a system, so the slopes come out the same): a loop over the knots, cheaper for a camber line's ~100 points
    than a LAPACK call through a threaded BLAS."""
    n = diag.size
    d, du, b = diag.astype(float).copy(), upper[:-1].astype(float).copy(), rhs.astype(float).copy()
    dl = lower[1:].astype(float).copy()  # dl[i]: row i + 1, column i
    du2 = np.zeros(max(n - 2, 0))
    for i in range(n - 1):
        if abs(d[i]) >= abs(dl[i]):  # no interchange
            if d[i] == 0.0:
                raise np.linalg.LinAlgError("singular spline system")
            fact = dl[i] / d[i]
            d[i + 1] = d[i + 1] - fact * du[i]
            b[i + 1] = b[i + 1] - fact * b[i]
        else:  # interchange rows i and i + 1
            fact = d[i] / dl[i]
            d[i] = dl[i]
            temp = d[i + 1]
            d[i + 1] = du[i] - fact * temp
            if i < n - 2:
                du2[i] = du[i + 1]
                du[i + 1] = -fact * du2[i]
            du[i] = temp
            temp = b[i]
            b[i] = b[i + 1]
            b[i + 1] = temp - fact * b[i + 1]
    if d[-1] == 0.0:
        raise np.linalg.LinAlgError("singular spline system")
    b[-1] = b[-1] / d[-1]
    if n > 1:
        b[-2] = (b[-2] - du[-1] * b[-1]) / d[-2]
    for i in range(n - 3, -1, -1):
        b[i] = (b[i] - du[i] * b[i + 1] - du2[i] * b[i + 2]) / d[i]
    return b
