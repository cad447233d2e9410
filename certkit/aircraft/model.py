"""The aircraft file, as pydantic v2 models. Every quantity is SI after validation.

Positions are in the airplane frame of :mod:`certkit.conventions` (X aft of the nose, Y right,
Z up). Field-level limits (positive areas, taper in (0, 1], fractions in [0, 1]) are declared
here; relations between fields (MLW ≤ MTOW, VD > VC, a CG polygon that does not cross itself …)
are checked in :mod:`certkit.aircraft.consistency` so that all problems are reported together.
"""

from __future__ import annotations

import math
from typing import Annotated, Any, Literal

import numpy as np
from pydantic import AfterValidator, BaseModel, ConfigDict, Field, ValidationInfo, field_validator, model_validator

from certkit.aircraft import derivative_names
from certkit.aircraft.quantities import (
    Acceleration,
    Angle,
    AngularRate,
    ArealDensity,
    Density,
    Force,
    Fraction,
    Gearing,
    Inertia,
    Length,
    Mass,
    MassPerEnergy,
    PositiveArea,
    PositiveForce,
    PositiveLength,
    PositiveMass,
    Pressure,
    SpecificFuelConsumption,
    Speed,
    SpeedOrSchedule,
    SpeedValue,
    Stiffness,
    Temperature,
    Time,
)
from certkit.aircraft.quantities import _converter as _quantity_converter


class _Section(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)


# --- reference -----------------------------------------------------------------------------


class Point(_Section):
    """A point in the airplane frame (X aft of the nose, Y right, Z up)."""

    x: Length
    y: Length = 0.0
    z: Length = 0.0


class Reference(_Section):
    """Reference values for coefficients: area S, span b, mean aerodynamic chord c̄, moment point."""

    area: PositiveArea
    span: PositiveLength
    mean_chord: PositiveLength
    moment_point: Point


# --- geometry ------------------------------------------------------------------------------


class Limits(_Section):
    """Deflection limits (rad): ``min`` ≤ δ ≤ ``max`` in the sign convention of the surface."""

    min: Angle
    max: Angle

    @model_validator(mode="after")
    def _ordered(self):
        if self.max <= self.min:
            raise ValueError(f"max ({self.max:.4f} rad) must be greater than min ({self.min:.4f} rad)")
        return self


class _Span(_Section):
    """A spanwise extent on a lifting surface, as fractions of the semispan (or of the fin height), outboard end
    beyond the inboard one."""

    span_start: Fraction
    span_end: Fraction

    @model_validator(mode="after")
    def _outboard(self):
        if self.span_end <= self.span_start:
            raise ValueError(f"span_end ({self.span_end}) must be outboard of span_start ({self.span_start})")
        return self


class ControlSegment(_Span):
    """A further span of trailing-edge surface moving with a control, ``gain`` × its deflection (the same sign
    convention): e.g. an inboard flaperon driven by the roll command with the outboard aileron."""

    name: str = Field(min_length=1, description="what the segment is, e.g. 'flaperon'")
    chord_ratio: Annotated[float, Field(gt=0.0, lt=1.0)]
    gain: Annotated[float, Field(gt=0.0, le=2.0)] = 1.0
    source: str | None = None


class ControlSurface(_Span):
    """A trailing-edge control surface on a lifting surface.

    Span fractions are of the semispan (or of the fin height); ``travel`` is the mechanical
    deflection range to the control-system stops (what the loads manoeuvres of §§25.331(c), 25.349 and
    25.351 deflect to, unless a §25.397 pilot-force limit comes first), ``design_limits`` the tighter
    range the design allows itself (the limit trims and controllability margins are checked against).
    Signs: :mod:`certkit.conventions`.
    """

    chord_ratio: Annotated[float, Field(gt=0.0, lt=1.0)]
    travel: Limits
    design_limits: Limits | None = None
    #: further spans moving with this control (each ``gain`` × its deflection); travel and limits are this
    #: control's, the command's
    segments: list[ControlSegment] = Field(default_factory=list)

    @model_validator(mode="after")
    def _consistent(self):
        spans = sorted(
            [("the control", self.span_start, self.span_end)]
            + [(f"segment {s.name!r}", s.span_start, s.span_end) for s in self.segments],
            key=lambda r: r[1],
        )
        for (a, _, a_end), (b, b_start, _) in zip(spans, spans[1:]):
            if b_start <= a_end:
                raise ValueError(
                    f"{b} (from {b_start}) overlaps or abuts {a} (to {a_end}): segments of one control need a gap"
                )
        d, t = self.design_limits, self.travel
        if d is not None and (d.min < t.min - 1e-12 or d.max > t.max + 1e-12):
            deg = 180.0 / math.pi
            raise ValueError(
                f"design_limits ({d.min * deg:.1f}° to {d.max * deg:.1f}°) must lie within the travel to the "
                f"control-system stops ({t.min * deg:.1f}° to {t.max * deg:.1f}°): a stop inside a design limit"
            )
        return self


class HighLiftDevice(_Span):
    """A flap or slat: spanwise extent (fractions of the semispan), chord ratio and type."""

    chord_ratio: Annotated[float, Field(gt=0.0, lt=0.6)]
    type: Literal["plain", "split", "slotted", "double_slotted", "fowler", "slat", "krueger"] = "slotted"


class MovableStabilizer(_Section):
    """A trimmable (movable) horizontal stabiliser: the whole tail's incidence is the long-term pitch trim and the
    elevator is left for manoeuvring. Angles are the stabiliser incidence to the body x axis, positive
    leading edge up (airplane nose-down trim), as ``horizontal_tail.incidence``, which is the datum the
    aerodynamic model is built at. Every steady trim solves for the stabiliser with the elevator at
    ``elevator_trim``; where the stabiliser reaches its limit, the elevator carries the rest."""

    travel: Limits = Field(description="incidence range to the structural stops (min: nose-up trim, leading edge down)")
    design_limits: Limits | None = Field(
        None, description="range the trim system allows (the trims are solved within it); the travel when omitted"
    )
    design_limits_by_configuration: dict[str, Limits] = Field(
        default_factory=dict,
        description="trim range of a configuration (a name under configurations) where it differs "
        "from design_limits, e.g. a nose-down limit that widens with the flaps extended; "
        "configurations not named use design_limits",
    )
    rate: Annotated[AngularRate, Field(gt=0)] | None = Field(
        None, description="trim rate of the stabiliser ('0.5 deg/s'), for out-of-trim cases"
    )
    elevator_trim: Angle = Field(0.0, description="elevator deflection at which the airplane is trimmed (default 0)")
    source: str = Field("", description="where the travel and rate come from")

    @model_validator(mode="after")
    def _consistent(self):
        d, t = self.design_limits, self.travel
        if d is not None and (d.min < t.min - 1e-12 or d.max > t.max + 1e-12):
            raise ValueError("design_limits must lie within the travel to the structural stops")
        return self

    def trim_limits(self, configuration: str | None = None, design: bool = True) -> tuple[Limits, str]:
        """The incidence range the trims of ``configuration`` are solved within, and the field it comes from: that
        configuration's entry of ``design_limits_by_configuration``, else ``design_limits``, else the ``travel``
        (``design`` False: the travel, one range for every configuration)."""
        if design and configuration in self.design_limits_by_configuration:
            return self.design_limits_by_configuration[configuration], f"design_limits_by_configuration.{configuration}"
        if design and self.design_limits is not None:
            return self.design_limits, "design_limits"
        return self.travel, "travel"


