"""The evidence kinds (see :mod:`certkit.engine.evidence`): charts of series, bar charts, heatmaps, and tables with
typed
columns. Plain dataclasses of numbers and strings (numpy arrays for series), picklable between processes."""

from __future__ import annotations

import re
from collections.abc import Collection
from dataclasses import dataclass, field
from typing import Any

import numpy as np

#: kinds of reference lines: a requirement's limit, a structural or control allowable, an event (time, speed),
#: a plain reference (a declared speed); the report draws each kind in its own line style
LINE_KINDS = ("limit", "allowable", "event", "reference")


@dataclass
class Axis:
    """A quantity on an axis: its name, the SI unit of its numbers and, optionally, the unit to show it in."""

    label: str
    unit: str = ""
    display: str | None = None
    log: bool = False
    #: names of the categories at 0, 1, … (station names along a span), instead of numeric ticks
    categories: list[str] | None = None


@dataclass
class Series:
    """One line (or scatter, ``style="none"``) of a panel; NaN in ``y`` breaks the line. ``end`` (in x) is where
    the run ended: nothing is drawn after it. ``colour`` picks a palette entry (default: by order in the chart)."""

    label: str
    x: np.ndarray
    y: np.ndarray
    critical: bool = False
    style: str = "-"
    marker: str = ""
    colour: int | None = None
    end: float | None = None

    def __post_init__(self) -> None:
        self.x = np.asarray(self.x, dtype=float)
        self.y = np.asarray(self.y, dtype=float)
        if self.x.shape != self.y.shape or self.x.ndim != 1:
            raise ValueError(f"series {self.label!r}: x {self.x.shape} and y {self.y.shape} must be equal 1-D arrays")
        if self.end is not None:
            keep = self.x <= self.end + 1e-9 * max(1.0, abs(self.end))
            self.x, self.y = self.x[keep], self.y[keep]


@dataclass
class Limit:
    """A horizontal (``axis="y"``) or vertical (``axis="x"``) line at ``value`` (SI, the axis's unit), labelled."""

    value: float
    label: str
    axis: str = "y"
    kind: str = "limit"

    def __post_init__(self) -> None:
        if self.kind not in LINE_KINDS:
            raise ValueError(f"limit {self.label!r}: kind {self.kind!r} not one of {LINE_KINDS}")
        if self.axis not in ("x", "y"):
            raise ValueError(f"limit {self.label!r}: axis must be 'x' or 'y'")


@dataclass
class Point:
    """A marked point (the critical point of a panel), labelled."""

    x: float
    y: float
    label: str = "critical"
    #: ``critical`` (a star, named in the legend) or ``corner`` (a small dot with its label beside it)
    kind: str = "critical"
    colour: int | None = None


@dataclass
class Panel:
    """One axes: its y quantity, series, limits and marked points; ``x`` overrides the chart's x axis (side-by-side
    panels on different quantities)."""

    y: Axis
    series: list[Series] = field(default_factory=list)
    limits: list[Limit] = field(default_factory=list)
    points: list[Point] = field(default_factory=list)
    title: str = ""
    x: Axis | None = None
    #: a band between two series (index pairs into ``series``), shaded
    band: tuple[int, int] | None = None


@dataclass
class Chart:
    """Panels on one x axis, stacked (``arrangement="column"``, shared x: time histories) or side by side
    (``"row"``: one panel per quantity)."""

    x: Axis
    panels: list[Panel]
    title: str = ""
    arrangement: str = "column"


@dataclass
class Bars:
    """One bar per label (``values`` SI in ``axis``'s unit); ``failing`` marks the bars of failing findings;
    ``limit`` is the line the bars are measured against. Horizontal bars for long labels."""

    labels: list[str]
    values: list[float]
    axis: Axis
    failing: list[bool]
    limit: Limit | None = None
    title: str = ""
    horizontal: bool = True


@dataclass
class Heatmap:
    """A matrix of values (NaN: not evaluated) over ``rows`` × ``columns``; cells below ``threshold`` fail."""

    rows: list[str]
    columns: list[str]
    values: np.ndarray
    scale: Axis
    row_label: str = ""
    column_label: str = ""
    title: str = ""
    threshold: float = 0.0

    def __post_init__(self) -> None:
        self.values = np.asarray(self.values, dtype=float)
        if self.values.shape != (len(self.rows), len(self.columns)):
            raise ValueError(
                f"heatmap {self.title!r}: values {self.values.shape} for {len(self.rows)} rows × "
                f"{len(self.columns)} columns"
            )


