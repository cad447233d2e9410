"""Lifting-surface geometry for the vortex lattice: plain dataclasses, camber lines, spacing laws.

Geometry frame: X aft, Y right, Z up (the AVL geometry frame, :mod:`certkit.conventions`); lengths
in metres, angles in radians. A :class:`Surface` is a list of :class:`Section` (leading-edge point,
chord, incidence, camber line) joined by straight lines, with the paneling and flag semantics of
AVL's SURFACE / SECTION / CONTROL keywords (Drela & Youngren, *AVL 3.x User Primer*, "Geometry
input file"). Nothing here depends on a file format: :mod:`.avl_file` and :func:`trapezoidal_surface`
both produce these objects.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from functools import cached_property
from pathlib import Path
from typing import Sequence

import numpy as np

from certkit.models.aero.interface import AeroReference

from .cubic_spline import NotAKnotSpline


class GeometryError(ValueError):
    """Degenerate or inconsistent lattice geometry; the message names the surface and section."""


# ----------------------------------------------------------------------------------------------
# Spacing laws (AVL semantics: 0 uniform, 1 cosine, 2 sine, -2 sine bunched at the other end,
# fractional values blend neighbouring laws linearly)
# ----------------------------------------------------------------------------------------------

_SPACING_NAMES = {"uniform": 0.0, "equal": 0.0, "cosine": 1.0, "sine": 2.0, "-sine": -2.0}


def spacing_parameter(spacing: float | str) -> float:
    """AVL spacing parameter in [-3, 3] from a number or a name (uniform, cosine, sine, -sine)."""
    if isinstance(spacing, str):
        try:
            return _SPACING_NAMES[spacing.strip().lower()]
        except KeyError:
            raise GeometryError(
                f"unknown spacing {spacing!r}; use one of {sorted(_SPACING_NAMES)} or a number in [-3, 3]"
            ) from None
    value = float(spacing)
    if not -3.0 <= value <= 3.0:
        raise GeometryError(f"spacing parameter {value} outside [-3, 3]")
    return value


def _blend_weights(parameter: float) -> tuple[float, float, float]:
    """Weights (uniform, cosine, sine) of AVL's piecewise-linear blend of spacing laws."""
    a = abs(parameter)
    if a < 1.0:
        return 1.0 - a, a, 0.0
    if a < 2.0:
        return 0.0, 2.0 - a, a - 1.0
    return a - 2.0, 0.0, 3.0 - a


def span_fractions(n_points: int, parameter: float) -> np.ndarray:
    """``n_points`` fractions 0..1 of the spanwise law (AVL SPACER): for a strip count n, call with
    2n+1 points; odd entries are strip edges, even entries the control-point stations."""
    w_eq, w_cos, w_sin = _blend_weights(parameter)
    frac = np.linspace(0.0, 1.0, n_points)
    theta = frac * math.pi
    sine = (1.0 - np.cos(theta / 2.0)) if parameter >= 0.0 else np.sin(theta / 2.0)
    return w_eq * frac + w_cos * 0.5 * (1.0 - np.cos(theta)) + w_sin * sine


