"""Physical consistency of an aircraft file: relations between fields.

Each check declares the sections it needs; it runs when those sections are valid on their own,
so a file with a bad speed and a bad mass gets both messages in one run.
"""

from __future__ import annotations

import math
from typing import Callable, Iterator

import numpy as np

from certkit.aircraft.derivative_names import SPEED_TERMS, unknown_names
from certkit.errors import Problem

Check = Callable[[dict], Iterator[tuple[str, str, object]]]
CHECKS: list[tuple[tuple[str, ...], Check]] = []


def needs(*sections: str):
    def register(fn: Check) -> Check:
        CHECKS.append((sections, fn))
        return fn

    return register


@needs("mass")
def _mass_order(s):
    m = s["mass"]
    if m.MLW is not None and m.MLW > m.MTOW:
        yield "mass.MLW", f"maximum landing weight must not exceed MTOW ({m.MTOW:.0f} kg)", m.MLW
    if m.MZFW is not None and m.MZFW > (m.MLW if m.MLW is not None else m.MTOW):
        limit = "MLW" if m.MLW is not None else "MTOW"
        yield "mass.MZFW", f"maximum zero-fuel weight must not exceed {limit} ({getattr(m, limit):.0f} kg)", m.MZFW
    if m.OEW is not None and m.OEW >= (m.MZFW if m.MZFW is not None else m.MTOW):
        limit = "MZFW" if m.MZFW is not None else "MTOW"
        yield "mass.OEW", f"operating empty weight must be below {limit} ({getattr(m, limit):.0f} kg)", m.OEW
    for name in ("MZFW", "OEW"):
        if getattr(m, name) is None and (m.fuel_tanks or m.payload_zones):
            yield f"mass.{name}", "needed with fuel tanks or payload zones (the loading solver's limits)", None
    if m.MRW is not None and m.MRW < m.MTOW:
        yield "mass.MRW", f"maximum ramp weight must be at least MTOW ({m.MTOW:.0f} kg)", m.MRW
    for i, c in enumerate(m.components):
        if c.inertia is not None and not _triangle_ok(c.inertia):
            yield (
                f"mass.components.{i}.inertia",
                "inertia tensor is not physically possible (not positive definite or violates Ixx+Iyy≥Izz)",
                None,
            )
    if m.inertia is not None and not _triangle_ok(m.inertia):
        yield (
            "mass.inertia",
            "inertia tensor is not physically possible (not positive definite or violates Ixx+Iyy≥Izz)",
            None,
        )
    for i, z in enumerate(m.payload_zones):
        if z.x_end <= z.x_start:
            yield f"mass.payload_zones.{i}.x_end", f"zone must end aft of its start ({z.x_start:.2f} m)", z.x_end


def _triangle_ok(t) -> bool:
    tensor = np.array([[t.Ixx, -t.Ixy, -t.Ixz], [-t.Ixy, t.Iyy, -t.Iyz], [-t.Ixz, -t.Iyz, t.Izz]])
    eig = np.linalg.eigvalsh(tensor)
    if eig.min() <= 0:
        return False
    a, b, c = sorted(eig)
    return a + b >= c * (1 - 1e-9)


@needs("speeds")
def _speed_order(s):
    sp = s["speeds"]

    def tas_free_compare(name_lo, name_hi, factor=1.0, what=""):
        lo, hi = getattr(sp, name_lo), getattr(sp, name_hi)
        if lo is None or hi is None:
            return None
        if lo.kind != hi.kind:
            return None  # different kinds compare only at an altitude; the rules do that
        if hi.value < factor * lo.value:
            return (
                f"speeds.{name_hi}",
                f"{name_hi} must not be below {what or name_lo} ({factor * lo.value:.2f} m/s {lo.kind})",
                hi.value,
            )
        return None

    for lo, hi in (
        ("VC", "VD"),
        ("VB", "VC"),
        ("V1", "VR"),
        ("VR", "V2"),
        ("VA", "VD"),
        ("VMO", "VD"),
        ("VMO", "VFC"),
        ("VFC", "VD"),
    ):
        found = tas_free_compare(lo, hi)
        if found:
            yield found
    for lo, hi in (("MC", "MD"), ("MMO", "MD"), ("MMO", "MFC"), ("MFC", "MD")):
        a, b = getattr(sp, lo), getattr(sp, hi)
        if a is not None and b is not None and b < a:
            yield f"speeds.{hi}", f"{hi} must not be below {lo} ({a:.3f})", b


