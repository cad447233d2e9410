"""Component drag build-up: parasite, compressibility, induced drag and configuration increments.

Every function takes numpy arrays (Mach, altitude, CL broadcast together) and returns arrays; SI
units, radians. Coefficients are on the wing reference area of the aircraft file.

Methods and sources
    Skin friction      turbulent flat plate, Prandtl–Schlichting with the compressibility factor
                       (Raymer, *Aircraft Design: A Conceptual Approach*, 6th ed., eq. 12.27);
                       laminar Blasius 1.328/√Re; laminar run followed by turbulent flow by the
                       equivalent-plate composite (Schlichting, *Boundary-Layer Theory*, ch. 21);
                       roughness cut-off Reynolds number, Raymer eq. 12.28 and Table 12.4.
    Form factors       lifting surfaces Raymer eq. 12.30; fuselage Raymer eq. 12.31; nacelles
                       Raymer eq. 12.32.
    Wetted areas       lifting surfaces S_exp (1.977 + 0.52 t/c) (Raymer eq. 7.9/7.10); fuselage
                       Torenbeek, *Synthesis of Subsonic Airplane Design* (1982), App. F:
                       π D L (1 − 2/λ)^(2/3) (1 + 1/λ²), D = √(w h), λ = L/D; nacelles a cylinder.
    Interference Q     Raymer §12.5.5: wing and fuselage 1.0, conventional tail 1.04, a nacelle
                       less than one diameter from the wing 1.3.
    Upsweep            aft-fuselage upsweep, D/q = 3.83 u^2.5 A_max (Raymer eq. 12.36, u in rad), when the
                       file declares ``geometry.fuselage.upsweep``.
    Miscellaneous      leakage and protuberances, 3 % of the component sum and the upsweep term (Raymer
                       §12.5.9: 2–5 % for transports).
    Wave drag          Korn equation with Shevell's sweep extension and Lock's fourth-power rise
                       (Malone & Mason, J. Aircraft 32(2), 1995; Gur, Mason & Schetz, J. Aircraft
                       47(4), 2010).
    Induced drag       CL²/(π A e); Oswald e after Nita & Scholz, "Estimating the Oswald factor
                       from basic aircraft geometrical parameters", DLRK 2012 (doi 10.48441/4427.2602).
    Increments         flaps Raymer eq. 12.61; landing gear Roskam, *Airplane Design* Part I,
                       Table 3.6 (ΔCD0 0.015–0.025); windmilling engine through
                       :func:`certkit.models.propulsion.engine.windmill_drag` (Torenbeek App. G
                       form); spoilers a flat-plate normal-force estimate (Hoerner, *Fluid-Dynamic
                       Drag*, 1965, ch. 3).

A coefficient declared by the user (aircraft file or :class:`DragOverrides`) replaces the estimate;
:attr:`DragBuildUp.overridden` lists every term so replaced, for the report.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable, Mapping

import numpy as np

from certkit import atmosphere as isa
from certkit.aircraft.model import Aircraft, Configuration, Geometry, LiftingSurface, Reference
from certkit.models.aero import planform
from certkit.models.propulsion.engine import windmill_drag

# --- skin friction ----------------------------------------------------------------------------

#: Equivalent sand roughness (m), Raymer Table 12.4 (ft values × 0.3048).
ROUGHNESS = {
    "camouflage paint": 3.33e-5 * 0.3048,
    "smooth paint": 2.08e-5 * 0.3048,
    "production sheet metal": 1.33e-5 * 0.3048,
    "polished sheet metal": 0.50e-5 * 0.3048,
    "smooth moulded composite": 0.17e-5 * 0.3048,
}


def reynolds_per_metre(mach, altitude):
    """ρ V / μ in the ISA (1/m)."""
    return isa.density(altitude) * isa.mach_to_tas(mach, altitude) / isa.dynamic_viscosity(altitude)


def turbulent_skin_friction(reynolds, mach=0.0):
    """Mean turbulent flat-plate Cf = 0.455 / ((log10 Re)^2.58 (1 + 0.144 M²)^0.65), Raymer eq. 12.27."""
    re = np.asarray(reynolds, dtype=float)
    m = np.asarray(mach, dtype=float)
    return 0.455 / (np.log10(re) ** 2.58 * (1.0 + 0.144 * m * m) ** 0.65)


def laminar_skin_friction(reynolds):
    """Mean laminar flat-plate Cf = 1.328/√Re (Blasius)."""
    return 1.328 / np.sqrt(np.asarray(reynolds, dtype=float))


def skin_friction(reynolds, mach=0.0, laminar_fraction=0.0):
    """Mean Cf of a plate laminar over ``laminar_fraction`` of its length, turbulent behind.

    Equivalent-plate composite: Cf = Cf_t(Re) − x_tr [Cf_t(x_tr Re) − Cf_l(x_tr Re)], the
    turbulent layer taken as if it had started at the leading edge (Schlichting, ch. 21).
    """
    re = np.asarray(reynolds, dtype=float)
    xt = np.asarray(laminar_fraction, dtype=float)
    re_tr = np.maximum(xt * re, 10.0)  # guards log10(0); the term is multiplied by x_tr = 0 there
    correction = xt * (turbulent_skin_friction(re_tr, mach) - laminar_skin_friction(re_tr))
    return turbulent_skin_friction(re, mach) - correction


def cutoff_reynolds(length, roughness):
    """Roughness-limited Reynolds number, subsonic: 38.21 (l/k)^1.053 (Raymer eq. 12.28)."""
    return 38.21 * (np.asarray(length, dtype=float) / roughness) ** 1.053


# --- form factors -----------------------------------------------------------------------------


def thickness_form_factor(thickness_ratio, x_max_thickness=0.4):
    """The thickness part of Raymer eq. 12.30: 1 + 0.6/(x/c)_m · t/c + 100 (t/c)⁴ (→ 1 as t/c → 0)."""
    tc = np.asarray(thickness_ratio, dtype=float)
    return 1.0 + 0.6 / x_max_thickness * tc + 100.0 * tc**4


def lifting_surface_form_factor(thickness_ratio, sweep_max_thickness, mach, x_max_thickness=0.4):
    """Raymer eq. 12.30: thickness factor × 1.34 M^0.18 (cos Λ_m)^0.28.

    The fitted Mach factor 1.34 M^0.18 falls below 1 under M ≈ 0.197 and to 0 at M = 0; it is held
    at 1 there, so at low speed the form factor is the thickness factor times the sweep factor.
    """
    mach_factor = np.maximum(1.34 * np.asarray(mach, dtype=float) ** 0.18, 1.0)
    return thickness_form_factor(thickness_ratio, x_max_thickness) * mach_factor * np.cos(sweep_max_thickness) ** 0.28


def fuselage_form_factor(fineness):
    """Raymer eq. 12.31: 1 + 60/f³ + f/400, f = length / equivalent diameter."""
    f = np.asarray(fineness, dtype=float)
    return 1.0 + 60.0 / f**3 + f / 400.0


def nacelle_form_factor(fineness):
    """Raymer eq. 12.32: 1 + 0.35/f."""
    return 1.0 + 0.35 / np.asarray(fineness, dtype=float)


# --- wetted areas -----------------------------------------------------------------------------


@dataclass(frozen=True)
class Trapezoid:
    """A trapezoidal planform: area, full-span aspect ratio b²/S, taper, quarter-chord sweep."""

    area: float
    aspect_ratio: float
    taper: float
    sweep_quarter_chord: float

    @property
    def mean_chord(self) -> float:
        return float(planform.mean_aerodynamic_chord(self.area, self.aspect_ratio, self.taper))

    def sweep_at(self, fraction: float) -> float:
        return float(planform.sweep_at(fraction, self.sweep_quarter_chord, self.aspect_ratio, self.taper))


def surface_planform(surface: LiftingSurface, fin: bool = False) -> Trapezoid:
    """The surface as a full-span trapezoid; a fin (aspect ratio h²/S) is mirrored: A = 2 h²/S."""
    a = 2.0 * surface.aspect_ratio if fin else surface.aspect_ratio
    area = 2.0 * surface.area if fin else surface.area
    return Trapezoid(area, a, surface.taper, surface.sweep_quarter_chord)


def exposed_planform(surface: LiftingSurface, covered_width: float) -> Trapezoid:
    """The trapezoid outboard of a body of width ``covered_width`` centred on the root.

    The chord at the body side is c_r (1 − (1 − λ) w/b); the exposed panels keep the tip chord
    and the quarter-chord sweep (a straight-tapered wing keeps its sweep when cut spanwise).
    """
    b = float(planform.span(surface.area, surface.aspect_ratio))
    c_root = float(planform.root_chord(surface.area, surface.aspect_ratio, surface.taper))
    c_side = c_root * (1.0 - (1.0 - surface.taper) * covered_width / b)
    c_tip = surface.taper * c_root
    area = 0.5 * (b - covered_width) * (c_side + c_tip)
    return Trapezoid(area, (b - covered_width) ** 2 / area, c_tip / c_side, surface.sweep_quarter_chord)


def lifting_surface_wetted_area(exposed_area, thickness_ratio):
    """S_wet = S_exp (1.977 + 0.52 t/c) (Raymer eq. 7.10, t/c > 0.05)."""
    return np.asarray(exposed_area, dtype=float) * (1.977 + 0.52 * np.asarray(thickness_ratio, dtype=float))


def equivalent_diameter(width, height):
    return np.sqrt(np.asarray(width, dtype=float) * np.asarray(height, dtype=float))


def fuselage_wetted_area(length, width, height):
    """Torenbeek (1982, App. F): π D L (1 − 2/λ)^(2/3) (1 + 1/λ²), D = √(w h), λ = L/D."""
    d = equivalent_diameter(width, height)
    lam = np.asarray(length, dtype=float) / d
    return np.pi * d * length * (1.0 - 2.0 / lam) ** (2.0 / 3.0) * (1.0 + 1.0 / lam**2)


def nacelle_wetted_area(length, diameter):
    """The outer cowl as a cylinder, π D L: the boat-tail it overstates roughly offsets the core
    cowl and plug it leaves out (an engineering estimate; no better closed form from L, D alone)."""
    return np.pi * np.asarray(diameter, dtype=float) * np.asarray(length, dtype=float)


# --- components -------------------------------------------------------------------------------


@dataclass(frozen=True)
class Component:
    """One wetted component: its wetted area, Reynolds length, form factor (a function of Mach),
    interference factor Q, laminar fraction of its length, and how many of it there are."""

    name: str
    wetted_area: float
    length: float
    form_factor: Callable[[np.ndarray], np.ndarray]
    interference: float = 1.0
    laminar_fraction: float = 0.0
    count: int = 1


#: Default interference factors, Raymer §12.5.5.
INTERFERENCE = {
    "wing": 1.0,
    "fuselage": 1.0,
    "horizontal tail": 1.04,
    "vertical tail": 1.04,
    "nacelle": 1.3,
    "pylon": 1.0,
}

#: Pylon planform assumed from the nacelle (no schema field): chord = nacelle length, exposed height
#: = 0.3 nacelle diameter, t/c 0.15 — a three-view estimate for under-wing pods.
PYLON_CHORD_PER_NACELLE_LENGTH = 1.0
PYLON_HEIGHT_PER_NACELLE_DIAMETER = 0.3
PYLON_THICKNESS_RATIO = 0.15


def _lifting_component(
    name, surface: LiftingSurface, plan: Trapezoid, x_max_thickness, q, laminar, fin: bool = False
) -> Component:
    tc = surface.thickness_ratio
    sweep_m = plan.sweep_at(x_max_thickness)
    wetted = float(lifting_surface_wetted_area(plan.area / (2.0 if fin else 1.0), tc))
    return Component(
        name,
        wetted,
        plan.mean_chord,
        lambda m: lifting_surface_form_factor(tc, sweep_m, m, x_max_thickness),
        q,
        laminar,
    )


def airframe_components(
    geometry: Geometry,
    *,
    n_nacelles: int = 2,
    x_max_thickness: float = 0.4,
    laminar_fraction: Mapping[str, float] | None = None,
    interference: Mapping[str, float] | None = None,
) -> list[Component]:
    """The wetted components of a tube-and-wing transport from the aircraft-file geometry.

    Wing: exposed outboard of the fuselage width. Tails: the declared areas are taken as exposed
    (the tail roots sit on the narrow tail cone). ``x_max_thickness`` is the chordwise position of
    maximum thickness (0.4 for supercritical sections; Raymer suggests 0.3 low-speed, 0.5 high-speed).
    """
    lam = dict(laminar_fraction or {})
    q = {**INTERFERENCE, **(interference or {})}
    fus = geometry.fuselage
    wing_exposed = exposed_planform(geometry.wing, fus.width)
    parts = [
        _lifting_component("wing", geometry.wing, wing_exposed, x_max_thickness, q["wing"], lam.get("wing", 0.0)),
        _lifting_component(
            "horizontal tail",
            geometry.horizontal_tail,
            surface_planform(geometry.horizontal_tail),
            x_max_thickness,
            q["horizontal tail"],
            lam.get("horizontal tail", 0.0),
        ),
        _lifting_component(
            "vertical tail",
            geometry.vertical_tail,
            surface_planform(geometry.vertical_tail, fin=True),
            x_max_thickness,
            q["vertical tail"],
            lam.get("vertical tail", 0.0),
            fin=True,
        ),
    ]
    fineness = fus.length / float(equivalent_diameter(fus.width, fus.height))
    parts.append(
        Component(
            "fuselage",
            float(fuselage_wetted_area(fus.length, fus.width, fus.height)),
            fus.length,
            lambda m: fuselage_form_factor(fineness),
            q["fuselage"],
            lam.get("fuselage", 0.0),
        )
    )
    nac = geometry.nacelle
    if nac is not None and n_nacelles > 0:
        f_nac = nac.length / nac.diameter
        parts.append(
            Component(
                "nacelle",
                float(nacelle_wetted_area(nac.length, nac.diameter)),
                nac.length,
                lambda m: nacelle_form_factor(f_nac),
                q["nacelle"],
                lam.get("nacelle", 0.0),
                n_nacelles,
            )
        )
        chord = PYLON_CHORD_PER_NACELLE_LENGTH * nac.length
        exposed = chord * PYLON_HEIGHT_PER_NACELLE_DIAMETER * nac.diameter
        parts.append(
            Component(
                "pylon",
                float(lifting_surface_wetted_area(exposed, PYLON_THICKNESS_RATIO)),
                chord,
                lambda m: lifting_surface_form_factor(PYLON_THICKNESS_RATIO, 0.0, m, x_max_thickness),
                q["pylon"],
                lam.get("pylon", 0.0),
                n_nacelles,
            )
        )
    return parts


def upsweep_drag_area(upsweep, max_cross_section):
    """Raymer eq. 12.36: the aft fuselage's upsweep drag area D/q = 3.83 u^2.5 A_max (u in radians, A_max m²)."""
    return 3.83 * np.asarray(upsweep, dtype=float) ** 2.5 * np.asarray(max_cross_section, dtype=float)


