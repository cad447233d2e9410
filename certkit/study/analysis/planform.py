"""Horizontal-tail and elevator planforms from the design variables (straight-tapered reference trapezoid).

Span b = √(A·S), root chord c_r = 2S / (b(1 + λ)), tip chord λ·c_r, quarter-chord line swept by Λ;
mean aerodynamic chord c̄ = ⅔ c_r (1 + λ + λ²)/(1 + λ) at y = (b/6)(1 + 2λ)/(1 + λ), aerodynamic centre at
its quarter chord (Raymer, *Aircraft Design: A Conceptual Approach*, 6th ed., §7.3, Fig. 7.5). The elevator
spans the fractions ``span_start``..``span_end`` of the semispan with the chord ratio ``chord_ratio`` of the
local chord, ahead of the trailing edge (the aircraft file's convention).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

HT = "geometry.horizontal_tail."
ELEVATOR = HT + "controls.elevator."
PLANFORM_VARIABLES = (HT + "area", HT + "aspect_ratio", HT + "taper", HT + "sweep_quarter_chord")
ELEVATOR_VARIABLES = (ELEVATOR + "span_start", ELEVATOR + "span_end", ELEVATOR + "chord_ratio")


@dataclass(frozen=True)
class Planform:
    area: float
    aspect_ratio: float
    taper: float
    sweep_quarter_chord: float  # rad
    elevator: tuple[float, float, float] | None = None  # span_start, span_end, chord_ratio

    @property
    def span(self) -> float:
        return math.sqrt(self.aspect_ratio * self.area)

    @property
    def root_chord(self) -> float:
        return 2.0 * self.area / (self.span * (1.0 + self.taper))

    def chord(self, y: np.ndarray | float) -> np.ndarray | float:
        return self.root_chord * (1.0 - (1.0 - self.taper) * np.abs(y) / (0.5 * self.span))

    def leading_edge(self, y: np.ndarray | float) -> np.ndarray | float:
        """x of the leading edge (aft positive) from the root leading edge."""
        return np.abs(y) * math.tan(self.sweep_quarter_chord) + 0.25 * self.root_chord - 0.25 * self.chord(y)

    @property
    def mac(self) -> float:
        lam = self.taper
        return 2.0 / 3.0 * self.root_chord * (1.0 + lam + lam * lam) / (1.0 + lam)

    @property
    def y_mac(self) -> float:
        return self.span / 6.0 * (1.0 + 2.0 * self.taper) / (1.0 + self.taper)

    @property
    def x_ac(self) -> float:
        return float(self.leading_edge(self.y_mac)) + 0.25 * self.mac

    def outline(self) -> np.ndarray:
        """Closed outline (x, y) of both panels, x from the aerodynamic centre."""
        s = 0.5 * self.span
        y = np.array([0.0, s, s, 0.0, -s, -s, 0.0])
        le = np.asarray(self.leading_edge(y))
        x = np.array([le[0], le[1], le[2] + self.chord(s), self.root_chord, le[4] + self.chord(s), le[5], le[6]])
        return np.column_stack([x - self.x_ac, y])

    def elevator_outlines(self) -> list[np.ndarray]:
        """Outlines (x, y) of the right and left elevators, x from the aerodynamic centre."""
        if self.elevator is None:
            return []
        start, end, ratio = self.elevator
        s = 0.5 * self.span
        out = []
        for side in (1.0, -1.0):
            y = side * s * np.array([start, end])
            te = np.asarray(self.leading_edge(y) + self.chord(y))
            hinge = te - ratio * np.asarray(self.chord(y))
            pts = np.array([[hinge[0], y[0]], [te[0], y[0]], [te[1], y[1]], [hinge[1], y[1]], [hinge[0], y[0]]])
            pts[:, 0] -= self.x_ac
            out.append(pts)
        return out


def planform_from(values: dict[str, float]) -> tuple[Planform | None, str]:
    """The planform of a design given by variable path → SI value; (None, reason) when a value is missing."""
    missing = [p for p in PLANFORM_VARIABLES if p not in values]
    if missing:
        return None, (
            f"planform not drawn: {', '.join(missing)} not a study variable (its value lives in the "
            f"aircraft file, which the analysis does not read)"
        )
    elevator: tuple[float, float, float] | None = None
    if all(p in values for p in ELEVATOR_VARIABLES):
        start, end, ratio = (values[p] for p in ELEVATOR_VARIABLES)
        elevator = (start, end, ratio)
    note = "" if elevator else "elevator not drawn: its span fractions and chord ratio are not all study variables"
    area, aspect_ratio, taper, sweep = (values[p] for p in PLANFORM_VARIABLES)
    return Planform(area, aspect_ratio, taper, sweep, elevator=elevator), note


def polygon_area(points: np.ndarray) -> float:
    """Shoelace area of a closed polygon."""
    x, y = points[:, 0], points[:, 1]
    return 0.5 * abs(float(np.dot(x[:-1], y[1:]) - np.dot(x[1:], y[:-1])))