@needs("aerodynamics", "configurations")
def _aero_configurations(s):
    names = set(s["configurations"])
    aero = s["aerodynamics"]
    for field in ("derivative_tables", "overrides"):
        for name in getattr(aero, field):
            if name not in names:
                yield (
                    f"aerodynamics.{field}.{name}",
                    f"unknown configuration (declared: {', '.join(sorted(names))})",
                    name,
                )
    for name, table in aero.derivative_tables.items():
        yield from _derivative_table(name, table, s.get("flight_condition"), s.get("propulsion"))


def _derivative_table(name, table, condition, propulsion):
    """Names of the table's form, one value per Mach breakpoint, what the dimensional form and the speed
    derivatives need (a flight condition, one Mach), thrust–speed only without a propulsion section."""
    at = f"aerodynamics.derivative_tables.{name}"
    mach = table.mach if table.mach is not None else [condition.mach if condition and condition.mach else 0.0]
    if table.mach is None and condition is None:
        yield f"{at}.mach", "give the Mach breakpoints or a flight_condition section (whose Mach number is used)", None
    if any(b <= a for a, b in zip(mach, mach[1:])):
        yield f"{at}.mach", "Mach breakpoints must increase strictly", table.mach
    for key in unknown_names(table.derivatives, table.form, table.control_names):
        yield (
            f"{at}.derivatives.{key}",
            f"not a {table.form} derivative name nor a term of a control in "
            f"{table.control_names} (names: `certkit schema`, aerodynamics.derivative_tables)",
            key,
        )
    for key, value in table.derivatives.items():
        if isinstance(value, list) and len(value) != len(mach):
            yield f"{at}.derivatives.{key}", f"needs one value per Mach breakpoint ({len(mach)})", value
    speed = [k for k in table.derivatives if k in SPEED_TERMS + ("CT_u", "T_u")]
    if (table.form == "dimensional" or speed) and condition is None:
        what = "the dimensional form" if table.form == "dimensional" else ", ".join(speed)
        yield at, f"{what} needs the flight_condition section (the speed and density the derivatives refer to)", None
    if (table.form == "dimensional" or speed) and len(mach) > 1:
        yield (
            f"{at}.mach",
            (
                "the dimensional form and speed derivatives refer to one flight condition: give one Mach "
                "number (a Mach-tabulated table carries its speed dependence in its breakpoints)"
            ),
            table.mach,
        )
    if (
        (table.form == "dimensional" or speed)
        and table.mach is not None
        and len(mach) == 1
        and condition is not None
        and condition.mach is not None
        and abs(mach[0] - condition.mach) > 1e-3
    ):
        yield (
            f"{at}.mach",
            f"the dimensional form and speed derivatives refer to the flight condition's Mach number "
            f"({condition.mach:g}); leave mach out or give that one",
            table.mach,
        )
    if table.form == "dimensional" and "CD0" not in table.derivatives:
        yield f"{at}.derivatives", "the dimensional form needs CD0, the drag coefficient in the flight condition", None
    thrust = [k for k in ("CT_u", "T_u") if k in table.derivatives]
    if thrust and propulsion is not None:
        yield (
            f"{at}.derivatives.{thrust[0]}",
            "a thrust–speed derivative is for files without propulsion (the "
            "declared engines carry their own thrust variation)",
            None,
        )


@needs("speeds", "configurations")
def _speed_configurations(s):
    names = set(s["configurations"])
    for field in ("VSR", "VFE"):
        for name in getattr(s["speeds"], field):
            if name not in names:
                yield f"speeds.{field}.{name}", f"unknown configuration (declared: {', '.join(sorted(names))})", name


@needs("configurations")
def _configurations(s):
    if "clean" not in s["configurations"]:
        yield "configurations", "a 'clean' configuration (flaps and gear up) is required", sorted(s["configurations"])


@needs("configurations")
def _tail_flap_increment(s):
    """The tail's share of the flap increments applies only with the flaps down."""
    for name, cfg in s["configurations"].items():
        if cfg.tail_flap_increment is not None and not cfg.flap > 0:
            yield (
                f"configurations.{name}.tail_flap_increment",
                "the tail's share of the flap increments needs the "
                f"flaps down (flap > 0); configuration {name!r} has flap {math.degrees(cfg.flap):g} deg",
                cfg.tail_flap_increment.model_dump(),
            )


