"""Unit conversion at the boundary (pint). Inside certkit every number is SI.

``to_si("4927.3 ft^2", "area")`` → 457.76 (m²); a bare number is taken as already SI.
Conversion happens when the aircraft file is read and when a report is written, never in a loop.
"""

from __future__ import annotations

import math
import re
from functools import lru_cache

from certkit.lean_imports import hidden
from certkit.user_cache import cache_folder

with hidden("dask"):  # pint's support of dask arrays, never used here (certkit.lean_imports)
    import pint


def _registry() -> pint.UnitRegistry:  # type: ignore[type-arg]  # pint's generic registry: quantity type unused
    """pint's registry, its parsed definitions cached in certkit's cache folder (a tenth of the start-up time).

    pint writes that cache in place, not atomically, so a process starting while another writes it can read a
    truncated file (``EOFError``), and a process killed while writing leaves one. A cache that cannot be read is
    removed and rebuilt once; if that fails too, or the folder cannot be written, the definitions are parsed afresh.
    """
    folder = cache_folder() / "pint"
    for _ in range(2):
        try:
            return pint.UnitRegistry(autoconvert_offset_to_baseunit=True, cache_folder=folder)
        except Exception:  # noqa: BLE001 - any failure of the cache (OSError, EOFError, UnpicklingError …)
            for stale in folder.glob("*.*"):
                try:
                    stale.unlink()
                except OSError:
                    pass
    return pint.UnitRegistry(autoconvert_offset_to_baseunit=True)


ureg = _registry()
ureg.define("knot_ = knot = kn = kt = kts")  # aliases used on flight decks

#: dimension name → (SI unit, pint dimensionality)
DIMENSIONS: dict[str, str] = {
    "length": "m",
    "area": "m**2",
    "mass": "kg",
    "force": "N",
    "speed": "m/s",
    "angle": "rad",
    "time": "s",
    "pressure": "Pa",
    "temperature": "K",
    "inertia": "kg*m**2",
    "moment": "N*m",
    "mass_flow": "kg/s",
    "acceleration": "m/s**2",
    "gearing": "rad/m",  # control gearing: surface angle per metre of cockpit travel
    "stiffness": "N/m",  # feel-spring gradient: force per metre of cockpit travel
    "density": "kg/m**3",
    "areal_density": "kg/m**2",  # mass per unit planform area (structural sizing)
    "angular_rate": "rad/s",
    "mass_per_energy": "kg/J",  # actuator mass per unit work capacity (stall force × stroke)
    "specific_fuel_consumption": "kg/N/s",  # thrust-specific fuel consumption ("0.52 lb/lbf/h")
    "dimensionless": "",
}


class UnitError(ValueError):
    """A quantity whose unit is unknown or of the wrong dimension."""


@lru_cache(maxsize=None)
def _si_unit(dimension: str) -> pint.Unit:
    if dimension not in DIMENSIONS:
        raise KeyError(f"unknown dimension {dimension!r}")
    return ureg.Unit(DIMENSIONS[dimension])


#: longest quantity text read ("97300 lbf" is 9 characters; a unit expression beyond this is a mistake)
MAX_QUANTITY_CHARS = 80
#: largest exponent a unit may carry ("m^3", "s^-2"); larger ones are rejected, never evaluated
MAX_UNIT_EXPONENT = 4

_NUMBER = r"[+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d{1,4})?"
_QUANTITY = re.compile(rf"^({_NUMBER})\s*(.*)$")
#: one token of a unit expression: a unit name, an integer exponent, a product, a quotient or a bracket
_UNIT_TOKEN = re.compile(
    r"\s*(?:(?P<name>[A-Za-zµμ°Ωℓ_][A-Za-z0-9µμ°Ωℓ_]*)|(?P<power>(?:\^|\*\*)\s*[+-]?\d+)"
    r"|(?P<op>[*/])|(?P<bracket>[()]))"
)


def _unit_expression(text: str) -> str:
    """``text`` checked to be a unit expression (names, ``*``, ``/``, a space for a product, brackets, small integer
    exponents) and returned in pint's syntax. Nothing is evaluated: a number or an operator where a unit name belongs
    ("9**9**9", "10**1000") is rejected."""
    out: list[str] = []
    pos, depth, expect_name = 0, 0, True
    while pos < len(text):
        m = _UNIT_TOKEN.match(text, pos)
        if m is None or m.end() == pos:
            raise UnitError(f"unexpected {text[pos:].strip()[:20]!r} in the unit {text!r}")
        pos = m.end()
        if m["name"]:
            if not expect_name:
                out.append("*")  # "kg m^2": a space is a product
            out.append(m["name"])
            expect_name = False
        elif m["power"]:
            exponent = int(m["power"].lstrip("^*").strip())
            if expect_name or abs(exponent) > MAX_UNIT_EXPONENT:
                raise UnitError(f"exponent in the unit {text!r} must follow a unit and lie within ±{MAX_UNIT_EXPONENT}")
            out.append(f"**{exponent}")
        elif m["op"]:
            if expect_name and not (m["op"] == "/" and out == []):
                raise UnitError(f"operator {m['op']!r} misplaced in the unit {text!r}")
            out.append(m["op"] if out else "1/")
            expect_name = True
        else:
            depth += 1 if m["bracket"] == "(" else -1
            if depth < 0 or depth > 3:
                raise UnitError(f"unbalanced brackets in the unit {text!r}")
            if m["bracket"] == "(" and not expect_name:
                out.append("*")
            out.append(m["bracket"])
            expect_name = m["bracket"] == "("
    if depth or (expect_name and out):
        raise UnitError(f"incomplete unit {text!r}")
    return "".join(out).replace("1//", "1/")