def fuselage_upsweep_drag(geometry: Geometry, reference_area: float) -> float:
    """ΔCD0 of the declared fuselage upsweep (zero when none is declared); A_max of the elliptic section w × h."""
    fus = geometry.fuselage
    if fus.upsweep is None:
        return 0.0
    return float(upsweep_drag_area(fus.upsweep, np.pi / 4.0 * fus.width * fus.height)) / reference_area


# --- parasite drag ----------------------------------------------------------------------------


@dataclass
class ComponentDrag:
    """One component's terms at every condition: Re, Cf, FF (arrays) and its CD0 contribution."""

    component: Component
    reynolds: np.ndarray
    skin_friction: np.ndarray
    form_factor: np.ndarray
    CD0: np.ndarray


@dataclass
class ParasiteDrag:
    """CD0 = (1 + misc) (Σ Cf FF Q S_wet / S_ref + ΔCD_upsweep), per condition, with the per-component terms."""

    components: list[ComponentDrag]
    miscellaneous: np.ndarray
    CD0: np.ndarray
    reference_area: float
    upsweep: float = 0.0

    def breakdown(self, index=()) -> "pandas.DataFrame":  # noqa: F821 (pandas imported lazily)
        """Rows name, count, S_wet (m², all of them), Re, Cf, FF, Q, CD0 at condition ``index``."""
        import pandas as pd  # deferred: pandas only for a breakdown table: a check and its workers load no pandas

        rows = [
            {
                "name": c.component.name,
                "count": c.component.count,
                "S_wet": c.component.wetted_area * c.component.count,
                "Re": float(np.asarray(c.reynolds)[index]),
                "Cf": float(np.asarray(c.skin_friction)[index]),
                "FF": float(np.asarray(c.form_factor)[index]),
                "Q": c.component.interference,
                "CD0": float(np.asarray(c.CD0)[index]),
            }
            for c in self.components
        ]
        if self.upsweep:
            rows.append(
                {
                    "name": "fuselage upsweep",
                    "count": 1,
                    "S_wet": np.nan,
                    "Re": np.nan,
                    "Cf": np.nan,
                    "FF": np.nan,
                    "Q": np.nan,
                    "CD0": self.upsweep,
                }
            )
        rows.append(
            {
                "name": "leakage and protuberances",
                "count": 1,
                "S_wet": np.nan,
                "Re": np.nan,
                "Cf": np.nan,
                "FF": np.nan,
                "Q": np.nan,
                "CD0": float(np.asarray(self.miscellaneous)[index]),
            }
        )
        table = pd.DataFrame(rows)
        table["share"] = table["CD0"] / table["CD0"].sum()
        return table