@needs("cg_envelope", "mass")
def _cg_envelope(s):
    env, m = s["cg_envelope"], s["mass"]
    pts = np.array([[v.x, v.mass] for v in env.vertices])
    crossing = _self_intersection(pts)
    if crossing is not None:
        i, j = crossing
        yield (
            "cg_envelope.vertices",
            (
                f"the polygon crosses itself: edge {i}–{i + 1} crosses edge {j}–{(j + 1) % len(pts)}; "
                "list the vertices in order around the envelope"
            ),
            None,
        )
    elif _polygon_area(pts) == 0.0:
        yield "cg_envelope.vertices", "the polygon has zero area", None
    heavy = max(v.mass for v in env.vertices)
    limit = m.MRW if m.MRW is not None else m.MTOW
    if heavy > limit * (1 + 1e-9):
        i = int(np.argmax([v.mass for v in env.vertices]))
        yield (
            f"cg_envelope.vertices.{i}.mass",
            f"envelope weight exceeds the maximum {('ramp' if m.MRW else 'takeoff')} weight ({limit:.0f} kg)",
            heavy,
        )
    names = [v.name for v in env.vertices if v.name]
    dupes = {n for n in names if names.count(n) > 1}
    for n in sorted(dupes):
        yield "cg_envelope.vertices", f"vertex name {n!r} is used more than once", n


@needs("cg_envelope", "mass")
def _reference_cg_inside(s):
    env = s["cg_envelope"]
    if env.reference_x is None:
        return
    xs = [v.x for v in env.vertices]
    if not (min(xs) <= env.reference_x <= max(xs)):
        yield (
            "cg_envelope.reference_x",
            f"reference CG lies outside the envelope ({min(xs):.2f} to {max(xs):.2f} m)",
            env.reference_x,
        )


@needs("geometry")
def _geometry(s):
    g = s["geometry"]
    if g.horizontal_tail.root_leading_edge.x <= g.wing.root_leading_edge.x:
        yield (
            "geometry.horizontal_tail.root_leading_edge.x",
            "horizontal tail must be aft of the wing leading edge",
            g.horizontal_tail.root_leading_edge.x,
        )
    for name in ("wing", "horizontal_tail", "vertical_tail"):
        x = getattr(g, name).root_leading_edge.x
        if not (0.0 <= x <= g.fuselage.length):
            yield (
                f"geometry.{name}.root_leading_edge.x",
                f"root lies outside the fuselage (0 to {g.fuselage.length:.2f} m)",
                x,
            )
    yield from _tail_on_fuselage(g)
    yield from _movable_stabilizer(g)


def _movable_stabilizer(g):
    """A movable stabiliser is the horizontal tail's; its datum incidence and the elevator's trim setting must lie
    within their ranges, and it needs an elevator to manoeuvre with."""
    for name in ("wing", "vertical_tail"):
        if getattr(g, name).stabilizer is not None:
            yield f"geometry.{name}.stabilizer", "only the horizontal tail can be a movable stabiliser", None
    t = g.horizontal_tail
    st = t.stabilizer
    if st is None:
        return
    deg = 180.0 / math.pi
    lim = st.design_limits or st.travel
    if not lim.min - 1e-12 <= t.incidence <= lim.max + 1e-12:
        yield (
            "geometry.horizontal_tail.incidence",
            f"the incidence is the stabiliser's datum and must lie within its "
            f"{'design limits' if st.design_limits else 'travel'} ({lim.min * deg:.2f}° to {lim.max * deg:.2f}°)",
            t.incidence,
        )
    elevator = t.controls.get("elevator")
    if elevator is None:
        yield "geometry.horizontal_tail.controls", "a movable stabiliser needs an elevator (controls.elevator)", None
        return
    e = elevator.design_limits or elevator.travel
    if not e.min <= st.elevator_trim <= e.max:
        yield (
            "geometry.horizontal_tail.stabilizer.elevator_trim",
            f"must lie within the elevator's limits ({e.min * deg:.1f}° to {e.max * deg:.1f}°)",
            st.elevator_trim,
        )


