"""§25.341(b) Continuous turbulence design criteria by design-envelope analysis of the rigid airplane: P_L = P_L-1g ±
U_σ Ā at every station of the wing and the horizontal tail (vertical turbulence) and of the fin (lateral turbulence,
felt by the fin alone as §25.341(a)'s lateral gust), Ā the rms load per unit rms gust velocity from the airplane's
frequency response and von Kármán's spectrum (:mod:`certkit.models.loads.turbulence`), compared with the declared
structural capability (§25.303, §25.305).

Verification (docs/regulation-notes.md §4): the words of (b) and (b)(1) are verified (Amdt. 25-141); the spectrum of
(b)(2) is printed as an image in the CFR and its scale L = 2,500 ft, the (b)(3) turbulence intensities (U_σref 90 ft/s
TAS at sea level, 79 ft/s at 24,000 ft and above, × F_g; 1.32 × at VB, ½ at VD) are from AC 25.341-1 and CS 25.341(b)
as secondary sources: UNVERIFIED, criteria here, overridable in the aircraft file.

It declares no loads to the design layer: its horizontal-tail loads on the baseline are 20–42 % of the envelope the
sizing loop's rules set (the pitch manoeuvres and the discrete gusts carry the same physics with larger loads), so the
tail's sizing would cost a turbulence analysis per iteration and change nothing.
"""

from __future__ import annotations

from functools import partial

import numpy as np
from certkit_rules.part25.support.fuel_states import fuel_detail, fuel_state_table, state_envelope
from certkit_rules.part25.support.gust_runs import (
    GUST_RUN_CRITERIA,
    flight_profile_alleviation,
    gust_speeds,
    level_flight_batch,
)
from certkit_rules.part25.support.loads_conditions import refusal_findings
from certkit_rules.part25.support.structural_checks import SAFETY, capability_finding, critical_state_finding

from certkit.engine.conditions import CgCorners, ConditionSpace, EnvelopeAltitudes
from certkit.engine.evidence.loads import run_envelope_evidence
from certkit.engine.registry import Criterion, SimulationRule, rule
from certkit.engine.results import LoadsRun
from certkit.models.loads.capability import declared_capabilities
from certkit.models.loads.gust_response import SURFACES, gust_batch
from certkit.models.loads.lateral_gust import FIN, lateral_gust_batch
from certkit.models.loads.model import airplane_loads
from certkit.models.loads.response import LoadEnvelope
from certkit.models.loads.turbulence import (
    lateral_turbulence_response,
    rms_per_unit,
    spatial_frequencies,
    steady_loads,
    turbulence_response,
)
from certkit.units import FT, KN

SECONDARY = "14 CFR 25.341(b)(3), values from AC 25.341-1 / CS 25.341(b)(3) (secondary sources, UNVERIFIED)"
SPEEDS = ("VB", "VC", "VD")


def turbulence_intensity(altitude, speed_point: str, f_g, crit):
    """U_σ (m/s TAS): U_σref (linear from its sea-level value to its value at the break altitude, constant above)
    × F_g, at VC; × ``vb_factor`` at VB, × ``vd_factor`` at VD."""
    h = np.asarray(altitude, dtype=float)
    ref = np.interp(
        h, [0.0, crit.sigma_break_altitude * FT], [crit.sigma_sea_level * FT, crit.sigma_high * FT]
    )  # constant beyond the break (np.interp holds the end value)
    factor = {"VB": crit.vb_factor, "VC": 1.0, "VD": crit.vd_factor}[speed_point]
    return ref * np.asarray(f_g, dtype=float) * factor


