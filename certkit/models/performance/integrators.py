"""Numerical integrators of the mission: cruise in weight, climb and descent by the energy method.

Cruise in weight (still air, level flight at constant true airspeed V on one level):
    dx/dW = −V / ḟ(W)  ⇒  x = ∫ SAR(W) dW,   SAR = V/ḟ  (specific air range, m/kg)
with ḟ(W) the fuel flow of the trimmed airplane at weight W. The SAR is tabulated on a weight grid, interpolated
by a cubic spline and integrated exactly by the spline's antiderivative. With constant L/D and TSFC c this is
the Breguet range x = V (L/D) / (c g) · ln(W₀/W₁) (e.g. Anderson, *Aircraft Performance and Design*, 1999,
eq. 5.153), which :func:`breguet_range` evaluates in closed form for the tests.

Climb and descent, energy method (Rutowski; Anderson §6.5; Raymer, *Aircraft Design*, §17.3.6): along a
schedule of (altitude h, true airspeed V) points, the specific energy E = h + V²/(2g) changes at the
specific excess power
    P_s = dE/dt = (T − D) V / (W g)
so that dt = dE / P_s, fuel dm = ḟ dt and distance dx = V dt (flight-path angles are small). The altitude
and the speed change along the schedule are both in E: accelerating at constant altitude (250 → 310 KCAS at
10,000 ft) costs time and fuel like a climb. Each schedule segment is integrated by the trapezoidal rule in E
(on 1/P_s, ḟ/P_s and V/P_s) with the weight at its end predicted and corrected once. The drag is the thrust of
the level-flight trim at the point (L = W; at climb angles of a few degrees cos γ ≈ 1).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np
from scipy.interpolate import CubicSpline

from certkit.units import G0


def breguet_range(speed, lift_to_drag, tsfc, w_start, w_end):
    """Closed-form Breguet range (m): V (L/D) / (c g) · ln(W₀/W₁); ``tsfc`` in kg/(N s)."""
    return (
        speed * lift_to_drag / (tsfc * G0) * np.log(np.asarray(w_start, dtype=float) / np.asarray(w_end, dtype=float))
    )


@dataclass
class LevelCruise:
    """Cruise on one level at true airspeed ``speed``: the SAR spline over ``weights`` (kg, increasing) and its
    antiderivative."""

    speed: float
    weights: np.ndarray
    sar: np.ndarray  # m/kg at each weight

    def __post_init__(self):
        self._spline = CubicSpline(self.weights, self.sar)
        self._integral = self._spline.antiderivative()

    @classmethod
    def from_fuel_flow(cls, speed: float, weights, fuel_flow) -> "LevelCruise":
        w, ff = np.asarray(weights, dtype=float), np.asarray(fuel_flow, dtype=float)
        return cls(speed, w, speed / ff)

    def specific_air_range(self, weight):
        return self._spline(weight)

    def distance(self, w_start, w_end):
        """Still-air distance (m) flown while the weight falls from ``w_start`` to ``w_end`` (kg)."""
        return self._integral(w_start) - self._integral(w_end)

    def time(self, w_start, w_end):
        return self.distance(w_start, w_end) / self.speed

    def weight_after(self, w_start: float, distance: float) -> float:
        """The weight (kg) after flying ``distance`` (m) from ``w_start``: the inverse of :meth:`distance`
        (Newton on the monotonic integral, SAR > 0)."""
        w = w_start - distance / float(self._spline(w_start))
        for _ in range(20):
            err = float(self.distance(w_start, w)) - distance
            w_new = w + err / float(self._spline(w))
            if abs(w_new - w) < 1e-6 * w_start:
                return w_new
            w = w_new
        return w


@dataclass
class PathResult:
    """Cumulative time (s), fuel (kg) and distance (m) at every schedule point (shape (n, K)), and whether the
    point was reached (the excess power kept its sign)."""

    time: np.ndarray
    fuel: np.ndarray
    distance: np.ndarray
    reached: np.ndarray


def fly_path(
    altitude,
    speed,
    w_start,
    required_thrust: Callable[[int, np.ndarray], np.ndarray],
    thrust,
    fuel_flow,
    min_excess_power=None,
) -> PathResult:
    """Energy-method integration along the schedule points ``altitude``, ``speed`` (K,) from ``w_start`` (n,
    kg; every weight flown at once). ``required_thrust(k, W)`` is the level-flight thrust (N, drag) at point k
    for weights W (n,); ``thrust`` (K,) the thrust set along the path (maximum climb, or idle for a descent)
    and ``fuel_flow`` (K,) its fuel flow (kg/s). The path may climb (P_s > 0) or descend (P_s < 0); where the
    excess power has the wrong sign for the energy change, the point and the rest of the path are not reached
    (NaN). ``min_excess_power`` (K,) m/s, climbing only: a point where the specific excess power falls below it is
    not reached either (the airplane does not climb through altitudes above its thrust-limited ceiling)."""
    h = np.asarray(altitude, dtype=float)
    v = np.asarray(speed, dtype=float)
    w = np.array(w_start, dtype=float, ndmin=1)
    n, K = w.size, h.size
    t_cum, f_cum, x_cum = (np.zeros((n, K)) for _ in range(3))
    reached = np.ones((n, K), dtype=bool)
    alive = np.ones(n, dtype=bool)

    def inverse_power(k, weight):
        ps = (thrust[k] - required_thrust(k, weight)) * v[k] / (weight * G0)
        return 1.0 / ps

    for k in range(K - 1):
        de = h[k + 1] - h[k] + (v[k + 1] ** 2 - v[k] ** 2) / (2 * G0)
        if abs(de) < 1e-9:
            t_cum[:, k + 1], f_cum[:, k + 1], x_cum[:, k + 1] = t_cum[:, k], f_cum[:, k], x_cum[:, k]
            reached[:, k + 1] = alive
            continue
        ia = inverse_power(k, w)
        dt = de * ia  # predictor: the weight at the segment's end
        w_end = w - fuel_flow[k] * np.maximum(dt, 0.0)
        ib = inverse_power(k + 1, w_end)
        dt = 0.5 * de * (ia + ib)
        fuel = 0.5 * de * (fuel_flow[k] * ia + fuel_flow[k + 1] * ib)
        dist = 0.5 * de * (v[k] * ia + v[k + 1] * ib)
        ok = (de * ia > 0) & (de * ib > 0) & np.isfinite(dt)
        if min_excess_power is not None:  # 1/P_s at or below 1/P_min (both positive) on the segment's two ends
            ok &= (ia * min_excess_power[k] <= 1.0) & (ib * min_excess_power[k + 1] <= 1.0)
        alive &= ok
        w = np.where(alive, w - fuel, w)
        t_cum[:, k + 1] = np.where(alive, t_cum[:, k] + dt, np.nan)
        f_cum[:, k + 1] = np.where(alive, f_cum[:, k] + fuel, np.nan)
        x_cum[:, k + 1] = np.where(alive, x_cum[:, k] + dist, np.nan)
        reached[:, k + 1] = alive
    return PathResult(t_cum, f_cum, x_cum, reached)


__all__ = ["breguet_range", "LevelCruise", "PathResult", "fly_path"]