class LiftingSurface(_Section):
    """A trapezoidal lifting surface (one pair of panels, or the fin on the plane of symmetry)."""

    area: PositiveArea
    aspect_ratio: Annotated[float, Field(gt=0.0, description="b²/S (for a fin: height²/S)")]
    taper: Annotated[
        float,
        Field(
            ge=0.02,
            le=1.0,
            description="tip chord / root chord (from 0.02: a pointed tip is outside the trapezoidal-panel model)",
        ),
    ]
    sweep_quarter_chord: Annotated[Angle, Field(gt=-1.2, lt=1.2)]
    dihedral: Annotated[Angle, Field(gt=-0.8, lt=0.8)] = 0.0
    thickness_ratio: Annotated[float, Field(gt=0.0, lt=0.4)] = 0.12
    root_leading_edge: Point
    incidence: Angle = 0.0
    tip_twist: Angle = Field(0.0, description="tip incidence relative to root (negative: washout)")
    airfoil: str = Field("NACA 0012", description="NACA 4-digit designation or an airfoil coordinate file")
    controls: dict[str, ControlSurface] = Field(default_factory=dict)
    flaps: HighLiftDevice | None = None
    slats: HighLiftDevice | None = None
    stabilizer: MovableStabilizer | None = Field(
        None,
        description="horizontal tail only: the whole tail's incidence "
        "moves to trim (travel, rate, elevator trim setting)",
    )


class Fuselage(_Section):
    length: PositiveLength
    width: PositiveLength
    height: PositiveLength
    upsweep: (
        Annotated[
            Angle,
            Field(
                ge=0.0,
                le=0.5,
                description=(
                    "upsweep of the aft fuselage's centre line, rad ('6 deg'): its drag by Raymer eq. 12.36 "
                    "(none: no upsweep drag)"
                ),
            ),
        ]
        | None
    ) = None


class Nacelle(_Section):
    length: PositiveLength
    diameter: PositiveLength


class LandingGear(_Section):
    """Gear contact points (static, gear extended), for the ground model."""

    main: Point
    nose: Point
    tail_strike_attitude: Annotated[Angle, Field(gt=0.0, lt=math.radians(30.0))] | None = Field(
        None,
        description="pitch attitude at which the aft fuselage touches the runway with the main gear on it "
        "(struts extended, e.g. the manufacturer's flight crew training manual); the simulated "
        "takeoff rotation stays below it while the gear carries load",
    )


class Geometry(_Section):
    wing: LiftingSurface
    horizontal_tail: LiftingSurface
    vertical_tail: LiftingSurface
    fuselage: Fuselage
    nacelle: Nacelle | None = None
    landing_gear: LandingGear | None = None


# --- mass ----------------------------------------------------------------------------------


class InertiaTensor(_Section):
    """Moments and products of inertia (kg m²) at the CG of the item, in the axes ``axes`` names.

    ``body`` (default): certkit's body axes (x forward along the fuselage reference line, z down). ``stability``:
    the stability axes of the flight condition (x along the relative wind in the plane of symmetry), whose x axis
    lies ``axes_angle`` above the body x axis (the body's trim angle of attack is −``axes_angle``; 0 when the
    derivatives are written about that condition's stability axes, as in Etkin & Reid's examples). ``principal``:
    the principal axes (no products of inertia), x ``axes_angle`` above the body x axis (nose-up positive).
    The tensor is turned into body axes by a rotation about y (Etkin & Reid eq. 4.8,1 form)."""

    Ixx: Annotated[Inertia, Field(ge=0)]
    Iyy: Annotated[Inertia, Field(ge=0)]
    Izz: Annotated[Inertia, Field(ge=0)]
    Ixz: Inertia = 0.0
    Ixy: Inertia = 0.0
    Iyz: Inertia = 0.0
    axes: Literal["body", "stability", "principal"] = "body"
    axes_angle: Annotated[
        Angle,
        Field(
            ge=-0.8,
            le=0.8,
            description="angle of the declared x axis above the body x axis (rotation about y, nose-up positive)",
        ),
    ] = 0.0

    @model_validator(mode="after")
    def _principal(self):
        if self.axes == "principal" and (self.Ixz or self.Ixy or self.Iyz):
            raise ValueError("principal axes have no products of inertia: give Ixz = Ixy = Iyz = 0 or axes: body")
        return self


class MassComponent(_Section):
    name: str
    mass: PositiveMass
    cg: Point
    inertia: InertiaTensor | None = None
    group: Literal["structure", "propulsion", "systems", "furnishings", "operator", "payload", "fuel", "other"] = (
        "other"
    )
    source: str | None = None


class FuelTank(_Section):
    """A fuel tank: its capacity and centroid; a wing tank (centroid off the plane of symmetry) may also declare the
    spanwise extent of its bay (|y| of the inboard and outboard ends), else the loads model places it from the side
    of body outboard as far as its centroid asks (:mod:`certkit.models.loads.fuel`)."""

    name: str
    capacity: PositiveMass
    cg: Point
    y_inboard: Length | None = Field(None, description="|y| of the tank bay's inboard end (wing tanks)")
    y_outboard: Length | None = Field(None, description="|y| of the tank bay's outboard end (wing tanks)")

    @model_validator(mode="after")
    def _bay(self):
        a, b = self.y_inboard, self.y_outboard
        if a is not None and b is not None and not a < abs(self.cg.y) < b:
            raise ValueError(
                f"the tank's centroid |y| = {abs(self.cg.y):.3f} m must lie between y_inboard "
                f"{a:.3f} m and y_outboard {b:.3f} m"
            )
        return self


class PayloadZone(_Section):
    """A cabin or hold zone: payload is distributed between its fore and aft ends."""

    name: str
    capacity: PositiveMass
    x_start: Length
    x_end: Length


class MassProperties(_Section):
    """Design masses, mass items and inertia. A file used only for ``trim``/``modes`` (a derivative-table airplane)
    needs MTOW (the mass flown unless a command says otherwise) and ``inertia``; the rules that need MLW, MZFW, OEW,
    tanks or zones are not evaluated without them."""

    MTOW: PositiveMass
    MLW: PositiveMass | None = None
    MZFW: PositiveMass | None = None
    OEW: PositiveMass | None = None
    MRW: PositiveMass | None = Field(None, description="maximum ramp (taxi) weight")
    max_fuel: PositiveMass | None = None
    max_payload: PositiveMass | None = None
    passengers: Annotated[int, Field(ge=0, le=10_000, strict=True, description="seats: a whole number")] | None = None
    oew_cg: Point | None = None
    cg: Point | None = Field(
        None,
        description="CG of the whole airplane at MTOW (a file without components, tanks "
        "or zones; default: the CG envelope's reference, else the moment point)",
    )
    inertia: InertiaTensor | None = Field(
        None,
        description="whole-airplane inertia at MTOW (used without components, "
        "or with them when inertia_used is 'declared')",
    )
    inertia_used: Literal["components", "declared"] = Field(
        "components",
        description="with both components and a declared inertia: which one the dynamics uses (the "
        "other is compared with it; a difference beyond inertia_tolerance is a warning)",
    )
    inertia_tolerance: Annotated[float, Field(gt=0.0, lt=1.0)] = Field(
        0.10,
        description="relative difference of a moment of inertia (build-up at MTOW vs declared) beyond which "
        "certkit warns",
    )
    components: list[MassComponent] = Field(default_factory=list)
    fuel_tanks: list[FuelTank] = Field(default_factory=list)
    payload_zones: list[PayloadZone] = Field(default_factory=list)


