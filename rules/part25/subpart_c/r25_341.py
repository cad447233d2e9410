"""§25.341(a) Discrete gust design criteria: 1 − cos vertical gusts of gradients 30–350 ft on the rigid
airplane (heave and pitch, the gust reaching the tail a tail arm later), wing and horizontal-tail loads
from the strip loads model, compared with the declared structural capability (§25.303, §25.305).

Verification (docs/regulation-notes.md §4): the words of (a)(1)–(3), (a)(5)(i) and the Z_mo definition
are verified (Amdt. 25-141); the formulas of (a)(2), (a)(4) and (a)(6) (the 1 − cos shape,
U_ds = U_ref F_g (H/350)^(1/6), F_g = 0.5 (F_gz + F_gm), F_gz = 1 − Z_mo/250 000, F_gm = √(R2 tan(π R1/4)))
are from FAA AC 25.341-1 via secondary sources and UNVERIFIED against the CFR; the (a)(5)(ii) half U_ref
at VD is unverified wording. They are criteria here, overridable in the aircraft file.

Limitations: rigid airplane (no structural modes, (a)(1) asks for all significant ones); the gust's lift builds up
with Küssner's function on each surface's mean chord (:mod:`certkit.models.loads.gust`), the airplane's own motion
is quasi-steady (no Wagner lag). Lateral gusts (same gradients, U_ds
and F_g) load the fin alone (:mod:`certkit.models.loads.lateral_gust`; the fuselage's and wing's share of the gust
not modelled): fin shear, bending and torsion against the declared fin capability.

Each finding also reports the manoeuvring envelope's load factor at its speed (§25.333/§25.337) and whether
the gust's peak n_z goes beyond it — information only: since Amdt. 25-86 §25.333 has no gust V–n envelope.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import partial

import numpy as np
from certkit_rules.part25.support.fuel_states import fuel_detail, fuelled_wing_envelope
from certkit_rules.part25.support.gust_runs import (
    GUST_CONDITIONS,
    GUST_REQUIRES,
    GUST_RUN_CRITERIA,
    GustRuns,
    gust_runs,
)
from certkit_rules.part25.support.loads_conditions import refusal_findings
from certkit_rules.part25.support.structural_checks import (
    SAFETY,
    beyond_mach_range,
    capability_finding,
    condition_mach,
    critical_state_finding,
    maneuver_limit_load_factor,
    set_aside_finding,
)

from certkit.engine.evidence.loads import allowables, envelope_evidence, gust_evidence
from certkit.engine.registry import Loads, SimulationRule, rule
from certkit.engine.results import LoadsRun
from certkit.models.loads.capability import declared_capabilities
from certkit.models.loads.gust_response import SURFACES
from certkit.models.loads.lateral_gust import FIN, lateral_gust_batch, simulate_lateral_gust
from certkit.models.loads.response import LoadEnvelope
from certkit.units import FT, KN


@rule
class DiscreteGust(SimulationRule):
    id = "25.341(a)"
    produces = (Loads("wing"), Loads("horizontal_tail"), Loads("vertical_tail"))
    cost = 8  # relative evaluation time (orders work over --jobs processes)
    run_with = "discrete-gust"  # §25.349(b) modifies these gust runs: one process simulates them once
    symbol = "discrete-gust"
    title = "Discrete vertical and lateral gusts (1 − cos), rigid airplane"
    amendment = "25-141"
    requirement = """
        In level flight the airplane meets symmetrical vertical gusts U = (U_ds/2)(1 − cos πs/H) for
        0 ≤ s ≤ 2H, with enough gradients H from 30 to 350 ft to find the critical response of each load
        quantity; U_ds = U_ref F_g (H/350)^(1/6), U_ref 56 ft/s EAS at sea level, 44 ft/s at 15,000 ft,
        20.86 ft/s at 60,000 ft (linear between) from VB to VC, half at VD; F_g the flight-profile
        alleviation factor. Positive and negative gusts; lateral gusts alike (the vertical tail). Limit
        gust loads by dynamic analysis; the
        structure carries them (limit) and 1.5 × them (ultimate), §25.303/§25.305.
    """
    margin = """
        Per condition and surface (wing, horizontal tail; the fin in lateral gusts): the smallest of (allowable limit
        load − |limit
        load|) and (allowable ultimate load − 1.5 × |limit load|) over the declared stations and quantities,
        the limit load the extreme over all gust gradients; without a declared structural capability the
        condition is not evaluated and reports its loads.
    """
    references = ("25.333", "25.335", "25.303", "25.305", "25.1527")
    requires = GUST_REQUIRES
    criteria = {**GUST_RUN_CRITERIA, **SAFETY}
    conditions = GUST_CONDITIONS
    limitations = (
        "Rigid airplane (no structural modes); the gust's lift builds up with Küssner's function (R. T. Jones' "
        "approximation, 2-D incompressible, on each surface's mean chord), the motion's lift is quasi-steady (no "
        "Wagner lag); the lateral "
        "gust loads the fin alone (the fuselage's and wing's share of it not modelled); U_ds and F_g formulas "
        "unverified against the CFR (AC 25.341-1)."
    )
    implementation = "partial"

    unevaluated = (
        (
            "25.341(a)",
            "the dynamic analysis is of the rigid airplane (no structural modes); the lateral gust acts on "
            "the fin alone (the fuselage's and wing's share is not modelled)",
        ),
    )

    def simulate(self, ctx, conditions, crit):
        surfaces = tuple(s for s in SURFACES if self.computes(s))
        return discrete_gusts(ctx, conditions, crit, surfaces, lateral=self.computes(FIN))

    def evidence(self, ctx, findings, crit):
        run = self.run
        if run is None or not run.simulated:
            return []
        allow = allowables(ctx, crit.ultimate_factor)
        lateral = run.lateral_envelope
        table = (
            envelope_evidence(lateral, (FIN,), "lateral gust", plot=False, allow=allow) if lateral is not None else []
        )
        return gust_evidence(run, allow) + table


@dataclass
class GustRun(LoadsRun):
    """The discrete gusts: per condition, sense, quantity and station the gradient that set each extreme
    (``which``: surface → (n, 2, 3, S) indices into ``gradients``, m), a ``replay`` of chosen (condition, gradient)
    pairs with their time histories, the loads model and the lateral gusts' fin envelope."""

    which: dict | None = None
    gradients: object = None
    replay: object = None
    loads: object = None
    lateral_envelope: object = None

    def envelopes(self) -> list:
        return [e for e in (self.envelope, self.lateral_envelope) if e is not None]


