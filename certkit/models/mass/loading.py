"""Loading conditions: the payload and fuel distribution that reaches a (weight, CG) point.

§25.21(a) asks for compliance at each weight–CG combination, and the dynamics needs the inertia
of each one. For a target mass W and CG station x:

1. the operating empty airplane is the component table (or OEW at its CG);
2. fuel fills the tanks in the declared order (mains, then centre, as on twin-aisle transports);
3. payload fills the cabin and hold zones; its CG can move between "forward zones first" and
   "aft zones first" (each zone is a uniform line load between its ends).

Among the payload/fuel splits with zero-fuel mass ≤ MZFW and fuel ≤ capacity, the one with the
most payload whose required payload CG is reachable is taken, and the zone fill is solved for the
exact CG. A corner no split reaches (an envelope corner drawn for a fleet, whose empty airplanes
differ from the declared one, e.g. a light corner a few per cent of MAC from the declared OEW CG)
is built from the same items: the payload as ballast at a station inside the fuselage, or else
the split and fill nearest the corner with the empty airplane moved fore or aft as a whole
(another operating empty CG, at the empty airplane's own height); never a point at the datum.
Each loading names how it was built (:attr:`Loading.construction`). The inertia follows from the
parallel-axis theorem over every item
(:func:`certkit.models.mass.properties.combine`). When the file has no component table, the empty
airplane is a point mass at ``oew_cg`` and the whole-airplane inertia is scaled from the declared
tensor with constant radii of gyration (I ∝ m), which the result states in its notes.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np

from certkit.models.mass.properties import MassComponent, MassProperties, body_axis_tensor, combine, inertia_from_radii


class LoadingError(ValueError):
    """A (weight, CG) point that no payload and fuel distribution of the airplane can reach."""


@dataclass(frozen=True)
class Loading:
    """A solved loading condition."""

    name: str
    target_mass: float
    target_x_cg: float
    payload: float
    fuel: float
    payload_by_zone: dict[str, float]
    fuel_by_tank: dict[str, float]
    properties: MassProperties
    items: tuple[MassComponent, ...] = field(default=())
    notes: tuple[str, ...] = field(default=())
    construction: str = ""

    def table(self) -> list[dict]:
        """Component table for the report: mass, CG and share of the total mass of every item."""
        return [
            {
                "item": c.name,
                "mass_kg": round(c.mass, 1),
                "x_m": round(c.cg[0], 3),
                "y_m": round(c.cg[1], 3),
                "z_m": round(c.cg[2], 3),
                "share": f"{100 * c.mass / self.properties.mass:.1f} %",
            }
            for c in self.items
        ]


def reference_cg(aircraft) -> float:
    """The reference CG station (m): the CG envelope's ``reference_x``, else the reference moment point."""
    env = aircraft.cg_envelope
    if env is not None and env.reference_x is not None:
        return env.reference_x
    return aircraft.mass.cg.x if aircraft.mass.cg is not None else aircraft.reference.moment_point.x


def _item(name, mass, x, y=0.0, z=0.0, inertia=None):
    return MassComponent(name, float(mass), (float(x), float(y), float(z)), inertia)


def empty_airplane(aircraft) -> tuple[list[MassComponent], list[str]]:
    """The operating empty airplane as mass items, with a note when it is a single point mass."""
    m = aircraft.mass
    if m.components:
        items = []
        for c in m.components:
            inertia = None
            if c.inertia is not None:
                inertia = body_axis_tensor(c.inertia)
            items.append(_item(c.name, c.mass, c.cg.x, c.cg.y, c.cg.z, inertia))
        total = sum(c.mass for c in m.components)
        notes = []
        if m.OEW is not None and abs(total - m.OEW) > 0.005 * m.OEW:
            notes.append(
                f"component masses sum to {total:.0f} kg, not the declared OEW {m.OEW:.0f} kg; the components are used"
            )
        return items, notes
    if m.OEW is None:
        return [], ["no component table and no OEW: the airplane is flown as a whole (mass.MTOW, mass.inertia)"]
    if m.oew_cg is None:
        p = aircraft.reference.moment_point
        return [_item("operating empty airplane", m.OEW, p.x, 0.0, p.z)], [
            "no component table and no mass.oew_cg: the empty airplane is a point mass at the reference moment point "
            f"(x {p.x:.3f} m, height {p.z:.3f} m)"
        ]
    c = m.oew_cg
    return [_item("operating empty airplane", m.OEW, c.x, c.y, c.z)], [
        f"no component table: the empty airplane is a point mass at mass.oew_cg (x {c.x:.3f} m, height {c.z:.3f} m)"
    ]