class EnvelopeVertex(_Section):
    name: str | None = None
    mass: PositiveMass
    x: Length


class CgEnvelope(_Section):
    """The weight–CG envelope: an ordered polygon of (mass, CG station) vertices."""

    vertices: Annotated[list[EnvelopeVertex], Field(min_length=3)]
    reference_x: Length | None = Field(None, description="reference CG station for rules evaluated at one CG")


# --- propulsion ----------------------------------------------------------------------------


class Engine(_Section):
    name: str
    position: Point
    thrust_angle: Angle = 0.0
    toe_angle: Angle = 0.0


class EngineDeck(_Section):
    """Installed thrust (and fuel flow) of one engine on an altitude × Mach × throttle grid.

    ``thrust[i][j][k]`` at ``altitude[i]``, ``mach[j]``, ``throttle[k]`` (0 idle … 1 maximum takeoff).
    A point outside the grid is an error unless ``allow_extrapolation`` is true (then it is stated).
    """

    altitude: Annotated[list[Length], Field(min_length=2)]
    mach: Annotated[list[float], Field(min_length=2)]
    throttle: Annotated[list[Annotated[float, Field(ge=0.0, le=1.0)]], Field(min_length=2)]
    thrust: list[list[list[Force]]]
    fuel_flow: list[list[list[float]]] | None = Field(None, description="kg/s, same layout as thrust")
    allow_extrapolation: bool = False
    source: str | None = None


class Propulsion(_Section):
    engines: Annotated[list[Engine], Field(min_length=1)]
    static_thrust: PositiveForce = Field(description="sea-level static thrust of one engine")
    bypass_ratio: Annotated[float, Field(gt=0)] = 8.0
    deck: EngineDeck | None = None
    failure_decay_time: Annotated[Time, Field(gt=0.0)] | None = Field(
        None,
        description="time constant of the first-order decay of a failed engine's thrust to its windmilling "
        "drag (fuel cut); without it a failed engine windmills at once",
    )
    flat_rating_temperature: Annotated[Temperature, Field(gt=200.0, lt=350.0)] | None = Field(
        None,
        description="ambient temperature up to which takeoff thrust is held at sea level static (the engine "
        "type certificate's 'flat rating ambient temperature', e.g. '30 degC'); above it thrust "
        "lapses with Mattingly's high-bypass law. Needed for off-standard days (takeoff_landing_envelope)",
    )


class TakeoffPilot(_Section):
    """How the pilot flies the directions of a takeoff run after an engine failure (the simulated takeoffs of
    §25.111/§25.113 and the §25.149(e) ground minimum control speed): a reaction time from the failure to the first
    pedal input, then the pedal moved at most at ``rudder_rate`` toward what the heading and centreline ask; and,
    where the procedure allows it (not for VMCG, which is flown with the rudder alone), pedal nose-wheel steering of
    at most ``nose_wheel_steering`` at full pedal. Defaults: 1 s from the failure to the first input (the recognition
    interval the takeoff speeds assume, §25.107(a)(2); AC 25-7D's VMCG guidance asks for the pilot's normal reaction,
    without anticipating the failure), full pedal in about a second (30 deg/s), no nose-wheel steering declared."""

    rudder_reaction_time: Annotated[Time, Field(ge=0.0, le=5.0)] = Field(
        1.0, description="time from the engine failure to the pilot's first rudder-pedal input, s (0 to 5 s)"
    )
    rudder_rate: Annotated[AngularRate, Field(gt=0.0, le=math.radians(200.0))] = Field(
        math.radians(30.0),
        description="largest rate at which the pilot moves the rudder, e.g. '30 deg/s' "
        "(greater than 0, at most 200 deg/s)",
    )
    nose_wheel_steering: Annotated[Angle, Field(ge=0.0, le=math.radians(80.0))] | None = Field(
        None,
        description="nose-wheel angle at full rudder pedal (pedal steering, e.g. '7 deg'), used on the runway "
        "where the procedure allows it; without it the nose wheel stays straight",
    )
    source: str | None = None


# --- aerodynamics: calibration and declared data ------------------------------------------


class DerivativeTable(_Section):
    """Stability and control derivatives of one configuration (wind tunnel, CFD or published data).

    ``form: nondimensional`` (default): per radian, stability axes, AVL rate normalisation, moments about
    ``reference.moment_point``; ``form: dimensional``: SI forces and moments per unit motion variable at the
    ``flight_condition`` (Etkin & Reid's X_u, Z_w, M_q ...). Names: :mod:`certkit.aircraft.derivative_names`
    (listed in ``certkit schema``). Each value is a number or one number per Mach breakpoint; ``mach`` defaults to
    the flight condition's Mach number. Speed derivatives (CL_u, CD_u, Cm_u) and the dimensional form need a single
    Mach (the flight condition's). Control terms are optional (``controls`` defaults to those the terms name);
    without a pitch control, trim holds the pitching moment at zero by the angle of attack alone (and says when it
    cannot). Declared tables replace the vortex lattice.
    """

    form: Literal["nondimensional", "dimensional"] = "nondimensional"
    mach: Annotated[list[Annotated[float, Field(ge=0.0, lt=1.0)]], Field(min_length=1)] | None = Field(
        None, description="Mach breakpoints (default: the flight condition's Mach number)"
    )
    derivatives: dict[str, float | list[float]] = Field(
        description="derivative name → value (or one value per Mach breakpoint):\n"
        + derivative_names.schema_description(),
        json_schema_extra={
            "properties": derivative_names.schema_properties(),
            "patternProperties": {
                r"^(CL|CD|CY|Cl|Cm|Cn|X|Y|Z|L|M|N)_[A-Za-z][A-Za-z0-9_]*$": {
                    "description": "control derivative <prefix>_<control>, per rad"
                }
            },
        },
    )
    controls: list[str] | None = Field(
        None,
        description="control surfaces the control terms (Cm_elevator …) refer "
        "to (default: those of elevator, aileron, rudder, stabilizer, "
        "spoiler, flap, slat the terms name)",
    )
    source: Annotated[str, Field(min_length=3)]

    @property
    def control_names(self) -> list[str]:
        if self.controls is not None:
            return list(self.controls)
        found: list[str] = []
        for name in self.derivatives:
            term = derivative_names.control_term(name, self.form)
            if term and term[1] not in found and term[1] in derivative_names.USUAL_CONTROLS:
                found.append(term[1])
        return found