@needs("geometry", "configurations")
def _stabilizer_configurations(s):
    """Each configuration's stabiliser trim limits name a declared configuration, lie within the travel to the
    structural stops and hold the datum incidence (as ``design_limits`` do)."""
    t = s["geometry"].horizontal_tail
    st = t.stabilizer
    if st is None:
        return
    names = set(s["configurations"])
    deg = 180.0 / math.pi
    at = "geometry.horizontal_tail.stabilizer.design_limits_by_configuration"
    for name, lim in st.design_limits_by_configuration.items():
        if name not in names:
            yield f"{at}.{name}", f"unknown configuration (declared: {', '.join(sorted(names))})", name
        tr = st.travel
        if lim.min < tr.min - 1e-12 or lim.max > tr.max + 1e-12:
            yield (
                f"{at}.{name}",
                f"{lim.min * deg:.2f}° to {lim.max * deg:.2f}° must lie within the travel to the "
                f"structural stops ({tr.min * deg:.2f}° to {tr.max * deg:.2f}°)",
                None,
            )
        if not lim.min - 1e-12 <= t.incidence <= lim.max + 1e-12:
            yield (
                f"{at}.{name}",
                f"{lim.min * deg:.2f}° to {lim.max * deg:.2f}° must hold the stabiliser's datum, "
                f"geometry.horizontal_tail.incidence ({t.incidence * deg:.2f}°)",
                None,
            )


def _tail_on_fuselage(g):
    """The horizontal tail's root chord must end on the fuselage (it is attached there) and its tip must not lie
    wholly behind the fuselage end; trapezoid geometry: b = √(A S), c_r = 2S / (b (1 + λ)),
    tan Λ_LE = tan Λ_c/4 + (1 − λ) / (A (1 + λ))."""
    t, length = g.horizontal_tail, g.fuselage.length
    b = math.sqrt(t.aspect_ratio * t.area)
    c_root = 2.0 * t.area / (b * (1.0 + t.taper))
    tan_le = math.tan(t.sweep_quarter_chord) + (1.0 - t.taper) / (t.aspect_ratio * (1.0 + t.taper))
    x_root = t.root_leading_edge.x
    if x_root + c_root > length:
        yield (
            "geometry.horizontal_tail",
            f"root chord {c_root:.2f} m from x = {x_root:.2f} m ends behind the fuselage "
            f"end ({length:.2f} m): the tail root would not be attached to the fuselage",
            round(x_root + c_root, 3),
        )
    x_tip = x_root + 0.5 * b * tan_le
    if x_tip > length:
        yield (
            "geometry.horizontal_tail",
            f"tip leading edge at x = {x_tip:.2f} m lies behind the fuselage end "
            f"({length:.2f} m): the planform (area, aspect ratio, taper, sweep) places the whole tip behind the "
            "airplane",
            round(x_tip, 3),
        )


@needs("reference", "geometry")
def _reference_vs_wing(s):
    r, w = s["reference"], s["geometry"].wing
    if abs(r.area - w.area) > 0.25 * w.area:
        yield "reference.area", f"differs from the wing area ({w.area:.1f} m²) by more than 25 %", r.area


@needs("propulsion", "geometry")
def _engines(s):
    length = s["geometry"].fuselage.length
    for i, e in enumerate(s["propulsion"].engines):
        if not (-0.2 * length <= e.position.x <= 1.2 * length):
            yield f"propulsion.engines.{i}.position.x", "engine far outside the airplane", e.position.x


@needs("propulsion")
def _deck(s):
    d = s["propulsion"].deck
    if d is None:
        return
    for axis in ("altitude", "mach", "throttle"):
        if np.any(np.diff(getattr(d, axis)) <= 0):
            yield f"propulsion.deck.{axis}", "must increase strictly", getattr(d, axis)
    shape = (len(d.altitude), len(d.mach), len(d.throttle))
    for name in ("thrust", "fuel_flow"):
        table = getattr(d, name)
        if table is not None and np.shape(np.array(table, dtype=object if _ragged(table) else float)) != shape:
            yield (
                f"propulsion.deck.{name}",
                f"must be {shape[0]} altitudes × {shape[1]} Mach numbers × {shape[2]} throttles",
                None,
            )


def _ragged(table) -> bool:
    return len({len(row) for row in table}) > 1 or len({len(r) for row in table for r in row}) > 1


def _polygon_area(pts: np.ndarray) -> float:
    # scale-free shoelace area in normalised units
    p = (pts - pts.min(0)) / np.maximum(np.ptp(pts, 0), 1e-12)
    x, y = p[:, 0], p[:, 1]
    return float(0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))))


