"""The flight model of an aircraft file: aerodynamics + loading + engines → equations of motion.

Builds :class:`certkit.models.dynamics.eom.AircraftModel` for a batch of loading conditions in one
configuration, with each engine at its position (so an inoperative engine gives its asymmetric
yawing moment and windmilling drag), thrust from the declared deck or, without one, the parametric
turbofan scaled to the declared static thrust. Control limits come from the geometry's control
surfaces: the design limits (``design_limits``) by default, the mechanical travel otherwise; a movable
stabiliser's design limits may differ per configuration (``design_limits_by_configuration``).

Ground model (:func:`ground_model`): the declared ``geometry.landing_gear`` contact points — the
main gear point and its mirror image (two main legs) and the nose gear — as spring–damper legs.
Each leg's stiffness is its share of the weight at a sizing loading (MTOW at the reference CG by
default, shared by the lever rule between the nose and the two mains) over a static stroke
(0.30 m, of the order of a large transport's oleo static compression, Currey, *Aircraft Landing
Gear Design: Principles and Practices*, AIAA 1988, ch. 5: static position about 2/3 … 3/4 of
a 0.4–0.6 m stroke), and its damping a fraction ``damping_ratio`` of the critical damping of
that share of the mass on that spring. Tyre rolling friction 0.02 (dry concrete, Torenbeek
*Synthesis of Subsonic Airplane Design* §K-2 / Raymer Table 17.1: 0.02–0.03), braked friction
0.4 added on the mains at full brake (Raymer Table 17.1: 0.3–0.5 dry concrete). These are model
settings, not regulation numbers.
"""

from __future__ import annotations

import numpy as np

from certkit.aircraft.derivative_names import STABILIZER
from certkit.atmosphere import speed_of_sound
from certkit.models.aero import planform
from certkit.models.aero.derivative_forms import thrust_speed_derivative
from certkit.models.aero.tail_ground_effect import lifting_line
from certkit.models.dynamics.eom import AircraftModel, Engine, GearLeg, GroundEffectWing, GroundModel
from certkit.models.dynamics.trim import StabilizerTrim, trim
from certkit.models.mass.loading import reference_cg, solve_loading
from certkit.models.propulsion.engine import EngineDeck, ParametricTurbofan, windmill_drag
from certkit.models.reference_condition import gravity, reference_condition

#: the aero control that moves each trim axis
ROLES = {"pitch": "elevator", "roll": "aileron", "yaw": "rudder"}


def thrust_function(aircraft):
    """``thrust(throttle, h, mach) -> N`` of one engine: the declared deck or the parametric turbofan."""
    p = aircraft.propulsion
    if p.deck is not None:
        d = p.deck
        deck = EngineDeck(
            d.altitude,
            d.mach,
            d.throttle,
            np.array(d.thrust, dtype=float),
            None if d.fuel_flow is None else np.array(d.fuel_flow, dtype=float),
            allow_extrapolation=d.allow_extrapolation,
            name="propulsion.deck",
        )
        return deck.thrust, "declared engine deck"
    engine = ParametricTurbofan(p.static_thrust)
    return engine.thrust, "parametric high-bypass turbofan scaled to the declared static thrust (Mattingly lapse)"


def throttle_for_thrust(thrust, target, h, mach, iterations: int = 48) -> np.ndarray:
    """The throttle (0–1) at which one engine gives ``target`` thrust (N) per condition: bisection, the thrust
    increasing with the throttle; 1 where the target is the full thrust."""
    lo, hi = np.zeros_like(h), np.ones_like(h)
    for _ in range(iterations):
        mid = 0.5 * (lo + hi)
        short = np.asarray(thrust(mid, h, mach), dtype=float) < target
        lo, hi = np.where(short, mid, lo), np.where(short, hi, mid)
    return np.where(target >= np.asarray(thrust(np.ones_like(h), h, mach), dtype=float), 1.0, 0.5 * (lo + hi))


def ideal_engine(aircraft) -> Engine:
    """A file without propulsion (a derivative-table airplane): one ideal thrust along the body x axis through
    the moment point, up to MTOW × g at full throttle, constant with speed unless the derivative table declares
    ∂T/∂u (T_u, CT_u; :func:`certkit.models.aero.derivative_forms.thrust_speed_derivative`) — the textbook
    assumption of Etkin & Reid §4.4 (thrust line through the CG, T_u given or zero)."""
    cond = reference_condition(aircraft)
    full = aircraft.mass.MTOW * gravity(aircraft)
    t_u = thrust_speed_derivative(aircraft, cond) if cond is not None else 0.0
    u0 = cond.tas if cond is not None else 0.0

    def thrust(throttle, h, mach):
        base = np.asarray(throttle, dtype=float) * full
        return base if t_u == 0.0 else base + t_u * (np.asarray(mach) * speed_of_sound(h) - u0)

    p = aircraft.reference.moment_point
    return Engine("ideal thrust", thrust, (p.x, p.y, p.z), (1.0, 0.0, 0.0), None)