class LatticeResolution(_Section):
    """Vortex-lattice panels per surface (chordwise × spanwise per half)."""

    chordwise: Annotated[int, Field(ge=1, le=40)] = 8
    spanwise: Annotated[int, Field(ge=2, le=120)] = 20


class Aerodynamics(_Section):
    derivative_tables: dict[str, DerivativeTable] = Field(
        default_factory=dict, description="configuration name → declared derivatives (replace the lattice)"
    )
    overrides: dict[str, dict[str, float]] = Field(
        default_factory=dict, description="configuration name → coefficient name → value (e.g. a measured CD0)"
    )
    overrides_source: str | None = None
    lattice: LatticeResolution = Field(default_factory=LatticeResolution)


# --- configurations, speeds, envelope, criteria --------------------------------------------


class FlightCondition(_Section):
    """The flight condition of published data: where dimensional and speed derivatives were taken, and the default
    condition of ``certkit trim`` and ``certkit modes``. Altitude (ISA) or density; a speed with its kind
    ('235.9 m/s TAS', '250 kn EAS') or a Mach number; the gravitational acceleration the source used."""

    altitude: Length | None = Field(None, description="pressure altitude (ISA); or give density")
    density: Annotated[Density, Field(gt=0.0)] | None = Field(
        None, description="air density; the ISA altitude with this density is flown"
    )
    speed: Speed | None = Field(None, description="airspeed with its kind; or give mach")
    mach: Annotated[float, Field(gt=0.0, lt=1.0)] | None = None
    gravity: Annotated[Acceleration, Field(gt=9.7, lt=9.9)] = Field(
        9.80665, description="gravitational acceleration of the equations of motion (standard 9.80665 m/s²)"
    )
    source: str | None = None

    @model_validator(mode="after")
    def _one_of_each(self):
        problems = []
        if (self.altitude is None) == (self.density is None):
            problems.append("give either altitude or density (one of the two)")
        if (self.speed is None) == (self.mach is None):
            problems.append("give either speed (with its kind) or mach (one of the two)")
        if problems:
            raise ValueError("; ".join(problems))
        return self


class StallWarning(_Section):
    """Where stall warning begins in a configuration (§25.207(c)-(d)): the 1-g lift coefficient at its onset, or the
    warning speed VSW as a ratio to VSR. One of the two, with its source."""

    CL: Annotated[float, Field(gt=0.0, lt=5.0)] | None = Field(
        None, description="trimmed 1-g lift coefficient at which stall warning begins"
    )
    speed_ratio: Annotated[float, Field(gt=1.0, lt=2.0)] | None = Field(
        None, description="VSW/VSR, the stall-warning speed over the reference stall speed (CAS)"
    )
    source: str | None = None

    @model_validator(mode="after")
    def _one(self):
        if (self.CL is None) == (self.speed_ratio is None):
            raise ValueError(
                "declare exactly one of CL (lift coefficient at the warning onset) and speed_ratio (VSW/VSR)"
            )
        return self


class TailFlapIncrement(_Section):
    """The horizontal tail's share of a configuration's flap increments: its lift and pitching-moment change from the
    change of downwash at the tail with the flaps down (tail-on minus tail-off increment, e.g. from wind-tunnel runs
    with and without the tail), on the reference area and chord, moment about the moment point."""

    delta_CL: Annotated[float, Field(gt=-1.0, lt=1.0)] = Field(description="tail lift change, usually negative")
    delta_Cm: Annotated[float, Field(gt=-2.0, lt=2.0)] = Field(
        description="tail pitching-moment change, usually nose-up"
    )
    source: str = Field(description="where the increments come from")


class LiftLimitByMach(_Section):
    """The maximum lift coefficient (trimmed, 1 g) against Mach number: the stall lines of the manoeuvring envelope
    and the airplane model's stall at each Mach number (linear between the entries, held beyond them)."""

    mach: list[Annotated[float, Field(ge=0.0, lt=1.0)]] = Field(min_length=2)
    CLmax: list[Annotated[float, Field(gt=0.0, lt=5.0)]] = Field(min_length=2)
    source: str = Field(min_length=1)

    @model_validator(mode="after")
    def _table(self):
        if len(self.mach) != len(self.CLmax):
            raise ValueError(f"{len(self.mach)} Mach numbers but {len(self.CLmax)} CLmax values: one per Mach number")
        if any(b <= a for a, b in zip(self.mach, self.mach[1:])):
            raise ValueError(f"mach {self.mach} must increase strictly")
        return self

    def at(self, mach: Any) -> Any:
        """CLmax at ``mach`` (scalar or array), linear between the entries and held beyond them."""
        return np.interp(mach, self.mach, self.CLmax)


class Configuration(_Section):
    flap: Annotated[
        Angle, Field(ge=0.0, le=math.radians(70.0), description="flap deflection, 0 (retracted) to 70 deg")
    ] = 0.0
    slat: Annotated[
        Angle, Field(ge=0.0, le=math.radians(70.0), description="slat deflection, 0 (retracted) to 70 deg")
    ] = 0.0
    gear: Literal["up", "down"] = "up"
    CLmax: Annotated[float, Field(gt=0.0, lt=5.0)] | None = Field(
        None, description="trimmed 1-g maximum lift coefficient"
    )
    CLmax_by_mach: LiftLimitByMach | None = Field(
        None,
        description="CLmax against Mach number (its value at the lowest Mach, at most 0.3, within 2 % of CLmax, "
        "the low-speed value of the stall speeds); without it CLmax holds at every Mach number",
    )
    CLmin: Annotated[float, Field(lt=0.0, gt=-5.0)] | None = Field(None, description="negative stall lift coefficient")
    delta_CL0: float = Field(0.0, description="tail-off (wing-body) lift increment of the high-lift devices")
    delta_CD0: Annotated[float, Field(ge=0.0, lt=0.3)] = Field(
        0.0,
        description="zero-lift drag increment of the high-lift devices and gear, 0 to 0.3 (landing flaps with the "
        "gear down are about 0.07-0.10: Roskam, Airplane Design Part I, Table 3.6)",
    )
    delta_Cm0: float = Field(0.0, description="tail-off (wing-body) pitching-moment increment of the high-lift devices")
    tail_flap_increment: TailFlapIncrement | None = Field(
        None,
        description="the horizontal tail's share of the flap increments (change of downwash at the tail); "
        "without it the vortex lattice estimates it for a file with geometry",
    )
    stall_warning: StallWarning | None = Field(
        None, description="stall-warning onset (§25.207); without it the rules use the latest warning §25.207(c) allows"
    )
    source: str | None = None

    @model_validator(mode="after")
    def _lift_limit_table_meets_clmax(self):
        t = self.CLmax_by_mach
        if t is None:
            return self
        if self.CLmax is None:
            raise ValueError("CLmax_by_mach needs CLmax (the low-speed value the table starts from)")
        if t.mach[0] > 0.3 or abs(t.CLmax[0] - self.CLmax) > 0.02 * self.CLmax:
            raise ValueError(
                f"CLmax_by_mach starts at M {t.mach[0]:g} with {t.CLmax[0]:g}: it must start at a low Mach number "
                f"(at most 0.3) within 2 % of CLmax ({self.CLmax:g}), the value of the stall speeds"
            )
        return self

    def clmax_at(self, mach: Any) -> Any:
        """CLmax at ``mach`` (scalar or array): the table's where one is declared, else CLmax; None without CLmax."""
        if self.CLmax is None:
            return None
        if self.CLmax_by_mach is None:
            return np.full(np.shape(mach), self.CLmax) if np.ndim(mach) else self.CLmax
        return self.CLmax_by_mach.at(mach)

    @model_validator(mode="after")
    def _warning_below_stall(self):
        w = self.stall_warning
        if w is not None and w.CL is not None and self.CLmax is not None and w.CL >= self.CLmax:
            raise ValueError(
                f"stall_warning.CL ({w.CL:g}) must be below CLmax ({self.CLmax:g}): warning begins before the stall"
            )
        return self


