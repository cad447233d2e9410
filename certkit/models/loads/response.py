"""Loads along a simulated response: time histories per condition, envelopes and critical cases.

:func:`response_loads` turns the recorded histories of a batch simulation
(:func:`certkit.models.dynamics.simulate.simulate`) into station loads of each surface at every time
step; :class:`LoadEnvelope` keeps, across the conditions, the maximum and minimum of every station
and quantity with the condition and time where it occurs (a loads engineer's critical-case list),
and the conditions that could not be simulated with the reason (DLR Loads Kernel style).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numba import njit

from certkit.models.aero.airplane import FLAP_CONTROL
from certkit.models.aero.interface import AeroState
from certkit.models.loads.model import QUANTITIES, UNITS, AirplaneLoads
from certkit.units import G0


def _rates_dot(t, x):
    """d/dt of the histories x (nt, n) on the time grid t: (nt,), or (nt, n) uniform per condition — ``np.gradient``
    along time (central differences inside, one-sided at the ends), its arithmetic in one compiled pass."""
    x = np.ascontiguousarray(x, dtype=float)
    if x.shape[0] < 2:
        return np.zeros_like(x)
    out = np.empty_like(x)
    if t.ndim == 2:  # np.gradient(x, axis=0) / (t[1] − t[0])
        _central_differences(x, 1.0, np.ascontiguousarray(t[1] - t[0], dtype=float), out)
        return out
    dt = np.diff(np.asarray(t, dtype=float))
    if (dt == dt[0]).all():  # numpy's uniform spacing: one step (dividing by 1 changes no bit)
        _central_differences(x, float(dt[0]), np.ones(x.shape[1]), out)
    else:
        _uneven_differences(x, dt, out)
    return out


@njit(cache=True)
def _central_differences(x, h, per_column, out):
    """out = np.gradient(x, h, axis=0) (x (nt ≥ 2, n)) divided by ``per_column`` (n,)."""
    nt, n = x.shape
    for j in range(n):
        out[0, j] = (x[1, j] - x[0, j]) / h / per_column[j]
        out[nt - 1, j] = (x[nt - 1, j] - x[nt - 2, j]) / h / per_column[j]
    for k in range(1, nt - 1):
        for j in range(n):
            out[k, j] = (x[k + 1, j] - x[k - 1, j]) / (2.0 * h) / per_column[j]


@njit(cache=True)
def _uneven_differences(x, dt, out):
    """out = np.gradient(x, t, axis=0) for the steps dt = diff(t) (nt − 1,), not all equal: numpy's second-order
    weights inside, one-sided differences at the ends."""
    nt, n = x.shape
    for j in range(n):
        out[0, j] = (x[1, j] - x[0, j]) / dt[0]
        out[nt - 1, j] = (x[nt - 1, j] - x[nt - 2, j]) / dt[nt - 2]
    for k in range(1, nt - 1):
        dx1, dx2 = dt[k - 1], dt[k]
        a = -(dx2) / (dx1 * (dx1 + dx2))
        b = (dx2 - dx1) / (dx1 * dx2)
        c = dx1 / (dx2 * (dx1 + dx2))
        for j in range(n):
            out[k, j] = a * x[k - 1, j] + b * x[k, j] + c * x[k + 1, j]


def times_at(t, k) -> np.ndarray:
    """The times of record indices ``k`` (n, ...) of each condition (axis 0 of ``k`` the conditions) on the grid
    ``t``: (nt,), or (nt, n) with a time step per condition."""
    if t.ndim == 1:
        return t[k]
    cols = np.arange(k.shape[0]).reshape((-1,) + (1,) * (k.ndim - 1))
    return t[k, cols]


def response_load_parts(
    loads: AirplaneLoads, sim, model, surfaces=("horizontal_tail",), extra_alpha=None, extra_beta=None, terms=None
) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """Aerodynamic and inertial station loads, each (nt, n, 3, n_stations), of each of ``surfaces`` along the
    simulation ``sim`` of the flight model ``model`` (its CGs and reference lengths).

    ``extra_alpha`` / ``extra_beta``: surface name → (nt, n) angle-of-attack / sideslip increment felt by that
    surface only (a vertical / lateral gust). ``terms``: the run's :func:`inertia_terms` when the caller has them."""
    h = sim.history
    V = np.maximum(h["V"], 1e-3)
    b, c = model.b, model.c
    names = list(sim.control_names)
    controls = {n: sim.controls[:, :, names.index(n)] for n in names if ":" not in n and n != "brake"}
    flap = flap_deflection(loads, model, h["mach"])
    terms = inertia_terms(sim, model) if terms is None else terms
    out = {}
    for name in surfaces:
        s = loads[name]
        alpha = h["alpha"] + (extra_alpha or {}).get(name, 0.0)
        inputs = {
            "alpha": alpha,
            "beta": h["beta"] + (extra_beta or {}).get(name, 0.0),
            "p_hat": h["p"] * b / (2 * V),
            "q_hat": h["q"] * c / (2 * V),
            "r_hat": h["r"] * b / (2 * V),
            **controls,
        }
        if name in flap:
            inputs[FLAP_CONTROL] = flap[name]
        out[name] = (s.aero_loads(h["qbar"], h["mach"], inputs), s.inertia_loads(terms))
    return out


