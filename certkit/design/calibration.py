"""Declared calibrations of the baseline, solved from their targets (``certkit calibrate``).

Performance (``calibration:`` of the aircraft file): the factor on the drag build-up's zero-lift drag that makes
the mission model (:mod:`certkit.models.performance.mission`) fly the target range with the target payload from
MTOW, the fuel-flow factor (installation losses) held as declared. The range falls monotonically with the factor,
so the solution takes secant steps on ln R against ln f (the first with slope −1, Breguet's for a factor on all
the drag) to a relative range error of 10⁻⁴; the factor is then rounded down to the four decimals the file holds,
so that the target range is reached.

Tail mass (``sizing.horizontal_tail.non_optimum_factor``): the factor that makes the horizontal-tail group the
design loop sizes from today's Subpart C loads (:func:`certkit.design.evaluate.evaluate_design`) equal to the
declared ``horizontal tail`` component of ``mass.components``. The sized mass is linear in the factor for fixed
loads — ``(factor − 1) × (covers + webs)`` plus the fittings' share of it — and the loads move little with the tail
mass, so a secant step from that slope converges in two or three loops.

Nothing here runs in a study: a study varies the design against the fixed, declared factors. The commands print
the values for the file; tests recompute them so that a model change that moves the baseline off its targets fails.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from certkit.errors import UserError
from certkit.models.aero.airplane import build_airplane_aero, lattice_derivatives
from certkit.models.performance.mission import MissionFlyer, fuel_capacity
from certkit.models.performance.mission_tables import build_tables

if TYPE_CHECKING:
    from certkit.aircraft import Aircraft
    from certkit.models.aero.airplane import LatticeDerivatives

#: told each iteration's (factor, achieved value) (``certkit calibrate`` prints them)
Progress = Callable[[float, float], object]

#: relative range error at which the drag-factor iteration stops
RANGE_TOLERANCE = 1e-4
#: relative mass error at which the tail-factor iteration stops (below the sizing loop's 5 kg on 2,630 kg)
MASS_TOLERANCE = 1e-3
MAX_ITERATIONS = 8
#: decimals of a factor as the aircraft file declares it
DECIMALS = 4


@dataclass
class Iteration:
    factor: float
    value: float


@dataclass
class CalibrationResult:
    """A solved factor: its name and path in the aircraft file, value, the target and what it gives."""

    name: str
    path: str
    factor: float
    target: float
    achieved: float
    unit: str
    iterations: list[Iteration] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)

    @property
    def error(self) -> float:
        return self.achieved / self.target - 1.0


_NEEDS_TARGET = (
    "calibration.target: the performance calibration needs a calibration: section with a target "
    "(range, payload, tolerance, source), a mission: section and mass.OEW and MTOW; see aircraft/lta.yaml"
)


def with_drag_factor(aircraft: Aircraft, factor: float) -> Aircraft:
    """``aircraft`` with its declared calibration's drag factor replaced."""
    cal = aircraft.calibration
    if cal is None:
        raise UserError("calibration: the aircraft file declares no calibration section")
    return aircraft.model_copy(update={"calibration": cal.model_copy(update={"drag_factor": float(factor)})})


def target_range(aircraft: Aircraft, lattice: LatticeDerivatives | None = None) -> float:
    """The range (m) the mission model flies with the calibration target's payload from MTOW (fuel-capacity
    limited when the tanks are smaller), reserves on landing."""
    cal, mission, mass = aircraft.calibration, aircraft.mission, aircraft.mass
    if cal is None or cal.target is None or mission is None or mass.OEW is None or mass.MTOW is None:
        raise UserError(_NEEDS_TARGET)
    target = cal.target
    payload = mission.design_payload if target.payload is None else target.payload
    aero = build_airplane_aero(
        aircraft, "clean", lattice=lattice if lattice is not None else lattice_derivatives(aircraft)
    )
    tables = build_tables(aircraft, aero, (0.8 * mass.OEW, 1.05 * mass.MTOW))
    flyer = MissionFlyer(aircraft, tables, float(mass.OEW))
    w = mass.MTOW
    capacity = fuel_capacity(aircraft)
    if capacity is not None:
        w = min(w, mass.OEW + payload + capacity - flyer.allowance["taxi_out"])
    return flyer.fly("calibration target", payload, w).distance_m