@rule
class ContinuousTurbulence(SimulationRule):
    id = "25.341(b)"
    cost = 4
    symbol = "continuous-turbulence"
    title = "Continuous vertical and lateral turbulence, design-envelope analysis, rigid airplane"
    amendment = "25-141"
    requirement = """
        The dynamic response of the airplane to continuous turbulence is taken into account: limit loads
        P_L = P_L-1g ± U_σ Ā at all critical altitudes, weights and speeds, Ā the ratio of the rms incremental load
        to the rms turbulence velocity from the frequency response of the loads and the normalised von Kármán
        spectrum (scale 2,500 ft), U_σ the limit turbulence intensity (true airspeed): 90 ft/s at sea level to
        79 ft/s at 24,000 ft and above, times the flight-profile alleviation factor, at VC; 1.32 times that at VB,
        half at VD; vertical and lateral turbulence. The structure carries the limit loads and 1.5 × them (ultimate),
        §25.303/§25.305.
    """
    margin = """
        Per condition and surface (wing in every fuel state of §25.343, horizontal tail; the fin in lateral
        turbulence): the smallest of (allowable
        limit load − |P_L|) and (allowable ultimate load − 1.5 × |P_L|) over the declared stations and quantities,
        with P_L = P_L-1g ± U_σ Ā of each station and quantity; without a declared capability the condition is not
        evaluated and reports its loads.
    """
    references = ("25.341", "25.321", "25.335", "25.343", "25.303", "25.305", "25.1527")
    requires = ("speeds.VB", "speeds.VC", "speeds.VD", "geometry.horizontal_tail")
    criteria = {
        "turbulence_scale": Criterion(2500.0, "ft", SECONDARY.replace("(b)(3)", "(b)(2)"), "von Kármán scale L"),
        "sigma_sea_level": Criterion(90.0, "ft/s", SECONDARY, "U_σref at sea level, TAS"),
        "sigma_high": Criterion(79.0, "ft/s", SECONDARY, "U_σref at and above the break altitude, TAS"),
        "sigma_break_altitude": Criterion(24000.0, "ft", SECONDARY, "altitude where U_σref stops decreasing"),
        "vb_factor": Criterion(1.32, "", SECONDARY, "U_σ at VB / U_σ at VC"),
        "vd_factor": Criterion(0.5, "", SECONDARY, "U_σ at VD / U_σ at VC"),
        "fgz_altitude": GUST_RUN_CRITERIA["fgz_altitude"],
        **SAFETY,
    }
    conditions = ConditionSpace(
        loading=CgCorners(),
        configurations=("clean",),
        altitudes=EnvelopeAltitudes(),
        extra=(("speed_point", SPEEDS),),
        note="VB (capped at VC), VC and VD in EAS, each Mach-limited at altitude, in level flight; U_σ in TAS.",
    )
    limitations = (
        "Rigid airplane (no structural modes: (b) asks for all significant ones); the gust's lift lags as Küssner's "
        "function gives in the frequency domain (a Sears-function approximation, 2-D incompressible, on each "
        "surface's mean chord), the motion's lift is quasi-steady (no Wagner lag); controls fixed, the phugoid "
        "and the spiral mode left out (flown by the pilot); lateral turbulence felt by the fin alone; U_σ, L and the "
        "speed factors from secondary sources (unverified)."
    )
    implementation = "partial"
    unevaluated = (
        (
            "25.341(b)",
            "the structural modes are not modelled (rigid airplane); in lateral turbulence the fuselage's and the "
            "wing's share of the gust is not modelled (the fin alone); the alternatives of (b)(4)–(5) are not offered",
        ),
    )

    def simulate(self, ctx, conditions, crit):
        return continuous_turbulence(ctx, conditions, crit)

    def evidence(self, ctx, findings, crit):
        return run_envelope_evidence(self.run, ctx, crit.ultimate_factor, (*SURFACES, FIN), "continuous turbulence")


def _check(c, surface: str, direction: str = "vertical") -> str:
    return f"(b) continuous turbulence, {direction}, {c.get('speed_point')}, {surface.replace('_', ' ')}"


