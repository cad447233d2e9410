"""Balanced symmetric manoeuvres: the airplane at a normal load factor n with zero pitching acceleration, and the
station loads of that one trimmed state.

A steady symmetric pull-up (n > 1) or push-over (n < 1) at the instant the flight path passes the angle γ of the
entry trim: the flight path turns at q = g (n − cos γ) / V (wings level, q the body pitch rate), the normal load
factor on the path is n (Etkin & Reid, *Dynamics of Flight*, 3rd ed., §6.7, the pull-up: n = 1 + V q / g in level
flight). Solved for each condition of a batch at once by Newton's method (forward-difference Jacobian) for the
angle of attack and the pitch control such that

    α̇ = 0 (the path-normal force balance: L + T sin(α + …) − W cos γ = m V q)   and   q̇ = 0 (moment balance),

the throttle and every other control held at the entry trim's (thrust ≈ drag of the 1 g flight; the speed change
the extra drag causes is not balanced — it is a longitudinal acceleration, not a pitching one). The horizontal
tail load is then the balancing load of the trimmed state and the wing carries the rest of n W, from the same
state, in the strip loads model (:mod:`certkit.models.loads.model`).
"""

from __future__ import annotations

from dataclasses import dataclass
from types import SimpleNamespace

import numpy as np

from certkit.models.dynamics.eom import AircraftModel
from certkit.models.dynamics.trim import assemble_state
from certkit.models.loads.response import inertia_terms, response_load_parts, with_fuel_states


@dataclass
class BalancedStates:
    """Balanced states of a batch: Euler states (n, 12), controls (n, nc), the kernel outputs, convergence."""

    x: np.ndarray
    u: np.ndarray
    outputs: object  # certkit.models.dynamics.eom.Outputs
    load_factor: np.ndarray  # the path-normal n asked for
    converged: np.ndarray
    residual: np.ndarray  # max |α̇|, |q̇| (rad/s, rad/s²)

    @property
    def alpha(self) -> np.ndarray:
        return self.outputs.alpha

    @property
    def pitch_rate(self) -> np.ndarray:
        return self.x[:, 7]


def linear_lift(model: AircraftModel) -> AircraftModel:
    """The flight model ``model`` with its aerodynamics' stall model removed (linear lift up to any C_L): the V–n
    envelope's corners on the stall lines ask for C_N,max, which a rounded stall model only approaches; the strip
    loads are linear in α as well. Models without a stall model are returned as they are."""
    aero = model.aero
    if getattr(aero, "stall", None) is None or not hasattr(aero, "without_stall"):
        return model
    return AircraftModel(
        aero.without_stall(),
        model.mass,
        model.cg,
        model.inertia,
        model.engines,
        model.operative,
        model.ground,
        model.g,
        n=model.n,
    )


def _entry(x_entry):
    """Speed, altitude, angle of attack and flight-path angle of steady Euler states (n, 12)."""
    u, w = x_entry[:, 3], x_entry[:, 5]
    alpha = np.arctan2(w, u)
    return np.hypot(u, w), x_entry[:, 2], alpha, x_entry[:, 10] - alpha


