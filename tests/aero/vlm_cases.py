"""Geometries shared by the vortex-lattice tests (built with the public API only)."""

from __future__ import annotations

import math

import numpy as np

from certkit.models.aero.interface import AeroReference
from certkit.models.aero.vlm import Configuration, ControlSpan, Section, Surface, trapezoidal_surface


def elliptic_wing(aspect_ratio: float, n_strips: int = 40, n_chord: int = 6, span: float = 10.0) -> Configuration:
    """Unswept elliptic planform (straight quarter-chord line), one strip between sections placed at
    cosine-spaced span stations; the tip chord is 0.1 % of the root chord."""
    area = span**2 / aspect_ratio
    c0 = 4.0 * area / (math.pi * span)
    eta = np.sin(np.linspace(0.0, math.pi / 2, n_strips + 1))
    chords = np.maximum(c0 * np.sqrt(np.clip(1.0 - eta**2, 0.0, None)), 1e-3 * c0)
    sections = [Section((-0.25 * c, e * span / 2, 0.0), c, n_span=1, span_spacing=0.0) for e, c in zip(eta, chords)]
    wing = Surface("wing", sections, n_chord=n_chord, chord_spacing=1.0, y_duplicate=0.0)
    return Configuration([wing], AeroReference(area, span, area / span, 0.0))


def rectangular_wing(aspect_ratio: float, n_span: int = 24, n_chord: int = 8) -> Configuration:
    chord = 1.0
    span = aspect_ratio * chord
    wing = trapezoidal_surface(
        "wing", area=span * chord, aspect_ratio=aspect_ratio, taper=1.0, n_chord=n_chord, n_span=n_span
    )
    return Configuration([wing], AeroReference(span * chord, span, chord, 0.25 * chord))


def transport(mach: float = 0.0, scale: int = 1) -> Configuration:
    """A generic twin-jet transport from planform parameters: swept wing with dihedral, twist-free,
    NACA 2412 camber, outboard ailerons; horizontal tail with elevator; fin with rudder (SI units).
    ``scale`` multiplies the panel counts."""
    wing = trapezoidal_surface(
        "wing",
        area=124.6,
        aspect_ratio=9.45,
        taper=0.24,
        sweep_quarter_chord=math.radians(25.0),
        dihedral=math.radians(5.0),
        root_leading_edge=(14.0, 0.0, -1.0),
        incidence=math.radians(1.0),
        camber="24",
        controls=[ControlSpan("aileron", 0.72, 0.95, 0.25)],
        n_chord=8 * scale,
        n_span=24 * scale,
    )
    htail = trapezoidal_surface(
        "htail",
        area=32.8,
        aspect_ratio=6.0,
        taper=0.25,
        sweep_quarter_chord=math.radians(30.0),
        dihedral=math.radians(7.0),
        root_leading_edge=(32.0, 0.0, 0.8),
        incidence=math.radians(-1.5),
        controls=[ControlSpan("elevator", 0.0, 0.9, 0.3)],
        n_chord=6 * scale,
        n_span=12 * scale,
    )
    fin = trapezoidal_surface(
        "fin",
        area=26.4,
        aspect_ratio=1.8,
        taper=0.3,
        sweep_quarter_chord=math.radians(35.0),
        root_leading_edge=(29.5, 0.0, 1.0),
        vertical=True,
        controls=[ControlSpan("rudder", 0.05, 0.9, 0.3)],
        n_chord=6 * scale,
        n_span=10 * scale,
    )
    mac = 4.17
    return Configuration(
        [wing, htail, fin],
        AeroReference(124.6, math.sqrt(124.6 * 9.45), mac, 17.5, 0.0),
        mach=mach,
        name="generic transport",
    )