def parasite_drag(
    geometry: Geometry,
    reference: Reference,
    mach,
    altitude,
    *,
    components: list[Component] | None = None,
    miscellaneous_fraction: float = 0.03,
    roughness: float | None = ROUGHNESS["smooth paint"],
    reynolds_per_metre_override=None,
) -> ParasiteDrag:
    """Component build-up of CD0 at arrays of Mach and altitude (broadcast together).

    ``reynolds_per_metre_override`` replaces the ISA unit Reynolds number (e.g. to compare with a
    wind-tunnel test); ``roughness`` (m, :data:`ROUGHNESS`) caps each component's Reynolds number
    at the cut-off value, None for hydraulically smooth surfaces.
    """
    mach = np.asarray(mach, dtype=float)
    altitude = np.asarray(altitude, dtype=float)
    unit_re = (
        reynolds_per_metre(mach, altitude)
        if reynolds_per_metre_override is None
        else np.broadcast_to(np.asarray(reynolds_per_metre_override, dtype=float), np.broadcast(mach, altitude).shape)
    )
    parts = airframe_components(geometry) if components is None else components
    terms = []
    for c in parts:
        re = unit_re * c.length
        if roughness is not None:
            re = np.minimum(re, cutoff_reynolds(c.length, roughness))
        cf = skin_friction(re, mach, c.laminar_fraction)
        ff = np.broadcast_to(c.form_factor(mach), re.shape)
        cd = cf * ff * c.interference * c.wetted_area * c.count / reference.area
        terms.append(ComponentDrag(c, re, cf, ff, cd))
    upsweep = fuselage_upsweep_drag(geometry, reference.area)
    total = sum(t.CD0 for t in terms) + upsweep
    misc = miscellaneous_fraction * total
    return ParasiteDrag(terms, misc, total + misc, reference.area, upsweep)


