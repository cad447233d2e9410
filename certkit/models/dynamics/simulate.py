"""Fixed-step RK4 time simulation of a whole batch of conditions.

The state is the quaternion state (n, 13) of :mod:`certkit.models.dynamics.eom`. Controls are the
trim controls plus pilot inputs from schedules (vectorised functions of time, one value per
condition) and, optionally, closed-loop controllers; they are held constant over a step
(zero-order hold, as a flight-control computer would), and so are the engines' forces, evaluated
at the start of each step (an engine's thrust changes over seconds, a step is 10 ms). The RK4
step runs in compiled code (:func:`certkit.models.dynamics.kernel.rk4_step`). Each condition may stop on its own
criteria: it is then frozen (state and records held) while the others go on; the run ends when
all have stopped or at ``t_end``.

Input schedules (amplitudes are floats or (n,) arrays — a different input per condition):
    :class:`Step`, :class:`Ramp`, :class:`Doublet`, :class:`Hold`, :class:`CheckedManeuver`
    (§25.331(c)(2): δ₁ sin ωt for 0 ≤ t ≤ 3π/(2ω), optionally held at its peak for up to 5 s
    before returning), :class:`RudderKick` (§25.351: ramp to full rudder, hold, ramp back).
    Schedules add: ``Step(1, a) + Ramp(3, 4, b)``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Iterator, Mapping, Sequence

import numpy as np

from certkit.models.dynamics.controlled_run import controlled_blocks, run_controlled
from certkit.models.dynamics.eom import QUAT_STATE, AircraftModel, euler_state_to_quat_state, quat_to_euler
from certkit.models.dynamics.kernel import OUTPUTS


class Schedule:
    """A control increment as a function of time, vectorised over conditions."""

    #: can :meth:`__call__` take a grid of times (nt, 1) or (nt, n) and give every step's values at once (the same
    #: element-wise arithmetic as one step at a time)? A schedule says so (those with Python branches on ``t`` cannot);
    #: else :meth:`over` calls it one step at a time.
    time_grid = False

    def __call__(self, t: float) -> np.ndarray | float:  # pragma: no cover - abstract
        raise NotImplementedError

    def over(self, times: np.ndarray) -> np.ndarray:
        """The increments at every time of ``times`` ((nt, 1), or (nt, n) with a time step per condition), (nt, n)
        or broadcastable to it."""
        if self.time_grid:
            return self(times)
        vals = [np.asarray(self(t[0] if t.shape[0] == 1 else t), dtype=float) for t in times]  # one step at a time
        out = np.empty((len(vals),) + np.broadcast_shapes(*(v.shape for v in vals)))
        for k, v in enumerate(vals):
            out[k] = v
        return out.reshape(len(vals), -1)

    def __add__(self, other: "Schedule") -> "Schedule":
        return _Sum(self, other)


@dataclass
class _Sum(Schedule):
    a: Schedule
    b: Schedule

    def __call__(self, t):
        return self.a(t) + self.b(t)

    def over(self, times):
        return self.a.over(times) + self.b.over(times)


@dataclass
class Hold(Schedule):
    """A constant increment (e.g. a held pull)."""

    time_grid = True
    value: float | np.ndarray

    def __call__(self, t):
        return np.asarray(self.value, dtype=float)


@dataclass
class Step(Schedule):
    time_grid = True
    t0: float
    amplitude: float | np.ndarray

    def __call__(self, t):
        return np.asarray(self.amplitude, dtype=float) * (t >= self.t0)


@dataclass
class Ramp(Schedule):
    """Linear from 0 at t0 to ``amplitude`` at t1, held after."""

    time_grid = True
    t0: float
    t1: float
    amplitude: float | np.ndarray

    def __call__(self, t):
        f = np.clip((t - self.t0) / max(self.t1 - self.t0, 1e-12), 0.0, 1.0)
        return np.asarray(self.amplitude, dtype=float) * f


@dataclass
class Doublet(Schedule):
    """+amplitude for ``width`` seconds from t0, then −amplitude for ``width``, then 0."""

    t0: float
    width: float
    amplitude: float | np.ndarray

    def __call__(self, t):
        a = np.asarray(self.amplitude, dtype=float)
        if self.t0 <= t < self.t0 + self.width:
            return a
        if self.t0 + self.width <= t < self.t0 + 2 * self.width:
            return -a
        return 0.0 * a


@dataclass
class Pulse(Schedule):
    t0: float
    width: float
    amplitude: float | np.ndarray

    def __call__(self, t):
        return np.asarray(self.amplitude, dtype=float) * (self.t0 <= t < self.t0 + self.width)


@dataclass
class CheckedManeuver(Schedule):
    """§25.331(c)(2) checked pitch manoeuvre: δ(t) = δ₁ sin(ω (t − t0)) for 0 ≤ t − t0 ≤ 3π/(2ω),
    zero after. With ``hold`` > 0 the deflection is held at its peak δ₁ (reached at π/(2ω)) for
    ``hold`` seconds before the sinusoid resumes back through zero (the rule allows at most 5 s).
    ``omega`` and ``delta1`` may be (n,) arrays."""

    time_grid = True
    delta1: float | np.ndarray
    omega: float | np.ndarray
    t0: float = 0.0
    hold: float = 0.0

    def __post_init__(self):
        if not 0.0 <= self.hold <= 5.0:
            raise ValueError(f"§25.331(c)(2) allows holding the peak deflection for at most 5 s, got {self.hold} s")

    def __call__(self, t):
        w = np.asarray(self.omega, dtype=float)
        d1 = np.asarray(self.delta1, dtype=float)
        tau = t - self.t0
        t_peak = np.pi / (2 * w)
        tau_eff = np.where(tau <= t_peak, tau, np.where(tau <= t_peak + self.hold, t_peak, tau - self.hold))
        on = (tau >= 0) & (tau_eff <= 3 * np.pi / (2 * w))
        return np.where(on, d1 * np.sin(w * tau_eff), 0.0)

    def duration(self) -> np.ndarray:
        return 3 * np.pi / (2 * np.asarray(self.omega, dtype=float)) + self.hold


@dataclass
class RudderKick(Schedule):
    """§25.351 yaw manoeuvre: rudder ramped to ``amplitude`` in ``ramp`` s from t0, held
    ``hold`` s (to the overswing / steady sideslip), then ramped back to neutral in ``ramp`` s."""

    time_grid = True
    t0: float
    amplitude: float | np.ndarray
    ramp: float = 0.5
    hold: float = 5.0

    def __call__(self, t):
        a = np.asarray(self.amplitude, dtype=float)
        t1 = self.t0 + self.ramp + self.hold
        up = np.clip((t - self.t0) / self.ramp, 0.0, 1.0)
        down = np.clip(1.0 - (t - t1) / self.ramp, 0.0, 1.0)
        return a * np.minimum(up, down)


class Function(Schedule):
    """Any function f(t) → (n,) array as a schedule; ``time_grid``: f also takes a grid of times (see
    :attr:`Schedule.time_grid`)."""

    def __init__(self, f: Callable[[float], np.ndarray], time_grid: bool = False):
        self.f = f
        self.time_grid = time_grid

    def __call__(self, t):
        return self.f(t)


# ---------------------------------------------------------------------- stop criteria
StopCriterion = Callable[[float, np.ndarray, object], np.ndarray]


def stop_when(name: str, predicate: Callable[[float, np.ndarray, object], np.ndarray]) -> StopCriterion:
    """A named stop criterion; ``predicate(t, x13, outputs) -> bool (n,)``."""
    predicate.__name__ = name
    return predicate


class Bound:
    """A stop criterion the compiled run evaluates itself: stop a condition when ``quantity`` — a recorded output
    (:data:`certkit.models.dynamics.kernel.OUTPUTS`, e.g. ``"n_z"``) or ``"t"`` — lies strictly below ``lower`` or
    above ``upper`` (scalars or one per condition; a NaN never stops). Called, it is an ordinary criterion."""

    def __init__(self, name: str, quantity: str, lower=-np.inf, upper=np.inf):
        if quantity != "t" and quantity not in OUTPUTS:
            raise ValueError(f"stop bound on {quantity!r}: one of {('t',) + OUTPUTS}")
        self.__name__, self.quantity, self.lower, self.upper = name, quantity, lower, upper

    def __call__(self, t, x, out):
        value = np.broadcast_to(t, (x.shape[0],)) if self.quantity == "t" else getattr(out, self.quantity)
        return (value < self.lower) | (value > self.upper)

    def arrays(self, n: int) -> tuple[int, np.ndarray, np.ndarray]:
        """(output column or −1 for the time, lower (n,), upper (n,)) for the compiled run."""
        col = -1 if self.quantity == "t" else OUTPUTS.index(self.quantity)
        return (
            col,
            np.broadcast_to(np.asarray(self.lower, dtype=float), (n,)),
            np.broadcast_to(np.asarray(self.upper, dtype=float), (n,)),
        )


def altitude_below(h_min) -> StopCriterion:
    return stop_when(f"h<{h_min}", lambda t, x, out: x[:, 2] < h_min)


def load_factor_beyond(nz_min, nz_max) -> StopCriterion:
    return stop_when("n_z limit", lambda t, x, out: (out.n_z < nz_min) | (out.n_z > nz_max))


def alpha_beyond(alpha_max) -> StopCriterion:
    return stop_when("alpha limit", lambda t, x, out: out.alpha > alpha_max)


def airborne_above(height) -> StopCriterion:
    """Takeoff: stop once the aircraft is ``height`` m above the runway with no gear load."""
    return stop_when(f"airborne {height} m", lambda t, x, out: (x[:, 2] > height) & (out.gear_load.sum(axis=1) <= 0.0))


# ---------------------------------------------------------------------- controllers
class Controller:
    """Closed-loop law: ``update(t, x13, outputs, u) -> u`` (n, n_controls); may keep state."""

    def update(self, t: float, x: np.ndarray, out, u: np.ndarray, dt: float) -> np.ndarray:  # pragma: no cover
        raise NotImplementedError


#: the Euler angles of :data:`RECORDED`, converted from the recorded attitude quaternions when first read
EULER = ("phi", "theta", "psi")


class Histories(Mapping[str, np.ndarray]):
    """A run's recorded histories by name (:data:`RECORDED` order), each (nt, n). The Euler angles (:data:`EULER`)
    are converted from the recorded attitude quaternions ``quat`` (nt, n, 4) when one is first read: most runs (the
    loads' gusts and manoeuvres) read none, and the conversion was 1.6 % of a design. Runs joined end to end
    (:meth:`joined`) join a history when it is first read."""

    __slots__ = ("_values", "_quat", "_parts", "_rows")

    def __init__(
        self,
        values: dict[str, np.ndarray],
        quat: np.ndarray | None,
        parts: Sequence["Histories"] = (),
        rows: Sequence[tuple["Histories", np.ndarray, np.ndarray, np.ndarray]] = (),
    ):
        self._values, self._quat, self._parts, self._rows = values, quat, tuple(parts), tuple(rows)

    def __getitem__(self, key: str) -> np.ndarray:
        values = self._values
        if key not in values:
            if key in EULER:
                eul = quat_to_euler(self._quaternions())
                values.update(phi=eul[:, :, 0], theta=eul[:, :, 1], psi=eul[:, :, 2])
            elif self._parts and key in RECORDED:
                values[key] = self._join(lambda p: p[key])
            elif self._rows and key in RECORDED:
                values[key] = self._gather(lambda h: h[key])
        return values[key]

    def __iter__(self) -> Iterator[str]:
        return iter(RECORDED)

    def __len__(self) -> int:
        return len(RECORDED)

    def _quaternions(self) -> np.ndarray:
        if self._quat is None:
            self._quat = (
                self._join(lambda p: p._quaternions()) if self._parts else self._gather(lambda h: h._quaternions())
            )
        return self._quat

    def _join(self, get: Callable[["Histories"], np.ndarray]) -> np.ndarray:
        parts = self._parts
        return np.concatenate([get(parts[0])] + [get(p)[1:] for p in parts[1:]])

    def _gather(self, get: Callable[["Histories"], np.ndarray]) -> np.ndarray:
        """The gathered history (:meth:`gathered`): each source's conditions' records at their rows."""
        first = get(self._rows[0][0])
        n = sum(len(columns) for _, _, columns, _ in self._rows)
        out = np.empty((self._rows[0][3].shape[0], n) + first.shape[2:], dtype=first.dtype)
        for source, at, columns, rows in self._rows:
            out[:, at] = get(source)[rows, columns]
        return out

    @staticmethod
    def gathered(rows: Sequence[tuple["Histories", np.ndarray, np.ndarray, np.ndarray]]) -> "Histories":
        """Histories made of other runs' conditions: per source, its histories, the conditions ``at`` (k,) they fill,
        their ``columns`` (k,) in the source and the source ``rows`` (nt, k) each record is read from (:func:`gather`).
        Each history is gathered when first read."""
        return Histories({}, None, (), rows)

    @staticmethod
    def joined(parts: Sequence["Histories"]) -> "Histories":
        """The histories of consecutive runs ``parts`` end to end, each after the first without its first record
        (a repeat of the previous run's last); the quaternions joined likewise, so the angles convert as they would
        part by part (element by element). Each history is joined when first read."""
        return Histories({}, None, parts)


@dataclass
class SimulationResult:
    """Recorded time histories: ``t`` (nt,) — (nt, n) with a time step per condition —, each history (nt, n);
    ``controls`` (nt, n, m).
    ``stop_time`` (n,) is when each condition stopped (``t_end`` if it did not) and
    ``stop_reason`` the criterion's name ('' if none)."""

    t: np.ndarray
    history: Mapping[str, np.ndarray]
    controls: np.ndarray
    control_names: tuple[str, ...]
    stop_time: np.ndarray
    stop_reason: list[str]
    final_state: np.ndarray

    def __getitem__(self, key: str) -> np.ndarray:
        return self.history[key]


RECORDED = (
    "V",
    "alpha",
    "beta",
    "p",
    "q",
    "r",
    "phi",
    "theta",
    "psi",
    "h",
    "x_N",
    "y_E",
    "n_x",
    "n_y",
    "n_z",
    "mach",
    "qbar",
    "alpha_dot",
    "CL",
)


def _scheduled_controls(u_trim, sched, nsteps: int, dt, per_row: bool) -> np.ndarray:
    """Every step's controls before any law, (nsteps + 1, n, m): the trim plus each schedule's increment at k·dt, added
    in order as the step-by-step loop adds them."""
    n, m = u_trim.shape
    U_all = np.empty((nsteps + 1, n, m))
    U_all[:] = u_trim
    steps = np.arange(nsteps + 1)
    times = steps[:, None] * dt[None, :] if per_row else (steps * dt)[:, None]  # each step's k·dt
    for j, s in sched:
        U_all[:, :, j] += s.over(times)
    return U_all


def gather(picks: Sequence[tuple[SimulationResult, int]]) -> SimulationResult | None:
    """The run of a batch whose condition j was run, with the same inputs, as column ``picks[j][1]`` of the run
    ``picks[j][0]`` — runs of one time step from t = 0 —, without running it again. A condition's records do not
    depend on the batch it is run in (each row is integrated alone) until it stops; after its stop it keeps its last
    record, and the run ends at the last condition's stop. So the gathered run has the records up to the latest of
    the conditions' stops, each condition's own up to its stop and its last one after; a condition that did not stop
    ran to its run's end, which must then be the gathered run's. None when it is not (the condition's records would
    go on: the run is needed) or the runs' grids differ. Every condition of one run, in its order: that run."""
    n = len(picks)
    first = picks[0][0]
    if len(first.stop_reason) == n and all(sim is first and c == j for j, (sim, c) in enumerate(picks)):
        return first
    stops = np.empty(n, dtype=np.int64)
    ran_out = np.zeros(n, dtype=bool)
    grid = first.t[:2]
    for j, (sim, c) in enumerate(picks):
        t = sim.t
        if t.ndim != 1 or not np.array_equal(t[:2], grid):
            return None
        if not sim.stop_reason[c]:  # ran to its run's end
            stops[j], ran_out[j] = t.shape[0] - 1, True
            continue
        k = int(np.searchsorted(t, sim.stop_time[c]))
        if k >= t.shape[0] or t[k] != sim.stop_time[c]:
            return None
        stops[j] = k
    length = int(stops.max()) + 1
    if (stops[ran_out] < length - 1).any():
        return None
    longest = picks[int(np.argmax(stops))][0]
    steps = np.arange(length)[:, None]
    by_source: dict[int, list[int]] = {}
    for j, (sim, _) in enumerate(picks):
        by_source.setdefault(id(sim), []).append(j)
    rows = []
    controls = np.empty((length, n, longest.controls.shape[2]))
    for js in by_source.values():
        at = np.array(js)
        sim = picks[js[0]][0]
        columns = np.array([picks[j][1] for j in js])
        read = np.minimum(steps, stops[at][None, :])  # a stopped condition's last record, repeated
        rows.append((sim.history, at, columns, read))
        controls[:, at] = sim.controls[read, columns]
    return SimulationResult(
        t=longest.t[:length],
        history=Histories.gathered(rows),
        controls=controls,
        control_names=longest.control_names,
        stop_time=np.array([sim.stop_time[c] for sim, c in picks]),
        stop_reason=[sim.stop_reason[c] for sim, c in picks],
        final_state=np.array([sim.final_state[c] for sim, c in picks]),
    )


def simulate(
    model: AircraftModel,
    x0: np.ndarray,
    u_trim: np.ndarray,
    t_end: float,
    dt: float = 0.01,
    inputs: Mapping[str, Schedule] | None = None,
    controllers: Sequence[Controller] = (),
    stop: Sequence[StopCriterion] = (),
    record_every: int = 1,
    limits: Mapping[str, tuple[float, float]] | None = None,
) -> SimulationResult:
    """Integrate the batch from ``x0`` (Euler (n, 12) — e.g. a trim's ``x`` — or quaternion
    (n, 13)) with controls ``u_trim`` (n, m) plus the scheduled ``inputs`` (control name →
    schedule), the ``controllers`` and the control ``limits`` (name → (min, max), clipped).

    ``dt`` may differ per condition ((n,) array, e.g. a gust resolved in its own length at each speed): every
    condition then takes the same number of steps, round(max(t_end / dt)), the schedules see each condition's own
    time (an (n,) array) and the result's ``t`` is (nt, n); without controllers, stop criteria or limits.

    Two kinds of run are stepped in compiled code, the same arithmetic as the loop below: every step's controls known
    (no controllers or limits, bounds as stop criteria: :meth:`AircraftModel.open_loop_run`), and laws that offer
    the compiled loop a block (the takeoff, engine-cut, landing and yaw laws,
    :mod:`certkit.models.dynamics.controlled_run`)."""
    x = np.array(x0, dtype=float)
    if x.shape[1] == 12:
        x = euler_state_to_quat_state(x)
    n = x.shape[0]
    per_row = np.ndim(dt) > 0
    if per_row:
        dt = np.broadcast_to(np.asarray(dt, dtype=float), (n,))
        if controllers or stop or limits:
            raise ValueError("a time step per condition takes no controllers, stop criteria or control limits")
    names = model.control_names
    u_trim = np.broadcast_to(np.asarray(u_trim, dtype=float), (n, len(names))).copy()
    sched = [(names.index(k), s) for k, s in (inputs or {}).items()]
    lim = [(names.index(k), lo, hi) for k, (lo, hi) in (limits or {}).items()]
    nsteps = int(round(float(np.max(np.asarray(t_end) / dt))))
    nrec = nsteps // record_every + 1
    # records in two blocks (the kernel's outputs and the state), one copy per step; Euler angles at the end
    out_rec = np.empty((nrec, n, len(OUTPUTS)))
    x_rec = np.empty((nrec, n, x.shape[1]))
    ctrl_hist = np.empty((nrec, n, len(names)))
    t_rec = np.empty((nrec, n) if per_row else nrec)
    active = np.ones(n, dtype=bool)
    stop_time = np.broadcast_to(nsteps * dt, (n,)).astype(float)
    stop_reason = [""] * n
    irec = 0
    compiled = None
    if not (controllers or lim) and all(isinstance(c, Bound) for c in stop) and model.runs_open_loop_compiled:
        # every step's controls known, the stop criteria bounds: one compiled run
        U_all = _scheduled_controls(u_trim, sched, nsteps, dt, per_row)
        x = np.ascontiguousarray(x)
        bounds = [c.arrays(n) for c in stop]
        stops = (
            np.array([b[0] for b in bounds], dtype=np.int64),
            np.array([b[1] for b in bounds]).reshape(len(stop), n),
            np.array([b[2] for b in bounds]).reshape(len(stop), n),
        )
        compiled, stop_step, stop_which = model.open_loop_run(
            x,
            U_all,
            np.ascontiguousarray(np.broadcast_to(dt, (n,)), dtype=float),
            record_every,
            out_rec,
            x_rec,
            ctrl_hist,
            stops,
        )
    elif controllers and not (lim or per_row or isinstance(dt, np.ndarray)):
        blocks = controlled_blocks(model, controllers, stop)
        if blocks is not None:  # the laws and the criterion stepped in compiled code, the same arithmetic
            x = np.ascontiguousarray(x)
            U_all = _scheduled_controls(u_trim, sched, nsteps, dt, False) if sched else u_trim[None]
            compiled, stop_step = run_controlled(
                model, x, U_all, dt, nsteps, record_every, blocks, out_rec, x_rec, ctrl_hist
            )
            stop_which = np.zeros(n, dtype=np.int64)  # its one criterion
    if compiled is not None:
        for i in np.flatnonzero(stop_step >= 0):
            stop_time[i] = stop_step[i] * dt
            stop_reason[i] = getattr(stop[stop_which[i]], "__name__", "stop")
        irec = compiled
        steps = np.arange(0, nsteps + 1, record_every)[:irec]
        t_rec[:irec] = steps[:, None] * dt if per_row else steps * dt
    for k in range(nsteps + 1 if compiled is None else 0):
        t = k * dt
        u = u_trim.copy()
        for j, s in sched:
            u[:, j] += s(t)
        xd1, out, gear, thrust = model.evaluate(x, u)
        if controllers or lim:
            outputs = model.make_outputs(out, gear, thrust)
            for c in controllers:
                u = c.update(t, x, outputs, u, dt)
            for j, lo, hi in lim:
                u[:, j] = np.clip(u[:, j], lo, hi)
            xd1, out, gear, thrust = model.evaluate(x, u)
        # stop criteria on the state at t
        if stop:
            outputs = model.make_outputs(out, gear, thrust)
            for crit in stop:
                hit = active & np.asarray(crit(t, x, outputs), dtype=bool)
                if hit.any():
                    for i in np.flatnonzero(hit):
                        stop_reason[i] = getattr(crit, "__name__", "stop")
                    stop_time[hit] = t
                    active &= ~hit
        if k % record_every == 0:
            if irec > 0 and not active.all():  # a stopped condition keeps its last record
                out_rec[irec] = np.where(active[:, None], out, out_rec[irec - 1])
                x_rec[irec] = np.where(active[:, None], x, x_rec[irec - 1])
                ctrl_hist[irec] = np.where(active[:, None], u, ctrl_hist[irec - 1])
            else:
                out_rec[irec], x_rec[irec], ctrl_hist[irec] = out, x, u
            t_rec[irec] = t
            irec += 1
        if k == nsteps or not active.any():
            break
        x = model.rk4_step(x, xd1, u, thrust, dt, active)
    out_rec, x_rec = out_rec[:irec], x_rec[:irec]
    hist = {name: out_rec[:, :, j] for j, name in enumerate(OUTPUTS) if name in RECORDED}
    hist.update({name: x_rec[:, :, j] for j, name in enumerate(QUAT_STATE[:9]) if name in RECORDED})
    return SimulationResult(
        t=t_rec[:irec],
        history=Histories({key: hist[key] for key in RECORDED if key not in EULER}, x_rec[:, :, 9:13]),
        controls=ctrl_hist[:irec],
        control_names=names,
        stop_time=stop_time,
        stop_reason=stop_reason,
        final_state=x,
    )


__all__ = [
    "Schedule",
    "Hold",
    "Step",
    "Ramp",
    "Doublet",
    "Pulse",
    "CheckedManeuver",
    "RudderKick",
    "Function",
    "StopCriterion",
    "Bound",
    "stop_when",
    "altitude_below",
    "load_factor_beyond",
    "alpha_beyond",
    "airborne_above",
    "Controller",
    "SimulationResult",
    "Histories",
    "simulate",
    "gather",
    "RECORDED",
]
