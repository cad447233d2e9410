"""The §25.341(a) discrete vertical gust runs shared by §25.341(a), §25.349(b) and §25.427(b) (regulation content, no
rule here): the gust criteria, the condition space, U_ds = U_ref F_g (H/350)^(1/6) and the batched 1 − cos gust
simulations, memoised in the context so that the rules evaluated in one process (``run_with = "discrete-gust"``)
simulate them once. The formulas' sources and verification status are in :mod:`certkit_rules.part25.subpart_c.r25_341`.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from certkit_rules.part25.support.fuel_states import fuel_state_table
from certkit_rules.part25.support.gust import SOURCE as UREF_SOURCE
from certkit_rules.part25.support.gust import reference_gust_velocity
from certkit_rules.part25.support.loads_conditions import trimmed_batch

from certkit.engine.conditions import CgCorners, ConditionSpace, EnvelopeAltitudes
from certkit.engine.registry import Criterion
from certkit.models.loads.gust_response import SURFACES, gust_batch, simulate_gust
from certkit.models.loads.model import airplane_loads
from certkit.models.loads.response import LoadEnvelope, fuel_state_peaks
from certkit.units import FT

AC = "FAA AC 25.341-1 via secondary sources; formula UNVERIFIED against the CFR (docs/regulation-notes.md §4)"
SPEEDS = ("VB", "VC", "VD")


def flight_profile_alleviation(aircraft, altitude, crit) -> float:
    """F_g at ``altitude`` (m): 0.5 (F_gz + F_gm) at sea level, F_gz = 1 − Z_mo/250 000 ft,
    F_gm = √(R2 tan(π R1/4)), R1 = MLW/MTOW, R2 = MZFW/MTOW, rising linearly to 1 at Z_mo (the ceiling)."""
    m = aircraft.mass
    zmo = aircraft.envelope.ceiling
    r1, r2 = m.MLW / m.MTOW, m.MZFW / m.MTOW
    fgz = 1.0 - zmo / (crit.fgz_altitude * FT)
    fgm = np.sqrt(r2 * np.tan(np.pi * r1 / 4.0))
    fg0 = 0.5 * (fgz + fgm)
    return float(fg0 + (1.0 - fg0) * min(max(altitude / zmo, 0.0), 1.0))


def design_gust_velocity(u_ref, f_g, H, crit):
    """U_ds = U_ref F_g (H / 350 ft)^(1/6) (same unit as U_ref; H in m)."""
    return u_ref * f_g * (np.asarray(H) / (crit.gradient_reference * FT)) ** crit.gradient_exponent


def gradients(crit) -> np.ndarray:
    """The gust gradients H (m) of the criterion, each within 30–350 ft."""
    values = np.array([float(v) for v in str(crit.gradients).replace(",", " ").split()])
    if values.size == 0 or values.min() < crit.gradient_min - 1e-9 or values.max() > crit.gradient_max + 1e-9:
        raise ValueError(
            f"gust gradients {values.tolist()} ft must lie within {crit.gradient_min}–{crit.gradient_max} ft"
        )
    return values * FT


def gust_speeds(ctx, h: float) -> dict[str, float]:
    """EAS (m/s) of VB, VC, VD at altitude h, Mach-limited; VB capped at VC."""
    vc = ctx.design_speed_eas_at("VC", h)
    return {
        "VB": min(ctx.design_speed_eas_at("VB", h), vc),
        "VC": vc,
        "VD": ctx.design_speed_eas_at("VD", h),
    }


#: the criteria that define the gust runs (shared by §25.349(b), which modifies the §25.341(a) conditions, and by
#: §25.427(b), which splits their tail loads)
GUST_RUN_CRITERIA = {
    "gradients": Criterion(
        "30 60 100 150 200 250 300 350",
        "ft",
        "14 CFR 25.341(a)(3) (verified: 'a sufficient number … in the range 30 feet to 350 feet')",
        "gust gradient distances H investigated",
    ),
    "gradient_min": Criterion(30.0, "ft", "14 CFR 25.341(a)(3)", "shortest gust gradient"),
    "gradient_max": Criterion(350.0, "ft", "14 CFR 25.341(a)(3)", "longest gust gradient"),
    "gradient_reference": Criterion(350.0, "ft", "14 CFR 25.341(a)(4), " + AC, "H of U_ds = U_ref F_g"),
    "gradient_exponent": Criterion(1 / 6, "", "14 CFR 25.341(a)(4), " + AC, "exponent of H/350"),
    "fgz_altitude": Criterion(250_000.0, "ft", "14 CFR 25.341(a)(6), " + AC, "F_gz = 1 − Z_mo / this"),
    "vd_factor": Criterion(0.5, "", "14 CFR 25.341(a)(5)(ii) (wording UNVERIFIED)", "U_ref at VD / U_ref (a)(5)(i)"),
    "steps_per_gust": Criterion(
        20, "", "certkit numerical choice (zero-order hold of the gust)", "simulation steps per gust length 2H/V"
    ),
    "settle_time": Criterion(1.5, "s", "certkit numerical choice", "time simulated after the gust leaves the tail"),
}
GUST_CRITERIA = tuple(GUST_RUN_CRITERIA)
#: what the gust runs need from the aircraft file
GUST_REQUIRES = ("speeds.VB", "speeds.VC", "speeds.VD", "geometry.horizontal_tail")
#: the conditions of the gust runs (§25.341(a), and §25.349(b) which modifies them)
GUST_CONDITIONS = ConditionSpace(
    loading=CgCorners(),
    configurations=("clean",),
    altitudes=EnvelopeAltitudes(),
    extra=(("speed_point", SPEEDS), ("gust", ("up", "down"))),
    note="VB (capped at VC), VC and VD in EAS, each Mach-limited at altitude; U_ref "
    "by altitude (" + UREF_SOURCE + "), F_g from the ceiling as Z_mo.",
)


@dataclass
class GustRuns:
    """The §25.341(a) gust runs of a set of conditions: per gust gradient (``gradients``) the symmetric load
    envelope, the extreme load factors, U_ds, and the wing's aerodynamic and inertial load histories (for the
    unsymmetrical gusts of §25.349(b)); the scheduled conditions that could not be trimmed with the reason."""

    refused: list  # Refusal of the scheduled conditions without a steady flight
    conditions: list  # the simulated (refined) conditions
    gradients: np.ndarray  # m
    envelopes: list  # LoadEnvelope per gradient
    nz_hi: np.ndarray  # (n_gradients, n)
    nz_lo: np.ndarray
    uds: np.ndarray  # (n_gradients, n) m/s EAS
    wing: list  # per gradient (t, aero, inertia) of the right half wing, (nt, n, 3, S) each; empty without its loads
    u_ref: np.ndarray = None
    f_g: np.ndarray = None
    v_eas: np.ndarray = None
    up: np.ndarray = None
    altitude: np.ndarray = None
    batch: object = None  # GustBatch of the simulated conditions
    loads: object = None  # AirplaneLoads
    steps_per_gust: float = 20.0
    settle_time: float = 1.5
    tail: list = None  # per gradient (t, aero, inertia) of the right half tailplane (§25.427(b)), like ``wing``
    #: the wing's loads in each fuel state of §25.343 (:mod:`certkit_rules.part25.support.fuel_states`): per state
    #: the minimum and maximum over time and every gradient, (M, n, 2, 3, S); the states' names and (n, M, K) kg
    wing_fuel_peaks: np.ndarray = None
    fuel_names: list = None
    fuel: np.ndarray = None

    @cached_property
    def symmetric(self) -> tuple[LoadEnvelope, dict]:
        """The envelope over every gradient and which gradient each extreme comes from (:meth:`LoadEnvelope.worst_of`),
        computed once for the rules that share the runs."""
        return LoadEnvelope.worst_of(self.envelopes)

    def replay(self, picks):
        """Re-simulate the (condition index, gradient index) pairs with their histories (evidence)."""
        out = []
        for i, j in picks:
            H = self.gradients[j]
            alpha = (1.0 if self.up[i] else -1.0) * self.uds[j, i] / self.v_eas[i]
            out.append(
                (
                    i,
                    H,
                    simulate_gust(
                        self.loads,
                        self.batch.subset([i]),
                        H,
                        alpha,
                        self.steps_per_gust,
                        self.settle_time,
                        split=("wing",),
                    ),
                )
            )
        return out


def gust_runs(ctx, conditions, crit, surfaces=SURFACES) -> GustRuns:
    """The gust runs of ``conditions`` with the loads of ``surfaces`` (the wing and the horizontal tail, or the tail
    alone), memoised on the conditions, the surfaces and the gust criteria (so that §25.341(a) and §25.349(b),
    evaluated in one process, simulate once)."""
    key = ("discrete_gust_runs", tuple(conditions), tuple(surfaces), tuple((k, str(crit[k])) for k in GUST_CRITERIA))
    return ctx.memo(key, lambda: _simulate_gust_runs(ctx, conditions, crit, tuple(surfaces)))


def _simulate_gust_runs(ctx, conditions, crit, surfaces=SURFACES) -> GustRuns:
    """The §25.341(a) runs: each condition at its speed point, U_ds = U_ref F_g (H/350)^(1/6) at every gradient."""

    def u_ref(conds):
        at_vd = np.array([c.get("speed_point") == "VD" for c in conds])
        return reference_gust_velocity(np.array([c.altitude for c in conds])) * np.where(at_vd, crit.vd_factor, 1.0)

    def f_g(conds):
        return np.array([flight_profile_alleviation(ctx.aircraft, c.altitude, crit) for c in conds])

    def design_velocity(conds, H):
        u, f = u_ref(conds), f_g(conds)
        return [design_gust_velocity(u, f, h_gust, crit) for h_gust in H]

    runs = simulate_gust_set(
        ctx,
        conditions,
        lambda c: gust_speeds(ctx, c.altitude)[c.get("speed_point")],
        design_velocity,
        gradients(crit),
        crit,
        surfaces,
    )
    runs.u_ref, runs.f_g = u_ref(runs.conditions), f_g(runs.conditions)
    return runs


def level_flight_batch(ctx, conditions, speed_of):
    """``conditions`` (one configuration) trimmed in level flight at ``speed_of(condition)`` (EAS, m/s), those of one
    loading, altitude and speed sharing a trim: (the trimmed batch, the batch rows of the conditions that trimmed, their
    refined conditions, the :class:`Refusal` of the others), as :meth:`TrimmedBatch.distribute` gives them."""
    entries, key_of, entry_of = [], {}, {}
    for c in conditions:
        v = float(speed_of(c))
        key = (c.loading, c.altitude, round(v, 6))
        if key not in key_of:
            key_of[key] = len(entries)
            entries.append(c.with_(speed=v, speed_kind="EAS", speed_name=None, gust=None))
        entry_of[c] = key_of[key]
    batch = trimmed_batch(ctx, entries)
    return (batch, *batch.distribute(conditions, entry_of.__getitem__, [e.speed for e in entries]))


def simulate_gust_set(ctx, conditions, speed_of, design_velocity, H, crit, surfaces=SURFACES) -> GustRuns:
    """The 1 − cos vertical gusts of ``conditions`` (one configuration), each trimmed in level flight at
    ``speed_of(condition)`` (EAS, m/s), at every gradient of ``H`` (m) with the design gust velocities
    ``design_velocity(simulated conditions, H) -> (gradients, n)`` (EAS, m/s), up or down as the condition's ``gust``
    says; ``crit`` holds ``steps_per_gust`` and ``settle_time``. Conditions of one loading, altitude and speed share a
    trim. The loads of ``surfaces`` (the horizontal tail always; without the wing no wing parts or fuel states)."""
    batch, rows, sim_conds, refused = level_flight_batch(ctx, conditions, speed_of)
    empty = np.zeros((len(H), 0))
    if not rows.size:
        return GustRuns(list(refused), [], H, [], empty, empty, empty, [])
    loads = airplane_loads(ctx)
    gb = gust_batch(loads, batch.model.subset(rows), batch.x[rows], batch.u[rows])
    up = np.array([c.get("gust") == "up" for c in sim_conds])
    alt = np.array([c.altitude for c in sim_conds])
    v_eas = np.array([c.speed for c in sim_conds])
    labels = [c.label() for c in sim_conds]
    envelopes, nz_hi, nz_lo, wing, tail = [], [], [], [], []
    with_wing = "wing" in surfaces
    fuel_names, fuel = fuel_state_table(ctx.aircraft, [c.mass for c in sim_conds]) if with_wing else (None, None)
    fuel_peaks = None
    velocities = np.asarray(design_velocity(sim_conds, H), dtype=float)
    for h_gust, uds in zip(H, velocities):
        run = simulate_gust(
            loads,
            gb,
            h_gust,
            np.where(up, 1.0, -1.0) * uds / v_eas,
            float(crit.steps_per_gust),
            float(crit.settle_time),
            surfaces=surfaces,
            split=surfaces,
        )
        envelopes.append(LoadEnvelope.from_histories(loads, run.loads, run.sim.t, labels, keys=sim_conds))
        nz_hi.append(run.sim["n_z"].max(axis=0))
        nz_lo.append(run.sim["n_z"].min(axis=0))
        tail.append((run.sim.t, *run.parts["horizontal_tail"]))
        if not with_wing:
            continue
        wing.append((run.sim.t, *run.parts["wing"]))
        peaks = fuel_state_peaks(run.loads["wing"], run.fuel_units.get("wing"), fuel)
        fuel_peaks = (
            peaks
            if fuel_peaks is None
            else np.stack(
                [np.fmin(fuel_peaks[:, :, 0], peaks[:, :, 0]), np.fmax(fuel_peaks[:, :, 1], peaks[:, :, 1])], axis=2
            )
        )
    return GustRuns(
        list(refused),
        sim_conds,
        H,
        envelopes,
        np.array(nz_hi),
        np.array(nz_lo),
        velocities,
        wing,
        None,
        None,
        v_eas,
        up,
        alt,
        gb,
        loads,
        float(crit.steps_per_gust),
        float(crit.settle_time),
        tail,
        fuel_peaks,
        fuel_names,
        fuel,
    )