def flap_deflection(loads: AirplaneLoads, model, mach) -> dict[str, np.ndarray]:
    """The lattice flap deflection (rad, shaped like ``mach``) of each lifting surface's strips such that the wing
    carries the flight model's flap lift increment (``model.aero.flap_lift``: tail off) and the horizontal tail its
    share from the change of downwash: the lattice gives where on the span the flap lift acts and how the tail's load
    is spread, the configuration's increments (declared, or Raymer's estimate and the finer downwash lattice of
    :mod:`certkit.models.aero.airplane`) how much there is (linear theory over-states a large deflection's lift, and
    the strip lattice's 20-odd wing strips over-state the flap's downwash at the tail by up to 60 %). Empty when the
    model has no flap lift or the loads model no flap."""
    aero = model.aero
    lift = getattr(aero, "flap_lift", None)
    if lift is None or not np.any(lift) or not _wing_has_flap(loads):
        return {}
    mach = np.asarray(mach, dtype=float)
    out = {}
    for name, row in (("wing", 0), ("horizontal_tail", 1)):
        s = loads.surfaces.get(name)
        if s is not None and FLAP_CONTROL in s.inputs:
            half = 0.5 * np.interp(mach, aero.mach, lift[row]) * aero.reference.area
            out[name] = s.input_for_lift(FLAP_CONTROL, half, mach) if np.any(half) else np.zeros_like(mach)
    return out


def holds_flap_lift(loads: AirplaneLoads, model) -> bool:
    """Whether the strip model's wing carries the flight model's flap lift (:func:`flap_deflection`): none to carry,
    or a wing flap in the loads model to spread it with."""
    lift = getattr(model.aero, "flap_lift", None)
    return lift is not None and (not np.any(lift) or _wing_has_flap(loads))


def _wing_has_flap(loads: AirplaneLoads | None) -> bool:
    """Whether the loads model's wing has the lattice's flap as an input."""
    wing = loads.surfaces.get("wing") if loads is not None else None
    return wing is not None and FLAP_CONTROL in wing.inputs


def inertia_terms(sim, model) -> dict[str, np.ndarray]:
    """The inertial terms (:data:`certkit.models.loads.model.INERTIA_TERMS`), each (nt, n), along the simulation
    ``sim``: load factors and the body angular accelerations (differentiated on the record's time grid)."""
    h, t = sim.history, sim.t
    qdot, pdot, rdot = _rates_dot(t, h["q"]), _rates_dot(t, h["p"]), _rates_dot(t, h["r"])
    xcg, zcg = model.cg[:, 0][None, :], model.cg[:, 2][None, :]
    return {
        "n_z": h["n_z"],
        "qdot_xcg": qdot * xcg,
        "qdot": qdot,
        "n_y": h["n_y"],
        "rdot_xcg": rdot * xcg,
        "rdot": rdot,
        "pdot_zcg": pdot * zcg,
        "pdot": pdot,
    }


def fuel_load_units(loads: AirplaneLoads, sim, model, surface: str = "wing") -> tuple[np.ndarray, np.ndarray] | None:
    """The fuel's inertial loading of ``surface`` along ``sim``, uncontracted: the inertial terms (nt, n, J) and their
    per-kilogram tables (K, J, 3, S) (:meth:`SurfaceLoads.fuel_term_tables`); None without tanks."""
    return loads[surface].fuel_term_tables(inertia_terms(sim, model))


