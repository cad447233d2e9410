"""Strength sizing of an idealised two-spar box at stations along a lifting surface's span.

Idealisation (Megson, *Aircraft Structures for Engineering Students*, 4th ed., ch. 19–23: the covers carry the
bending as direct stress, the spar webs the shear, the closed cell the torsion by Bredt–Batho shear flow;
Niu, *Airframe Structural Design*, 1988, ch. 9; Torenbeek, *Synthesis of Subsonic Airplane Design*, 1982,
App. C, for the same two-spar preliminary-design box):

* box between the front and rear spar chord fractions f and r: streamwise width w = (r − f) c; spar heights
  and mean depth h from the airfoil depth factors (:func:`certkit.models.structure.section.depth_factors`)
  times the local thickness t·c;
* the box axis is swept by Λ_b, tan Λ_b = tan Λ_c/4 + ((f + r)/2 − ¼) dc/ds (a chord-fraction line of a
  straight-tapered planform). The streamwise-station bending M is resolved onto the box: the normal section
  has width w cos Λ_b and carries M / cos Λ_b. Its covers (skin and stringers smeared, one per side, each of
  thickness t_c) work at the allowable direct stress σ with the lever h − t_c between their centroids:
  σ t_c w cos Λ_b (h − t_c) = M / cos Λ_b, so t_c = (h − √(h² − 4K)) / 2 with K = M / (σ w cos² Λ_b);
  a box with h² < 4K cannot carry M at any cover thickness (an error);
* torsion (the streamwise torsion taken about the box axis; the M sin Λ_b coupling of a swept box is reacted
  at the root rib and is not sized here): Bredt–Batho shear flow q_T = T / (2 A), A = h w cos Λ_b; the
  cover's skin (a fraction of the smeared cover) carries q_T at the cover's allowable shear stress;
* webs: shear flow q_V = V / (h_fs + h_rs) (the shear shared in proportion to the spar heights, both webs of
  one thickness) plus q_T, at the web's allowable shear stress;
* each thickness is the largest of its strength requirements and its minimum gauge; the governing criterion
  is reported per station.

Masses per unit span (one box, i.e. one half of a mirrored surface): covers 2 ρ t_c w (planform area), webs
ρ t_w (h_fs + h_rs) / cos Λ_b (the webs run along the swept axis). Loads are ULTIMATE load magnitudes.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.interpolate import PchipInterpolator

from certkit.models.structure.section import depth_factors


class StructuralSizingError(ValueError):
    """A box that no cover thickness can make strong enough (the load exceeds what the depth allows)."""


@dataclass(frozen=True)
class BoxMaterial:
    """Allowables (Pa), density (kg/m³), the skin's share of a smeared cover and the minimum gauges (m)."""

    density: float
    cover_stress: float
    cover_shear: float
    web_shear: float
    skin_fraction: float
    min_cover: float
    min_web: float

    @classmethod
    def from_strains(
        cls,
        *,
        density,
        cover_modulus,
        cover_shear_modulus,
        web_shear_modulus,
        strain,
        shear_strain,
        skin_fraction,
        min_cover,
        min_web,
    ) -> "BoxMaterial":
        """A laminate linear to failure: allowable stress = modulus × design ultimate strain."""
        return cls(
            density,
            cover_modulus * strain,
            cover_shear_modulus * shear_strain,
            web_shear_modulus * shear_strain,
            skin_fraction,
            min_cover,
            min_web,
        )


@dataclass(frozen=True)
class BoxStations:
    """Stations along the span in the plane of the surface (m from the root, increasing), the streamwise chord (m),
    thickness ratio and quarter-chord sweep (rad, in the plane of the surface) at each."""

    span: np.ndarray
    chord: np.ndarray
    thickness_ratio: np.ndarray
    sweep_quarter_chord: np.ndarray

    def __post_init__(self):
        n = np.size(self.span)
        for name in ("span", "chord", "thickness_ratio", "sweep_quarter_chord"):
            object.__setattr__(self, name, np.broadcast_to(np.asarray(getattr(self, name), dtype=float), (n,)).copy())
        if n < 2 or np.any(np.diff(self.span) <= 0):
            raise ValueError("box stations: at least two, with the span increasing strictly from the root")
        if np.any(self.chord <= 0) or np.any(self.thickness_ratio <= 0):
            raise ValueError("box stations: chords and thickness ratios must be positive")