@lru_cache(maxsize=512)
def _unit_of(unit_text: str) -> pint.Unit:
    """The pint unit of a checked unit expression (:func:`_unit_expression`)."""
    try:
        unit = ureg.parse_units(_unit_expression(unit_text))
    except UnitError:
        raise
    except Exception as exc:  # pint raises several exception types for unknown names
        raise UnitError(f"unknown unit {unit_text!r} ({exc.__class__.__name__})") from None
    return unit


#: largest magnitude of a quantity in SI: a laminate modulus is 1e11 Pa, a widebody's yaw inertia 1e8 kg·m²; beyond
#: this a value is a slip (and its squares and products would overflow in the checks and models)
MAX_SI_MAGNITUDE = 1e15


def finite_number(value: float, what: object) -> float:
    """``value`` if finite, else a :class:`UnitError` naming ``what`` (the text as written)."""
    if not math.isfinite(value):
        raise UnitError(f"{what!r} is not a finite number (NaN, infinity and numbers beyond ±1.8e308 are not accepted)")
    return value


def physical(value: float, what: object) -> float:
    """``value`` (SI) if finite and within ±:data:`MAX_SI_MAGNITUDE`, else a :class:`UnitError`."""
    if abs(finite_number(value, what)) > MAX_SI_MAGNITUDE:
        raise UnitError(
            f"{what!r} is beyond any physical value certkit takes (magnitude above {MAX_SI_MAGNITUDE:.0e} in SI units)"
        )
    return value


@lru_cache(maxsize=4096)
def _parse_string(text: str, dimension: str) -> float:
    if len(text) > MAX_QUANTITY_CHARS:
        raise UnitError(
            f"quantity text of {len(text)} characters is too long (at most {MAX_QUANTITY_CHARS}): "
            "write a number and a unit, e.g. '4927.3 ft^2'"
        )
    m = _QUANTITY.match(text)
    if m is None:
        raise UnitError(f"cannot read {text!r} as a quantity: expected a number and a unit, e.g. '97300 lbf'")
    number = finite_number(float(m[1]), text)
    if not m[2]:
        return physical(number, text)  # a bare number is SI, as a number would be
    if m[2][0] in "*^0123456789.":
        raise UnitError(
            f"cannot read {text!r}: write one decimal number then the unit (e.g. '3.87e8 lb'); "
            "arithmetic is not evaluated"
        )
    unit = _unit_of(m[2])
    if unit.dimensionality != _si_unit(dimension).dimensionality:
        expected = DIMENSIONS[dimension] or "no unit"
        raise UnitError(f"{text!r} is not a {dimension} (expected a unit convertible to {expected})")
    return physical(float(ureg.Quantity(number, unit).to(_si_unit(dimension)).magnitude), text)


def si_reading(text: str) -> float | None:
    """The magnitude of quantity ``text`` in SI base units ("80 deg" → 1.396), whatever its dimension; None when it
    cannot be read (for messages that compare the text with an SI limit)."""
    m = _QUANTITY.match(text.strip()) if len(text) <= MAX_QUANTITY_CHARS else None
    if m is None or not m[2] or m[2][0] in "*^0123456789.":
        return None
    try:
        return float(ureg.Quantity(float(m[1]), _unit_of(m[2])).to_base_units().magnitude)
    except Exception:  # an unknown unit: no reading
        return None


def to_unit(text: str, unit: str) -> float:
    """Quantity ``text`` ("500 ft") in ``unit`` ("m"), read as :func:`to_si` reads (no arithmetic, finite)."""
    m = _QUANTITY.match(text.strip()) if len(text) <= MAX_QUANTITY_CHARS else None
    if m is None or not m[2] or m[2][0] in "*^0123456789.":
        raise UnitError(f"cannot read {text!r} as a number and a unit convertible to {unit!r}")
    try:
        target = ureg.parse_units(_unit_expression(unit))
        value = ureg.Quantity(finite_number(float(m[1]), text), _unit_of(m[2])).to(target).magnitude
    except UnitError:
        raise
    except Exception:  # pint's dimensionality errors, unknown target units
        raise UnitError(f"{text!r} cannot be converted to {unit!r}") from None
    return finite_number(float(value), text)


def to_si(value: object, dimension: str) -> float:
    """Convert ``value`` (a number in SI, or a string with a unit) to a finite float in SI units.

    The text is read as one decimal number and a unit expression (:func:`_unit_expression`); arithmetic is never
    evaluated, and NaN, infinities and overflowing numbers are a :class:`UnitError`."""
    if isinstance(value, bool):
        raise UnitError(f"{value!r} is not a {dimension}")
    if isinstance(value, (int, float)):
        try:
            return physical(float(value), value)
        except OverflowError:
            raise UnitError(f"a number of {len(str(abs(value)))} digits is beyond ±1.8e308") from None
    if isinstance(value, str):
        return _parse_string(value.strip(), dimension)
    raise UnitError(f"{value!r} is not a number or a string with a unit")


def from_si(value: float, unit: str) -> float:
    """Convert an SI value to ``unit`` (for reports): ``from_si(174.9, "kn")``."""
    q = ureg.Quantity(value, _base_of(unit))
    return float(q.to(unit).magnitude)


@lru_cache(maxsize=None)
def _base_of(unit: str) -> pint.Unit:
    dim = ureg.Unit(unit).dimensionality
    for name in DIMENSIONS:
        if _si_unit(name).dimensionality == dim:
            return _si_unit(name)
    raise UnitError(f"no SI unit known for {unit!r}")


# Constants (SI) used across models.
G0 = 9.80665  # standard gravity, m/s²  (ISO 2533)
FT = 0.3048
LB = 0.45359237
LBF = LB * G0
KN = 1852.0 / 3600.0
NMI = 1852.0
"""international nautical mile (m)"""