def tank_groups(tanks) -> list[list]:
    """Tanks in filling order; mirror-image tanks (same x and z, opposite y) form one group and are
    filled together, so that fuel never moves the CG sideways."""
    groups: dict[tuple, list] = {}
    for t in tanks:
        key = (round(t.cg.x, 3), round(abs(t.cg.y), 3), round(t.cg.z, 3))
        groups.setdefault(key, []).append(t)
    return list(groups.values())


def _fill(groups, fuels) -> tuple[list, np.ndarray, np.ndarray]:
    """Each fuel mass of ``fuels`` (kg, an array) in the tank ``groups`` (:func:`tank_groups`) in declared order (each
    group filled before the next, its tanks in proportion to their capacity): the tanks, the kg in each (tanks,
    fuels), and whether a mass exceeds the tanks' capacity."""
    left = np.array(fuels, dtype=float)
    fuels = left.copy()
    tanks, shares = [], []
    for group in groups:
        capacity = sum(t.capacity for t in group)
        load = np.minimum(left, capacity)
        for t in group:
            tanks.append(t)
            shares.append(load * t.capacity / capacity)
        left = left - load
    return tanks, np.array(shares).reshape(len(tanks), fuels.size), left > 1e-6 * np.maximum(fuels, 1.0)


def _fuel_shares(groups, fuel: float) -> list[tuple[object, float]]:
    """(tank, kg) of ``fuel`` by :func:`_fill`; tanks left empty are omitted."""
    tanks, shares, overfull = _fill(groups, [fuel])
    _refuse_overfull([fuel], overfull)
    return [(t, share) for t, share in zip(tanks, shares[:, 0].tolist()) if share > 0]


def _refuse_overfull(fuels, overfull) -> None:
    """LoadingError naming the first of the fuel masses ``fuels`` (kg) that :func:`_fill` found beyond the tanks."""
    if np.any(overfull):
        raise LoadingError(f"{fuels[int(np.argmax(overfull))]:.0f} kg of fuel exceeds the tank capacity")


