"""Rolling manoeuvres (§25.349(a)) as a batched rigid-airplane simulation, and the mirror image of a response.

:func:`symmetric_manoeuvre_state` sets up the instant of a steady symmetric pull-up (or push-over) at a
given normal load factor: wings level, the flight path at its trimmed angle γ at that instant, the
pitch rate, angle of attack and elevator solved (batched Newton) so that α and q are steady (ẇ = 0,
q̇ = 0) and the CG normal load factor is the target; the throttle stays at its trim value. From it
:func:`simulate_roll` ramps the roll control by ``amplitude`` (per condition) and holds it, the other
controls held — the pilot keeps the pull and does not coordinate.

The strip loads model holds one half of each mirrored surface (the right one). :func:`mirror` returns the
response of the mirror-image airplane (β, p, r, n_y, φ, ψ and the antisymmetric controls reversed): the
right-half loads along the mirrored response are the left-half loads along the original one.

The regulation's numbers (the load factors, the speeds, the roll-rate ratios) belong to the rule. For a roll
rate asked for as a fraction of another condition's, :func:`aileron_for_roll_rate` finds the fraction of the
aileron deflection that reaches it; :func:`rolling_window` gives the part of a response whose loads belong to the
manoeuvre; :func:`stall_line_load_factor` where a symmetric manoeuvre state lies beyond the lift available.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from certkit.atmosphere import density, speed_of_sound
from certkit.models.dynamics.simulate import Ramp, gather, simulate

#: histories that change sign in the mirror image (Y ↔ −Y)
ANTISYMMETRIC_STATES = ("beta", "p", "r", "n_y", "phi", "psi", "y_E")
#: controls whose positive deflection is antisymmetric (aileron: right TE down, left up) or lateral (rudder)
ANTISYMMETRIC_CONTROLS = ("aileron", "rudder")


@dataclass
class ManoeuvreStates:
    x: np.ndarray  # (n, 12) Euler states
    u: np.ndarray  # (n, m) controls
    n_z: np.ndarray  # achieved CG normal load factor
    pitch_rate: np.ndarray  # rad/s
    alpha: np.ndarray
    converged: np.ndarray  # bool


def _state(V, h, alpha, gamma, q, psi=0.0):
    n = V.size
    x = np.zeros((n, 12))
    x[:, 2] = h
    x[:, 3] = V * np.cos(alpha)
    x[:, 5] = V * np.sin(alpha)
    x[:, 7] = q
    x[:, 10] = alpha + gamma
    x[:, 11] = psi
    return x


def symmetric_manoeuvre_state(
    model, x_trim, u_trim, n_target, gamma, pitch: str = "elevator", tol: float = 1e-8, max_iter: int = 30
) -> ManoeuvreStates:
    """The instant of a steady wings-level pull-up (n > 1) or push-over (n < 1) at CG normal load factor
    ``n_target`` from the trimmed states ``x_trim`` (n, 12), ``u_trim`` on flight paths ``gamma`` (rad).

    Unknowns α, q, pitch control; equations ẇ = 0, q̇ = 0, n_z = n_target. Starts from the trim and the
    kinematic pitch rate g (n − cos γ)/V."""
    x_trim = np.asarray(x_trim, dtype=float)
    n = x_trim.shape[0]
    V = np.hypot(np.hypot(x_trim[:, 3], x_trim[:, 4]), x_trim[:, 5])
    h = x_trim[:, 2]
    gamma = np.broadcast_to(np.asarray(gamma, dtype=float), (n,))
    n_target = np.broadcast_to(np.asarray(n_target, dtype=float), (n,))
    je = model.control_index(pitch)
    u = np.array(u_trim, dtype=float)
    z = np.stack([np.arctan2(x_trim[:, 5], x_trim[:, 3]), model.g * (n_target - np.cos(gamma)) / V, u[:, je]], axis=1)
    scale = np.array([1.0 / model.g, 1.0, 1.0])

    def residual(z):
        uu = u.copy()
        uu[:, je] = z[:, 2]
        xd, out = model.derivatives_euler(_state(V, h, z[:, 0], gamma, z[:, 1]), uu, with_outputs=True)
        return np.stack([xd[:, 5], xd[:, 7], out.n_z - n_target], axis=1) * scale

    r = residual(z)
    for _ in range(max_iter):
        rn = np.max(np.abs(r), axis=1)
        if np.all(rn <= tol):
            break
        J = np.empty((n, 3, 3))
        for j, hstep in enumerate((1e-6, 1e-7, 1e-6)):
            zp = z.copy()
            zp[:, j] += hstep
            J[:, :, j] = (residual(zp) - r) / hstep
        dz = -np.linalg.solve(J, r[:, :, None])[:, :, 0]
        dz = np.where(np.isfinite(dz), dz, 0.0)
        dz /= np.maximum(np.max(np.abs(dz) / np.array([0.03, 0.05, 0.2]), axis=1), 1.0)[:, None]
        z = np.where((rn > tol)[:, None], z + dz, z)
        r = residual(z)
    u[:, je] = z[:, 2]
    x = _state(V, h, z[:, 0], gamma, z[:, 1])
    _, out = model.derivatives_euler(x, u, with_outputs=True)
    return ManoeuvreStates(x, u, out.n_z, z[:, 1], z[:, 0], np.max(np.abs(r), axis=1) <= 1e-6)


def simulate_roll(
    model,
    x0,
    u0,
    amplitude,
    duration: float,
    dt: float = 0.02,
    ramp: float = 0.1,
    aileron: str = "aileron",
    controllers=(),
):
    """The roll control ``aileron`` ramped by ``amplitude`` (rad, per condition) over ``ramp`` s from t = 0
    and held to ``duration`` s; the other controls held at ``u0`` unless ``controllers`` move them."""
    n = np.asarray(x0).shape[0]
    amplitude = np.broadcast_to(np.asarray(amplitude, dtype=float), (n,)).copy()
    return simulate(model, x0, u0, duration, dt, inputs={aileron: Ramp(0.0, ramp, amplitude)}, controllers=controllers)


def mirror(sim, controls=ANTISYMMETRIC_CONTROLS):
    """The response of the mirror-image airplane (Y → −Y): antisymmetric histories and controls reversed."""
    hist = {k: (-v if k in ANTISYMMETRIC_STATES else v) for k, v in sim.history.items()}
    c = sim.controls.copy()
    for j, name in enumerate(sim.control_names):
        if name in controls:
            c[:, :, j] = -c[:, :, j]
    return replace(sim, history=hist, controls=c)


#: the roll acceleration, as a fraction of its peak, below which the roll rate counts as steady: a first-order roll
#: mode p = p_ss (1 − e^(−t/τ)) has ṗ/ṗ_max = e^(−t/τ), so the rate is then within 2 % of the steady rolling velocity
#: (a plateau that keeps creeping up by a fraction of a degree per second, as the sideslip builds, is steady)
STEADY_ROLL_ACCELERATION = 0.02


def peak_roll_rate(sim, p0=None) -> tuple[np.ndarray, np.ndarray]:
    """The roll rate |p − p0| of each condition where it first stops growing, or first grows at less than
    :data:`STEADY_ROLL_ACCELERATION` of its peak rate of growth after that peak — the steady rolling velocity the
    aileron input reaches, before the flight path departs from the condition (rad/s) — and the index of that time
    step (the last one if |p − p0| grows throughout)."""
    p = sim["p"]
    base = p[0] if p0 is None else np.asarray(p0)
    d = np.abs(p - base[None, :])
    growth = d[1:] - d[:-1]  # (nt − 1, n)
    after_peak = np.arange(growth.shape[0])[:, None] >= np.argmax(growth, axis=0)[None, :]
    stops = (growth <= 0.0) | (after_peak & (growth < STEADY_ROLL_ACCELERATION * growth.max(axis=0)))
    k = np.where(stops.any(axis=0), np.argmax(stops, axis=0), d.shape[0] - 1)
    return d[k, np.arange(d.shape[1])], k


def rolling_window(sim) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The part of a roll response whose loads belong to the manoeuvre: from the aileron input to the steady rolling
    velocity (where |p| first stops growing, :func:`peak_roll_rate`); beyond it the flight path departs from the
    condition (bank growing, a push-over diving and gaining speed). Returns (the end time per condition (s), the
    (n_t, n) mask of the window, the index of its last step)."""
    _, k_peak = peak_roll_rate(sim)
    t_end = sim.t[k_peak]
    return t_end, sim.t[:, None] <= t_end[None, :] + 1e-9, k_peak