def balanced_states(
    model,
    x_entry,
    u_entry,
    load_factor,
    pitch_control: str = "elevator",
    g: float = 9.80665,
    tol: float = 1e-9,
    max_iter: int = 30,
) -> BalancedStates:
    """The balanced manoeuvre of every condition of ``model`` (n) entered from its steady state ``x_entry`` /
    ``u_entry`` (straight trims: the speed, altitude, flight-path angle and the controls kept) at the path-normal
    load factors ``load_factor`` (scalar or (n,)). Conditions that do not converge are flagged, not raised."""
    V, h, alpha0, gamma = _entry(np.asarray(x_entry, dtype=float))
    n_cond = V.size
    nz = np.broadcast_to(np.asarray(load_factor, dtype=float), (n_cond,)).astype(float)
    q = g * (nz - np.cos(gamma)) / np.maximum(V, 1.0)
    j_pitch = list(model.control_names).index(pitch_control)
    u_entry = np.asarray(u_entry, dtype=float)

    def state(z, idx):
        x = assemble_state(V[idx], h[idx], z[:, 0], 0.0, 0.0, gamma[idx], 0.0)
        x[:, 7] = q[idx]
        u = u_entry[idx].copy()
        u[:, j_pitch] = z[:, 1]
        return x, u

    def residual(z, idx):
        x, u = state(z, idx)
        xd, out = model.derivatives_euler(x, u, with_outputs=True, rows=idx)
        return np.stack([out.alpha_dot, xd[:, 7]], axis=1)

    # initial guess: the entry α scaled with the load factor (lift ∝ α from zero lift near α = 0), entry pitch control
    z = np.stack([alpha0 * np.maximum(nz, 0.2) / np.maximum(np.cos(gamma), 0.5), u_entry[:, j_pitch]], axis=1)
    everyone = np.arange(n_cond)
    r = residual(z, everyone)
    step = np.array([1e-6, 1e-6])
    max_step = np.array([0.05, 0.1])
    for _ in range(max_iter):
        idx = np.flatnonzero(np.max(np.abs(r), axis=1) > tol)
        if idx.size == 0:
            break
        za, ra = z[idx], r[idx]
        zp = np.concatenate([za + [step[0], 0.0], za + [0.0, step[1]]])
        rp = residual(zp, np.tile(idx, 2)).reshape(2, idx.size, 2)
        jac = np.stack([(rp[0] - ra) / step[0], (rp[1] - ra) / step[1]], axis=-1)  # (m, eq, unknown)
        det = jac[:, 0, 0] * jac[:, 1, 1] - jac[:, 0, 1] * jac[:, 1, 0]
        det = np.where(np.abs(det) > 1e-300, det, 1e-300)
        dz = (
            -np.stack(
                [jac[:, 1, 1] * ra[:, 0] - jac[:, 0, 1] * ra[:, 1], -jac[:, 1, 0] * ra[:, 0] + jac[:, 0, 0] * ra[:, 1]],
                axis=1,
            )
            / det[:, None]
        )
        dz = np.where(np.isfinite(dz), dz, 0.0)
        dz /= np.maximum(np.max(np.abs(dz) / max_step, axis=1), 1.0)[:, None]
        z[idx] = za + dz
        r[idx] = residual(z[idx], idx)
    x, u = state(z, everyone)
    _, out = model.derivatives_euler(x, u, with_outputs=True)
    res = np.max(np.abs(r), axis=1)
    return BalancedStates(x, u, out, nz, res <= tol * 10, res)


#: how a balanced state holds its pitching moment (:func:`balanced_within_stops`)
ELEVATOR_ALONE, STABILIZER_RETRIMMED, ELEVATOR_AT_STOP = 0, 1, 2


def balanced_within_stops(
    model, x_entry, u_entry, load_factor, stops, tol: float = 1e-9, retrim=True
) -> tuple[BalancedStates, np.ndarray]:
    """Balanced states (:func:`balanced_states`) whose pitch controls stay within their stops where the airplane
    allows it, and the scheme of each (``ELEVATOR_ALONE``, ``STABILIZER_RETRIMMED``, ``ELEVATOR_AT_STOP``).

    The elevator balances first, the stabiliser held at the entry trim's setting. Where that needs the elevator
    beyond its stop (``stops``: control name → (min, max) rad) and the model has a movable stabiliser, the
    stabiliser is retrimmed with the elevator back at its entry (trimmed) deflection, as a pilot or a
    stabiliser auto-trim unloads the column in a held manoeuvre; where the stabiliser would then pass its own stop,
    the elevator is held at its stop in the direction needed and the stabiliser balances the rest. A state still
    beyond a stop after that is returned as it is (the caller reads the deflections against ``stops``): the
    airplane cannot hold the condition. ``retrim`` (bool or (n,) bool) False keeps a condition's stabiliser where its
    entry put it whatever the elevator needs (an out-of-trim condition, whose mistrim is the condition itself)."""
    x_entry, u_entry = np.asarray(x_entry, dtype=float), np.asarray(u_entry, dtype=float)
    st = balanced_states(model, x_entry, u_entry, load_factor, "elevator", tol=tol)
    scheme = np.full(st.x.shape[0], ELEVATOR_ALONE)
    names = list(model.control_names)
    if "stabilizer" not in names or "elevator" not in stops:
        return st, scheme
    je, js = names.index("elevator"), names.index("stabilizer")
    lo, hi = stops["elevator"]
    s_lo, s_hi = stops.get("stabilizer", (-np.inf, np.inf))
    nz = st.load_factor
    x, u, conv, res = st.x.copy(), st.u.copy(), st.converged.copy(), st.residual.copy()
    may_retrim = np.broadcast_to(np.asarray(retrim, dtype=bool), nz.shape)
    rows = np.flatnonzero(((u[:, je] < lo) | (u[:, je] > hi)) & may_retrim)
    for code in (STABILIZER_RETRIMMED, ELEVATOR_AT_STOP):
        if not rows.size:
            break
        entry_u = u_entry[rows].copy()
        if code == ELEVATOR_AT_STOP:
            entry_u[:, je] = np.where(st.u[rows, je] > hi, hi, lo)  # the stop the elevator alone went past
        sub = balanced_states(model.subset(rows), x_entry[rows], entry_u, nz[rows], "stabilizer", tol=tol)
        x[rows], u[rows], conv[rows], res[rows], scheme[rows] = sub.x, sub.u, sub.converged, sub.residual, code
        rows = rows[(sub.u[:, js] < s_lo) | (sub.u[:, js] > s_hi)]
    _, out = model.derivatives_euler(x, u, with_outputs=True)
    return BalancedStates(x, u, out, nz, conv, res), scheme