class Speeds(_Section):
    """Declared speeds. Per-configuration speeds map a configuration name to a speed."""

    VSR: dict[str, Speed] = Field(default_factory=dict, description="reference stall speed per configuration")
    V1: Speed | None = None
    VR: Speed | None = None
    V2: Speed | None = None
    VMC: Speed | None = Field(None, description="minimum control speed in the air (VMCA)")
    VMCG: Speed | None = None
    VMU: Speed | None = None
    VLOF: Speed | None = None
    VREF: Speed | None = None
    VFTO: Speed | None = None
    VA: SpeedOrSchedule | None = Field(
        None, description="design manoeuvring speed: one speed, or a schedule with altitude (kind, altitude, speed)"
    )
    VB: SpeedOrSchedule | None = Field(
        None, description="design speed for maximum gust intensity: one speed, or a schedule with altitude"
    )
    VC: Speed | None = None
    MC: Annotated[float, Field(gt=0.0, lt=3.0)] | None = None
    VD: Speed | None = None
    MD: Annotated[float, Field(gt=0.0, lt=3.0)] | None = None
    VMO: Speed | None = None
    MMO: Annotated[float, Field(gt=0.0, lt=3.0)] | None = None
    VFC: Speed | None = Field(
        None,
        description="maximum speed for stability characteristics (§25.253(b)); without it "
        "the stability rules use the least §25.253(b) allows, midway between VMO and VD",
    )
    MFC: Annotated[float, Field(gt=0.0, lt=3.0)] | None = Field(None, description="Mach counterpart of VFC")
    VFE: dict[str, Speed] = Field(default_factory=dict, description="flap-extended speed per configuration")
    VLE: Speed | None = None
    VLO: Speed | None = None


class LoadFactors(_Section):
    positive: Annotated[float, Field(gt=0.0)]
    negative: Annotated[float, Field(le=0.0)] = -1.0
    flaps_extended: Annotated[float, Field(gt=0.0)] | None = None


class Envelope(_Section):
    ceiling: PositiveLength = Field(description="maximum operating altitude")
    min_altitude: Length = 0.0
    limit_load_factors: LoadFactors | None = Field(None, description="declared design limit load factors")
    altitude_points: Annotated[int, Field(ge=2, le=50)] = 5


class WatLimit(_Section):
    """One point of the flight manual's weight–altitude–temperature limits (§25.1533(a)(1)/(2)): the maximum takeoff
    and/or landing weight the applicant declares at an airport pressure altitude and ambient temperature."""

    pressure_altitude: Length = Field(description="airport pressure altitude")
    temperature: Annotated[Temperature, Field(gt=180.0, lt=360.0)] = Field(description="ambient temperature")
    takeoff_weight: PositiveMass | None = Field(
        None, description="maximum takeoff weight there (§25.121(a)–(c) are checked at the lower of it and MTOW)"
    )
    landing_weight: PositiveMass | None = Field(
        None, description="maximum landing weight there (§25.121(d) is checked at the lower of it and MLW)"
    )
    source: str | None = None


class TakeoffLandingEnvelope(_Section):
    """Airport pressure altitudes and ambient temperatures the airplane is certificated to take off and land in (the
    flight manual's takeoff and landing envelope); §25.121 is evaluated over it (weight–altitude–temperature)."""

    pressure_altitude_min: Annotated[Length, Field(ge=-610.0)] = Field(
        description="lowest airport pressure altitude (at least -2000 ft)"
    )
    pressure_altitude_max: Annotated[Length, Field(le=6000.0)] = Field(description="highest airport pressure altitude")
    temperature_min: Annotated[Temperature, Field(gt=180.0)] = Field(description="coldest ambient temperature")
    temperature_max: Annotated[Temperature, Field(lt=360.0)] = Field(description="hottest ambient temperature")
    isa_deviation_max: Annotated[Temperature, Field(gt=0.0, le=60.0)] | None = Field(
        None,
        description="hot limit as a deviation from ISA (K, e.g. '40 delta_degC'); the hot limit at an altitude "
        "is the lower of this line and temperature_max",
    )
    altitude_points: Annotated[int, Field(ge=2, le=10)] = Field(
        3, description="pressure altitudes evaluated, evenly from the lowest to the highest (sea level added)"
    )
    wat_limits: list[WatLimit] = Field(
        default_factory=list,
        description=("declared flight-manual WAT limit weights; §25.121 is also checked at each point at that weight"),
    )
    source: str | None = None


class Performance(_Section):
    """Declared (flight-test or handbook) performance figures the rules match their simulations to."""

    takeoff_field_length: PositiveLength | None = Field(
        None,
        description="takeoff field length at MTOW, sea level, standard day (§25.113(a): the greater of the "
        "one-engine-inoperative distance to 35 ft and 1.15 × the all-engines distance to 35 ft); "
        "§25.113 checks the simulated takeoff distance against it",
    )
    source: str | None = None


class TsfcCalibration(_Section):
    """A cruise thrust-specific fuel consumption of the installed engine at one flight condition: the engine model's
    fuel flow is scaled so that it gives this value there (its variation with Mach and altitude is kept)."""

    value: Annotated[SpecificFuelConsumption, Field(gt=0.0, description="TSFC, e.g. '0.526 lb/lbf/h'")]
    mach: Annotated[float, Field(gt=0.0, lt=1.0)]
    altitude: Length
    source: Annotated[str, Field(min_length=3)]


class EngineAllowance(_Section):
    """A ground or terminal-area phase flown as a time at a fixed throttle (0 idle … 1 maximum) at the given Mach
    number, sea level, standard day: its fuel is the engine model's fuel flow times the time."""

    time: Annotated[Time, Field(ge=0.0)]
    throttle: Fraction
    mach: Annotated[float, Field(ge=0.0, lt=1.0)] = 0.0


class ReservePolicy(_Section):
    """Reserve fuel carried beyond the trip: contingency (a fraction of trip fuel), the flight to an alternate
    (climb, cruise at ``alternate_altitude`` at the climb-schedule speed, descent) and a final reserve held at
    ``hold_altitude`` at the minimum-drag speed for ``hold_time``."""

    contingency_fraction: Annotated[float, Field(ge=0.0, lt=0.5)]
    alternate_distance: Annotated[Length, Field(ge=0.0)]
    alternate_altitude: PositiveLength
    hold_time: Annotated[Time, Field(ge=0.0)]
    hold_altitude: Annotated[Length, Field(ge=0.0)]
    source: Annotated[str, Field(min_length=3)]


