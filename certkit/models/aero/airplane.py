"""The aerodynamic model of a whole airplane in one configuration — the object the rules use.

Built once per aircraft and configuration (the Context caches it) and evaluated on arrays of
states (:class:`certkit.models.aero.derivative_model.StabilityDerivativeModel`). Two sources:

* **declared tables** (``aerodynamics.derivative_tables.<config>``): wind-tunnel, CFD or published
  derivatives, used as they are; no geometry beyond the reference values is needed;
* **estimated**: the vortex lattice of the wing, horizontal and vertical tails (own solver,
  :mod:`certkit.models.aero.vlm`) at several Mach numbers gives lift, moment and lateral stability
  and control derivatives, wing–tail interference included; the fuselage contributions to Cm_α and
  Cn_β (:mod:`certkit.models.aero.fuselage`) and the drag build-up (:mod:`certkit.models.aero.drag`)
  are added; high-lift increments come from the configuration (declared ΔCL0, ΔCD0, ΔCm0, or the
  lattice's flap derivative times the flap angle) with the tail's share from the change of downwash
  (declared, or a lattice with the flap deflected), the downwash-lag CL_α̇, Cm_α̇ from the tail's
  downwash gradient (:mod:`certkit.models.aero.tail_downwash`), and the stall from the configuration's CLmax.

Any coefficient named in ``aerodynamics.overrides.<config>`` replaces its estimate; every
replacement is recorded so that the report lists it.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from scipy.optimize import brentq

from certkit.aircraft.derivative_names import STABILIZER
from certkit.atmosphere import cas_to_mach
from certkit.models.aero.derivative_forms import nondimensional_table
from certkit.models.aero.derivative_model import StabilityDerivativeModel, StallModel
from certkit.models.aero.drag import configuration_drag_increment, drag_buildup
from certkit.models.aero.fuselage import fuselage_derivatives
from certkit.models.aero.high_lift import FlapSettings, estimated_clmax, lift_and_moment_increment
from certkit.models.aero.interface import AeroReference
from certkit.models.aero.tail_downwash import WING, downwash_lag, flap_at_tail, free_air_downwash, slopes
from certkit.models.aero.vlm import Configuration as LatticeConfiguration
from certkit.models.aero.vlm import ControlSpan, VortexLattice, trapezoidal_surface
from certkit.models.reference_condition import reference_condition

#: Mach breakpoints at which the lattice is solved; the model interpolates between them
DEFAULT_MACHS = (0.2, 0.4, 0.6, 0.75, 0.84, 0.9)
#: the highest breakpoint added for a declared MD beyond them: the Prandtl–Glauert stretch is 1/β = 3.2 at M 0.95
#: (the normal Mach of a 30°-swept wing 0.82); a higher MD stays beyond the model's range (its conditions set aside)
MAX_MACH_BREAKPOINT = 0.95


def mach_breakpoints(aircraft) -> tuple[float, ...]:
    """The Mach breakpoints of the aircraft's lattice: :data:`DEFAULT_MACHS`, and its declared MD where that lies
    beyond them (up to :data:`MAX_MACH_BREAKPOINT`), so that the dive Mach number's loads and handling are
    computed rather than extrapolated. Above the drag-divergence Mach number the linear (Prandtl–Glauert) lattice
    over-states the lift slope and misses the shock-induced changes of the moment (Mach tuck): a named model limit,
    written in the model's notes."""
    speeds = getattr(aircraft, "speeds", None)
    md = getattr(speeds, "MD", None) if speeds is not None else None
    if md is None or md <= DEFAULT_MACHS[-1] + 1e-3 or md > MAX_MACH_BREAKPOINT:
        return DEFAULT_MACHS
    return (*DEFAULT_MACHS, round(float(md), 4))


