"""Read (and write) AVL geometry files as :class:`~.geometry.Configuration` objects.

Format: Drela & Youngren, *AVL 3.x User Primer*, "Geometry input file". Supported: the header
(title, Mach, IYsym IZsym Zsym, Sref Cref Bref, Xref Yref Zref, optional CDp), SURFACE with
COMPONENT (INDEX), YDUPLICATE, SCALE, TRANSLATE, ANGLE, NOWAKE, NOALBE, NOLOAD, CDCL (stored, not
used), SECTION with NACA, AIRFOIL, AFILE, CLAF, CONTROL, DESIGN (ignored); BODY blocks are skipped
with a warning. Comments start with ``#`` or ``!``; keywords are recognised by their first four
letters, as AVL does. Lengths are taken as metres, angles converted from degrees to radians;
control gains (deg/deg in AVL) are rad/rad here, the same ratio.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from certkit.models.aero.interface import AeroReference

from .geometry import CamberLine, Configuration, ControlSurface, GeometryError, Section, Surface, spacing_parameter


class AvlFileError(ValueError):
    """An AVL file that cannot be read: the message names the file, the line and the keyword."""


_SURFACE_KEYS = {"COMP", "INDE", "YDUP", "SCAL", "TRAN", "ANGL", "NOWA", "NOAL", "NOLO", "CDCL", "SECT"}
_SECTION_KEYS = {"NACA", "AIRF", "AFIL", "CLAF", "CONT", "DESI", "CDCL"}
_TOP_KEYS = {"SURF", "BODY"}
_BODY_KEYS = {"BFIL", "YDUP", "SCAL", "TRAN", "NOWA"}
_ALL_KEYS = _SURFACE_KEYS | _SECTION_KEYS | _TOP_KEYS | _BODY_KEYS


@dataclass
class _Line:
    number: int
    text: str

    @property
    def key(self) -> str:
        return self.text.split()[0][:4].upper()


@dataclass
class AvlExtras:
    """File content with no place in :class:`Configuration`: symmetry flags and CDCL polars."""

    iysym: int = 0
    izsym: int = 0
    zsym: float = 0.0
    cdcl: dict[str, list[float]] = field(default_factory=dict)


def _clean(text: str) -> str:
    for mark in ("#", "!"):
        text = text.split(mark, 1)[0]
    return text.strip()


def _is_keyword(line: _Line) -> bool:
    first = line.text.split()[0]
    return first[:1].isalpha() and first[:4].upper() in _ALL_KEYS


class _Reader:
    def __init__(self, path: Path):
        self.path = path
        raw = path.read_text(errors="replace").splitlines()
        self.lines = [_Line(i + 1, _clean(t)) for i, t in enumerate(raw)]
        self.lines = [ln for ln in self.lines if ln.text]
        self.pos = 0
        self.keyword = "header"

    def fail(self, line: _Line | None, message: str) -> AvlFileError:
        where = f"line {line.number}" if line else "end of file"
        return AvlFileError(f"{self.path}: {where} ({self.keyword}): {message}")

    def peek(self) -> _Line | None:
        return self.lines[self.pos] if self.pos < len(self.lines) else None

    def next(self, what: str) -> _Line:
        line = self.peek()
        if line is None:
            raise self.fail(None, f"file ends where {what} was expected")
        self.pos += 1
        return line

    def numbers(self, what: str, minimum: int, maximum: int | None = None) -> tuple[_Line, list[float]]:
        line = self.next(what)
        parts = line.text.split()
        values = []
        for p in parts[: maximum or len(parts)]:
            try:
                values.append(float(p))
            except ValueError:
                if len(values) >= minimum:
                    break
                raise self.fail(line, f"expected {what}, found {line.text!r}") from None
        if len(values) < minimum:
            raise self.fail(line, f"expected {what} ({minimum} numbers), found {line.text!r}")
        return line, values


def read_avl(path: str | Path, *, with_extras: bool = False):
    """Configuration from an AVL geometry file (``with_extras=True``: also an :class:`AvlExtras`)."""
    path = Path(path)
    if not path.is_file():
        raise AvlFileError(f"{path}: no such file")
    rd = _Reader(path)
    extras = AvlExtras()
    title = rd.next("the title").text
    _, (mach,) = rd.numbers("Mach", 1, 1)
    _, sym = rd.numbers("IYsym IZsym Zsym", 3, 3)
    extras.iysym, extras.izsym, extras.zsym = int(sym[0]), int(sym[1]), sym[2]
    _, (sref, cref, bref) = rd.numbers("Sref Cref Bref", 3, 3)
    _, (xref, yref, zref) = rd.numbers("Xref Yref Zref", 3, 3)
    cdp = 0.0
    line = rd.peek()
    if line is not None and not _is_keyword(line):
        _, (cdp,) = rd.numbers("CDp", 1, 1)
    if sref <= 0 or cref <= 0 or bref <= 0:
        raise AvlFileError(f"{path}: reference quantities Sref, Cref, Bref must be positive ({sref}, {cref}, {bref})")

    surfaces: list[Surface] = []
    while (line := rd.peek()) is not None:
        rd.pos += 1
        if not _is_keyword(line):
            raise rd.fail(line, f"unexpected line {line.text!r}: expected SURFACE or BODY")
        rd.keyword = line.text.split()[0].upper()
        if line.key == "SURF":
            surfaces.append(_read_surface(rd, extras))
        elif line.key == "BODY":
            name = rd.next("the body name").text
            warnings.warn(
                f"{path}: line {line.number}: BODY {name!r} skipped (the vortex lattice models lifting surfaces only)",
                stacklevel=2,
            )
            while (nxt := rd.peek()) is not None and not (_is_keyword(nxt) and nxt.key in _TOP_KEYS):
                rd.pos += 1
        else:
            raise rd.fail(line, f"keyword {line.text.split()[0]!r} outside a SURFACE")
    if not surfaces:
        raise AvlFileError(f"{path}: no SURFACE found")
    if extras.izsym != 0:
        raise AvlFileError(f"{path}: line 3 (IZsym): z-symmetry (ground plane) is not supported")
    if extras.iysym != 0:
        warnings.warn(f"{path}: IYsym={extras.iysym} replaced by explicit mirror images about y = 0", stacklevel=2)
        for s in surfaces:
            if s.y_duplicate is None:
                s.y_duplicate = 0.0
    config = Configuration(
        surfaces, AeroReference(sref, bref, cref, xref, zref), mach=mach, y_ref=yref, cd0=cdp, name=title
    )
    return (config, extras) if with_extras else config


def _read_surface(rd: _Reader, extras: AvlExtras) -> Surface:
    name = rd.next("the surface name").text
    line, vals = rd.numbers("Nchord Cspace [Nspan Sspace]", 2, 4)
    surface = Surface(name, [], n_chord=int(vals[0]), chord_spacing=vals[1])
    if len(vals) >= 3 and int(vals[2]) > 0:
        surface.n_span = int(vals[2])
        surface.span_spacing = vals[3] if len(vals) >= 4 else 1.0
    section: Section | None = None
    while (line := rd.peek()) is not None:
        if not _is_keyword(line):
            raise rd.fail(line, f"unexpected line {line.text!r} in surface {name!r}")
        if line.key in _TOP_KEYS:
            break
        rd.pos += 1
        key = line.key
        rd.keyword = line.text.split()[0].upper()
        if key in ("COMP", "INDE"):
            surface.component = int(rd.numbers("component index", 1, 1)[1][0])
        elif key == "YDUP":
            surface.y_duplicate = rd.numbers("y of the mirror plane", 1, 1)[1][0]
        elif key == "SCAL":
            surface.scale = tuple(rd.numbers("x, y, z scale factors", 3, 3)[1])
        elif key == "TRAN":
            surface.translate = tuple(rd.numbers("x, y, z offsets", 3, 3)[1])
        elif key == "ANGL":
            surface.incidence = math.radians(rd.numbers("incidence angle (deg)", 1, 1)[1][0])
        elif key == "NOWA":
            surface.wake = False
        elif key == "NOAL":
            surface.alpha_beta = False
        elif key == "NOLO":
            surface.load = False
        elif key == "CDCL":
            extras.cdcl[name] = rd.numbers("CL1 CD1 CL2 CD2 CL3 CD3", 6, 6)[1]
        elif key == "SECT":
            _, v = rd.numbers("Xle Yle Zle Chord Ainc [Nspan Sspace]", 5, 7)
            section = Section((v[0], v[1], v[2]), v[3], math.radians(v[4]))
            if len(v) >= 6:
                section.n_span = int(v[5])
                section.span_spacing = v[6] if len(v) >= 7 else 1.0
            surface.sections.append(section)
        elif section is None:
            raise rd.fail(line, f"{rd.keyword} before the first SECTION of surface {name!r}")
        elif key == "NACA":
            des = rd.next("a NACA designation")
            try:
                section.camber = CamberLine.naca(des.text.split()[0])
            except GeometryError as exc:
                raise rd.fail(des, str(exc)) from None
        elif key == "AIRF":
            pts = []
            while (nxt := rd.peek()) is not None and not _is_keyword(nxt):
                _, xy = rd.numbers("airfoil x y", 2, 2)
                pts.append(xy)
            try:
                section.camber = CamberLine.from_coordinates(
                    [p[0] for p in pts], [p[1] for p in pts], f"{name} AIRFOIL"
                )
            except GeometryError as exc:
                raise rd.fail(line, str(exc)) from None
        elif key == "AFIL":
            fname = rd.next("an airfoil file name")
            target = rd.path.parent / fname.text.split()[0].strip('"')
            if not target.is_file():
                raise rd.fail(fname, f"airfoil file {target} not found")
            try:
                section.camber = CamberLine.from_file(target)
            except GeometryError as exc:
                raise rd.fail(fname, str(exc)) from None
        elif key == "CLAF":
            section.claf = rd.numbers("CLaf", 1, 1)[1][0]
        elif key == "CONT":
            ctl = rd.next("name gain Xhinge XYZhvec SgnDup")
            parts = ctl.text.split()
            try:
                v = [float(p) for p in parts[1:7]]
            except ValueError:
                raise rd.fail(ctl, f"expected name gain Xhinge XYZhvec SgnDup, found {ctl.text!r}") from None
            if len(v) < 6:
                raise rd.fail(ctl, f"expected name gain Xhinge XYZhvec SgnDup, found {ctl.text!r}")
            section.controls.append(ControlSurface(parts[0], v[1], v[0], (v[2], v[3], v[4]), v[5]))
        elif key == "DESI":
            rd.next("design variable name and weight")
        else:
            raise rd.fail(line, f"keyword {rd.keyword!r} not allowed in a surface")
    return surface


# ----------------------------------------------------------------------------------------------
# Writer (for feeding our own geometries to AVL / optvl)
# ----------------------------------------------------------------------------------------------


def _fmt(*values: float) -> str:
    return "  ".join(f"{v:.10g}" for v in values)


def write_avl(config: Configuration, path: str | Path) -> Path:
    """Write ``config`` as an AVL geometry file (angles in degrees). Camber lines with a NACA name
    are written as NACA, others as AIRFOIL coordinates with a thin symmetric thickness about the
    camber line."""
    path = Path(path)
    ref = config.reference
    out = [
        config.name or "certkit configuration",
        _fmt(config.mach),
        "0  0  0.0",
        _fmt(ref.area, ref.chord, ref.span),
        _fmt(ref.x_ref, config.y_ref, ref.z_ref),
        _fmt(config.cd0),
    ]
    for s in config.surfaces:
        out += ["#" + "-" * 60, "SURFACE", s.name]
        nspan = f"  {s.n_span}  {_space(s.span_spacing)}" if s.n_span else ""
        out.append(f"{s.n_chord}  {_space(s.chord_spacing)}{nspan}")
        if s.component is not None:
            out += ["COMPONENT", str(s.component)]
        if s.y_duplicate is not None:
            out += ["YDUPLICATE", _fmt(s.y_duplicate)]
        out += ["SCALE", _fmt(*s.scale), "TRANSLATE", _fmt(*s.translate), "ANGLE", _fmt(math.degrees(s.incidence))]
        out += [k for k, flag in (("NOWAKE", s.wake), ("NOALBE", s.alpha_beta), ("NOLOAD", s.load)) if not flag]
        for sec in s.sections:
            extra = f"  {sec.n_span}  {_space(sec.span_spacing)}" if (not s.n_span and sec.n_span) else ""
            out += ["SECTION", _fmt(*sec.leading_edge, sec.chord, math.degrees(sec.incidence)) + extra]
            cam = sec.camber
            if cam is not None and cam.name.upper().startswith("NACA"):
                out += ["NACA", cam.name.upper().removeprefix("NACA").strip()]
            elif cam is not None and np.any(cam.z):
                x = 0.5 * (1.0 - np.cos(np.linspace(0.0, math.pi, 41)))
                zc = np.interp(x, cam.x, cam.z)
                t = 0.01 * np.sin(math.pi * x) ** 0.5
                xs = np.concatenate([x[::-1], x[1:]])
                zs = np.concatenate([(zc + t)[::-1], (zc - t)[1:]])
                out += ["AIRFOIL"] + [_fmt(a, b) for a, b in zip(xs, zs)]
            if sec.claf != 1.0:
                out += ["CLAF", _fmt(sec.claf)]
            for c in sec.controls:
                out += ["CONTROL", f"{c.name}  {_fmt(c.gain, c.hinge_x_over_c, *c.hinge_vector, c.duplicate_sign)}"]
    path.write_text("\n".join(out) + "\n")
    return path


def _space(value: float | str) -> str:
    return _fmt(spacing_parameter(value))
