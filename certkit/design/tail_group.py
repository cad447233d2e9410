"""The sized horizontal-tail group of a design: structure (:mod:`certkit.models.structure.tail`), elevator actuators
(:mod:`certkit.models.structure.actuators`) and the structural capability of the sized box, in the form the aircraft
data takes (a mass component, concentrated actuator masses, ``structure.horizontal_tail`` capabilities).

Design hinge moment of the actuators: the largest |H| of the elevator over the time histories of the pitch
manoeuvres the rules simulate (§25.331(c)(1) sudden full deflection at VA, §25.331(c)(2) checked manoeuvres up to
VD), H = q̄ S_e c_e (Ch_0 + Ch_α α + Ch_δ δ_e) with the hinge-moment derivatives of the vortex lattice
(:mod:`certkit.models.aero.hinge_moment`, AVL's method) at the airplane model's Mach breakpoints, interpolated
linearly in Mach as the airplane model is.

Capability of the sized box at a load station (ultimate; limit taken equal to ultimate for the CFRP box, as the
baseline's declared capabilities do, docs/baseline-sources.md §10): bending M = σ w cos²Λ t (h − t) (the cover
equation :func:`certkit.models.structure.box.size_box` solves, at the sized cover thickness); torsion the lesser of
the covers' 2 h w cos Λ · t G_s f_skin and the webs' 2 h w cos Λ (t_w τ_w − V/(h_fs + h_rs)); shear
(t_w τ_w − q_T) (h_fs + h_rs), with the design V and T of the station (the box was sized for them together).
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from certkit.errors import UserError
from certkit.models.aero.hinge_moment import hinge_moment_derivatives
from certkit.models.loads.model import QUANTITIES, airplane_loads
from certkit.models.structure.actuators import size_elevator_actuators
from certkit.models.structure.box import UltimateLoads
from certkit.models.structure.tail import box_material, size_horizontal_tail

if TYPE_CHECKING:
    from certkit.aircraft import Aircraft
    from certkit.aircraft.model import MassComponent
    from certkit.design.tail_loads import TailLoadEnvelope
    from certkit.engine.context import Context
    from certkit.engine.results import Condition, RuleResult
    from certkit.models.structure.actuators import ActuatorSizing
    from certkit.models.structure.tail import HorizontalTailSizing


@dataclass(frozen=True)
class SizingSpec:
    tolerance_kg: float
    max_iterations: int


def declared_sizing(aircraft: Aircraft) -> SizingSpec:
    s = getattr(aircraft, "sizing", None)
    if s is None or s.horizontal_tail is None or s.loop is None:
        raise UserError(
            "a design evaluation sizes the horizontal tail: the aircraft file needs the sizing section "
            "(sizing.horizontal_tail and sizing.loop; see aircraft/lta.yaml)"
        )
    return SizingSpec(float(s.loop.mass_tolerance), int(s.loop.max_iterations))


@dataclass
class TailGroup:
    """A tail group: structure component (mass, CG, inertia), actuators (total mass, positions) and capabilities."""

    structure_mass: float
    cg: tuple[float, float, float]
    inertia: tuple[float, float, float, float]  # Ixx, Iyy, Izz, Ixz about its own CG
    box_mass: float = 0.0
    actuator_mass: float = 0.0
    actuator_positions: Any = ()  # (n, 3) m
    #: station (file form) → (shear, bending, torsion) ultimate
    capability: dict[str | float, tuple[float, float, float]] = field(default_factory=dict)
    sized: HorizontalTailSizing | None = None
    actuators: ActuatorSizing | None = None
    hinge: dict[str, Any] = field(default_factory=dict)

    @property
    def total_mass(self) -> float:
        return self.structure_mass + self.actuator_mass

    def component(self) -> dict[str, Any]:
        Ixx, Iyy, Izz, Ixz = self.inertia
        return {
            "group": "structure",
            "mass": self.structure_mass,
            "cg": {"x": self.cg[0], "y": self.cg[1], "z": self.cg[2]},
            "inertia": {"Ixx": Ixx, "Iyy": Iyy, "Izz": Izz, "Ixz": Ixz},
            "source": "sized from the Subpart C loads (certkit.design)"
            if self.sized is not None
            else "declared, scaled with the planform area (sizing loop start)",
        }

    def actuator_component(self, name: str) -> dict[str, Any]:
        """The actuators as one component: their total mass at their centroid with the point masses' inertia."""
        p = np.asarray(self.actuator_positions, dtype=float)
        m = self.actuator_mass / len(p)
        c = p.mean(axis=0)
        d = p - c
        Ixx = m * float(np.sum(d[:, 1] ** 2 + d[:, 2] ** 2))
        Iyy = m * float(np.sum(d[:, 0] ** 2 + d[:, 2] ** 2))
        Izz = m * float(np.sum(d[:, 0] ** 2 + d[:, 1] ** 2))
        Ixz = m * float(np.sum(d[:, 0] * d[:, 2]))
        return {
            "name": name,
            "group": "systems",
            "mass": self.actuator_mass,
            "cg": {"x": float(c[0]), "y": float(c[1]), "z": float(c[2])},
            "inertia": {"Ixx": Ixx, "Iyy": max(Iyy, 1e-9), "Izz": max(Izz, 1e-9), "Ixz": Ixz},
            "source": f"{len(p)} elevator actuators sized for "
            f"{self.hinge.get('design_hinge_moment_Nm', 0.0) / 1e3:.1f} kN·m",
        }

    def capabilities(self) -> list[dict[str, Any]]:
        out = []
        for station, values in self.capability.items():
            for q, v in zip(QUANTITIES, values):
                out.append(
                    {
                        "station": station,
                        "quantity": q,
                        "limit": float(v),
                        "ultimate": float(v),
                        "source": "sized box (certkit.design.tail_group): ultimate capability at its gauges",
                    }
                )
        return out

    def as_dict(self) -> dict[str, Any]:
        out: dict[str, Any] = {
            "structure_mass_kg": self.structure_mass,
            "actuator_mass_kg": self.actuator_mass,
            "total_mass_kg": self.total_mass,
            "box_mass_kg": self.box_mass,
            "cg_m": list(self.cg),
            "inertia_kg_m2": dict(zip(("Ixx", "Iyy", "Izz", "Ixz"), self.inertia)),
            "capability_ultimate": {str(k): dict(zip(QUANTITIES, v)) for k, v in self.capability.items()},
            "hinge_moment": self.hinge,
        }
        if self.sized is not None:
            out["items_kg"] = dict(self.sized.masses)
            out["stations"] = self.sized.station_table()
            out["notes"] = list(self.sized.notes)
        if self.actuators is not None:
            out["actuators"] = self.actuators.summary()
        return out