# --- compressibility drag ---------------------------------------------------------------------

#: Korn airfoil technology factor κ_A (Malone & Mason 1995).
KAPPA_SUPERCRITICAL = 0.95
KAPPA_CONVENTIONAL = 0.87


def drag_divergence_mach(CL, thickness_ratio, sweep, kappa_a=KAPPA_SUPERCRITICAL):
    """Korn–Shevell: M_DD = κ_A/cosΛ − (t/c)/cos²Λ − CL/(10 cos³Λ)."""
    c = np.cos(sweep)
    return kappa_a / c - np.asarray(thickness_ratio, dtype=float) / c**2 - np.asarray(CL, dtype=float) / (10.0 * c**3)


def critical_mach(m_dd):
    """M_crit = M_DD − (0.1/80)^(1/3): where Lock's law reaches dCD/dM = 0.1 at M_DD."""
    return np.asarray(m_dd, dtype=float) - (0.1 / 80.0) ** (1.0 / 3.0)


def wave_drag(mach, CL, thickness_ratio, sweep, kappa_a=KAPPA_SUPERCRITICAL):
    """Lock's fourth-power law: CD_wave = 20 (M − M_crit)⁴ above M_crit, zero below."""
    excess = np.maximum(
        np.asarray(mach, dtype=float) - critical_mach(drag_divergence_mach(CL, thickness_ratio, sweep, kappa_a)), 0.0
    )
    return 20.0 * excess**4