def stall_line_load_factor(model, x) -> np.ndarray | None:
    """The load factor on the stall line at each state's speed and altitude: CLmax(M) q̄ S / (m g) from the aero
    model's stall CLmax (None when the model has no stall model)."""
    clmax = getattr(model.aero, "clmax", None)
    V = np.hypot(np.hypot(x[:, 3], x[:, 4]), x[:, 5])
    values = clmax(V / speed_of_sound(x[:, 2])) if callable(clmax) else None
    if values is None:
        return None
    qbar = 0.5 * density(x[:, 2]) * V**2
    return values * qbar * model.S / (model.mass * model.g)


#: where in the accepted roll-rate band [target, (1 + tol) target] the corrections aim: above its middle, as the
#: roll rate grows slightly less than in proportion to the deflection (up to 1.5 % at VD on a large transport)
AIM = 0.7


def aileron_for_roll_rate(
    model,
    x0,
    u0,
    amplitude,
    target,
    scaled,
    sim_full,
    *,
    duration: float,
    dt: float,
    ramp: float,
    tolerance: float,
    steps: int,
):
    """The fraction of the aileron ``amplitude`` (rad, per condition) whose peak roll rate (:func:`peak_roll_rate`)
    lies in [target, (1 + tolerance) target] for the ``scaled`` conditions (the others keep the whole amplitude),
    corrected proportionally from the full-amplitude response ``sim_full`` (the roll rate is nearly linear in the
    deflection) at most ``steps`` times; a target beyond the whole amplitude keeps it. Returns the simulation of the
    final fractions, its peak roll rates and the fractions."""
    n = len(x0)
    p = peak_roll_rate(sim_full)[0].copy()
    simulated = np.ones(n)
    flown = [(sim_full, i) for i in range(n)]  # each condition's run at its latest fraction: the run and its column
    frac = np.where(scaled, np.clip(target * (1 + AIM * tolerance) / np.maximum(p, 1e-9), 0.0, 1.0), 1.0)

    def fly() -> None:
        """The conditions whose fraction changed since their last run, run again (a condition's run does not depend
        on its batch: the others keep theirs)."""
        rows = np.flatnonzero(frac != simulated)
        part = simulate_roll(model.subset(rows), x0[rows], u0[rows], (frac * amplitude)[rows], duration, dt, ramp)
        p[rows], simulated[rows] = peak_roll_rate(part)[0], frac[rows]
        for j, i in enumerate(rows):
            flown[i] = (part, j)

    for _ in range(int(steps)):
        if np.array_equal(frac, simulated):
            break
        fly()
        done = ~scaled | ((p >= target) & (p <= target * (1 + tolerance))) | ((frac >= 1.0) & (p < target))
        if done.all():
            break
        frac = np.where(done, frac, np.clip(frac * target * (1 + AIM * tolerance) / np.maximum(p, 1e-9), 0.0, 1.0))
    if not np.array_equal(frac, simulated):
        fly()
    sim = gather(flown)
    if sim is None:  # runs of other lengths (not the case of simulate_roll's fixed duration): the batch's own run
        sim = simulate_roll(model, x0, u0, frac * amplitude, duration, dt, ramp)
    return sim, p, frac