def discrete_gusts(ctx, conditions, crit, surfaces=SURFACES, lateral: bool = True) -> GustRun:
    """The vertical gusts' findings on ``surfaces`` (the wing and the horizontal tail, or the tail alone) and, with
    ``lateral``, the lateral gusts' on the fin."""
    runs = gust_runs(ctx, conditions, crit, surfaces)
    findings = refusal_findings(
        runs.refused, lambda c: [f"(a) discrete gust, {c.get('gust')}, {s.replace('_', ' ')}" for s in surfaces]
    )
    if not runs.conditions:
        return GustRun(findings, reason="no condition could be trimmed (see the findings)")
    sim_conds, H, up = runs.conditions, runs.gradients, runs.up
    env, which = runs.symmetric
    nz_hi, nz_lo, uds_all, u_ref, f_g, v_eas, alt = (
        runs.nz_hi,
        runs.nz_lo,
        runs.uds,
        runs.u_ref,
        runs.f_g,
        runs.v_eas,
        runs.altitude,
    )
    caps = {s: declared_capabilities(ctx, s) for s in surfaces}
    # information, not a criterion: the §25.333 manoeuvring envelope's load factor at each speed (§25.337), to
    # show where gusts load the airplane beyond the manoeuvres (since Amdt. 25-86 there is no gust V–n envelope)
    n_env = [
        round(maneuver_limit_load_factor(ctx, float(v_eas[i]), float(alt[i]), bool(up[i])), 4)
        for i in range(len(sim_conds))
    ]
    for i, c in enumerate(sim_conds):
        sense = 1 if up[i] else 0
        j_nz = int(np.argmax(nz_hi[:, i]) if up[i] else np.argmin(nz_lo[:, i]))
        beyond_mach = beyond_mach_range(runs.loads, condition_mach(c))
        for s in surfaces:
            jb = int(which[s][i, sense, 1, 0])  # gradient of the extreme root bending in the gust's sense
            if beyond_mach:
                check = partial(
                    _not_evaluated, beyond_mach, peaks=(runs.wing_fuel_peaks[:, i] if s == "wing" else env.peaks[s][i])
                )
            elif s == "wing":  # the wing in each fuel state (§25.343), the critical one named
                check = partial(
                    critical_state_finding,
                    peaks_by_state=runs.wing_fuel_peaks[:, i],
                    state_details=partial(fuel_detail, runs.fuel_names[i], runs.fuel[i], runs.loads["wing"].tank_names),
                )
            else:
                check = partial(capability_finding, peaks=env.peaks[s][i])
            findings.append(
                check(
                    c,
                    f"(a) discrete gust, {c.get('gust')}, {s.replace('_', ' ')}",
                    s,
                    stations=env.stations[s],
                    capabilities=caps[s],
                    ultimate_factor=crit.ultimate_factor,
                    U_ref_ft_s_EAS=round(float(u_ref[i] / FT), 2),
                    F_g=round(float(f_g[i]), 4),
                    critical_H_root_bending_ft=round(float(H[jb] / FT), 0),
                    U_ds_ft_s_EAS=round(float(uds_all[jb, i] / FT), 2),
                    peak_n_z=round(float(nz_hi[j_nz, i] if up[i] else nz_lo[j_nz, i]), 4),
                    critical_H_n_z_ft=round(float(H[j_nz] / FT), 0),
                    V_kn_EAS=round(float(v_eas[i] / KN), 1),
                    maneuver_envelope_n_z=n_env[i],
                    beyond_maneuver_envelope=bool(
                        (nz_hi[j_nz, i] > n_env[i]) if up[i] else (nz_lo[j_nz, i] < n_env[i])
                    ),
                    tail_lag_s=round(float(runs.batch.tail_arm / runs.batch.v_tas[i]), 4),
                )
            )
    fin, lateral_env = lateral_gusts(ctx, runs, crit) if lateral else ([], None)
    return GustRun(
        findings + fin,
        sim_conds,
        envelope=fuelled_wing_envelope(env, runs.wing_fuel_peaks),
        which=which,
        gradients=H,
        replay=runs.replay,
        loads=runs.loads,
        lateral_envelope=lateral_env,
    )