def _self_intersection(pts: np.ndarray) -> tuple[int, int] | None:
    """First pair of non-adjacent edges that properly intersect, or None."""
    p = (pts - pts.min(0)) / np.maximum(np.ptp(pts, 0), 1e-12)
    n = len(p)

    def orient(a, b, c):
        return np.sign((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))

    for i in range(n):
        a, b = p[i], p[(i + 1) % n]
        for j in range(i + 2, n):
            if i == 0 and j == n - 1:
                continue  # adjacent through the closing edge
            c, d = p[j], p[(j + 1) % n]
            if orient(a, b, c) * orient(a, b, d) < 0 and orient(c, d, a) * orient(c, d, b) < 0:
                return i, j
    return None


def consistency_problems(sections: dict) -> list[Problem]:
    """Run every check whose sections are available; return problems (path, message, value)."""
    problems = []
    for required, check in CHECKS:
        if all(sections.get(name) is not None for name in required):
            try:
                with np.errstate(over="raise", divide="raise", invalid="raise"):
                    for path, message, value in check(sections) or ():
                        problems.append(Problem(path, message, value))
            except (ArithmeticError, ValueError, np.linalg.LinAlgError) as exc:  # finite but extreme values
                problems.append(
                    Problem(
                        required[0],
                        f"values too extreme to check against {', '.join(required[1:]) or 'each other'} "
                        f"({exc.__class__.__name__}): check the magnitudes and units",
                        None,
                    )
                )
    return problems


@needs("structure")
def _structure(s):
    st = s["structure"]
    for surface in ("wing", "horizontal_tail", "vertical_tail"):
        seen = {}
        for i, c in enumerate(getattr(st, surface)):
            path = f"structure.{surface}.{i}"
            if surface == "vertical_tail" and c.station == "side_of_body":
                yield (
                    f"{path}.station",
                    "the fin has no side-of-body station: use root or a fraction of its height",
                    c.station,
                )
            key = ("root" if c.station in ("root", 0.0) else c.station, c.quantity)
            if key in seen:
                yield path, f"{c.quantity} at this station is already declared (item {seen[key]})", None
            seen.setdefault(key, i)
            for sense in ("negative", "positive"):
                lim = getattr(c.limit, sense, c.limit)
                ult = getattr(c.ultimate, sense, c.ultimate)
                if ult < lim:
                    yield (
                        f"{path}.ultimate",
                        f"ultimate allowable ({sense} sense, {ult:.4g}) is below the limit allowable ({lim:.4g})",
                        ult,
                    )


@needs("structure", "geometry")
def _capability_stations(s):
    """Every declared capability must sit at a station the loads are computed at (:mod:`certkit.models.loads.model`):
    inboard of the tip, and the side of body outboard of the surface's root, inside its semispan."""
    st, g = s["structure"], s["geometry"]
    for surface in ("wing", "horizontal_tail", "vertical_tail"):
        semispan = 0.5 * float(np.sqrt(getattr(g, surface).aspect_ratio * getattr(g, surface).area))
        for i, c in enumerate(getattr(st, surface)):
            path = f"structure.{surface}.{i}.station"
            if not isinstance(c.station, str) and c.station >= 1.0:
                yield (
                    path,
                    "no load acts at the tip: a capability station must lie inboard of it (0 ≤ station < 1)",
                    c.station,
                )
            if c.station == "side_of_body" and surface != "vertical_tail" and 0.5 * g.fuselage.width >= semispan:
                yield (
                    path,
                    f"the side of body (half the fuselage width, {0.5 * g.fuselage.width:.2f} m) lies outside the "
                    f"{surface.replace('_', ' ')} semispan ({semispan:.2f} m): no load is computed there",
                    c.station,
                )


@needs("envelope")
def _flap_load_factor(s):
    lf = s["envelope"].limit_load_factors
    if lf is not None and lf.flaps_extended is not None and lf.flaps_extended > lf.positive:
        yield (
            "envelope.limit_load_factors.flaps_extended",
            f"the flaps-extended limit load factor (§25.345(a)) must "
            f"not exceed the clean positive limit load factor ({lf.positive:g}, §25.337(b))",
            lf.flaps_extended,
        )


#: the lifting surface that carries each primary control
_CONTROL_SURFACE = {"elevator": "horizontal_tail", "aileron": "wing", "rudder": "vertical_tail"}