def steady_load_parts(loads, model, x, u, outputs, surfaces) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """Aerodynamic and inertial station loads, each (n, 3, S), of ``surfaces`` in the steady states ``x``/``u``
    (outputs of the flight model there): the strip loads of :func:`response_load_parts` at one instant, with the
    angular accelerations zero (a balanced state)."""
    record = _steady_record(model, x, u, outputs)
    parts = response_load_parts(loads, record, model, tuple(surfaces))
    return {k: (a[0], i[0]) for k, (a, i) in parts.items()}


def steady_fuel_units(loads, model, x, u, outputs, surface: str = "wing") -> np.ndarray | None:
    """Inertial station loads per kilogram of each tank's fuel, (n, K, 3, S), of ``surface`` in the steady states
    (:meth:`certkit.models.loads.model.SurfaceLoads.fuel_loads`); None without tanks."""
    units = loads[surface].fuel_loads(inertia_terms(_steady_record(model, x, u, outputs), model))
    return None if units is None else units[0]


@dataclass
class BalancedLoads:
    """The balanced states of a batch and their station loads (:func:`balanced_loads`): the model with linear lift
    they were solved on, the states, how each holds its pitching moment (``scheme``), the aerodynamic and inertial
    parts of each surface's loads ((n, 3, S) each), their sums (NaN where the balance did not converge) and the
    wing's loads in each fuel state ((M, n, 3, S); all NaN for a configuration whose wing loads are not held)."""

    model: AircraftModel
    state: BalancedStates
    scheme: np.ndarray
    parts: dict
    total: dict
    wing_states: np.ndarray


def balanced_loads(
    loads, model, x_entry, u_entry, load_factor, stops, surfaces, *, tol: float, fuel, wing: bool = True, retrim=True
) -> BalancedLoads:
    """Balanced states at ``load_factor`` from the entry trims (:func:`balanced_within_stops`, on the model with
    linear lift, :func:`linear_lift`; ``retrim`` as there) and the station loads of ``surfaces`` there; the wing's
    loads in the fuel states ``fuel`` ((n, M, K) kg per condition, state and tank), all NaN where ``wing`` is False
    (a configuration whose wing loads the strip model does not hold)."""
    model = linear_lift(model)
    st, scheme = balanced_within_stops(model, x_entry, u_entry, load_factor, stops, tol=tol, retrim=retrim)
    parts = steady_load_parts(loads, model, st.x, st.u, st.outputs, surfaces)
    total = {s: a + i for s, (a, i) in parts.items()}
    units = steady_fuel_units(loads, model, st.x, st.u, st.outputs, "wing") if wing else None
    wing_states = np.array(
        np.broadcast_to(with_fuel_states(total["wing"], units, fuel), (fuel.shape[1],) + total["wing"].shape)
    )
    if not wing:
        wing_states[:] = np.nan
    bad = ~st.converged
    for s in surfaces:
        total[s][bad] = np.nan
    wing_states[:, bad] = np.nan
    return BalancedLoads(model, st, scheme, parts, total, wing_states)


def _steady_record(model, x, u, outputs):
    """A one-instant simulation record of the steady states (angular accelerations zero)."""
    o = outputs
    history = {
        "V": o.V,
        "alpha": o.alpha,
        "beta": o.beta,
        "mach": o.mach,
        "qbar": o.qbar,
        "n_z": o.n_z,
        "n_y": o.n_y,
        "p": x[:, 6],
        "q": x[:, 7],
        "r": x[:, 8],
    }
    return SimpleNamespace(
        history={k: np.asarray(v, dtype=float)[None, :] for k, v in history.items()},
        t=np.zeros(1),
        controls=np.asarray(u, dtype=float)[None],
        control_names=model.control_names,
    )