def with_fuel_states(total: np.ndarray, units: np.ndarray | None, fuel: np.ndarray | None) -> np.ndarray:
    """Station loads (..., n, 3, S) without fuel plus each fuel state's: (M, ..., n, 3, S) for the fuel states
    ``fuel`` (n, M, K) kg per condition, state and tank and the per-kilogram loads ``units`` (..., n, K, 3, S). Without
    tanks or states: ``total`` with a leading axis of one."""
    if units is None or fuel is None or fuel.shape[1] == 0:
        return np.asarray(total)[None]
    return np.asarray(total)[None] + np.einsum("...nkqs,nmk->m...nqs", units, fuel)


def fuel_state_peaks(
    total: np.ndarray, fuel_terms: tuple[np.ndarray, np.ndarray] | None, fuel: np.ndarray | None
) -> np.ndarray:
    """Per fuel state, the minimum and maximum over time of station loads: (M, n, 2, 3, S) from the loads without
    fuel ``total`` (nt, n, 3, S), the fuel's inertial loading ``fuel_terms`` — the terms (nt, n, J) and their
    per-kilogram tables (K, J, 3, S), :func:`fuel_load_units` — and the fuel states ``fuel`` (n, M, K) kg. The states
    are contracted with the small tables first, then one compiled pass over the histories gives every state's
    extremes (NaN times ignored, as :meth:`LoadEnvelope.from_histories` does; all-NaN stays NaN). Without tanks or
    states: one state, the loads as they are."""
    if fuel_terms is None or fuel is None or fuel.shape[1] == 0:
        return np.stack([np.fmin.reduce(total, axis=0), np.fmax.reduce(total, axis=0)], axis=1)[None]
    x, tables = fuel_terms
    nt, n = total.shape[:2]
    q = int(np.prod(total.shape[2:]))
    per_state = np.einsum("nmk,kjq->nmjq", fuel, tables.reshape(tables.shape[0], tables.shape[1], q))
    # the conditions innermost (contiguous: the compiled loops run over them in vector registers)
    lo_hi = np.empty((2, fuel.shape[1], q, n))
    _fuel_state_peaks(
        np.ascontiguousarray(np.asarray(total, dtype=float).reshape(nt, n, q).transpose(0, 2, 1)),
        np.ascontiguousarray(np.broadcast_to(x, (nt, n, x.shape[-1])).transpose(0, 2, 1), dtype=float),
        np.ascontiguousarray(per_state.transpose(1, 2, 3, 0)),
        lo_hi,
    )
    return lo_hi.transpose(1, 3, 0, 2).reshape((fuel.shape[1], n, 2) + total.shape[2:])


@njit(cache=True)
def _fuel_state_peaks(total, terms, per_state, lo_hi):
    """lo_hi[0/1, m, j, i] = min/max over t of total[t, j, i] + Σ_k terms[t, k, i] per_state[m, k, j, i], NaN skipped:
    each state's load of one time formed for every condition at once, the terms added in the order of k."""
    nt, q, n = total.shape
    n_states, n_terms = per_state.shape[0], per_state.shape[1]
    lo, hi = lo_hi[0], lo_hi[1]
    lo[:] = np.inf
    hi[:] = -np.inf
    v = np.empty(n)
    for t in range(nt):
        for m in range(n_states):
            for j in range(q):
                for i in range(n):
                    v[i] = total[t, j, i]
                for k in range(n_terms):
                    for i in range(n):
                        v[i] += terms[t, k, i] * per_state[m, k, j, i]
                for i in range(n):
                    x = v[i]
                    if x < lo[m, j, i]:
                        lo[m, j, i] = x
                    if x > hi[m, j, i]:
                        hi[m, j, i] = x
    for m in range(n_states):
        for j in range(q):
            for i in range(n):
                if lo[m, j, i] > hi[m, j, i]:  # every time NaN
                    lo[m, j, i] = np.nan
                    hi[m, j, i] = np.nan


def response_loads(
    loads: AirplaneLoads, sim, model, surfaces=("horizontal_tail",), extra_alpha=None, valid=None
) -> dict[str, np.ndarray]:
    """Station loads (nt, n, 3, n_stations) of each of ``surfaces`` along the simulation ``sim``: the sum of
    :func:`response_load_parts`. ``valid``: (nt, n) booleans; loads outside are set to NaN (times after a stop
    criterion or beyond the time the paragraph asks to consider)."""
    return summed_loads(response_load_parts(loads, sim, model, surfaces, extra_alpha), valid)


