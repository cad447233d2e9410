"""The horizontal-tail structural group sized from its ultimate loads: mass by item, CG and own inertia.

* Torque box (both halves): :func:`certkit.models.structure.box.size_box` at stations from the root (plane of
  symmetry) to the tip, on the trapezoidal planform of ``geometry.horizontal_tail`` in the plane of the surface
  (span s = y / cos Γ). The fully stressed covers and webs ("ideal" material) are multiplied by the declared
  non-optimum factor — joints, splices, fasteners, cut-outs, doublers and the panel-stability and
  damage-tolerance margins an idealised strength sizing leaves out (Niu, *Airframe Structural Design*, 1988,
  ch. 1 weight; York & Labell, NASA CR-166173, 1980, the "non-optimum" factor of an analytical box weight).
* Secondary items from declared areal weights on their planform areas (Torenbeek, *Synthesis of Subsonic
  Airplane Design*, 1982, App. C; Roskam, *Airplane Design* Part V, 1985): ribs on the box, leading edge ahead
  of the front spar, fixed trailing edge aft of the rear spar (to the hinge line along the elevator), the
  elevator aft of its hinge line (``controls.elevator`` span and chord ratio); fittings and attachments as a
  fraction of box + ribs. The elevator actuators are not in this group (:mod:`.actuators`).
* Mass properties: each item is distributed along the span (the box and ribs by their sized mass per unit span,
  the others by their planform area) and placed at the centroid of its chordwise band, at ±y on both halves
  with the dihedral; each band strip also has its chordwise own inertia m ℓ²/12. CG and the inertia tensor
  about it (body axes) by :func:`certkit.models.mass.properties.combine_arrays`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from certkit.aircraft.model import InertiaTensor, Point
from certkit.aircraft.model import MassComponent as FileComponent
from certkit.errors import UserError
from certkit.models.mass.properties import MassProperties, combine_arrays
from certkit.models.structure.box import BoxMaterial, BoxSizing, BoxStations, UltimateLoads, size_box

ITEMS = ("covers", "webs", "non_optimum", "ribs", "leading_edge", "trailing_edge", "elevator", "fittings")


@dataclass(frozen=True)
class TailPlanform:
    """One half of the horizontal tail in the plane of the surface: stations s (m from the root), chord, and
    what places them in the airplane frame."""

    span: np.ndarray
    chord: np.ndarray
    tip: float  # in-plane semispan, m
    root_chord: float
    root_leading_edge: tuple[float, float, float]
    sweep_quarter_chord: float  # planform (projected), rad
    dihedral: float
    thickness_ratio: float

    def leading_edge_x(self) -> np.ndarray:
        """X of the leading edge at each station (the trapezoid of
        :func:`certkit.models.aero.vlm.trapezoidal_surface`)."""
        y = self.span * math.cos(self.dihedral)
        return (
            self.root_leading_edge[0] + y * math.tan(self.sweep_quarter_chord) + 0.25 * (self.root_chord - self.chord)
        )


def tail_planform(surface, n: int = 121) -> TailPlanform:
    """The planform of an aircraft-file lifting surface (``geometry.horizontal_tail``) at ``n`` stations."""
    semi = math.sqrt(surface.area * surface.aspect_ratio) / 2.0
    c_root = surface.area / (semi * (1.0 + surface.taper))
    tip = semi / math.cos(surface.dihedral)
    s = np.linspace(0.0, tip, n)
    chord = c_root * (1.0 - (1.0 - surface.taper) * s / tip)
    p = surface.root_leading_edge
    return TailPlanform(
        s, chord, tip, c_root, (p.x, p.y, p.z), surface.sweep_quarter_chord, surface.dihedral, surface.thickness_ratio
    )


def box_material(data) -> BoxMaterial:
    """The box material of the aircraft file's ``sizing.horizontal_tail``."""
    m, g = data.material, data.minimum_gauge
    return BoxMaterial.from_strains(
        density=m.density,
        cover_modulus=m.cover_modulus,
        cover_shear_modulus=m.cover_shear_modulus,
        web_shear_modulus=m.web_shear_modulus,
        strain=m.design_strain,
        shear_strain=m.design_shear_strain,
        skin_fraction=m.skin_fraction,
        min_cover=g.cover,
        min_web=g.web,
    )


