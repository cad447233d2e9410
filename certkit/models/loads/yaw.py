"""The yaw manoeuvre (§25.351) as a batched rigid-airplane simulation with the roll held by the aileron.

Phase 1: from the trimmed state the rudder is ramped (``ramp`` s, "suddenly") by ``amplitude`` (per
condition) and held; the ailerons alone hold the wings level (:class:`RollHold`). Each condition is frozen
once its sideslip has settled: over the last ``window`` seconds β stays within ``tolerance`` × |β| of its
current value (after its first peak), or at ``t_max``. Phase 2 starts from each condition's settled state:
the rudder is ramped back to its trim position and the response recorded for ``return_time`` s.

The instants the loads rule needs (rudder fully applied, overswing peak of |β|, settled state, and the
return) are returned with the time histories; the regulation's numbers (speeds, pedal forces) belong to
the rule.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from certkit.models.dynamics import pilot_kernel
from certkit.models.dynamics.controlled_run import KernelBlock, columns
from certkit.models.dynamics.eom import quat_to_euler
from certkit.models.dynamics.simulate import Controller, Ramp, simulate, stop_when


class RollHold(Controller):
    """Aileron-only wings-level hold: δa = δa0 + K_φ φ + K_i ∫φ dt + K_p p, clipped (positive δa gives a
    negative rolling moment, :mod:`certkit.conventions`); the integral removes the steady bank the
    proportional hold would leave in a steady sideslip. The rudder is left to the schedules."""

    def __init__(
        self,
        model,
        u0,
        k_phi: float = 2.0,
        k_p: float = 1.0,
        k_i: float = 1.0,
        aileron: str = "aileron",
        limits=(-np.radians(25), np.radians(25)),
        integral=None,
    ):
        self.j = model.control_index(aileron)
        self.da0 = np.asarray(u0, dtype=float)[:, self.j].copy()
        self.k_phi, self.k_p, self.k_i, self.limits = k_phi, k_p, k_i, limits
        self.integral = np.zeros(model.n) if integral is None else np.asarray(integral, dtype=float).copy()

    def update(self, t, x, out, u, dt):
        phi = quat_to_euler(x[:, 9:13])[:, 0]
        self.integral += phi * dt
        u[:, self.j] = np.clip(
            self.da0 + self.k_phi * phi + self.k_i * self.integral + self.k_p * x[:, 6], *self.limits
        )
        return u

    def kernel_block(self) -> KernelBlock:
        """This law for a compiled run (:mod:`certkit.models.dynamics.controlled_run`)."""
        n = self.da0.shape[0]

        def restore(s):
            self.integral = s[:, 0].copy()

        consts = np.array([self.k_phi, self.k_p, self.k_i, self.limits[0], self.limits[1]], dtype=float)
        state = columns(n, self.integral)
        return KernelBlock(
            "lateral", pilot_kernel.ROLL_HOLD, consts, columns(n, self.da0), state, restore, self, (self.j, -1, -1)
        )


class SideslipSettled:
    """Stateful stop criterion: β within ``tolerance`` × |β| over the last ``window`` s, after its peak."""

    def __init__(self, n: int, dt: float, window: float, tolerance: float, t_min: float):
        self.buf = np.full((max(int(round(window / dt)), 2), n), np.nan)
        self.k = 0
        self.tol, self.t_min = tolerance, t_min
        self.peak = np.zeros(n)
        self.__name__ = f"sideslip settled within {100 * tolerance:g} %"

    def __call__(self, t, x, out):
        b = out.beta
        self.buf[self.k % self.buf.shape[0]] = b
        self.k += 1
        self.peak = np.maximum(self.peak, np.abs(b))
        if self.k < self.buf.shape[0] or t < self.t_min:
            return np.zeros(b.shape, dtype=bool)
        band = np.nanmax(np.abs(self.buf - b[None, :]), axis=0)
        return (band <= self.tol * np.abs(b)) & (np.abs(b) < self.peak)

    def kernel_block(self) -> KernelBlock | None:
        """This criterion for a compiled run (:mod:`certkit.models.dynamics.controlled_run`), before its first use."""
        if self.k != 0:
            return None
        m, n = self.buf.shape

        def restore(s):
            self.buf[:] = s[:, :m].T
            self.peak = s[:, m].copy()
            self.k = int(s[0, m + 1]) if n else 0

        state = np.column_stack([self.buf.T, self.peak, np.zeros(n)])
        consts = np.array([m, self.tol, self.t_min], dtype=float)
        return KernelBlock("stop", pilot_kernel.SIDESLIP_SETTLED, consts, np.zeros((n, 1)), state, restore, self)


@dataclass
class YawRun:
    held: object  # SimulationResult of phase 1 (rudder applied and held)
    returned: object  # SimulationResult of phase 2 (rudder returned to neutral)
    t_full: float  # rudder fully applied
    t_overswing: np.ndarray  # (n,) time of the |β| peak in phase 1
    t_steady: np.ndarray  # (n,) end of phase 1 (settled or t_max)
    settled: np.ndarray  # (n,) bool
    beta_band: np.ndarray  # (n,) residual |β| variation over the last window (rad)
    u_steady: np.ndarray  # (n, m) controls at the end of phase 1


def simulate_yaw(
    model,
    x0,
    u0,
    amplitude,
    dt: float = 0.02,
    ramp: float = 0.2,
    t_max: float = 20.0,
    window: float = 4.0,
    tolerance: float = 0.02,
    return_time: float = 3.0,
    rudder: str = "rudder",
    aileron_limits=(-np.radians(25), np.radians(25)),
) -> YawRun:
    n = x0.shape[0]
    amplitude = np.broadcast_to(np.asarray(amplitude, dtype=float), (n,)).copy()
    jr = model.control_index(rudder)
    settle = SideslipSettled(n, dt, window, tolerance, t_min=ramp + window)
    roll = RollHold(model, u0, limits=aileron_limits)
    held = simulate(
        model,
        x0,
        u0,
        t_max,
        dt,
        inputs={rudder: Ramp(0.0, ramp, amplitude)},
        controllers=[roll],
        stop=[stop_when(settle.__name__, settle)],
    )
    beta = held["beta"]
    live = held.t[:, None] <= held.stop_time[None, :] + 1e-9
    t_over = held.t[np.argmax(np.where(live, np.abs(beta), -1.0), axis=0)]
    k_end = np.minimum(np.searchsorted(held.t, held.stop_time - 1e-9), len(held.t) - 1)
    win = live & (held.t[:, None] >= held.stop_time[None, :] - window - 1e-9)
    b_end = beta[k_end, np.arange(n)]
    band = np.nanmax(np.where(win, np.abs(beta - b_end[None, :]), np.nan), axis=0)
    u_end = held.controls[k_end, np.arange(n)].copy()
    # phase 2: rudder back to its trim position from the settled state, roll still held
    u2 = u_end.copy()
    back = -(u_end[:, jr] - np.asarray(u0)[:, jr])
    roll2 = RollHold(model, u0, limits=aileron_limits, integral=roll.integral)
    returned = simulate(
        model, held.final_state, u2, return_time, dt, inputs={rudder: Ramp(0.0, ramp, back)}, controllers=[roll2]
    )
    return YawRun(
        held, returned, ramp, t_over, held.stop_time.copy(), np.array([r != "" for r in held.stop_reason]), band, u_end
    )


#: the instants and the interval of a yaw run whose loads are read (:func:`yaw_phase_loads`)
YAW_PHASES = ("full", "overswing", "steady", "returned")


def yaw_phase_loads(run: YawRun, held, returned) -> tuple[dict, dict]:
    """The loads of a yaw run at its instants and over its return: ``held`` and ``returned`` are the loads
    ((n_t, n, 3, S)) along ``run.held`` and ``run.returned``. "full" (rudder fully applied), "overswing" (the |β|
    peak) and "steady" (end of the held phase) are the loads at that instant as a (min, max) pair of equal values;
    "returned" is the envelope over the rudder's return. Returns (peaks: phase → (n, 2, 3, S), times: phase →
    (n, 2, 3, S) s from the rudder input)."""
    n = held.shape[1]
    cols, t = np.arange(n), run.held.t

    def at(times):
        k = np.minimum(np.searchsorted(t, np.asarray(times) - 1e-9), len(t) - 1)
        return held[k, cols]  # (n, 3, S)

    peaks, times = {}, {}
    for phase, when in (("full", np.full(n, run.t_full)), ("overswing", run.t_overswing), ("steady", run.t_steady)):
        loads = at(when)
        peaks[phase] = np.stack([loads, loads], axis=1)
        times[phase] = np.broadcast_to(when[:, None, None, None], peaks[phase].shape).copy()
    lo, hi = np.nanmin(returned, axis=0), np.nanmax(returned, axis=0)
    t_lo = run.returned.t[np.nanargmin(returned, axis=0)] + run.t_steady[:, None, None]
    t_hi = run.returned.t[np.nanargmax(returned, axis=0)] + run.t_steady[:, None, None]
    peaks["returned"], times["returned"] = np.stack([lo, hi], axis=1), np.stack([t_lo, t_hi], axis=1)
    return peaks, times