def continuous_turbulence(ctx, conditions, crit) -> LoadsRun:
    """Design-envelope loads of every condition: each trimmed in level flight at its speed point, linearised, its
    station loads' Ā integrated over von Kármán's spectrum, P_1g ± U_σ Ā per station, quantity and fuel state."""
    batch, rows, sim_conds, refused = level_flight_batch(
        ctx, conditions, lambda c: gust_speeds(ctx, c.altitude)[c.get("speed_point")]
    )
    findings = refusal_findings(refused, lambda c: [_check(c, s) for s in SURFACES] + [_check(c, FIN, "lateral")])
    if not rows.size:
        return LoadsRun(findings, reason="no condition could be trimmed in level flight (see the findings)")
    loads = airplane_loads(ctx)
    gb = gust_batch(loads, batch.model.subset(rows), batch.x[rows], batch.u[rows])
    steady = steady_loads(loads, gb, SURFACES)
    scale = float(crit.turbulence_scale) * FT
    omega = spatial_frequencies(scale)
    response = turbulence_response(loads, gb, steady, omega)
    f_g = np.array([flight_profile_alleviation(ctx.aircraft, c.altitude, crit) for c in sim_conds])
    u_sigma = np.array(
        [turbulence_intensity(c.altitude, c.get("speed_point"), f_g[i], crit) for i, c in enumerate(sim_conds)]
    )
    abar_nz = rms_per_unit(np.abs(response.n_z.T) ** 2, omega, scale)  # (n,) per m/s
    fuel_names, fuel = fuel_state_table(ctx.aircraft, [c.mass for c in sim_conds])  # (n, M, K) kg
    peaks: dict[str, np.ndarray] = {}
    wing_states = None
    for s in SURFACES:
        p1g = steady.total(s)  # (n, 3, S)
        h = np.moveaxis(response.loads[s], 0, -1)  # (n, 3, S, nΩ)
        if s == "wing" and response.fuel_per_kg[s] is not None:
            # each fuel state's 1-g load and frequency response: the fuel's inertia added per kilogram of each tank
            p1g_m = p1g[:, None] + np.einsum("nkqs,nmk->nmqs", steady.fuel_per_kg[s], fuel)
            h_m = h[:, None] + np.einsum("wnkqs,nmk->nmqsw", response.fuel_per_kg[s], fuel)  # (n, M, 3, S, nΩ)
            band = u_sigma[:, None, None, None] * rms_per_unit(np.abs(h_m) ** 2, omega, scale)  # (n, M, 3, S)
            wing_states = np.moveaxis(np.stack([p1g_m - band, p1g_m + band], axis=2), 1, 0)  # (M, n, 2, 3, S)
            peaks[s] = state_envelope(wing_states)  # the envelope over the fuel states
            continue
        band = u_sigma[:, None, None] * rms_per_unit(np.abs(h) ** 2, omega, scale)  # (n, 3, S)
        peaks[s] = np.stack([p1g - band, p1g + band], axis=1)  # (n, 2, 3, S)
    lb = lateral_gust_batch(loads, batch.model.subset(rows), batch.x[rows], batch.u[rows])
    fin_steady = steady_loads(loads, lb, (FIN,))
    lateral = lateral_turbulence_response(loads, lb, fin_steady, omega)
    abar_ny = rms_per_unit(np.abs(lateral.n_z.T) ** 2, omega, scale)
    band = u_sigma[:, None, None] * rms_per_unit(np.abs(np.moveaxis(lateral.loads[FIN], 0, -1)) ** 2, omega, scale)
    peaks[FIN] = np.stack([fin_steady.total(FIN) - band, fin_steady.total(FIN) + band], axis=1)
    stations = {s: loads[s].station_names for s in (*SURFACES, FIN)}
    caps = {s: declared_capabilities(ctx, s) for s in (*SURFACES, FIN)}
    for i, c in enumerate(sim_conds):
        details = dict(
            V_kn_EAS=round(float(c.speed / KN), 1),
            U_sigma_ft_s_TAS=round(float(u_sigma[i] / FT), 2),
            F_g=round(float(f_g[i]), 4),
            Abar_n_z_per_ft_s=round(float(abar_nz[i] * FT), 5),
            n_z_limit_band=round(float(u_sigma[i] * abar_nz[i]), 4),
        )
        lateral_details = dict(
            {k: v for k, v in details.items() if k not in ("Abar_n_z_per_ft_s", "n_z_limit_band")},
            Abar_n_y_per_ft_s=round(float(abar_ny[i] * FT), 5),
            n_y_limit_band=round(float(u_sigma[i] * abar_ny[i]), 4),
        )
        findings.append(
            capability_finding(
                c,
                _check(c, FIN, "lateral"),
                FIN,
                peaks[FIN][i],
                stations[FIN],
                caps[FIN],
                crit.ultimate_factor,
                **lateral_details,
            )
        )
        for s in SURFACES:
            if s == "wing" and wing_states is not None:
                check = partial(
                    critical_state_finding,
                    peaks_by_state=wing_states[:, i],
                    state_details=partial(fuel_detail, fuel_names[i], fuel[i], loads["wing"].tank_names),
                )
            else:
                check = partial(capability_finding, peaks=peaks[s][i])
            findings.append(
                check(
                    c,
                    _check(c, s),
                    s,
                    stations=stations[s],
                    capabilities=caps[s],
                    ultimate_factor=crit.ultimate_factor,
                    **details,
                )
            )
    envelope = LoadEnvelope(
        stations,
        peaks,
        {s: np.zeros_like(p) for s, p in peaks.items()},
        [c.label() for c in sim_conds],
        keys=list(sim_conds),
    )
    return LoadsRun(findings, sim_conds, envelope=envelope)