def initial_group(aircraft: Aircraft, base_aircraft: Aircraft, component: MassComponent) -> TailGroup:
    """The loop's start: the declared tail component, its mass and inertia scaled with the planform area of the
    design over the declared one (an areal-weight guess, inertia with the square of the ratio), and no structural
    capability: the tail-load margins of iteration 0 are not used."""
    if aircraft.geometry is None or base_aircraft.geometry is None:
        raise ValueError("the tail group is sized from the geometry section")
    ratio = aircraft.geometry.horizontal_tail.area / base_aircraft.geometry.horizontal_tail.area
    inertia = component.inertia
    tensor = (0.0, 0.0, 0.0, 0.0) if inertia is None else (inertia.Ixx, inertia.Iyy, inertia.Izz, inertia.Ixz)
    Ixx, Iyy, Izz, Ixz = (v * ratio**2 for v in tensor)
    return TailGroup(component.mass * ratio, (component.cg.x, component.cg.y, component.cg.z), (Ixx, Iyy, Izz, Ixz))


def _file_station(name: str) -> str | float:
    if name in ("root", "side of body"):
        return name.replace(" ", "_")
    return round(float(name.split("%")[0]) / 100.0, 6)


def box_capability(
    aircraft: Aircraft, sized: HorizontalTailSizing, station_names: Sequence[str], station_span: Any
) -> dict[str | float, tuple[float, float, float]]:
    """Ultimate shear (N), bending and torsion (N·m) the sized box carries at each load station (module doc)."""
    if aircraft.sizing is None or aircraft.sizing.horizontal_tail is None:
        raise ValueError("the box's capability needs sizing.horizontal_tail")
    mat = box_material(aircraft.sizing.horizontal_tail)
    b = sized.box
    cos = np.cos(b.sweep)
    t, h, w = b.t_cover, b.depth, b.width
    webs = b.front_spar_height + b.rear_spar_height
    bending = mat.cover_stress * w * cos**2 * t * (h - t)
    shear_design = np.abs(b.loads.shear)
    q_t = np.abs(b.loads.torsion) / (2.0 * h * w * cos)
    torsion = np.minimum(
        2.0 * h * w * cos * t * mat.cover_shear * mat.skin_fraction,
        2.0 * h * w * cos * np.maximum(b.t_web * mat.web_shear - shear_design / webs, 0.0),
    )
    shear = np.maximum(b.t_web * mat.web_shear - q_t, 0.0) * webs
    return {
        _file_station(name): (
            float(np.interp(s, b.span, shear)),
            float(np.interp(s, b.span, bending)),
            float(np.interp(s, b.span, torsion)),
        )
        for name, s in zip(station_names, station_span)
    }