def summed_loads(parts: dict[str, tuple[np.ndarray, np.ndarray]], valid=None) -> dict[str, np.ndarray]:
    """:func:`response_loads` from the (aerodynamic, inertial) ``parts`` of :func:`response_load_parts` (for a caller
    that also keeps the parts)."""
    out = {}
    for name, (aero, inertia) in parts.items():
        total = aero + inertia
        if valid is not None:
            total = np.where(valid[:, :, None, None], total, np.nan)
        out[name] = total
    return out


def below_stall(model, sim) -> np.ndarray | None:
    """(nt, n) booleans: True where the linear lift coefficient of the airplane along ``sim`` (its aerodynamics
    without the stall model) is at or below the stall model's CLmax — the times at which strip loads, linear in α,
    represent the airplane's lift; past the stall the airplane's lift is rounded onto CLmax and the linear strips
    overstate it. None when the aerodynamics have no stall model."""
    aero = model.aero
    if getattr(aero, "stall", None) is None or not hasattr(aero, "without_stall"):
        return None
    h = sim.history
    V = np.maximum(h["V"], 1e-3)
    names = list(sim.control_names)
    controls = {n: sim.controls[:, :, names.index(n)] for n in aero.control_names if n in names}
    state = AeroState(
        alpha=h["alpha"],
        beta=h["beta"],
        p_hat=h["p"] * model.b / (2 * V),
        q_hat=h["q"] * model.c / (2 * V),
        r_hat=h["r"] * model.b / (2 * V),
        mach=h["mach"],
        controls=controls,
    )
    return aero.without_stall().coefficients(state).CL <= aero.clmax(h["mach"])