#: lift coefficient at which the wave drag is folded into CD0(M) (transport design CL, as the CRM's)
DESIGN_CL = 0.5
#: calibrated airspeed of the climb schedule that fixes the Reynolds number at each Mach breakpoint
SCHEDULE_CAS = 300 * 1852 / 3600
COEFFICIENTS = ("CL", "CD", "CY", "Cl", "Cm", "Cn")
#: the wing's flap as a lattice control, in the airplane's lattice (:func:`lattice_derivatives`, shared with the strip
#: loads) and :func:`downwash_configurations`' (the flight model's flap increments are the configuration's,
#: :func:`_high_lift`: the flap is not a control of the flight model)
FLAP_CONTROL = "flap"
#: the lattice's tail lift and moment increments per unit flap lift increment of the wing (not model terms)
FLAP_TAIL_TERMS = ("tail_CL_per_flap_CL", "tail_Cm_per_flap_CL")
#: the table's entry holding the free-air downwash at the tail (not a model term; lowest Mach breakpoint)
FREE_AIR_DOWNWASH = "free_air_downwash"
#: lattice derivatives carried into the flight model (the others are zero by symmetry or not used)
CARRIED = (
    "CL_alpha",
    "CL_q",
    "CY_beta",
    "CY_p",
    "CY_r",
    "Cl_beta",
    "Cl_p",
    "Cl_r",
    "Cm_alpha",
    "Cm_q",
    "Cn_beta",
    "Cn_p",
    "Cn_r",
)


def aero_reference(aircraft) -> AeroReference:
    r = aircraft.reference
    return AeroReference(r.area, r.span, r.mean_chord, r.moment_point.x, r.moment_point.z)


def _camber_digits(airfoil: str) -> str | None:
    digits = airfoil.strip().upper().removeprefix("NACA").strip()
    return digits if len(digits) == 4 and digits.isdigit() else None


#: span fractions of the extra sections of a twisted surface: the lattice interpolates the incidence between sections
#: through the chord projections (as AVL does), which on a tapered surface keeps the larger inboard chord's angle
#: over most of the interval; with sections every eighth of the span the declared linear twist is represented within
#: 0.01° (with the control edges alone the baseline's wing had 0.8° more incidence at mid-semispan, and the lattice's
#: zero-α lift depended on where the controls end)
TWIST_SECTIONS = tuple(k / 8 for k in range(1, 8))


def _flap_span(wing) -> list[ControlSpan]:
    """The wing's trailing-edge flap as the lattice control :data:`FLAP_CONTROL` (none when no flap is declared)."""
    f = wing.flaps
    return [] if f is None else [ControlSpan(FLAP_CONTROL, f.span_start, f.span_end, f.chord_ratio, kind="symmetric")]


def _surface(
    name: str,
    s,
    resolution,
    *,
    vertical: bool = False,
    component: int | None = None,
    controls=None,
    extra_controls=(),
):
    """A lattice surface from an aircraft-file lifting surface, with its controls (or only ``controls``, a list of
    :class:`ControlSpan`), ``extra_controls`` after them, and tip twist."""
    if controls is None:
        controls = [
            span
            for cname, c in s.controls.items()
            for span in [ControlSpan(cname, c.span_start, c.span_end, c.chord_ratio)]
            + [ControlSpan(cname, g.span_start, g.span_end, g.chord_ratio, gain=g.gain) for g in c.segments]
        ]
        if s.stabilizer is not None and not vertical:
            # a movable stabiliser: the whole chord turns about the lateral (pitch) axis, i.e. a change of the tail's
            # incidence from its declared datum (the control's deflection δs = i_h − incidence)
            controls.append(ControlSpan(STABILIZER, 0.0, 1.0, 1.0, hinge_vector=(0.0, 1.0, 0.0)))
    controls = list(controls) + list(extra_controls)
    surface = trapezoidal_surface(
        name,
        area=s.area,
        aspect_ratio=s.aspect_ratio,
        taper=s.taper,
        sweep_quarter_chord=s.sweep_quarter_chord,
        dihedral=s.dihedral,
        root_leading_edge=(s.root_leading_edge.x, s.root_leading_edge.y, s.root_leading_edge.z),
        incidence=s.incidence,
        thickness_ratio=s.thickness_ratio,
        camber=_camber_digits(s.airfoil),
        vertical=vertical,
        controls=controls,
        n_chord=resolution.chordwise,
        n_span=resolution.spanwise,
        chord_spacing=1.0,
        span_spacing=1.0,
        component=component,
        section_etas=TWIST_SECTIONS if s.tip_twist and not vertical else (),
    )
    if s.tip_twist and not vertical:
        root_y = surface.sections[0].leading_edge[1]
        semi = surface.sections[-1].leading_edge[1] - root_y
        surface = replace(
            surface,
            sections=[
                replace(sec, incidence=sec.incidence + s.tip_twist * (sec.leading_edge[1] - root_y) / semi)
                for sec in surface.sections
            ],
        )
    return surface