class DragCondition(_Section):
    """The design cruise condition at which the trimmed cruise drag coefficient is reported (at the cruise Mach)."""

    altitude: Length
    mass: PositiveMass | None = Field(None, description="none: the mid-cruise mass of the design-range mission")


class Mission(_Section):
    """The mission the design is flown on (:mod:`certkit.models.performance.mission`): a climb on a CAS/Mach
    schedule, a step cruise at ``cruise_mach`` from the level that maximises specific air range at the top of
    climb (levels ``initial_altitude`` + k ``altitude_step`` up to ``max_altitude``), a descent at idle on the
    same schedule, allowances for taxi, takeoff and approach, reserves by ``reserves``."""

    cruise_mach: Annotated[float, Field(gt=0.0, lt=1.0)]
    initial_altitude: PositiveLength = Field(description="lowest cruise level considered")
    altitude_step: PositiveLength = Field(description="step between cruise levels (step climbs)")
    max_altitude: PositiveLength | None = Field(None, description="highest cruise level (none: envelope.ceiling)")
    climb_speed: Speed = Field(description="climb and descent CAS above speed_limit_altitude, up to the cruise Mach")
    low_altitude_speed: Speed = Field(description="climb and descent speed below speed_limit_altitude")
    speed_limit_altitude: Annotated[Length, Field(ge=0.0)]
    climb_throttle: Fraction = Field(
        1.0, description="maximum-climb rating as a fraction of the engine model's maximum"
    )
    residual_climb_rate: Annotated[
        SpeedValue,
        Field(ge=0.0, description="rate of climb that a cruise level must still allow at maximum-climb thrust"),
    ]
    buffet_onset_CL: Annotated[
        float,
        Field(
            gt=0.0,
            lt=2.0,
            description="1-g initial-buffet lift coefficient at the cruise Mach (trimmed, reference area)",
        ),
    ]
    buffet_load_factor: Annotated[float, Field(ge=1.0, le=2.0)] = 1.3
    design_payload: PositiveMass
    cruise_cg: Length | None = Field(None, description="CG station of the mission's trims (none: the reference CG)")
    taxi_out: EngineAllowance
    takeoff: EngineAllowance
    approach: EngineAllowance
    taxi_in: EngineAllowance
    reserves: ReservePolicy
    tsfc: TsfcCalibration | None = Field(None, description="cruise TSFC the engine model is calibrated to")
    nominal_distance: PositiveLength = Field(description="still-air distance of the block-fuel mission")
    range_requirement: PositiveLength = Field(description="design range the design must reach (constraint)")
    drag_condition: DragCondition
    source: str | None = None


class RangeTarget(_Section):
    """A published or required range the performance calibration reproduces: ``range`` with ``payload`` from MTOW
    with the mission's reserves (the design-range mission of :mod:`certkit.models.performance.mission`)."""

    range: PositiveLength
    payload: PositiveMass | None = Field(None, description="none: mission.design_payload")
    tolerance: Annotated[float, Field(gt=0.0, lt=0.2, description="relative tolerance the calibration is tested to")]
    source: Annotated[str, Field(min_length=3)]


class PerformanceCalibration(_Section):
    """Declared factors that close the gap between the drag and engine models and the airplane's published
    performance (FLOPS's drag and fuel-flow factors): fixed for every design of a study, shown in the report.
    ``certkit calibrate`` solves ``drag_factor`` for ``target`` with ``fuel_flow_factor`` as declared."""

    drag_factor: Annotated[
        float,
        Field(
            ge=0.7,
            le=1.5,
            description=(
                "multiplies the zero-lift drag of the build-up (parasite and wave drag, CD0) of every configuration; "
                "the "
                "induced drag, declared configuration increments and derivative tables are not scaled"
            ),
        ),
    ] = 1.0
    fuel_flow_factor: Annotated[
        float,
        Field(
            ge=0.8,
            le=1.3,
            description=("multiplies the engine model's TSFC: installation losses (customer bleed, power off-take)"),
        ),
    ] = 1.0
    fuel_flow_source: Annotated[str, Field(min_length=3)] | None = None
    target: RangeTarget | None = None
    source: Annotated[str, Field(min_length=3)]


class CriterionOverride(_Section):
    """Override of a rule's numeric criteria; the justification is printed in the report."""

    justification: Annotated[str, Field(min_length=10)]
    values: dict[str, float | str | bool]


# --- structure -----------------------------------------------------------------------------

StructuralQuantity = Literal["shear", "bending", "torsion"]
_QUANTITY_DIMENSION = {"shear": "force", "bending": "moment", "torsion": "moment"}


class SenseAllowable(_Section):
    """Allowable load magnitudes that differ with the sense of the load: ``negative`` (download on the
    wing or tailplane, leftward on the fin, tip-down bending, nose-down torsion) and ``positive``
    (upward / rightward, tip-up bending, nose-up torsion). N for shear, N·m for bending and torsion."""

    negative: Annotated[float, Field(gt=0)]
    positive: Annotated[float, Field(gt=0)]


class StructuralCapability(_Section):
    """What the structure of one surface carries at one station for one load quantity (§25.305).

    ``station``: ``root`` (the surface's root on the plane of symmetry, the fin's root at the fuselage
    axis), ``side_of_body`` (wing and horizontal tail, at half the fuselage width) or a fraction 0–1 of
    the semispan (fin height) measured in the plane of the surface. ``limit`` is the allowable limit
    load (no detrimental permanent deformation), ``ultimate`` the allowable ultimate load (no
    failure): each a magnitude valid in both senses or ``{negative, positive}``. Shear in force units
    (``"1200 kN"``, ``"270000 lbf"``), bending and torsion in moment units (``"9.5 MN*m"``,
    ``"7.0e6 lbf*ft"``); SI after validation. Signs follow :mod:`certkit.models.loads.model`."""

    station: Literal["root", "side_of_body"] | Fraction
    quantity: StructuralQuantity
    limit: Annotated[float, Field(gt=0)] | SenseAllowable
    ultimate: Annotated[float, Field(gt=0)] | SenseAllowable
    source: Annotated[str, Field(min_length=3, description="where the allowables come from (stress report, test)")]

    @field_validator("limit", "ultimate", mode="before")
    @classmethod
    def _units(cls, value: object, info: ValidationInfo) -> object:
        quantity = info.data.get("quantity")
        if quantity not in _QUANTITY_DIMENSION:
            return value  # the quantity's own error is reported
        convert = _quantity_converter(_QUANTITY_DIMENSION[quantity])
        if isinstance(value, dict):
            return {k: convert(v) if k in ("negative", "positive") else v for k, v in value.items()}
        return convert(value)


class FuselageCapability(StructuralCapability):
    """What the fuselage carries at the horizontal tail's attachment: the torsion about the X axis an unsymmetrical
    tail loading puts into it (§25.427(b)); positive as the full side's air load up on the right half."""

    station: Literal["tail"]
    quantity: Literal["torsion"]