# --- induced drag -----------------------------------------------------------------------------

#: Nita & Scholz (2012) factor for the viscous drag due to lift, jet transports (CD0 ≈ 0.020).
K_E_CD0_JET = 0.873


def planform_span_efficiency(aspect_ratio, taper, sweep_quarter_chord):
    """Nita & Scholz theoretical e: 1/(1 + f(λ − Δλ) A), Hoerner's f and the sweep shift
    Δλ = −0.357 + 0.45 exp(−0.0375 Λ[deg])."""
    dl = -0.357 + 0.45 * np.exp(-0.0375 * np.degrees(sweep_quarter_chord))
    x = np.asarray(taper, dtype=float) - dl
    f = 0.0524 * x**4 - 0.15 * x**3 + 0.1659 * x**2 - 0.0706 * x + 0.0119
    return 1.0 / (1.0 + f * np.asarray(aspect_ratio, dtype=float))


def oswald_efficiency(
    aspect_ratio, taper, sweep_quarter_chord, fuselage_diameter, span, k_cd0=K_E_CD0_JET, inviscid_span_efficiency=None
):
    """Oswald e after Nita & Scholz: e_theo · (1 − 2 (d_F/b)²) · k_e,D0.

    With ``inviscid_span_efficiency`` (a vortex-lattice Trefftz-plane e, which already contains the
    planform and the fuselage it models) e = e_lattice · k_e,D0. Their Mach factor k_e,M is not
    applied: it falls to zero near M 0.85, and the compressibility drag here is the Lock term.
    """
    if inviscid_span_efficiency is not None:
        return np.asarray(inviscid_span_efficiency, dtype=float) * k_cd0
    k_fuselage = 1.0 - 2.0 * (np.asarray(fuselage_diameter, dtype=float) / span) ** 2
    return planform_span_efficiency(aspect_ratio, taper, sweep_quarter_chord) * k_fuselage * k_cd0