@dataclass(frozen=True)
class UltimateLoads:
    """Ultimate load magnitudes at stations (span in the plane of the surface from the root, m): shear (N),
    bending and torsion (N·m), each the largest magnitude of either sense over the design conditions."""

    span: np.ndarray
    shear: np.ndarray
    bending: np.ndarray
    torsion: np.ndarray

    @classmethod
    def from_limit_peaks(cls, span, peaks, factor: float = 1.5) -> "UltimateLoads":
        """From limit-load peaks shaped (..., 2, 3, n_stations) — the min/max of shear, bending, torsion of
        :class:`certkit.models.loads.response.LoadEnvelope` ``peaks[surface]`` — times the factor of safety."""
        p = np.abs(np.asarray(peaks, dtype=float))
        p = np.nanmax(p.reshape(-1, 3, p.shape[-1]), axis=0) * factor
        return cls(np.asarray(span, dtype=float), p[0], p[1], p[2])

    def interpolate(self, span, tip: float) -> "UltimateLoads":
        """The loads at ``span`` (m): monotone cubic (PCHIP, Fritsch & Carlson 1980) through the stations and
        zero at the ``tip`` (the free end carries no load); beyond the tip, zero."""
        s = np.asarray(self.span, dtype=float)
        order = np.argsort(s)
        s = s[order]
        out = []
        for values in (self.shear, self.bending, self.torsion):
            v = np.asarray(values, dtype=float)[order]
            if s[-1] < tip * (1 - 1e-9):
                xs, vs = np.append(s, tip), np.append(v, 0.0)
            else:
                xs, vs = s, v
            f = PchipInterpolator(xs, vs, extrapolate=True)
            x = np.asarray(span, dtype=float)
            out.append(np.where(x > tip, 0.0, np.maximum(f(np.clip(x, xs[0], None)), 0.0)))
        return UltimateLoads(np.asarray(span, dtype=float), *out)


@dataclass(frozen=True)
class BoxSizing:
    """Sized box at each station (one half of a mirrored surface). Thicknesses in m; masses in kg."""

    span: np.ndarray
    width: np.ndarray
    depth: np.ndarray
    front_spar_height: np.ndarray
    rear_spar_height: np.ndarray
    sweep: np.ndarray  # box-axis sweep, rad
    lever: np.ndarray
    t_cover: np.ndarray
    t_web: np.ndarray
    cover_governs: tuple[str, ...]
    web_governs: tuple[str, ...]
    cover_mass_per_span: np.ndarray  # kg/m, both covers
    web_mass_per_span: np.ndarray  # kg/m, both webs
    loads: UltimateLoads

    @property
    def cover_mass(self) -> float:
        return float(np.trapezoid(self.cover_mass_per_span, self.span))

    @property
    def web_mass(self) -> float:
        return float(np.trapezoid(self.web_mass_per_span, self.span))


def box_sweep(stations: BoxStations, mid_fraction: float) -> np.ndarray:
    """Sweep (rad) of the chord-fraction line ``mid_fraction`` from the quarter-chord sweep and the chord taper."""
    dc = np.gradient(stations.chord, stations.span)
    return np.arctan(np.tan(stations.sweep_quarter_chord) + (mid_fraction - 0.25) * dc)


def size_box(
    stations: BoxStations, loads: UltimateLoads, material: BoxMaterial, front_spar: float, rear_spar: float
) -> BoxSizing:
    """Cover and web thicknesses at each station for the ultimate ``loads`` (given at the same stations)."""
    if not np.allclose(loads.span, stations.span):
        raise ValueError("size_box: the loads must be given at the box stations (use UltimateLoads.interpolate)")
    k = depth_factors(front_spar, rear_spar)
    tc = stations.thickness_ratio * stations.chord
    h, h_fs, h_rs = k.mean * tc, k.front_spar * tc, k.rear_spar * tc
    w = (rear_spar - front_spar) * stations.chord
    sweep = box_sweep(stations, 0.5 * (front_spar + rear_spar))
    cos = np.cos(sweep)
    m = np.abs(loads.bending)
    kk = m / (material.cover_stress * w * cos**2)
    disc = h**2 - 4.0 * kk
    if np.any(disc < 0):
        i = int(np.argmin(disc))
        raise StructuralSizingError(
            f"box at {stations.span[i]:.3f} m from the root: ultimate bending {m[i] / 1e3:.1f} kN·m exceeds what a "
            f"{h[i]:.3f} m deep, {w[i]:.3f} m wide box can carry at {material.cover_stress / 1e6:.0f} MPa "
            f"(at most {material.cover_stress * w[i] * cos[i] ** 2 * h[i] ** 2 / 4e3:.1f} kN·m)"
        )
    t_bend = 0.5 * (h - np.sqrt(np.maximum(disc, 0.0)))
    q_t = np.abs(loads.torsion) / (2.0 * h * w * cos)
    t_tors = q_t / (material.cover_shear * material.skin_fraction)
    t_min = np.full_like(h, material.min_cover)
    cover_options = np.stack([t_bend, t_tors, t_min])
    t_cover = cover_options.max(axis=0)
    cover_governs = tuple(("bending", "torsion", "minimum gauge")[i] for i in cover_options.argmax(axis=0))
    web_shear = np.abs(loads.shear) / (h_fs + h_rs)
    web_options = np.stack([(web_shear + q_t) / material.web_shear, np.full_like(h, material.min_web)])
    t_web = web_options.max(axis=0)
    web_governs = tuple(("shear and torsion", "minimum gauge")[i] for i in web_options.argmax(axis=0))
    rho = material.density
    return BoxSizing(
        stations.span,
        w,
        h,
        h_fs,
        h_rs,
        sweep,
        h - t_cover,
        t_cover,
        t_web,
        cover_governs,
        web_governs,
        2.0 * rho * t_cover * w,
        rho * t_web * (h_fs + h_rs) / cos,
        loads,
    )
