"""Rigid-airplane response to discrete 1 − cos vertical gusts, batched over conditions, with the strip
loads of the wing and the horizontal tail.

The trimmed batch's flight model is rebuilt around :func:`certkit.models.loads.gust.gust_aero` (same
masses, CGs, inertias and engines; the gust pseudo-controls added at zero). The gust front reaches the
wing's centre of pressure at t = 0 and the tail's a tail arm / V later (``tail_lag``); the gust angle is
U/V with U and V both in EAS (the ratio is the same in TAS). The wing and the tail strips feel their
own gust angle on top of the airplane's angle of attack (:func:`response_loads` ``extra_alpha``).

One simulation per gust gradient H: the step resolves the shortest gust of the group
(``steps_per_gust`` per 2H/V) and the run ends ``settle`` seconds after the gust has left the tail of
the slowest condition. The numbers the regulation sets (H range, U_ds) belong to the rule.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from certkit.models.dynamics.eom import AircraftModel
from certkit.models.dynamics.simulate import Function, Histories, SimulationResult, simulate
from certkit.models.loads.gust import gust_aero, gust_tables, penetration_lagged
from certkit.models.loads.response import inertia_terms, response_load_parts

SURFACES = ("wing", "horizontal_tail")


def pressure_centres(loads) -> dict[str, float]:
    """X (m) of the centre of pressure of a unit uniform angle of attack on the wing and the horizontal
    tail (mean over the Mach breakpoints), from the root shear and torsion of the strip model."""
    out = {}
    for name in SURFACES:
        s = loads[name]
        k = s.inputs.index("alpha")
        normal, torsion = s.aero[:, k, 0, 0], s.aero[:, k, 2, 0]
        x_axis = float(np.interp(0.0, s.strip_span, s.strip_x))
        out[name] = float(np.mean(x_axis - torsion / np.where(np.abs(normal) > 1e-12, normal, 1.0)))
    return out


@dataclass
class GustBatch:
    """A trimmed batch ready for gust runs: the gust flight model, initial states and controls."""

    model: AircraftModel
    x0: np.ndarray
    u0: np.ndarray
    v_tas: np.ndarray  # m/s
    tail_arm: float  # m, wing to tail centre of pressure
    chords: tuple[float, float]  # m, wing and tail mean chords (the penetration lag)

    def subset(self, idx) -> "GustBatch":
        idx = np.asarray(idx)
        return GustBatch(
            self.model.subset(idx), self.x0[idx], self.u0[idx], self.v_tas[idx], self.tail_arm, self.chords
        )


def with_aero(base_model: AircraftModel, aero, u0) -> tuple[AircraftModel, np.ndarray]:
    """The flight model ``base_model`` (same masses, CGs, inertias, engines) around the aerodynamics ``aero`` (the base
    model's with pseudo-controls added), and the controls ``u0`` in its order (the added ones zero)."""
    model = AircraftModel(
        aero, base_model.mass, base_model.cg, base_model.inertia, base_model.engines, base_model.operative
    )
    old = list(base_model.control_names)
    u = np.zeros((np.shape(u0)[0], len(model.control_names)))
    for j, name in enumerate(model.control_names):
        if name in old:
            u[:, j] = np.asarray(u0)[:, old.index(name)]
    return model, u


def gust_batch(loads, base_model: AircraftModel, x0, u0) -> GustBatch:
    """Wrap the trimmed batch's flight model with the gust pseudo-controls (zero in the trim)."""
    tables = gust_tables(loads, base_model.aero.reference)
    model, u = with_aero(base_model, gust_aero(base_model.aero, **tables), u0)
    v = np.hypot(np.hypot(x0[:, 3], x0[:, 4]), x0[:, 5])  # body velocity components u, v, w of the Euler state
    xc = pressure_centres(loads)
    chords = (loads["wing"].mean_chord, loads["horizontal_tail"].mean_chord)
    return GustBatch(model, np.asarray(x0, dtype=float), u, v, xc["horizontal_tail"] - xc["wing"], chords)


@dataclass
class GustRun:
    sim: object
    loads: dict[str, np.ndarray]  # surface → (nt, n, 3, S)
    alpha_gust: dict[str, np.ndarray]  # surface → (nt, n) gust angle felt
    dt: float
    parts: dict[str, tuple[np.ndarray, np.ndarray]]  # surface → aerodynamic and inertial loads, for ``split``
    #: surface → the fuel's inertial loading, uncontracted: terms (nt, n, J) and per-kilogram tables (K, J, 3, S), for
    #: the surfaces of ``split`` with tanks (:meth:`certkit.models.loads.model.SurfaceLoads.fuel_term_tables`)
    fuel_units: dict[str, tuple] = field(default_factory=dict)


def simulate_gust(
    loads,
    gb: GustBatch,
    H: float,
    alpha_peak,
    steps_per_gust: float,
    settle: float,
    max_step: float = 0.05,
    settle_step: float = 0.04,
    surfaces=SURFACES,
    split=(),
) -> GustRun:
    """One gust gradient ``H`` (m) for the whole batch; ``alpha_peak`` (n,) the peak gust angle
    U_ds/V (signed: positive = upward gust), in the two phases of :func:`two_phase_run`. For the
    surfaces in ``split`` the aerodynamic and inertial loads are also kept apart (``GustRun.parts``)."""
    a = np.asarray(alpha_peak, dtype=float) * np.ones(gb.x0.shape[0])
    v = gb.v_tas
    lag = gb.tail_arm / v

    c_wing, c_tail = gb.chords

    @_grids_kept
    def wing(t):
        return penetration_lagged(v * t, H, a, c_wing)

    @_grids_kept
    def tail(t):
        return penetration_lagged(v * (t - lag), H, a, c_tail)

    gusts = {"gust_wing": Function(wing, time_grid=True), "gust_tail": Function(tail, time_grid=True)}
    parts, sim, dt = two_phase_run(
        gb.model, gb.x0, gb.u0, H, v, lag, gusts, steps_per_gust, settle, max_step, settle_step
    )
    felt: dict[str, list] = {"wing": [], "horizontal_tail": []}  # the gust angles of each phase, on its own times
    nt, slices = phase_records(parts)
    hist: dict[str, np.ndarray] = {}
    kept: dict[str, tuple[np.ndarray, np.ndarray]] = {}
    fuel: dict[str, list] = {}
    for k, (part, (keep, rows)) in enumerate(zip(parts, slices)):  # loads per phase (rate derivatives in its step)
        tp = phase_times(parts, k)
        extra = {"wing": wing(tp), "horizontal_tail": tail(tp)}
        for s, angles in extra.items():
            felt[s].append(angles[keep])
        terms = inertia_terms(part, gb.model)  # the loads' and the fuel's
        L = response_load_parts(
            loads, part, gb.model, surfaces, extra_alpha={s: extra[s] for s in surfaces if s in extra}, terms=terms
        )
        for s, (aero, inertia) in L.items():
            hist[s] = phase_into(hist.get(s), nt, keep, rows, aero, inertia)
            if s in split:
                if s not in kept:
                    kept[s] = (np.empty(hist[s].shape), np.empty(hist[s].shape))
                kept[s][0][rows], kept[s][1][rows] = aero[keep], inertia[keep]
                tables = loads[s].fuel_term_tables(terms)
                if tables is not None:
                    fuel.setdefault(s, []).append((tables[0][keep], tables[1]))
    return GustRun(
        sim,
        hist,
        {s: np.concatenate(v_) for s, v_ in felt.items()},  # on the run's times (the phases' times, concatenated)
        dt,
        kept,
        {s: (np.concatenate([x for x, _ in v_]), v_[0][1]) for s, v_ in fuel.items()},
    )


def _grids_kept(f):
    """``f`` of a time grid, the values of its last two grids kept: the gust phase's run evaluates the gust on its
    grid of times (and the free phase's run on its own), then the loads read it again on the gust phase's records'
    times — the same values, not computed twice."""
    kept: list[tuple[np.ndarray, np.ndarray]] = []

    def at(t):
        t = np.asarray(t, dtype=float)
        for grid, values in kept:
            if grid.shape == t.shape and grid.tobytes() == t.tobytes():
                return values
        kept[:] = kept[-1:] + [(t.copy(), f(t))]
        return kept[-1][1]

    return at


def two_phase_run(
    model, x0, u0, H: float, v, lag, inputs, steps_per_gust: float, settle: float, max_step: float, settle_step: float
):
    """A gust run in two phases: while the gust of gradient ``H`` crosses the airplane (reaching its last surface
    ``lag`` (n,) s after the first), each condition resolving the gust in its own length 2H/V in ``steps_per_gust``
    steps (at most ``max_step``; the same number of steps for all); then ``settle`` seconds of free response at
    ``settle_step`` (the longest gradients' own step: the short-period motion left, ω ≈ 1–3 rad/s, needs no finer;
    tests/loads/test_gust_settle_step.py), the inputs going on there on the run's clock, each held at its value in the
    middle of the step (a gust whose lift lags, Küssner's function, still lifts after it has passed, decaying within a
    few of the coarse steps: the midpoint keeps that hold second-order). Returns the phases, their concatenation and
    the smallest step."""
    dt = np.minimum(max_step, 2 * H / v / steps_per_gust)
    steps = float(np.ceil(np.max((2 * H / v + lag) / dt)))
    if np.ptp(dt) == 0.0:
        dt = float(dt[0])
    first = simulate(model, x0, u0, steps * dt, dt, inputs=inputs)
    parts = [first]
    if settle > 0:
        step = max(float(np.min(dt)), settle_step)
        mid = _per_condition(first.t)[-1] + 0.5 * step  # each input held at its value in the middle of the step

        def later(f):
            def at(t):  # a time, or a grid (nt,) or (nt, n), on the free phase's clock
                t = np.asarray(t, dtype=float)
                return f((t[:, None] if t.ndim == 1 else t) + mid)

            return Function(at, time_grid=True)

        after = {name: later(f) for name, f in inputs.items()}
        parts.append(simulate(model, first.final_state, u0, settle, step, inputs=after))
    return parts, _concatenate(parts), float(np.min(dt))


def phase_records(parts) -> tuple[int, list[tuple[slice, slice]]]:
    """The records of a run of :func:`two_phase_run`'s ``parts``: their number, and per phase the records it keeps
    (a later phase's first repeats the last one) and where they go in the run's."""
    slices, start = [], 0
    for k, part in enumerate(parts):
        count = part.t.shape[0] - (k > 0)
        slices.append((slice(None) if k == 0 else slice(1, None), slice(start, start + count)))
        start += count
    return start, slices


def phase_into(hist, nt: int, keep: slice, rows: slice, aero: np.ndarray, inertia: np.ndarray) -> np.ndarray:
    """The run's station-load history ``hist`` ((nt, …), made at the first phase when None) with one phase's loads,
    aerodynamic plus inertial, written in place: its records ``keep`` at the run's ``rows`` (:func:`phase_records`)."""
    if hist is None:
        hist = np.empty((nt,) + aero.shape[1:])
    np.add(aero[keep], inertia[keep], out=hist[rows])
    return hist


def phase_times(parts, k: int) -> np.ndarray:
    """The times of phase ``k`` of :func:`two_phase_run` on the run's clock, (nt, n) or (nt, 1)."""
    return _per_condition(parts[k].t) + (parts[0].t[-1] if k else 0.0)


def _per_condition(t):
    """A time grid as (nt, n) or (nt, 1) for broadcasting over the conditions."""
    return t if t.ndim == 2 else t[:, None]


def _concatenate(parts):
    """One :class:`SimulationResult` from consecutive runs (each after the first starts where the previous
    ended; its first record, a repeat, is dropped)."""
    if len(parts) == 1:
        return parts[0]
    n = parts[0].stop_time.shape[0]
    if any(p.t.ndim == 2 for p in parts):  # a time step per condition in some phase: every grid (nt, n)

        def grid(p):
            return np.broadcast_to(_per_condition(p.t), (p.t.shape[0], n))
    else:

        def grid(p):
            return p.t

    t, ctrl = [grid(parts[0])], [parts[0].controls]
    offset = grid(parts[0])[-1]
    for p in parts[1:]:
        t.append(grid(p)[1:] + offset)
        ctrl.append(p.controls[1:])
        offset = offset + grid(p)[-1]
    last = parts[-1]
    return SimulationResult(
        np.concatenate(t),
        Histories.joined([p.history for p in parts]),
        np.concatenate(ctrl),
        parts[0].control_names,
        parts[0].stop_time,
        parts[0].stop_reason,
        last.final_state,
    )