class Structure(_Section):
    """Declared structural capabilities per lifting surface, and of the fuselage at the tail (the loads rules compare
    their limit loads and 1.5 × limit loads with them, §25.303/§25.305)."""

    wing: list[StructuralCapability] = Field(default_factory=list)
    horizontal_tail: list[StructuralCapability] = Field(default_factory=list)
    vertical_tail: list[StructuralCapability] = Field(default_factory=list)
    fuselage: list[FuselageCapability] = Field(default_factory=list)


# --- control forces ----------------------------------------------------------------------


class HingeMoment(_Section):
    """Hinge-moment derivatives of a control surface, per radian: C_h = Ch_0 + Ch_alpha α_s + Ch_delta δ, with
    α_s the local angle of attack of the surface it is hinged to (tailplane, fin or wing) and δ its deflection,
    the hinge moment H = C_h q_s S c positive in the sense of positive δ (:mod:`certkit.conventions`)."""

    Ch_0: float = 0.0
    Ch_alpha: float
    Ch_delta: Annotated[
        float,
        Field(
            lt=0.0,
            description="restoring (negative): a surface with Ch_delta ≥ 0 is "
            "overbalanced and cannot be flown reversible",
        ),
    ]


#: fields that only one type of control-force model takes
_TYPE_FIELDS = {
    "reversible": ("hinge_moment", "chord", "area", "span", "downwash_gradient"),
    "artificial_feel": ("gradient", "q_feel_reference"),
}


class ControlFeel(_Section):
    """The force model of one cockpit control (:mod:`certkit.models.control_force`), of one of two types.

    ``type: reversible`` — an aerodynamically reversible (or boosted) control: the pilot holds
    ``hinge_moment_fraction`` of the surface's hinge moment through the gearing, F = −G f η q S c C_h. Needs
    ``hinge_moment``, ``chord`` (mean chord aft of the hinge line) and ``area`` (area aft of the hinge line) or
    ``span`` (area = span × chord); for the elevator both halves as one surface, for the aileron one side.

    ``type: artificial_feel`` — a fully powered control with a feel unit: F = ``preload`` + ``gradient`` ×
    displacement from the feel neutral (the trim), the gradient scaled by q / ``q_feel_reference`` when given.

    Both: the linkage is a linear ``gearing`` (surface angle per length of column or pedal travel,
    ``"0.9 deg/in"``) or, for a wheel, ``wheel_gearing`` (surface rad per wheel rad) with ``wheel_diameter``
    (the force is then at the rim); ``friction`` is the control's friction force (§25.173(b) free return).
    """

    type: Literal["reversible", "artificial_feel"]
    gearing: Annotated[Gearing, Field(gt=0.0)] | None = None
    wheel_gearing: Annotated[float, Field(gt=0.0)] | None = None
    wheel_diameter: PositiveLength | None = None
    friction: Annotated[Force, Field(ge=0.0)] | None = Field(
        None, description="friction force at the cockpit control, for the free return of §25.173(b)"
    )
    # reversible
    hinge_moment: HingeMoment | None = None
    chord: PositiveLength | None = None
    area: PositiveArea | None = None
    span: PositiveLength | None = None
    hinge_moment_fraction: Annotated[
        float,
        Field(
            gt=0.0,
            le=1.0,
            description="share of the hinge moment the pilot carries: 1 unboosted, 1/(1+B) with a boost ratio B",
        ),
    ] = 1.0
    dynamic_pressure_ratio: Annotated[
        float, Field(gt=0.0, le=1.2, description="η = q at the surface / free-stream q")
    ] = 1.0
    downwash_gradient: Annotated[float, Field(ge=0.0, lt=1.0)] | None = Field(
        None,
        description="dε/dα at the tailplane (elevator) or dσ/dβ at the fin (rudder); default: elevator "
        "2 a_w/(π A) from the wing, rudder 0",
    )
    downwash_at_zero_alpha: Angle = Field(0.0, description="ε at zero body angle of attack (elevator only)")
    # artificial feel
    preload: Annotated[Force, Field(ge=0.0)] = Field(0.0, description="breakout force")
    gradient: Annotated[Stiffness, Field(gt=0.0)] | None = Field(
        None, description="force per cockpit travel ('20 lbf/in')"
    )
    q_feel_reference: Annotated[Pressure, Field(gt=0.0)] | None = Field(
        None, description="dynamic pressure at which the gradient is as declared (q-feel); none: constant gradient"
    )
    source: str | None = None

    @model_validator(mode="after")
    def _complete(self):
        problems = []
        wheel = self.wheel_gearing is not None or self.wheel_diameter is not None
        if self.gearing is not None and wheel:
            problems.append("give either gearing (column or pedals) or wheel_gearing with wheel_diameter, not both")
        elif self.gearing is None and not (self.wheel_gearing is not None and self.wheel_diameter is not None):
            problems.append(
                "needs gearing (surface angle per cockpit travel, e.g. '0.9 deg/in') or wheel_gearing "
                "with wheel_diameter"
            )
        other = "artificial_feel" if self.type == "reversible" else "reversible"
        stray = [f for f in _TYPE_FIELDS[other] if getattr(self, f) is not None]
        if stray:
            problems.append(
                f"{', '.join(stray)} belong{'s' if len(stray) == 1 else ''} to type {other}, not {self.type}"
            )
        if self.type == "reversible":
            missing = [f for f in ("hinge_moment", "chord") if getattr(self, f) is None]
            if missing:
                problems.append(f"type reversible needs {' and '.join(missing)}")
            if (self.area is None) == (self.span is None):
                problems.append(
                    "type reversible needs the surface's area aft of the hinge line or its span (one of the two)"
                )
        elif self.gradient is None:
            problems.append("type artificial_feel needs gradient (force per cockpit travel, e.g. '20 lbf/in')")
        if problems:
            raise ValueError("; ".join(problems))
        return self

    @property
    def surface_area(self) -> float:
        return self.area if self.area is not None else self.span * self.chord


class ControlForces(_Section):
    """Cockpit control-force models per primary control (:mod:`certkit.models.control_force`)."""

    elevator: ControlFeel | None = None
    aileron: ControlFeel | None = None
    rudder: ControlFeel | None = None
    source: str | None = None


# --- structural sizing (design loop) ----------------------------------------------------


class LaminateAllowables(_Section):
    """Material of a sized box: a laminate linear to failure, allowable stress = modulus × design ultimate strain
    (:class:`certkit.models.structure.box.BoxMaterial`)."""

    density: Annotated[Density, Field(gt=0, description="kg/m³ of the laminate ('1580 kg/m^3')")]
    cover_modulus: Annotated[Pressure, Field(gt=0, description="E_x of the cover laminate (skin + stringers)")]
    cover_shear_modulus: Annotated[Pressure, Field(gt=0, description="G_xy of the cover laminate")]
    web_shear_modulus: Annotated[Pressure, Field(gt=0, description="G_xy of the spar-web laminate")]
    design_strain: Annotated[float, Field(gt=0, lt=0.05, description="design ultimate direct strain of the covers")]
    design_shear_strain: Annotated[float, Field(gt=0, lt=0.1, description="design ultimate shear strain")]
    skin_fraction: Annotated[
        float, Field(gt=0, le=1, description="skin share of the smeared cover (carries the torsion)")
    ]
    source: Annotated[str, Field(min_length=3)]