@dataclass(frozen=True)
class Column:
    """A table column: its key in the rows, its header, the SI (or stated) unit of its numbers, and the display
    unit when not the default. ``kind``: ``number``, ``integer`` or ``text``."""

    key: str
    name: str
    unit: str = ""
    display: str | None = None
    kind: str = "number"
    #: the key of the column that holds each row's unit (mixed units: a findings table's value, limit, margin)
    unit_key: str | None = None


@dataclass
class Table:
    """Rows of values under typed columns (None or NaN: no value)."""

    columns: list[Column]
    rows: list[list[Any]]

    @classmethod
    def from_dicts(cls, rows: list[dict[str, Any]], columns: list[Column] | None = None) -> Table:
        """A table of dict rows; ``columns`` names some keys (others named by :func:`column_for_key`), columns in
        the order of ``columns`` then of the keys' first appearance."""
        given = {c.key: c for c in columns or ()}
        keys = list(given)
        for row in rows:
            keys += [k for k in row if k not in keys]
        cols = [given.get(k) or column_for_key(k, [row.get(k) for row in rows]) for k in keys]
        return cls(cols, [[row.get(k) for k in keys] for row in rows])

    def __len__(self) -> int:
        return len(self.rows)

    def as_dicts(self) -> list[dict[str, Any]]:
        return [{c.key: v for c, v in zip(self.columns, row)} for row in self.rows]


#: internal key → (header, unit) where the key's own words are not what a reviewer reads
_NAMES = {
    "CL_over_CLmax": ("CL / CLmax", ""),
    "alpha_deg": ("angle of attack α", "deg"),
    "beta_deg": ("sideslip β", "deg"),
    "bank_deg": ("bank φ", "deg"),
    "phi_deg": ("bank φ", "deg"),
    "zeta": ("damping ratio ζ", ""),
    "wn_rad_s": ("natural frequency ωn", "rad/s"),
    "tau_s": ("time constant τ", "s"),
    "t_double_s": ("time to double", "s"),
    "time_s": ("time", "s"),
    "H_ft": ("gust gradient H", "ft"),
    "speed_kn_cas": ("speed (CAS)", "kn"),
    "altitude_ft": ("altitude", "ft"),
    "mach": ("Mach", ""),
    "n_z": ("load factor n", "g"),
    "thrust_available_N": ("thrust available", "N"),
    "thrust_at_trim_N": ("thrust at trim", "N"),
    "x_cg_pct_mac": ("CG", "% MAC"),
    "gamma_deg": ("flight-path angle γ", "deg"),
    "flight_path_deg": ("flight-path angle γ", "deg"),
    "load_factor": ("load factor n", "g"),
    "control_usage": ("control usage", ""),
    "throttle": ("throttle", ""),
}
#: the unit a key's value is shown in: the key's own unit (it was chosen for the reader), SI ones in aviation units
_SHOWN = {"N": "lbf", "m": "ft", "kg": "lb", "m/s": "kn"}
#: key suffix → unit (the value is in this unit)
_SUFFIXES = (
    ("_rad_s", "rad/s"),
    ("_m_s", "m/s"),
    ("_ft_s", "ft/s"),
    ("_fpm", "ft/min"),
    ("_deg_s", "deg/s"),
    ("_deg", "deg"),
    ("_kn", "kn"),
    ("_ft", "ft"),
    ("_kN", "kN"),
    ("_lbf", "lbf"),
    ("_lb", "lb"),
    ("_kg", "kg"),
    ("_N", "N"),
    ("_pct", "%"),
    ("_m", "m"),
    ("_s", "s"),
    ("_g", "g"),
)


def column_for_key(key: str, values: Collection[object] = ()) -> Column:
    """A column for an internal key: a known name, else the key's words with its unit suffix (``vef_kn`` →
    "vef" in kn, ``rudder_min_deg`` → "rudder min" in deg; a unit written as the key's last word, ``"VEF kn"``,
    likewise); text when every value is a string."""
    kind = "text" if any(isinstance(v, str) for v in values) and not any(_is_number(v) for v in values) else "number"
    if key in _NAMES:
        name, unit = _NAMES[key]
        return Column(key, name, unit, _SHOWN.get(unit, unit), kind=kind)
    words, unit = key, ""
    for suffix, u in _SUFFIXES:
        if key.endswith(suffix) and len(key) > len(suffix):
            words, unit = key[: -len(suffix)], u
            break
    else:
        m = re.match(r"^(.*\S)\s+(kn|ft|deg|%|s|kN|lbf|lb|kg|N|m)$", key)
        if m:
            words, unit = m[1], m[2]
    return Column(key, words.replace("_", " "), unit, _SHOWN.get(unit, unit) if unit else None, kind=kind)


def _is_number(v: object) -> bool:
    return isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, bool)
