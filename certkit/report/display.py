"""Units and numbers as the report shows them: aviation units first (kn, ft, lb, lbf, g, deg; structural loads in
kN and kN·m), numbers rounded to a documented precision.

Precision: a column (or a single value) is shown with :data:`SIGNIFICANT` significant digits of its largest
magnitude, so every number of a column has the same decimals and round-off noise (``5.551e-17``) reads ``0``;
``-0`` reads ``0``; a missing value (None, NaN) reads an em dash.
"""

from __future__ import annotations

import math
import re

from certkit.units import FT, G0, LB, LBF

KN = 1852.0 / 3600.0
#: SI (or stated) unit → (unit shown, factor: shown = value / factor); units not listed are shown as they are
DEFAULT = {
    "m/s": ("kn", KN),
    "m": ("ft", FT),
    "kg": ("lb", LB),
    "N": ("lbf", LBF),
    "N·m": ("kN·m", 1e3),
    "N*m": ("kN·m", 1e3),
    "rad": ("deg", math.pi / 180.0),
    "rad/s": ("deg/s", math.pi / 180.0),
    "rad/s²": ("deg/s²", math.pi / 180.0),
    "m/s²": ("g", G0),
    "gradient": ("%", 0.01),
}
#: explicit display units (``display=`` of an axis or column) → (SI unit, factor)
EXPLICIT = {
    "kN": ("N", 1e3),
    "kN·m": ("N·m", 1e3),
    "MN·m": ("N·m", 1e6),
    "ft/s": ("m/s", FT),
    "ft/min": ("m/s", FT / 60),
    "kn": ("m/s", KN),
    "ft": ("m", FT),
    "lb": ("kg", LB),
    "lbf": ("N", LBF),
    "deg": ("rad", math.pi / 180.0),
    "deg/s": ("rad/s", math.pi / 180.0),
    "1,000 lb": ("kg", 1000 * LB),
    "nmi": ("m", 1852.0),
    "%": ("gradient", 0.01),
    "m/s": ("m/s", 1.0),
    "N": ("N", 1.0),
    "m": ("m", 1.0),
    "kg": ("kg", 1.0),
    "g": ("m/s²", G0),
}
SIGNIFICANT = 4
DASH = "—"


def unit_and_factor(unit: str, display: str | None = None) -> tuple[str, float]:
    """(unit shown, factor) for numbers in ``unit``: shown = value / factor."""
    if display == unit:
        return unit, 1.0
    if display:
        si, factor = EXPLICIT.get(display, (None, 1.0))
        if si != unit and not (unit == "N*m" and si == "N·m"):
            raise ValueError(f"cannot show {unit!r} in {display!r}")
        return display, factor
    return DEFAULT.get(unit, (unit, 1.0))


def axis_label(label: str, unit: str) -> str:
    return f"{label} ({unit})" if unit else label


def decimals(values, significant: int = SIGNIFICANT) -> int:
    """Decimals that give ``significant`` digits to the largest finite magnitude of ``values`` (0 to 6)."""
    return _places(max((abs(v) for v in values if _finite(v)), default=0.0), significant)


def _places(top: float, significant: int = SIGNIFICANT) -> int:
    """:func:`decimals` of the largest magnitude ``top``."""
    if top == 0.0:
        return 0
    return min(6, max(0, significant - 1 - math.floor(math.log10(top))))


def format_number(value, places: int, thousands: bool = True) -> str:
    """``value`` with ``places`` decimals (thousands separated), ``-0`` as ``0``, missing as an em dash."""
    if not _finite(value):
        return DASH
    return _fixed(float(value), places, thousands)


def _fixed(value: float, places: int, thousands: bool = True) -> str:
    """:func:`format_number` of a finite float."""
    v = round(value, places)
    if v == 0.0:
        v = 0.0
    return f"{v:,.{places}f}" if thousands else f"{v:.{places}f}"


def format_value(value) -> str:
    """One number on its own at :data:`SIGNIFICANT` digits."""
    if type(value) is float:  # the common case, without the generality of decimals() and _finite()
        return _fixed(value, _places(abs(value))) if math.isfinite(value) else DASH
    return format_number(value, decimals([value])) if _finite(value) else DASH


def _finite(v) -> bool:
    try:
        return v is not None and not isinstance(v, (bool, str)) and math.isfinite(float(v))
    except (TypeError, ValueError):
        return False


_SI_WORDS = ((re.compile(r"m/s²"), "g"), (re.compile(r"(?<![\w/])m/s(?![\w²])"), "kn"))


def in_display_units(text: str) -> str:
    """A description written with SI units (a rule's margin: "m/s EAS") in the units the report shows its numbers
    in ("kn EAS"): speeds in knots, accelerations in g."""
    for pattern, shown in _SI_WORDS:
        text = pattern.sub(shown, text)
    return text