@needs("control_forces", "geometry")
def _control_forces(s):
    forces, g = s["control_forces"], s["geometry"]
    for name, surface in _CONTROL_SURFACE.items():
        if getattr(forces, name) is not None and name not in getattr(g, surface).controls:
            yield (
                f"control_forces.{name}",
                f"no control surface named {name!r} on geometry.{surface} "
                f"(declared: {', '.join(getattr(g, surface).controls) or 'none'})",
                None,
            )


@needs("sizing")
def _sizing_spars(s):
    t = s["sizing"].horizontal_tail
    if t is not None and t.rear_spar <= t.front_spar:
        yield "sizing.horizontal_tail.rear_spar", f"must lie aft of the front spar ({t.front_spar})", t.rear_spar


@needs("sizing", "geometry")
def _sizing_geometry(s):
    sz, ht = s["sizing"], s["geometry"].horizontal_tail
    elevator = ht.controls.get("elevator")
    if (
        sz.horizontal_tail is not None
        and elevator is not None
        and 1.0 - elevator.chord_ratio < sz.horizontal_tail.rear_spar
    ):
        yield (
            "sizing.horizontal_tail.rear_spar",
            f"the elevator hinge line ({1.0 - elevator.chord_ratio:.3f} of the chord, "
            "geometry.horizontal_tail.controls.elevator.chord_ratio) lies ahead of the rear spar",
            sz.horizontal_tail.rear_spar,
        )
    if sz.elevator_actuators is not None and elevator is None:
        yield (
            "sizing.elevator_actuators",
            "no control surface named 'elevator' on geometry.horizontal_tail "
            f"(declared: {', '.join(ht.controls) or 'none'})",
            None,
        )


@needs("mass")
def _fuel_capacity(s):
    m = s["mass"]
    capacity = sum(t.capacity for t in m.fuel_tanks)
    if m.max_fuel is not None and m.fuel_tanks and m.max_fuel > capacity * (1 + 1e-3):
        yield "mass.max_fuel", f"exceeds the capacity of the declared fuel tanks ({capacity:.0f} kg)", m.max_fuel


@needs("mission", "mass")
def _mission_payload(s):
    mission, m = s["mission"], s["mass"]
    if m.MZFW is None or m.OEW is None:
        yield "mass", "the mission needs mass.MZFW and mass.OEW", None
        return
    room = m.MZFW - m.OEW
    if m.max_payload is not None and mission.design_payload > m.max_payload * (1 + 1e-9):
        yield "mission.design_payload", f"exceeds mass.max_payload ({m.max_payload:.0f} kg)", mission.design_payload
    elif mission.design_payload > room * (1 + 1e-9):
        yield "mission.design_payload", f"exceeds MZFW − OEW ({room:.0f} kg)", mission.design_payload
    dc = mission.drag_condition
    if dc.mass is not None and not (m.OEW < dc.mass <= m.MTOW):
        yield (
            "mission.drag_condition.mass",
            f"must lie between OEW ({m.OEW:.0f} kg) and MTOW ({m.MTOW:.0f} kg)",
            dc.mass,
        )


@needs("mission", "envelope")
def _mission_altitudes(s):
    mission, ceiling = s["mission"], s["envelope"].ceiling
    top = mission.max_altitude if mission.max_altitude is not None else ceiling
    if mission.max_altitude is not None and mission.max_altitude > ceiling * (1 + 1e-9):
        yield "mission.max_altitude", f"above envelope.ceiling ({ceiling:.0f} m)", mission.max_altitude
    if mission.initial_altitude > top * (1 + 1e-9):
        yield "mission.initial_altitude", f"above the highest cruise level ({top:.0f} m)", mission.initial_altitude
    r = mission.reserves
    if r.alternate_altitude > ceiling:
        yield "mission.reserves.alternate_altitude", f"above envelope.ceiling ({ceiling:.0f} m)", r.alternate_altitude
    if r.hold_altitude >= r.alternate_altitude:
        yield (
            "mission.reserves.hold_altitude",
            f"must be below the alternate cruise altitude ({r.alternate_altitude:.0f} m)",
            r.hold_altitude,
        )
    if mission.speed_limit_altitude >= mission.initial_altitude:
        yield (
            "mission.speed_limit_altitude",
            f"must be below the initial cruise altitude ({mission.initial_altitude:.0f} m)",
            mission.speed_limit_altitude,
        )
    if not (0.0 <= mission.drag_condition.altitude <= ceiling):
        yield (
            "mission.drag_condition.altitude",
            f"outside 0 … envelope.ceiling ({ceiling:.0f} m)",
            mission.drag_condition.altitude,
        )
    lo, hi = mission.low_altitude_speed, mission.climb_speed
    if lo.kind == hi.kind and lo.value > hi.value:
        yield "mission.low_altitude_speed", f"must not exceed the climb speed ({hi.value:.2f} m/s {hi.kind})", lo.value