def induced_drag(CL, aspect_ratio, oswald):
    """CDi = CL² / (π A e)."""
    return np.asarray(CL, dtype=float) ** 2 / (np.pi * aspect_ratio * np.asarray(oswald, dtype=float))


# --- increments -------------------------------------------------------------------------------

#: Raymer eq. 12.61 flap constants F_flap (per degree above 10°).
FLAP_FACTOR = {"plain": 0.0144, "split": 0.0144, "slotted": 0.0074}
#: Roskam Part I Table 3.6, landing gear ΔCD0 0.015–0.025: the middle of the band.
LANDING_GEAR_DELTA_CD0 = 0.020


def flap_drag_increment(deflection, flap_type="slotted", chord_ratio=0.30, flapped_area_ratio=0.60):
    """Raymer eq. 12.61: ΔCD0 = F_flap (c_f/c)(S_flapped/S_ref)(δ_f[deg] − 10), zero below 10°.

    Defaults (no schema fields): flap chord 30 %, flapped area 60 % of the reference area, the
    values of a large twin's inboard and outboard single/double-slotted flaps.
    """
    excess = np.maximum(np.degrees(np.asarray(deflection, dtype=float)) - 10.0, 0.0)
    return FLAP_FACTOR[flap_type] * chord_ratio * flapped_area_ratio * excess


