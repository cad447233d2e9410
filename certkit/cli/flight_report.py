"""``certkit trim`` and ``certkit modes``: one condition's trim and its dynamic modes.

The condition is a CG-envelope corner (or a weight and CG), a configuration, an altitude and a
speed (EAS, CAS, TAS with units, or a Mach number), and a trim kind: straight level flight, steady
climb or descent at a flight-path angle, coordinated turn at a bank angle, one engine inoperative
(bank toward the live engine), or steady heading sideslip.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from certkit.atmosphere import to_tas
from certkit.engine.conditions import CgCorners, cg_limits_at, reference_cg
from certkit.errors import UserError
from certkit.models.dynamics.linearize import linearize
from certkit.models.dynamics.modes import identify_modes
from certkit.models.dynamics.trim import trim
from certkit.models.flight import ROLES, control_limits, flight_model, model_stabilizer
from certkit.models.mass.loading import solve_loading
from certkit.models.reference_condition import declared_speed_at, reference_condition
from certkit.units import UnitError, to_si

KINDS = {"straight": "straight", "climb": "straight", "turn": "turn", "oei": "oei", "sideslip": "sideslip"}


@dataclass
class FlightCondition:
    loading_name: str
    mass: float
    x_cg: float
    configuration: str
    altitude: float
    tas: float
    kind: str
    gamma: float
    bank: float
    beta: float
    inoperative: str | None


def _quantity(text: str, dimension: str, option: str) -> float:
    try:
        return to_si(text, dimension)  # a bare number is SI; NaN, infinities and arithmetic are refused
    except UnitError as exc:
        raise UserError(f"{option} {text!r}: {exc}") from None


def _is_number(text: str) -> bool:
    """A finite decimal number ("0.84"; not "nan", "inf" or "1e999")."""
    try:
        return math.isfinite(float(text))
    except ValueError:
        return False


def parse_speed(text: str) -> tuple[float, str]:
    """``"250 kn EAS"``, ``"128 m/s TAS"``, ``"M0.84"`` or ``"0.84 MACH"`` → (value in SI or Mach, kind)."""
    t = text.strip()
    if t.upper().startswith("M") and _is_number(t[1:]):
        return float(t[1:]), "MACH"
    parts = t.split()
    if len(parts) >= 2 and parts[-1].upper() in ("EAS", "CAS", "TAS", "MACH"):
        kind = parts[-1].upper()
        value = " ".join(parts[:-1])
        if kind == "MACH" and not _is_number(value):
            raise UserError(f"--speed {text!r}: the Mach number must be a finite number")
        return (float(value), kind) if kind == "MACH" else (_quantity(value, "speed", "--speed"), kind)
    raise UserError(f"--speed {text!r}: give a value with its kind, e.g. '250 kn EAS', '280 kn CAS', 'M0.84'")


def condition_from_options(
    aircraft, corner, weight, cg, configuration, altitude, speed, kind, gamma_deg, bank_deg, beta_deg, inoperative
) -> FlightCondition:
    if configuration not in aircraft.configurations:
        raise UserError(f"--config {configuration!r}: not declared (declared: {', '.join(aircraft.configurations)})")
    if corner and aircraft.cg_envelope is None:
        raise UserError(f"--corner {corner!r}: the aircraft file has no cg_envelope section; give --weight and --cg")
    if corner:
        corners = {c.name: c for c in CgCorners().loadings(aircraft)}
        if corner not in corners:
            raise UserError(f"--corner {corner!r}: not a named corner (corners: {', '.join(corners)})")
        c = corners[corner]
        name, mass, x_cg = c.name, c.mass, c.x_cg
    else:
        mass = _quantity(weight, "mass", "--weight") if weight else aircraft.mass.MTOW
        x_cg = _quantity(cg, "length", "--cg") if cg else reference_cg(aircraft)
        if aircraft.cg_envelope is not None:
            try:
                fwd, aft = cg_limits_at(aircraft, mass)
            except ValueError as exc:
                raise UserError(f"--weight: {exc}") from None
            x_cg = x_cg if cg else min(max(x_cg, fwd), aft)
            if not (fwd - 1e-6 <= x_cg <= aft + 1e-6):
                raise UserError(
                    f"--cg {x_cg:.3f} m is outside the CG envelope at {mass:.0f} kg ({fwd:.3f} to {aft:.3f} m)"
                )
        name = f"{mass:.0f} kg at {x_cg:.3f} m"
    h, tas = _altitude_and_speed(aircraft, altitude, speed)
    if kind not in KINDS:
        raise UserError(f"--maneuver {kind!r}: one of {', '.join(KINDS)}")
    engines = [e.name for e in aircraft.propulsion.engines] if aircraft.propulsion is not None else []
    if kind == "oei" and inoperative not in engines:
        raise UserError(f"--inoperative: name the failed engine ({', '.join(engines)})")
    return FlightCondition(
        name,
        mass,
        x_cg,
        configuration,
        h,
        tas,
        KINDS[kind],
        np.radians(gamma_deg),
        np.radians(bank_deg),
        np.radians(beta_deg),
        inoperative,
    )


DEFAULT_ALTITUDE, DEFAULT_SPEED = "35000 ft", "M0.84"


def _altitude_and_speed(aircraft, altitude: str | None, speed: str | None) -> tuple[float, float]:
    """Altitude (m) and true airspeed (m/s) of the options; an option not given is the file's flight_condition
    (when declared), else 35 000 ft and M0.84."""
    ref = reference_condition(aircraft)
    if altitude is None:
        h = ref.altitude if ref is not None else _quantity(DEFAULT_ALTITUDE, "length", "--altitude")
    else:
        h = _quantity(altitude, "length", "--altitude")
        if not (-600.0 <= h <= 20_000.0):
            raise UserError(f"--altitude {altitude!r}: outside the modelled atmosphere (-600 m to 20 km)")
    if aircraft.envelope is not None and h > aircraft.envelope.ceiling + 1e-6:
        raise UserError(f"--altitude {h:.0f} m is above the envelope ceiling ({aircraft.envelope.ceiling:.0f} m)")
    if speed is None and ref is not None:
        return h, declared_speed_at(aircraft.flight_condition, h)
    value, speed_kind = parse_speed(speed if speed is not None else DEFAULT_SPEED)
    return h, float(to_tas(value, speed_kind, h))


def trim_condition(ctx, fc: FlightCondition):
    """Trim the condition; returns (trim batch, flight model)."""
    aircraft = ctx.aircraft
    loading = solve_loading(aircraft, fc.mass, fc.x_cg, fc.loading_name)
    operative = None
    if fc.inoperative:
        operative = np.array([[e.name != fc.inoperative for e in aircraft.propulsion.engines]])
    model = flight_model(aircraft, ctx.aero(fc.configuration).model, [loading], operative=operative)
    batch = trim(
        model,
        fc.tas,
        fc.altitude,
        kind=fc.kind,
        gamma=fc.gamma,
        bank=fc.bank,
        beta=fc.beta,
        limits=control_limits(aircraft, True, fc.configuration),
        roles=ROLES,
        stabilizer=model_stabilizer(aircraft, model, True, fc.configuration),
    )
    return batch, model, loading


def trim_report(ctx, fc: FlightCondition) -> dict:
    batch, model, loading = trim_condition(ctx, fc)
    out = _trim_dict(ctx, fc, batch, loading)
    if not batch.results[0].converged and _no_pitch_control(model):
        out["warnings"].append(_NO_PITCH_CONTROL)
    return out


_NO_PITCH_CONTROL = (
    "the aerodynamics have no pitch control (no elevator terms), so the pitching moment must vanish "
    "at the trim angle of attack by itself: declare elevator terms (CL_elevator, Cm_elevator) or a "
    "condition at which the table is trimmed"
)


def _no_pitch_control(model) -> bool:
    return "elevator" not in model.aero_controls


def _trim_dict(ctx, fc: FlightCondition, batch, loading) -> dict:
    r = batch.results[0]
    warning = ctx.inertia_warning()
    out = {
        "condition": {
            "loading": fc.loading_name,
            "mass_kg": fc.mass,
            "x_cg_m": fc.x_cg,
            "configuration": fc.configuration,
            "altitude_m": fc.altitude,
            "tas_m_s": fc.tas,
            "kind": fc.kind,
            "gamma_deg": np.degrees(fc.gamma),
            "bank_deg": np.degrees(fc.bank),
            "beta_deg": np.degrees(fc.beta),
            "inoperative": fc.inoperative,
        },
        "converged": r.converged,
        "residual_norm": r.residual_norm,
        "iterations": r.iterations,
        "alpha_deg": np.degrees(r.alpha),
        "beta_deg": np.degrees(r.beta),
        "theta_deg": np.degrees(r.theta),
        "phi_deg": np.degrees(r.phi),
        "controls": {k: (v if k.startswith("throttle") else float(np.degrees(v))) for k, v in r.controls.items()},
        "controls_unit": "deg (throttle 0-1)",
        "thrust_N": r.thrust,
        "limits_exceeded": [{"message": lim.message, "hint": lim.hint} for lim in r.limits_exceeded],
        "inertia_kg_m2": {
            "Ixx": loading.properties.Ixx,
            "Iyy": loading.properties.Iyy,
            "Izz": loading.properties.Izz,
            "Ixz": loading.properties.Ixz,
        },
        "loading_built": loading.construction,
        "loading_notes": list(loading.notes),
        "warnings": [warning] if warning else [],
    }
    if (
        r.stabilizer is not None
    ):  # a movable stabiliser: its incidence (the controls give its deflection from the datum)
        lim, basis = ctx.aircraft.geometry.horizontal_tail.stabilizer.trim_limits(fc.configuration)
        out["stabilizer"] = {
            "incidence_deg": float(np.degrees(r.stabilizer)),
            "required_deg": float(np.degrees(r.stabilizer_required)),
            "at_stop": r.stabilizer_at_stop,
            "limits_deg": [float(np.degrees(lim.min)), float(np.degrees(lim.max))],
            "limits": basis,
        }
    return out


def modes_report(ctx, fc: FlightCondition, density_gradient: bool = True) -> dict:
    """The trim and the modes about it; ``density_gradient``: the altitude state in the linear model
    (:mod:`certkit.models.dynamics.modes`)."""
    batch, model, loading = trim_condition(ctx, fc)
    out = _trim_dict(ctx, fc, batch, loading)
    if not batch.results[0].converged:
        hint = f"; {_NO_PITCH_CONTROL}" if _no_pitch_control(model) else ""
        raise UserError("the condition does not trim: " + batch.results[0].summary() + hint)
    modes = identify_modes(linearize(model, batch.x, batch.u), 0, density_gradient=density_gradient)
    out["density_gradient"] = density_gradient
    out["modes"] = {
        name: {
            "eigenvalue": [m.eigenvalue.real, m.eigenvalue.imag],
            "natural_frequency_rad_s": m.natural_frequency,
            "damping_ratio": m.damping_ratio,
            "period_s": m.period,
            "time_to_half_s": m.time_to_half,
            "time_to_double_s": m.time_to_double,
        }
        for name, m in modes.items()
    }
    return out