def engines(aircraft) -> list[Engine]:
    if aircraft.propulsion is None:
        return [ideal_engine(aircraft)]
    thrust, _ = thrust_function(aircraft)
    g = aircraft.geometry
    inlet = 0.85 * g.nacelle.diameter if g is not None and g.nacelle is not None else None
    drag = windmill_drag(inlet) if inlet else None
    out = []
    for e in aircraft.propulsion.engines:
        ct, st = np.cos(e.thrust_angle), np.sin(e.thrust_angle)
        direction = (
            ct * np.cos(e.toe_angle),
            ct * np.sin(e.toe_angle),
            -st,
        )  # body axes, thrust line tilted up by thrust_angle
        out.append(Engine(e.name, thrust, (e.position.x, e.position.y, e.position.z), direction, drag))
    return out


def control_limits(aircraft, design: bool = True, configuration: str | None = None) -> dict[str, tuple[float, float]]:
    """(min, max) in radians of every control surface, design limits where declared; a movable stabiliser's as
    deflections from its datum incidence (the model's ``stabilizer`` control), its design limits those of
    ``configuration`` (:meth:`certkit.aircraft.model.MovableStabilizer.trim_limits`; None: the default pair)."""
    limits: dict[str, tuple[float, float]] = {"throttle": (0.0, 1.0)}
    g = aircraft.geometry
    if g is None:
        return limits
    for surface in (g.wing, g.horizontal_tail, g.vertical_tail):
        for name, c in surface.controls.items():
            lim = c.design_limits if (design and c.design_limits is not None) else c.travel
            limits[name] = (lim.min, lim.max)
    st = g.horizontal_tail.stabilizer
    if st is not None:
        lim, _ = st.trim_limits(configuration, design)
        limits[STABILIZER] = (lim.min - g.horizontal_tail.incidence, lim.max - g.horizontal_tail.incidence)
    return limits


def stabilizer_trim(aircraft, design: bool = True, configuration: str | None = None):
    """The movable stabiliser of the aircraft as a trim device
    (:class:`certkit.models.dynamics.trim.StabilizerTrim`) within the limits of ``configuration``, None without one
    (or without geometry, e.g. an airplane given by derivative tables, whose model has no stabiliser control)."""
    g = aircraft.geometry
    if g is None or g.horizontal_tail.stabilizer is None:
        return None
    st = g.horizontal_tail.stabilizer
    return StabilizerTrim(
        control_limits(aircraft, design, configuration)[STABILIZER],
        datum=g.horizontal_tail.incidence,
        elevator_trim=st.elevator_trim,
        control=STABILIZER,
        elevator=ROLES["pitch"],
    )


def model_stabilizer(aircraft, model, design: bool = True, configuration: str | None = None):
    """:func:`stabilizer_trim` when ``model``'s aerodynamics carry the stabiliser control (a declared derivative
    table may not), else None: the trims of that model keep the elevator as the pitch control."""
    if STABILIZER not in model.aero_controls:
        return None
    return stabilizer_trim(aircraft, design, configuration)


def flight_model(aircraft, aero_model, loadings, operative=None, ground: GroundModel | None = None) -> AircraftModel:
    """Equations of motion for the loadings (:class:`certkit.models.mass.loading.Loading`) of one batch
    (with ``ground`` — e.g. :func:`ground_model` — for takeoff and landing)."""
    mass = np.array([ld.properties.mass for ld in loadings])
    cg = np.array([ld.properties.cg for ld in loadings])
    inertia = np.array([ld.properties.inertia for ld in loadings])

    return AircraftModel(
        aero_model, mass, cg, inertia, engines(aircraft), operative=operative, ground=ground, g=gravity(aircraft)
    )


def gear_static_loads(aircraft, mass: float, x_cg: float, g: float = 9.80665) -> tuple[float, float]:
    """(nose, each main) static reactions (N) at rest by the lever rule about the gear contact stations."""
    lg = aircraft.geometry.landing_gear
    base = lg.main.x - lg.nose.x
    nose = mass * g * (lg.main.x - x_cg) / base
    main = mass * g * (x_cg - lg.nose.x) / base / 2.0
    return nose, main