def with_carry_through(surface, z_axis: float):
    """The fin continued below its root to the fuselage axis with the root chord and no control:
    the lattice's stand-in for the fuselage acting as the fin's end plate, the same treatment the
    wing and tailplane get by running to the plane of symmetry (a fin floating above the body
    would shed its root vortex and lose the end-plate lift, cf. DATCOM §5.3.1.1 where the body
    raises a fin's effective aspect ratio)."""
    root = surface.sections[0]
    x, y, z = root.leading_edge
    if z - z_axis <= 1e-9:
        return surface
    base = replace(root, leading_edge=(x, y, z_axis), controls=[])
    return replace(surface, sections=[base] + list(surface.sections))


def lattice_configuration(aircraft, name: str = "", flap: bool = False) -> LatticeConfiguration:
    """Wing (component 1), horizontal tail and fin (component 2) as a lattice configuration; each
    surface reaches the fuselage axis (wing and tailplane through the plane of symmetry, the fin
    down to z = 0 by :func:`with_carry_through`). ``flap``: the wing's trailing-edge flap (when declared) as one
    more control, :data:`FLAP_CONTROL` (the lattice of :func:`lattice_derivatives`, whose flap unit solution the strip
    loads use)."""
    g = aircraft.geometry
    if g is None:
        raise ValueError("the vortex lattice needs the geometry section (or declare aerodynamics.derivative_tables)")
    res = aircraft.aerodynamics.lattice
    fin = _surface("vertical_tail", g.vertical_tail, res, vertical=True, component=2)
    flaps = _flap_span(g.wing) if flap else []
    surfaces = [
        _surface("wing", g.wing, res, component=1, extra_controls=flaps),
        _surface("horizontal_tail", g.horizontal_tail, res, component=2),
        with_carry_through(fin, 0.0),
    ]
    return LatticeConfiguration(surfaces, aero_reference(aircraft), name=name)


#: strips per half-wing and chordwise vortices of the lattice that gives the downwash at the tail (converged within
#: about 2 % on the baseline, see :mod:`certkit.models.aero.tail_downwash`)
DOWNWASH_WING_STRIPS = 64
DOWNWASH_CHORDWISE = 4


def downwash_configurations(aircraft) -> tuple[LatticeConfiguration, LatticeConfiguration]:
    """Wing (at least :data:`DOWNWASH_WING_STRIPS` strips per half, its trailing-edge flap as the control
    :data:`FLAP_CONTROL` when it has one) with the horizontal tail, and the same tail alone: the downwash at the tail
    (the fin carries no load in symmetric flow and is left out)."""
    g = aircraft.geometry
    res = aircraft.aerodynamics.lattice.model_copy(update={"chordwise": DOWNWASH_CHORDWISE})
    strips = max(DOWNWASH_WING_STRIPS, res.spanwise)
    wing = _surface(
        "wing", g.wing, res.model_copy(update={"spanwise": strips}), component=1, controls=_flap_span(g.wing)
    )
    tail = _surface("horizontal_tail", g.horizontal_tail, res, component=2, controls=[])
    ref = aero_reference(aircraft)
    return (
        LatticeConfiguration([wing, tail], ref, name="wing and horizontal tail (downwash)"),
        LatticeConfiguration([tail], ref, name="horizontal tail alone"),
    )