def _fuel_moments(groups, fuels: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For each fuel mass of ``fuels`` (kg), the moment Σ share·x of its :func:`_fuel_shares` (kg·m, the tanks summed in
    the same order, the empty ones left out) and whether it exceeds the tanks' capacity, at once for all the masses."""
    tanks, shares, overfull = _fill(groups, fuels)
    moment = np.zeros(overfull.shape)
    for t, share in zip(tanks, shares):
        moment = moment + np.where(share > 0, share * float(t.cg.x), 0.0)
    return moment, overfull


def fuel_by_tank(aircraft, fuel: float) -> np.ndarray:
    """kg of ``fuel`` in each declared tank (the file's order), the tanks filled group by group in the declared order
    (:func:`tank_groups`) and used in the reverse order. Raises LoadingError beyond the capacity."""
    tanks = aircraft.mass.fuel_tanks
    out = np.zeros(len(tanks))
    where = {id(t): k for k, t in enumerate(tanks)}
    for t, share in _fuel_shares(tank_groups(tanks), fuel):
        out[where[id(t)]] = share
    return out


def _fuel_items(aircraft, fuel: float, groups=None) -> list[MassComponent]:
    """The fuel of :func:`_fuel_shares` as a point mass per tank."""
    groups = tank_groups(aircraft.mass.fuel_tanks) if groups is None else groups
    return [_item(f"fuel: {t.name}", share, t.cg.x, t.cg.y, t.cg.z) for t, share in _fuel_shares(groups, fuel)]


@dataclass(frozen=True)
class _Bay:
    name: str
    capacity: float
    x_start: float
    x_end: float


def bays(zones, per_zone: int = 10) -> list[_Bay]:
    """Each payload zone split into ``per_zone`` equal bays, so that a fill order can load forward or aft."""
    return list(_bays(tuple((z.name, z.capacity, z.x_start, z.x_end) for z in zones), per_zone))


@lru_cache(maxsize=64)
def _bays(zones: tuple, per_zone: int) -> tuple[_Bay, ...]:
    """:func:`bays` of zones given as (name, capacity, x_start, x_end), remembered (every loading of every design
    splits the same declared zones)."""
    out = []
    for name, capacity, x_start, x_end in zones:
        edges = np.linspace(x_start, x_end, per_zone + 1)
        out += [_Bay(name, capacity / per_zone, a, b) for a, b in zip(edges[:-1], edges[1:])]
    return tuple(out)


def _payload_fill(zones, payload: float, forward_first: bool) -> list[tuple[object, float]]:
    order = sorted(zones, key=lambda z: 0.5 * (z.x_start + z.x_end), reverse=not forward_first)
    out, left = [], payload
    for z in order:
        load = min(left, z.capacity)
        out.append((z, load))
        left -= load
    if left > 1e-6 * max(payload, 1.0):
        raise LoadingError(f"{payload:.0f} kg of payload exceeds the zone capacity")
    return out


def _moment(fill) -> float:
    return sum(load * 0.5 * (z.x_start + z.x_end) for z, load in fill)


def _payload_cg_ranges(zones, payloads: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The payload CG of the forward-first and aft-first fills (:func:`_payload_fill`) of each payload (kg), at once
    from the cumulative capacities and moments of the bays in each order; ±inf for no payload."""
    centres = np.array([0.5 * (z.x_start + z.x_end) for z in zones])
    caps = np.array([z.capacity for z in zones])
    payloads = np.asarray(payloads, dtype=float)
    out = []
    for order in (np.argsort(centres, kind="stable"), np.argsort(-centres, kind="stable")):
        c, x = caps[order], centres[order]
        C = np.concatenate([[0.0], np.cumsum(c)])
        M = np.concatenate([[0.0], np.cumsum(c * x)])
        k = np.clip(np.searchsorted(C, payloads, side="right") - 1, 0, len(c) - 1)  # bays filled before the last
        moment = M[k] + np.clip(payloads - C[k], 0.0, c[k]) * x[k]
        with np.errstate(divide="ignore", invalid="ignore"):
            out.append(np.where(payloads > 0, moment / np.where(payloads > 0, payloads, 1.0), np.nan))
    lo, hi = out
    return np.where(payloads > 0, lo, -np.inf), np.where(payloads > 0, hi, np.inf)


def _payload_items(zones, payload: float, x_target: float) -> list[MassComponent]:
    """Blend the forward-first and aft-first fills to put the payload CG at ``x_target`` exactly."""
    fwd, aft = _payload_fill(zones, payload, True), _payload_fill(zones, payload, False)
    x_f, x_a = _moment(fwd) / payload, _moment(aft) / payload
    s = 0.0 if x_a == x_f else float(np.clip((x_target - x_f) / (x_a - x_f), 0.0, 1.0))
    loads: dict[int, float] = {}
    for weight, fill in ((1 - s, fwd), (s, aft)):
        for z, load in fill:
            loads[id(z)] = loads.get(id(z), 0.0) + weight * load
    by_zone: dict[str, list] = {}
    for z in zones:
        if loads.get(id(z), 0.0) > 0:
            by_zone.setdefault(z.name, []).append((z, loads[id(z)]))
    items = []
    for name, parts in by_zone.items():
        # each loaded bay is a uniform line load: its own pitch/yaw inertia is m L²/12
        mass = sum(load for _, load in parts)
        x = sum(load * 0.5 * (z.x_start + z.x_end) for z, load in parts) / mass
        own = sum(
            load * ((z.x_end - z.x_start) ** 2 / 12 + (0.5 * (z.x_start + z.x_end) - x) ** 2) for z, load in parts
        )
        items.append(_item(f"payload: {name}", mass, x, inertia=np.diag([1e-9 * mass, own, own])))
    return items


def solve_loading(aircraft, mass: float, x_cg: float, name: str = "", samples: int = 201) -> Loading:
    """The payload/fuel distribution reaching ``mass`` (kg) at CG station ``x_cg`` (m), with its inertia."""
    m = aircraft.mass
    if not (m.components or m.fuel_tanks or m.payload_zones):
        return _scaled_loading(
            aircraft,
            mass,
            x_cg,
            name,
            [
                "no components, tanks or payload zones: whole-airplane mass at the CG, inertia scaled from the "
                "declared "
                "tensor (at MTOW) at constant radii of gyration"
            ],
        )
    empty, notes = empty_airplane(aircraft)
    oew = sum(c.mass for c in empty)
    oew_moment = sum(c.mass * c.cg[0] for c in empty)
    if mass < oew * (1 - 1e-9):
        return _scaled_loading(
            aircraft,
            mass,
            x_cg,
            name,
            notes
            + [
                f"{mass:.0f} kg is below the operating empty mass {oew:.0f} kg: inertia scaled from the declared tensor"
            ],
        )
    if not (m.fuel_tanks and m.payload_zones):
        return _fallback_loading(
            aircraft, mass, x_cg, name, empty, notes + ["no fuel tanks or payload zones declared"], 0.0
        )
    zones = bays(m.payload_zones)
    fuel_cap = sum(t.capacity for t in m.fuel_tanks)
    zone_cap = sum(z.capacity for z in zones)
    useful = mass - oew
    p_max = min(useful, m.MZFW - oew, zone_cap, m.max_payload if m.max_payload else np.inf)
    p_min = max(0.0, useful - fuel_cap)
    if p_max < p_min - 1e-9:
        raise LoadingError(
            f"{mass:.0f} kg cannot be reached: needs more fuel than the tanks hold with payload ≤ {p_max:.0f} kg"
        )
    best, nearest = None, None
    payloads = np.linspace(p_max, p_min, samples)
    lo, hi = _payload_cg_ranges(zones, payloads)
    groups = tank_groups(m.fuel_tanks)
    fuels = useful - payloads
    fuel_moment, overfull = _fuel_moments(groups, fuels)
    rest = mass * x_cg - oew_moment - fuel_moment  # the moment the payload must supply, per split
    empty_payload = payloads <= 1e-9
    with np.errstate(divide="ignore", invalid="ignore"):
        x_needed = rest / np.where(empty_payload, 1.0, payloads)
    reached = np.where(
        empty_payload, np.abs(rest) <= 1e-6 * mass * max(x_cg, 1.0), (lo - 1e-9 <= x_needed) & (x_needed <= hi + 1e-9)
    )
    first = int(np.argmax(reached)) if reached.any() else samples
    # the splits are tried in order: one that cannot be fuelled before the first that reaches the CG stops them
    _refuse_overfull(fuels, overfull[: first + 1])
    if first < samples:
        payload = float(payloads[first])
        best = (
            float(fuels[first]),
            [] if empty_payload[first] else _payload_items(zones, payload, float(x_needed[first])),
        )
    else:  # the split nearest the corner: the smallest moment missed (the empty airplane would have to supply it)
        x_reached = np.clip(x_needed, lo, hi)
        misses = np.where(empty_payload, rest, payloads * (x_needed - x_reached)).tolist()
        for k, miss in enumerate(misses):
            if nearest is None or abs(miss) < abs(nearest[0]) - 1e-9:
                payload = float(payloads[k])
                nearest = (miss, payload, float(fuels[k]), None if empty_payload[k] else float(x_reached[k]))
    if best is None:
        return _fallback_loading(
            aircraft,
            mass,
            x_cg,
            name,
            empty,
            notes,
            useful - p_max,
            nearest=None if nearest is None else (nearest, zones, groups),
        )
    fuel, payload_items = best
    return _assemble(aircraft, name, mass, x_cg, empty, _fuel_items(aircraft, fuel, groups), payload_items, notes)


def _assemble(aircraft, name, mass, x_cg, empty, fuel_items, payload_items, notes, construction="") -> Loading:
    items = empty + fuel_items + payload_items
    props = _whole_airplane_if_declared(aircraft, items)
    payload = {c.name.removeprefix("payload: "): c.mass for c in payload_items}
    fuel = {c.name.removeprefix("fuel: "): c.mass for c in fuel_items}
    if not construction:
        construction = (
            f"declared items: empty airplane {_empty_kind(empty)}, {sum(fuel.values()):.0f} kg fuel in its "
            f"tanks, {sum(payload.values()):.0f} kg payload in its zones"
        )
    return Loading(
        name,
        mass,
        x_cg,
        sum(payload.values()),
        sum(fuel.values()),
        payload,
        fuel,
        props,
        tuple(items),
        tuple(notes),
        construction,
    )


def _empty_kind(empty) -> str:
    return f"({len(empty)} components)" if len(empty) > 1 else "(one item)"


def _fallback_loading(aircraft, mass, x_cg, name, empty, notes, fuel, nearest=None) -> Loading:
    """A corner no declared distribution reaches (envelope limits are drawn for a fleet and need not be reachable
    with the declared empty airplane). First: the fuel in its tanks and the payload as ballast at the station giving
    the CG, inside the fuselage (keeps the wing-fuel roll inertia). Else (:func:`_moved_empty_loading`): the nearest
    split and fill, with the empty airplane moved as a whole to reach the CG."""
    oew_moment = sum(c.mass * c.cg[0] for c in empty)
    oew = sum(c.mass for c in empty)
    fuel_items = _fuel_items(aircraft, fuel) if aircraft.mass.fuel_tanks and fuel > 0 else []
    ballast = mass - oew - sum(c.mass for c in fuel_items)
    length = aircraft.geometry.fuselage.length if aircraft.geometry else np.inf
    if ballast > 1e-6 * mass:
        x = (mass * x_cg - oew_moment - sum(c.mass * c.cg[0] for c in fuel_items)) / ballast
        if 0.0 <= x <= length:
            note = (
                f"no distribution of the declared fuel and payload reaches {mass:.0f} kg at CG {x_cg:.3f} m: "
                f"fuel in its tanks and {ballast:.0f} kg of payload as ballast at station {x:.2f} m"
            )
            built = (
                f"declared items with ballast: empty airplane {_empty_kind(empty)}, "
                f"{sum(c.mass for c in fuel_items):.0f} kg fuel in its tanks, {ballast:.0f} kg payload at station "
                f"{x:.2f} m"
            )
            return _assemble(
                aircraft,
                name,
                mass,
                x_cg,
                empty,
                fuel_items,
                [_item("payload: ballast", ballast, x)],
                notes + [note],
                built,
            )
    return _moved_empty_loading(aircraft, mass, x_cg, name, empty, notes, nearest, fuel_items)


def _moved_empty_loading(aircraft, mass, x_cg, name, empty, notes, nearest, fuel_items) -> Loading:
    """The corner built from the declared items with the empty airplane moved fore or aft as a whole: the fuel in its
    tanks and the payload in its zones of the split nearest the corner (``nearest`` from :func:`solve_loading`:
    (moment missed, payload, fuel, payload CG), zones, tank groups), and every empty-airplane item shifted by the
    distance that brings the CG to the corner. The CG height and the inertia about the CG are those of real items
    (the inertia follows ``mass.inertia_used`` as for any loading); only the empty CG station differs from the
    declared one, as an operator's empty airplane does."""
    payload_items = []
    if nearest is not None:
        (_, payload, fuel, x_payload), zones, groups = nearest
        fuel_items = _fuel_items(aircraft, fuel, groups) if fuel > 0 else []
        payload_items = _payload_items(zones, payload, x_payload) if payload > 1e-9 else []
    oew = sum(c.mass for c in empty)
    moment = sum(c.mass * c.cg[0] for c in empty + fuel_items + payload_items)
    shift = (mass * x_cg - moment) / oew
    moved = [MassComponent(c.name, c.mass, (c.cg[0] + shift, c.cg[1], c.cg[2]), c.inertia) for c in empty]
    x_empty = sum(c.mass * c.cg[0] for c in moved) / oew
    z_empty = sum(c.mass * c.cg[2] for c in moved) / oew
    direction = "aft" if shift > 0 else "forward"
    built = (
        f"declared items, empty airplane moved {abs(shift):.2f} m {direction} (empty CG station {x_empty:.2f} m, "
        f"height {z_empty:.2f} m): {sum(c.mass for c in fuel_items):.0f} kg fuel in its tanks, "
        f"{sum(c.mass for c in payload_items):.0f} kg payload in its zones"
    )
    note = (
        f"no distribution of the declared fuel and payload reaches {mass:.0f} kg at CG {x_cg:.3f} m with the "
        f"declared empty airplane: it is moved {abs(shift):.2f} m {direction} as a whole (another operating empty CG)"
    )
    return _assemble(aircraft, name, mass, x_cg, moved, fuel_items, payload_items, notes + [note], built)


def _scaled_loading(aircraft, mass, x_cg, name, notes) -> Loading:
    z = aircraft.mass.cg.z if aircraft.mass.cg is not None else 0.0  # the declared whole-airplane CG height
    props = MassProperties(float(mass), np.array([x_cg, 0.0, z]), whole_airplane_inertia(aircraft, mass))
    return Loading(
        name,
        mass,
        x_cg,
        0.0,
        0.0,
        {},
        {},
        props,
        (),
        tuple(notes),
        f"whole airplane: one mass at the CG, height {z:.2f} m (mass.cg.z), declared inertia scaled with mass",
    )


def _declared_inertia(aircraft) -> np.ndarray | None:
    t = aircraft.mass.inertia
    return None if t is None else body_axis_tensor(t)


def _whole_airplane_if_declared(aircraft, items) -> MassProperties:
    """Mass, CG and inertia of the items: the parallel-axis build-up when the file has a component table and uses it
    (``mass.inertia_used: components``); else the declared whole-airplane tensor scaled with mass (with no component
    table the parallel-axis inertia of point masses is meaningless, and is not formed)."""
    m = aircraft.mass
    if m.components and not (m.inertia is not None and m.inertia_used == "declared"):
        return combine(items)
    total = sum(c.mass for c in items)
    cg = sum(c.mass * np.asarray(c.cg, dtype=float) for c in items) / total
    return MassProperties(float(total), cg, whole_airplane_inertia(aircraft, total))


def whole_airplane_inertia(aircraft, mass: float) -> np.ndarray:
    """The declared whole-airplane tensor (at MTOW) scaled by mass at constant radii of gyration, or,
    without one, Roskam radii of gyration (needs span and fuselage length)."""
    declared = _declared_inertia(aircraft)
    if declared is not None:
        return declared * mass / aircraft.mass.MTOW
    g = aircraft.geometry
    if g is None:
        raise LoadingError("no inertia: declare mass.inertia, mass.components or the geometry (span, fuselage length)")
    return inertia_from_radii(mass, np.sqrt(g.wing.aspect_ratio * g.wing.area), g.fuselage.length)


def inertia_comparison(aircraft) -> str | None:
    """With both a component table and a declared whole-airplane inertia: the two at MTOW (the component build-up of
    the MTOW loading at the reference CG, parallel-axis theorem, against the declared tensor) when a moment of
    inertia differs by more than ``mass.inertia_tolerance``, naming both values and the one the dynamics uses;
    None when they agree or only one exists."""
    m = aircraft.mass
    if not m.components or m.inertia is None:
        return None
    try:
        loading = solve_loading(aircraft, m.MTOW, reference_cg(aircraft), "MTOW")
        built = combine(loading.items) if loading.items else None
    except (LoadingError, ValueError) as exc:
        return f"the declared mass.inertia could not be compared with the component build-up at MTOW: {exc}"
    if built is None:
        return None
    declared = whole_airplane_inertia(aircraft, m.MTOW)
    off = []
    for k, name in enumerate(("Ixx", "Iyy", "Izz")):
        b, d = float(built.inertia[k, k]), float(declared[k, k])
        if abs(b - d) > m.inertia_tolerance * abs(d):
            off.append(f"{name} {b:.4g} kg·m² from the components vs {d:.4g} kg·m² declared ({(b - d) / d:+.0%})")
    if not off:
        return None
    used = (
        "the declared tensor (mass.inertia_used: declared)"
        if m.inertia_used == "declared"
        else "the component build-up (mass.inertia_used: components; set 'declared' to use the declared tensor)"
    )
    return (
        f"declared inertia and component build-up disagree beyond {m.inertia_tolerance:.0%} at MTOW: "
        f"{'; '.join(off)}. The dynamics uses {used}"
    )


def reachable_cg_range(aircraft, mass: float, samples: int = 201) -> tuple[float, float] | None:
    """The most forward and most aft CG stations (m) the airplane's own loading reaches at ``mass`` (kg): the
    operating empty airplane (its components), fuel in the declared tank order and payload filled forward-first or
    aft-first (:func:`_payload_cg_ranges`), over every payload/fuel split with zero-fuel mass ≤ MZFW, fuel ≤ the tanks'
    capacity and payload ≤ the zones' capacity and the maximum payload. None when the file declares no tanks or zones,
    or no split reaches ``mass``."""
    m = aircraft.mass
    if not (m.fuel_tanks and m.payload_zones):
        return None
    empty, _ = empty_airplane(aircraft)
    oew = sum(c.mass for c in empty)
    oew_moment = sum(c.mass * c.cg[0] for c in empty)
    zones = bays(m.payload_zones)
    useful = mass - oew
    p_max = min(useful, m.MZFW - oew, sum(z.capacity for z in zones), m.max_payload if m.max_payload else np.inf)
    p_min = max(0.0, useful - sum(t.capacity for t in m.fuel_tanks))
    if useful < 0 or p_max < p_min - 1e-9:
        return None
    payloads = np.linspace(p_max, max(p_min, 0.0), samples)
    fwd, aft = _payload_cg_ranges(zones, payloads)
    groups = tank_groups(m.fuel_tanks)
    fuels = useful - payloads
    fuel_moment, overfull = _fuel_moments(groups, fuels)
    _refuse_overfull(fuels, overfull)
    base = oew_moment + fuel_moment
    with np.errstate(invalid="ignore"):
        x_fwd = (base + np.where(payloads > 0, payloads * fwd, 0.0)) / mass
        x_aft = (base + np.where(payloads > 0, payloads * aft, 0.0)) / mass
    return float(np.nanmin(x_fwd)), float(np.nanmax(x_aft))