def _hinge_moments(ctx: Context, results: Iterable[RuleResult]) -> list[tuple[Any, ...]]:
    """Per run of the rules that produce elevator hinge moments (their declaration, ``Rule.produces``; the caller
    passes their results): (rule id, hinge moments H (samples,) of the elevator, their (time, condition) indices,
    Mach, q̄, α, δ, conditions, times, derivatives)."""
    samples = []
    for res in results:
        run = res.run
        if run is None or run.records is None or "elevator" not in list(run.records.control_names):
            continue
        sim = run.records
        valid = run.valid
        h = sim.history
        de = sim.controls[:, :, list(sim.control_names).index("elevator")]
        mask = np.ones(de.shape, dtype=bool) if valid is None else np.asarray(valid, dtype=bool)
        samples.append(
            (
                res.id,
                h["qbar"][mask],
                h["mach"][mask],
                h["alpha"][mask],
                de[mask],
                np.argwhere(mask),
                run.conditions,
                sim.t,
            )
        )
    if not samples:
        raise ValueError(
            "no rule produced elevator hinge moments (a pitch-manoeuvre history) to size the actuators from"
        )
    aero = ctx.aero("clean")
    lattice = aero.lattice
    if lattice is None:
        raise ValueError("the elevator's hinge moments need the vortex lattice (the aerodynamic tables are declared)")
    grid = np.asarray(aero.mach, dtype=float)  # the Mach breakpoints the loads model has already solved
    derivs = ctx.memo(
        ("aero", "clean", "elevator hinge-moment derivatives"),  # geometry only: shared by the loop
        lambda: [hinge_moment_derivatives(lattice.at_mach(float(m)), "elevator") for m in grid],
    )
    table = {k: np.array([getattr(d, k) for d in derivs]) for k in ("Ch_0", "Ch_alpha", "Ch_delta")}
    ref = derivs[0]
    out = []
    for rid, qbar, m, alpha, de, where, conds, t in samples:
        coef = {k: np.interp(m, grid, v) for k, v in table.items()}  # linear in Mach, held beyond the ends
        H = qbar * ref.area * ref.chord * (coef["Ch_0"] + coef["Ch_alpha"] * alpha + coef["Ch_delta"] * de)
        out.append((rid, H, where, m, qbar, alpha, de, conds, t, coef, ref))
    return out


