"""Names and units a reader of the study report sees: a response key (``objective.block_fuel_kg``) as its words
("block fuel") in an aviation unit (lb), and a variable's SI value in the unit the study file declared for it
(``unit_label``: ft², deg). Values stay SI in the analysis; these only label and scale what is shown."""

from __future__ import annotations

import re

from certkit.units import from_si

#: a response key's unit suffix → (SI unit, unit shown); distances of a mission in nautical miles, its times in hours
_SUFFIXES = (
    ("_m_s", "m/s", "kn"),
    ("_kg", "kg", "lb"),
    ("_N", "N", "lbf"),
    ("_rad", "rad", "deg"),
    ("_m", "m", "ft"),
    ("_s", "s", "s"),
    ("_deg", "deg", "deg"),
)
_MISSION_WORDS = ("range", "distance")
#: a mode quantity of a design record (``mode.<mode>.<quantity>.<corner>.<configuration>``) → (words, unit, SI)
_MODE_QUANTITIES = {
    "zeta": ("damping ratio ζ", ""),
    "wn_rad_s": ("natural frequency ω_n", "rad/s"),
    "period_s": ("period", "s"),
    "t_half_s": ("time to half amplitude", "s"),
    "t_double_s": ("time to double amplitude", "s"),
    "cap": ("CAP ω²/(n/α)", "(rad/s²)/g"),
}
_KINDS = ("objective.", "constraint.", "mission.", "subcheck.", "handling.", "rule.")


def display_factor(unit: str, si_unit: str = "") -> float:
    """SI units per one display ``unit`` (shown = SI / factor); 1 without a unit or for one units cannot read."""
    if not unit or unit == si_unit:
        return 1.0
    try:
        return 1.0 / from_si(1.0, unit)
    except Exception:  # an unknown display unit: values stay SI rather than no report
        return 1.0


def response_label(name: str) -> tuple[str, str, float]:
    """(words, unit shown, factor) of a response key: ``objective.block_fuel_kg`` → ("block fuel", "lb", 0.4536),
    ``constraint.range_margin_m`` → ("range margin", "nmi", 1852), ``mission.block_time_s`` → ("block time", "h",
    3600); a key without a unit suffix keeps its words and no unit."""
    mode = re.match(r"^mode\.([a-z_]+)\.([a-z_]+)\.([^.]+)\.([^.]+)$", name)
    if mode and mode[2] in _MODE_QUANTITIES:
        words, unit = _MODE_QUANTITIES[mode[2]]
        return f"{mode[1].replace('_', ' ')} {words}, {mode[3]} {mode[4]}", unit, 1.0
    stem = name
    for kind in _KINDS:
        if stem.startswith(kind):
            stem = stem[len(kind) :]
            break
    for suffix, si_unit, shown in _SUFFIXES:
        if stem.endswith(suffix):
            stem = stem[: -len(suffix)]
            if si_unit == "m" and any(w in stem for w in _MISSION_WORDS):
                shown = "nmi"
            elif si_unit == "s" and "block" in stem:
                shown = "h"
            return _words(stem), shown, display_factor(shown, si_unit)
    return _words(stem), "", 1.0


def _words(stem: str) -> str:
    """``25.335(a).margin_x`` → "§25.335(a) margin x"; ``block_fuel`` → "block fuel"."""
    m = re.match(r"^(\d+\.\d+[a-z]?(?:\([a-z0-9]+\))*)\.(.*)$", stem)
    if m:
        return f"§{m[1]} {m[2].replace('_', ' ').replace('.', ' ')}"
    return stem.replace("_", " ")


def response_axis(name: str) -> str:
    """A response as an axis title: "block fuel (lb)"."""
    words, unit, _ = response_label(name)
    return f"{words} ({unit})" if unit else words