def flight_controls(vl: VortexLattice) -> tuple[str, ...]:
    """The lattice's controls that are the flight model's: all but the wing's flap (:data:`FLAP_CONTROL`), whose unit
    solution only the strip loads use."""
    return tuple(c for c in vl.control_names if c != FLAP_CONTROL)


@dataclass
class AirplaneAero:
    """One configuration's aerodynamic model and its provenance."""

    configuration: str
    model: StabilityDerivativeModel
    mach: tuple[float, ...]
    table: dict[str, list[float]]
    source: str
    neutral_point: list[float] | None = None
    span_efficiency: list[float] | None = None
    overrides: dict[str, dict] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)
    lattice: VortexLattice | None = field(default=None, repr=False)


#: what :func:`lattice_derivatives` returns: the table (name → one value per Mach number; two entries hold objects),
#: the neutral points, the span efficiencies and the lattice
LatticeDerivatives = tuple[dict[str, Any], list[float], list[float], VortexLattice]


def lattice_derivatives(aircraft: Any, machs: Sequence[float] | None = None) -> LatticeDerivatives:
    """Derivatives at α = 0 for each Mach number (None: :func:`mach_breakpoints`): (table name → values, neutral
    points, e, lattice).

    The table also holds the downwash-lag derivatives CL_alphadot, Cm_alphadot at each Mach number, for a
    wing with flaps the tail's flap ratios :data:`FLAP_TAIL_TERMS` at the lowest one, and the free-air downwash at the
    tail there (:data:`FREE_AIR_DOWNWASH`, a :class:`~certkit.models.aero.tail_downwash.FreeAirDownwash`)
    (:mod:`certkit.models.aero.tail_downwash`)."""
    machs = mach_breakpoints(aircraft) if machs is None else machs
    # one lattice for the flight model and the strip loads: the wing's flap is a control of it (the loads spread the
    # configurations' flap lift with its unit solution), not a control of the flight model (the configurations'
    # flap increments are :func:`_high_lift`'s)
    vl = VortexLattice(lattice_configuration(aircraft, flap=True), mach=machs[0])
    on, alone = downwash_configurations(aircraft)
    wing_tail, tail = VortexLattice(on, mach=machs[0]), VortexLattice(alone, mach=machs[0])
    free_air = free_air_downwash(wing_tail, tail)
    gradient_low = free_air.gradient
    table: dict[str, Any] = {}
    xnp: list[float] = []
    e: list[float] = []
    wing_slope: list[float] = []
    for m in machs:
        lat = vl.at_mach(m)
        d = lat.stability_derivatives(alpha=0.0)
        sol = d.solution
        for key in CARRIED:
            table.setdefault(key, []).append(d[key])
        wing_slope.append(slopes(lat, WING)[0])
        lag = downwash_lag(gradient_low * wing_slope[-1] / wing_slope[0], lat, tail.at_mach(m))
        table.setdefault("CL_alphadot", []).append(lag.CL_alphadot)
        table.setdefault("Cm_alphadot", []).append(lag.Cm_alphadot)
        for cname in flight_controls(lat):
            for coef in COEFFICIENTS:
                table.setdefault(f"{coef}_{cname}", []).append(d[f"{coef}_delta_{cname}"])
        table.setdefault("CL0", []).append(sol.CL)
        table.setdefault("Cm0", []).append(sol.Cm)
        xnp.append(d.neutral_point)
        e.append(sol.span_efficiency)
    if aircraft.geometry.wing.flaps is not None:
        at_tail = flap_at_tail(wing_tail, tail, FLAP_CONTROL)
        table[FLAP_TAIL_TERMS[0]] = [at_tail.CL_per_wing_CL] * len(machs)
        table[FLAP_TAIL_TERMS[1]] = [at_tail.Cm_per_wing_CL] * len(machs)
    table[FREE_AIR_DOWNWASH] = free_air
    return table, xnp, e, vl


