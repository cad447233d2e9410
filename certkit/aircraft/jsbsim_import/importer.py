"""``certkit import jsbsim AIRCRAFT.xml``: a certkit aircraft file from a JSBSim flight-dynamics model.

What is mapped (JSBSim's structural frame — X aft, Y right, Z up, inches — is certkit's airplane frame):

* ``metrics`` → ``reference`` (wing area, span, chord; the AERORP as the moment point).
* ``mass_balance`` (empty weight, CG, inertia), ``pointmass`` items and the fuel tanks' contents → the whole
  airplane as JSBSim loads it: ``mass.MTOW`` (the mass flown), ``mass.cg`` and ``mass.inertia`` about that CG, as
  JSBSim forms it: the empty tensor plus every item (the empty airplane included) as a point mass about the total
  CG. With ``negated_crossproduct_inertia="true"`` (JSBSim's default) the file's products are the tensor's
  elements (J_xz = −∫xz dm), so certkit's Ixz is −ixz; with "false" they are the products themselves.
* ``propulsion``: each engine's thruster location and orientation → ``propulsion.engines``; a turbine engine's
  IdleThrust and MilThrust tables (Mach × density altitude) → ``propulsion.deck`` with JSBSim's steady-state law
  thrust = (idle + (mil − idle) · MilThrust(M, h) · throttle²) (1 − bleed), idle = mil · IdleThrust(M, h)
  (JSBSim Reference Manual, turbine engine; N2 at its steady value for the throttle).
* ``aerodynamics``: every coefficient function of the six axes is evaluated (:mod:`.functions`) and
  differentiated numerically (central differences) at the reference state — level flight at the given Mach and
  altitude, α and δe from lift = weight and Cm = 0 — at each Mach breakpoint of its Mach tables below Mach 1:
  the certkit derivative table (stability axes: JSBSim's body-axis rolling and yawing moments and their rate
  derivatives are turned through α_ref). ``aero/cl-squared`` terms become the polar's ``k``; ``|δe|`` terms the
  elevator drag with the sign of the reference δe. JSBSim's aileron (left surface, trailing edge down positive) is
  certkit's with the opposite sign; elevator and rudder have certkit's signs.

Everything else is listed in the report (configuration increments, sideslip tables, ground effect, the flight
control system, ground reactions, other engine types) with the reason it was not mapped.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import yaml

from certkit import atmosphere as isa
from certkit.aircraft.jsbsim_import.functions import Unsupported, evaluate, properties_used, table_arrays
from certkit.errors import UserError
from certkit.units import FT, G0, LB, LBF

IN = 0.0254
SLUG_FT2 = LB * G0 / FT * FT * FT  # kg m² per slug ft²
_LENGTH = {"IN": IN, "FT": FT, "M": 1.0, "CM": 0.01, "MM": 0.001}
_AREA = {"FT2": FT * FT, "M2": 1.0, "IN2": IN * IN}
_MASS = {"LBS": LB, "KG": 1.0, "SLUG": LB * G0 / FT}
_INERTIA = {"SLUG*FT2": SLUG_FT2, "KG*M2": 1.0}
EARTH_RADIUS = 6_356_766.0  # m, the geopotential radius of the 1976 standard atmosphere

#: the motion variables the importer sets (everything an aerodynamic function may read at the reference state)
_STEP = 1e-5


@dataclass
class ImportResult:
    data: dict
    unmapped: list[str] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    reference_alpha: float = 0.0
    reference_elevator: float = 0.0


def _fail(path, what: str, element=None) -> UserError:
    return UserError(f"{path}: {what}")


def _number(el, path, what: str) -> float:
    if el is None or el.text is None:
        raise _fail(path, f"{what} is missing")
    try:
        value = float(el.text)
    except ValueError:
        raise _fail(path, f"{what}: {el.text.strip()!r} is not a number") from None
    if not math.isfinite(value):
        raise _fail(path, f"{what}: {el.text.strip()!r} is not finite")
    return value


def _quantity(el, path, what: str, units: dict, default: str) -> float:
    value = _number(el, path, what)
    unit = (el.get("unit") or default).upper()
    if unit not in units:
        raise _fail(path, f"{what}: unit {unit!r} not understood (expected one of {', '.join(units)})")
    return value * units[unit]


def _location(el, path, what: str) -> np.ndarray:
    if el is None:
        raise _fail(path, f"{what} is missing")
    unit = (el.get("unit") or "IN").upper()
    if unit not in _LENGTH:
        raise _fail(path, f"{what}: unit {unit!r} not understood")
    return (
        np.array([_number(el.find(a), path, f"{what}/{a}") if el.find(a) is not None else 0.0 for a in ("x", "y", "z")])
        * _LENGTH[unit]
    )


def read_xml(path: str | Path) -> ET.Element:
    p = Path(path)
    if not p.is_file():
        raise UserError(f"{path}: no such JSBSim aircraft file")
    try:
        root = ET.parse(p).getroot()
    except ET.ParseError as exc:
        line, col = exc.position
        raise UserError(f"{path}:{line}:{col}: not well-formed XML ({exc})") from None
    if root.tag != "fdm_config":
        raise UserError(f"{path}: the root element is <{root.tag}>, expected <fdm_config> (a JSBSim aircraft file)")
    return root


# --- mass --------------------------------------------------------------------------------------------------------


def _point_tensor(mass: float, d_body: np.ndarray) -> np.ndarray:
    return mass * (float(d_body @ d_body) * np.eye(3) - np.outer(d_body, d_body))


def mass_properties(root, path, unmapped: list[str]) -> tuple[float, np.ndarray, np.ndarray, list[str]]:
    """(mass kg, CG airplane frame m, inertia tensor J body axes about the CG, notes) as JSBSim loads the FDM."""
    mb = root.find("mass_balance")
    if mb is None:
        raise _fail(path, "<mass_balance> is missing")
    empty = _quantity(mb.find("emptywt"), path, "mass_balance/emptywt", _MASS, "LBS")
    cg_el = next((loc for loc in mb.findall("location") if loc.get("name") == "CG"), None)
    items = [("empty airplane", empty, _location(cg_el, path, "mass_balance/location CG"))]
    for pm in mb.findall("pointmass"):
        items.append(
            (
                f"point mass {pm.get('name', '')}".strip(),
                _quantity(pm.find("weight"), path, "pointmass/weight", _MASS, "LBS"),
                _location(pm.find("location"), path, "pointmass/location"),
            )
        )
    prop = root.find("propulsion")
    for i, tank in enumerate(prop.findall("tank") if prop is not None else []):
        contents = tank.find("contents")
        if contents is not None:
            m = _quantity(contents, path, f"tank {i} contents", _MASS, "LBS")
            if m > 0:
                items.append(
                    (
                        f"tank {i} ({tank.get('type', 'FUEL').lower()})",
                        m,
                        _location(tank.find("location"), path, f"tank {i} location"),
                    )
                )
        if tank.find("radius") is not None:
            unmapped.append(f"tank {i}: its radius (own inertia of the fuel) is not modelled; the fuel is a point mass")
    total = sum(m for _, m, _ in items)
    cg = sum(m * x for _, m, x in items) / total
    get = lambda tag: (  # noqa: E731
        _quantity(mb.find(tag), path, f"mass_balance/{tag}", _INERTIA, "SLUG*FT2") if mb.find(tag) is not None else 0.0
    )
    ixx, iyy, izz, ixy, ixz, iyz = (get(t) for t in ("ixx", "iyy", "izz", "ixy", "ixz", "iyz"))
    if mb.get("negated_crossproduct_inertia", "true").lower() == "false":  # the products ∫xy dm … themselves
        J = np.array([[ixx, -ixy, -ixz], [-ixy, iyy, -iyz], [-ixz, -iyz, izz]])
    else:  # JSBSim's default: the tensor's elements, given in the structural frame (xy, yz change sign in body axes)
        J = np.array([[ixx, -ixy, ixz], [-ixy, iyy, -iyz], [ixz, -iyz, izz]]) * np.array(
            [[1, -1, 1], [-1, 1, -1], [1, -1, 1]]
        )
    for _, m, x in items:
        d = (x - cg) * np.array([-1.0, 1.0, -1.0])  # airplane frame → body axes (x forward, z down)
        J = J + _point_tensor(m, d)
    notes = [f"mass {total:.0f} kg = " + " + ".join(f"{name} {m:.0f}" for name, m, _ in items)]
    return total, cg, J, notes


# --- propulsion --------------------------------------------------------------------------------------------------


def _engine_file(path: Path, name: str) -> Path | None:
    here = path.parent
    for candidate in (
        here / "Engines" / f"{name}.xml",
        here / "engine" / f"{name}.xml",
        here / f"{name}.xml",
        here.parent.parent / "engine" / f"{name}.xml",
    ):
        if candidate.is_file():
            return candidate
    return None


def _turbine_deck(engine_path: Path, unmapped: list[str]) -> tuple[dict, float, float] | None:
    """(deck dict, military thrust N, bypass ratio) of a JSBSim turbine engine file, None if not a turbine."""
    root = ET.parse(engine_path).getroot()
    if root.tag != "turbine_engine":
        unmapped.append(
            f"engine {engine_path.name}: <{root.tag}> is not a turbine engine; not mapped (certkit's "
            "ideal thrust is used)"
        )
        return None
    mil = _quantity(root.find("milthrust"), engine_path, "milthrust", {"LBS": LBF, "N": 1.0}, "LBS")
    bleed = float(root.findtext("bleed", "0") or 0)
    bypass = float(root.findtext("bypassratio", "5") or 5)
    tables = {}
    for fn in root.findall("function"):
        if fn.get("name") in ("IdleThrust", "MilThrust"):
            tables[fn.get("name")] = table_arrays(fn.find("table"))
    if set(tables) != {"IdleThrust", "MilThrust"}:
        unmapped.append(f"engine {engine_path.name}: no IdleThrust/MilThrust tables; not mapped")
        return None
    if root.findtext("augmented", "0").strip() == "1":
        unmapped.append(f"engine {engine_path.name}: afterburner (augmentation) not mapped; dry thrust only")
    (_, mi, ai, idle), (_, mm, am, milt) = tables["IdleThrust"], tables["MilThrust"]
    machs = np.array(sorted({m for m in np.concatenate([mi, mm]) if m <= min(mi.max(), mm.max())}))
    alts_ft = np.array(sorted({a for a in np.concatenate([ai, am]) if a <= min(ai.max(), am.max())}))

    def bilinear(rows, cols, data, m, a):
        along = np.array([np.interp(m, rows, data[:, j]) for j in range(data.shape[1])])
        return float(np.interp(a, cols, along))

    throttles = np.linspace(0.0, 1.0, 21)
    thrust = []
    for a in alts_ft:
        per_mach = []
        for m in machs:
            idle_thrust = mil * bilinear(mi, ai, idle, m, a)
            gain = (mil - idle_thrust) * bilinear(mm, am, milt, m, a)
            per_mach.append([(idle_thrust + gain * t * t) * (1.0 - bleed) for t in throttles])
        thrust.append(per_mach)
    deck = {
        "altitude": [float(a * FT) for a in alts_ft],
        "mach": [float(m) for m in machs],
        "throttle": [float(t) for t in throttles],
        "thrust": thrust,
        "source": f"JSBSim turbine engine {engine_path.name}: (idle + (mil − idle) MilThrust(M, h) throttle²)"
        f"(1 − bleed {bleed:g}), density altitude read as ISA altitude",
    }
    return deck, mil, bypass


def propulsion(root, path: Path, unmapped: list[str]) -> dict | None:
    prop = root.find("propulsion")
    if prop is None or not prop.findall("engine"):
        unmapped.append("no engines: certkit's ideal thrust is used")
        return None
    engines, decks = [], []
    for k, e in enumerate(prop.findall("engine")):
        thruster = e.find("thruster")
        if thruster is None:
            raise _fail(path, f"engine {k}: <thruster> is missing")
        loc = _location(thruster.find("location"), path, f"engine {k} thruster location")
        orient = thruster.find("orient")
        pitch = yaw = 0.0
        if orient is not None:
            unit = math.pi / 180 if (orient.get("unit") or "RAD").upper() == "DEG" else 1.0
            pitch = float(orient.findtext("pitch", "0")) * unit
            yaw = float(orient.findtext("yaw", "0")) * unit
        engines.append(
            {
                "name": f"engine {k + 1}",
                "position": {"x": float(loc[0]), "y": float(loc[1]), "z": float(loc[2])},
                "thrust_angle": pitch,
                "toe_angle": yaw,
            }
        )
        file = _engine_file(path, e.get("file", ""))
        if file is None:
            unmapped.append(
                f"engine {k + 1}: engine file {e.get('file')!r} not found next to the aircraft or in "
                "the JSBSim engine folder"
            )
            decks.append(None)
            continue
        if thruster.get("file", "direct") != "direct":
            unmapped.append(f"engine {k + 1}: thruster {thruster.get('file')!r} (propeller or nozzle) not mapped")
        decks.append(_turbine_deck(file, unmapped))
    if any(d is None for d in decks):
        unmapped.append("propulsion: not every engine could be read; certkit's ideal thrust is used instead")
        return None
    if len({(d[1], d[2]) for d in decks}) != 1:
        unmapped.append("engines of different types: not mapped (one deck for all); certkit's ideal thrust is used")
        return None
    deck, mil, bypass = decks[0]
    return {"engines": engines, "static_thrust": mil, "bypass_ratio": bypass, "deck": deck}


# --- aerodynamics ------------------------------------------------------------------------------------------------

_KNOWN = {
    "aero/qbar-psf",
    "metrics/Sw-sqft",
    "metrics/bw-ft",
    "metrics/cbarw-ft",
    "velocities/mach",
    "aero/alpha-rad",
    "aero/beta-rad",
    "aero/bi2vel",
    "aero/ci2vel",
    "velocities/p-aero-rad_sec",
    "velocities/q-aero-rad_sec",
    "velocities/r-aero-rad_sec",
    "aero/alphadot-rad_sec",
    "fcs/elevator-pos-rad",
    "fcs/left-aileron-pos-rad",
    "fcs/right-aileron-pos-rad",
    "fcs/rudder-pos-rad",
    "fcs/mag-elevator-pos-rad",
    "aero/cl-squared",
    "aero/h_b-mac-ft",
    "aero/h_b-cg-ft",
    "aero/alpha-deg",
    "aero/beta-deg",
    "aero/mag-beta-rad",
}
#: configuration properties held at zero (retracted) in the imported clean table
_CONFIG = {
    "fcs/flap-pos-deg": "flaps",
    "fcs/flap-pos-norm": "flaps",
    "gear/gear-pos-norm": "landing gear",
    "fcs/speedbrake-pos-norm": "speedbrake",
    "fcs/spoiler-pos-norm": "spoilers",
}
_NORMALISE = {"DRAG": "S", "SIDE": "S", "LIFT": "S", "ROLL": "b", "PITCH": "c", "YAW": "b"}


@dataclass
class _Aero:
    helpers: list
    axes: dict  # axis → list of function elements
    S: float
    b: float
    c: float

    def props(self, state: dict, V: float) -> dict:
        """JSBSim property values (JSBSim units: ft, psf, rad) at a state of certkit variables."""
        q = 0.5  # psf; every coefficient is normalised by it
        alpha, beta = state["alpha"], state["beta"]
        b_ft, c_ft = self.b / FT, self.c / FT
        V_fps = V / FT
        p = {
            "aero/qbar-psf": q,
            "metrics/Sw-sqft": self.S / (FT * FT),
            "metrics/bw-ft": b_ft,
            "metrics/cbarw-ft": c_ft,
            "velocities/mach": state["mach"],
            "aero/alpha-rad": alpha,
            "aero/alpha-deg": math.degrees(alpha),
            "aero/beta-rad": beta,
            "aero/beta-deg": math.degrees(beta),
            "aero/mag-beta-rad": abs(beta),
            "aero/bi2vel": b_ft / (2 * V_fps),
            "aero/ci2vel": c_ft / (2 * V_fps),
            "velocities/p-aero-rad_sec": state["p"] * 2 * V_fps / b_ft,
            "velocities/q-aero-rad_sec": state["q"] * 2 * V_fps / c_ft,
            "velocities/r-aero-rad_sec": state["r"] * 2 * V_fps / b_ft,
            "aero/alphadot-rad_sec": state["alphadot"] * 2 * V_fps / c_ft,
            "fcs/elevator-pos-rad": state["elevator"],
            "fcs/mag-elevator-pos-rad": abs(state["elevator"]),
            "fcs/left-aileron-pos-rad": -state["aileron"],
            "fcs/right-aileron-pos-rad": state["aileron"],
            "fcs/rudder-pos-rad": state["rudder"],
            "aero/cl-squared": state.get("cl2", 0.0),
            "aero/h_b-mac-ft": 1e3,
            "aero/h_b-cg-ft": 1e3,
        }
        p.update({k: 0.0 for k in _CONFIG})
        for h in self.helpers:
            p[h.get("name")] = evaluate(h, p)
        return p

    def coefficients(self, state: dict, V: float, skip=()) -> dict:
        p = self.props(state, V)
        qS = p["aero/qbar-psf"] * p["metrics/Sw-sqft"]
        length = {"S": 1.0, "b": p["metrics/bw-ft"], "c": p["metrics/cbarw-ft"]}
        out = {}
        for axis, functions in self.axes.items():
            total = sum(evaluate(f, p) for f in functions if f.get("name") not in skip)
            out[axis] = total / (qS * length[_NORMALISE[axis]])
        return out


def _aero_model(root, path, S, b, c, unmapped) -> tuple[_Aero, list]:
    aero = root.find("aerodynamics")
    if aero is None:
        raise _fail(path, "<aerodynamics> is missing")
    helpers = [f for f in aero.findall("function")]
    axes: dict = {}
    induced = []
    for ax in aero.findall("axis"):
        name = (ax.get("name") or "").upper()
        if name not in _NORMALISE:
            unmapped.append(f"aerodynamic axis {name!r} (certkit reads DRAG, SIDE, LIFT, ROLL, PITCH, YAW): not mapped")
            continue
        for fn in ax.findall("function"):
            used = properties_used(fn) - {h.get("name") for h in helpers}
            unknown = used - _KNOWN - set(_CONFIG)
            short = fn.get("name", "?").split("/")[-1]
            if unknown:
                unmapped.append(
                    f"{name} {short}: reads {', '.join(sorted(unknown))}, which the importer does not model: not mapped"
                )
                continue
            config = used & set(_CONFIG)
            if config:
                unmapped.append(
                    f"{name} {short}: {', '.join(sorted({_CONFIG[c] for c in config}))} increment; the "
                    "imported table is the clean airplane (flaps, gear, speedbrake, spoilers retracted)"
                )
                continue
            if "aero/cl-squared" in used:
                induced.append(fn)
            if (
                any(
                    v.text.strip() in ("aero/beta-rad", "aero/mag-beta-rad")
                    for t in fn.iter("table")
                    for v in t.findall("independentVar")
                )
                or "aero/mag-beta-rad" in used
            ):
                unmapped.append(f"{name} {short}: tabulated in |β| (no linear term at β = 0): not mapped")
                continue
            axes.setdefault(name, []).append(fn)
    for a in _NORMALISE:
        axes.setdefault(a, [])
    if any(True for h in helpers for v in h.iter("independentVar") if "h_b" in v.text):
        unmapped.append("ground effect (functions of aero/h_b-*): evaluated out of ground effect")
    return _Aero(helpers, axes, S, b, c), induced


def _reference_trim(model: _Aero, induced, mass, g, q, V, mach) -> tuple[float, float]:
    """α and δe of level flight at the reference state: CL = W/(qS) and Cm = 0 (thrust neglected)."""
    CL_needed = mass * g / (q * model.S)
    x = np.array([0.03, 0.0])
    for _ in range(30):

        def f(z):
            st = _state(mach, alpha=z[0], elevator=z[1])
            c = model.coefficients(st, V)
            return np.array([c["LIFT"] - CL_needed, c["PITCH"]])

        r = f(x)
        J = np.column_stack([(f(x + e) - f(x - e)) / (2 * _STEP) for e in np.eye(2) * _STEP])
        dx = np.linalg.solve(J, -r)
        x = x + dx
        if np.max(np.abs(dx)) < 1e-10:
            break
    return float(x[0]), float(x[1])


def _state(mach, **kw) -> dict:
    s = {
        "mach": mach,
        "alpha": 0.0,
        "beta": 0.0,
        "p": 0.0,
        "q": 0.0,
        "r": 0.0,
        "alphadot": 0.0,
        "elevator": 0.0,
        "aileron": 0.0,
        "rudder": 0.0,
    }
    s.update(kw)
    return s


def _alpha_validity(model: _Aero, alpha0: float) -> tuple[float, float]:
    """The α interval around α_ref on which every α table is on one linear segment."""
    lo, hi = -math.pi / 2, math.pi / 2
    for functions in model.axes.values():
        for fn in functions:
            for t in fn.iter("table"):
                names, rows, cols, _ = table_arrays(t)
                if names[0] == "aero/alpha-rad":
                    below, above = rows[rows <= alpha0], rows[rows > alpha0]
                    lo = max(lo, below.max()) if below.size else lo
                    hi = min(hi, above.min()) if above.size else hi
    return lo, hi


def derivative_table(model: _Aero, induced, alpha0, de0, V, machs) -> dict[str, list[float]]:
    """Non-dimensional stability-axis derivatives at each Mach breakpoint (module docstring)."""
    skip = {f.get("name") for f in induced}
    out: dict[str, list[float]] = {}
    ca, sa = math.cos(alpha0), math.sin(alpha0)
    R = np.array([[ca, sa], [-sa, ca]])  # body (Cl, Cn) → stability axes
    for mach in machs:
        base = _state(mach, alpha=alpha0)

        def d(var, axis, at=None):
            s0 = dict(base, **(at or {}))  # noqa: B023  (called within this iteration)
            plus, minus = dict(s0), dict(s0)
            plus[var] += _STEP
            minus[var] -= _STEP
            return (model.coefficients(plus, V, skip)[axis] - model.coefficients(minus, V, skip)[axis]) / (2 * _STEP)

        c0 = model.coefficients(base, V, skip)
        row = {}
        for coef, axis in (("CL", "LIFT"), ("CD", "DRAG"), ("Cm", "PITCH")):
            slope = d("alpha", axis)
            row[f"{coef}_alpha"] = slope
            row[f"{coef}0" if coef != "CD" else "CD0"] = c0[axis] - slope * alpha0
            row[f"{coef}_q"] = d("q", axis)
            row[f"{coef}_alphadot"] = d("alphadot", axis)
            row[f"{coef}_elevator"] = d("elevator", axis, {"elevator": de0})
        del row["CD_q"], row["CD_alphadot"]
        for var, name in (("beta", "beta"), ("p", "p"), ("r", "r"), ("aileron", "aileron"), ("rudder", "rudder")):
            row[f"CY_{name}"] = d(var, "SIDE")
            body = np.array([d(var, "ROLL"), d(var, "YAW")])
            if var in ("p", "r"):
                continue
            row[f"Cl_{name}"], row[f"Cn_{name}"] = (float(v) for v in R @ body)
        rate_body = np.array([[d("p", "ROLL"), d("r", "ROLL")], [d("p", "YAW"), d("r", "YAW")]])
        rate = R @ rate_body @ R.T
        row["Cl_p"], row["Cl_r"], row["Cn_p"], row["Cn_r"] = (float(v) for v in rate.ravel())
        if induced:
            st = dict(base, cl2=1.0)
            p = model.props(st, V)
            qS = p["aero/qbar-psf"] * p["metrics/Sw-sqft"]
            row["k"] = sum(evaluate(f, p) for f in induced) / qS
        for key, value in row.items():
            out.setdefault(key, []).append(float(value))
    return {k: v for k, v in out.items() if any(abs(x) > 1e-12 for x in v)}


def _mach_breakpoints(model: _Aero, mach_ref: float) -> list[float]:
    found = {mach_ref}
    for functions in model.axes.values():
        for fn in functions:
            for t in fn.iter("table"):
                names, rows, cols, _ = table_arrays(t)
                if names[0] == "velocities/mach":
                    found |= {float(m) for m in rows if 0.0 <= m < 0.99}
                    if rows.max() > 0.99:
                        found.add(0.99)
    return sorted(found)


# --- the whole file ----------------------------------------------------------------------------------------------


def import_jsbsim(path: str | Path, mach: float = 0.8, altitude: float = 35_000 * FT) -> ImportResult:
    """The certkit aircraft data of the JSBSim FDM at ``path`` (module docstring), linearised in α at level
    flight at ``mach`` and ``altitude`` (m)."""
    path = Path(path)
    if not 0.05 <= mach < 0.99:
        raise UserError(f"--mach {mach}: the imported table needs 0.05 <= Mach < 0.99")
    if not 0.0 <= altitude <= 20_000.0:
        raise UserError(f"--altitude {altitude:.0f} m: outside 0 … 20 km")
    root = read_xml(path)
    unmapped: list[str] = []
    met = root.find("metrics")
    if met is None:
        raise _fail(path, "<metrics> is missing")
    S = _quantity(met.find("wingarea"), path, "metrics/wingarea", _AREA, "FT2")
    b = _quantity(met.find("wingspan"), path, "metrics/wingspan", _LENGTH, "FT")
    c = _quantity(met.find("chord"), path, "metrics/chord", _LENGTH, "FT")
    arp_el = next((loc for loc in met.findall("location") if loc.get("name") == "AERORP"), None)
    arp = _location(arp_el, path, "metrics/location AERORP")
    mass, cg, J, notes = mass_properties(root, path, unmapped)
    g = G0 * (EARTH_RADIUS / (EARTH_RADIUS + altitude)) ** 2
    V = mach * float(isa.speed_of_sound(altitude))
    q = 0.5 * float(isa.density(altitude)) * V * V
    model, induced = _aero_model(root, path, S, b, c, unmapped)
    try:
        alpha0, de0 = _reference_trim(model, induced, mass, g, q, V, mach)
        machs = _mach_breakpoints(model, mach)
        table = derivative_table(model, induced, alpha0, de0, V, machs)
    except (Unsupported, np.linalg.LinAlgError) as exc:
        raise UserError(f"{path}: the aerodynamics cannot be evaluated ({exc})") from None
    lo, hi = _alpha_validity(model, alpha0)
    notes.append(
        f"α tables linearised at α_ref = {math.degrees(alpha0):.3f}° (level flight at Mach {mach:g}, "
        f"{altitude:.0f} m, δe {math.degrees(de0):.3f}°): exact for α in [{math.degrees(lo):.2f}°, "
        f"{math.degrees(hi):.2f}°]"
    )
    if induced:
        notes.append("aero/cl-squared terms: the polar's k")
    if table.get("CD_elevator"):
        notes.append("drag of |δe|: linear with the sign of the reference elevator")
    fcs = root.find("flight_control")
    if fcs is not None and list(fcs.iter()):
        unmapped.append(
            f"flight control system {fcs.get('name', '')!r} (yaw damper, trims, surface scaling): not "
            "imported; certkit flies the surfaces directly (close such loops yourself)"
        )
    if root.find("ground_reactions") is not None:
        unmapped.append(
            "ground reactions (gear contacts): not mapped (certkit's landing gear needs the geometry section)"
        )
    for section in ("system", "autopilot", "external_reactions", "buoyant_forces"):
        if root.find(section) is not None:
            unmapped.append(f"<{section}>: not mapped")
    Ixz = -float(J[0, 2])
    data = {
        "name": f"{root.get('name', path.stem)} (imported from JSBSim)",
        "description": f"Imported by certkit from {path.name}: derivative table linearised at Mach {mach:g}, "
        f"{altitude:.0f} m (see the header for what was not mapped)",
        "reference": {
            "area": S,
            "span": b,
            "mean_chord": c,
            "moment_point": {"x": float(arp[0]), "y": float(arp[1]), "z": float(arp[2])},
        },
        "mass": {
            "MTOW": mass,
            "cg": {"x": float(cg[0]), "y": float(cg[1]), "z": float(cg[2])},
            "inertia": {
                "Ixx": float(J[0, 0]),
                "Iyy": float(J[1, 1]),
                "Izz": float(J[2, 2]),
                "Ixz": Ixz,
                "Ixy": -float(J[0, 1]),
                "Iyz": -float(J[1, 2]),
            },
        },
        "flight_condition": {
            "altitude": altitude,
            "mach": mach,
            "gravity": g,
            "source": "import point; gravity at that altitude (inverse square, 1976 standard atmosphere radius)",
        },
        "aerodynamics": {
            "derivative_tables": {
                "clean": {
                    "mach": machs,
                    "derivatives": {k: (v if len(v) > 1 else v[0]) for k, v in table.items()},
                    "controls": ["elevator", "aileron", "rudder"],
                    "source": f"JSBSim {path.name}, imported by certkit",
                }
            }
        },
        "sources": {"jsbsim": f"JSBSim aircraft model {path.name} ({root.get('name', '')})"},
    }
    prop = propulsion(root, path, unmapped)
    if prop is not None:
        data["propulsion"] = prop
    return ImportResult(data, unmapped, notes, alpha0, de0)


def to_yaml(result: ImportResult) -> str:
    """The aircraft file: a header (what was mapped, what was not) and the data (SI numbers)."""
    head = ["# certkit aircraft file imported from a JSBSim FDM (certkit import jsbsim). SI units throughout."]
    head += [f"# note: {n}" for n in result.notes]
    head += [f"# not mapped: {u}" for u in result.unmapped]
    return "\n".join(head) + "\n" + yaml.safe_dump(_plain(result.data), sort_keys=False, allow_unicode=True, width=120)


def _plain(value):
    """Plain Python numbers, lists and dicts (numpy scalars are not YAML)."""
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, np.generic):
        return value.item()
    return value