def solve_drag_factor(aircraft: Aircraft, *, progress: Progress | None = None) -> CalibrationResult:
    """The drag factor that flies the declared target range (fuel-flow factor as declared)."""
    cal = aircraft.calibration
    if cal is None or cal.target is None or aircraft.mission is None:
        raise UserError(_NEEDS_TARGET)
    goal = float(cal.target.range)
    lattice = lattice_derivatives(aircraft)
    f = float(cal.drag_factor)
    history = []
    for _ in range(MAX_ITERATIONS):
        r = target_range(with_drag_factor(aircraft, f), lattice)
        history.append(Iteration(f, r))
        if progress:
            progress(f, r)
        if abs(r / goal - 1.0) < RANGE_TOLERANCE:
            break
        slope = -1.0  # d ln R / d ln f: −1 if the factor scaled all the drag; the secant of the last two after that
        if len(history) > 1:
            a, b = history[-2], history[-1]
            slope = np.log(b.value / a.value) / np.log(b.factor / a.factor)
        f = f * (goal / r) ** (1.0 / slope)
    # the factor as the file holds it (4 decimals), rounded down so that the target range is reached, not missed by
    # a fraction of a mile (the range constraint of a study is ≥ 0 on the baseline)
    step = 10.0**-DECIMALS
    # (+ 1e-6: a factor already at 4 decimals whose quotient comes out as …999 stays itself)
    declared = round(np.floor(history[-1].factor / step + 1e-6) * step, DECIMALS)
    for _ in range(MAX_ITERATIONS):
        if declared == history[-1].factor and history[-1].value >= goal:
            break
        if declared == history[-1].factor:
            declared = round(declared - step, DECIMALS)
        r = target_range(with_drag_factor(aircraft, declared), lattice)
        history.append(Iteration(float(declared), r))
        if progress:
            progress(declared, r)
    last = history[-1]
    return CalibrationResult(
        "drag factor",
        "calibration.drag_factor",
        last.factor,
        goal,
        last.value,
        "m",
        history,
        [f"fuel-flow factor held at {cal.fuel_flow_factor:.4f} ({cal.fuel_flow_source or cal.source})"],
    )


def tail_group_mass(source: str | Path, factor: float | None = None) -> tuple[float, dict[str, Any]]:
    """The horizontal-tail structure the design loop sizes for ``source`` (an aircraft file path) with the
    non-optimum factor replaced by ``factor`` (None: as declared): (mass kg, the sizing details)."""
    from certkit.design.evaluate import (  # deferred: only `certkit calibrate --tail` evaluates a design (+0.3 s)
        evaluate_design,
    )

    settings = {} if factor is None else {"sizing.horizontal_tail.non_optimum_factor": float(factor)}
    rec = evaluate_design(source, settings, responses=["sizing.*"])
    return float(rec["responses"]["sizing.ht_structure_mass_kg"]), rec["details"]["sizing"]


def declared_tail_mass(aircraft: Aircraft) -> float:
    """The declared ``horizontal tail`` component mass (kg): the tail calibration's target."""
    for c in aircraft.mass.components:
        if c.name == "horizontal tail":
            return float(c.mass)
    raise UserError(
        "mass.components: the tail calibration needs a component named 'horizontal tail' (the declared "
        "group mass it reproduces)"
    )


def solve_tail_factor(source: str | Path, aircraft: Aircraft, *, progress: Progress | None = None) -> CalibrationResult:
    """The non-optimum factor whose sized tail group equals the declared one, today's loads."""
    data = aircraft.sizing.horizontal_tail if aircraft.sizing is not None else None
    if data is None:
        raise UserError("sizing.horizontal_tail: the tail calibration needs the sizing section; see aircraft/lta.yaml")
    goal = declared_tail_mass(aircraft)
    f = float(data.non_optimum_factor)
    history = []
    for _ in range(MAX_ITERATIONS):
        m, details = tail_group_mass(source, f)
        history.append(Iteration(f, m))
        if progress:
            progress(f, m)
        if abs(m / goal - 1.0) < MASS_TOLERANCE:
            break
        slope = mass_per_factor(details, f)
        f_new = f + (goal - m) / slope
        if f_new < 1.0:
            history.append(Iteration(1.0, np.nan))
            return CalibrationResult(
                "non-optimum factor",
                "sizing.horizontal_tail.non_optimum_factor",
                1.0,
                goal,
                m,
                "kg",
                history,
                [
                    f"no factor ≥ 1 reaches the declared mass: at {f:.4f} the group "
                    f"is {m:.0f} kg and would need {f_new:.3f}"
                ],
            )
        f = round(f_new, DECIMALS)  # evaluated as the file will hold it
    last = history[-1]
    return CalibrationResult(
        "non-optimum factor",
        "sizing.horizontal_tail.non_optimum_factor",
        last.factor,
        goal,
        last.value,
        "kg",
        history,
        sizing_summary(details),
    )