@dataclass(frozen=True)
class HorizontalTailSizing:
    """Sized horizontal-tail group (both halves). ``masses``: kg by item (:data:`ITEMS`; ``non_optimum`` is the
    increment (factor − 1) × (covers + webs)); ``box``: one half's sized box with its per-station gauges;
    ``properties``: mass, CG (airplane frame) and inertia about the CG (body axes)."""

    masses: dict[str, float]
    box: BoxSizing
    planform: TailPlanform
    properties: MassProperties
    non_optimum_factor: float
    notes: list[str] = field(default_factory=list)

    @property
    def mass(self) -> float:
        return float(sum(self.masses.values()))

    def component(self, name: str = "horizontal tail"):
        """The group as an aircraft-file mass component (to replace the declared one)."""
        p = self.properties
        return FileComponent(
            name=name,
            group="structure",
            mass=p.mass,
            cg=Point(x=p.cg[0], y=p.cg[1], z=p.cg[2]),
            inertia=InertiaTensor(Ixx=p.Ixx, Iyy=p.Iyy, Izz=p.Izz, Ixz=p.Ixz),
            source=f"sized from the ultimate loads (non-optimum factor {self.non_optimum_factor:g})",
        )

    def station_table(self) -> list[dict]:
        """Per-station gauges (mm) and governing criteria of the box, every tenth station and the tip."""
        b = self.box
        rows = []
        for i in sorted(set(range(0, b.span.size, max(1, b.span.size // 10))) | {b.span.size - 1}):
            rows.append(
                {
                    "span_m": round(float(b.span[i]), 3),
                    "chord_m": round(float(self.planform.chord[i]), 3),
                    "bending_kNm": round(float(b.loads.bending[i]) / 1e3, 1),
                    "shear_kN": round(float(b.loads.shear[i]) / 1e3, 1),
                    "torsion_kNm": round(float(b.loads.torsion[i]) / 1e3, 1),
                    "cover_mm": round(float(b.t_cover[i]) * 1e3, 2),
                    "cover_governs": b.cover_governs[i],
                    "web_mm": round(float(b.t_web[i]) * 1e3, 2),
                    "web_governs": b.web_governs[i],
                }
            )
        return rows


def _band_fractions(planform: TailPlanform, data, elevator):
    """Chordwise bands (start, end chord fractions) of each secondary item at every station, and the mask of the
    stations inside the elevator's span."""
    eta = planform.span / planform.tip
    n = eta.size
    f, r = data.front_spar, data.rear_spar
    if elevator is not None:
        inside = (eta >= elevator.span_start) & (eta <= elevator.span_end)
        hinge = 1.0 - elevator.chord_ratio
    else:
        inside, hinge = np.zeros(n, dtype=bool), 1.0
    te_end = np.where(inside, hinge, 1.0)
    return {
        "leading_edge": (np.zeros(n), np.full(n, f)),
        "ribs": (np.full(n, f), np.full(n, r)),
        "trailing_edge": (np.full(n, r), te_end),
        "elevator": (np.where(inside, hinge, 1.0), np.ones(n)),
    }, inside


def size_horizontal_tail(aircraft, loads: UltimateLoads, *, n_stations: int = 121) -> HorizontalTailSizing:
    """Size the horizontal-tail group of ``aircraft`` (the pydantic :class:`certkit.aircraft.model.Aircraft`) for
    the ULTIMATE loads ``loads`` (stations in the plane of the surface from the root, e.g. the loads model's
    ``SurfaceLoads.station_span``; interpolated monotonically, zero at the tip)."""
    data = aircraft.sizing.horizontal_tail if aircraft.sizing is not None else None
    if data is None:
        raise UserError(
            "horizontal-tail sizing needs the aircraft file's sizing.horizontal_tail section "
            "(material allowables, spar positions, minimum gauges, areal weights, non-optimum factor)"
        )
    surface = aircraft.geometry.horizontal_tail
    elevator = surface.controls.get("elevator")
    plan = tail_planform(surface, n_stations)
    sweep_in_plane = math.atan(math.tan(surface.sweep_quarter_chord) * math.cos(surface.dihedral))
    stations = BoxStations(plan.span, plan.chord, surface.thickness_ratio, sweep_in_plane)
    box = size_box(
        stations, loads.interpolate(plan.span, plan.tip), box_material(data), data.front_spar, data.rear_spar
    )
    bands, inside = _band_fractions(plan, data, elevator)
    w = data.areal_weights
    areal = {"ribs": w.ribs, "leading_edge": w.leading_edge, "trailing_edge": w.trailing_edge, "elevator": w.elevator}
    # mass per unit span of one half, by item, and the chordwise band each item occupies
    per_span = {
        "covers": box.cover_mass_per_span,
        "webs": box.web_mass_per_span,
        "non_optimum": (data.non_optimum_factor - 1.0) * (box.cover_mass_per_span + box.web_mass_per_span),
    }
    band_of = {"covers": bands["ribs"], "webs": bands["ribs"], "non_optimum": bands["ribs"]}
    for item, (start, end) in bands.items():
        per_span[item] = areal[item] * (end - start) * plan.chord
        band_of[item] = (start, end)
    box_and_ribs = sum(per_span[k] for k in ("covers", "webs", "non_optimum", "ribs"))
    per_span["fittings"] = data.fittings_fraction * box_and_ribs
    band_of["fittings"] = bands["ribs"]
    masses = {k: 2.0 * float(np.trapezoid(per_span[k], plan.span)) for k in ITEMS}
    properties = _mass_properties(plan, per_span, band_of)
    notes = [
        f"box sized at {n_stations} stations (root to tip, in the plane of the surface); covers governed by "
        f"bending at {box.cover_governs.count('bending')}, torsion at {box.cover_governs.count('torsion')} and the "
        f"minimum gauge at {box.cover_governs.count('minimum gauge')} stations",
        "streamwise torsion taken as box torsion; the bending–torsion coupling of the swept box (M sin Λ) is "
        "reacted at the root rib and not sized",
    ]
    if elevator is None:
        notes.append("no elevator declared: the whole trailing edge aft of the rear spar is fixed trailing edge")
    return HorizontalTailSizing(masses, box, plan, properties, data.non_optimum_factor, notes)


def _mass_properties(plan: TailPlanform, per_span: dict, band_of: dict) -> MassProperties:
    """CG and inertia of the group from strips of every item on both halves (trapezoid-rule weights)."""
    s = plan.span
    weights = np.zeros(s.size)
    weights[:-1] += 0.5 * np.diff(s)
    weights[1:] += 0.5 * np.diff(s)
    x_le = plan.leading_edge_x()
    y = s * math.cos(plan.dihedral)
    z = plan.root_leading_edge[2] + s * math.sin(plan.dihedral)
    masses, points, own = [], [], []
    for name, mps in per_span.items():
        start, end = band_of[name]
        x = x_le + 0.5 * (start + end) * plan.chord
        length = (end - start) * plan.chord
        m = mps * weights
        j = np.flatnonzero(m > 0)
        # each loaded strip on the right half then the left: a slender rod along the chord (m l²/12 about y and z)
        side = np.tile([1.0, -1.0], j.size)
        mj, lj = np.repeat(m[j], 2), np.repeat(length[j], 2)
        masses.append(mj)
        points.append(
            np.stack(
                [np.repeat(x[j], 2), side * np.repeat(y[j], 2) + plan.root_leading_edge[1], np.repeat(z[j], 2)], axis=1
            )
        )
        rods = np.zeros((mj.size, 3, 3))
        rods[:, 1, 1] = rods[:, 2, 2] = 1.0 * mj * lj**2 / 12.0
        own.append(rods)
    return combine_arrays(np.concatenate(masses), np.concatenate(points), np.concatenate(own))