def landing_gear_drag_increment(gear: str) -> float:
    """Roskam Part I Table 3.6 class-I increment (middle of 0.015–0.025) when the gear is down."""
    return LANDING_GEAR_DELTA_CD0 if gear == "down" else 0.0


def configuration_drag_increment(configuration: Configuration, **flap_options) -> tuple[float, bool]:
    """(ΔCD0, declared): the file's ``delta_CD0`` when non-zero (it covers flaps, slats and gear),
    else flaps by Raymer eq. 12.61 plus gear by Roskam Part I; slats add no estimated increment."""
    if configuration.delta_CD0 != 0.0:
        return configuration.delta_CD0, True
    estimate = float(flap_drag_increment(configuration.flap, **flap_options)) + landing_gear_drag_increment(
        configuration.gear
    )
    return estimate, False


def windmilling_drag_coefficient(mach, altitude, inlet_diameter, reference_area, n_failed=1):
    """ΔCD of ``n_failed`` windmilling turbofans: the propulsion model's drag over q S."""
    mach = np.asarray(mach, dtype=float)
    q = 0.5 * isa.GAMMA * isa.pressure(altitude) * mach**2
    drag = windmill_drag(inlet_diameter)(q, mach)
    return n_failed * drag / (np.maximum(q, 1e-9) * reference_area)


def spoiler_drag_increment(deflection, spoiler_area, reference_area, normal_force_coefficient=1.2):
    """ΔCD ≈ C_N (S_sp/S) sin²δ: the panel's normal force (Hoerner flat plate, C_N ≈ 1.2) resolved
    along the wind. An upper estimate: the panel sits in the wing's boundary layer."""
    s = np.sin(np.asarray(deflection, dtype=float))
    return normal_force_coefficient * spoiler_area / reference_area * s * s


# --- the build-up -----------------------------------------------------------------------------


@dataclass(frozen=True)
class DragOverrides:
    """Declared coefficients that replace the estimates (None: estimate)."""

    CD0: float | None = None
    oswald_efficiency: float | None = None
    delta_CD0: float | None = None
    drag_divergence_mach: float | None = None


@dataclass
class DragBuildUp:
    """Drag terms per condition (arrays broadcast over Mach, altitude, CL)."""

    CL: np.ndarray
    CD0: np.ndarray
    CD_wave: np.ndarray
    CDi: np.ndarray
    delta_CD0: np.ndarray
    oswald_efficiency: np.ndarray
    parasite: ParasiteDrag
    overridden: tuple[str, ...] = field(default_factory=tuple)

    @property
    def CD(self) -> np.ndarray:
        return self.CD0 + self.CD_wave + self.CDi + self.delta_CD0

    @property
    def lift_to_drag(self) -> np.ndarray:
        return self.CL / self.CD


