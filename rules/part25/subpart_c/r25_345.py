"""§25.345(a)(2) High-lift devices, flaps-extended gusts: at each flap configuration's design flap speed VF
(§25.335(e)), positive and negative 1 − cos vertical gusts of U_ds = 25 ft/s EAS and gradient H = 12.5 c̄ (c̄ the wing's
mean geometric chord, S/b) normal to the flight path in level flight, on the rigid airplane (heave and pitch, the gust
reaching the tail a tail arm later, as §25.341(a)); wing and horizontal-tail loads from the strip loads model with the
configuration's flap lift on the wing's strips and the flaps' downwash on the tail's, compared with the declared
structural capability (§25.303, §25.305).

Wording: the gust of (a)(2), its U_ds, H and c̄ checked against EASA CS 25.345(a)(2) (ED Decision 2016/010/R, harmonised
with the FAR); the FAR text was not retrieved (docs/regulation-notes.md §3). VF is the larger of the placard VFE and
the §25.335(e)(3) minima, as §25.331(b)'s flap points take it; (a)(1), the 2.0 g manoeuvre flaps extended, is one of
those points ("VF at n flaps").
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import partial

import numpy as np
from certkit_rules.part25.support.balanced_runs import BALANCED_RUN_CRITERIA, design_flap_speed
from certkit_rules.part25.support.fuel_states import fuel_detail, fuelled_wing_envelope
from certkit_rules.part25.support.gust_runs import GUST_RUN_CRITERIA, simulate_gust_set
from certkit_rules.part25.support.loads_conditions import refusal_findings
from certkit_rules.part25.support.stability_speeds import FLAP_ALTITUDE, flap_altitude_findings
from certkit_rules.part25.support.structural_checks import (
    SAFETY,
    capability_finding,
    critical_state_finding,
)

from certkit.engine.conditions import CgCorners, ConditionSpace, EnvelopeAltitudes
from certkit.engine.evidence.loads import run_envelope_evidence
from certkit.engine.registry import Criterion, Loads, SimulationRule, rule
from certkit.engine.results import Finding, LoadsRun
from certkit.models.aero import planform
from certkit.models.loads.capability import declared_capabilities
from certkit.models.loads.gust_response import SURFACES
from certkit.models.loads.response import LoadEnvelope
from certkit.units import FT, KN

CS = "CS 25.345(a)(2) (ED Decision 2016/010/R, harmonised with 14 CFR 25.345(a)(2); FAR text not retrieved)"


@dataclass(frozen=True)
class FlapConfigurations(ConditionSpace):
    """Every configuration of the aircraft file other than ``clean`` (the flap positions), at every corner of the
    weight–CG envelope and altitude (those above the flap altitude limit are not applicable)."""

    def expand(self, aircraft):
        flaps = tuple(c for c in aircraft.configurations if c != "clean")
        return ConditionSpace.expand(replace(self, configurations=flaps), aircraft) if flaps else []


@rule
class FlapGusts(SimulationRule):
    id = "25.345(a)(2)"
    produces = (Loads("wing"), Loads("horizontal_tail"))
    cost = 3
    symbol = "flap-gusts"
    title = "Flaps-extended vertical gusts at the design flap speeds"
    amendment = "25-141"
    requirement = """
        With the flaps in their takeoff, approach and landing positions, at the design flap speeds of §25.335(e),
        the airplane meets positive and negative gusts of 25 ft/s EAS acting normal to the flight path in level
        flight; the gust loads are found by rational analysis with the rigid-body motions, the gust shape that of
        §25.341(a)(2) with U_ds = 25 ft/s EAS, H = 12.5 c̄ and c̄ the wing's mean geometric chord. The structure
        carries the limit loads and 1.5 × them (ultimate), §25.303/§25.305.
    """
    margin = """
        Per condition and surface (wing in every fuel state of §25.343, horizontal tail): the smallest of (allowable
        limit load − |limit load|) and (allowable ultimate load − 1.5 × |limit load|) over the declared stations and
        quantities, the limit load the extreme of the gust response; without a declared structural capability the
        condition is not evaluated and reports its loads.
    """
    references = ("25.335", "25.341", "25.331", "25.303", "25.305")
    requires = ("speeds.VFE", "geometry.horizontal_tail", "geometry.wing")
    criteria = {
        "gust_velocity": Criterion(25.0, "ft/s", CS, "U_ds, EAS"),
        "gradient_chords": Criterion(12.5, "", CS, "H = this × the wing's mean geometric chord S/b"),
        "vf_takeoff_factor": BALANCED_RUN_CRITERIA["vf_takeoff_factor"],
        "vf_landing_factor": BALANCED_RUN_CRITERIA["vf_landing_factor"],
        "flap_altitude_max": FLAP_ALTITUDE,
        "steps_per_gust": GUST_RUN_CRITERIA["steps_per_gust"],
        "settle_time": GUST_RUN_CRITERIA["settle_time"],
        **SAFETY,
    }
    conditions = FlapConfigurations(
        loading=CgCorners(),
        altitudes=EnvelopeAltitudes(),
        extra=(("gust", ("up", "down")),),
        note="each flap configuration at its VF (EAS): the larger of the placard VFE and the §25.335(e)(3) minima.",
    )
    limitations = (
        "Rigid airplane (no structural modes), Küssner's gust-penetration lag and quasi-steady motion (no Wagner "
        "lag), as §25.341(a); "
        "the flap lift is the configuration's increment (declared, or Raymer's estimate) spread with the linear "
        "lattice's flap distribution; the flaps' own structure and supports are not modelled."
    )
    implementation = "partial"
    unevaluated = (
        (
            "25.345(b)",
            "the flaps' structure (the head-on 25 ft/s gust, and the slipstream of (b)(1)) is not modelled: no strip "
            "model of the flap itself",
        ),
        ("25.345(c)", "flaps used en route are not declared in the aircraft file's configurations: not evaluated"),
        ("25.345(d)", "not evaluated (the paragraph's text was not retrieved)"),
    )

    def simulate(self, ctx, conditions, crit):
        return flap_gusts(ctx, conditions, crit)

    def evidence(self, ctx, findings, crit):
        return run_envelope_evidence(self.run, ctx, crit.ultimate_factor, SURFACES, "flaps-extended gusts")


def mean_geometric_chord(aircraft) -> float:
    """c̄ = S/b of the wing (m), the chord §25.345(a)(2)'s gradient refers to."""
    wing = aircraft.geometry.wing
    return float(wing.area / planform.span(wing.area, wing.aspect_ratio))