@needs("mission", "cg_envelope")
def _mission_cg(s):
    x = s["mission"].cruise_cg
    xs = [v.x for v in s["cg_envelope"].vertices]
    if x is not None and not (min(xs) <= x <= max(xs)):
        yield "mission.cruise_cg", f"outside the CG envelope ({min(xs):.2f} to {max(xs):.2f} m)", x


#: stations of mass items and gear may lie this fraction of the fuselage length ahead of the nose or behind the tail
#: (a radome, a tail cone, an APU exhaust); beyond it a station is a mistake (a unit or datum slip)
STATION_MARGIN = 0.1


@needs("geometry", "cg_envelope")
def _cg_ahead_of_main_gear(s):
    """Every CG the envelope allows lies ahead of the main gear contact (else the airplane sits on its tail), and
    the nose gear ahead of the main gear."""
    gear = s["geometry"].landing_gear
    if gear is None:
        return
    vertices = s["cg_envelope"].vertices
    i = int(np.argmax([v.x for v in vertices]))
    if vertices[i].x >= gear.main.x:
        yield (
            f"cg_envelope.vertices.{i}.x",
            f"CG at or behind the main gear (geometry.landing_gear.main.x = "
            f"{gear.main.x:.2f} m): the airplane would tip onto its tail",
            vertices[i].x,
        )
    if gear.nose.x >= gear.main.x:
        yield "geometry.landing_gear.nose.x", f"must lie ahead of the main gear ({gear.main.x:.2f} m)", gear.nose.x


@needs("geometry", "mass")
def _stations_on_the_airplane(s):
    """Mass items, fuel tanks, payload zones and gear within the fuselage length ± :data:`STATION_MARGIN`."""
    length = s["geometry"].fuselage.length
    lo, hi = -STATION_MARGIN * length, (1 + STATION_MARGIN) * length
    m, gear = s["mass"], s["geometry"].landing_gear
    stations = [(f"mass.components.{i}.cg.x", c.cg.x) for i, c in enumerate(m.components)]
    stations += [(f"mass.fuel_tanks.{i}.cg.x", t.cg.x) for i, t in enumerate(m.fuel_tanks)]
    stations += [
        (f"mass.payload_zones.{i}.{end}", getattr(z, end))
        for i, z in enumerate(m.payload_zones)
        for end in ("x_start", "x_end")
    ]
    stations += [(f"geometry.landing_gear.{leg}.x", getattr(gear, leg).x) for leg in ("main", "nose")] if gear else []
    stations += [("mass.oew_cg.x", m.oew_cg.x)] if m.oew_cg is not None else []
    for path, x in stations:
        if not lo <= x <= hi:
            yield (
                path,
                f"station outside the airplane ({lo:.2f} to {hi:.2f} m: the fuselage length ± {STATION_MARGIN:.0%})",
                x,
            )
    if gear is not None and m.oew_cg is not None and m.oew_cg.x >= gear.main.x:
        yield "mass.oew_cg.x", f"empty-weight CG at or behind the main gear ({gear.main.x:.2f} m)", m.oew_cg.x


_AXES = {"Ixx": (1, 2), "Iyy": (0, 2), "Izz": (0, 1)}