def schedule_altitude(aircraft, machs) -> np.ndarray:
    """Altitude where the 300 KCAS climb schedule reaches each Mach number (sea level below it, the
    ceiling above it): the Reynolds number of the drag build-up at that Mach breakpoint."""
    top = aircraft.envelope.ceiling
    out = []
    for m in machs:
        f = lambda h, m=m: float(cas_to_mach(SCHEDULE_CAS, h)) - m  # noqa: E731  (Mach rises with altitude at fixed CAS)
        out.append(0.0 if f(0.0) >= 0 else top if f(top) <= 0 else brentq(f, 0.0, top))
    return np.array(out)


def drag_terms(aircraft, machs) -> tuple[list[float], list[float], list[str]]:
    """CD0(M) (parasite at the schedule's Reynolds number plus wave drag at the design CL) and the
    induced-drag factor k = 1/(π A e) (Oswald e of the drag build-up), clean configuration."""
    machs = np.asarray(machs, dtype=float)
    b = drag_buildup(aircraft, machs, schedule_altitude(aircraft, machs), DESIGN_CL)
    k = 1.0 / (np.pi * aircraft.geometry.wing.aspect_ratio * b.oswald_efficiency)
    notes = [f"CD0 includes wave drag at CL {DESIGN_CL} (Korn/Lock); Reynolds number on the 300 KCAS climb schedule"]
    factor = drag_factor(aircraft)
    if factor != 1.0:
        notes.append(
            f"zero-lift drag of the build-up (parasite and wave) × {factor:.4f}: the declared performance "
            f"calibration ({aircraft.calibration.source})"
        )
    return list(factor * (b.CD0 + b.CD_wave)), list(k), notes


def drag_factor(aircraft) -> float:
    """The declared calibration's factor on the build-up's zero-lift drag (1 without a ``calibration:`` section)."""
    cal = getattr(aircraft, "calibration", None)
    return 1.0 if cal is None else float(cal.drag_factor)


def fuselage_terms(aircraft) -> dict[str, float]:
    """Fuselage Cm_α (Gilruth & White), Cn_β (Raymer 16.50) and CY_β (DATCOM 5.2.1.1) increments, per radian."""
    f = fuselage_derivatives(aircraft.geometry, aircraft.reference)
    return {"Cm_alpha": f.Cm_alpha, "Cn_beta": f.Cn_beta, "CY_beta": f.CY_beta}


