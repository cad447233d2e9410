"""Text and JSON forms of a :class:`certkit.models.performance.mission.MissionResult` (``certkit mission``)."""

from __future__ import annotations

import math

import numpy as np

from certkit.units import FT, LB

NMI = 1852.0


def _finite(value):
    """JSON-safe copy: NaN and infinities become None, numpy scalars plain floats."""
    if isinstance(value, dict):
        return {k: _finite(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_finite(v) for v in value]
    if isinstance(value, (float, np.floating)):
        return float(value) if math.isfinite(value) else None
    if isinstance(value, np.bool_):
        return bool(value)
    return value


def mission_json(result) -> dict:
    return _finite({"schema": "certkit.mission/1", **result.as_dict()})


def _profile(p) -> list[str]:
    lines = [
        f"{p.name}: payload {p.payload_kg / LB:,.0f} lb, takeoff {p.takeoff_weight_kg / LB:,.0f} lb, "
        f"ramp fuel {p.ramp_fuel_kg / LB:,.0f} lb, landing {p.landing_weight_kg / LB:,.0f} lb, "
        f"initial level {p.initial_altitude_m / FT:,.0f} ft"
        + "".join(f", step to {s.to_altitude_m / FT:,.0f} ft at {s.weight_kg / LB:,.0f} lb" for s in p.steps),
        f"  {'phase':<10}{'time min':>10}{'fuel lb':>12}{'distance nmi':>15}",
    ]
    for ph in p.phases:
        lines.append(f"  {ph.name:<10}{ph.time_s / 60:>10.1f}{ph.fuel_kg / LB:>12,.0f}{ph.distance_m / NMI:>15,.1f}")
    lines.append(
        f"  {'block':<10}{p.block_time_s / 60:>10.1f}{p.block_fuel_kg / LB:>12,.0f}{p.distance_m / NMI:>15,.1f}"
    )
    lines.append("  reserves on landing: " + ", ".join(f"{k} {v / LB:,.0f} lb" for k, v in p.reserves.items()))
    return lines


def _calibration(cal: dict) -> list[str]:
    if not cal:
        return ["calibration: none declared (drag and fuel flow as modelled)"]
    line = (
        f"calibration: zero-lift drag x {cal['drag_factor']:.4f}, fuel flow x {cal['fuel_flow_factor']:.4f} "
        f"({cal['source']})"
    )
    t = cal.get("target")
    if t:
        line += f"; target {t['range_m'] / NMI:,.0f} nmi within {100 * t['tolerance']:g} % ({t['source']})"
    return [line]


def mission_table(result) -> str:
    d, n, c = result.design, result.nominal, result.cruise_drag
    margin = result.range_margin_m
    lines = [
        f"design range {result.design_range_m / NMI:,.0f} nmi (required {result.range_requirement_m / NMI:,.0f} nmi: "
        f"{'met' if margin >= 0 else 'NOT met'}, margin {margin / NMI:+,.0f} nmi)",
        f"nominal mission {n.distance_m / NMI:,.0f} nmi: block fuel {n.block_fuel_kg / LB:,.0f} lb "
        f"({n.block_fuel_kg:,.0f} kg), block time {n.block_time_s / 3600:.2f} h",
        f"cruise drag at M {c.mach:.2f}, {c.altitude_m / FT:,.0f} ft, {c.mass_kg / LB:,.0f} lb: CD {c.CD:.5f}, CL "
        f"{c.CL:.4f}, "
        f"L/D {c.lift_to_drag:.2f}, alpha {math.degrees(c.alpha):.2f} deg, elevator {math.degrees(c.elevator):.2f} deg"
        + ("" if c.converged else " (trim NOT converged)"),
        f"OEW {result.oew_kg / LB:,.0f} lb",
        *_calibration(result.calibration),
        "",
        "payload-range (reserves on landing):",
        f"  {'point':<24}{'payload lb':>12}{'ramp fuel lb':>14}{'takeoff lb':>12}{'range nmi':>11}",
    ]
    for p in result.payload_range:
        lines.append(
            f"  {p.name:<24}{p.payload_kg / LB:>12,.0f}{p.ramp_fuel_kg / LB:>14,.0f}{p.takeoff_weight_kg / LB:>12,.0f}"
            f"{p.range_m / NMI:>11,.0f}"
        )
    lines += [""] + _profile(d) + [""] + _profile(n) + [""]
    lines += [f"note: {note}" for note in result.notes]
    lines.append(f"({result.timings['total_s']:.2f} s)")
    return "\n".join(lines)