def _check(c, surface: str) -> str:
    return f"(a)(2) flaps-extended gust, {c.get('gust')}, {surface.replace('_', ' ')}"


def flap_gusts(ctx, conditions, crit) -> LoadsRun:
    """The flaps-extended gusts of every condition, one trimmed batch per flap configuration."""
    H = crit.gradient_chords * mean_geometric_chord(ctx.aircraft)
    uds = float(crit.gust_velocity) * FT
    caps = {s: declared_capabilities(ctx, s) for s in SURFACES}
    findings, envelopes, done = [], [], []
    by_cfg: dict[str, list] = {}
    for c in conditions:
        by_cfg.setdefault(c.configuration, []).append(c)
    for cfg, conds in by_cfg.items():
        vf, ok = {}, []  # altitude → (VF EAS, its note): VF depends on the configuration and altitude only
        for c in conds:
            high = flap_altitude_findings(ctx, c, float(crit.flap_altitude_max), [_check(c, s) for s in SURFACES])
            if high:
                findings += high
                continue
            try:
                if c.altitude not in vf:
                    vf[c.altitude] = design_flap_speed(ctx, cfg, c.altitude, crit)
            except LookupError as exc:
                findings += [Finding.not_evaluated(c, _check(c, s), str(exc)) for s in SURFACES]
                continue
            ok.append(c)
        if not ok:
            continue
        runs = simulate_gust_set(
            ctx,
            ok,
            lambda c: vf[c.altitude][0],  # noqa: B023  (called within this iteration)
            lambda sim, gradients: np.full((len(gradients), len(sim)), uds),
            np.array([H]),
            crit,
        )
        findings += refusal_findings(runs.refused, lambda c: [_check(c, s) for s in SURFACES])
        if not runs.conditions:
            continue
        env = runs.envelopes[0]
        for i, c in enumerate(runs.conditions):
            details = dict(
                V_kn_EAS=round(float(runs.v_eas[i] / KN), 1),
                U_ds_ft_s_EAS=round(uds / FT, 2),
                H_ft=round(H / FT, 1),
                peak_n_z=round(float(runs.nz_hi[0, i] if runs.up[i] else runs.nz_lo[0, i]), 4),
                speed_note=vf[c.altitude][1],
            )
            for s in SURFACES:
                if s == "wing":
                    check = partial(
                        critical_state_finding,
                        peaks_by_state=runs.wing_fuel_peaks[:, i],
                        state_details=partial(
                            fuel_detail, runs.fuel_names[i], runs.fuel[i], runs.loads["wing"].tank_names
                        ),
                    )
                else:
                    check = partial(capability_finding, peaks=env.peaks[s][i])
                findings.append(
                    check(
                        c,
                        _check(c, s),
                        s,
                        stations=env.stations[s],
                        capabilities=caps[s],
                        ultimate_factor=crit.ultimate_factor,
                        **details,
                    )
                )
        envelopes.append(fuelled_wing_envelope(env, runs.wing_fuel_peaks))
        done += runs.conditions
    if not envelopes:
        return LoadsRun(findings, reason="no flaps-extended condition could be trimmed (see the findings)")
    return LoadsRun(findings, done, envelope=LoadEnvelope.merge(envelopes))