def build_airplane_aero(
    aircraft, configuration: str, machs=None, drag=drag_terms, fuselage=fuselage_terms, lattice=None
) -> AirplaneAero:
    """The model of ``configuration``: declared tables if any, else the lattice estimate at ``machs`` (None:
    :func:`mach_breakpoints`; ``lattice``: the result of :func:`lattice_derivatives` at the same Mach numbers, shared
    between configurations).

    ``drag(aircraft, machs) -> (CD0 list, k list, notes)`` and ``fuselage(aircraft) -> {"Cm_alpha": Δ,
    "Cn_beta": Δ}`` supply the semi-empirical terms (None leaves them out).
    """
    cfg = aircraft.configurations[configuration]
    declared = aircraft.aerodynamics.derivative_tables.get(configuration)
    notes: list[str] = []
    clmax = cfg.CLmax
    if clmax is None and aircraft.geometry is not None:
        clmax = estimated_clmax(aircraft.geometry.wing, cfg, FlapSettings.of(aircraft.configurations))
        notes.append(f"configuration {configuration}: CLmax {clmax:.2f} estimated (Raymer eqs 12.15, 12.21)")
    elif clmax is None:
        notes.append(f"configurations.{configuration}.CLmax not declared: no stall model")
    stall = StallModel(clmax) if clmax else None
    if cfg.CLmax_by_mach is not None and stall is not None:
        notes.append(
            f"configuration {configuration}: CLmax against Mach from CLmax_by_mach ({cfg.CLmax_by_mach.source})"
        )
    ref = aero_reference(aircraft)
    tail_downwash = None  # the free-air downwash at the tail (lattice only): the ground effect at the tail needs it
    flap_lift = None  # the flap lift increments on the wing and the tail (lattice only): the strip loads spread them
    if declared is not None:
        nd = nondimensional_table(declared, aircraft, reference_condition(aircraft))
        table, machs, controls = nd.derivatives, nd.mach, nd.controls
        notes += nd.notes
        result = AirplaneAero(
            configuration, None, tuple(machs), table, f"declared table: {declared.source}", notes=notes
        )
    else:
        table, xnp, e, vl = lattice if lattice is not None else lattice_derivatives(aircraft, machs)
        controls = flight_controls(vl)
        free_air = table.get(FREE_AIR_DOWNWASH)
        table = {k: list(v) for k, v in table.items() if k != FREE_AIR_DOWNWASH}
        flap_tail = [table.pop(k, None) for k in FLAP_TAIL_TERMS]
        machs = tuple(mach_breakpoints(aircraft) if machs is None else machs)
        if len(machs) != len(table["CL0"]):
            raise ValueError(f"the lattice's tables hold {len(table['CL0'])} Mach numbers, not the {len(machs)} asked")
        if machs[-1] > DEFAULT_MACHS[-1] + 1e-3:
            notes.append(
                f"lattice solved up to MD = M {machs[-1]:g} (Prandtl–Glauert): beyond drag divergence it over-states "
                "the lift slope and has no shock-induced moment change (Mach tuck)"
            )
        result = AirplaneAero(
            configuration,
            None,
            tuple(machs),
            table,
            "vortex lattice (certkit.models.aero.vlm)",
            neutral_point=xnp,
            span_efficiency=e,
            notes=notes,
            lattice=vl,
        )
        if fuselage is not None:
            for key, delta in fuselage(aircraft).items():
                table[key] = [v + delta for v in table[key]]
            result.source += " + fuselage corrections"
        if drag is not None:
            cd0, k, drag_notes = drag(aircraft, machs)
            table["CD0"], table["k"] = list(cd0), list(k)
            result.source += " + drag build-up"
            notes += drag_notes
        tail_flap_cl, flap_lift = _high_lift(aircraft, configuration, cfg, table, notes, flap_tail)
        if free_air is not None:
            tail_downwash = free_air.with_flap(tail_flap_cl)
    for key, value in aircraft.aerodynamics.overrides.get(configuration, {}).items():
        estimate = table.get(key)
        table[key] = value
        result.overrides[key] = {"estimate": estimate, "value": value, "source": aircraft.aerodynamics.overrides_source}
    try:
        result.model = StabilityDerivativeModel(
            ref,
            table,
            mach=machs,
            control_names=controls,
            stall=stall if cfg.CLmax_by_mach is None or stall is None else replace(stall, CLmax=cfg.clmax_at(machs)),
            tail_downwash=tail_downwash,
            flap_lift=flap_lift,
        )
    except KeyError as exc:
        raise ValueError(f"aerodynamics of configuration {configuration!r}: {exc.args[0]}") from None
    return result