def ground_model(
    aircraft,
    mass: float | None = None,
    x_cg: float | None = None,
    elevation: float = 0.0,
    static_stroke: float = 0.30,
    damping_ratio: float = 0.5,
    rolling_friction: float = 0.02,
    brake_friction: float = 0.4,
    side_friction: float = 0.6,
    nose_wheel: str = "straight",
) -> GroundModel:
    """Spring–damper legs from ``geometry.landing_gear`` (module docstring); ``mass``/``x_cg`` the sizing
    loading (default MTOW at the reference CG). ``nose_wheel``: "straight" (held straight, side friction as the
    mains'), "steered" (turned by the model's ``nose_wheel_steering`` control) or "castering" (steering disengaged:
    the wheel trails freely, no side force). Raises ValueError when the gear is not declared."""
    g = aircraft.geometry
    if g is None or g.landing_gear is None:
        raise ValueError("geometry.landing_gear is not declared (main and nose gear contact points)")
    lg = g.landing_gear
    mass = aircraft.mass.MTOW if mass is None else mass
    x_cg = reference_cg(aircraft) if x_cg is None else x_cg
    nose_load, main_load = gear_static_loads(aircraft, mass, x_cg)
    if nose_load <= 0 or main_load <= 0:
        raise ValueError(
            f"the CG at {x_cg:.2f} m is not between the nose ({lg.nose.x:.2f} m) and main gear ({lg.main.x:.2f} m)"
        )

    if nose_wheel not in ("straight", "steered", "castering"):
        raise ValueError(f"nose_wheel must be 'straight', 'steered' or 'castering', not {nose_wheel!r}")

    def leg(name, pos, load, braked, side=side_friction, steered=False):
        k = load / static_stroke
        c = damping_ratio * 2.0 * np.sqrt(k * load / 9.80665)
        return GearLeg(
            name, pos, k, c, rolling_friction=rolling_friction, side_friction=side, braked=braked, steered=steered
        )

    main_y = abs(lg.main.y)
    legs = [
        leg("main left", (lg.main.x, -main_y, lg.main.z), main_load, True),
        leg("main right", (lg.main.x, main_y, lg.main.z), main_load, True),
        leg(
            "nose",
            (lg.nose.x, lg.nose.y, lg.nose.z),
            nose_load,
            False,
            side=0.0 if nose_wheel == "castering" else side_friction,
            steered=nose_wheel == "steered",
        ),
    ]
    return GroundModel(
        legs, elevation=elevation, brake_friction=brake_friction, wing=ground_effect_wing(g.wing, g.horizontal_tail)
    )


def ground_effect_wing(wing, horizontal_tail=None) -> GroundEffectWing:
    """The declared wing for ground effect: height taken at the MAC quarter chord (DATCOM §1.2.2 station,
    dihedral included), the wing's own span, aspect ratio and half-chord sweep; with ``horizontal_tail``, both
    quarter-chord lines for the downwash at the tail (:mod:`certkit.models.aero.tail_ground_effect`)."""
    line = lifting_line(wing)
    point = (line.reference[0], 0.0, line.reference[1])
    lines = None if horizontal_tail is None else (line, lifting_line(horizontal_tail))
    return GroundEffectWing(
        point,
        float(planform.span(wing.area, wing.aspect_ratio)),
        float(wing.aspect_ratio),
        float(planform.sweep_at(0.5, wing.sweep_quarter_chord, wing.aspect_ratio, wing.taper)),
        lines,
    )


def level_trims(aircraft, aero, masses, x_cg: float, altitude, tas, loading_name: str = ""):
    """Straight, wings-level trims of one batch in the configuration of ``aero`` (an
    :class:`certkit.models.aero.airplane.AirplaneAero`) at the masses (kg), one CG station (m), altitudes (m) and true
    airspeeds (m/s), with the design control limits of that configuration: the trims a
    :class:`certkit.engine.context.Context` would make for the same conditions, for models that hold no Context (the
    mission).
    Each distinct mass is loaded once."""
    masses = [float(m) for m in masses]
    solved: dict[float, object] = {}
    for m in masses:
        if m not in solved:
            solved[m] = solve_loading(aircraft, m, float(x_cg), loading_name)
    model = flight_model(aircraft, aero.model, [solved[m] for m in masses])
    config = aero.configuration
    return trim(
        model,
        np.asarray(tas, dtype=float),
        np.asarray(altitude, dtype=float),
        kind="straight",
        limits=control_limits(aircraft, True, config),
        roles=ROLES,
        stabilizer=model_stabilizer(aircraft, model, True, config),
    )
