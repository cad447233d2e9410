"""Minimum unstick speed VMU: the lowest speed at which the airplane can lift off and fly (§25.107(d)).

§25.107(d) defines VMU as "the calibrated airspeed at and above which the airplane can safely lift off the ground,
and continue the takeoff", to be found "throughout the range of thrust-to-weight ratios" and allowed "from free air
data if these data are verified by ground takeoff tests". In the flight test the airplane is rotated early and held
at the highest attitude it can reach — on a geometry-limited airplane the tail on the runway (EASA AMC 25.107(e)(1)(iv):
the aft under-surface in contact over 96–100 % of the lift-off speed) — and the speed at which it leaves the runway is
VMU. Here the same, quasi-statically, with the airplane model of the batch (its ground effect included):

* at a pitch attitude θ on a level runway, with the flight path along the runway (α = θ, β = 0, no rates), the CG at
  the height at which the lowest gear contact point just touches (no gear load: the airplane is at the point of
  lift-off), the throttles and the other controls as given (takeoff thrust; the stabiliser at its takeoff setting);
* the elevator that makes the pitching acceleration zero (secant iteration) — clipped to its limits; an attitude
  whose balance needs more nose-up elevator than the stop cannot be held by the aerodynamic controls and is flagged;
* the unstick speed at θ: the true airspeed at which the vertical acceleration is zero (lift, thrust and weight
  balance; bisection — the vertical force grows with the speed);
* VMU: the least unstick speed over the attitudes up to ``theta_max`` (the tail-strike attitude) that the elevator
  can hold and whose lift coefficient stays within ``cl_max`` (the free-air trimmed C_Lmax of the configuration: the
  model's ground effect multiplies the whole lift and does not lower the stall angle near the ground, so a lift
  coefficient beyond the free-air maximum is not credited: the conservative side). It is *geometry-limited* when that
  least speed is the one at ``theta_max`` (the tail would touch before the lift stops growing), *lift-limited* when it
  lies at a lower attitude (the lift maximum is reached first), *elevator-limited* when the elevator cannot hold the
  attitudes above it.

The speed is the dynamic-pressure balance of a steady lift-off: the pitch rate and the vertical speed of a real
lift-off, and the strut extension during the rotation, are not in it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from certkit.models.dynamics.eom import AircraftModel
from certkit.models.dynamics.ground import gear_heights

#: speed bracket of the bisection (m/s TAS)
SPEED_RANGE = (20.0, 150.0)
#: a lower attitude's unstick speed must undercut the highest attitude's by this much (m/s) to call it lift-limited
FLAT = 0.05


@dataclass(frozen=True)
class Unstick:
    """The minimum unstick speed of each condition of the batch."""

    speed: np.ndarray  # m/s TAS (nan where no attitude up to theta_max can be held)
    attitude: np.ndarray  # rad, the attitude it is reached at
    elevator: np.ndarray  # rad, the elevator that holds it
    lift_coefficient: np.ndarray  # CL at that point
    limited_by: tuple[str, ...]  # "attitude limit" (geometry) | "lift maximum" | "elevator" | "none"
    attitudes: np.ndarray  # (k,) rad, the attitudes searched (highest first)
    speeds: np.ndarray  # (k, n) m/s TAS, the unstick speed at each attitude (nan where the elevator cannot hold it
    # or the lift coefficient would exceed C_Lmax)

    @property
    def geometry_limited(self) -> np.ndarray:
        return np.array([s == "attitude limit" for s in self.limited_by])

    def take(self, rows: slice) -> "Unstick":
        """The conditions ``rows`` of the batch."""
        return Unstick(
            speed=self.speed[rows],
            attitude=self.attitude[rows],
            elevator=self.elevator[rows],
            lift_coefficient=self.lift_coefficient[rows],
            limited_by=self.limited_by[rows],
            attitudes=self.attitudes,
            speeds=self.speeds[:, rows],
        )


def _liftoff_states(model: AircraftModel, rows: np.ndarray, theta: np.ndarray, V) -> np.ndarray:
    """Euler states (m, 12) at attitude θ on a level runway, velocity along it, the lowest gear point touching."""
    x = np.zeros((rows.size, 12))
    x[:, 10] = theta
    x[:, 3] = V * np.cos(theta)
    x[:, 5] = V * np.sin(theta)
    x[:, 2] = 1e-3 - gear_heights(model, x, rows).min(axis=1)  # lowest contact 1 mm above the runway
    return x


def _balance(model, rows, theta, V, u, j, limits, iterations: int = 4):
    """Vertical acceleration (m/s², up), the elevator balancing the pitch (clipped) and whether it had to be clipped,
    and the outputs, at speed V (m)."""
    x = _liftoff_states(model, rows, theta, V)
    u = u.copy()
    d_prev, d = np.full(rows.size, -0.1), np.zeros(rows.size)
    u[:, j] = d_prev
    q_prev = model.derivatives_euler(x, u, rows=rows)[:, 7]
    u[:, j] = d
    q = model.derivatives_euler(x, u, rows=rows)[:, 7]
    for _ in range(iterations):
        slope = (q - q_prev) / np.where(d != d_prev, d - d_prev, 1.0)
        d_new = d - q / np.where(slope != 0.0, slope, -1.0)
        d_prev, q_prev, d = d, q, d_new
        u[:, j] = d
        q = model.derivatives_euler(x, u, rows=rows)[:, 7]
    lo, hi = limits
    clipped = (d < lo) | (d > hi)
    u[:, j] = np.clip(d, lo, hi)
    xd, out = model.derivatives_euler(x, u, with_outputs=True, rows=rows)
    vertical = np.sin(theta) * xd[:, 3] - np.cos(theta) * xd[:, 5]
    return vertical, u[:, j], clipped, out


def unstick_speeds(model: AircraftModel, controls, attitudes, limits, elevator: str = "elevator", iterations=36):
    """Unstick speed (m/s TAS, (k, n)), elevator and clipped flags at each attitude of ``attitudes`` (k,) for each
    condition of the batch (module docstring); ``controls`` (n, n_controls) hold everything but the elevator."""
    if model.ground is None:
        raise ValueError("the unstick speed needs a model with a ground model (the gear's contact points)")
    attitudes = np.asarray(attitudes, dtype=float)
    k, n = attitudes.size, model.n
    rows = np.tile(np.arange(n), k)
    theta = np.repeat(attitudes, n)
    u = np.asarray(controls, dtype=float)[rows]
    j = model.control_index(elevator)
    lo, hi = np.full(rows.size, SPEED_RANGE[0]), np.full(rows.size, SPEED_RANGE[1])
    for _ in range(iterations):
        mid = 0.5 * (lo + hi)
        up = _balance(model, rows, theta, mid, u, j, limits)[0] >= 0.0
        hi, lo = np.where(up, mid, hi), np.where(up, lo, mid)
    _, de, clipped, out = _balance(model, rows, theta, hi, u, j, limits)
    never = _balance(model, rows, theta, np.full(rows.size, SPEED_RANGE[1]), u, j, limits)[0] < 0.0
    speed = np.where(never, np.nan, hi)
    shape = (k, n)
    return speed.reshape(shape), de.reshape(shape), clipped.reshape(shape), out.CL.reshape(shape)


def minimum_unstick_speed(
    model: AircraftModel,
    controls,
    theta_max,
    limits,
    cl_max=np.inf,
    elevator: str = "elevator",
    step: float = np.radians(0.25),
    span: float = np.radians(8.0),
) -> Unstick:
    """VMU of each condition of the batch over the attitudes from ``theta_max`` (rad; the tail-strike attitude)
    down by ``span`` in steps of ``step``, the lift coefficient at most ``cl_max`` (module docstring)."""
    attitudes = theta_max - np.arange(0.0, span + 0.5 * step, step)
    V, de, clipped, cl = unstick_speeds(model, controls, attitudes, limits, elevator)
    beyond_lift = cl > cl_max
    held = ~clipped & ~beyond_lift & np.isfinite(V)
    Vh = np.where(held, V, np.inf)
    best = np.argmin(Vh, axis=0)
    cols = np.arange(model.n)
    found = np.isfinite(Vh[best, cols])
    limited = []
    for i in range(model.n):
        if not found[i]:
            limited.append("none")
        elif beyond_lift[0, i]:
            limited.append("lift maximum")
        elif not held[0, i]:
            limited.append("elevator")
        elif best[i] > 0 and Vh[0, i] - Vh[best[i], i] > FLAT:
            limited.append("lift maximum")
        else:
            limited.append("attitude limit")
    top = np.where(np.array(limited) == "attitude limit", 0, best)  # within FLAT of the top: the limit attitude's
    return Unstick(
        speed=np.where(found, Vh[top, cols], np.nan),
        attitude=np.where(found, attitudes[top], np.nan),
        elevator=np.where(found, de[top, cols], np.nan),
        lift_coefficient=np.where(found, cl[top, cols], np.nan),
        limited_by=tuple(limited),
        attitudes=attitudes,
        speeds=np.where(held, V, np.nan),
    )


__all__ = ["Unstick", "minimum_unstick_speed", "unstick_speeds"]