def _not_evaluated(
    reason,
    cond,
    check,
    surface,
    peaks=None,
    stations=(),
    capabilities=None,
    ultimate_factor=None,
    peaks_by_state=None,
    state_details=None,
    **details,
):
    """A not-evaluated finding in place of :func:`capability_finding` (same call), with ``reason`` and the loads."""
    return set_aside_finding(cond, check, reason, peaks if peaks is not None else peaks_by_state, stations, **details)


def lateral_gusts(ctx, runs: GustRuns, crit) -> tuple[list, LoadEnvelope | None]:
    """The lateral 1 − cos gusts on the fin (:mod:`certkit.models.loads.lateral_gust`) at the entries of the vertical
    gust runs (one per loading, altitude and speed point), with the same gradients and U_ds: one finding per entry
    (condition ``gust lateral``) against the declared fin capability. The gust from the left is the mirror image of
    the gust from the right (symmetric airplane: every fin load changes sign), so both are in each envelope."""
    idx = [i for i, c in enumerate(runs.conditions) if c.get("gust") == "up"]
    if not idx:
        return [], None
    lb = lateral_gust_batch(runs.loads, runs.batch.model.subset(idx), runs.batch.x0[idx], runs.batch.u0[idx])
    conds = [runs.conditions[i].with_(gust="lateral") for i in idx]
    labels = [c.label() for c in conds]
    envelopes, ny = [], []
    for j, H in enumerate(runs.gradients):
        sim, fin, _ = simulate_lateral_gust(
            runs.loads, lb, H, runs.uds[j, idx] / runs.v_eas[idx], float(crit.steps_per_gust), float(crit.settle_time)
        )
        envelopes.append(
            LoadEnvelope.from_histories(
                runs.loads, {FIN: np.concatenate([fin, -fin])}, np.concatenate([sim.t, sim.t]), labels
            )
        )
        ny.append(np.abs(sim["n_y"]).max(axis=0))
    env, which = LoadEnvelope.worst_of(envelopes)
    caps = declared_capabilities(ctx, FIN)
    findings = []
    for k, c in enumerate(conds):
        jb = int(which[FIN][k, 1, 0, 0])  # gradient of the largest root shear
        i = idx[k]
        beyond_mach = beyond_mach_range(runs.loads, condition_mach(c))
        findings.append(
            (partial(_not_evaluated, beyond_mach) if beyond_mach else capability_finding)(
                c,
                "(a) discrete lateral gust, vertical tail",
                FIN,
                env.peaks[FIN][k],
                env.stations[FIN],
                caps,
                crit.ultimate_factor,
                U_ref_ft_s_EAS=round(float(runs.u_ref[i] / FT), 2),
                F_g=round(float(runs.f_g[i]), 4),
                critical_H_root_shear_ft=round(float(runs.gradients[jb] / FT), 0),
                U_ds_ft_s_EAS=round(float(runs.uds[jb, i] / FT), 2),
                V_kn_EAS=round(float(runs.v_eas[i] / KN), 1),
                peak_gust_sideslip_deg=round(float(np.degrees(runs.uds[jb, i] / runs.v_eas[i])), 3),
                peak_n_y=round(float(max(v[k] for v in ny)), 4),
                direction="from the right and (mirror image) the left",
            )
        )
    return findings, env
