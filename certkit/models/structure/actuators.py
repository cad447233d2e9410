"""Elevator actuators sized from the design hinge moment: piston area, stroke, mass, hydraulic flow.

A linear actuator on a horn of arm r about the hinge line (perpendicular to the horn at neutral):

* force: each actuator reacts ``share`` of one panel's hinge moment (the elevator's design hinge moment H is
  for both panels; a panel carries H / 2): F = share · H / (2 r), stall force F_s = margin · F; piston area
  A = F_s / p at the supply pressure p (the full differential pressure across the piston);
* stroke over the travel [δ_min, δ_max]: s = r (sin δ_max − sin δ_min);
* rate: at the declared surface rate δ̇ the piston speed is r δ̇ (at neutral, its largest) and the flow
  Q = A r δ̇ per actuator, so Q = margin · share · (H/2) · δ̇ / p whatever the arm;
* mass: m = fixed_mass + mass_per_work · F_s · s, the work-capacity scaling of hydraulic actuator weight
  (thin-walled cylinder: barrel mass ∝ ρ p r² L / σ ∝ F s; docs/baseline-sources.md §11 derives the
  coefficient). The actuators are concentrated masses at the hinge line, mid-span of each panel's actuator
  stations (:meth:`ActuatorSizing.components`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from certkit.errors import UserError
from certkit.models.mass.properties import MassComponent

US_GALLON = 3.785411784e-3  # m³


@dataclass(frozen=True)
class ActuatorSizing:
    """One elevator actuator's sizing (SI) and the installation totals."""

    count: int
    design_hinge_moment: float  # N·m, both panels
    force: float  # N, design force of one actuator
    stall_force: float  # N
    piston_area: float  # m²
    bore: float  # m, diameter of the piston area
    stroke: float  # m
    arm: float  # m
    mass: float  # kg, one actuator
    flow: float  # m³/s, one actuator at the surface rate
    positions: tuple[tuple[float, float, float], ...]  # airplane frame, each actuator

    @property
    def total_mass(self) -> float:
        return self.count * self.mass

    @property
    def total_flow(self) -> float:
        return self.count * self.flow

    @property
    def flow_l_per_min(self) -> float:
        return self.flow * 1e3 * 60.0

    @property
    def flow_gpm(self) -> float:
        """US gallons per minute, one actuator."""
        return self.flow / US_GALLON * 60.0

    def components(self):
        """Concentrated masses (:class:`certkit.models.mass.properties.MassComponent`), one per actuator."""
        return [MassComponent(f"elevator actuator {i + 1}", self.mass, p) for i, p in enumerate(self.positions)]

    def summary(self) -> dict:
        values = {
            "design_hinge_moment_kNm": (self.design_hinge_moment / 1e3, 2),
            "stall_force_kN": (self.stall_force / 1e3, 2),
            "piston_area_cm2": (self.piston_area * 1e4, 2),
            "bore_mm": (self.bore * 1e3, 1),
            "stroke_mm": (self.stroke * 1e3, 1),
            "mass_kg_each": (self.mass, 2),
            "total_mass_kg": (self.total_mass, 2),
            "flow_l_per_min_each": (self.flow_l_per_min, 2),
            "flow_gpm_each": (self.flow_gpm, 2),
            "total_flow_gpm": (self.count * self.flow_gpm, 2),
        }
        return {"count": self.count, **{k: round(float(v), n) for k, (v, n) in values.items()}}


def hinge_line_positions(aircraft, per_panel: int) -> tuple[tuple[float, float, float], ...]:
    """Actuator stations on the elevator hinge line: ``per_panel`` evenly spaced in each panel's span (the centres
    of equal spanwise shares), on both panels, in the plane of the tailplane."""
    ht = aircraft.geometry.horizontal_tail
    e = ht.controls["elevator"]
    semi = math.sqrt(ht.area * ht.aspect_ratio) / 2.0
    c_root = ht.area / (semi * (1.0 + ht.taper))
    p = ht.root_leading_edge
    out = []
    for k in range(per_panel):
        eta = e.span_start + (k + 0.5) / per_panel * (e.span_end - e.span_start)
        y = eta * semi
        chord = c_root * (1.0 - (1.0 - ht.taper) * eta)
        x = p.x + y * math.tan(ht.sweep_quarter_chord) + 0.25 * (c_root - chord) + (1.0 - e.chord_ratio) * chord
        z = p.z + y * math.tan(ht.dihedral)
        out += [(x, p.y + y, z), (x, p.y - y, z)]
    return tuple(out)


def size_elevator_actuators(aircraft, hinge_moment_Nm: float) -> ActuatorSizing:
    """Size the elevator actuators of ``aircraft`` (its ``sizing.elevator_actuators`` data and the elevator's
    travel) for the design hinge moment of the whole elevator (both panels, N·m, magnitude)."""
    data = aircraft.sizing.elevator_actuators if aircraft.sizing is not None else None
    if data is None:
        raise UserError("elevator actuator sizing needs the aircraft file's sizing.elevator_actuators section")
    if not (math.isfinite(hinge_moment_Nm) and hinge_moment_Nm >= 0):
        raise ValueError(f"design hinge moment must be a finite magnitude ≥ 0, got {hinge_moment_Nm!r}")
    travel = aircraft.geometry.horizontal_tail.controls["elevator"].travel
    force = data.share * 0.5 * hinge_moment_Nm / data.arm
    stall = data.margin * force
    area = stall / data.pressure
    stroke = data.arm * (math.sin(travel.max) - math.sin(travel.min))
    mass = data.fixed_mass + data.mass_per_work * stall * stroke
    flow = area * data.arm * data.surface_rate
    return ActuatorSizing(
        2 * data.per_panel,
        hinge_moment_Nm,
        force,
        stall,
        area,
        math.sqrt(4.0 * area / math.pi),
        stroke,
        data.arm,
        mass,
        flow,
        hinge_line_positions(aircraft, data.per_panel),
    )