@needs("geometry", "mass")
def _inertia_bounds(s):
    """The whole-airplane inertia (at MTOW) against two bounds it cannot leave.

    Upper: a mass spread over an interval of width w about its mean has a variance of at most w²/4 (Popoviciu's
    inequality on variances, 1935), so I_yy ≤ MTOW (Δx² + Δz²)/4 with Δx, Δy, Δz the airplane's extents (fuselage
    length with the station margin, the largest span, fuselage height + fin height + gear depth). Lower: the declared
    components are part of the airplane at MTOW, and the inertia of a part about the whole's CG is at least its
    inertia about its own CG (parallel-axis theorem), so I ≥ Σ m_i d_i² + Σ I_i over the components."""
    m, g = s["mass"], s["geometry"]
    if m.inertia is None:
        return
    spans = [math.sqrt(t.aspect_ratio * t.area) for t in (g.wing, g.horizontal_tail)]
    depth = max(0.0, -min(leg.z for leg in (g.landing_gear.main, g.landing_gear.nose))) if g.landing_gear else 0.0
    extent = (
        (1 + 2 * STATION_MARGIN) * g.fuselage.length,
        max(spans + [g.fuselage.width]),
        g.fuselage.height + math.sqrt(g.vertical_tail.aspect_ratio * g.vertical_tail.area) + depth,
    )
    lower = _component_inertia(m.components) if sum(c.mass for c in m.components) <= m.MTOW * (1 + 1e-9) else None
    for name, (a, b) in _AXES.items():
        declared = getattr(m.inertia, name)
        upper = m.MTOW * (extent[a] ** 2 + extent[b] ** 2) / 4.0
        if declared > upper:
            yield (
                f"mass.inertia.{name}",
                f"larger than any mass of MTOW within the airplane's extents can have "
                f"({upper:.4g} kg·m²): check the unit",
                declared,
            )
        if lower is not None and declared < lower[name] * (1 - 1e-3):
            yield (
                f"mass.inertia.{name}",
                f"smaller than the inertia of the declared mass.components alone "
                f"({lower[name]:.4g} kg·m² about their own CG): adding mass cannot reduce it; check the unit or "
                "the components",
                declared,
            )


def _component_inertia(components) -> dict[str, float] | None:
    """Moments of inertia of the components about their common CG (point masses plus their own inertias)."""
    if not components:
        return None
    masses = np.array([c.mass for c in components])
    r = np.array([[c.cg.x, c.cg.y, c.cg.z] for c in components])
    out = {}
    with np.errstate(all="ignore"):  # absurd (finite) inputs may overflow: then there is no bound to check
        d = r - masses @ r / masses.sum()
        for name, (a, b) in _AXES.items():
            own = sum(getattr(c.inertia, name) for c in components if c.inertia is not None)
            out[name] = float(masses @ (d[:, a] ** 2 + d[:, b] ** 2)) + own
    return out if all(map(math.isfinite, out.values())) else None


@needs("takeoff_landing_envelope")
def _takeoff_landing_envelope(s):
    """Ranges that run from low to high, a hot limit above the coldest, declared WAT limits inside the envelope with a
    weight, and (with engines) the flat rating an off-standard day needs."""
    env = s["takeoff_landing_envelope"]
    if env.pressure_altitude_min >= env.pressure_altitude_max:
        yield (
            "takeoff_landing_envelope.pressure_altitude_max",
            f"must exceed pressure_altitude_min ({env.pressure_altitude_min:.0f} m)",
            env.pressure_altitude_max,
        )
    if env.temperature_min >= env.temperature_max:
        yield (
            "takeoff_landing_envelope.temperature_max",
            f"must exceed temperature_min ({env.temperature_min:.2f} K)",
            env.temperature_max,
        )
    for i, w in enumerate(env.wat_limits):
        where = f"takeoff_landing_envelope.wat_limits.{i}"
        if not env.pressure_altitude_min - 1e-6 <= w.pressure_altitude <= env.pressure_altitude_max + 1e-6:
            yield (
                f"{where}.pressure_altitude",
                f"outside the envelope's pressure altitudes ({env.pressure_altitude_min:.0f}"
                f"…{env.pressure_altitude_max:.0f} m)",
                w.pressure_altitude,
            )
        if not env.temperature_min - 1e-6 <= w.temperature <= env.temperature_max + 1e-6:
            yield (
                f"{where}.temperature",
                f"outside the envelope's temperatures ({env.temperature_min:.2f}…{env.temperature_max:.2f} K)",
                w.temperature,
            )
        if w.takeoff_weight is None and w.landing_weight is None:
            yield f"{where}", "declares neither takeoff_weight nor landing_weight", None
    p = s.get("propulsion")
    if p is not None and p.flat_rating_temperature is None:
        yield (
            "propulsion.flat_rating_temperature",
            "needed with takeoff_landing_envelope: the thrust on a day other than "
            "ISA follows from it (the engine type certificate's flat rating ambient temperature)",
            None,
        )