def time_extremes(L: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The record index of the minimum and of the maximum over time (axis 0) of histories ``L`` (nt ≥ 1, n, ...), NaN
    skipped, the first of equal extremes (index 0 where every time is NaN), and those extremes (n, 2, ...): min [0],
    max [1] (NaN where every time is NaN). One compiled pass over the histories; the same indices and values as
    ``np.argmin``/``np.argmax`` of the histories with NaN filled by ±inf."""
    nt, rest = L.shape[0], L.shape[1:]
    if nt == 0:
        raise ValueError("no records: the extremes over time of an empty history are undefined")
    flat = np.ascontiguousarray(L, dtype=float).reshape(nt, -1)
    m = flat.shape[1]
    ilo, ihi = np.zeros(m, dtype=np.int64), np.zeros(m, dtype=np.int64)
    out = np.empty((2, m))
    _time_extremes(flat, ilo, ihi, out)
    peaks = np.ascontiguousarray(np.moveaxis(out.reshape((2,) + rest), 0, 1))
    return ilo.reshape(rest), ihi.reshape(rest), peaks


@njit(cache=True)
def _time_extremes(L, ilo, ihi, out):
    """ilo/ihi[j] = first t of the smallest/largest non-NaN L[t, j] (0 if none); out[0/1, j] = L at them."""
    nt, m = L.shape
    lo = np.full(m, np.inf)
    hi = np.full(m, -np.inf)
    for t in range(nt):
        for j in range(m):
            v = L[t, j]
            if v < lo[j]:
                lo[j] = v
                ilo[j] = t
            if v > hi[j]:
                hi[j] = v
                ihi[j] = t
    for j in range(m):
        out[0, j] = L[ilo[j], j]
        out[1, j] = L[ihi[j], j]


@dataclass
class CriticalCase:
    surface: str
    station: str
    quantity: str
    sense: str  # "max" or "min"
    value: float
    unit: str
    condition: int  # index into the envelope's conditions
    time: float


@dataclass
class LoadEnvelope:
    """Max/min of each surface, quantity and station over the time histories of every condition.

    ``peaks[surface]`` is (n_conditions, 2, 3, n_stations): per condition the minimum [0] and maximum
    [1] over time; ``times`` the same shape, when they occur. ``failed`` lists (condition index,
    reason) of conditions that could not be simulated."""

    stations: dict[str, tuple[str, ...]]
    peaks: dict[str, np.ndarray]
    times: dict[str, np.ndarray]
    labels: list[str]
    failed: list[tuple[int, str]] = field(default_factory=list)
    #: an identity per condition row that the caller passes and this model does not interpret (a rule passes its
    #: conditions, so that a design loop can find which conditions set the envelope); empty when not given
    keys: list = field(default_factory=list)

    @classmethod
    def from_histories(
        cls, loads: AirplaneLoads, histories: dict[str, np.ndarray], t: np.ndarray, labels, failed=(), keys=None
    ) -> "LoadEnvelope":
        peaks, times = {}, {}
        for name, L in histories.items():
            ilo, ihi, peaks[name] = time_extremes(L)
            times[name] = np.stack([times_at(t, ilo), times_at(t, ihi)], axis=1)
        return cls(
            {k: loads[k].station_names for k in histories},
            peaks,
            times,
            list(labels),
            list(failed),
            list(keys) if keys is not None else [],
        )

    @classmethod
    def merge(cls, parts: list["LoadEnvelope"]) -> "LoadEnvelope":
        """One envelope over several batches (conditions appended in order)."""
        parts = [p for p in parts if p is not None]
        labels, failed = [], []
        peaks: dict[str, list] = {}
        times: dict[str, list] = {}
        stations = {}
        for p in parts:
            offset = len(labels)
            labels += p.labels
            failed += [(i + offset, r) for i, r in p.failed]
            for k in p.peaks:
                peaks.setdefault(k, []).append(p.peaks[k])
                times.setdefault(k, []).append(p.times[k])
                stations[k] = p.stations[k]
        keyed = all(len(p.keys) == len(p.labels) for p in parts)
        return cls(
            stations,
            {k: np.concatenate(v) for k, v in peaks.items()},
            {k: np.concatenate(v) for k, v in times.items()},
            labels,
            failed,
            [key for p in parts for key in p.keys] if keyed else [],
        )

    @classmethod
    def worst_of(cls, parts: list["LoadEnvelope"]) -> tuple["LoadEnvelope", dict[str, np.ndarray]]:
        """One envelope over several runs of the same conditions (e.g. one per gust gradient): per
        condition the lowest minimum and highest maximum; also, per surface, the index of the run each
        extreme comes from ((n, 2, 3, S) integers)."""
        first = parts[0]
        peaks, times, which = {}, {}, {}
        for k in first.peaks:
            P = np.stack([p.peaks[k] for p in parts])  # (nr, n, 2, 3, S)
            T = np.stack([p.times[k] for p in parts])
            lo = np.argmin(np.where(np.isnan(P[:, :, 0]), np.inf, P[:, :, 0]), axis=0)
            hi = np.argmax(np.where(np.isnan(P[:, :, 1]), -np.inf, P[:, :, 1]), axis=0)
            w = np.stack([lo, hi], axis=1)
            which[k] = w
            peaks[k] = np.take_along_axis(P, w[None], axis=0)[0]
            times[k] = np.take_along_axis(T, w[None], axis=0)[0]
        return cls(dict(first.stations), peaks, times, list(first.labels), list(first.failed), list(first.keys)), which

    def extreme(self, surface: str, quantity: str, station: int = 0, sense: str = "max") -> tuple[float, int]:
        """The extreme (value, condition index) of one quantity at one station over all conditions."""
        q = QUANTITIES.index(quantity)
        col = self.peaks[surface][:, 1 if sense == "max" else 0, q, station]
        if np.all(np.isnan(col)):
            return float("nan"), -1
        i = int(np.nanargmax(col) if sense == "max" else np.nanargmin(col))
        return float(col[i]), i

    def critical_cases(self) -> list[CriticalCase]:
        """For every surface, station, quantity and sense: the critical condition and time."""
        out = []
        for name, _P in self.peaks.items():
            for s, station in enumerate(self.stations[name]):
                for q, quantity in enumerate(QUANTITIES):
                    for sense in ("max", "min"):
                        value, i = self.extreme(name, quantity, s, sense)
                        if i < 0:
                            continue
                        tt = float(self.times[name][i, 1 if sense == "max" else 0, q, s])
                        out.append(CriticalCase(name, station, quantity, sense, value, UNITS[quantity], i, tt))
        return out

    def table(self, surface: str | None = None) -> list[dict]:
        """The critical-case table (rows for the report)."""
        rows = []
        for c in self.critical_cases():
            if surface and c.surface != surface:
                continue
            rows.append(
                {
                    "surface": c.surface,
                    "station": c.station,
                    "quantity": c.quantity,
                    "sense": c.sense,
                    "value": _fmt(c.value, c.unit),
                    "condition": self.labels[c.condition],
                    "time_s": round(c.time, 3),
                }
            )
        return rows


def _fmt(value: float, unit: str) -> str:
    if unit == "N":
        return f"{value / 1e3:,.1f} kN"
    return f"{value / 1e3:,.1f} kN·m"


def load_factor_at(n_z, qdot, x_cg, x):
    """Rigid-body normal load factor at airplane station X (m) for load factor n_z at a CG at X_cg."""
    return n_z + qdot * (x_cg - x) / G0