def design_hinge_moment(ctx: Context, results: Iterable[RuleResult]) -> dict[str, Any]:
    """The largest elevator hinge moment over the pitch-manoeuvre histories the rules kept (module doc)."""
    best: dict[str, Any] | None = None
    for rid, H, where, m, qbar, alpha, de, conds, t, coef, ref in _hinge_moments(ctx, results):
        i = int(np.argmax(np.abs(H)))
        if best is None or abs(H[i]) > abs(best["design_hinge_moment_Nm"]):
            k, c = where[i]
            best = {
                "design_hinge_moment_Nm": float(abs(H[i])),
                "signed_Nm": float(H[i]),
                "rule": rid,
                "condition": conds[c].label() if conds is not None and c < len(conds) else str(c),
                "time_s": float(t[k]),
                "mach": float(m[i]),
                "qbar_Pa": float(qbar[i]),
                "alpha_deg": float(np.degrees(alpha[i])),
                "elevator_deg": float(np.degrees(de[i])),
                "Ch_alpha_per_rad": float(coef["Ch_alpha"][i]),
                "Ch_delta_per_rad": float(coef["Ch_delta"][i]),
                "elevator_area_m2": ref.area,
                "elevator_chord_m": ref.chord,
            }
    if best is None:
        raise ValueError("no elevator hinge moment in the pitch-manoeuvre histories")
    return best


def hinge_critical_conditions(
    ctx: Context, results: Iterable[RuleResult], fraction: float
) -> dict[str, list[Condition] | None]:
    """Per rule id, the conditions of the kept pitch manoeuvres whose largest elevator hinge moment reaches
    ``fraction`` of the design hinge moment (rules whose runs do not name their conditions: None, all)."""
    runs = _hinge_moments(ctx, results)
    top = max(float(np.max(np.abs(H))) for _, H, *_ in runs if H.size)
    out: dict[str, list[Condition] | None] = {}
    for rid, H, where, *_, conds, _t, _coef, _ref in runs:
        if conds is None:
            out[rid] = None
            continue
        peak = np.zeros(len(conds))
        np.maximum.at(peak, where[:, 1], np.abs(H))
        out[rid] = [conds[c] for c in np.flatnonzero(peak >= fraction * top)]
    return out


def size_tail_group(
    aircraft: Aircraft,
    ctx: Context,
    envelope: TailLoadEnvelope,
    results: Iterable[RuleResult],
    allowance: float = 0.0,
) -> TailGroup:
    """Size the structure for the limit-load envelope × its factor of safety (the loads rules' ``ultimate_factor``
    in force) × (1 + ``allowance``) and the actuators for the design hinge moment."""
    tail = airplane_loads(ctx)["horizontal_tail"]
    if tuple(tail.station_names) != tuple(envelope.stations):
        raise ValueError(f"load stations {envelope.stations} differ from the loads model's {tail.station_names}")
    if envelope.ultimate_factor is None:
        raise ValueError("the tail's load envelope carries no factor of safety (ultimate_factor)")
    ult_lim = envelope.limit * (1.0 + allowance) * envelope.ultimate_factor
    ult = UltimateLoads(np.asarray(tail.station_span, dtype=float), ult_lim[0], ult_lim[1], ult_lim[2])
    sized = size_horizontal_tail(aircraft, ult)
    p = sized.properties
    hinge = design_hinge_moment(ctx, results)
    actuators = None
    if aircraft.sizing is not None and aircraft.sizing.elevator_actuators is not None:
        actuators = size_elevator_actuators(aircraft, hinge["design_hinge_moment_Nm"])
    return TailGroup(
        sized.mass,
        (float(p.cg[0]), float(p.cg[1]), float(p.cg[2])),
        (p.Ixx, p.Iyy, p.Izz, p.Ixz),
        box_mass=sized.masses["covers"] + sized.masses["webs"],
        actuator_mass=actuators.total_mass if actuators else 0.0,
        actuator_positions=actuators.positions if actuators else (),
        capability=box_capability(aircraft, sized, tail.station_names, tail.station_span),
        sized=sized,
        actuators=actuators,
        hinge=hinge,
    )