def drag_buildup(
    aircraft: Aircraft,
    mach,
    altitude,
    CL,
    *,
    configuration: str = "clean",
    inviscid_span_efficiency=None,
    overrides: DragOverrides | None = None,
    kappa_a: float = KAPPA_SUPERCRITICAL,
    **parasite_options,
) -> DragBuildUp:
    """Total drag CD = CD0 + CD_wave + CDi + ΔCD0(configuration) for the aircraft at arrays of
    Mach, altitude and CL. ``inviscid_span_efficiency`` is the lattice e when available;
    ``parasite_options`` go to :func:`parasite_drag`."""
    ov = overrides or DragOverrides()
    g, ref = aircraft.geometry, aircraft.reference
    mach, altitude, CL = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (mach, altitude, CL)))
    overridden = []

    parasite = parasite_drag(g, ref, mach, altitude, **parasite_options)
    cd0 = parasite.CD0
    if ov.CD0 is not None:
        cd0, _ = np.broadcast_arrays(np.float64(ov.CD0), mach)
        overridden.append("CD0")

    wing = g.wing
    if ov.drag_divergence_mach is not None:
        excess = np.maximum(mach - critical_mach(ov.drag_divergence_mach), 0.0)
        cd_wave = 20.0 * excess**4
        overridden.append("drag_divergence_mach")
    else:
        cd_wave = wave_drag(mach, CL, wing.thickness_ratio, wing.sweep_quarter_chord, kappa_a)

    if ov.oswald_efficiency is not None:
        e = np.full_like(mach, ov.oswald_efficiency)
        overridden.append("oswald_efficiency")
    else:
        d_fus = float(equivalent_diameter(g.fuselage.width, g.fuselage.height))
        e = np.broadcast_to(
            oswald_efficiency(
                wing.aspect_ratio,
                wing.taper,
                wing.sweep_quarter_chord,
                d_fus,
                ref.span,
                inviscid_span_efficiency=inviscid_span_efficiency,
            ),
            mach.shape,
        )

    if ov.delta_CD0 is not None:
        delta, declared = ov.delta_CD0, True
        overridden.append("delta_CD0")
    else:
        delta, declared = configuration_drag_increment(aircraft.configurations[configuration])
        if declared:
            overridden.append(f"delta_CD0 ({configuration}, aircraft file)")

    return DragBuildUp(
        CL,
        cd0,
        cd_wave,
        induced_drag(CL, wing.aspect_ratio, e),
        np.full_like(mach, delta),
        e,
        parasite,
        tuple(overridden),
    )


__all__ = [
    "ROUGHNESS",
    "INTERFERENCE",
    "KAPPA_SUPERCRITICAL",
    "KAPPA_CONVENTIONAL",
    "reynolds_per_metre",
    "turbulent_skin_friction",
    "laminar_skin_friction",
    "skin_friction",
    "cutoff_reynolds",
    "thickness_form_factor",
    "lifting_surface_form_factor",
    "fuselage_form_factor",
    "nacelle_form_factor",
    "Trapezoid",
    "surface_planform",
    "exposed_planform",
    "lifting_surface_wetted_area",
    "equivalent_diameter",
    "fuselage_wetted_area",
    "nacelle_wetted_area",
    "Component",
    "airframe_components",
    "upsweep_drag_area",
    "fuselage_upsweep_drag",
    "ComponentDrag",
    "ParasiteDrag",
    "parasite_drag",
    "drag_divergence_mach",
    "critical_mach",
    "wave_drag",
    "planform_span_efficiency",
    "oswald_efficiency",
    "induced_drag",
    "flap_drag_increment",
    "landing_gear_drag_increment",
    "configuration_drag_increment",
    "windmilling_drag_coefficient",
    "spoiler_drag_increment",
    "DragOverrides",
    "DragBuildUp",
    "drag_buildup",
]