def _high_lift(aircraft, name, cfg, table, notes, flap_tail=(None, None)) -> tuple[float, list[float] | None]:
    """ΔCL0, ΔCm0 of the configuration: declared increments, else Raymer's estimate from the wing's flaps
    (:mod:`certkit.models.aero.high_lift`), else the lattice's flap derivative × angle (tail-on already);
    the first two are tail-off, so the tail's share (:func:`_tail_flap_share`) is added to them. Returns the tail's
    lift share at the lowest Mach breakpoint (0 when none is added: its downwash change is then not known) and the
    lift increments on the wing (tail off) and on the tail, per Mach breakpoint, where the wing has a declared flap
    to carry them (else None)."""
    wing = aircraft.geometry.wing
    flap_cl, flap_cm = table.get("CL_flap"), table.get("Cm_flap")
    if cfg.delta_CL0 or cfg.delta_Cm0 or not cfg.flap:
        d_cl = [cfg.delta_CL0] * len(table["CL0"])
        d_cm = [cfg.delta_Cm0] * len(table["CL0"])
    elif wing.flaps is not None:
        ref = aircraft.reference
        settings = FlapSettings.of(aircraft.configurations)
        pairs = [
            lift_and_moment_increment(wing, wing.flaps, cfg.flap, a, ref.moment_point.x, ref.mean_chord, settings)
            for a in table["CL_alpha"]
        ]
        d_cl, d_cm = [p[0] for p in pairs], [p[1] for p in pairs]
        notes.append(
            f"configuration {name}: flap lift and moment increments estimated (Raymer eq. 12.22, "
            f"{settings.zero_lift_shift_basis(cfg.flap)}; ΔCL0 {d_cl[0]:.3f}, ΔCm0 {d_cm[0]:.3f} at the lowest Mach "
            "breakpoint)"
        )
    elif flap_cl is not None:
        d_cl = [d * cfg.flap for d in flap_cl]
        d_cm = [d * cfg.flap for d in flap_cm]
        notes.append(
            f"configuration {name}: flap increments from the lattice (linear theory; overestimates large deflections)"
        )
    else:
        d_cl = d_cm = [0.0] * len(table["CL0"])
        notes.append(
            f"configuration {name}: flap {np.degrees(cfg.flap):.0f} deg has no declared increments and "
            "no flap on the wing: lift and moment increments not modelled"
        )
    tail_off = bool(cfg.delta_CL0 or cfg.delta_Cm0) or wing.flaps is not None  # declared or Raymer: tail-off
    tail_cl = 0.0
    wing_cl = list(d_cl)
    if cfg.flap > 0 and tail_off:
        d_cl, d_cm = _tail_flap_share(name, cfg, d_cl, d_cm, flap_tail, notes)
        tail_cl = d_cl[0] - wing_cl[0]
    lift = [wing_cl, [t - w for t, w in zip(d_cl, wing_cl)]] if wing.flaps is not None and tail_off else None
    table["CL0"] = [v + d for v, d in zip(table["CL0"], d_cl)]
    table["Cm0"] = [v + d for v, d in zip(table["Cm0"], d_cm)]

    delta, declared = configuration_drag_increment(cfg)
    if delta:
        table["CD0"] = [v + delta for v in table.get("CD0", [0.0] * len(table["CL0"]))]
        if not declared:
            notes.append(f"configuration {name}: ΔCD0 {delta:.4f} estimated (flaps Raymer 12.61, gear Roskam Part I)")
    return tail_cl, lift


def _tail_flap_share(name, cfg, d_cl, d_cm, flap_tail, notes):
    """The tail-off flap increments (d_cl, d_cm per Mach breakpoint) with the horizontal tail's share added: the
    declared ``tail_flap_increment``, else the lattice's tail increments per unit wing flap lift
    (:func:`certkit.models.aero.tail_downwash.flap_at_tail`) times the wing's ΔCL0."""
    declared = cfg.tail_flap_increment
    if declared is not None:
        notes.append(
            f"configuration {name}: tail share of the flap increments declared (ΔCL {declared.delta_CL:+.4f}, "
            f"ΔCm {declared.delta_Cm:+.4f}; {declared.source})"
        )
        return [d + declared.delta_CL for d in d_cl], [d + declared.delta_Cm for d in d_cm]
    per_cl, per_cm = flap_tail
    if per_cl is None:
        notes.append(
            f"configuration {name}: no flap on the lattice's wing: the change of downwash at the tail with "
            "the flaps down is not modelled (the flap increments are tail-off)"
        )
        return d_cl, d_cm
    t_cl = [r * d for r, d in zip(per_cl, d_cl)]
    t_cm = [r * d for r, d in zip(per_cm, d_cl)]
    notes.append(
        f"configuration {name}: tail share of the flap increments from the change of downwash in the vortex "
        f"lattice with the flap deflected (ΔCL {t_cl[0]:+.4f}, ΔCm {t_cm[0]:+.4f} at the lowest Mach breakpoint)"
    )
    return [a + b for a, b in zip(d_cl, t_cl)], [a + b for a, b in zip(d_cm, t_cm)]