class MinimumGauges(_Section):
    """Minimum thicknesses of the sized box (smeared cover, spar web)."""

    cover: Annotated[Length, Field(gt=0)]
    web: Annotated[Length, Field(gt=0)]
    source: Annotated[str, Field(min_length=3)]


class ArealWeights(_Section):
    """Masses per unit planform area of the tail's secondary items (both halves): ribs on the box planform, the
    leading edge ahead of the front spar, the fixed trailing edge aft of the rear spar (to the hinge line along
    the elevator, to the trailing edge elsewhere), the elevator aft of its hinge line."""

    ribs: Annotated[ArealDensity, Field(ge=0)]
    leading_edge: Annotated[ArealDensity, Field(ge=0)]
    trailing_edge: Annotated[ArealDensity, Field(ge=0)]
    elevator: Annotated[ArealDensity, Field(ge=0)]
    source: Annotated[str, Field(min_length=3)]


class TailStructureSizing(_Section):
    """Structural sizing data of the horizontal tail (:func:`certkit.models.structure.tail.size_horizontal_tail`)."""

    front_spar: Annotated[float, Field(gt=0, lt=1, description="front spar chord fraction")]
    rear_spar: Annotated[float, Field(gt=0, lt=1, description="rear spar chord fraction")]
    material: LaminateAllowables
    minimum_gauge: MinimumGauges
    areal_weights: ArealWeights
    fittings_fraction: Annotated[
        float, Field(ge=0, lt=1, description="fittings and attachments, fraction of box + ribs")
    ]
    non_optimum_factor: Annotated[
        float,
        Field(
            ge=1,
            le=3,
            description="sized (ideal) cover and web mass × factor = built box mass (joints, fasteners, cut-outs)",
        ),
    ]
    source: Annotated[str, Field(min_length=3, description="where the factors come from and how they were calibrated")]


class SizingLoop(_Section):
    """Convergence of the design loop (loads → sizing → mass → loads)."""

    mass_tolerance: Annotated[Mass, Field(gt=0, description="converged when the sized mass changes by less than this")]
    max_iterations: Annotated[int, Field(ge=1, le=50)]


class ActuatorSizingData(_Section):
    """Elevator actuators (:func:`certkit.models.structure.actuators.size_elevator_actuators`): piston area =
    margin × share × panel hinge moment / (arm × pressure); stroke = arm (sin δ_max − sin δ_min) over the travel;
    mass = fixed_mass + mass_per_work × stall force × stroke; flow at ``surface_rate``."""

    per_panel: Annotated[int, Field(ge=1, le=6, description="actuators on each elevator panel")]
    pressure: Annotated[Pressure, Field(gt=0, description="hydraulic supply pressure ('3000 psi')")]
    arm: Annotated[Length, Field(gt=0, description="moment arm of the actuator about the hinge line (horn)")]
    margin: Annotated[float, Field(ge=1, le=3, description="stall force over the design force")]
    share: Annotated[
        float,
        Field(
            gt=0,
            le=1,
            description="fraction of the panel hinge moment one actuator must react "
            "(1: each actuator holds the panel alone)",
        ),
    ]
    surface_rate: Annotated[AngularRate, Field(gt=0, description="design surface rate ('40 deg/s')")]
    mass_per_work: Annotated[MassPerEnergy, Field(ge=0, description="actuator mass per unit stall force × stroke")]
    fixed_mass: Annotated[Mass, Field(ge=0, description="mass independent of size (servo valve, manifold, sensors)")]
    source: Annotated[str, Field(min_length=3)]


class Sizing(_Section):
    """Structural sizing data for design studies: the horizontal-tail group, the loop's tolerance and
    the elevator actuators."""

    horizontal_tail: TailStructureSizing | None = None
    loop: SizingLoop | None = None
    elevator_actuators: ActuatorSizingData | None = None
    cg_envelope: Literal["declared", "loading"] = Field(
        "declared",
        description="the weight–CG corners a design is evaluated at: 'declared' (cg_envelope as written) "
        "or 'loading' (each corner moved to the CG the design's own loading reaches at its weight — OEW and its CG "
        "with the sized tail, payload zones and fuel tanks — with the declared corner as the bound)",
    )


def _printable(name: str) -> str:
    if not name.isprintable():
        raise ValueError(
            "the name must be one line of printable characters (no control characters such as a "
            "newline or NUL): it names the report folder and heads the report"
        )
    return name


RuleId = Annotated[str, Field(pattern=r"^\d+\.\d+[a-z]?(\([a-z0-9]+\))*$")]


class Aircraft(_Section):
    """A transport airplane as certkit reads it from YAML."""

    name: Annotated[str, Field(min_length=1, max_length=200), AfterValidator(_printable)]
    description: str | None = None
    reference: Reference
    geometry: Geometry | None = Field(None, description="needed unless every configuration has derivative tables")
    mass: MassProperties
    cg_envelope: CgEnvelope | None = Field(None, description="needed by the rules (their CG corners)")
    propulsion: Propulsion | None = Field(
        None,
        description="without it: an ideal thrust along the body x axis "
        "through the moment point, constant with speed unless "
        "the derivative table gives T_u / CT_u",
    )
    configurations: dict[str, Configuration] = Field(default_factory=lambda: {"clean": Configuration()})
    speeds: Speeds = Field(default_factory=Speeds)
    envelope: Envelope | None = Field(None, description="needed by the rules (altitudes, ceiling, load factors)")
    flight_condition: FlightCondition | None = Field(
        None, description="condition of published derivatives; default condition of trim and modes"
    )
    aerodynamics: Aerodynamics = Field(default_factory=Aerodynamics)
    structure: Structure | None = Field(None, description="declared structural capabilities (allowable loads)")
    performance: Performance | None = Field(None, description="declared performance figures (takeoff field length)")
    takeoff_pilot: TakeoffPilot = Field(
        default_factory=TakeoffPilot,
        description="the pilot of the simulated takeoff "
        "runs: reaction to an engine failure, rudder rate, nose-wheel steering",
    )
    takeoff_landing_envelope: TakeoffLandingEnvelope | None = Field(
        None, description="airport altitude and temperature range: §25.121 over weight–altitude–temperature"
    )
    mission: Mission | None = Field(None, description="mission definition for range, payload-range and block fuel")
    calibration: PerformanceCalibration | None = Field(
        None, description="declared drag and fuel-flow factors reproducing published performance (certkit calibrate)"
    )
    control_forces: ControlForces | None = Field(
        None, description="cockpit control-force models (hinge moments or feel)"
    )
    sizing: Sizing | None = Field(
        None, description="structural sizing data for design studies (horizontal tail, actuators)"
    )
    criteria: dict[RuleId, CriterionOverride] = Field(default_factory=dict)
    sources: dict[str, str] = Field(default_factory=dict, description="citations used in the file")