def sizing_summary(details: dict[str, Any]) -> list[str]:
    """The numbers of the sized group the documentation quotes: items, CG, own inertia, the envelope at the root,
    the actuators' design hinge moment."""
    g, env = details["group"], details["envelope"]
    items = ", ".join(f"{k.replace('_', ' ')} {v:,.0f} kg" for k, v in g["items_kg"].items())
    root = env["stations"].index("root") if "root" in env["stations"] else 0
    loads = env["limit_loads"]
    inertia = g["inertia_kg_m2"]
    hinge = g.get("hinge_moment") or {}
    lines = [
        f"sized group {g['structure_mass_kg']:,.1f} kg ({g['structure_mass_kg'] / 0.45359237:,.0f} lb): {items}",
        f"CG x {g['cg_m'][0]:.2f} m, z {g['cg_m'][2]:.2f} m; own inertia Ixx {inertia['Ixx']:.2g}, Iyy "
        f"{inertia['Iyy']:.2g}, Izz {inertia['Izz']:.2g} kg·m²",
        f"limit envelope at the root: shear {loads['shear'][root] / 1e3:,.0f} kN, bending "
        f"{loads['bending'][root] / 1e3:,.0f} kN·m, torsion {loads['torsion'][root] / 1e3:,.0f} kN·m (× 1.5 ultimate)",
        f"elevator actuators {g['actuator_mass_kg']:,.0f} kg for "
        f"{hinge.get('design_hinge_moment_Nm', float('nan')) / 1e3:,.0f} kN·m "
        f"({hinge.get('rule', '?')}, elevator {hinge.get('elevator_deg', float('nan')):.1f} deg)",
        f"loop iterations {len(details['history'])}",
    ]
    return lines


def mass_per_factor(details: dict[str, Any], factor: float) -> float:
    """d(mass)/d(factor) of the sized group at fixed loads: the non-optimum increment per unit of (factor − 1),
    with the fittings' fraction of it (fittings are a fraction of box + ribs)."""
    items = details["group"]["items_kg"]
    ideal = items["covers"] + items["webs"]
    fittings_share = items["fittings"] / (items["covers"] + items["webs"] + items["non_optimum"] + items["ribs"])
    return float(ideal * (1.0 + fittings_share))


def calibration_text(result: CalibrationResult) -> str:
    """What ``certkit calibrate`` prints: the factor as the file's YAML line, the target and what it gives."""
    scale, unit = (1852.0, "nmi") if result.unit == "m" else (0.45359237, "lb")
    leaf = result.path.rsplit(".", 1)[-1]
    lines = [
        f"{result.name}: {result.factor:.4f}   ({result.path})",
        f"target {result.target / scale:,.0f} {unit}; with it {result.achieved / scale:,.0f} {unit} "
        f"({100 * result.error:+.2f} %) after {len(result.iterations)} evaluation(s)",
        *result.notes,
        "",
        "for the aircraft file:",
        f"  {leaf}: {result.factor:.4f}",
    ]
    return "\n".join(lines)


__all__ = [
    "calibration_text",
    "CalibrationResult",
    "Iteration",
    "with_drag_factor",
    "target_range",
    "solve_drag_factor",
    "tail_group_mass",
    "declared_tail_mass",
    "solve_tail_factor",
    "mass_per_factor",
    "sizing_summary",
    "RANGE_TOLERANCE",
    "MASS_TOLERANCE",
]