def chord_fractions(n: int, parameter: float, claf: float = 1.0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Chordwise stations for ``n`` vortices (AVL CSPACER): panel edges (n+1), bound-vortex x/c and
    control-point x/c (n each). Each panel is split in quarters: vortex at 1/4, control point at 3/4
    (moved by ``claf``, the CLAF lift-slope factor)."""
    w_eq, w_cos, w_sin = _blend_weights(parameter)
    i = np.arange(1, n + 1, dtype=float)
    d0 = 1.0 / (4 * n)
    x0 = (4 * i - 4) * d0
    uni = np.stack([x0, x0 + d0, x0 + d0 + 2 * d0 * claf])
    d1 = math.pi / (4 * n + 2)
    t1 = (4 * i - 3) * d1
    cos_ = 0.5 * (1.0 - np.cos(np.stack([t1, t1 + d1, t1 + d1 + 2 * d1 * claf])))
    d2 = 0.5 * math.pi / (4 * n + 1)
    if parameter > 0.0:
        t2 = (4 * i - 3) * d2
        sin_ = 1.0 - np.cos(np.stack([t2, t2 + d2, t2 + d2 + 2 * d2 * claf]))
    else:
        t2 = (4 * i - 4) * d2
        sin_ = np.sin(np.stack([t2, t2 + d2, t2 + d2 + 2 * d2 * claf]))
    edge, vortex, control = w_eq * uni + w_cos * cos_ + w_sin * sin_
    edges = np.append(edge, 1.0)
    edges[0] = 0.0
    return edges, vortex, control


# ----------------------------------------------------------------------------------------------
# Camber lines
# ----------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class CamberLine:
    """Mean camber line z/c(x/c), x/c in [0, 1]; only its slope enters the lattice."""

    x: np.ndarray
    z: np.ndarray
    name: str = ""

    def slope(self, xc: np.ndarray) -> np.ndarray:
        """dz/dx at chord fractions ``xc`` (not-a-knot cubic spline through the camber points)."""
        return self._spline.derivative(np.clip(xc, self.x[0], self.x[-1]))

    @cached_property
    def _spline(self):
        return NotAKnotSpline(self.x, self.z)

    @classmethod
    def flat(cls) -> "CamberLine":
        return cls(np.array([0.0, 1.0]), np.array([0.0, 0.0]), "flat")

    @classmethod
    def naca(cls, designation: str) -> "CamberLine":
        """NACA 4-digit mean line (Abbott & von Doenhoff, §6.4): ``"2412"`` → 2 % camber at 40 %."""
        digits = designation.strip().upper().removeprefix("NACA").strip()
        if len(digits) != 4 or not digits.isdigit():
            raise GeometryError(f"NACA designation {designation!r} is not a 4-digit series airfoil")
        m, p = int(digits[0]) / 100.0, int(digits[1]) / 10.0
        x = 0.5 * (1.0 - np.cos(np.linspace(0.0, math.pi, 101)))
        if m == 0.0 or p == 0.0:
            return cls(x, np.zeros_like(x), f"NACA {digits}")
        z = np.where(x < p, m / p**2 * (2 * p * x - x**2), m / (1 - p) ** 2 * ((1 - 2 * p) + 2 * p * x - x**2))
        return cls(x, z, f"NACA {digits}")

    @classmethod
    def from_coordinates(cls, x: Sequence[float], z: Sequence[float], name: str = "") -> "CamberLine":
        """Camber line of an airfoil given as one closed contour (Selig order: trailing edge, upper
        surface, leading edge, lower surface, trailing edge), as AVL/XFOIL's GETCAM: the contour is
        splined in arc length, each point is paired with the point of equal x on the other side, the
        camber is their mean, measured from the leading-edge (minimum x) height."""
        from scipy.interpolate import CubicSpline  # deferred: scipy only for airfoil files: an .avl run loads no scipy

        x = np.asarray(x, float)
        z = np.asarray(z, float)
        if x.size < 5 or x.size != z.size:
            raise GeometryError(f"airfoil {name!r}: too few coordinates ({x.size})")
        keep = np.concatenate([[True], np.hypot(np.diff(x), np.diff(z)) > 0.0])
        x, z = x[keep], z[keep]
        s = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(x), np.diff(z)))])
        sx, sz = CubicSpline(s, x), CubicSpline(s, z)
        fine = np.linspace(0.0, s[-1], 20001)
        s_le = fine[int(np.argmin(sx(fine)))]
        x_le, z_le, x_te = float(sx(s_le)), float(sz(s_le)), 0.5 * (x[0] + x[-1])
        if not (x_te > x_le) or s_le <= 0.0 or s_le >= s[-1]:
            raise GeometryError(f"airfoil {name!r}: coordinates are not one contour (TE, upper, LE, lower, TE)")
        sides = []
        for lo, hi in ((s_le, 0.0), (s_le, s[-1])):
            ss = np.linspace(lo, hi, 4001)
            xs = np.maximum.accumulate(sx(ss))
            sides.append((xs, sz(ss)))
        upper = s < s_le
        opposite = np.where(upper, np.interp(x, *sides[1]), np.interp(x, *sides[0]))
        xc = np.append(x, x_le)
        zc = np.append(0.5 * (z + opposite), z_le)
        order = np.argsort(xc, kind="stable")
        xc, zc = xc[order], zc[order]
        tol = 1.0e-3 * s[-1]
        groups = np.concatenate([[0], np.cumsum(np.diff(xc) > tol)])
        counts = np.bincount(groups)
        xc = np.bincount(groups, xc) / counts
        zc = np.bincount(groups, zc) / counts
        chord = x_te - x_le
        return cls((xc - x_le) / chord, (zc - zc[0]) / chord, name)

    @classmethod
    def from_file(cls, path: str | Path) -> "CamberLine":
        """Camber line of an airfoil coordinate file, Selig or Lednicer format."""
        path = Path(path)
        x, z, name = read_airfoil_file(path)
        return cls.from_coordinates(x, z, name or path.stem)


def read_airfoil_file(path: Path) -> tuple[np.ndarray, np.ndarray, str]:
    """Coordinates of a Selig (one contour TE→upper→LE→lower→TE) or Lednicer (point counts, upper
    LE→TE, then lower LE→TE) airfoil file, returned in Selig order."""
    lines = [ln.split() for ln in path.read_text().splitlines()]
    name = ""
    rows: list[list[float]] = []
    blocks: list[list[list[float]]] = [[]]
    for k, parts in enumerate(lines):
        if not parts:
            if blocks[-1]:
                blocks.append([])
            continue
        try:
            values = [float(p) for p in parts[:2]]
        except ValueError:
            if k == 0 or not rows:
                name = " ".join(parts)
                continue
            raise GeometryError(f"{path}: line {k + 1}: cannot read coordinates from {' '.join(parts)!r}") from None
        if len(values) < 2:
            raise GeometryError(f"{path}: line {k + 1}: expected two numbers")
        rows.append(values)
        blocks[-1].append(values)
    blocks = [b for b in blocks if b]
    if not rows:
        raise GeometryError(f"{path}: no coordinates")
    first = rows[0]
    if first[0] > 1.5 and first[1] > 1.5:  # Lednicer: "NU NL" counts line
        n_upper, n_lower = int(first[0]), int(first[1])
        pts = np.array(rows[1:])
        if len(pts) != n_upper + n_lower:
            raise GeometryError(f"{path}: Lednicer counts {n_upper}+{n_lower} do not match {len(pts)} points")
        upper, lower = pts[:n_upper], pts[n_upper:]
        contour = np.vstack([upper[::-1], lower[1:] if np.allclose(lower[0], upper[0]) else lower])
    else:
        contour = np.array(rows)
    return contour[:, 0], contour[:, 1], name


# ----------------------------------------------------------------------------------------------
# Surfaces
# ----------------------------------------------------------------------------------------------


@dataclass
class ControlSurface:
    """A control declared on a section (AVL CONTROL): it acts between consecutive sections that both
    carry it. ``hinge_x_over_c`` > 0: trailing-edge surface aft of the hinge; < 0: leading-edge
    surface ahead of |x/c|. ``gain`` is surface rotation per unit control variable (rad/rad), the
    positive rotation being right-handed about ``hinge_vector`` (zero vector: along the hinge line
    from this section to the next). ``duplicate_sign`` (AVL SgnDup) multiplies the deflection on the
    mirrored half: +1 symmetric (elevator), -1 antisymmetric (aileron)."""

    name: str
    hinge_x_over_c: float
    gain: float = 1.0
    hinge_vector: tuple[float, float, float] = (0.0, 0.0, 0.0)
    duplicate_sign: float = 1.0


@dataclass
class Section:
    """One defining section of a surface: leading-edge point (m, geometry frame), chord (m),
    incidence (rad, nose up about the spanwise axis), camber line, the controls it carries, and the
    per-interval spanwise paneling used when the surface gives none (AVL Nspan, Sspace)."""

    leading_edge: tuple[float, float, float]
    chord: float
    incidence: float = 0.0
    camber: CamberLine | None = None
    controls: list[ControlSurface] = field(default_factory=list)
    n_span: int = 0
    span_spacing: float | str = 1.0
    claf: float = 1.0


@dataclass
class Surface:
    """A lifting surface (AVL SURFACE). ``n_span``/``span_spacing`` (if given) distribute vortices
    over the whole surface, nodes then moved onto the sections; otherwise each section's own
    ``n_span`` applies to the interval after it. ``y_duplicate``: mirror image about y = value.
    ``component``: surfaces of one component see each other with a negligible vortex core, others
    with AVL's core of twice the strip width. ``wake=False`` is NOWAKE, ``alpha_beta=False`` NOALBE,
    ``load=False`` NOLOAD. ``scale``/``translate``/``incidence`` are AVL's SCALE/TRANSLATE/ANGLE."""

    name: str
    sections: list[Section]
    n_chord: int = 8
    chord_spacing: float | str = 1.0
    n_span: int | None = None
    span_spacing: float | str = 1.0
    y_duplicate: float | None = None
    component: int | None = None
    wake: bool = True
    alpha_beta: bool = True
    load: bool = True
    scale: tuple[float, float, float] = (1.0, 1.0, 1.0)
    translate: tuple[float, float, float] = (0.0, 0.0, 0.0)
    incidence: float = 0.0

    def control_names(self) -> list[str]:
        names: list[str] = []
        for sec in self.sections:
            for c in sec.controls:
                if c.name not in names:
                    names.append(c.name)
        return names


@dataclass
class Configuration:
    """Everything the lattice needs: surfaces, reference quantities (AeroReference; ``y_ref`` for
    completeness), default Mach number and a zero-lift drag coefficient added to CD (AVL CDp)."""

    surfaces: list[Surface]
    reference: AeroReference
    mach: float = 0.0
    y_ref: float = 0.0
    cd0: float = 0.0
    name: str = ""

    @property
    def control_names(self) -> tuple[str, ...]:
        names: list[str] = []
        for s in self.surfaces:
            for n in s.control_names():
                if n not in names:
                    names.append(n)
        return tuple(names)

    def with_reference(self, **changes) -> "Configuration":
        """Copy with reference quantities changed, e.g. ``x_ref=cg_x``."""
        return replace(self, reference=replace(self.reference, **changes))


# ----------------------------------------------------------------------------------------------
# Trapezoidal helper
# ----------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class ControlSpan:
    """A control on a trapezoidal surface: spanwise extent as fractions of the semi-span (or fin
    height), ``chord_ratio`` = control chord / local chord. Sign follows :mod:`certkit.conventions`
    (Etkin): elevator and flap trailing edge down, aileron right trailing edge down, rudder trailing
    edge left, when ``kind`` is left to be inferred from the name; ``gain`` scales it. Several spans of one name
    are the segments of one control (e.g. an outboard aileron and an inboard flaperon on the roll command), each
    moving ``gain`` × the control's deflection."""

    name: str
    eta_inboard: float
    eta_outboard: float
    chord_ratio: float
    gain: float = 1.0
    kind: str | None = None  # "symmetric", "antisymmetric" or "rudder"; default from the name
    hinge_vector: tuple[float, float, float] = (0.0, 0.0, 0.0)  # zero: along the hinge line


def _control_kind(spec: ControlSpan) -> str:
    if spec.kind:
        return spec.kind
    name = spec.name.lower()
    if "aileron" in name or "spoileron" in name:
        return "antisymmetric"
    if "rudder" in name:
        return "rudder"
    return "symmetric"


def _segment_gaps(where: str, controls: Sequence[ControlSpan]) -> list[float]:
    """A control of several spans (one name: the segments move together, each with its gain, as AVL's CONTROL
    lines on several sections): the span fractions of a section in the middle of each gap between its segments,
    which carries no part of it, so that the gap does not deflect (a control acts between two sections that
    both carry it). Overlapping segments of one name are refused."""
    out = []
    by_name: dict[str, list[ControlSpan]] = {}
    for c in controls:
        by_name.setdefault(c.name, []).append(c)
    for name, spans in by_name.items():
        spans = sorted(spans, key=lambda c: c.eta_inboard)
        for a, b in zip(spans, spans[1:]):
            if b.eta_inboard < a.eta_outboard - 1e-12:
                raise GeometryError(
                    f"{where}: control {name!r} has overlapping segments ({a.eta_inboard}–{a.eta_outboard} and "
                    f"{b.eta_inboard}–{b.eta_outboard})"
                )
            if b.eta_inboard > a.eta_outboard + 1e-12:
                out.append(0.5 * (a.eta_outboard + b.eta_inboard))
            elif (a.chord_ratio, a.gain) != (b.chord_ratio, b.gain):
                raise GeometryError(
                    f"{where}: control {name!r} has abutting segments at {a.eta_outboard} with different chord ratios "
                    "or gains: one section cannot carry both (leave a gap between them)"
                )
    return out


def trapezoidal_surface(
    name: str,
    *,
    area: float,
    aspect_ratio: float,
    taper: float,
    sweep_quarter_chord: float = 0.0,
    dihedral: float = 0.0,
    root_leading_edge: tuple[float, float, float] = (0.0, 0.0, 0.0),
    incidence: float = 0.0,
    thickness_ratio: float = 0.12,
    camber: str | None = None,
    vertical: bool = False,
    controls: Sequence[ControlSpan] = (),
    n_chord: int = 8,
    n_span: int = 16,
    chord_spacing: float | str = 1.0,
    span_spacing: float | str = 1.0,
    component: int | None = None,
    section_etas: Sequence[float] = (),
) -> Surface:
    """A straight-tapered surface from planform parameters (area m², aspect ratio b²/S, taper
    c_tip/c_root, quarter-chord sweep and dihedral in rad). Horizontal surfaces are mirrored about
    y = root y (``area`` and ``aspect_ratio`` refer to the whole surface); a vertical surface
    (``vertical=True``) lies in the plane of symmetry, spans upward, is not mirrored, and its
    ``aspect_ratio`` is height²/area. ``camber`` is a NACA 4-digit mean-line designation's first two
    digits or a full designation ("24" or "2412"); the thickness ratio completes the designation and
    does not enter the lattice. Sections are placed at the root, the tip, every control edge and the span
    fractions ``section_etas``."""
    where = f"surface {name!r}"
    for label, value in (("area", area), ("aspect ratio", aspect_ratio), ("taper", taper)):
        if not (value > 0.0 and math.isfinite(value)):
            raise GeometryError(f"{where}: {label} must be positive, got {value}")
    span = math.sqrt(area * aspect_ratio)
    semi = span if vertical else span / 2.0
    c_root = (area if vertical else area / 2.0) * 2.0 / (semi * (1.0 + taper))
    tan_c4 = math.tan(sweep_quarter_chord)
    camber_line = None
    if camber:
        digits = camber.strip().upper().removeprefix("NACA").strip()
        if len(digits) == 2:
            digits = f"{digits}{min(99, round(100 * thickness_ratio)):02d}"
        camber_line = CamberLine.naca(digits)

    etas = {0.0, 1.0} | {float(e) for e in section_etas if 0.0 < e < 1.0}
    for c in controls:
        if not (0.0 <= c.eta_inboard < c.eta_outboard <= 1.0):
            raise GeometryError(
                f"{where}: control {c.name!r} span fractions ({c.eta_inboard}, {c.eta_outboard}) must satisfy 0 <= "
                "inboard < outboard <= 1"
            )
        if not 0.0 < c.chord_ratio <= 1.0:  # 1: the whole chord turns (an all-moving surface's incidence)
            raise GeometryError(f"{where}: control {c.name!r} chord ratio {c.chord_ratio} must be in (0, 1]")
        etas.update((c.eta_inboard, c.eta_outboard))
    etas.update(_segment_gaps(where, controls))
    x0, y0, z0 = root_leading_edge
    sections: list[Section] = []
    stations: list[float] = []
    for eta in sorted(etas):  # one section per station: edges given twice within round-off are one
        if not stations or eta > stations[-1] + 1e-9:
            stations.append(eta)
    for eta in stations:
        chord = c_root * (1.0 - (1.0 - taper) * eta)
        s = eta * semi
        x_le = x0 + s * tan_c4 + 0.25 * (c_root - chord)
        if vertical:
            le = (x_le, y0, z0 + s)
        else:
            le = (x_le, y0 + s, z0 + s * math.tan(dihedral))
        sec_controls = []
        named: set[str] = set()
        for c in controls:
            if c.eta_inboard - 1e-12 <= eta <= c.eta_outboard + 1e-12 and c.name not in named:
                named.add(c.name)
                kind = _control_kind(c)
                if kind == "antisymmetric":  # right trailing edge down positive, left up
                    sec_controls.append(ControlSurface(c.name, 1.0 - c.chord_ratio, c.gain, duplicate_sign=-1.0))
                elif kind == "rudder":  # hinge along +z: positive rotation swings the TE to +y (right)
                    sec_controls.append(ControlSurface(c.name, 1.0 - c.chord_ratio, -c.gain))
                else:
                    sec_controls.append(ControlSurface(c.name, 1.0 - c.chord_ratio, c.gain, c.hinge_vector))
        sections.append(Section(le, chord, 0.0 if vertical else incidence, camber_line, sec_controls))
    return Surface(
        name,
        sections,
        n_chord=n_chord,
        chord_spacing=chord_spacing,
        n_span=n_span,
        span_spacing=span_spacing,
        y_duplicate=None if vertical else y0,
        component=component,
    )
